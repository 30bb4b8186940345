"""Every FreeCAD curve with an exact NURBS form through Curve.from_freecad / to_freecad /
to_edge, judged by FreeCAD's own evaluation.

For each curve type: FreeCAD makes the curve (or an edge on part of it), bezjoin
converts it, and

* at corresponding parameters (``freecad_parameter``: the documented map) the
  two give the same point, to 1e-12 of the curve's size;
* the shapes are identical, independently of that map: every sample point of
  one curve lies on the other within 1e-12 of the size (nearest points found by
  Newton's method on the other curve's own derivatives, started from FreeCAD's
  projection ``parameter`` or from the map);
* the round trip (to_freecad, to_edge, and from_freecad again) keeps the shape
  and the parameters.

The end-to-end case rounds the vertex of a Sketcher wire (an arc and a line) with
``bezjoin.fillet_vertex`` and checks the resulting Part edges with FreeCAD.
"""

import math
import unittest

import FreeCAD
import Part
import Sketcher

import bezjoin
from bezjoin import Curve, UnsupportedGeometryError
from bezjoin import _freecad

V = FreeCAD.Vector
RELATIVE = 1e-12
SAMPLES = 400


def norm(a):
    return math.sqrt(sum(x * x for x in a))


def gap(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def freecad_range_and_value(obj):
    """FreeCAD's parameter range of ``obj`` and its point at a parameter, read from
    FreeCAD directly (an edge: its range and ``valueAt``; a curve: its own)."""
    if isinstance(obj, Part.Shape):
        edge = obj if isinstance(obj, Part.Edge) else obj.Edges[0]
        return edge.FirstParameter, edge.LastParameter, lambda t: tuple(edge.valueAt(t))
    return obj.FirstParameter, obj.LastParameter, lambda t: tuple(obj.value(t))


def freecad_derivatives(obj):
    """``t -> (C(t), C'(t), C''(t))`` from FreeCAD."""
    if isinstance(obj, Part.Shape):
        edge = obj if isinstance(obj, Part.Edge) else obj.Edges[0]
        return lambda t: (tuple(edge.valueAt(t)), tuple(edge.derivative1At(t)),
                          tuple(edge.derivative2At(t)))
    return lambda t: (tuple(obj.value(t)), tuple(obj.getDN(t, 1)), tuple(obj.getDN(t, 2)))


def nearest(jet, point, t, lo, hi, steps=8):
    """Newton's method on ``(C(t) - point) . C'(t) = 0`` within ``[lo, hi]``; the
    distance from ``point`` to the curve near ``t``."""
    for _ in range(steps):
        value, first, second = jet(t)
        offset = sub(value, point)
        slope = dot(first, first) + dot(offset, second)
        if slope <= 0:
            break
        t = min(max(t - dot(offset, first) / slope, lo), hi)
    return gap(jet(t)[0], point)


def sample_parameters(first, last, count=SAMPLES):
    return [first + (last - first) * i / count if i < count else last for i in range(count + 1)]


class ConversionCase(unittest.TestCase):
    """The checks shared by every curve type."""

    def check(self, obj, *, nurbs, mapping, degree=None, rational=None):
        """Convert ``obj`` as it comes and with ``nurbs=True``; check each; return
        the facts of the first for more checks."""
        facts = self.check_one(obj, False, nurbs, mapping, degree, rational)
        exact = self.check_one(obj, True, True, "same" if mapping == "affine" else mapping,
                               degree, rational)
        if nurbs:
            self.assertEqual(exact, facts)
        return facts

    def check_one(self, obj, flag, nurbs, mapping, degree, rational):
        """Convert ``obj`` (``nurbs=flag``); check the points at corresponding
        parameters, the shape both ways, the round trip; return the knots, poles,
        weights and size."""
        first, last, value = freecad_range_and_value(obj)
        with Curve.from_freecad(obj, nurbs=flag) as curve:
            self.assertEqual(curve.is_nurbs, nurbs)
            self.assertEqual(curve.dim, 3)
            if degree is not None:
                self.assertEqual(curve.degree, degree)
            if rational is not None:
                self.assertEqual(curve.is_rational, rational)
            domain = curve.domain
            if nurbs:
                # a NURBS conversion keeps FreeCAD's parameter range
                self.assertEqual(domain, (first, last))
            else:
                self.assertEqual(domain, (0.0, 1.0))
            us = sample_parameters(*domain)
            ours = [curve.evaluate(u) for u in us]
            ts = [_freecad.freecad_parameter(obj, u, flag) for u in us]
            theirs = [value(t) for t in ts]
            size = max([1.0] + [norm(p) for p in theirs])
            tolerance = RELATIVE * size

            # 1. corresponding parameters: the documented map
            self.assertEqual((ts[0], ts[-1]), (first, last))
            for u, t, a, b in zip(us, ts, ours, theirs):
                self.assertLessEqual(gap(a, b), tolerance, (u, t))
                back = _freecad.curve_parameter(obj, t, flag)
                self.assertLessEqual(abs(back - u), 1e-12 * max(1.0, abs(u)), (u, t))
            self.assertEqual(ts, sorted(ts))
            self.check_map_kind(obj, flag, mapping, us, ts, first, last)

            # 2. the same shape, found without the map: our points on FreeCAD's curve
            #    (from FreeCAD's projection) and FreeCAD's points on ours
            jet = freecad_derivatives(obj)
            projector = obj if not isinstance(obj, Part.Shape) else (
                obj if isinstance(obj, Part.Edge) else obj.Edges[0])
            for point, t in zip(ours[1:-1:7], ts[1:-1:7]):
                guess = self.projected(projector, point, t, first, last)
                self.assertLessEqual(nearest(jet, point, guess, first, last), tolerance)

            def our_jet(u):
                rows = curve.derivatives(u, 2)
                return rows[0], rows[1], rows[2]

            for t in sample_parameters(first, last, 97)[1:-1]:
                point = value(t)
                guess = _freecad.curve_parameter(obj, t, flag)
                self.assertLessEqual(nearest(our_jet, point, guess, *domain), tolerance)

            # 3. round trip: FreeCAD geometry of ours has our parameters and FreeCAD's shape
            back = curve.to_freecad()
            self.assertIsInstance(back, Part.BSplineCurve if nurbs else Part.BezierCurve)
            self.assertEqual((back.FirstParameter, back.LastParameter), domain)
            edge = curve.to_edge()
            self.assertEqual((edge.FirstParameter, edge.LastParameter), domain)
            for u, b in list(zip(us, theirs))[::5]:
                self.assertLessEqual(gap(tuple(back.value(u)), b), tolerance, u)
                self.assertLessEqual(gap(tuple(edge.valueAt(u)), b), tolerance, u)
            if nurbs:
                self.assertEqual(back.isRational(), curve.is_rational)
                self.assertEqual(_freecad.expand_knots(back.getKnots(), back.getMultiplicities()),
                                 curve.knots)
            self.assertEqual([tuple(p) for p in back.getPoles()], curve.points)
            self.assertAlmostEqual(edge.Length, curve.length(), delta=1e-9 * edge.Length)
            with Curve.from_freecad(back, nurbs=nurbs) as again:
                self.assertEqual(again.points, curve.points)
                self.assertEqual(again.knots, curve.knots)
                self.assertEqual(again.weights, curve.weights)
            with Curve.from_freecad(edge, nurbs=nurbs) as again:
                self.assertEqual(again.points, curve.points)
                self.assertEqual(again.domain, domain)
            return curve.knots, curve.points, curve.weights, size

    def projected(self, projector, point, t, first, last):
        """FreeCAD's projection parameter of ``point`` (brought into [first, last]
        by whole periods for a periodic curve); ``t`` if FreeCAD gives none."""
        curve = projector.Curve if isinstance(projector, Part.Edge) else projector
        try:
            guess = curve.parameter(V(*point))
        except Exception:  # noqa: BLE001
            return t
        if curve.isPeriodic():
            period = curve.period()
            while guess < first - 1e-9:
                guess += period
            while guess > last + 1e-9:
                guess -= period
        return min(max(guess, first), last)

    def check_map_kind(self, obj, flag, mapping, us, ts, first, last):
        if mapping == "same":
            self.assertEqual(ts, us)
        elif mapping == "affine":
            for u, t in zip(us, ts):
                self.assertAlmostEqual(t, first + (last - first) * u, delta=1e-15 * abs(last))
        else:
            # FreeCAD's parameter at the knots, close to it in between
            for u, t in zip(us, ts):
                self.assertLess(abs(t - u), 0.017)
            breaks = _freecad.conic_breaks(first, last, mapping == "ellipse")
            for k in breaks:
                self.assertEqual(_freecad.freecad_parameter(obj, k, flag), k)


def tilted_circle(radius=2.5):
    return Part.Circle(V(1.0, -2.0, 0.5), V(0.3, -0.4, 0.87), radius)


def tilted_ellipse():
    ellipse = Part.Ellipse(V(0, 0, 0), 4.0, 1.5)
    ellipse.rotate(FreeCAD.Placement(V(2, 1, -1), FreeCAD.Rotation(V(1, 2, 3), 35)))
    return ellipse


def hyperbola():
    curve = Part.Hyperbola()
    curve.MajorRadius, curve.MinorRadius = 3.0, 1.25
    curve.rotate(FreeCAD.Placement(V(-1, 0.5, 2), FreeCAD.Rotation(V(0, 1, 1), 50)))
    return curve


def parabola():
    curve = Part.Parabola()
    curve.Focal = 1.5
    curve.rotate(FreeCAD.Placement(V(3, -2, 1), FreeCAD.Rotation(V(1, 0, 1), -20)))
    return curve


def interpolated_bspline(periodic=False):
    points = [V(0, 0, 0), V(2, 1, 0.5), V(3, 3, -1), V(5, 2, 0), V(6, 4, 1), V(4, 6, 2)]
    spline = Part.BSplineCurve()
    spline.interpolate(points, PeriodicFlag=periodic)
    return spline


def rational_bspline():
    """A cubic rational B-spline of 4 spans with a double knot, on [1, 5]."""
    poles = [V(0, 0, 0), V(1, 2, 0), V(2, 2, 1), V(3, 0, 1), V(4, -1, 0), V(5, 1, -1),
             V(6, 3, 0), V(7, 2, 2)]
    spline = Part.BSplineCurve()
    spline.buildFromPolesMultsKnots(poles, [4, 1, 2, 1, 4], [1.0, 2.0, 3.0, 4.0, 5.0], False, 3,
                                    [1.0, 0.5, 2.0, 1.0, 0.7, 1.3, 1.0, 0.9])
    return spline


def periodic_rational_bspline():
    """A closed periodic rational quadratic B-spline (uniform knots on [0, 5])."""
    poles = [V(2, 0, 0), V(1, 2, 1), V(-1, 2, 0), V(-2, 0, -1), V(0, -2, 0)]
    spline = Part.BSplineCurve()
    spline.buildFromPolesMultsKnots(poles, [1] * 6, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0], True, 2,
                                    [1.0, 0.6, 1.4, 1.0, 0.8])
    return spline


class Lines(ConversionCase):
    def test_line_segment_and_line_edges_are_degree_one_bezier_curves(self):
        self.check(Part.LineSegment(V(1, 2, 3), V(4, -1, 0.5)), nurbs=False, mapping="affine",
                   degree=1)
        self.check(Part.makeLine(V(1, 2, 3), V(4, -1, 0.5)), nurbs=False, mapping="affine",
                   degree=1)
        line = Part.Line(V(0, 0, 1), V(1, 1, 1))
        edge = Part.Edge(line, -2.0, 3.5)
        self.check(edge, nurbs=False, mapping="affine", degree=1)
        with Curve.from_freecad(edge) as curve:
            self.assertEqual(curve.points, [tuple(line.value(-2.0)), tuple(line.value(3.5))])


class Conics(ConversionCase):
    def test_full_circle_edge_and_circle_geometry(self):
        circle = tilted_circle()
        for obj in (Part.Edge(circle), circle, Part.makeCircle(1.5, V(1, 1, 1), V(0, 1, 0))):
            knots, _poles, weights, _size = self.check(obj, nurbs=True, mapping="ellipse",
                                                       degree=2, rational=True)
            self.assertEqual(knots, [0.0] * 3 + [k for k in (0.5 * math.pi, math.pi,
                                                               1.5 * math.pi) for _ in (0, 1)]
                             + [2 * math.pi] * 3)
            self.assertAlmostEqual(weights[1], math.cos(math.pi / 4), delta=1e-16)
        with Curve.from_freecad(Part.Edge(circle)) as curve:
            # closed: first pole = last pole; the library's ellipse arc exactly
            self.assertEqual(curve.points[0], curve.points[-1])
            with Curve.ellipse_arc(tuple(circle.Center), tuple(circle.XAxis),
                                   tuple(circle.YAxis), circle.Radius, circle.Radius) as arc:
                self.assertEqual(curve.points, arc.points)
                self.assertEqual(curve.knots, arc.knots)

    def test_circle_arcs(self):
        circle = tilted_circle()
        for first, last in ((0.3, 1.9), (5.0, 7.5), (0.0, 1e-4), (1.0, 1.0 + 2 * math.pi)):
            self.check(Part.Edge(circle, first, last), nurbs=True, mapping="ellipse", degree=2)
        self.check(Part.ArcOfCircle(circle, 2.0, 4.5), nurbs=True, mapping="ellipse")
        sketch_arc = Part.ArcOfCircle(V(0, 0, 0), V(1, 1, 0), V(2, 0, 0))
        self.check(sketch_arc, nurbs=True, mapping="ellipse")
        self.check(sketch_arc.toShape(), nurbs=True, mapping="ellipse")

    def test_circle_angles_by_atan2(self):
        """The documented map against the angle measured in the circle's frame."""
        circle = tilted_circle()
        edge = Part.Edge(circle, 0.3, 4.0)
        centre, x_axis, y_axis = (tuple(circle.Center), tuple(circle.XAxis),
                                  tuple(circle.YAxis))
        with Curve.from_freecad(edge) as curve:
            for u in sample_parameters(0.3, 4.0, 50):
                offset = sub(curve.evaluate(u), centre)
                angle = math.atan2(dot(offset, y_axis), dot(offset, x_axis))
                t = _freecad.freecad_parameter(edge, u)
                self.assertLess(abs(math.remainder(angle - t, 2 * math.pi)), 1e-12)

    def test_ellipse_and_arcs_of_ellipse(self):
        ellipse = tilted_ellipse()
        self.check(ellipse, nurbs=True, mapping="ellipse", degree=2, rational=True)
        self.check(Part.Edge(ellipse), nurbs=True, mapping="ellipse")
        self.check(Part.Edge(ellipse, 4.0, 6.5), nurbs=True, mapping="ellipse")
        arc = Part.ArcOfEllipse(ellipse, -1.0, 2.0)
        self.check(arc, nurbs=True, mapping="ellipse")
        self.check(arc.toShape(), nurbs=True, mapping="ellipse")

    def test_arcs_of_hyperbola(self):
        curve = hyperbola()
        self.check(Part.ArcOfHyperbola(curve, -2.0, 1.5), nurbs=True, mapping="hyperbola",
                   degree=2, rational=True)
        self.check(Part.Edge(curve, 0.2, 0.3), nurbs=True, mapping="hyperbola")
        self.check(Part.Edge(curve, -3.0, 3.0), nurbs=True, mapping="hyperbola")

    def test_arcs_of_parabola_keep_the_parameter(self):
        curve = parabola()
        self.check(Part.ArcOfParabola(curve, -2.0, 3.0), nurbs=True, mapping="same", degree=2,
                   rational=False)
        self.check(Part.Edge(curve, 0.5, 7.0), nurbs=True, mapping="same")
        # FreeCAD's own B-spline of the parabola is the same curve, pole for pole
        with Curve.from_freecad(Part.Edge(curve, -1.0, 2.0)) as ours:
            theirs = curve.toBSpline(-1.0, 2.0)
            self.assertEqual(theirs.Degree, 2)
            for a, b in zip(ours.points, theirs.getPoles()):
                self.assertLess(gap(a, tuple(b)), 1e-14 * 10)


class FreeCADsOwnNurbsForms(unittest.TestCase):
    """What FreeCAD 0.20 itself gives for conics, against the conversion."""

    def nurbs_of(self, edge):
        return edge.toNurbs().Edges[0]

    def test_exact_edge_to_nurbs_is_the_same_curve_for_arcs_up_to_a_quarter_turn(self):
        cases = [(tilted_circle(), 0.3, 1.7), (tilted_circle(), 5.0, 5.0 + 0.5 * math.pi),
                 (tilted_ellipse(), 0.3, 1.5), (hyperbola(), -1.0, 0.5),
                 (hyperbola(), -0.5, 0.5)]
        for conic, first, last in cases:
            edge = Part.Edge(conic, first, last)
            theirs = self.nurbs_of(edge)
            self.assertEqual((theirs.FirstParameter, theirs.LastParameter), (first, last))
            spline = theirs.Curve
            with Curve.from_freecad(edge) as ours:
                self.assertEqual(ours.pole_count, spline.NbPoles)
                self.assertEqual(ours.knots, _freecad.expand_knots(spline.getKnots(),
                                                                   spline.getMultiplicities()))
                for a, b in zip(ours.weights, spline.getWeights()):
                    self.assertAlmostEqual(a, b, delta=1e-15)
                size = max(norm(p) for p in ours.points)
                for a, b in zip(ours.points, spline.getPoles()):
                    self.assertLess(gap(a, tuple(b)), 1e-15 * size)

    def test_exact_edge_to_nurbs_cuts_a_full_circle_otherwise(self):
        edge = Part.Edge(tilted_circle())
        theirs = self.nurbs_of(edge).Curve
        self.assertEqual(len(theirs.getKnots()), 4)   # three spans
        with Curve.from_freecad(edge) as ours:
            self.assertEqual(len(set(ours.knots)), 5)   # four quarter turns

    def test_curve_to_bspline_of_a_circle_is_only_an_approximation(self):
        circle = tilted_circle()
        approximation = circle.toBSpline(0.3, 1.7)
        self.assertFalse(approximation.isRational())
        worst = max((approximation.value(t) - circle.value(t)).Length
                    for t in sample_parameters(0.3, 1.7, 50))
        self.assertGreater(worst, 1e-10)
        self.assertLess(worst, 1e-6)


class SelfCheck(unittest.TestCase):
    def test_a_conversion_that_misses_freecads_points_is_refused(self):
        original = _freecad.hyperbola_arc

        def stretched(cls, centre, x_axis, y_axis, major, minor, first, last):
            return original(cls, centre, x_axis, y_axis, major * (1 + 1e-6), minor, first, last)

        _freecad.hyperbola_arc = stretched
        try:
            with self.assertRaises(UnsupportedGeometryError) as caught:
                Curve.from_freecad(Part.ArcOfHyperbola(hyperbola(), -1.0, 1.0))
        finally:
            _freecad.hyperbola_arc = original
        self.assertIn("does not reproduce FreeCAD's points", str(caught.exception))
        with Curve.from_freecad(Part.ArcOfHyperbola(hyperbola(), -1.0, 1.0)) as curve:
            self.assertTrue(curve.is_rational)


class Beziers(ConversionCase):
    def test_polynomial_bezier_stays_a_bezier_curve(self):
        bezier = Part.BezierCurve()
        bezier.setPoles([V(0, 0, 0), V(1, 3, 1), V(3, 3, -1), V(4, 0, 2), V(6, 1, 0)])
        self.check(bezier, nurbs=False, mapping="same", degree=4)
        self.check(Part.Edge(bezier, 0.2, 0.7), nurbs=False, mapping="affine", degree=4)

    def test_rational_bezier_is_a_one_span_nurbs_curve(self):
        bezier = Part.BezierCurve()
        bezier.setPoles([V(0, 0, 0), V(1, 3, 1), V(3, 3, -1), V(4, 0, 2)])
        bezier.setWeight(2, 0.4)
        bezier.setWeight(3, 2.5)
        knots, poles, weights, _size = self.check(bezier, nurbs=True, mapping="same", degree=3,
                                                  rational=True)
        self.assertEqual(knots, [0.0] * 4 + [1.0] * 4)
        self.assertEqual(poles, [tuple(p) for p in bezier.getPoles()])
        self.assertEqual(weights, list(bezier.getWeights()))
        self.check(Part.Edge(bezier, 0.25, 0.9), nurbs=True, mapping="same", rational=True)


class BSplines(ConversionCase):
    def test_multi_span_polynomial_bspline_keeps_poles_and_knots(self):
        spline = interpolated_bspline()
        knots, poles, _weights, _size = self.check(spline, nurbs=True, mapping="same",
                                                   degree=3, rational=False)
        self.assertEqual(poles, [tuple(p) for p in spline.getPoles()])
        self.assertEqual(knots, _freecad.expand_knots(spline.getKnots(),
                                                      spline.getMultiplicities()))
        # trimmed to an edge's range, across knots
        first, last = spline.FirstParameter, spline.LastParameter
        self.check(Part.Edge(spline, first + 0.13 * (last - first), first + 0.71 * (last - first)),
                   nurbs=True, mapping="same")

    def test_rational_multi_span_bspline(self):
        spline = rational_bspline()
        knots, poles, weights, _size = self.check(spline, nurbs=True, mapping="same", degree=3,
                                                  rational=True)
        self.assertEqual(knots, [1.0] * 4 + [2.0, 3.0, 3.0, 4.0] + [5.0] * 4)
        self.assertEqual(poles, [tuple(p) for p in spline.getPoles()])
        self.assertEqual(weights, list(spline.getWeights()))
        self.check(Part.Edge(spline, 1.5, 3.0), nurbs=True, mapping="same", rational=True)
        self.check(Part.Edge(spline, 2.0, 4.75), nurbs=True, mapping="same", rational=True)

    def test_periodic_bsplines_become_clamped_on_the_same_range(self):
        for spline in (interpolated_bspline(periodic=True), periodic_rational_bspline()):
            self.assertTrue(spline.isPeriodic())
            first, last = spline.FirstParameter, spline.LastParameter
            period = last - first
            cases = [spline, Part.Edge(spline),
                     Part.Edge(spline, first + 0.2 * period, first + 0.6 * period),
                     # across the seam
                     Part.Edge(spline, first + 0.7 * period, first + 1.3 * period)]
            for obj in cases:
                knots, poles, _weights, _size = self.check(obj, nurbs=True, mapping="same",
                                                           rational=spline.isRational())
                degree = spline.Degree
                # clamped: end knots of multiplicity degree + 1, the ends are poles
                self.assertEqual(len(set(knots[:degree + 1])), 1)
                self.assertEqual(len(set(knots[-degree - 1:])), 1)
                value = freecad_range_and_value(obj)[2]
                lo, hi = freecad_range_and_value(obj)[:2]
                self.assertLess(gap(poles[0], value(lo)), 1e-12 * 10)
                self.assertLess(gap(poles[-1], value(hi)), 1e-12 * 10)
            with Curve.from_freecad(spline) as whole:
                # the whole period: a closed curve
                self.assertLess(gap(whole.points[0], whole.points[-1]), 1e-12 * 10)

    def test_unclamped_non_periodic_bspline_is_clamped_on_its_domain(self):
        spline = Part.BSplineCurve()
        spline.buildFromPolesMultsKnots([V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 1),
                                         V(0, 0, 2)], [1] * 8, [float(i) for i in range(8)],
                                        False, 2)
        self.assertEqual((spline.FirstParameter, spline.LastParameter), (2.0, 5.0))
        knots, _poles, _weights, _size = self.check(spline, nurbs=True, mapping="same")
        self.assertEqual(knots, [2.0] * 3 + [3.0, 4.0] + [5.0] * 3)

    def test_single_span_bspline_trimmed_is_a_bezier_piece(self):
        spline = Part.BSplineCurve()
        spline.buildFromPolesMultsKnots([V(0, 0, 0), V(1, 2, 0), V(3, 2, 1), V(4, 0, 0)],
                                        [4, 4], [2.0, 5.0], False, 3)
        self.check(spline, nurbs=False, mapping="affine", degree=3)
        self.check(Part.Edge(spline, 2.5, 4.0), nurbs=False, mapping="affine", degree=3)


class PlacedShapesAndSketches(ConversionCase):
    def test_edges_of_moved_shapes_are_converted_where_they_are(self):
        placement = FreeCAD.Placement(V(10, -3, 4), FreeCAD.Rotation(V(1, 1, 0), 40))
        for edge in (Part.makeCircle(2.0, V(1, 0, 0), V(0, 0, 1), 30, 200),
                     Part.Edge(rational_bspline(), 1.5, 4.5),
                     Part.Edge(interpolated_bspline(periodic=True)),
                     Part.Edge(Part.ArcOfHyperbola(hyperbola(), -1.0, 1.0))):
            moved = edge.copy()
            moved.Placement = placement
            self.assertGreater(gap(tuple(moved.valueAt(moved.FirstParameter)),
                                   tuple(edge.valueAt(edge.FirstParameter))), 1.0)
            mapping = "same"
            if isinstance(edge.Curve, Part.Circle):
                mapping = "ellipse"
            elif isinstance(edge.Curve, Part.Hyperbola):
                mapping = "hyperbola"
            self.check(moved, nurbs=True, mapping=mapping)
            self.check(Part.Wire([moved]), nurbs=True, mapping=mapping)

    def test_sketch_geometry_and_sketch_edges(self):
        document = FreeCAD.newDocument("BezjoinSketchGeometry")
        try:
            sketch = document.addObject("Sketcher::SketchObject", "Sketch")
            sketch.Placement = FreeCAD.Placement(V(0, 0, 5), FreeCAD.Rotation(V(1, 0, 0), 30))
            sketch.addGeometry(Part.ArcOfEllipse(Part.Ellipse(V(0, 0, 0), 6, 2), 0.5, 2.5))
            sketch.addGeometry(Part.ArcOfParabola(Part.Parabola(), -1.0, 2.0))
            document.recompute()
            for geometry in sketch.Geometry:
                kind = "ellipse" if isinstance(geometry, Part.ArcOfEllipse) else "same"
                self.check(geometry, nurbs=True, mapping=kind)
            for edge in sketch.Shape.Edges:
                kind = "ellipse" if isinstance(edge.Curve, Part.Ellipse) else "same"
                self.check(edge, nurbs=True, mapping=kind)
        finally:
            FreeCAD.closeDocument(document.Name)


def oriented(curve, end_at, start_at):
    """``curve`` reversed if needed so that it ends nearer ``end_at`` (or starts
    nearer ``start_at``); a new curve either way."""
    first, last = curve.domain
    a, b = curve.evaluate(first), curve.evaluate(last)
    if end_at is not None:
        return curve.reverse() if gap(a, end_at) < gap(b, end_at) else curve.copy()
    return curve.reverse() if gap(b, start_at) < gap(a, start_at) else curve.copy()


class SketchVertexRoundedInFreeCAD(unittest.TestCase):
    """A Sketcher wire of an arc and a line, its vertex rounded C2 by fillet_vertex,
    the result back as Part edges judged by FreeCAD."""

    def make_sketch(self, document, reverse_arc):
        sketch = document.addObject("Sketcher::SketchObject", "Corner")
        circle = Part.Circle(V(0, 0, 0), V(0, 0, 1), 10.0)
        # the arc ends (or, reversed, starts) at (0, 10), where the line starts
        arc = (Part.ArcOfCircle(circle, 0.0, 0.5 * math.pi) if not reverse_arc
               else Part.ArcOfCircle(circle, 0.5 * math.pi, math.pi))
        sketch.addGeometry(arc, False)
        sketch.addGeometry(Part.LineSegment(V(0, 10, 0), V(-12, 16, 0)), False)
        vertex = 2 if not reverse_arc else 1
        sketch.addConstraint(Sketcher.Constraint("Coincident", 0, vertex, 1, 1))
        document.recompute()
        return sketch

    def round_vertex(self, reverse_arc):
        document = FreeCAD.newDocument("BezjoinSketchCorner")
        try:
            sketch = self.make_sketch(document, reverse_arc)
            wire = sketch.Shape.Wires[0]
            arc_edge, line_edge = [e for e in wire.Edges if isinstance(e.Curve, Part.Circle)] + \
                [e for e in wire.Edges if isinstance(e.Curve, Part.Line)]
            corner = (0.0, 10.0, 0.0)
            with Curve.from_freecad(arc_edge) as arc, Curve.from_freecad(line_edge) as line:
                self.assertTrue(arc.is_nurbs)
                self.assertFalse(line.is_nurbs)
                with oriented(arc, corner, None) as p, oriented(line, None, corner) as q, \
                        bezjoin.fillet_vertex(p, q, setback=2.0, p_order=2, q_order=2,
                                              gap=1e-9) as result:
                    pieces = list(result.curves())
                    self.assertTrue(result.p_trimmed.is_nurbs)
                    edges = [piece.to_edge() for piece in pieces]
                    kept_arc = [result.p_trimmed.evaluate(u)
                                for u in sample_parameters(*result.p_trimmed.domain, 50)]
            return arc_edge, line_edge, edges, kept_arc
        finally:
            FreeCAD.closeDocument(document.Name)

    def check_rounded(self, reverse_arc):
        arc_edge, line_edge, edges, kept_arc = self.round_vertex(reverse_arc)
        self.assertEqual([type(e.Curve).__name__ for e in edges],
                         ["BSplineCurve", "BezierCurve", "BezierCurve"])
        # connected within 1e-9, and FreeCAD makes one wire of them
        for left, right in zip(edges, edges[1:]):
            self.assertLess(gap(tuple(left.valueAt(left.LastParameter)),
                                tuple(right.valueAt(right.FirstParameter))), 1e-9)
        rounded = Part.Wire(edges)
        self.assertEqual(len(rounded.Edges), 3)
        self.assertTrue(rounded.isValid())
        # C2 for FreeCAD: tangents and curvature continuous across both joins
        for left, right in zip(edges, edges[1:]):
            t_left, t_right = left.tangentAt(left.LastParameter), right.tangentAt(
                right.FirstParameter)
            self.assertLess((t_left - t_right).Length, 1e-9)
            k_left = left.curvatureAt(left.LastParameter)
            k_right = right.curvatureAt(right.FirstParameter)
            self.assertLess(abs(k_left - k_right) * 10.0, 1e-8, (k_left, k_right))
        # the arc's curvature 1/10 and the line's 0 reach the blend's ends
        blend = edges[1]
        self.assertAlmostEqual(blend.curvatureAt(blend.FirstParameter), 0.1, delta=1e-9)
        self.assertLess(blend.curvatureAt(blend.LastParameter), 1e-9)
        # the kept pieces are the sketch's own geometry, set back by 2 along each
        for point in kept_arc:
            self.assertAlmostEqual(norm(point), 10.0, delta=1e-12 * 10)
        kept_arc_edge, kept_line_edge = edges[0], edges[2]
        self.assertAlmostEqual(kept_arc_edge.Length, arc_edge.Length - 2.0, delta=1e-9)
        self.assertAlmostEqual(kept_line_edge.Length, line_edge.Length - 2.0, delta=1e-9)
        self.assertLess(kept_arc_edge.distToShape(Part.Vertex(V(0, 10, 0)))[0], 2.0 + 1e-9)
        for t in sample_parameters(kept_line_edge.FirstParameter, kept_line_edge.LastParameter,
                                   20):
            point = kept_line_edge.valueAt(t)
            self.assertLess(line_edge.distToShape(Part.Vertex(point))[0], 1e-12 * 20)
        # the far ends are untouched
        far_arc = arc_edge.Vertexes[0 if not reverse_arc else 1].Point
        self.assertLess((kept_arc_edge.valueAt(kept_arc_edge.FirstParameter) - far_arc).Length,
                        1e-12 * 10)
        self.assertLess((kept_line_edge.valueAt(kept_line_edge.LastParameter)
                         - V(-12, 16, 0)).Length, 1e-12 * 20)

    def test_arc_into_line(self):
        self.check_rounded(reverse_arc=False)

    def test_arc_drawn_the_other_way_is_reversed_first(self):
        self.check_rounded(reverse_arc=True)


class ToFreeCAD(unittest.TestCase):
    def test_nurbs_curves_become_bspline_curves(self):
        with Curve.nurbs([(0, 0), (1, 2), (3, 3), (5, 1), (6, -1)],
                         [0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0], 2,
                         [1.0, 1.0, 1.0, 0.5, 1.0]) as curve:
            spline = curve.to_freecad()
            self.assertIsInstance(spline, Part.BSplineCurve)
            self.assertFalse(spline.isPeriodic())
            self.assertTrue(spline.isRational())
            self.assertEqual(spline.Degree, 2)
            self.assertEqual(spline.getKnots(), [0.0, 1.0, 2.5, 4.0])
            self.assertEqual(spline.getMultiplicities(), [3, 1, 1, 3])
            self.assertEqual([tuple(p) for p in spline.getPoles()],
                             [(0, 0, 0), (1, 2, 0), (3, 3, 0), (5, 1, 0), (6, -1, 0)])
            self.assertEqual(list(spline.getWeights()), [1.0, 1.0, 1.0, 0.5, 1.0])
            for u in sample_parameters(0.0, 4.0, 40):
                self.assertLess(gap(tuple(spline.value(u)), curve.evaluate(u) + (0.0,)), 1e-14)
            edge = curve.to_edge()
            self.assertEqual((edge.FirstParameter, edge.LastParameter), (0.0, 4.0))

    def test_polynomial_nurbs_and_unclamped_nurbs(self):
        with Curve.nurbs([(0, 0, 0), (1, 1, 1), (2, -1, 0), (3, 0, 2), (4, 2, 1), (5, 1, -1)],
                         list(range(10)), 3) as curve:
            spline = curve.to_freecad()
            self.assertFalse(spline.isRational())
            self.assertEqual((spline.FirstParameter, spline.LastParameter), curve.domain)
            for u in sample_parameters(*curve.domain, 30):
                self.assertLess(gap(tuple(spline.value(u)), curve.evaluate(u)), 1e-13)

    def test_nurbs_without_a_freecad_form(self):
        for make, words in (
                (lambda: Curve.nurbs([(0.0,), (1.0,)], [0, 0, 1, 1], 1), ("dimension 1",)),
                (lambda: Curve.nurbs([(i, 0, 0) for i in range(27)], [0] * 27 + [1] * 27, 26),
                 ("degree 26", "25", "Part.BSplineCurve"))):
            with make() as curve:
                with self.assertRaises(UnsupportedGeometryError) as caught:
                    curve.to_freecad()
                for word in words:
                    self.assertIn(word, str(caught.exception))


if __name__ == "__main__":
    unittest.main()
