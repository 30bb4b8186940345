"""bezjoin's operations judged by FreeCAD: curves built as FreeCAD objects go through
bezjoin and come back as Part.BezierCurve; the pieces must meet, and the chain joined
into one Part.BSplineCurve must have the promised continuity (knot removal and
one-sided derivatives from getDN); the merged curve's FreeCAD segment at mu must be
P^ and Q^. The workbench operations are driven the same way."""

import math
import random
import unittest

import FreeCAD
import Part

import bezjoin
from bezjoin import Curve
from bezjoin_workbench import commands, operations
from judge import (bezier, chain_bspline, derivative_jumps, gap, poles, size,
                   smoothness_by_knot_removal)

V = FreeCAD.Vector


def random_points(rng, degree, spread=3.0):
    return [tuple(rng.uniform(-spread, spread) for _ in range(3)) for _ in range(degree + 1)]


def assert_chain_smooth(test, pieces, widths, order):
    """Pieces meet to 1e-12 (relative to their size) and every join is C^order."""
    scale = size(pieces)
    for left, right in zip(pieces, pieces[1:]):
        test.assertLessEqual(gap(left.EndPoint, right.StartPoint), 1e-12 * scale)
    for i in range(len(pieces) - 1):
        jumps = derivative_jumps(pieces[i], widths[i], pieces[i + 1], widths[i + 1], order)
        test.assertLess(max(jumps), 1e-10, (i, jumps))
    spline = chain_bspline(pieces, widths)
    for index in range(2, len(pieces) + 1):
        test.assertGreaterEqual(smoothness_by_knot_removal(spline, index, 1e-9 * scale), order)
    return spline


class CommandDriver:
    """Activated() with the selection and the form replaced: a feature is made, or the
    library's message is shown."""

    def drive(self, command, inputs, parameters):
        document = FreeCAD.newDocument("BezjoinCommands")
        shown = []
        saved_ask, saved_warning = commands.ask, commands.QtGui.QMessageBox.warning
        saved_main_window = getattr(commands.FreeCADGui, "getMainWindow", None)
        command.inputs = lambda: inputs
        commands.ask = lambda title, fields: dict(parameters)
        commands.QtGui.QMessageBox.warning = lambda parent, title, text: shown.append(text)
        commands.FreeCADGui.getMainWindow = lambda: None
        try:
            FreeCAD.setActiveDocument(document.Name)
            command.Activated()
            made = [(obj.Name, obj.Shape.copy(),
                     {name: getattr(obj, name) for name in obj.PropertiesList
                      if obj.getGroupOfProperty(name) == "Bezjoin"})
                    for obj in document.Objects if obj.TypeId == "Part::Feature"]
            return made, shown
        finally:
            commands.ask, commands.QtGui.QMessageBox.warning = saved_ask, saved_warning
            del command.inputs  # back to the class's selection reader
            if saved_main_window is None:
                del commands.FreeCADGui.getMainWindow
            else:
                commands.FreeCADGui.getMainWindow = saved_main_window
            FreeCAD.closeDocument(document.Name)


class ConnectJudgedByFreeCAD(unittest.TestCase, CommandDriver):
    """P|[0,u0] and Q|[v0,1] cut by FreeCAD's own segment, R from bezjoin: the chain
    is C^k over the knot intervals (u0, alpha, (1 - v0) alpha / beta)."""

    def check_chain(self, p_points, q_points, u0, v0, order, alpha, beta):
        p_freecad, q_freecad = bezier(p_points), bezier(q_points)
        with Curve.from_freecad(p_freecad) as p, Curve.from_freecad(q_freecad) as q, \
                bezjoin.connect(p, u0, q, v0, p_order=order, q_order=order, p_scale=alpha,
                                q_scale=beta) as r:
            blend = r.to_freecad()
        p_kept, q_kept = p_freecad.copy(), q_freecad.copy()
        p_kept.segment(0.0, u0)
        q_kept.segment(v0, 1.0)
        spline = assert_chain_smooth(self, [p_kept, blend, q_kept],
                                     [u0, alpha, (1.0 - v0) * alpha / beta], order)
        edge = Part.Edge(spline)
        scale = size([p_freecad, q_freecad])
        self.assertLessEqual(gap(edge.valueAt(edge.FirstParameter), p_points[0]), 1e-12 * scale)
        self.assertLessEqual(gap(edge.valueAt(edge.LastParameter), q_points[-1]), 1e-12 * scale)
        return blend

    def test_paper_mode_cubics_give_a_c3_chain_of_degree_7(self):
        rng = random.Random(11)
        blend = self.check_chain(random_points(rng, 3), random_points(rng, 3), 0.8, 0.15, 3,
                                 1.0, 1.0)
        self.assertEqual(blend.Degree, 7)

    def test_scaled_c2_blend_between_different_degrees(self):
        rng = random.Random(12)
        blend = self.check_chain(random_points(rng, 4), random_points(rng, 3), 0.65, 0.4, 2,
                                 1.6, 0.7)
        self.assertEqual(blend.Degree, 5)

    def test_bridge_between_end_points(self):
        rng = random.Random(13)
        self.check_chain(random_points(rng, 2), random_points(rng, 5), 1.0, 0.0, 1, 1.0, 1.0)

    def test_blend_edges_bridges_the_facing_ends(self):
        first_curve = bezier([(0, 0, 0), (1, 1, 0), (2, 1, 0)])
        second_curve = bezier([(6, 0, 0), (5, 1, 0), (4, 1, 0)])
        edge = operations.blend_edges(Part.Edge(first_curve), Part.Edge(second_curve),
                                      p_order=2, q_order=2, p_scale=1.2, q_scale=0.8)
        blend = edge.Curve
        self.assertEqual(blend.Degree, 5)
        self.assertEqual(tuple(blend.StartPoint), (2.0, 1.0, 0.0))
        self.assertEqual(tuple(blend.EndPoint), (4.0, 1.0, 0.0))
        second_forward = second_curve.copy()
        second_forward.reverse()
        assert_chain_smooth(self, [first_curve, blend, second_forward], [1.0, 1.2, 1.2 / 0.8], 2)

    def test_blend_command_makes_a_feature_or_shows_the_reason(self):
        first = Part.Edge(bezier([(0, 0, 0), (1, 1, 0), (2, 1, 0)]))
        second = Part.Edge(bezier([(4, 1, 0), (5, 1, 0), (6, 0, 0)]))
        parameters = {"u0": 1.0, "v0": 0.0, "p_order": None, "q_order": 1, "p_scale": 1.0,
                      "q_scale": 1.0, "auto_scale": False}
        made, shown = self.drive(commands.BlendCommand(), [first, second], parameters)
        self.assertEqual(shown, [])
        self.assertEqual(len(made), 1)
        self.assertEqual(made[0][1].Edges[0].Curve.Degree, 2 + 1 + 1)
        offset = Part.OffsetCurve(Part.Circle(), 0.5, FreeCAD.Vector(0, 0, 1)).toShape()
        made, shown = self.drive(commands.BlendCommand(), [first, offset], parameters)
        self.assertEqual(made, [])
        self.assertEqual(len(shown), 1)
        self.assertIn("second edge:", shown[0])
        self.assertIn("OffsetCurve", shown[0])
        made, shown = self.drive(commands.BlendCommand(), [first, second],
                                 dict(parameters, p_scale=-1.0))
        self.assertEqual(made, [])
        self.assertTrue(shown[0].startswith("BZJ_ERR_INVALID_ARGUMENT: "), shown)


    def test_blend_with_an_order_above_a_line_degree(self):
        line = bezier([(0, 0, 0), (2, 0, 0)])
        arc_like = bezier([(3, 1, 0), (3, 2, 0), (2, 3, 0)])
        edge = operations.blend_edges(Part.Edge(line), Part.Edge(arc_like), p_order=2,
                                      q_order=2, auto_scale=False)
        blend = edge.Curve
        self.assertEqual(blend.Degree, 5)
        # C2 to the line: the blend's second derivative vanishes where it leaves the line
        self.assertLessEqual(gap(blend.getDN(0.0, 2), (0, 0, 0)), 1e-12)
        assert_chain_smooth(self, [line, blend, arc_like], [1.0, 1.0, 1.0], 2)

    def test_blend_with_automatic_scale_is_a_smooth_chain_at_that_scale(self):
        first_curve = bezier([(0, 0, 0), (1, 1, 0), (2, 1, 0)])
        second_curve = bezier([(4, 1, 0), (5, 1, 0), (6, 0, 0)])
        edge = operations.blend_edges(Part.Edge(first_curve), Part.Edge(second_curve),
                                      p_order=2, q_order=2, auto_scale=True)
        with Curve.from_freecad(first_curve) as p, Curve.from_freecad(second_curve) as q, \
                bezjoin.connect_auto_scale(p, 1.0, q, 0.0, p_order=2, q_order=2) as result:
            scale = result.scale
            self.assertEqual(poles(edge.Curve), result.curve.points)
        assert_chain_smooth(self, [first_curve, edge.Curve, second_curve], [1.0, scale, 1.0], 2)


class RoundCornerJudgedByFreeCAD(unittest.TestCase, CommandDriver):
    def test_fillet_pieces_form_a_smooth_bspline(self):
        p_freecad = bezier([(0, 0, 0), (1, 0.3, 0), (2, 1.2, 0), (3, 3.0, 0)])
        q_freecad = bezier([(0, 3.0, 0), (1.2, 2.0, 0), (2.5, 1.6, 0), (4, 1.0, 0)])
        for order, alpha, beta in ((1, 1.0, 1.0), (2, 1.3, 0.9)):
            with Curve.from_freecad(p_freecad) as p, Curve.from_freecad(q_freecad) as q, \
                    bezjoin.fillet(p, q, p_setback=0.5, q_setback=0.7, p_order=order,
                                   q_order=order, p_scale=alpha, q_scale=beta) as result:
                pieces = [c.to_freecad() for c in result.curves()]
            # u0 and v0 from FreeCAD's own projection of the kept ends onto P and Q
            u0 = p_freecad.parameter(pieces[0].EndPoint)
            v0 = q_freecad.parameter(pieces[2].StartPoint)
            self.assertLessEqual(gap(p_freecad.value(u0), pieces[0].EndPoint), 1e-9)
            kept = p_freecad.copy()
            kept.segment(0.0, u0)
            self.assertEqual(len(poles(pieces[0])), len(poles(kept)))
            for ours, theirs in zip(poles(pieces[0]), poles(kept)):
                self.assertLessEqual(gap(ours, theirs), 1e-9)
            assert_chain_smooth(self, pieces, [u0, alpha, (1 - v0) * alpha / beta], order)

    def test_round_corner_of_a_path_and_of_crossing_edges(self):
        # an L corner: the edges only share the vertex (2, 0, 0)
        first = Part.makeLine(V(0, 0, 0), V(2, 0, 0))
        second = Part.Edge(bezier([(2, 0, 0), (2, 1, 0), (3, 2, 0)]))
        wire = operations.round_corner(second, first, setback=0.5, p_order=2, q_order=2)
        self.assertEqual(len(wire.Edges), 3)
        self.assertTrue(wire.isValid())
        ends = sorted([tuple(wire.OrderedVertexes[0].Point),
                       tuple(wire.OrderedVertexes[-1].Point)])
        self.assertEqual(ends, [(0.0, 0.0, 0.0), (3.0, 2.0, 0.0)])
        # the corner vertex is cut off at the setback from it
        self.assertGreater(wire.distToShape(Part.Vertex(V(2, 0, 0)))[0], 0.01)
        edges = wire.OrderedEdges
        for left, right in zip(edges, edges[1:]):
            self.assertLessEqual(gap(left.valueAt(left.LastParameter),
                                     right.valueAt(right.FirstParameter)), 1e-12)
            a = left.tangentAt(left.LastParameter)
            b = right.tangentAt(right.FirstParameter)
            self.assertLessEqual(gap(a, b), 1e-9)
            # C2 through a line: the curvature is continuous (zero on the line side)
            self.assertLessEqual(abs(left.curvatureAt(left.LastParameter)
                                     - right.curvatureAt(right.FirstParameter)), 1e-7)
        # crossing edges
        cross = operations.round_corner(Part.makeLine(V(0, 0, 0), V(4, 4, 0)),
                                        Part.makeLine(V(0, 4, 0), V(4, 0, 0)), setback=1.0,
                                        p_order=1, q_order=1)
        self.assertEqual(len(cross.Edges), 3)
        self.assertLessEqual(gap(cross.OrderedVertexes[0].Point, (0, 0, 0)), 1e-12)
        self.assertLessEqual(gap(cross.OrderedVertexes[-1].Point, (4, 0, 0)), 1e-12)

    def test_round_corner_of_an_arc_and_a_line_at_a_sketch_vertex(self):
        # A sketch's arc (radius 3, a quarter turn) and a line leaving its end
        # with a solver's gap of 3e-8: the vertex is rounded C2, the arc part
        # stays on the circle, the curvature runs from 1/3 to 0.
        arc = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 3.0), 0.0, 0.5 * math.pi)
        arc_edge = arc.toShape()
        line_edge = Part.makeLine(V(0, 3 + 3e-8, 0), V(-4, 3, 0))
        for first, second in ((arc_edge, line_edge), (line_edge, arc_edge)):
            wire = operations.round_corner(first, second, setback=0.6, p_order=2, q_order=2)
            self.assertEqual(len(wire.Edges), 3)
            edges = wire.OrderedEdges
            for left, right in zip(edges, edges[1:]):
                self.assertLessEqual(gap(left.valueAt(left.LastParameter),
                                         right.valueAt(right.FirstParameter)), 1e-9)
                self.assertLessEqual(gap(left.tangentAt(left.LastParameter),
                                         right.tangentAt(right.FirstParameter)), 1e-8)
                self.assertLessEqual(abs(left.curvatureAt(left.LastParameter)
                                         - right.curvatureAt(right.FirstParameter)), 1e-7)
            arc_part = [e for e in edges
                        if abs(e.curvatureAt(0.5 * (e.FirstParameter + e.LastParameter))
                               - 1 / 3) < 1e-9]
            self.assertEqual(len(arc_part), 1)
            for i in range(11):
                t = arc_part[0].FirstParameter + i / 10 * (arc_part[0].LastParameter
                                                           - arc_part[0].FirstParameter)
                self.assertAlmostEqual(arc_part[0].valueAt(t).Length, 3.0, delta=1e-12)

    def test_blend_from_an_arc_end_to_a_line(self):
        arc = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 2.0), 0.3, 1.2).toShape()
        line = Part.makeLine(V(-1, 4, 0), V(-3, 5, 0))
        edge = operations.blend_edges(arc, line, p_order=2, q_order=1)
        # the blend starts at the arc's end with its tangent direction
        end = arc.valueAt(arc.LastParameter)
        self.assertLessEqual(gap(edge.valueAt(edge.FirstParameter), end), 1e-12)
        a = edge.tangentAt(edge.FirstParameter)
        b = arc.tangentAt(arc.LastParameter)
        self.assertLessEqual(gap(a, b), 1e-9)

    def test_round_corner_with_auto_scale_stays_inside_the_corner(self):
        # Long lines, short setback: scale 1 loops past the corner (2, 0, 0);
        # the automatic scale keeps the blend inside the corner's quadrant.
        first = Part.makeLine(V(-6, 0, 0), V(2, 0, 0))
        second = Part.makeLine(V(2, 0, 0), V(2, 8, 0))
        for auto, inside in ((False, False), (True, True)):
            wire = operations.round_corner(first, second, setback=0.5, p_order=2, q_order=2,
                                           auto_scale=auto)
            blend = wire.OrderedEdges[1].Curve
            poles = blend.getPoles()
            self.assertEqual(all(p.x <= 2 + 1e-12 and p.y >= -1e-12 for p in poles), inside,
                             (auto, poles))
            edges = wire.OrderedEdges
            for left, right in zip(edges, edges[1:]):
                self.assertLessEqual(gap(left.valueAt(left.LastParameter),
                                         right.valueAt(right.FirstParameter)), 1e-12)
                self.assertLessEqual(gap(left.tangentAt(left.LastParameter),
                                         right.tangentAt(right.FirstParameter)), 1e-9)

    def test_auto_scale_does_not_depend_on_how_fast_the_edges_run(self):
        # FreeCAD's lines run at their length and arcs at their radius. With one scale
        # for both ends, a 90 degree corner of lines 1000 and 10 long (setback 1, the
        # default orders 1 and 1) got a blend whose curvature peaked at 1.29e4, and a
        # line into an arc of radius 500 one at 26 times the G1 arc's (user testing,
        # session 40). The blend leaves both edges at one speed: the corner of lines
        # 1000 / 10 is the corner of lines 10 / 10, and the blends bend at most twice
        # as much as the G1 arc of the same setback.
        def peak(wire):
            blend = wire.OrderedEdges[1]
            first, last = blend.FirstParameter, blend.LastParameter
            return max(blend.curvatureAt(first + (last - first) * i / 400)
                       for i in range(401))

        corner = V(0, 0, 0)
        peaks = []
        for a, b in ((10, 10), (1000, 10), (10, 1000)):
            wire = operations.round_corner(Part.makeLine(V(-a, 0, 0), corner),
                                           Part.makeLine(corner, V(0, b, 0)), setback=1.0)
            peaks.append(peak(wire))
        self.assertLessEqual(peaks[0], 2.0)  # the G1 arc: curvature 1
        for other in peaks[1:]:
            self.assertAlmostEqual(other, peaks[0], delta=1e-6 * peaks[0])
        circle = Part.Circle(V(0, 500, 0), V(0, 0, 1), 500)
        arc = Part.ArcOfCircle(circle, math.radians(-60), math.radians(-30)).toShape()
        arc.translate(corner - arc.Vertexes[0].Point)  # it turns 30 degrees off the line
        for setback in (1.0, 5.0):
            wire = operations.round_corner(Part.makeLine(V(-100, 0, 0), corner), arc,
                                           setback=setback)
            self.assertLessEqual(peak(wire), 2.0 * math.tan(math.radians(15)) / setback)

    def test_blend_does_not_depend_on_how_fast_the_edges_run(self):
        # Lines 1000 and 10 long, blended across a gap of (2, 2) at 90 degrees with the
        # automatic scale, peaked at curvature 6472, lines 10 and 10 at 0.67 (user
        # testing, session 40); the same for Bezier edges (the fast path), whose speed
        # is their polygon's.
        def peak(edge):
            first, last = edge.FirstParameter, edge.LastParameter
            return max(edge.curvatureAt(first + (last - first) * i / 400) for i in range(401))

        def line(a, b):
            return Part.makeLine(V(*a), V(*b))

        def straight_bezier(a, b):
            return Part.Edge(bezier([a, tuple((2 * x + y) / 3 for x, y in zip(a, b)),
                                     tuple((x + 2 * y) / 3 for x, y in zip(a, b)), b]))

        for make in (line, straight_bezier):
            peaks = [peak(operations.blend_edges(make((-a, 0, 0), (0, 0, 0)),
                                                 make((2, 2, 0), (2, 2 + b, 0))))
                     for a, b in ((10, 10), (1000, 10), (10, 1000))]
            self.assertLessEqual(peaks[0], 1.0, make.__name__)
            for other in peaks[1:]:
                self.assertAlmostEqual(other, peaks[0], delta=1e-6 * peaks[0],
                                       msg=make.__name__)

    def test_round_wire_by_setback_does_not_depend_on_the_sides_lengths(self):
        # The same defect in a chain: a 1000 x 10 rectangle rounded by setback 1 (G2)
        # peaked at curvature 521 at every corner, a 10 x 10 square at 1.19 (user
        # testing, session 40). The curves go to the library at unit speed; the kept
        # parts of the lines are still lines.
        def peaks(width, height):
            corners = [V(0, 0, 0), V(width, 0, 0), V(width, height, 0), V(0, height, 0)]
            wire = operations.round_wire(Part.makePolygon(corners + corners[:1]),
                                         setback=1.0, continuity="G2")
            self.assertTrue(wire.isClosed() and wire.isValid())
            lines = [e for e in wire.Edges if e.Curve.TypeId == "Part::GeomLine"]
            blends = [e for e in wire.Edges if e.Curve.TypeId != "Part::GeomLine"]
            self.assertEqual((len(lines), len(blends)), (4, 4))
            return [max(e.curvatureAt(e.FirstParameter + (e.LastParameter - e.FirstParameter)
                                      * i / 200) for i in range(201)) for e in blends]

        square = peaks(10, 10)
        self.assertLessEqual(max(square), 2.0)  # the G1 arc: curvature 1
        for peak in peaks(1000, 10) + peaks(10, 1000):
            self.assertAlmostEqual(peak, square[0], delta=1e-6 * square[0])

    def test_round_corner_command(self):
        first = Part.makeLine(V(0, 0, 0), V(2, 0, 0))
        second = Part.makeLine(V(2, 0, 0), V(2, 2, 0))
        parameters = {"setback": 0.5, "second_setback": 0.8, "p_order": None, "q_order": None,
                      "p_scale": 1.0, "q_scale": 1.0, "auto_scale": False,
                      "reverse_first": False, "reverse_second": False}
        made, shown = self.drive(commands.RoundCornerCommand(), [first, second], parameters)
        self.assertEqual(shown, [])
        self.assertEqual([name for name, _shape, _report in made], ["RoundedCorner"])
        self.assertEqual(len(made[0][1].Edges), 3)
        made, shown = self.drive(commands.RoundCornerCommand(), [first, second],
                                 dict(parameters, setback=5.0))
        self.assertEqual(made, [])
        self.assertTrue(shown[0].startswith("BZJ_ERR_INVALID_ARGUMENT: "), shown)


class SplineJudgedByFreeCAD(unittest.TestCase, CommandDriver):
    def test_spline_passes_through_the_points_and_is_c1(self):
        points = [(0, 0, 0), (0.3, 0.5, 0.1), (0.7, 0.9, 0.2), (1, 1, 0.2), (2, 0.9, 0),
                  (2.5, 0.5, 0), (3.6, 1.4, 0.3), (4, 2, 0.5)]
        wire = operations.spline_through_points([V(*p) for p in points])
        edges = wire.Edges
        self.assertEqual(len(edges), 3)
        curves = [e.Curve for e in edges]
        for curve in curves:
            self.assertIsInstance(curve, Part.BezierCurve)
            self.assertEqual(curve.Degree, 3)
        on_curve = [(curves[0], 0.0, 0), (curves[0], 1 / 3, 1), (curves[0], 2 / 3, 2),
                    (curves[0], 1.0, 3), (curves[1], 2 / 3, 4), (curves[1], 1.0, 5),
                    (curves[2], 2 / 3, 6), (curves[2], 1.0, 7)]
        for curve, u, index in on_curve:
            self.assertLessEqual(gap(curve.value(u), points[index]), 1e-12)
        nodes = [points[0], points[3], points[5], points[7]]
        widths = [gap(nodes[i], nodes[i + 1]) for i in range(3)]
        assert_chain_smooth(self, curves, widths, 1)

    def test_wrong_point_count_is_explained(self):
        with self.assertRaises(bezjoin.BezjoinError) as caught:
            operations.spline_through_points([V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)])
        self.assertIn("2 m + 2", str(caught.exception))

    def test_spline_command(self):
        points = [V(0, 0, 0), V(0.3, 0.5, 0), V(0.7, 0.9, 0), V(1, 1, 0), V(2, 0.9, 0),
                  V(2.5, 0.5, 0)]
        made, shown = self.drive(commands.SplineCommand(), points, {})
        self.assertEqual(shown, [])
        (name, shape, _report), = made
        self.assertEqual(name, "OnCurveSpline")
        self.assertEqual(len(shape.Edges), 2)
        made, shown = self.drive(commands.SplineCommand(), points[:5], {})
        self.assertEqual(made, [])
        self.assertIn("2 m + 2", shown[0])


class MergeJudgedByFreeCAD(unittest.TestCase, CommandDriver):
    def test_freecad_segment_of_the_merged_curve_at_mu_is_p_hat_and_q_hat(self):
        rng = random.Random(21)
        for mu in ("half", 0.35, "optimal"):
            p_points, q_points = random_points(rng, 4), random_points(rng, 4)
            q_points[0] = p_points[-1]
            with Curve.from_freecad(bezier(p_points)) as p, \
                    Curve.from_freecad(bezier(q_points)) as q, \
                    bezjoin.merge(p, q, mu=mu, metric="l2") as result:
                merged = result.merged.to_freecad()
                p_hat, q_hat = result.p_hat.points, result.q_hat.points
                used = result.mu
            left, right = merged.copy(), merged.copy()
            left.segment(0.0, used)
            right.segment(used, 1.0)
            scale = size([merged])
            self.assertEqual(len(p_hat), merged.NbPoles)
            self.assertEqual(len(p_hat), len(poles(left)))
            self.assertEqual(len(q_hat), len(poles(right)))
            for ours, theirs in zip(p_hat, poles(left)):
                self.assertLessEqual(gap(ours, theirs), 1e-12 * scale)
            for ours, theirs in zip(q_hat, poles(right)):
                self.assertLessEqual(gap(ours, theirs), 1e-12 * scale)

    def test_merge_edges_feature_and_report(self):
        first = Part.Edge(bezier([(0, 0, 0), (1, 1, 0), (2, 1, 0), (3, 0, 0)]))
        second = Part.Edge(bezier([(6, 0, 0), (5, -1, 0), (4, -1, 0), (3, 0, 0)]))
        merged = operations.merge_edges(first, second, fix_ends=True, mu="half")
        curve = merged.shape.Curve
        self.assertIsInstance(curve, Part.BezierCurve)
        self.assertEqual(curve.Degree, 3)
        # oriented end to start: the first edge's start and the second edge's start are
        # the merged curve's ends (fixed)
        self.assertLessEqual(gap(curve.StartPoint, (0, 0, 0)), 1e-12)
        self.assertLessEqual(gap(curve.EndPoint, (6, 0, 0)), 1e-12)
        self.assertEqual(merged.mu, 0.5)
        self.assertGreater(merged.max_deviation, 0.0)
        self.assertIn("mu = 0.5", merged.describe())

    def test_merge_edges_of_bsplines_is_one_smooth_bspline(self):
        """Two adjacent cubic B-spline edges (FreeCAD's own curves, 3 spans each)
        become one B-spline edge whose interior knots are theirs mapped and none
        at the join; FreeCAD's knot removal proves it C3 there, where FreeCAD's
        own join keeps a knot of multiplicity 3 (C0)."""
        def spline(points, knots):
            curve = Part.BSplineCurve()
            curve.buildFromPolesMultsKnots([V(*x) for x in points],
                                           [4] + [1] * (len(knots) - 2) + [4], knots,
                                           False, 3)
            return curve
        first = spline([(0, 0, 0), (1, 1, 0), (2, 1.5, 0), (3, 0.5, 0), (4, 1, 0), (5, 0, 0)],
                       [0.0, 0.3, 0.7, 1.0])
        second = spline([(5, 0, 0), (6, -0.8, 0), (7, -1, 0), (8, 0, 0), (9, 0.5, 0),
                         (10, 0, 0)], [2.0, 2.5, 3.2, 4.0])
        merged = operations.merge_edges(Part.Edge(first), Part.Edge(second), mu="optimal",
                                        metric="l2", fix_ends=True)
        curve = merged.shape.Curve
        self.assertIsInstance(curve, Part.BSplineCurve)
        mu = merged.mu
        expected = [mu * k for k in (0.3, 0.7)] + [mu + (1 - mu) * (k - 2.0) / 2.0
                                                   for k in (2.5, 3.2)]
        knots = curve.getKnots()
        self.assertEqual(len(knots), 6)
        for ours, theirs in zip(knots[1:-1], expected):
            self.assertLessEqual(abs(ours - theirs), 1e-14)
        self.assertEqual(curve.NbPoles, 6 + 6 - 4)
        # FreeCAD as the judge of the join: a knot inserted at mu (3 times) is
        # removable again, so the curve is C3 there
        judged = curve.copy()
        judged.insertKnot(mu, 3)
        index = [round(k, 15) for k in judged.getKnots()].index(round(mu, 15)) + 1
        self.assertEqual(smoothness_by_knot_removal(judged, index, 1e-9), 3)
        # FreeCAD's own join of the two edges keeps a C0 knot there
        joined = first.copy()
        shifted = second.copy()
        shifted.setKnots([1.0 + (k - 2.0) / 2.0 for k in shifted.getKnots()])
        self.assertTrue(joined.join(shifted))
        at_join = [round(k, 15) for k in joined.getKnots()].index(1.0) + 1
        self.assertEqual(smoothness_by_knot_removal(joined, at_join, 1e-9), 0)
        # the merged curve stays within the library's (parametric) deviation of the
        # edges, point against point; the geometric one (the distance) is no larger
        self.assertGreater(merged.parametric_deviation, 0.0)
        for i in range(101):
            f = i / 100.0
            self.assertLessEqual(gap(curve.value(mu * f), first.value(f)),
                                 merged.parametric_deviation * (1 + 1e-9) + 1e-12)
        self.assertGreater(merged.max_deviation, 0.0)
        self.assertLessEqual(merged.max_deviation, merged.parametric_deviation * (1 + 1e-9))
        self.assertLessEqual(gap(curve.StartPoint, (0, 0, 0)), 1e-12)
        self.assertLessEqual(gap(curve.EndPoint, (10, 0, 0)), 1e-12)

    def test_merge_command_records_the_report(self):
        first = Part.Edge(bezier([(0, 0, 0), (1, 1, 0), (2, 1, 0), (3, 0, 0)]))
        second = Part.Edge(bezier([(3, 0, 0), (4, -1, 0), (5, -1, 0), (6, 0, 0)]))
        parameters = {"metric": "l2", "mu_mode": "given", "mu": 0.3, "fix_ends": False,
                      "keep_first": False, "keep_second": False}
        made, shown = self.drive(commands.MergeCommand(), [first, second], parameters)
        self.assertEqual(shown, [])
        (name, shape, report), = made
        self.assertEqual(name, "Merged")
        self.assertEqual(report["MergeMu"], 0.3)
        self.assertGreater(report["MergeMaxDeviation"], 0.0)
        self.assertGreater(report["MergeMetric"], 0.0)
        self.assertEqual(shape.Edges[0].Curve.Degree, 3)
        made, shown = self.drive(commands.MergeCommand(), [first, second],
                                 dict(parameters, keep_first=True, keep_second=True))
        self.assertEqual(made, [])
        self.assertTrue(shown[0].startswith("BZJ_ERR_INCONSISTENT: "), shown)
