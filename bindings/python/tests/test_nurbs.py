"""NURBS curves through the bindings: Curve.nurbs, Curve.ellipse_arc and the NURBS
properties, judged by an independent rational de Boor evaluator written here; the
NURBS rules of the curve operations (parameters kept by split and segment, spans
equal to the curve, reversal on the same domain) and of connect; every error names
its argument."""

import copy
import math
import pickle
import random

import pytest

import bezjoin
from bezjoin import BezjoinError, Curve
from reference import assert_close, distance, norm

# A rational quadratic, 5 poles, 3 spans [0, 1], [1, 2.5], [2.5, 4]; the first
# span's weights are all 1 (a polynomial span).
RQ_POLES = [(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (5.0, 1.0), (6.0, -1.0)]
RQ_WEIGHTS = [1.0, 1.0, 1.0, 0.5, 1.0]
RQ_KNOTS = [0.0, 0.0, 0.0, 1.0, 2.5, 4.0, 4.0, 4.0]
RQ_BREAKS = [0.0, 1.0, 2.5, 4.0]

# An unclamped uniform cubic (domain [3, 6]) in 3D.
UC_POLES = [(0, 0, 0), (1, 1, 1), (2, -1, 0), (3, 0, 2), (4, 2, 1), (5, 1, -1)]
UC_KNOTS = list(range(10))


def de_boor(poles, knots, degree, u, weights=None):
    """C(u) of the rational B-spline, from the span on the right of u (the left at
    the domain's end), by de Boor's algorithm on homogeneous points."""
    count = len(poles)
    weights = weights or [1.0] * count
    k = degree
    while k + 1 < count and knots[k + 1] <= u:
        k += 1
    d = [[w * x for x in poles[j + k - degree]] + [w]
         for j, w in ((j, weights[j + k - degree]) for j in range(degree + 1))]
    for r in range(1, degree + 1):
        for j in range(degree, r - 1, -1):
            lo, hi = knots[j + k - degree], knots[j + 1 + k - r]
            a = (u - lo) / (hi - lo)
            d[j] = [(1 - a) * x + a * y for x, y in zip(d[j - 1], d[j])]
    return tuple(x / d[degree][-1] for x in d[degree][:-1])


def samples(a, b, n=29):
    """n parameters inside (a, b), away from its ends."""
    return [a + (b - a) * (i + 0.43) / n for i in range(n)]


def same_curve_at(piece, whole, params, relative=1e-12):
    for u in params:
        first, second = piece.derivatives(u, 1), whole.derivatives(u, 1)
        assert_close(first[0], second[0], relative)
        assert_close(first[1], second[1], relative * 100)


@pytest.fixture
def rational():
    with Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, RQ_WEIGHTS) as curve:
        yield curve


@pytest.fixture
def unclamped():
    with Curve.nurbs(UC_POLES, UC_KNOTS, 3) as curve:
        yield curve


# -- construction and inspection ----------------------------------------------------


def test_properties_round_trip(rational, unclamped):
    assert rational.is_nurbs and rational.is_rational
    assert rational.degree == 2 and rational.dim == 2 and rational.pole_count == 5
    assert rational.points == RQ_POLES
    assert rational.knots == RQ_KNOTS
    assert rational.weights == RQ_WEIGHTS
    assert rational.domain == (0.0, 4.0)
    assert unclamped.is_nurbs and not unclamped.is_rational
    assert unclamped.weights == [1.0] * 6
    assert unclamped.domain == (3.0, 6.0)
    assert unclamped.points == [tuple(float(x) for x in p) for p in UC_POLES]
    with Curve([(0, 0), (1, 2), (3, 0)]) as bezier:
        assert not bezier.is_nurbs and not bezier.is_rational
        assert bezier.pole_count == 3
        assert bezier.knots == [0.0] * 3 + [1.0] * 3
        assert bezier.weights == [1.0] * 3
        assert bezier.domain == (0.0, 1.0)


def test_equal_weights_are_not_rational_and_read_as_one():
    with Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, [2.0] * 5) as curve, \
            Curve.nurbs(RQ_POLES, RQ_KNOTS, 2) as plain:
        assert not curve.is_rational
        assert curve.weights == [1.0] * 5
        same_curve_at(curve, plain, samples(0, 4))


@pytest.mark.parametrize("seed", [3, 5, 8])
def test_evaluation_matches_de_boor(seed):
    rng = random.Random(seed)
    degree = rng.randint(1, 4)
    count = degree + 1 + rng.randint(0, 5)
    poles = [tuple(rng.uniform(-5, 5) for _ in range(3)) for _ in range(count)]
    weights = [rng.uniform(0.2, 3.0) for _ in range(count)]
    inner = sorted(rng.uniform(0.1, 0.9) for _ in range(count - degree - 1))
    knots = [0.0] * (degree + 1) + inner + [1.0] * (degree + 1)
    with Curve.nurbs(poles, knots, degree, weights) as curve:
        for u in [i / 40 for i in range(41)]:
            assert_close(curve.evaluate(u), de_boor(poles, knots, degree, u, weights), 1e-12,
                         scale=10.0)


def test_unclamped_evaluation_matches_de_boor(unclamped):
    for u in [3.0 + 3.0 * i / 30 for i in range(31)]:
        assert_close(unclamped(u), de_boor(UC_POLES, UC_KNOTS, 3, u), 1e-13, scale=10.0)


def test_derivatives_above_the_degree(rational, unclamped):
    rows = unclamped.derivatives(4.5, 6)
    assert all(row == (0.0, 0.0, 0.0) for row in rows[4:])
    assert norm(rows[3]) > 0
    assert norm(rational.derivatives(3.0, 5)[5]) > 0  # a rational span has them all


def test_eval_many_blocks_are_eval(rational):
    ts = [0.0, 0.5, 1.0, 2.5, 3.9, 4.0]
    many = rational.derivatives_many(ts, 2)
    assert many == [rational.derivatives(t, 2) for t in ts]


def test_to_nurbs_copy_and_pickle(rational):
    with Curve([(0, 0), (1, 2), (3, 0)]) as bezier, bezier.to_nurbs() as as_nurbs:
        assert as_nurbs.is_nurbs and as_nurbs.knots == [0.0] * 3 + [1.0] * 3
        same_curve_at(as_nurbs, bezier, samples(0, 1))
    with Curve([(2.5, -1.0)]) as point, point.to_nurbs() as raised:
        assert raised.degree == 1 and raised.evaluate(0.3) == (2.5, -1.0)
    with rational.copy() as twin, copy.deepcopy(rational) as deep, \
            pickle.loads(pickle.dumps(rational)) as restored:
        for other in (twin, deep, restored):
            assert other.is_nurbs and other.is_rational
            assert other.knots == RQ_KNOTS and other.weights == RQ_WEIGHTS
            assert other.points == RQ_POLES
    assert repr(rational).startswith("Curve.nurbs([(0.0, 0.0), (1.0, 2.0)")


# -- conics -------------------------------------------------------------------------


@pytest.mark.parametrize("a0,a1", [(0.0, math.pi / 2), (-1.0, 2.0), (0.3, 0.3 + 2 * math.pi)])
def test_circle_points_are_on_the_circle(a0, a1):
    centre = (1.0, -2.0)
    with Curve.ellipse_arc(centre, (1, 0), (0, 1), 2.0, 2.0, a0, a1) as arc:
        assert arc.is_rational and arc.degree == 2
        assert arc.domain == (a0, a1)
        first, last = arc.domain
        for i in range(201):
            point = arc.evaluate(first + (last - first) * i / 200)
            assert abs(distance(point, centre) - 2.0) <= 1e-14 * 2.0
        assert_close(arc.evaluate(a0), (1 + 2 * math.cos(a0), -2 + 2 * math.sin(a0)), 1e-15)
        assert_close(arc.evaluate(a1), (1 + 2 * math.cos(a1), -2 + 2 * math.sin(a1)), 1e-15)
        assert abs(arc.length() - 2.0 * (a1 - a0)) <= 1e-12 * 2.0 * (a1 - a0)
        # The knots sit at equal angles: there the curve is at that angle.
        for knot in sorted(set(arc.knots)):
            assert_close(arc(knot), (1 + 2 * math.cos(knot), -2 + 2 * math.sin(knot)), 1e-14)


def test_ellipse_in_space():
    s = math.sqrt(0.5)
    with Curve.ellipse_arc((0, 0, 1), (s, s, 0), (0, 0, 1), 3.0, 1.0) as ellipse:
        assert ellipse.dim == 3 and ellipse.domain == (0.0, 2 * math.pi)
        spans = ellipse.bezier_spans()
        assert len(spans) == 4  # quarter turns
        for span in spans:
            span.close()
        for u in samples(0, 2 * math.pi, 50):
            x, y, z = ellipse(u)
            a = (x * s + y * s) / 3.0
            b = (z - 1.0) / 1.0
            assert abs(a * a + b * b - 1.0) <= 1e-14
            assert abs(x - y) <= 1e-14
        assert_close(ellipse(0.0), ellipse(2 * math.pi), 1e-15)


# -- the operations keep the parameters -----------------------------------------------


@pytest.mark.parametrize("t", [1.7, 2.5])
def test_split_keeps_parameters(rational, t):
    left, right = rational.split(t)
    with left, right:
        assert left.is_nurbs and right.is_nurbs
        assert left.domain == (0.0, t) and right.domain == (t, 4.0)
        same_curve_at(left, rational, samples(0.0, t))
        same_curve_at(right, rational, samples(t, 4.0))
        assert_close(left(t), right(t), 1e-14)


@pytest.mark.parametrize("a,b", [(0.3, 3.1), (1.0, 2.5), (0.0, 4.0)])
def test_segment_keeps_parameters(rational, a, b):
    with rational.segment(a, b) as piece:
        assert piece.domain == (a, b)
        same_curve_at(piece, rational, samples(a, b))
        assert_close(piece(a), rational(a), 1e-14)
        assert_close(piece(b), rational(b), 1e-14)


def test_split_and_segment_of_an_unclamped_curve(unclamped):
    left, right = unclamped.split(4.2)
    with left, right, unclamped.segment(3.0, 5.5) as piece:
        assert left.domain == (3.0, 4.2) and right.domain == (4.2, 6.0)
        assert piece.domain == (3.0, 5.5)
        same_curve_at(left, unclamped, samples(3.0, 4.2))
        same_curve_at(right, unclamped, samples(4.2, 6.0))
        same_curve_at(piece, unclamped, samples(3.0, 5.5))
        # A split piece is clamped at the cut, a segment at both ends: there
        # the end pole is the curve's point.
        assert_close(left.points[-1], unclamped(4.2), 1e-13)
        assert_close(right.points[0], unclamped(4.2), 1e-13)
        assert_close(piece.points[0], unclamped(3.0), 1e-13)
        assert_close(piece.points[-1], unclamped(5.5), 1e-13)


def test_reverse_on_the_same_domain(unclamped):
    with unclamped.reverse() as backwards:
        assert backwards.domain == (3.0, 6.0)
        for u in samples(3.0, 6.0):
            value, speed = backwards.derivatives(u, 1)
            assert_close(value, unclamped(9.0 - u), 1e-13)
            assert_close(speed, tuple(-x for x in unclamped.derivatives(9.0 - u, 1)[1]), 1e-11)


def test_elevate_keeps_the_curve(rational):
    with rational.elevate(4) as raised:
        assert raised.degree == 4 and raised.is_rational and raised.domain == (0.0, 4.0)
        same_curve_at(raised, rational, samples(0.0, 4.0), 1e-11)


def test_length_is_additive(rational):
    whole = rational.length()
    assert whole == rational.length(0.0, 4.0)
    assert abs(rational.length(0.0, 1.7) + rational.length(1.7) - whole) <= 1e-12 * whole
    assert rational.length(4.0, 0.0) == -whole


def test_bezier_spans_equal_the_curve(rational, unclamped):
    for curve, breaks, bezier_kinds in ((rational, RQ_BREAKS, [True, False, False]),
                                        (unclamped, [3.0, 4.0, 5.0, 6.0], [True] * 3)):
        spans = curve.bezier_spans()
        try:
            assert [not s.is_nurbs for s in spans] == bezier_kinds
            for span, a, b in zip(spans, breaks, breaks[1:]):
                if span.is_nurbs:
                    assert span.domain == (a, b)
                    same_curve_at(span, curve, samples(a, b))
                else:
                    assert span.domain == (0.0, 1.0)
                    for s in samples(0.0, 1.0):
                        value, speed = span.derivatives(s, 1)
                        u = a + (b - a) * s
                        assert_close(value, curve(u), 1e-12)
                        assert_close(tuple(x / (b - a) for x in speed),
                                     curve.derivatives(u, 1)[1], 1e-10)
        finally:
            for span in spans:
                span.close()
    with Curve([(0, 0), (1, 2), (3, 0)]) as bezier:
        (only,) = bezier.bezier_spans()
        with only:
            assert not only.is_nurbs and only.points == bezier.points


# -- connect ------------------------------------------------------------------------


def test_connect_circle_to_bspline_above_the_degrees():
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1.0, 1.0, 0.0, 1.5 * math.pi) as arc, \
            Curve.nurbs([(8, 0), (9, 1), (10, 3), (11, 2), (12, 0), (13, 1)],
                        [0, 0, 0, 0, 0.5, 0.5, 1, 1, 1, 1], 3) as q:
        u0 = arc.knots[3]  # pi / 2, a knot: P's jet from the left
        left, right = arc.split(u0)
        with left, right, bezjoin.connect(arc, u0, q, 0.5, p_order=4, q_order=5,
                                                   auto_scale=False) as r:
            assert not r.is_nurbs and r.degree == 10
            p_jet = left.derivatives(u0, 4)
            assert norm([a - b for a, b in zip(p_jet[2], arc.derivatives(u0, 2)[2])]) > 1e-3
            for got, want in zip(r.derivatives(0.0, 4), p_jet):
                assert_close(got, want, 1e-8)
            for got, want in zip(r.derivatives(1.0, 5), q.derivatives(0.5, 5)):
                assert_close(got, want, 1e-8)
        with bezjoin.connect_auto_scale(arc, 1.5 * math.pi, q, 0.0, p_order=2,
                                        q_order=2) as result:
            assert result.scale > 0 and not result.curve.is_nurbs


# -- errors name their argument --------------------------------------------------------


def expect_error(status_name, call, *words):
    with pytest.raises(BezjoinError) as caught:
        call()
    assert caught.value.status_name == status_name, caught.value
    for word in words:
        assert word in caught.value.message, caught.value.message
    return caught.value


def test_construction_errors():
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS, 0),
                 "degree")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS[:-1], 2),
                 "knots")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, RQ_WEIGHTS[:-1]), "weights")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, [1, 1, 0, 1, 1]), "weights[2]")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, []),
                 "weights")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: Curve.nurbs(RQ_POLES, RQ_KNOTS, 2, [1, math.nan, 1, 1, 1]), "weights[1]")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: Curve.nurbs(RQ_POLES, [0, 0, 0, math.inf, 2.5, 4, 4, 4], 2), "knots[3]")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.nurbs(RQ_POLES, [0, 0, 0, 3, 2.5, 4, 4, 4], 2), "knots",
                 "decrease")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.nurbs(RQ_POLES, [0, 0, 0, 1, 1, 1, 4, 4], 2), "knots",
                 "multiplicity")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve.nurbs(RQ_POLES[:2], RQ_KNOTS, 2),
                 "poles")
    with pytest.raises(TypeError):
        Curve.nurbs(RQ_POLES, RQ_KNOTS, 2.5)


def test_ellipse_errors():
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0,), (1,), (1,), 1, 1), "dim")
    expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0, 0), (0, 1), 1, 1), "x_axis")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0, 0), (2, 0), (0, 1), 1, 1), "x_axis", "unit")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0), (0.6, 0.8), 1, 1), "orthogonal")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 0.0, 1), "x_radius")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1, math.nan), "y_radius")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1, 1, 1.0, 1.0), "a1")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1, 1, 0.0, 7.0), "a1")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: Curve.ellipse_arc((0, math.nan), (1, 0), (0, 1), 1, 1), "centre[1]")


def test_parameter_errors(rational):
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.evaluate(4.5), "t = 4.5", "[0, 4]")
    expect_error("BZJ_ERR_NON_FINITE", lambda: rational.evaluate(math.nan), "t")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: rational.derivatives_many([0.5, 1.0, -1.0], 1), "ts[2] = -1")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.split(0.0), "t = 0", "(0, 4)")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.split(4.0), "t = 4")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.segment(2.0, 2.0), "b")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.segment(-1.0, 2.0), "a = -1")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.length(0.0, 5.0), "b = 5")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.elevate(1), "new_degree")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: rational.elevate(10**6), "new_degree")
    with Curve([(0, 0), (1, 1)]) as line:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.connect(rational, 4.5, line, 0.0),
                     "u0 = 4.5")


def test_intersect_and_fillet_take_nurbs():
    with Curve.ellipse_arc((1, 2), (1, 0), (0, 1), 3.0, 3.0, 0.0, 2 * math.pi) as circle, \
            Curve([(-5, 2.5), (7, 2.5)]) as line:
        hits = bezjoin.intersect(line, circle)
        assert len(hits) == 2
        for (u, v), x in zip(hits, (1 - math.sqrt(8.75), 1 + math.sqrt(8.75))):
            assert_close(line.evaluate(u), (x, 2.5), 1e-12)
            assert_close(circle.evaluate(v), (x, 2.5), 1e-12)
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1.0, 1.0, -2.5, 1.2) as a, \
            Curve.ellipse_arc((1.2, 0), (1, 0), (0, 1), 1.0, 1.0, 1.5, 4.5) as b:
        with bezjoin.fillet(a, b, setback=0.15, p_order=3, q_order=3, p_scale=1.0,
                            q_scale=1.0) as f:
            assert f.p_trimmed.is_nurbs and f.q_trimmed.is_nurbs and not f.blend.is_nurbs
            first, u0 = f.p_trimmed.domain
            v0, last = f.q_trimmed.domain
            assert first == -2.5 and last == 4.5
            for got, want in zip(f.blend.derivatives(0.0, 3), a.derivatives(u0, 3)):
                assert_close(got, want, 1e-8)
            for got, want in zip(f.blend.derivatives(1.0, 3), b.derivatives(v0, 3)):
                assert_close(got, want, 1e-8)


def test_fillet_deviation_takes_nurbs():
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1.0, 1.0, -2.5, 1.2) as a, \
            Curve.ellipse_arc((1.2, 0), (1, 0), (0, 1), 1.0, 1.0, 1.5, 4.5) as b:
        with bezjoin.fillet_deviation(a, b, 0.02, p_order=2, q_order=2) as r:
            assert 0.02 * (1 - 1e-9) <= r.deviation <= 0.02
            assert r.p_trimmed.is_nurbs and r.q_trimmed.is_nurbs


def test_fillet_vertex_rounds_the_wire_corner():
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1.0, 1.0, 0.0, math.pi / 2) as arc, \
            Curve([(0, 1 + 3e-8), (0, -2)]) as down:
        with bezjoin.fillet_vertex(arc, down, setback=0.2, p_order=2, q_order=2,
                                   auto_scale=False, gap=1e-7) as f:
            _, u0 = f.p_trimmed.domain
            assert_close([arc.length(u0, math.pi / 2)], [0.2], 1e-10)
            for got, want in zip(f.blend.derivatives(0.0, 2), arc.derivatives(u0, 2)):
                assert_close(got, want, 1e-8)
            # the line's second derivative is 0, and so is the blend's there
            assert norm(f.blend.derivatives(1.0, 2)[2]) < 1e-8
        expect_error("BZJ_ERR_NO_INTERSECTION",
                     lambda: bezjoin.fillet_vertex(arc, down, setback=0.2, gap=1e-9), "gap")


def test_merge_of_bsplines(rational):
    """A B-spline cut at a parameter that is not a knot and merged back at the
    cut's own mu is the original (knots mapped to [0, 1], none at the join);
    two unrelated B-splines merge into one NURBS whose pieces keep their knots;
    a rational curve is refused by name."""
    poles = [(0.0, 0.0), (1.0, 2.0), (2.5, 2.5), (4.0, 0.5), (5.0, 1.5), (6.5, 0.0)]
    knots = [2.0] * 4 + [3.0, 4.5] + [6.0] * 4
    with Curve.nurbs(poles, knots, 3) as whole:
        t = 3.7
        left, right = whole.split(t)
        with left, right:
            mu = (t - 2.0) / 4.0
            with bezjoin.merge(left, right, mu=mu, metric="l2") as m:
                assert m.merged.is_nurbs and m.p_hat.is_nurbs and m.q_hat.is_nurbs
                assert m.max_deviation <= 1e-12
                assert_close(m.merged.knots, [(k - 2.0) / 4.0 for k in knots], 1e-15)
                for u in samples(0.0, 1.0):
                    assert_close(m.merged.derivatives(u, 0)[0],
                                 de_boor(poles, knots, 3, 2.0 + 4.0 * u), 1e-12)
                assert m.p_hat.knots == left.knots and m.q_hat.knots == right.knots
        with Curve.nurbs(RQ_POLES, RQ_KNOTS, 2) as quadratic, \
                bezjoin.merge(whole, quadratic, mu="optimal", fix_ends=True) as m:
            assert m.merged.degree == 3
            inner = m.merged.knots[4:-4]
            assert all(abs(k - m.mu) > 1e-9 for k in inner)
            assert_close(m.merged.derivatives(0.0, 0)[0], poles[0], 1e-12)
            assert_close(m.merged.derivatives(1.0, 0)[0], RQ_POLES[-1], 1e-12)
        with Curve([(6.5, 0.0), (7, 1), (8, 1), (9, 0)]) as bezier:
            expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(rational, bezier),
                         "p: the curve is rational")
            with bezjoin.merge_chain([whole, bezier, whole]) as chain:
                assert chain.merged.is_nurbs and all(c.is_nurbs for c in chain.pieces)
                assert chain.pieces[0].knots == whole.knots


def test_sizes_beyond_size_t_or_memory_are_errors_naming_the_argument():
    """A size ctypes would wrap around (2**64 becomes 0) or Python cannot allocate is a
    BezjoinError naming the argument, not another argument's complaint, an
    OverflowError or a MemoryError."""
    arc = Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 5, 5, 0, 2)
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: Curve.nurbs([(0, 0), (1, 0)], [0, 0, 1, 1], 2 ** 64),
                 "degree = 18446744073709551616", "largest size_t")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: arc.derivatives(1.0, 2 ** 64),
                 "max_order = 18446744073709551616")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: arc.derivatives(1.0, 2 ** 62),
                 "max_order", "more than can be allocated")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: arc.derivatives_many([0.5, 1.0], 2 ** 62),
                 "max_order", "more than can be allocated")


def test_a_rational_curve_refuses_an_overflowing_order_without_quadratic_work():
    """Orders far above the degree on a rational curve: the quotient rule's terms above
    the degree are zero and skipped, so order 10**6 fails by name (the first order
    that overflows) after linear work; it used to take minutes."""
    arc = Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 5, 5, 0, 2)
    expect_error("BZJ_ERR_NON_FINITE", lambda: arc.derivatives(1.0, 10 ** 6),
                 "derivative of order")
