"""Curve conversion and the exact operations, judged by FreeCAD's geometry."""

import math
import random
import unittest

import FreeCAD
import Part

from bezjoin import Curve, UnsupportedGeometryError
from judge import (bezier, chain_bspline, derivative_jumps, gap, poles, size,
                   smoothness_by_knot_removal)

V = FreeCAD.Vector


def random_points(rng, degree, spread=10.0):
    return [tuple(rng.uniform(-spread, spread) for _ in range(3)) for _ in range(degree + 1)]


class RoundTrip(unittest.TestCase):
    def setUp(self):
        self.rng = random.Random(91)

    def test_bezier_poles_survive_exactly(self):
        for degree in (1, 2, 3, 5, 8, 13, 25):
            original = bezier(random_points(self.rng, degree))
            with Curve.from_freecad(original) as curve:
                self.assertEqual(curve.degree, degree)
                self.assertEqual(curve.dim, 3)
                self.assertEqual(curve.points, poles(original))
                back = curve.to_freecad()
            self.assertIsInstance(back, Part.BezierCurve)
            self.assertEqual(poles(back), poles(original))

    def test_edge_on_a_whole_bezier_keeps_poles_exactly(self):
        original = bezier(random_points(self.rng, 4))
        with Curve.from_freecad(Part.Edge(original)) as curve:
            self.assertEqual(curve.points, poles(original))
            self.assertEqual(poles(curve.to_freecad()), poles(original))
            edge = curve.to_edge()
        self.assertIsInstance(edge, Part.Edge)
        self.assertEqual(poles(edge.Curve), poles(original))

    def test_single_span_bspline_is_taken_as_its_bezier(self):
        points = random_points(self.rng, 4)
        spline = Part.BSplineCurve()
        spline.buildFromPolesMultsKnots([V(*p) for p in points], [5, 5], [2.0, 5.0], False, 4)
        with Curve.from_freecad(spline) as curve:
            self.assertEqual(curve.points, points)
            # same geometry: the Bezier parameter is (x - 2) / 3
            for x in (2.0, 2.6, 4.1, 5.0):
                self.assertLess(gap(curve.evaluate((x - 2.0) / 3.0), spline.value(x)),
                                1e-12 * size([bezier(points)]))

    def test_trimmed_edge_gives_its_part_exactly(self):
        original = bezier(random_points(self.rng, 5))
        edge = Part.Edge(original, 0.2, 0.7)
        with Curve.from_freecad(edge) as curve:
            scale = size([original])
            for s in (0.0, 0.25, 0.5, 1.0):
                self.assertLess(gap(curve.evaluate(s), edge.valueAt(0.2 + 0.5 * s)),
                                1e-13 * scale)
            # FreeCAD's own segment of the Bezier curve agrees pole by pole
            reference = original.copy()
            reference.segment(0.2, 0.7)
            self.assertEqual(len(curve.points), len(poles(reference)))
            for ours, theirs in zip(curve.points, poles(reference)):
                self.assertLess(gap(ours, theirs), 1e-13 * scale)

    def test_line_edge_is_degree_one(self):
        edge = Part.makeLine(V(1, 2, 3), V(4, -1, 0.5))
        with Curve.from_freecad(edge) as curve:
            self.assertEqual(curve.degree, 1)
            self.assertEqual(curve.points, [(1.0, 2.0, 3.0), (4.0, -1.0, 0.5)])
        segment = Part.LineSegment(V(0, 0, 0), V(1, 1, 1))
        with Curve.from_freecad(segment) as curve:
            self.assertEqual(curve.points, [(0.0, 0.0, 0.0), (1.0, 1.0, 1.0)])

    def test_single_edge_shape(self):
        original = bezier(random_points(self.rng, 3))
        shape = Part.Wire([Part.Edge(original)])
        with Curve.from_freecad(shape) as curve:
            self.assertEqual(curve.points, poles(original))

    def test_two_dimensional_curve_goes_to_z_zero(self):
        with Curve([(0, 1), (2, 3), (4, 1)]) as curve:
            self.assertEqual(poles(curve.to_freecad()), [(0, 1, 0), (2, 3, 0), (4, 1, 0)])


class Rejections(unittest.TestCase):
    def assertRejected(self, obj, *words):
        with self.assertRaises(UnsupportedGeometryError) as caught:
            Curve.from_freecad(obj)
        for word in words:
            self.assertIn(word, str(caught.exception))

    def test_geometry_without_an_exact_nurbs_form_is_refused_with_what_to_do(self):
        arc = Part.ArcOfCircle(Part.Circle(V(0, 0, 0), V(0, 0, 1), 2.0), 0.2, 1.5)
        offset = Part.OffsetCurve(arc, 0.5, V(0, 0, 1))
        for obj in (offset, offset.toShape()):
            self.assertRejected(obj, "Part.OffsetCurve", "no exact NURBS form", "toBSpline",
                                "approximateBSpline")
        self.assertRejected(Part.Geom2d.Circle2d(), "Part.Geom2d.Circle2d", "2D", "toShape")
        self.assertRejected(Part.Geom2d.BSplineCurve2d(), "Geom2d", "3D edge")
        self.assertRejected("edge", "str", "not FreeCAD geometry", "Part.Edge")

    def test_unbounded_curves_are_refused_with_what_to_do(self):
        self.assertRejected(Part.Line(V(0, 0, 0), V(1, 0, 0)), "Part.Line", "unbounded",
                            "Part.Edge(curve, first, last)")
        for conic in (Part.Parabola(), Part.Hyperbola()):
            self.assertRejected(conic, "unbounded", "Part.ArcOfParabola")
        self.assertRejected(Part.Edge(Part.Line(V(0, 0, 0), V(1, 0, 0))), "Line", "unbounded",
                            "trim it")

    def test_shape_with_several_edges(self):
        box_edges = Part.makeBox(1, 1, 1)
        self.assertRejected(box_edges, "12 edges")

    def test_curves_without_a_freecad_form(self):
        for points, words in (([(0.0,), (1.0,)], ("dimension 1",)),
                              ([(0, 0, 0, 0), (1, 1, 1, 1)], ("dimension 4",)),
                              ([(1, 2, 3)], ("degree-0",)),
                              ([(i, 0, 0) for i in range(27)], ("degree 26", "25"))):
            with Curve(points) as curve:
                with self.assertRaises(UnsupportedGeometryError) as caught:
                    curve.to_freecad()
                for word in words:
                    self.assertIn(word, str(caught.exception))


class ExactOperationsAgreeWithFreeCAD(unittest.TestCase):
    def setUp(self):
        self.rng = random.Random(7)

    def test_value_and_derivatives_match_getDN(self):
        for degree in (2, 5, 9):
            original = bezier(random_points(self.rng, degree))
            with Curve.from_freecad(original) as curve:
                for t in (0.0, 0.3, 0.77, 1.0):
                    rows = curve.derivatives(t, degree)
                    self.assertLess(gap(rows[0], original.value(t)), 1e-13 * size([original]))
                    for k in range(1, degree + 1):
                        theirs = tuple(original.getDN(t, k))
                        scale = max(1.0, math.sqrt(sum(x * x for x in theirs)))
                        self.assertLess(gap(rows[k], theirs), 1e-12 * scale, (degree, t, k))

    def test_elevation_matches_increase(self):
        original = bezier(random_points(self.rng, 4))
        with Curve.from_freecad(original) as curve, curve.elevate(9) as elevated:
            reference = original.copy()
            reference.increase(9)
            self.assertEqual(len(elevated.points), len(poles(reference)))
            for ours, theirs in zip(elevated.points, poles(reference)):
                self.assertLess(gap(ours, theirs), 1e-13 * size([original]))

    def test_reverse_matches_reverse(self):
        original = bezier(random_points(self.rng, 6))
        with Curve.from_freecad(original) as curve, curve.reverse() as backwards:
            reference = original.copy()
            reference.reverse()
            self.assertEqual(backwards.points, poles(reference))

    def test_length_matches_edge_length(self):
        original = bezier(random_points(self.rng, 5))
        with Curve.from_freecad(original) as curve:
            self.assertLess(abs(curve.length() - Part.Edge(original).Length),
                            1e-9 * curve.length())

    def test_split_pieces_form_one_smooth_bspline(self):
        degree = 5
        original = bezier(random_points(self.rng, degree))
        with Curve.from_freecad(original) as curve:
            left, right = curve.split(0.35)
            with left, right:
                pieces = [left.to_freecad(), right.to_freecad()]
        self.assertEqual(pieces[0].EndPoint, pieces[1].StartPoint)
        spline = chain_bspline(pieces, [0.35, 0.65])
        tolerance = 1e-9 * size(pieces)
        # the split point is no knot at all: removable entirely
        self.assertEqual(smoothness_by_knot_removal(spline, 2, tolerance), degree)
        jumps = derivative_jumps(pieces[0], 0.35, pieces[1], 0.65, degree)
        self.assertLess(max(jumps), 1e-11)
        for x in (0.1, 0.35, 0.8):
            self.assertLess(gap(spline.value(x), original.value(x)), 1e-13 * size(pieces))


class JudgeDiscriminates(unittest.TestCase):
    """Negative controls: the judges must reject joins that are not smooth."""

    def test_c0_and_c1_joins_are_seen_as_such(self):
        rng = random.Random(3)
        degree = 4
        left = bezier(random_points(rng, degree))
        right_points = random_points(rng, degree)
        right_points[0] = tuple(left.EndPoint)
        right = bezier(right_points)
        tolerance = 1e-9 * size([left, right])
        spline = chain_bspline([left, right], [1.0, 1.0])
        self.assertEqual(smoothness_by_knot_removal(spline, 2, tolerance), 0)
        jumps = derivative_jumps(left, 1.0, right, 1.0, 2)
        self.assertEqual(jumps[0], 0.0)
        self.assertGreater(jumps[1], 1e-3)
        # make it C1 but not C2 over intervals (1, 2): Q1 - Q0 = 2 (P4 - P3)
        end, before = left.getPole(degree + 1), left.getPole(degree)
        right_points[1] = tuple(end + (end - before) * 2.0)
        right = bezier(right_points)
        spline = chain_bspline([left, right], [1.0, 2.0])
        self.assertEqual(smoothness_by_knot_removal(spline, 2, tolerance), 1)
        jumps = derivative_jumps(left, 1.0, right, 2.0, 2)
        self.assertLess(jumps[1], 1e-14)
        self.assertGreater(jumps[2], 1e-3)


if __name__ == "__main__":
    unittest.main()
