"""fillet_deviation and fillet_chain: the blend keeps to the deviation bound (re-measured
here), the setbacks are what the report says (arc lengths re-measured), the pieces of a
chain meet and their derivatives agree across every join, and the error paths."""

import math

import pytest

import bezjoin
from bezjoin import Curve
from reference import de_casteljau, derivative, distance, norm
from test_curve import expect_error

P_POINTS = [(0, 0), (1, 0.3), (2, 1.2), (3, 3.0)]
Q_POINTS = [(0, 3.0), (1.2, 2.0), (2.5, 1.6), (4, 1.0)]


def closest_distance(points, x):
    """min over t of |R(t) - x| for the Bezier curve ``points``: dense sampling, then
    golden-section refinement around the best sample."""
    samples = 2000
    best = min(range(samples + 1), key=lambda i: distance(de_casteljau(points, i / samples), x))
    low, high = max(0.0, (best - 1) / samples), min(1.0, (best + 1) / samples)
    ratio = (math.sqrt(5) - 1) / 2
    for _ in range(100):
        a, b = high - ratio * (high - low), low + ratio * (high - low)
        if distance(de_casteljau(points, a), x) < distance(de_casteljau(points, b), x):
            high = b
        else:
            low = a
    return distance(de_casteljau(points, (low + high) / 2), x)


@pytest.mark.parametrize("max_deviation,ratio,order", [(0.1, 1.0, 1), (0.05, 1.7, 2),
                                                       (0.2, 0.6, 3)])
def test_fillet_deviation_keeps_to_the_bound(max_deviation, ratio, order):
    with Curve(P_POINTS) as p, Curve(Q_POINTS) as q:
        ((u_star, v_star),) = bezjoin.intersect(p, q)
        corner = p.evaluate(u_star)
        with bezjoin.fillet_deviation(p, q, max_deviation, setback_ratio=ratio, p_order=order,
                                      q_order=order) as result:
            assert isinstance(result, bezjoin.DeviationFilletResult)
            # The bound is strict and nearly all of it is used.
            assert max_deviation * (1 - 1e-9) <= result.deviation <= max_deviation
            # The reported deviation is the blend's distance from the corner.
            blend = result.blend.points
            assert abs(closest_distance(blend, corner) - result.deviation) <= 1e-9 * max_deviation
            # Setbacks: dq = ratio * dp, both arc lengths from the crossing.
            assert abs(result.q_setback - ratio * result.p_setback) <= 1e-12 * result.q_setback
            assert abs(p.length(result.u0, u_star) - result.p_setback) <= 1e-9
            assert abs(q.length(v_star, result.v0) - result.q_setback) <= 1e-9
            # The kept parts end at the reported cuts, and the chain is C^order
            # with knot intervals (u0, s, 1 - v0), s the automatic scale (the default).
            p_kept, q_kept = result.p_trimmed.points, result.q_trimmed.points
            assert distance(p_kept[-1], p.evaluate(result.u0)) <= 1e-12
            assert distance(q_kept[0], q.evaluate(result.v0)) <= 1e-12
            assert result.scale > 0
            widths = (result.u0, result.scale, 1.0 - result.v0)
            assert_smooth((p_kept, blend, q_kept), widths, order)


@pytest.mark.parametrize("scales", [{}, {"p_scale": 1.0, "q_scale": 1.0}, {"p_scale": 0.7},
                                    {"auto_scale": False}])
def test_fillet_deviation_is_fillet_with_the_setbacks_found(scales):
    with Curve(P_POINTS) as p, Curve(Q_POINTS) as q, \
            bezjoin.fillet_deviation(p, q, 0.1, setback_ratio=1.3, p_order=2, q_order=2,
                                     **scales) as found:
        if scales:  # explicit scales: used as given (a missing one is 1.0), no scale chosen
            assert found.scale is None
            again_scales = {"p_scale": scales.get("p_scale", 1.0),
                            "q_scale": scales.get("q_scale", 1.0)}
        else:  # the default: the automatic scale of the setbacks it found
            with bezjoin.fillet(p, q, p_setback=found.p_setback, q_setback=found.q_setback,
                                p_order=2, q_order=2) as automatic:
                assert abs(automatic.scale - found.scale) <= 1e-5 * found.scale
            again_scales = {"p_scale": found.scale, "q_scale": found.scale}
        with bezjoin.fillet(p, q, p_setback=found.p_setback, q_setback=found.q_setback,
                            p_order=2, q_order=2, **again_scales) as again:
            for ours, theirs in zip(found.curves(), again.curves()):
                assert max(distance(a, b) for a, b in zip(ours.points, theirs.points)) <= 1e-9


def test_default_fillet_deviation_of_fast_lines_stays_in_the_corner():
    """Lines 50 and 30 long crossing at the origin, deviation 0.1: with the paper's
    scale 1 the blend's control points go past the corner (the blend loops); the
    default keeps the whole control polygon in the corner's quadrant."""
    with Curve([(-40, 0), (10, 0)]) as p, Curve([(0, -10), (0, 20)]) as q:
        with bezjoin.fillet_deviation(p, q, 0.1, p_scale=1.0, q_scale=1.0) as paper:
            assert any(x > 0 or y < 0 for x, y in paper.blend.points)
        with bezjoin.fillet_deviation(p, q, 0.1) as result:
            assert 0.1 * (1 - 1e-9) <= result.deviation <= 0.1
            assert all(x <= 1e-12 and y >= -1e-12 for x, y in result.blend.points)
            # Arc length of the blend: between the chord and the two setbacks.
            chord = math.hypot(result.p_setback, result.q_setback)
            assert chord <= result.blend.length() <= result.p_setback + result.q_setback


def test_fillet_deviation_errors():
    with Curve([(0, 0), (4, 4)]) as p, Curve([(0, 4), (4, 0)]) as q, \
            Curve([(0, 5), (4, 5)]) as away:
        error = expect_error("BZJ_ERR_INVALID_ARGUMENT",
                             lambda: bezjoin.fillet_deviation(p, q, 100.0), "max_deviation")
        assert "cannot be reached" in error.message
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_deviation(p, q, -0.1), "max_deviation")
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.fillet_deviation(p, q, 0.1, setback_ratio=math.nan),
                     "setback_ratio")
        # An order above the degree is accepted, as for connect.
        with bezjoin.fillet_deviation(p, q, 0.1, p_order=1, q_order=3) as above:
            assert above.blend.degree == 1 + 3 + 1
        expect_error("BZJ_ERR_NO_INTERSECTION", lambda: bezjoin.fillet_deviation(p, away, 0.1))
        with pytest.raises(TypeError, match="q must be a bezjoin.Curve"):
            bezjoin.fillet_deviation(p, None, 0.1)


def assert_smooth(chain, widths, order, closing=False):
    """Consecutive pieces (control points) meet, and derivatives 1..order agree
    when scaled by the pieces' knot intervals; ``closing``: the last piece joins
    the first too."""
    pairs = [(i, i + 1) for i in range(len(chain) - 1)]
    if closing:
        pairs.append((len(chain) - 1, 0))
    for left, right in pairs:
        assert distance(chain[left][-1], chain[right][0]) <= 1e-12, (left, right)
        size = max(norm(derivative(chain[left], 1.0, k)) / widths[left] ** k
                   for k in range(order + 1))
        for k in range(1, order + 1):
            a = tuple(x / widths[left] ** k for x in derivative(chain[left], 1.0, k))
            b = tuple(x / widths[right] ** k for x in derivative(chain[right], 0.0, k))
            assert distance(a, b) <= 1e-9 * max(1.0, size), (left, right, k)


# A curved triangle: three cubic sides meeting end to end, bulged outwards. Each side
# is chord-linear (its control points are evenly spaced along the chord), so a point
# X on side i has parameter <X - a, b - a> / |b - a|^2.
VERTICES = [(0.0, 0.0), (4.0, 0.0), (1.0, 3.0)]


def bulged_side(a, b, h=-0.08):
    normal = (-(b[1] - a[1]), b[0] - a[0])
    return [tuple(a[c] + i / 3 * (b[c] - a[c]) + (h if i in (1, 2) else 0.0) * normal[c]
                  for c in range(2)) for i in range(4)]


def chord_parameter(a, b, x):
    d = (b[0] - a[0], b[1] - a[1])
    return ((x[0] - a[0]) * d[0] + (x[1] - a[1]) * d[1]) / (d[0] ** 2 + d[1] ** 2)


def side_widths(trimmed, sides):
    """The knot interval of each trimmed side: the length of its parameter range."""
    widths = []
    for i, piece in enumerate(trimmed):
        a, b = sides[i][0], sides[i][-1]
        widths.append(chord_parameter(a, b, piece[-1]) - chord_parameter(a, b, piece[0]))
    return widths


@pytest.mark.parametrize("order,p_setback,q_setback,scale", [(1, 0.5, 0.5, 1.0),
                                                             (2, 0.5, 0.4, 1.0),
                                                             (3, 0.4, 0.6, 1.3)])
def test_closed_chain_is_smooth_at_every_join(order, p_setback, q_setback, scale):
    sides = [bulged_side(VERTICES[i], VERTICES[(i + 1) % 3]) for i in range(3)]
    curves = [Curve(s) for s in sides]
    try:
        with bezjoin.fillet_chain(curves, p_setback=p_setback, q_setback=q_setback,
                                  p_order=order, q_order=order, p_scale=scale, q_scale=scale,
                                  closed=True) as result:
            assert isinstance(result, bezjoin.FilletChainResult)
            assert len(result.pieces) == 6 and result.closed
            pieces = [c.points for c in result.pieces]
            assert [c.points for c in result.trimmed] == pieces[0::2]
            assert [c.points for c in result.blends] == pieces[1::2]
            for blend in pieces[1::2]:
                assert len(blend) == 2 * order + 2
            # Each trimmed side is a part of its side, cut at the setbacks (arc length).
            widths = side_widths(pieces[0::2], sides)
            for i, piece in enumerate(pieces[0::2]):
                a, b = sides[i][0], sides[i][-1]
                start, end = chord_parameter(a, b, piece[0]), chord_parameter(a, b, piece[-1])
                assert 0.0 < start < end < 1.0
                assert distance(piece[0], curves[i].evaluate(start)) <= 1e-12
                assert abs(curves[i].length(start, 0.0) + q_setback) <= 1e-9
                assert abs(curves[i].length(end, 1.0) - p_setback) <= 1e-9
            all_widths = [w for width in widths for w in (width, scale)]
            assert_smooth(pieces, all_widths, order, closing=True)
            assert result.curves() == result.pieces
        assert all(piece.closed for piece in result.pieces)
    finally:
        for c in curves:
            c.close()


def test_open_chain_keeps_the_outer_ends():
    sides = [bulged_side(VERTICES[i], VERTICES[(i + 1) % 3]) for i in range(3)]
    curves = [Curve(s) for s in sides]
    try:
        with bezjoin.fillet_chain(curves, setback=0.5, p_order=2, q_order=2,
                                  auto_scale=False) as open_chain, \
                bezjoin.fillet_chain(curves, setback=0.5, p_order=2, q_order=2,
                                     p_scale=1.0, q_scale=1.0, closed=True) as closed_chain:
            pieces = [c.points for c in open_chain.pieces]
            assert len(pieces) == 5 and not open_chain.closed
            assert distance(pieces[0][0], sides[0][0]) <= 1e-15
            assert distance(pieces[-1][-1], sides[2][-1]) <= 1e-15
            # Its inner corners are those of the closed chain.
            assert pieces[1:4] == [c.points for c in closed_chain.pieces[1:4]]
            widths = side_widths(pieces[0::2], sides)
            assert_smooth(pieces, [widths[0], 1.0, widths[1], 1.0, widths[2]], 2)
    finally:
        for c in curves:
            c.close()


def test_two_crossing_curves_are_the_fillet_of_their_corner():
    with Curve(P_POINTS) as p, Curve(Q_POINTS) as q, \
            bezjoin.fillet_chain([p, q], setback=0.5, p_order=2, q_order=2) as chain, \
            bezjoin.fillet(p, q, setback=0.5, p_order=2, q_order=2) as single:
        assert [c.points for c in chain.pieces] == [c.points for c in single.curves()]


def test_default_orders_are_the_lowest_degree():
    with Curve([(0, 0), (1, 0.1), (2, 0)]) as p, Curve([(1.5, -1), (1.6, 0), (1.5, 1), (1.4, 2)]) \
            as q, bezjoin.fillet_chain([p, q], setback=0.3) as chain:
        assert chain.blends[0].degree == 2 + 2 + 1


def test_fillet_chain_errors():
    with Curve([(0, 0), (4, 0)]) as a, Curve([(4, 0), (0, 3)]) as b, \
            Curve([(10, 10), (11, 10)]) as far, Curve([(0, 0, 0), (1, 1, 1)]) as space:
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_chain([a], setback=0.5), "at least 2")
        expect_error("BZJ_ERR_NO_INTERSECTION",
                     lambda: bezjoin.fillet_chain([a, far], setback=0.5), "corner 0")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_chain([a, b], setback=4.5))
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.fillet_chain([a, b], setback=math.inf))
        expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                     lambda: bezjoin.fillet_chain([a, space], setback=0.5))
        with pytest.raises(TypeError, match="curves\\[1\\] must be a bezjoin.Curve"):
            bezjoin.fillet_chain([a, None], setback=0.5)
        with pytest.raises(TypeError, match="closed must be a bool"):
            bezjoin.fillet_chain([a, b], setback=0.5, closed=1)
        with pytest.raises(TypeError, match="not both"):
            bezjoin.fillet_chain([a, b], setback=0.5, q_setback=0.5)
        with pytest.raises(TypeError, match="needs setback"):
            bezjoin.fillet_chain([a, b], p_setback=0.5)
