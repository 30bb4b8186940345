"""Issue 19 in the workbench, judged by FreeCAD on the resulting shapes (model
coordinates): sketches in placed containers, whole wires rounded into one closed wire,
merge defaults that keep the ends and refuse corners, shared vertices, and the checks
made before a command's form opens."""

import math
import re
import unittest

import FreeCAD
import Part

import bezjoin
from bezjoin_workbench import commands, operations
from judge import gap
from test_operations_in_freecad import CommandDriver

V = FreeCAD.Vector


class Picked:
    """What ``FreeCADGui.Selection.getSelectionEx()`` gives for one object (no GUI here)."""

    def __init__(self, obj, names=()):
        self.Object = obj
        self.SubElementNames = list(names)
        self.SubObjects = [obj.Shape.getElement(name) for name in names]


def rectangle_sketch(container, width=40.0, height=20.0):
    """A closed width x height rectangle sketch inside ``container`` (a Body or a Part)."""
    document = container.Document
    sketch = document.addObject("Sketcher::SketchObject", "Sketch")
    container.addObject(sketch)
    corners = [V(0, 0, 0), V(width, 0, 0), V(width, height, 0), V(0, height, 0)]
    for i in range(4):
        sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
    document.recompute()
    return sketch


def cut_corners(test, shape, corners, least=1e-3):
    for corner in corners:
        test.assertGreater(shape.distToShape(Part.Vertex(V(*corner)))[0], least, corner)


class SketchInAPlacedContainer(unittest.TestCase, CommandDriver):
    """A sketch in a Body placed at x = 100: results land at x = 100..140, not 0..40."""

    def setUp(self):
        self.document = FreeCAD.newDocument("BezjoinPlaced")
        self.body = self.document.addObject("PartDesign::Body", "Body")
        self.body.Placement = FreeCAD.Placement(V(100, 0, 0), FreeCAD.Rotation())
        self.sketch = rectangle_sketch(self.body)
        # FreeCAD's own shape of the sketch leaves the Body's placement out
        self.assertAlmostEqual(self.sketch.Shape.BoundBox.XMin, 0.0, delta=1e-9)

    def tearDown(self):
        FreeCAD.closeDocument(self.document.Name)

    def test_round_wire_of_the_sketch_is_in_model_coordinates(self):
        wire = operations.round_wire(operations.model_shape(self.sketch), radius=2.0)
        box = wire.BoundBox
        self.assertAlmostEqual(box.XMin, 100.0, delta=1e-9)
        self.assertAlmostEqual(box.XMax, 140.0, delta=1e-9)
        self.assertAlmostEqual(box.YMin, 0.0, delta=1e-9)
        self.assertAlmostEqual(box.YMax, 20.0, delta=1e-9)
        cut_corners(self, wire, [(100, 0, 0), (140, 0, 0), (140, 20, 0), (100, 20, 0)])

    def test_selected_edges_and_the_command_result_are_in_model_coordinates(self):
        edges = commands.selected_edges(2, [Picked(self.sketch, ["Edge1", "Edge2"])])
        for edge in edges:
            self.assertGreaterEqual(edge.BoundBox.XMin, 100.0 - 1e-9)
        parameters = {"setback": 2.0, "second_setback": 2.0, "p_order": None,
                      "q_order": None, "p_scale": 1.0, "q_scale": 1.0, "auto_scale": True,
                      "reverse_first": False, "reverse_second": False}
        made, shown = self.drive(commands.RoundCornerCommand(), edges, parameters)
        self.assertEqual(shown, [])
        ((_name, shape, _report),) = made
        self.assertAlmostEqual(shape.BoundBox.XMin, 100.0, delta=1e-9)
        self.assertAlmostEqual(shape.BoundBox.XMax, 140.0, delta=1e-9)
        cut_corners(self, shape, [(140, 0, 0)])
        # the whole sketch selected: its wire, in model coordinates
        path = commands.selected_path([Picked(self.sketch)])
        self.assertEqual(len(path), 4)
        self.assertAlmostEqual(Part.Wire(path).BoundBox.XMin, 100.0, delta=1e-9)
        made, shown = self.drive(commands.RoundWireByRadiusCommand(), path,
                                 {"radius": 2.0, "order": 2, "closed": "auto"})
        self.assertEqual(shown, [])
        self.assertAlmostEqual(made[0][1].BoundBox.XMin, 100.0, delta=1e-9)
        self.assertAlmostEqual(made[0][1].BoundBox.XMax, 140.0, delta=1e-9)

    def test_rotated_part_container(self):
        part = self.document.addObject("App::Part", "Part")
        part.Placement = FreeCAD.Placement(V(0, 50, 0), FreeCAD.Rotation(V(0, 0, 1), 90))
        sketch = rectangle_sketch(part, 30.0, 10.0)
        wire = operations.round_wire(operations.model_shape(sketch), setback=1.0)
        # the rectangle's corners taken to the model by the container's placement
        corners = [part.Placement.multVec(V(x, y, 0)) for x, y in
                   ((0, 0), (30, 0), (30, 10), (0, 10))]
        box = wire.BoundBox
        self.assertAlmostEqual(box.XMin, min(c.x for c in corners), delta=1e-9)
        self.assertAlmostEqual(box.XMax, max(c.x for c in corners), delta=1e-9)
        self.assertAlmostEqual(box.YMin, min(c.y for c in corners), delta=1e-9)
        self.assertAlmostEqual(box.YMax, max(c.y for c in corners), delta=1e-9)
        cut_corners(self, wire, [tuple(c) for c in corners])


class RoundWholeWires(unittest.TestCase):
    rectangle = Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(40, 20, 0), V(0, 20, 0),
                                  V(0, 0, 0)])
    corners = [(0, 0, 0), (40, 0, 0), (40, 20, 0), (0, 20, 0)]

    def check_closed_face(self, wire):
        self.assertEqual(wire.ShapeType, "Wire")
        self.assertTrue(wire.isClosed())
        self.assertTrue(wire.isValid())
        self.assertEqual(len(wire.Edges), 8)
        face = Part.Face(wire)
        self.assertTrue(face.isValid())
        # a little less than the rectangle: only the corners are cut
        self.assertLess(face.Area, 800.0)
        self.assertGreater(face.Area, 800.0 - 4 * 4.0)
        cut_corners(self, wire, self.corners)
        edges = wire.OrderedEdges
        for left, right in zip(edges, edges[1:] + edges[:1]):
            self.assertLessEqual(gap(left.tangentAt(left.LastParameter),
                                     right.tangentAt(right.FirstParameter)), 1e-8)

    def test_closed_rectangle_by_radius_is_one_closed_wire_with_a_face(self):
        self.check_closed_face(operations.round_wire(self.rectangle, radius=1.5))

    def test_closed_rectangle_by_setback_is_one_closed_wire_with_a_face(self):
        wire = operations.round_wire(self.rectangle, setback=1.5)
        self.check_closed_face(wire)
        lines = sorted(e.Length for e in wire.Edges if e.Curve.TypeId != "Part::GeomBezierCurve")
        for got, want in zip(lines, [17.0, 17.0, 37.0, 37.0]):
            self.assertAlmostEqual(got, want, delta=1e-9)

    def test_loose_edges_and_g3(self):
        edges = list(reversed(self.rectangle.Edges))
        wire = operations.round_wire(edges, radius=1.0, continuity="G3")
        self.assertTrue(wire.isClosed())
        self.assertTrue(Part.Face(wire).isValid())
        open_wire = operations.round_wire(Part.makePolygon([V(0, 0, 0), V(10, 0, 0),
                                                            V(10, 10, 0)]), radius=1.0)
        self.assertFalse(open_wire.isClosed())
        self.assertEqual(len(open_wire.Edges), 3)

    def test_a_corner_that_does_not_fit_is_named_and_nothing_is_built(self):
        thin = Part.makePolygon([V(0, 0, 0), V(40, 0, 0), V(40, 4, 0), V(0, 4, 0), V(0, 0, 0)])
        for options in ({"radius": 3.0}, {"setback": 3.0}):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.round_wire(thin, **options)
            self.assertRegex(str(caught.exception), r"corner \d|curves\[\d\]", options)
        with self.assertRaises(TypeError):
            operations.round_wire(thin)

    def test_round_corner_by_radius(self):
        first = Part.makeLine(V(0, 0, 0), V(40, 0, 0))
        second = Part.makeLine(V(40, 0, 0), V(40, 20, 0))
        wire = operations.round_corner(first, second, radius=2.0)
        self.assertEqual(len(wire.Edges), 3)
        edges = wire.OrderedEdges
        # at a right angle the arc of radius r touches each side r from the vertex
        self.assertAlmostEqual(edges[0].Length, 38.0, delta=1e-9)
        self.assertAlmostEqual(edges[2].Length, 18.0, delta=1e-9)
        cut_corners(self, wire, [(40, 0, 0)], 0.1)
        for left, right in zip(edges, edges[1:]):
            self.assertLessEqual(abs(left.curvatureAt(left.LastParameter)
                                     - right.curvatureAt(right.FirstParameter)), 1e-7)


class MergeDefaults(unittest.TestCase):
    def test_ends_are_kept(self):
        for first, second in (
                (Part.makeLine(V(0, 0, 0), V(10, 0, 0)), Part.makeLine(V(10, 0, 0), V(25, 0, 0))),
                (Part.makeLine(V(0, 0, 0), V(40, 0, 0)),
                 Part.makeLine(V(40, 0, 0), V(40.001, 0, 0)))):
            merged = operations.merge_edges(first, second).shape
            ends = sorted([tuple(merged.valueAt(merged.FirstParameter)),
                           tuple(merged.valueAt(merged.LastParameter))])
            self.assertLessEqual(gap(ends[0], first.Vertexes[0].Point), 1e-9)
            self.assertLessEqual(gap(ends[1], second.Vertexes[-1].Point), 1e-9)

    def test_a_corner_beyond_the_limit_is_refused_with_its_angle(self):
        first = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        second = Part.makeLine(V(10, 0, 0), V(10, 10, 0))
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.merge_edges(first, second)
        angle = re.search(r"turn by ([0-9.]+) degrees", str(caught.exception))
        self.assertIsNotNone(angle, str(caught.exception))
        self.assertAlmostEqual(float(angle.group(1)), 90.0, delta=1e-6)
        self.assertEqual(operations.MAX_MERGE_ANGLE_DEGREES, 30.0)
        # the limit is a keyword: a gentle 20 degree bend merges, a stricter limit refuses it
        bent = Part.makeLine(V(10, 0, 0), V(10 + 10 * math.cos(math.radians(20)),
                                            10 * math.sin(math.radians(20)), 0))
        self.assertEqual(operations.merge_edges(first, bent).shape.ShapeType, "Edge")
        with self.assertRaises(bezjoin.BezjoinError):
            operations.merge_edges(first, bent, max_angle=10.0)
        self.assertEqual(operations.merge_edges(first, second, max_angle=None).shape.ShapeType,
                         "Edge")


    def test_an_arc_is_refused_naming_the_edge_not_the_library_curve(self):
        # User testing, session 43: an arc gave "p: the curve is rational (its weights
        # differ): a merge of B-splines takes polynomial B-splines, since R restricted
        # to a piece is polynomial", as "q:" when it was the second edge.
        circle = Part.Circle(V(0, 0, 0), V(0, 0, 1), 10)
        arc = Part.ArcOfCircle(circle, 0.0, 1.0).toShape()
        line = Part.makeLine(V(10, -10, 0), V(10, 0, 0))
        for first, second, name in ((arc, Part.ArcOfCircle(circle, 1.0, 2.0).toShape(), "first"),
                                    (line, arc, "second")):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.merge_edges(first, second)
            message = str(caught.exception)
            self.assertIn(f"the {name} edge is rational", message)
            self.assertNotIn("p:", message)
            self.assertNotIn("R restricted", message)

    def test_edges_that_do_not_meet_are_refused_with_their_gap(self):
        # Two lines 566 mm apart used to be bridged by one 781 mm edge (deviation 320 mm).
        first = Part.makeLine(V(0, 0, 0), V(500, 0, 0))
        far = Part.makeLine(V(900, 400, 0), V(1400, 400, 0))
        near = Part.makeLine(V(510, 0, 0), V(1000, 0, 0))
        for second, distance in ((far, math.hypot(400, 400)), (near, 10.0)):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.merge_edges(first, second)
            message = str(caught.exception)
            self.assertIn("do not meet", message)
            found = re.search(r"ends are ([0-9.e+-]+) apart", message)
            self.assertIsNotNone(found, message)
            self.assertAlmostEqual(float(found.group(1)), distance, delta=1e-3)
            self.assertIn("max_gap", message)
        # The limit is a keyword: a length, or None for any gap.
        self.assertEqual(operations.merge_edges(first, near, max_gap=10.5).shape.ShapeType,
                         "Edge")
        with self.assertRaises(bezjoin.BezjoinError):
            operations.merge_edges(first, near, max_gap=9.5)
        self.assertEqual(operations.merge_edges(first, far, max_gap=None).shape.ShapeType,
                         "Edge")
        # A sketch solver's gap (1e-9 of the size) still merges.
        touching = Part.makeLine(V(500, 1e-7, 0), V(900, 1e-7, 0))
        self.assertEqual(operations.merge_edges(first, touching).shape.ShapeType, "Edge")

    def test_limits_that_are_not_numbers_are_refused_by_name(self):
        # MaxAngle = NaN passed every comparison and merged two lines at 90 degrees into
        # their chord (deviation 7.07 mm); a negative angle or gap was stored and used.
        first = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        second = Part.makeLine(V(10, 0, 0), V(10, 10, 0))
        with self.assertRaises(bezjoin.BezjoinError):
            operations.merge_edges(first, second)
        for keyword, value, name in (("max_angle", float("nan"), "MaxAngle"),
                                     ("max_angle", -10.0, "MaxAngle"),
                                     ("max_gap", float("nan"), "MaxGap"),
                                     ("max_gap", -1.0, "MaxGap")):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.merge_edges(first, second, **{keyword: value})
            self.assertIn(name, str(caught.exception))
            self.assertIn(keyword, str(caught.exception))
        straight = Part.makeLine(V(10, 0, 0), V(20, 0, 0))
        self.assertEqual(operations.merge_edges(first, straight, max_angle=0.0).shape.ShapeType,
                         "Edge")


class SharedVertices(unittest.TestCase):
    def test_blend_of_edges_sharing_a_vertex_is_refused(self):
        first = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        second = Part.makeLine(V(10, 0, 0), V(10, 10, 0))
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.blend_edges(first, second)
        self.assertIn("share a vertex", str(caught.exception))
        # positions apart still blend
        edge = operations.blend_edges(first, second, u0=0.5, v0=0.5)
        self.assertGreater(gap(edge.valueAt(edge.FirstParameter),
                               edge.valueAt(edge.LastParameter)), 1.0)

    def test_round_corner_uses_the_shared_vertex_when_the_edges_also_cross(self):
        first = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        curve = Part.BezierCurve()
        curve.setPoles([V(10, 0, 0), V(10, 6, 0), V(3, 6, 0), V(3, -3, 0)])
        second = Part.Edge(curve)
        # the second edge crosses the first one away from the vertex too (near x = 4)
        crossings = [p for p in first.section(second).Vertexes if p.Point.x < 9.0]
        self.assertEqual(len(crossings), 1)
        for options in ({"setback": 1.0}, {"radius": 0.5}):
            wire = operations.round_corner(first, second, **options)
            edges = wire.OrderedEdges
            # the blend is near the vertex (10, 0), the crossing near x = 4 is left alone
            blend = [e for e in edges if e.Curve.TypeId == "Part::GeomBezierCurve"
                     and e.distToShape(Part.Vertex(V(10, 0, 0)))[0] < 1.0]
            self.assertTrue(blend, options)
            cut_corners(self, wire, [(10, 0, 0)])
            ends = sorted([tuple(wire.OrderedVertexes[0].Point),
                           tuple(wire.OrderedVertexes[-1].Point)])
            self.assertLessEqual(gap(ends[0], (0, 0, 0)), 1e-12, options)
            self.assertLessEqual(gap(ends[1], (3, -3, 0)), 1e-12, options)

    def test_a_1e_7_gap_at_the_vertex_is_rounded(self):
        first = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        second = Part.makeLine(V(10, 1e-7, 0), V(10, 10, 0))
        for options in ({"setback": 1.0}, {"radius": 1.0}):
            wire = operations.round_corner(first, second, **options)
            self.assertEqual(len(wire.Edges), 3)
            ends = sorted([tuple(wire.OrderedVertexes[0].Point),
                           tuple(wire.OrderedVertexes[-1].Point)])
            self.assertLessEqual(gap(ends[0], (0, 0, 0)), 1e-12)
            self.assertLessEqual(gap(ends[1], (10, 10, 0)), 1e-12)
            cut_corners(self, wire, [(10, 0, 0)], 0.1)


class ChecksBeforeTheForm(unittest.TestCase):
    def drive_recording(self, command, inputs, parameters):
        """Activated() with the selection, the form and the message box replaced:
        (features made, messages shown, forms opened)."""
        document = FreeCAD.newDocument("BezjoinChecks")
        shown, opened = [], []
        saved_ask, saved_warning = commands.ask, commands.QtGui.QMessageBox.warning
        saved_main_window = getattr(commands.FreeCADGui, "getMainWindow", None)
        command.inputs = lambda: inputs
        commands.ask = lambda title, fields: opened.append(fields) or dict(parameters)
        commands.QtGui.QMessageBox.warning = lambda parent, title, text: shown.append(text)
        commands.FreeCADGui.getMainWindow = lambda: None
        try:
            FreeCAD.setActiveDocument(document.Name)
            command.Activated()
            made = [obj.Shape.copy() for obj in document.Objects
                    if obj.TypeId == "Part::Feature"]
            return made, shown, opened
        finally:
            commands.ask, commands.QtGui.QMessageBox.warning = saved_ask, saved_warning
            del command.inputs
            if saved_main_window is None:
                del commands.FreeCADGui.getMainWindow
            else:
                commands.FreeCADGui.getMainWindow = saved_main_window
            FreeCAD.closeDocument(document.Name)

    def test_bad_selections_are_refused_before_the_form_opens(self):
        line = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        offset = Part.OffsetCurve(Part.Circle(), 0.5, V(0, 0, 1)).toShape()
        for command in (commands.BlendCommand(), commands.RoundCornerCommand(),
                        commands.MergeCommand()):
            for inputs, words in (([line, offset], "second edge:"),
                                  ([line, line.copy()], "same edge")):
                made, shown, opened = self.drive_recording(command, inputs, {})
                self.assertEqual((made, opened), ([], []), command.title)
                self.assertEqual(len(shown), 1)
                self.assertIn(words, shown[0])

    def test_the_same_edge_twice_is_refused_by_the_operations(self):
        line = Part.makeLine(V(0, 0, 0), V(10, 0, 0))
        reversed_line = Part.makeLine(V(10, 0, 0), V(0, 0, 0))
        for operation in (operations.blend_edges, operations.merge_edges):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operation(line, reversed_line)
            self.assertIn("same edge", str(caught.exception))
        with self.assertRaises(bezjoin.BezjoinError):
            operations.round_corner(line, line, setback=1.0)

    def test_the_setback_default_scales_with_the_model(self):
        def lines(scale):
            return [Part.makeLine(V(0, 0, 0), V(40 * scale, 0, 0)),
                    Part.makeLine(V(40 * scale, 0, 0), V(40 * scale, 20 * scale, 0))]
        defaults = []
        for scale in (1.0, 10.0):
            fields = commands.RoundCornerCommand().fields_for(lines(scale))
            values = {key: default for key, _l, _k, default, _e in fields}
            self.assertEqual(values["setback"], values["second_setback"])
            defaults.append(values["setback"])
            # the operation's own default: the corner is cut that far from the vertex
            wire = operations.round_corner(*lines(scale))
            self.assertAlmostEqual(wire.OrderedEdges[0].Length, 40 * scale - values["setback"],
                                   delta=1e-9 * scale)
            blend = wire.OrderedEdges[1]
            self.assertLess(blend.Length, 2 * values["setback"])
        self.assertAlmostEqual(defaults[1], 10 * defaults[0], delta=1e-12)
        self.assertLess(defaults[0], 20.0)
        # The wire command's radius too (it started at 1 whatever the model's size),
        # and the wire rounds with it.
        for scale in (1.0, 100.0):
            path = lines(scale) + [Part.makeLine(V(40 * scale, 20 * scale, 0),
                                                 V(0, 20 * scale, 0))]
            fields = commands.RoundWireByRadiusCommand().fields_for(path)
            radius = {key: default for key, _l, _k, default, _e in fields}["radius"]
            self.assertAlmostEqual(radius, 2.0 * scale, delta=1e-12 * scale)
            self.assertEqual(len(operations.round_wire_by_radius(path, radius).reports), 2)

    def test_orders_above_the_bezier_limit_are_refused_before_building(self):
        first = Part.makeLine(V(0, 0, 0), V(2, 0, 0))
        second = Part.makeLine(V(3, 1, 0), V(3, 3, 0))
        self.assertLessEqual(2 * commands.MAX_ORDER + 1, operations.MAX_BEZIER_DEGREE)
        edge = operations.blend_edges(first, second, p_order=commands.MAX_ORDER,
                                      q_order=commands.MAX_ORDER)
        self.assertTrue(edge.isValid())
        for call in (lambda: operations.blend_edges(first, second, p_order=13, q_order=13),
                     lambda: operations.round_corner(
                         Part.makeLine(V(0, 0, 0), V(4, 0, 0)),
                         Part.makeLine(V(4, 0, 0), V(4, 4, 0)), setback=1.0, p_order=20,
                         q_order=6)):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                call()
            self.assertEqual(caught.exception.status_name, "BZJ_ERR_INVALID_ARGUMENT")
            self.assertIn("degree 27", str(caught.exception))

    def test_articles_in_messages(self):
        class Ellipse:
            pass
        with self.assertRaises(Exception) as caught:
            operations.edge_curve(Ellipse(), "first edge")
        self.assertIn("an Ellipse", str(caught.exception))
        self.assertNotIn("a Ellipse", str(caught.exception))
        self.assertEqual(operations.with_articles("a Part.Line and a ellipse"),
                         "a Part.Line and an ellipse")
