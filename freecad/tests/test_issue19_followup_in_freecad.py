"""Issue 19, the rest: the one-call blend of two edges (bezjoin.connect_edges), results
placed in the container of their sources, and the smallest edge FreeCAD holds."""

import math
import unittest

import FreeCAD
import Part

import bezjoin

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


if __name__ == "__main__":
    unittest.main()
