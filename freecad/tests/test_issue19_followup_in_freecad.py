"""Issue 19, the rest: the one-call blend of two edges (bezjoin.connect_edges), results
placed in the container of their sources, and the smallest edge FreeCAD holds."""

import math
import unittest

import FreeCAD
import Part

import bezjoin
from bezjoin_workbench import features, operations
from test_features_in_freecad import constrained_rectangle

V = FreeCAD.Vector


def bezier_edge(points):
    curve = Part.BezierCurve()
    curve.setPoles([V(*p) for p in points])
    return curve.toShape()


def composition(p_edge, u0, q_edge, v0, **options):
    """The blend the long way: from_freecad, connect, to_freecad."""
    with bezjoin.Curve.from_freecad(p_edge) as p, bezjoin.Curve.from_freecad(q_edge) as q, \
            bezjoin.connect(p, u0, q, v0, **options) as blend:
        return blend.to_freecad()


class ConnectEdges(unittest.TestCase):
    """connect_edges gives the poles of from_freecad + connect + to_freecad, bit for bit,
    for the fast Bezier edges and (through the composition) for every other edge."""

    P = bezier_edge([(0, 0, 0), (1, 1, 0.2), (2, 1, 0.1), (3, 0, 0)])
    Q = bezier_edge([(4, 0.5, 0), (5, 0, 0.3), (6, 1, 0.2), (7, 0, 0)])

    def assertSameCurve(self, ours, theirs):
        self.assertIsInstance(ours, Part.BezierCurve)
        self.assertEqual(ours.Degree, theirs.Degree)
        self.assertEqual([tuple(p) for p in ours.getPoles()],
                         [tuple(p) for p in theirs.getPoles()])

    def test_bezier_edges_bit_for_bit(self):
        cases = [dict(p_order=3, q_order=3, p_scale=0.8, q_scale=0.8),
                 dict(p_order=2, q_order=1, p_scale=1.3, q_scale=0.6),
                 dict(p_order=3, q_order=3), dict(), dict(auto_scale=False),
                 dict(p_scale=2.0)]
        for options in cases:
            for u0, v0 in ((1.0, 0.0), (0.7, 0.2)):
                with self.subTest(options=options, u0=u0, v0=v0):
                    self.assertSameCurve(bezjoin.connect_edges(self.P, u0, self.Q, v0, **options),
                                         composition(self.P, u0, self.Q, v0, **options))

    def test_ends_match_freecads_derivatives(self):
        """The defining property, judged by FreeCAD: R^(k)(0) = s^k P^(k)(1) and
        R^(k)(1) = s^k Q^(k)(0), k <= 3, with FreeCAD's getDN on the edges."""
        blend = bezjoin.connect_edges(self.P, 1.0, self.Q, 0.0, p_order=3, q_order=3,
                                      p_scale=0.8, q_scale=0.8)
        for k in range(4):
            for here, edge, there in ((0.0, self.P, 1.0), (1.0, self.Q, 0.0)):
                ours = blend.value(here) if k == 0 else blend.getDN(here, k)
                theirs = (edge.Curve.value(there) if k == 0
                          else edge.Curve.getDN(there, k) * 0.8 ** k)
                self.assertLess((ours - theirs).Length, 1e-10 * max(1.0, theirs.Length), (k, here))

    def test_other_edges_take_the_composition(self):
        arc = Part.ArcOfCircle(Part.Circle(V(10, 0, 0), V(0, 0, 1), 2.0), 0.0, 2.0).toShape()
        line = Part.LineSegment(V(0, 0, 0), V(3, 0, 0)).toShape()
        partial = Part.Edge(self.Q.Curve, 0.2, 0.9)
        bspline = self.Q.Curve.toBSpline().toShape()
        for p_edge, q_edge, u0, v0 in ((self.P, arc, 1.0, 0.0), (line, self.Q, 1.0, 0.0),
                                       (self.P, partial, 1.0, 0.0), (bspline, self.P, 1.0, 0.0)):
            with self.subTest(p=p_edge.Curve.TypeId, q=q_edge.Curve.TypeId):
                options = dict(p_order=2, q_order=2, p_scale=0.5, q_scale=0.5)
                self.assertSameCurve(bezjoin.connect_edges(p_edge, u0, q_edge, v0, **options),
                                     composition(p_edge, u0, q_edge, v0, **options))

    def test_errors_are_the_compositions(self):
        for options, u0, v0, text in ((dict(p_scale=1.0), 1.5, 0.0, "u0"),
                                      (dict(p_scale=-1.0), 1.0, 0.0, "scale"),
                                      (dict(p_order=20, q_order=20), 1.0, 0.0, "degree 41")):
            with self.subTest(text=text):
                with self.assertRaises(bezjoin.BezjoinError) as ours:
                    bezjoin.connect_edges(self.P, u0, self.Q, v0, **options)
                with self.assertRaises(bezjoin.BezjoinError) as theirs:
                    composition(self.P, u0, self.Q, v0, **options)
                self.assertEqual(str(ours.exception), str(theirs.exception))
                self.assertIn(text, str(ours.exception))
        offset = Part.OffsetCurve(self.Q.Curve, 1.0, V(0, 0, 1)).toShape()
        with self.assertRaises(bezjoin.UnsupportedGeometryError):
            bezjoin.connect_edges(self.P, 1.0, offset, 0.0)

    def test_wild_poles_leave_the_fast_path_with_the_same_answer(self):
        """Poles far from the ends (beyond the verbatim ratio of from_freecad): the
        composition decides, as from_freecad does."""
        wild = bezier_edge([(0, 0, 0), (1e5, 1e5, 0), (-1e5, 1e5, 0), (1, 0, 0)])
        self.assertIsNone(bezjoin._freecad._verbatim_values(wild, Part))
        self.assertSameCurve(bezjoin.connect_edges(wild, 1.0, self.Q, 0.0, p_scale=1e-3),
                             composition(wild, 1.0, self.Q, 0.0, p_scale=1e-3))


class TreePlacement(unittest.TestCase):
    """A feature goes into the App::Part holding its sources (its shape local to the
    Part, shown where the sources are); a Body takes PartDesign features only, so a
    feature on a Body's sketch goes to the Part holding the Body, or to the root."""

    def setUp(self):
        self.document = FreeCAD.newDocument("BezjoinTree")
        self.part = self.document.addObject("App::Part", "Part")
        self.part.Placement = FreeCAD.Placement(V(100, 50, 5), FreeCAD.Rotation(V(0, 0, 1), 30))

    def tearDown(self):
        FreeCAD.closeDocument(self.document.Name)

    def recompute(self, *objects):
        self.document.recompute()
        for obj in objects:
            self.assertTrue(obj.isValid(), (obj.Name, obj.getStatusString()))

    def check_rounded(self, feature, sketch):
        """The result, taken to the model as FreeCAD shows it, rounds the sketch's
        corners in the model (the sketch's own vertices taken to the model): the
        corners are cut, the sides' middles are on it."""
        shape = operations.model_shape(feature)
        self.assertTrue(shape.Wires[0].isClosed())
        corners = [v.Point for v in operations.model_shape(sketch).Wires[0].OrderedVertexes]
        self.assertEqual(len(corners), 4)
        for i, corner in enumerate(corners):
            self.assertGreater(shape.distToShape(Part.Vertex(corner))[0], 1e-3, corner)
            middle = (corner + corners[(i + 1) % 4]) * 0.5
            self.assertLess(shape.distToShape(Part.Vertex(middle))[0], 1e-7, middle)

    def check_corner(self, corner, sketch, setback):
        """The rounded corner of the sketch's Edge1 and Edge2, in the model: the shared
        vertex is cut, and the blend starts ``setback`` from it along each edge (a vertex
        of the result there)."""
        first, second = (operations.model_shape(sketch, name) for name in ("Edge1", "Edge2"))
        shared = [v.Point for v in first.Vertexes
                  if any((v.Point - w.Point).Length < 1e-9 for w in second.Vertexes)][0]
        shape = operations.model_shape(corner)
        self.assertGreater(shape.distToShape(Part.Vertex(shared))[0], 1e-3)
        vertices = [v.Point for v in shape.Vertexes]
        for edge in (first, second):
            other = [v.Point for v in edge.Vertexes if (v.Point - shared).Length > 1e-9][0]
            want = shared + (other - shared).normalize() * setback
            self.assertLess(min((p - want).Length for p in vertices), 1e-7, want)

    def test_a_sketch_in_a_part_gives_a_feature_in_the_part(self):
        sketch, width = constrained_rectangle(self.document, self.part, 40.0, 20.0)
        wire = features.make_round_wire(self.document, sketch, Radius=2.0)
        self.recompute(wire)
        self.assertIs(wire.getParentGeoFeatureGroup(), self.part)
        self.assertIn(wire, self.part.Group)
        # No dependency cycle: the Part holding the feature is no "container" of it.
        self.assertNotIn(self.part, list(wire.Containers))
        self.check_rounded(wire, sketch)
        # Local to the Part: obj.Shape alone lies where the sketch's own shape does.
        box, sketch_box = wire.Shape.BoundBox, sketch.Shape.BoundBox
        self.assertAlmostEqual(box.XMin, sketch_box.XMin, delta=1e-7)
        self.assertAlmostEqual(box.YMax, sketch_box.YMax, delta=1e-7)
        # Parametric in the Part: the sketch changes, the Part moves.
        sketch.setDatum(width, FreeCAD.Units.Quantity("60 mm"))
        self.recompute(wire)
        self.check_rounded(wire, sketch)
        self.part.Placement = FreeCAD.Placement(V(-20, 0, 0), FreeCAD.Rotation(V(1, 0, 0), 90))
        self.recompute(wire)
        self.check_rounded(wire, sketch)

    def test_a_sketch_in_a_body_in_a_part_gives_a_feature_in_the_part(self):
        body = self.document.addObject("PartDesign::Body", "Body")
        self.part.addObject(body)
        body.Placement = FreeCAD.Placement(V(0, 0, 30), FreeCAD.Rotation(V(0, 1, 0), 45))
        sketch, _width = constrained_rectangle(self.document, body, 40.0, 20.0)
        with self.assertRaises(Exception) as refused:  # what a Body says to a Part feature
            body.addObject(self.document.addObject("Part::FeaturePython", "Stray"))
        self.assertIn("not allowed", str(refused.exception))
        corner = features.make_round_corner(self.document, (sketch, "Edge1"),
                                            (sketch, "Edge2"), Setback=3.0)
        self.recompute(corner)
        self.assertIs(corner.getParentGeoFeatureGroup(), self.part)
        self.assertEqual(list(corner.Containers), [body])  # the Body moves the sources
        self.check_corner(corner, sketch, 3.0)
        body.Placement = FreeCAD.Placement(V(5, 5, 5), FreeCAD.Rotation())
        self.recompute(corner)
        self.check_corner(corner, sketch, 3.0)

    def test_a_sketch_in_a_body_alone_gives_a_feature_at_the_root(self):
        body = self.document.addObject("PartDesign::Body", "Body")
        body.Placement = FreeCAD.Placement(V(100, 0, 0), FreeCAD.Rotation())
        sketch, _width = constrained_rectangle(self.document, body, 40.0, 20.0)
        wire = features.make_round_wire(self.document, sketch, Radius=2.0)
        self.recompute(wire)
        self.assertIsNone(wire.getParentGeoFeatureGroup())
        self.assertEqual(list(wire.Containers), [body])
        self.assertAlmostEqual(wire.Shape.BoundBox.XMin, 100.0, delta=1e-7)
        self.check_rounded(wire, sketch)

    def test_sources_in_different_containers_give_their_common_part(self):
        inner = self.document.addObject("App::Part", "Inner")
        self.part.addObject(inner)
        inner.Placement = FreeCAD.Placement(V(0, 0, 10), FreeCAD.Rotation())
        first = self.document.addObject("Part::Feature", "First")
        first.Shape = Part.LineSegment(V(0, 0, 0), V(10, 0, 0)).toShape()
        inner.addObject(first)
        second = self.document.addObject("Part::Feature", "Second")
        second.Shape = Part.LineSegment(V(15, 0, 0), V(25, 5, 0)).toShape()
        self.part.addObject(second)
        self.document.recompute()
        blend = features.make_blend(self.document, first, second)
        self.recompute(blend)
        self.assertIs(blend.getParentGeoFeatureGroup(), self.part)
        self.assertEqual(list(blend.Containers), [inner])
        shape = operations.model_shape(blend)
        start, end = (shape.Edges[0].valueAt(shape.Edges[0].FirstParameter),
                      shape.Edges[0].valueAt(shape.Edges[0].LastParameter))
        want_start = operations.model_shape(first).Vertexes[1].Point
        want_end = operations.model_shape(second).Vertexes[0].Point
        self.assertLess((start - want_start).Length, 1e-7)
        self.assertLess((end - want_end).Length, 1e-7)
        # Loose sources at the root: the feature stays at the root.
        loose = self.document.addObject("Part::Feature", "Loose")
        loose.Shape = Part.LineSegment(V(30, 0, 0), V(40, 0, 0)).toShape()
        blend2 = features.make_blend(self.document, second, loose)
        self.recompute(blend2)
        self.assertIsNone(blend2.getParentGeoFeatureGroup())


class TinyEdge(unittest.TestCase):
    """Issue 19, item 4: "a 40 mm line plus a 1e-9 mm line moves 10 mm". FreeCAD holds a
    1e-9 mm edge when it is made from a curve (Part.LineSegment(...).toShape(),
    Part.Edge(curve), a Bezier curve's edge); its two vertices fall within the vertex
    tolerance (1e-7 mm) and become one, so the edge is topologically closed. What
    cannot make it is the vertex route: Part.makeLine gives a null shape below 1e-7 mm,
    Part.Edge(Vertex, Vertex) raises "BRep_API: command not done". The smallest step a
    curve at x = 40 can take is one ulp (7.1e-15 mm); equal points raise "Both points
    are equal"."""

    FIRST = Part.LineSegment(V(0, 0, 0), V(40, 0, 0)).toShape()

    def merged_ends(self, second):
        merged = operations.merge_edges(self.FIRST, second)
        shape = merged.shape
        self.assertEqual(shape.ShapeType, "Edge")
        # its distance from the edges is measured too (the arc length sampler refuses
        # the tiny edge; equal parameter steps do), to within the tiny edge's length:
        # below the vertex tolerance distToShape goes to its one vertex
        self.assertLessEqual(merged.max_deviation, 1.01 * second.Length + 1e-13)
        return shape.valueAt(shape.FirstParameter), shape.valueAt(shape.LastParameter)

    def test_a_1e_9_mm_edge_merges_with_the_ends_kept(self):
        tiny_end = V(40 + 1e-9, 0, 0)
        for second in (Part.LineSegment(V(40, 0, 0), tiny_end).toShape(),
                       Part.Edge(Part.LineSegment(V(40, 0, 0), tiny_end)),
                       bezier_edge([(40, 0, 0), (40 + 1e-9, 0, 0)])):
            with self.subTest(curve=second.Curve.TypeId):
                self.assertTrue(second.isValid())
                self.assertAlmostEqual(second.Length, tiny_end.x - 40.0, delta=1e-20)
                self.assertTrue(second.isClosed())  # one vertex: 1e-9 < the tolerance 1e-7
                start, end = self.merged_ends(second)
                # kept to a few ulps of 40 (7.1e-15), not moved by 10 mm
                self.assertLessEqual(start.Length, 1e-14)
                self.assertLessEqual((end - second.valueAt(second.LastParameter)).Length, 2e-14)

    def test_the_smallest_step_freecad_represents(self):
        ulp = math.ulp(40.0)
        for steps in (1, 2):
            second = Part.LineSegment(V(40, 0, 0), V(40 + steps * ulp, 0, 0)).toShape()
            self.assertEqual(second.Length, steps * ulp)
            start, end = self.merged_ends(second)
            self.assertLessEqual(start.Length, 1e-14)
            self.assertLessEqual(abs(end.x - (40 + steps * ulp)), ulp)
        with self.assertRaises(Part.OCCError) as caught:
            Part.LineSegment(V(40, 0, 0), V(40, 0, 0))
        self.assertIn("Both points are equal", str(caught.exception))

    def test_the_vertex_routes_refuse_edges_below_the_tolerance(self):
        """FreeCAD's limit as FreeCAD words it (why the 1e-9 case needs a curve first)."""
        made = Part.makeLine(V(40, 0, 0), V(40 + 1e-9, 0, 0))
        with self.assertRaises(Exception) as caught:
            made.Length
        self.assertIn("Unknown exception while reading attribute 'Length'", str(caught.exception))
        with self.assertRaises(Part.OCCError) as caught:
            Part.Edge(Part.Vertex(V(40, 0, 0)), Part.Vertex(V(40 + 1e-9, 0, 0)))
        self.assertIn("BRep_API: command not done", str(caught.exception))
        # at the tolerance itself the vertex route still works
        self.assertAlmostEqual(Part.makeLine(V(40, 0, 0), V(40 + 1e-7, 0, 0)).Length,
                               (40 + 1e-7) - 40, delta=1e-20)


if __name__ == "__main__":
    unittest.main()
