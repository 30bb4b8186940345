"""intersect and fillet: crossings are common points, the kept parts and the setbacks are
what was asked (arc lengths re-measured), the chain is smooth, and every error path."""

import math

import pytest

import bezjoin
from bezjoin import Curve
from reference import derivative, distance, norm
from test_curve import expect_error


def test_two_lines_cross_where_expected():
    with Curve([(0, 0), (4, 4)]) as p, Curve([(0, 4), (4, 0)]) as q:
        crossings = bezjoin.intersect(p, q)
    assert len(crossings) == 1
    u, v = crossings[0]
    assert abs(u - 0.5) <= 1e-12 and abs(v - 0.5) <= 1e-12


def test_crossings_are_common_points_ordered_by_u():
    # a wave crossing a line three times
    wave = [(0, -1), (1, 3), (2, -3), (3, 1)]
    line = [(-0.5, 0.1), (3.5, -0.1)]
    with Curve(wave) as p, Curve(line) as q:
        crossings = bezjoin.intersect(p, q)
        assert len(crossings) == 3
        assert [u for u, _v in crossings] == sorted(u for u, _v in crossings)
        for u, v in crossings:
            assert distance(p.evaluate(u), q.evaluate(v)) <= 1e-12 * 10


def test_more_crossings_than_the_first_request_holds(monkeypatch):
    import bezjoin._fillet as fillet_module

    wave = [(0, -1), (1, 3), (2, -3), (3, 1)]
    line = [(-0.5, 0.1), (3.5, -0.1)]
    with Curve(wave) as p, Curve(line) as q:
        expected = bezjoin.intersect(p, q)
        monkeypatch.setattr(fillet_module, "FIRST_CAPACITY", 1)
        assert bezjoin.intersect(p, q) == expected
        assert len(expected) == 3


def test_no_crossing_is_an_empty_list():
    with Curve([(0, 0), (1, 0)]) as p, Curve([(0, 1), (1, 1)]) as q:
        assert bezjoin.intersect(p, q) == []


def kept_parameter(whole, trimmed, at_start):
    """The u0 (or v0) with trimmed = whole|[0,u0] (or whole|[v0,1]), from first derivatives."""
    if at_start:
        return norm(derivative(trimmed, 0.0, 1)) / norm(derivative(whole, 0.0, 1))
    return 1.0 - norm(derivative(trimmed, 1.0, 1)) / norm(derivative(whole, 1.0, 1))


@pytest.mark.parametrize("order,p_setback,q_setback,alpha,beta", [
    (1, 0.5, 0.5, 1.0, 1.0), (2, 0.4, 0.9, 1.0, 1.0), (2, 0.6, 0.6, 1.4, 0.8), (3, 0.3, 0.3, 1, 1)])
def test_fillet_keeps_the_right_parts_and_is_smooth(order, p_setback, q_setback, alpha, beta):
    p_points = [(0, 0), (1, 0.3), (2, 1.2), (3, 3.0)]
    q_points = [(0, 3.0), (1.2, 2.0), (2.5, 1.6), (4, 1.0)]
    with Curve(p_points) as p, Curve(q_points) as q:
        ((u_star, v_star),) = bezjoin.intersect(p, q)
        with bezjoin.fillet(p, q, p_setback=p_setback, q_setback=q_setback, p_order=order,
                            q_order=order, p_scale=alpha, q_scale=beta) as result:
            p_kept, blend, q_kept = (c.points for c in result.curves())
            u0 = kept_parameter(p_points, p_kept, True)
            v0 = kept_parameter(q_points, q_kept, False)
            assert distance(p_kept[0], p_points[0]) <= 1e-12
            assert distance(q_kept[-1], q_points[-1]) <= 1e-12
            assert distance(p_kept[-1], p.evaluate(u0)) <= 1e-10
            assert distance(q_kept[0], q.evaluate(v0)) <= 1e-10
            assert abs(p.length(u0, u_star) - p_setback) <= 1e-9
            assert abs(q.length(v_star, v0) - q_setback) <= 1e-9
            assert len(blend) == 2 * order + 2
            widths = (u0, alpha, (1 - v0) * alpha / beta)
            chain = (p_kept, blend, q_kept)
            for left, right in ((0, 1), (1, 2)):
                for k in range(order + 1):
                    a = tuple(x / widths[left] ** k for x in derivative(chain[left], 1.0, k))
                    b = tuple(x / widths[right] ** k for x in derivative(chain[right], 0.0, k))
                    assert distance(a, b) <= 1e-9 * max(1.0, norm(a)), (left, k)


def test_symmetric_setback():
    with Curve([(0, 0), (4, 4)]) as p, Curve([(0, 4), (4, 0)]) as q, \
            bezjoin.fillet(p, q, setback=1.0, p_order=1, q_order=1) as result:
        corner = (2.0, 2.0)
        assert abs(distance(result.p_trimmed.points[-1], corner) - 1.0) <= 1e-12
        assert abs(distance(result.q_trimmed.points[0], corner) - 1.0) <= 1e-12


def test_auto_scale_keeps_a_fast_corner_inside():
    """Lines of speed 8 as cubics, C^3, setback 0.5: scale 1 puts the blend's second
    control point past the corner; the automatic scale keeps the whole control
    polygon in the corner's quadrant, and the chain is C^3 with widths (u0, s, 1 - v0)."""
    p_points = [(-4, 0), (-4 / 3, 0), (4 / 3, 0), (4, 0)]
    q_points = [(0, -4), (0, -4 / 3), (0, 4 / 3), (0, 4)]
    with Curve(p_points) as p, Curve(q_points) as q:
        with bezjoin.fillet(p, q, setback=0.5, p_scale=1.0, q_scale=1.0) as paper:
            assert paper.scale is None
            assert paper.blend.points[1][0] > 0.0
        with bezjoin.fillet(p, q, setback=0.5, auto_scale=True) as result:
            s = result.scale
            assert 0.0 < s < 1.0
            assert all(x <= 1e-15 and y >= -1e-15 for x, y in result.blend.points)
            u0, v0 = 0.5 - 0.5 / 8, 0.5 + 0.5 / 8
            widths = (u0, s, 1 - v0)
            chain = tuple(c.points for c in result.curves())
            for left, right in ((0, 1), (1, 2)):
                size = max(norm(derivative(chain[left], 1.0, k)) / widths[left] ** k
                           for k in range(4))
                for k in range(4):
                    a = tuple(x / widths[left] ** k for x in derivative(chain[left], 1.0, k))
                    b = tuple(x / widths[right] ** k for x in derivative(chain[right], 0.0, k))
                    assert distance(a, b) <= 1e-9 * size, (left, k)
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet(p, q, setback=9.0, auto_scale=True), "p_setback")


def test_fillet_errors():
    with Curve([(0, 0), (4, 4)]) as p, Curve([(0, 4), (4, 0)]) as q, \
            Curve([(0, 5), (4, 5)]) as away, Curve([(0, 0, 0), (1, 1, 1)]) as space:
        expect_error("BZJ_ERR_NO_INTERSECTION", lambda: bezjoin.fillet(p, away, setback=0.5))
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.fillet(p, q, setback=10.0))
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.fillet(p, q, setback=-1.0))
        expect_error("BZJ_ERR_NON_FINITE", lambda: bezjoin.fillet(p, q, setback=math.nan))
        # An order above the degree is accepted, as for connect.
        with bezjoin.fillet(p, q, setback=0.5, p_order=2, q_order=1) as above:
            assert above.blend.degree == 2 + 1 + 1
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet(p, q, setback=0.5, p_scale=0.0), "p_scale")
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.fillet(p, space, setback=0.5))
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.intersect(p, space))
        with pytest.raises(TypeError, match="not both"):
            bezjoin.fillet(p, q, setback=0.5, p_setback=0.5)
        with pytest.raises(TypeError, match="needs setback"):
            bezjoin.fillet(p, q, p_setback=0.5)
        with pytest.raises(TypeError, match="p must be a bezjoin.Curve"):
            bezjoin.intersect(None, q)


def test_balanced_scale_gives_a_corner_of_unequal_lines_the_blend_of_equal_ones():
    """Lines 1000 and 10 long at a right angle, setback 1, are cut at the points where
    lines 10 and 10 are: the balanced blend is the same curve, both its ends run at one
    speed, and ``scales`` are that speed over each edge's speed. The one-s automatic
    scale leaves the short edge at 1/100 of the long one's speed: a near-kink."""
    with Curve([(-1000, 0), (0, 0)]) as long, Curve([(-10, 0), (0, 0)]) as short, \
            Curve([(0, 0), (0, 10)]) as up:
        with bezjoin.fillet_vertex(short, up, setback=1, p_order=2, q_order=2,
                                   auto_scale="balanced", gap=0.0) as equal, \
                bezjoin.fillet_vertex(long, up, setback=1, p_order=2, q_order=2,
                                      auto_scale="balanced", gap=0.0) as unequal, \
                bezjoin.fillet_vertex(long, up, setback=1, p_order=2, q_order=2,
                                      auto_scale=True, gap=0.0) as automatic:
            assert unequal.scale is None
            alpha, beta = unequal.scales
            assert math.isclose(alpha * 1000, beta * 10, rel_tol=1e-12)
            for a, b in zip(unequal.blend.points, equal.blend.points):
                assert distance(a, b) <= 1e-12
            start = norm(unequal.blend.derivatives(0.0, 1)[1])
            end = norm(unequal.blend.derivatives(1.0, 1)[1])
            assert math.isclose(start, end, rel_tol=1e-12)
            assert math.isclose(start, alpha * 1000, rel_tol=1e-12)
            moved = max(distance(a, b)
                        for a, b in zip(automatic.blend.points, equal.blend.points))
            assert moved > 1e-2
            assert automatic.scales == (automatic.scale, automatic.scale)
            reference = equal.blend.points
        # At a crossing, through bzj_fillet_balanced_scale: both ends at one speed.
        with Curve([(-1000, 0), (5, 0)]) as p, Curve([(0, -5), (0, 10)]) as q, \
                bezjoin.fillet(p, q, setback=1, p_order=2, q_order=2,
                               auto_scale="balanced") as crossing:
            for a, b in zip(crossing.blend.points, reference):
                assert distance(a, b) <= 1e-12
        with bezjoin.fillet(long, up, setback=1, p_scale=2.0) as given:
            assert given.scale is None and given.scales == (2.0, 1.0)


def test_auto_scale_takes_balanced_only_where_offered():
    with Curve([(-10, 0), (0, 0)]) as p, Curve([(0, 0), (0, 10)]) as q:
        with pytest.raises(TypeError, match="auto_scale"):
            bezjoin.fillet_vertex(p, q, setback=1, auto_scale="fair")
        with pytest.raises(TypeError, match="auto_scale"):
            bezjoin.fillet_deviation(p, q, max_deviation=0.1, auto_scale="balanced")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_vertex(p, q, setback=20, auto_scale="balanced"),
                     "p_setback")


def test_balanced_chain_rounds_a_long_rectangle_as_a_square():
    """A closed 1000 x 10 rectangle of lines and a 10 x 10 square, setback 1, orders 2:
    every balanced corner blend of the rectangle is the square's blend moved to that
    corner (the cuts are the same points relative to the corner; only the sides' speeds
    differ), and ``corner_scales`` are that speed over each side's speed. With one s a
    corner the long sides' corners are different curves."""
    def rectangle(width, height):
        corners = [(0, 0), (width, 0), (width, height), (0, height)]
        return [Curve([corners[i], corners[(i + 1) % 4]]) for i in range(4)]

    def blends(curves, mode):
        with bezjoin.fillet_chain(curves, setback=1, p_order=2, q_order=2, closed=True,
                                  auto_scale=mode) as result:
            shapes = []
            for i, blend in enumerate(result.blends):
                # The corner after curve i is the start of curve i + 1.
                corner = curves[(i + 1) % 4].points[0]
                shapes.append([tuple(x - c for x, c in zip(point, corner))
                               for point in blend.points])
            return shapes, result.corner_scales, result.scales

    square, long = rectangle(10, 10), rectangle(1000, 10)
    try:
        square_shapes, _, _ = blends(square, "balanced")
        long_shapes, pairs, scales = blends(long, "balanced")
        auto_shapes, auto_pairs, auto_scales = blends(long, True)
    finally:
        for curve in square + long:
            curve.close()
    assert scales is None and len(pairs) == 4
    lengths = [1000, 10, 1000, 10]
    for i, (alpha, beta) in enumerate(pairs):
        # alpha |P'| = beta |Q'|: side i before the corner, side i + 1 after it.
        assert math.isclose(alpha * lengths[i], beta * lengths[(i + 1) % 4], rel_tol=1e-12)
    for a, b in zip(long_shapes, square_shapes):
        for x, y in zip(a, b):
            assert distance(x, y) <= 1e-9
    assert auto_pairs == [(s, s) for s in auto_scales]
    moved = max(distance(x, y) for a, b in zip(auto_shapes, square_shapes) for x, y in zip(a, b))
    assert moved > 1e-2
