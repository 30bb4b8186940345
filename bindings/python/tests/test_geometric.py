"""bzj_connect_geometric through the bindings: given shape values satisfy the
beta-constraints, the default (fair) G2 blend of a long-edge corner does not loop
and meets both edges with the same unit tangent and curvature vector, and errors
name their argument."""

import math

import bezjoin
from bezjoin import Curve
from reference import assert_close


def frame(jet):
    """Unit tangent and curvature vector of a 2D jet (value, r', r'')."""
    a, b = jet[1], jet[2]
    s2 = a[0] ** 2 + a[1] ** 2
    m = a[0] * b[0] + a[1] * b[1]
    s = math.sqrt(s2)
    return ([x / s for x in a], [(b[c] * s2 - m * a[c]) / (s2 * s2) for c in range(2)])


def test_given_shapes_are_the_beta_constraints():
    with Curve([(0, 0), (1, 2), (3, 2), (4, 0)]) as p, \
            Curve([(6, 1), (7, 3), (9, 2), (10, 0)]) as q, \
            bezjoin.connect_geometric(p, 0.7, q, 0.2, p_shape=[0.8, 0.3],
                                      q_shape=[1.2, -0.2]) as g:
        assert g.p_shape == [0.8, 0.3] and g.q_shape == [1.2, -0.2]
        pj, r0 = p.derivatives(0.7, 2), g.curve.derivatives(0.0, 2)
        assert_close(r0[1], [0.8 * x for x in pj[1]], 1e-9)
        assert_close(r0[2], [0.64 * x + 0.3 * y for x, y in zip(pj[2], pj[1])], 1e-9)
        qj, r1 = q.derivatives(0.2, 2), g.curve.derivatives(1.0, 2)
        assert_close(r1[2], [1.44 * x - 0.2 * y for x, y in zip(qj[2], qj[1])], 1e-9)


def test_report_false_gives_the_same_curve_without_the_report():
    with Curve([(0, 0), (1, 2), (3, 2), (4, 0)]) as p, \
            Curve([(6, 1), (7, 3), (9, 2), (10, 0)]) as q:
        for shapes in ({"p_shape": [0.8, 0.3], "q_shape": [1.2, -0.2]}, {}):
            with bezjoin.connect_geometric(p, 0.7, q, 0.2, **shapes) as full, \
                    bezjoin.connect_geometric(p, 0.7, q, 0.2, report=False, **shapes) as bare:
                assert bare.curve.points == full.curve.points
                assert (bare.p_shape, bare.q_shape) == (full.p_shape, full.q_shape)
                assert full.energy > 0 and full.curvature_extrema >= 0
                assert (bare.energy, bare.curvature_min, bare.curvature_max,
                        bare.curvature_extrema) == (None, None, None, None)


def test_default_g2_corner_is_fair_and_loop_free():
    with Curve([(-40, 0), (0, 0)]) as a, Curve([(0, 0), (0, 20)]) as b, \
            bezjoin.connect_geometric(a, 0.95, b, 0.1) as g:
        assert g.curvature_extrema == 1
        assert g.p_shape[0] > 0 and g.q_shape[0] > 0
        length = g.curve.length(0.0, 1.0)
        assert 2.8 < length < 4.0  # the arc of radius 2 is 3.14; scale 1 loops (18.6)
        for edge, u, t in ((a, 0.95, 0.0), (b, 0.1, 1.0)):
            t1, k1 = frame(edge.derivatives(u, 2))
            t2, k2 = frame(g.curve.derivatives(t, 2))
            assert_close(t1, t2, 1e-12)
            assert all(abs(x - y) <= 1e-9 for x, y in zip(k1, k2))


def test_errors_name_the_argument():
    with Curve([(0, 0), (1, 2), (3, 2), (4, 0)]) as p, \
            Curve([(6, 1), (7, 3), (9, 2), (10, 0)]) as q:
        for call, word in (
                (lambda: bezjoin.connect_geometric(p, 0.7, q, 0.2, p_shape=[-1.0, 0.0]),
                 "p_shape[0]"),
                (lambda: bezjoin.connect_geometric(p, 0.7, q, 0.2, p_order=7), "p_order"),
                (lambda: bezjoin.connect_geometric(p, 1.5, q, 0.2), "u0")):
            try:
                call().close()
            except bezjoin.BezjoinError as error:
                assert error.status_name == "BZJ_ERR_INVALID_ARGUMENT" and word in str(error)
            else:
                raise AssertionError(f"no error for {word}")


def test_fillet_radius_cuts_where_the_arc_touches():
    with Curve([(-40, 0), (0, 0)]) as a, Curve([(0, 0), (0, 20)]) as b, \
            bezjoin.fillet_radius(a, b, 2.0) as f:
        assert_close(f.p_trimmed.derivatives(1.0, 0)[0], (-2.0, 0.0), 1e-10)
        assert_close(f.q_trimmed.derivatives(0.0, 0)[0], (0.0, 2.0), 1e-10)
        assert f.curvature_extrema == 1 and f.curvature_max > 0.5
        for edge, u, t in ((f.p_trimmed, 1.0, 0.0), (f.q_trimmed, 0.0, 1.0)):
            t1, k1 = frame(edge.derivatives(u, 2))
            t2, k2 = frame(f.blend.derivatives(t, 2))
            assert_close(t1, t2, 1e-12)
            assert all(abs(x - y) <= 1e-9 for x, y in zip(k1, k2))
        try:
            bezjoin.fillet_radius(a, b, 50.0).close()
        except bezjoin.BezjoinError as error:
            assert error.status_name == "BZJ_ERR_INVALID_ARGUMENT" and "radius" in str(error)
        else:
            raise AssertionError("a radius that does not fit was accepted")
