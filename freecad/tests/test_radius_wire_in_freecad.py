"""Issue 18 in the workbench, judged by FreeCAD: the operations' defaults never loop
(the automatic scale), and "Round wire corners by radius" rounds every corner of an
open or closed wire (lines and arcs, edges in any direction) G2, cutting each corner
where the arc of that radius touches its edges."""

import math
import unittest

import FreeCAD
import Part

import bezjoin
from bezjoin_workbench import commands, operations
from judge import gap
from test_operations_in_freecad import CommandDriver

V = FreeCAD.Vector


def assert_g2_path(test, wire, closed):
    """Consecutive edges of ``wire`` meet with the same tangent and curvature (and the
    last meets the first when ``closed``)."""
    edges = wire.OrderedEdges
    pairs = list(zip(edges, edges[1:]))
    if closed:
        pairs.append((edges[-1], edges[0]))
    for left, right in pairs:
        a, b = left.valueAt(left.LastParameter), right.valueAt(right.FirstParameter)
        test.assertLessEqual(gap(a, b), 1e-9)
        test.assertLessEqual(gap(left.tangentAt(left.LastParameter),
                                 right.tangentAt(right.FirstParameter)), 1e-8)
        test.assertLessEqual(abs(left.curvatureAt(left.LastParameter)
                                 - right.curvatureAt(right.FirstParameter)), 1e-6)


def self_intersects(edge, count=400):
    """Whether a planar (z = 0) edge crosses itself: two non-adjacent chords of a
    dense polyline on it cross."""
    points = [edge.valueAt(edge.FirstParameter + i / count * (edge.LastParameter
                                                               - edge.FirstParameter))
              for i in range(count + 1)]

    def orientation(p, q, r):
        return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x)

    chords = list(zip(points, points[1:]))
    for i, (a, b) in enumerate(chords):
        for c, d in chords[i + 2:]:
            if (orientation(a, b, c) * orientation(a, b, d) < 0
                    and orientation(c, d, a) * orientation(c, d, b) < 0):
                return True
    return False


class DefaultsNeverLoop(unittest.TestCase):
    """Lines 40 and 20 long meeting at a vertex, setback 2 (issue 18's example)."""

    first = Part.makeLine(V(-40, 0, 0), V(0, 0, 0))
    second = Part.makeLine(V(0, 0, 0), V(0, 20, 0))

    def test_round_corner_default_stays_in_the_corner(self):
        quarter_arc = math.pi  # radius 2, a right angle
        paper = operations.round_corner(self.first, self.second, setback=2.0,
                                        auto_scale=False)
        self.assertTrue(self_intersects(paper.OrderedEdges[1]))
        for wire in (operations.round_corner(self.first, self.second, setback=2.0),
                     operations.round_corner(self.second, self.first, setback=2.0)):
            blend = wire.OrderedEdges[1]
            self.assertFalse(self_intersects(blend))
            self.assertLess(blend.Length, 2 * quarter_arc)
            self.assertTrue(all(p.x <= 1e-12 and p.y >= -1e-12 for p in blend.Curve.getPoles()))
            edges = wire.OrderedEdges
            for left, right in zip(edges, edges[1:]):
                self.assertLessEqual(gap(left.tangentAt(left.LastParameter),
                                         right.tangentAt(right.FirstParameter)), 1e-9)

    def test_blend_default_stays_in_the_corner(self):
        # The gap between the lines' facing ends, bridged by the default blend.
        first = Part.makeLine(V(-40, 0, 0), V(-2, 0, 0))
        second = Part.makeLine(V(0, 2, 0), V(0, 20, 0))
        paper = operations.blend_edges(first, second, auto_scale=False)
        self.assertTrue(self_intersects(paper))
        edge = operations.blend_edges(first, second)
        self.assertFalse(self_intersects(edge))
        self.assertTrue(all(p.x <= 1e-12 and p.y >= -1e-12 for p in edge.Curve.getPoles()))
        # explicit scales are the raw construction, as before
        scaled = operations.blend_edges(first, second, p_scale=1.0, q_scale=1.0)
        self.assertEqual(scaled.Curve.getPoles(), paper.Curve.getPoles())


class RoundWireByRadius(unittest.TestCase, CommandDriver):
    def test_closed_rectangle_is_cut_at_the_radius_and_g2(self):
        wire = Part.makePolygon([V(0, 0, 0), V(10, 0, 0), V(10, 6, 0), V(0, 6, 0), V(0, 0, 0)])
        rounded = operations.round_wire_by_radius(wire, 1.5)
        self.assertTrue(rounded.closed)
        self.assertEqual(len(rounded.reports), 4)
        shape = rounded.shape
        self.assertTrue(shape.isValid() and shape.isClosed())
        self.assertEqual(len(shape.Edges), 8)
        assert_g2_path(self, shape, closed=True)
        # At a right angle the arc of radius r touches each side r from the vertex:
        # the kept sides are 10 - 3 and 6 - 3 long.
        lines = sorted(e.Length for e in shape.Edges if e.Curve.TypeId != "Part::GeomBezierCurve")
        for got, want in zip(lines, [3.0, 3.0, 7.0, 7.0]):
            self.assertAlmostEqual(got, want, delta=1e-9)
        # The kept parts of the sides are line segments, as the sides were (user testing,
        # session 44: B8 gave degree-1 Bezier edges), by radius and by setback.
        for wire in (shape, operations.round_wire(wire, setback=1.5)):
            kinds = sorted(e.Curve.TypeId for e in wire.Edges)
            self.assertEqual(kinds.count("Part::GeomLine"), 4, kinds)
        # Every corner vertex is cut off; every blend stays in its corner and has one
        # curvature maximum, measured by FreeCAD.
        for corner in ((0, 0), (10, 0), (10, 6), (0, 6)):
            self.assertGreater(shape.distToShape(Part.Vertex(V(*corner, 0)))[0], 0.1)
        for report in rounded.reports:
            self.assertEqual(report.curvature_extrema, 1)
            self.assertLess(report.arc_deviation, 1.5)

    def slot_edges(self):
        """A slot-like profile: a line, a half circle of radius 150 tangent to it and to
        the next line (two smooth joins), the next line, and a closing line with two
        right-angle corners."""
        arc = Part.ArcOfCircle(Part.Circle(V(800, 150, 0), V(0, 0, 1), 150.0),
                               -0.5 * math.pi, 0.5 * math.pi).toShape()
        return [Part.makeLine(V(0, 0, 0), V(800, 0, 0)), arc,
                Part.makeLine(V(800, 300, 0), V(0, 300, 0)),
                Part.makeLine(V(0, 300, 0), V(0, 0, 0))]

    def test_smooth_joins_are_left_as_they_are(self):
        edges = self.slot_edges()
        rounded = operations.round_wire_by_radius(edges, 20.0)
        self.assertTrue(rounded.closed)
        # The two right-angle corners rounded, the two tangent joins (after edge 1 and
        # after edge 2 along the path) kept.
        self.assertEqual(len(rounded.reports), 2)
        self.assertEqual(sorted(rounded.smooth_joins), [1, 2])
        self.assertIn("2 smooth joins left as they are", rounded.describe())
        shape = rounded.shape
        self.assertTrue(shape.isValid() and shape.isClosed())
        self.assertEqual(len(shape.Edges), 6)
        Part.Face(shape)
        # The half circle is kept whole and the sharp corners are cut off.
        arcs = [e for e in shape.Edges if abs(e.Length - 150.0 * math.pi) < 1e-9]
        self.assertEqual(len(arcs), 1)
        # G2 at the four joins of the blends; the smooth joins stay what they were:
        # the same tangent, the curvature stepping from the line's 0 to the arc's 1/150.
        ordered = shape.OrderedEdges
        for left, right in zip(ordered, ordered[1:] + ordered[:1]):
            a, b = left.LastParameter, right.FirstParameter
            self.assertLessEqual(gap(left.valueAt(a), right.valueAt(b)), 1e-9)
            self.assertLessEqual(gap(left.tangentAt(a), right.tangentAt(b)), 1e-8)
            step = abs(left.curvatureAt(a) - right.curvatureAt(b))
            if arcs[0].isSame(left) or arcs[0].isSame(right):
                self.assertAlmostEqual(step, 1 / 150.0, delta=1e-9)
            else:
                self.assertLessEqual(step, 1e-6)
        for corner in ((0, 0), (0, 300)):
            self.assertGreater(shape.distToShape(Part.Vertex(V(*corner, 0)))[0], 1.0)
        for point in ((400, 0), (800, 0), (950, 150), (800, 300), (400, 300)):
            self.assertLess(shape.distToShape(Part.Vertex(V(*point, 0)))[0], 1e-9)
        # By setback too (C^k blends, the automatic scale), and on the path started
        # elsewhere and run the other way.
        for path in (edges, edges[2:] + edges[:2], list(reversed(edges))):
            for wire in (operations.round_wire(path, setback=10.0),
                         operations.round_wire(path, radius=20.0)):
                self.assertTrue(wire.isValid() and wire.isClosed())
                self.assertEqual(len(wire.Edges), 6)
                self.assertTrue(any(abs(e.Length - 150.0 * math.pi) < 1e-9
                                    for e in wire.Edges))

    def test_a_line_split_in_collinear_pieces_rounds_as_the_whole_line(self):
        # User testing, session 44 (B7): a line split into pieces of 1000 and 0.1 (as
        # sketches have them) blocked a fillet that fits the unsplit line: the smooth
        # join between the pieces ended a run. The pieces are now rounded as one line,
        # and a split vertex the rounding does not reach is kept.
        corner = V(1000.1, 0, 0)
        up = Part.makeLine(corner, V(1000.1, 50, 0))
        whole = [Part.makeLine(V(0, 0, 0), corner), up]
        split = [Part.makeLine(V(0, 0, 0), V(1000, 0, 0)), Part.makeLine(V(1000, 0, 0), corner),
                 up]

        def samples(wire):
            return [edge.valueAt(edge.FirstParameter + f * (edge.LastParameter
                                                            - edge.FirstParameter))
                    for edge in wire.OrderedEdges for f in (0.0, 0.3, 0.7, 1.0)]

        for options in (dict(radius=5.0), dict(setback=5.0)):
            expected = operations.round_wire(whole, **options)
            got = operations.round_wire(split, **options)
            self.assertEqual(len(got.Edges), 3, options)
            for a, b in zip(samples(got), samples(expected)):
                self.assertLessEqual(gap(a, b), 1e-9, options)
        # Split at 900: the fillet of radius 5 ends 5 before the corner, so the split
        # vertex stays, a smooth join left as it is, the rest as the whole line's.
        far = [Part.makeLine(V(0, 0, 0), V(900, 0, 0)), Part.makeLine(V(900, 0, 0), corner), up]
        rounded = operations.round_wire_by_radius(far, 5.0)
        self.assertEqual(rounded.smooth_joins, [1])
        self.assertIn("1 smooth joins left as they are", rounded.describe())
        shape = rounded.shape
        self.assertEqual(len(shape.Edges), 4)
        self.assertTrue(any(gap(v.Point, V(900, 0, 0)) <= 1e-12 for v in shape.Vertexes))
        assert_g2_path(self, shape, closed=False)
        expected = operations.round_wire(whole, radius=5.0)
        self.assertAlmostEqual(shape.Length, expected.Length, delta=1e-9)
        # The same path given backwards, its edges reversed, and as a closed
        # triangle: the split vertex kept, the wire valid and G2.
        backwards = [Part.makeLine(V(1000.1, 50, 0), corner), Part.makeLine(corner, V(900, 0, 0)),
                     Part.makeLine(V(900, 0, 0), V(0, 0, 0))]
        triangle = far + [Part.makeLine(V(1000.1, 50, 0), V(0, 0, 0))]
        for path, closed in ((backwards, False), (triangle, True)):
            rounded = operations.round_wire_by_radius(path, 5.0)
            shape = rounded.shape
            self.assertTrue(shape.isValid(), path)
            self.assertEqual(len(rounded.smooth_joins), 1)
            self.assertTrue(any(gap(v.Point, V(900, 0, 0)) <= 1e-12 for v in shape.Vertexes))
            assert_g2_path(self, shape, closed=closed)
        # A fillet that fits neither names the corner as a call on the unsplit path
        # would number it along the split one (between edges 2 and 3: corner 1).
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(split, 2000.0)
        self.assertIn("corner 1", str(caught.exception))

    def test_a_bad_setback_is_named_as_the_setback(self):
        # User testing, session 43: setback=-1 gave "p_setback = -1 is outside > 0",
        # the library's argument name and range notation.
        square = Part.makePolygon([V(0, 0, 0), V(10, 0, 0), V(10, 10, 0), V(0, 10, 0),
                                   V(0, 0, 0)])
        for bad in (-1.0, 0.0, math.inf, math.nan):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.round_wire(square, setback=bad)
            message = str(caught.exception)
            self.assertIn("setback (Setback) must be a length above 0", message)
            self.assertNotIn("p_setback", message)
        self.assertTrue(operations.round_wire(square, setback=1.0).isClosed())

    def test_closed_on_an_open_path_says_the_path_is_open(self):
        # User testing, session 43: closed=True on a U whose ends are 10 apart said only
        # "corner 2: the curves do not cross".
        u = Part.makePolygon([V(0, 10, 0), V(0, 0, 0), V(10, 0, 0), V(10, 10, 0)])
        for options in (dict(radius=1.0), dict(setback=1.0)):
            with self.assertRaises(bezjoin.BezjoinError) as caught:
                operations.round_wire(u, closed=True, **options)
            message = str(caught.exception)
            self.assertIn("the path is open: its ends are 10 apart", message)
            self.assertFalse(operations.round_wire(u, **options).isClosed())

    def test_errors_number_corners_and_edges_along_the_whole_path(self):
        # The slot is rounded in one run (edges 3, 4, 1 along the path after its
        # smooth joins); the library's run-local numbers are given as path numbers.
        edges = self.slot_edges()
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(edges, 200.0)  # two arcs of 200 on a 300 side
        self.assertIn("curves[3]", str(caught.exception))
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(edges, 900.0)
        self.assertIn("corner 2 radius", str(caught.exception))

    def test_a_zero_tangent_join_is_not_taken_for_a_smooth_one(self):
        # A Bezier edge with a repeated first pole has no tangent at its start: that
        # join has no direction to compare, so the library judges it (and refuses it
        # by name) instead of the workbench leaving it unrounded.
        cusp = Part.BezierCurve()
        cusp.setPoles([V(10, 0, 0), V(10, 0, 0), V(10, 5, 0), V(10, 10, 0)])
        edges = [Part.makeLine(V(0, 0, 0), V(10, 0, 0)), cusp.toShape(),
                 Part.makeLine(V(10, 10, 0), V(0, 10, 0))]
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(edges, 1.0)
        self.assertIn("tangent is zero", str(caught.exception))

    def test_a_wire_with_only_smooth_joins_has_no_corner_to_round(self):
        top = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 5.0), 0.0,
                               math.pi).toShape()
        bottom = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 5.0), math.pi,
                                  2 * math.pi).toShape()
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius([top, bottom], 1.0)
        self.assertIn("every join of the wire is smooth", str(caught.exception))

    def test_open_sketch_path_with_an_arc_and_reversed_edges(self):
        # line -> quarter arc (radius 3, tangent to neither line) -> line, edges in
        # mixed directions as a sketch may store them.
        arc = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 3.0), 0.0,
                               0.5 * math.pi).toShape()
        start = Part.makeLine(V(3, 0, 0), V(5, -4, 0))  # runs away from the arc
        end = Part.makeLine(V(-5, 4, 0), V(0, 3, 0))  # ends at the arc's end
        rounded = operations.round_wire_by_radius([start, arc, end], 0.5)
        self.assertFalse(rounded.closed)
        self.assertEqual(len(rounded.reports), 2)
        shape = rounded.shape
        self.assertEqual(len(shape.Edges), 5)
        assert_g2_path(self, shape, closed=False)
        ends = sorted([tuple(shape.OrderedVertexes[0].Point),
                       tuple(shape.OrderedVertexes[-1].Point)])
        self.assertEqual(ends, [(-5.0, 4.0, 0.0), (5.0, -4.0, 0.0)])
        # The arc's kept part stays on its circle.
        arc_part = [e for e in shape.Edges
                    if abs(e.curvatureAt(0.5 * (e.FirstParameter + e.LastParameter)) - 1 / 3)
                    < 1e-9]
        self.assertEqual(len(arc_part), 1)
        for i in range(11):
            t = arc_part[0].FirstParameter + i / 10 * (arc_part[0].LastParameter
                                                       - arc_part[0].FirstParameter)
            self.assertAlmostEqual(arc_part[0].valueAt(t).Length, 3.0, delta=1e-12)

    def test_closed_choice_overrides_the_path(self):
        wire = Part.makePolygon([V(0, 0, 0), V(8, 0, 0), V(8, 8, 0), V(0, 0, 0)])
        open_rounded = operations.round_wire_by_radius(wire, 1.0, closed=False)
        self.assertEqual(len(open_rounded.reports), 2)
        self.assertEqual(len(open_rounded.shape.Edges), 5)
        # The corner from the last edge back to the first is kept sharp; the others are cut.
        self.assertLessEqual(open_rounded.shape.distToShape(Part.Vertex(V(0, 0, 0)))[0], 1e-12)
        for corner in ((8, 0), (8, 8)):
            self.assertGreater(open_rounded.shape.distToShape(Part.Vertex(V(*corner, 0)))[0],
                               0.05)
        closed_rounded = operations.round_wire_by_radius(wire, 1.0, order=3)
        self.assertEqual(len(closed_rounded.reports), 3)
        assert_g2_path(self, closed_rounded.shape, closed=True)

    def test_errors_name_the_radius_and_the_path(self):
        wire = Part.makePolygon([V(0, 0, 0), V(4, 0, 0), V(4, 4, 0)])
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(wire, 50.0)
        self.assertEqual(caught.exception.status_name, "BZJ_ERR_INVALID_ARGUMENT")
        self.assertIn("radius", caught.exception.message)
        apart = [Part.makeLine(V(0, 0, 0), V(4, 0, 0)), Part.makeLine(V(5, 1, 0), V(5, 4, 0))]
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius(apart, 1.0)
        self.assertIn("edge 2", caught.exception.message)
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.round_wire_by_radius([Part.makeLine(V(0, 0, 0), V(4, 0, 0))], 1.0)
        self.assertIn("at least 2 edges", caught.exception.message)

    def test_round_wire_command(self):
        wire = Part.makePolygon([V(0, 0, 0), V(10, 0, 0), V(10, 6, 0), V(0, 6, 0), V(0, 0, 0)])
        parameters = {"radius": 1.0, "order": 2, "closed": "auto"}
        made, shown = self.drive(commands.RoundWireByRadiusCommand(), wire.OrderedEdges,
                                 parameters)
        self.assertEqual(shown, [])
        ((name, shape, report),) = made
        self.assertEqual(name, "RoundedWire")
        self.assertEqual(len(shape.Edges), 8)
        self.assertEqual(report["FilletRadius"], 1.0)
        self.assertGreater(report["MaxArcDeviation"], 0.0)
        made, shown = self.drive(commands.RoundWireByRadiusCommand(), wire.OrderedEdges,
                                 dict(parameters, closed="no"))
        self.assertEqual(len(made[0][1].Edges), 7)
        made, shown = self.drive(commands.RoundWireByRadiusCommand(), wire.OrderedEdges,
                                 dict(parameters, radius=40.0))
        self.assertEqual(made, [])
        self.assertTrue(shown[0].startswith("BZJ_ERR_INVALID_ARGUMENT: "), shown)
        self.assertIn("radius", shown[0])
