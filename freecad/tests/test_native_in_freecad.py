"""Issue 19, item 7: the optional compiled fast path (bezjoin/_native.c) gives what the
ctypes route gives, bit for bit: the same curves, the same poles, the same errors;
and blend_edges' fast path (through connect_edges) gives what its general path gives.

Each case runs twice in this process, once with the compiled module and once with the
ctypes route only (bezjoin._freecad.use_native); without the module both runs take the
ctypes route and the comparisons still hold. BEZJOIN_EXPECT_NATIVE=1 (set by
freecad/run-tests.sh after building the module) makes its absence a failure.
"""

import math
import os
import random
import unittest

import FreeCAD
import Part

import bezjoin
from bezjoin import _freecad
from bezjoin_workbench import operations

V = FreeCAD.Vector


def bezier_edge(points, first=None, last=None):
    curve = Part.BezierCurve()
    curve.setPoles([V(*p) for p in points])
    if first is None:
        return curve.toShape()
    return Part.Edge(curve, first, last)


def random_points(rng, count, spread=10.0):
    return [tuple(rng.uniform(-spread, spread) for _ in range(3)) for _ in range(count)]


def outcome(function):
    """What ``function()`` gives: ``("ok", value)`` or ``("raised", type, message)``."""
    try:
        return ("ok", function())
    except Exception as error:  # noqa: BLE001 (compared, not handled)
        return ("raised", type(error), str(error))


def on_both_routes(function):
    """``(compiled, ctypes)``: ``outcome(function)`` with the compiled module in use (when
    it is present) and with the ctypes route only."""
    previous = _freecad.use_native(True)
    try:
        compiled = outcome(function)
        _freecad.use_native(False)
        plain = outcome(function)
    finally:
        _freecad.use_native(previous)
    return compiled, plain


def poles(curve):
    return [tuple(p) for p in curve.getPoles()]


def curve_state(curve):
    """What a bezjoin.Curve is: kind, shape, points (and knots, weights for NURBS)."""
    try:
        state = [curve.is_nurbs, curve.degree, curve.dim, curve.points, curve._bezier_shape]
        if curve.is_nurbs:
            state += [curve.knots, curve.weights if curve.is_rational else None]
        return state
    finally:
        curve.close()


def described(result, describe):
    return (result[0], describe(result[1])) if result[0] == "ok" else result


class CompiledModule(unittest.TestCase):
    def test_present_when_built(self):
        if os.environ.get("BEZJOIN_EXPECT_NATIVE") != "1":
            self.skipTest("BEZJOIN_EXPECT_NATIVE is not 1 (the module was not built)")
        self.assertIsNotNone(_freecad.native(), "bezjoin._native was built but is not used")

    def test_use_native_switches_routes(self):
        previous = _freecad.use_native(True)
        try:
            present = _freecad.native() is not None
            self.assertEqual(_freecad.use_native(False), present)
            self.assertIsNone(_freecad.native())
            self.assertFalse(_freecad.use_native(True))
            self.assertEqual(_freecad.native() is not None, present)
        finally:
            _freecad.use_native(previous)


class FromFreecad(unittest.TestCase):
    """Curve.from_freecad: the same curve (kind, degree, points bit for bit) or the same
    error on both routes, for edges on and off the verbatim fast path."""

    def edges(self):
        rng = random.Random(19)
        cases = []
        for degree in range(1, 12):
            for spread in (1.0, 1e3, 1e-3):
                cases.append((f"degree {degree} spread {spread}",
                              bezier_edge(random_points(rng, degree + 1, spread))))
        # Poles far from the ends (off the verbatim path for a cubic).
        cases.append(("wild cubic", bezier_edge([(0, 0, 0), (5e4, 1, 0), (-5e4, 2, 0),
                                                 (1, 0, 0)])))
        cases.append(("huge", bezier_edge([(1e200, 0, 0), (2e200, 1, 0), (3e200, 0, 0)])))
        cases.append(("part of a cubic", bezier_edge(random_points(rng, 4), 0.2, 0.7)))
        rational = Part.BezierCurve()
        rational.setPoles([V(0, 0, 0), V(1, 1, 0), V(2, 0, 0)])
        rational.setWeight(2, 3.0)
        cases.append(("rational", rational.toShape()))
        cases.append(("line", Part.LineSegment(V(0, 0, 0), V(3, 4, 0)).toShape()))
        cases.append(("arc", Part.ArcOfCircle(Part.Circle(V(1, 2, 0), V(0, 0, 1), 2.0),
                                              0.3, 2.0).toShape()))
        spline = Part.BSplineCurve()
        spline.interpolate([V(0, 0, 0), V(1, 2, 0), V(3, 1, 1), V(4, 0, 0)])
        cases.append(("B-spline", spline.toShape()))
        cases.append(("Part curve, not an edge", Part.LineSegment(V(0, 0, 0), V(1, 0, 0))))
        cases.append(("wire of two edges", Part.Wire([
            Part.LineSegment(V(0, 0, 0), V(1, 0, 0)).toShape(),
            Part.LineSegment(V(1, 0, 0), V(1, 1, 0)).toShape()])))
        cases.append(("offset curve", Part.OffsetCurve(
            Part.LineSegment(V(0, 0, 0), V(1, 0, 0)), 1.0, V(0, 0, 1)).toShape()))
        cases.append(("not geometry", "Edge1"))
        return cases

    def test_same_curve_or_error_on_both_routes(self):
        for name, edge in self.edges():
            for nurbs in (False, True):
                with self.subTest(name, nurbs=nurbs):
                    compiled, plain = on_both_routes(
                        lambda: bezjoin.Curve.from_freecad(edge, nurbs))
                    self.assertEqual(described(compiled, curve_state),
                                     described(plain, curve_state))

    def test_fast_curve_is_the_verbatim_bezier_curve(self):
        """The compiled route's curve has FreeCAD's poles verbatim and a working handle."""
        points = [(0.0, 0.0, 0.0), (1.0, 1.0, 0.2), (2.0, 1.0, 0.1), (3.0, 0.0, 0.0)]
        curve = bezjoin.Curve.from_freecad(bezier_edge(points))
        self.assertEqual(curve.points, points)
        self.assertEqual((curve.is_nurbs, curve.degree, curve.dim), (False, 3, 3))
        curve.close()
        self.assertTrue(curve.closed)
        curve.close()  # harmless twice
        with self.assertRaises(ValueError):
            curve.points


class ToFreecad(unittest.TestCase):
    def test_same_poles_on_both_routes(self):
        rng = random.Random(7)
        curves = [bezjoin.Curve(random_points(rng, n)) for n in (2, 4, 8, 26)]
        curves.append(bezjoin.Curve(random_points(rng, 27)))  # degree 26: refused
        curves.append(bezjoin.Curve([(0, 0), (1, 2), (3, 1)]))  # 2D: ctypes route
        with bezjoin.Curve(random_points(rng, 5)) as whole:
            left, right = whole.split(0.3)  # shape unknown to the bindings
        curves += [left, right]
        closed = bezjoin.Curve(random_points(rng, 4))
        closed.close()
        curves.append(closed)
        for index, curve in enumerate(curves):
            with self.subTest(index=index):
                compiled, plain = on_both_routes(curve.to_freecad)
                self.assertEqual(described(compiled, poles), described(plain, poles))
            curve.close()


class ConnectEdges(unittest.TestCase):
    """bezjoin.connect_edges: the same blend (poles bit for bit) or the same error on
    both routes, for valid and invalid arguments and every kind of edge."""

    def test_same_blend_or_error_on_both_routes(self):
        rng = random.Random(1919)
        edges = [bezier_edge(random_points(rng, n)) for n in (2, 4, 4, 6, 9)]
        edges.append(bezier_edge(random_points(rng, 4), 0.0, 0.5))
        edges.append(Part.LineSegment(V(20, 0, 0), V(25, 3, 1)).toShape())
        edges.append(Part.ArcOfCircle(Part.Circle(V(1, 2, 0), V(0, 0, 1), 2.0),
                                      0.3, 2.0).toShape())
        options = [dict(), dict(p_order=3, q_order=3, p_scale=0.8, q_scale=0.8),
                   dict(p_order=1, q_order=2, p_scale=2, q_scale=1), dict(auto_scale=True),
                   dict(auto_scale=False), dict(p_scale=0.5), dict(q_order=0),
                   dict(p_order=-1), dict(p_order=12, q_order=13), dict(p_order=1.5),
                   dict(p_order=True), dict(auto_scale="yes"), dict(p_scale="big"),
                   dict(p_scale=0.0), dict(q_scale=float("nan"))]
        positions = [(1.0, 0.0), (0.4, 0.6), (1, 0), (2.0, 0.0), (float("nan"), 0.0),
                     ("1", 0.0)]
        for i, p_edge in enumerate(edges):
            for j, q_edge in enumerate(edges):
                if i == j:
                    continue
                for k, option in enumerate(options):
                    u0, v0 = positions[(i + j + k) % len(positions)]
                    with self.subTest(p=i, q=j, options=option, u0=u0, v0=v0):
                        compiled, plain = on_both_routes(
                            lambda: bezjoin.connect_edges(p_edge, u0, q_edge, v0, **option))
                        self.assertEqual(described(compiled, poles), described(plain, poles))


def general_blend(*args, **kwargs):
    """blend_edges through its general path only (the fast path switched off)."""
    fast = operations._blend_bezier_edges
    operations._blend_bezier_edges = lambda *a, **k: None
    try:
        return operations.blend_edges(*args, **kwargs)
    finally:
        operations._blend_bezier_edges = fast


def edge_state(edge):
    return (edge.ParameterRange, poles(edge.Curve))


class BlendEdgesFastPath(unittest.TestCase):
    """operations.blend_edges takes connect_edges for two whole Bezier edges and gives
    the edge (curve, parameter range) of its general path, or the same error."""

    def test_same_edge_or_error_as_the_general_path(self):
        rng = random.Random(2024)
        p_points = [(0, 0, 0), (1, 1, 0.2), (2, 1, 0.1), (3, 0, 0)]
        q_points = [(4, 0.5, 0), (5, 0, 0.3), (6, 1, 0.2), (7, 0, 0)]
        pairs = [
            ("facing", p_points, q_points),
            ("second reversed", p_points, q_points[::-1]),
            ("first reversed", p_points[::-1], q_points),
            ("both reversed", p_points[::-1], q_points[::-1]),
            ("tie: a closed pair", [(0, 0, 0), (1, 1, 0), (2, 0, 0)],
             [(2, 0, 0), (1, -1, 0), (0, 0, 0)]),
            ("shared vertex", p_points, [(3, 0, 0), (4, 1, 0), (5, 0, 0)]),
            ("gap at the tolerance", [(0, 0, 0), (1, 0, 0)], [(1 + 2e-7, 0, 0), (2, 1, 0)]),
            ("lines as Bezier edges", [(0, 0, 0), (10, 0, 0)], [(12, 2, 0), (12, 10, 0)]),
            ("random", random_points(rng, 5), random_points(rng, 3)),
            ("high degrees", random_points(rng, 14), random_points(rng, 13)),
        ]
        options = [dict(), dict(u0=0.7, v0=0.2), dict(p_order=2, q_order=1, p_scale=1.5),
                   dict(orient=False), dict(auto_scale=False), dict(p_order=12, q_order=13),
                   dict(u0=0, v0=1), dict(u0=1.5)]
        for name, first, second in pairs:
            for option in options:
                with self.subTest(name, options=option):
                    a, b = bezier_edge(first), bezier_edge(second)
                    fast = outcome(lambda: operations.blend_edges(a, b, **option))
                    general = outcome(lambda: general_blend(a, b, **option))
                    self.assertEqual(described(fast, edge_state), described(general, edge_state))

    def test_fast_path_is_taken(self):
        """For two facing whole Bezier edges blend_edges is connect_edges' curve: with
        given scales, and with the automatic scale when the blend leaves both edges at
        the same speed. With the automatic scale and different speeds the general path
        balances them (the library's balanced scale, session 41), so the fast path
        declines."""
        a = bezier_edge([(0, 0, 0), (1, 1, 0.2), (2, 1, 0.1), (3, 0, 0)])
        b = bezier_edge([(4, 0.5, 0), (5, 0, 0.3), (6, 1, 0.2), (7, 0, 0)])
        given = dict(p_scale=1.5, q_scale=0.5, auto_scale=False)
        taken = operations._blend_bezier_edges(a, b, 1.0, 0.0, None, None, 1.5, 0.5, False,
                                               True)
        self.assertIsNotNone(taken)
        self.assertEqual(edge_state(taken), edge_state(
            Part.Edge(bezjoin.connect_edges(a, 1.0, b, 0.0, **given), 0.0, 1.0)))
        self.assertTrue(math.isclose(taken.valueAt(0.0).x, 3.0, abs_tol=1e-12))
        self.assertIsNone(operations._blend_bezier_edges(a, b, 1.0, 0.0, None, None, None,
                                                         None, None, True))
        # b's first leg as long as a's last one: the same speed at both ends
        same = bezier_edge([(4, 0.5, 0), (5, -0.5, -0.1), (6, 1, 0.2), (7, 0, 0)])
        taken = operations._blend_bezier_edges(a, same, 1.0, 0.0, None, None, None, None,
                                               None, True)
        self.assertIsNotNone(taken)
        self.assertEqual(edge_state(taken), edge_state(
            Part.Edge(bezjoin.connect_edges(a, 1.0, same, 0.0), 0.0, 1.0)))


if __name__ == "__main__":
    unittest.main()
