"""merge(degree=...) (bzj_merge_to_degree) and merge_chain: the merged curve has the
degree asked for, its pieces between the breakpoints are the changed curves, the
constraints hold, the report is what it says (metric recomputed independently,
deviation resampled), and the error paths."""

import math
import random

import pytest

import bezjoin
from bezjoin import Curve
from reference import de_casteljau, derivative, distance
from test_curve import expect_error, random_points
from test_merge import METRIC_FUNCTIONS, close_points


def segment_points(points, a, b):
    with Curve(points) as c, c.segment(a, b) as piece:
        return piece.points


def elevated_points(points, degree):
    with Curve(points) as c, c.elevate(degree) as e:
        return e.points


def sampled_deviation(pieces, originals, samples=257):
    return max(distance(de_casteljau(piece, i / (samples - 1)),
                        de_casteljau(original, i / (samples - 1)))
               for piece, original in zip(pieces, originals) for i in range(samples))


@pytest.mark.parametrize("metric", ["discrete", "l2"])
@pytest.mark.parametrize("degree", [3, 5, 7])
def test_merge_to_degree_gives_that_degree_and_split_pieces(metric, degree):
    rng = random.Random(23)
    p_points = random_points(rng, 3, 2, 3.0)
    q_points = random_points(rng, 3, 2, 3.0)
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.merge(p, q, metric=metric, mu=0.4, degree=degree) as result, \
            bezjoin.merge(p, q, metric=metric, mu=0.4) as plain:
        assert result.merged.degree == degree
        assert result.mu == 0.4
        r_points = result.merged.points
        assert close_points(result.p_hat.points, segment_points(r_points, 0.0, 0.4), 1e-12)
        assert close_points(result.q_hat.points, segment_points(r_points, 0.4, 1.0), 1e-12)
        # The metric compares the changed curves with the inputs elevated to `degree`.
        metric_value = METRIC_FUNCTIONS[metric](
            result.p_hat.points, elevated_points(p_points, degree),
            result.q_hat.points, elevated_points(q_points, degree))
        assert abs(metric_value - result.metric_value) <= 1e-9 * max(1.0, metric_value)
        # More freedom: no larger change than the merge at the curves' own degree.
        assert result.metric_value <= plain.metric_value * (1 + 1e-12)
        if degree == 3:
            assert close_points(r_points, plain.merged.points, 1e-12)


def test_merge_to_degree_keeps_points_up_to_that_degree():
    rng = random.Random(5)
    with Curve(random_points(rng, 3, 2, 2.0)) as p, Curve(random_points(rng, 3, 2, 2.0)) as q, \
            bezjoin.merge(p, q, degree=6, p_points=[(0.3, 4)]) as result:
        kept = [derivative(result.p_hat.points, 0.3, k) for k in range(5)]
        original = [derivative(p.points, 0.3, k) for k in range(5)]
        for a, b in zip(kept, original):
            assert distance(a, b) <= 1e-8 * max(1.0, math.sqrt(sum(x * x for x in b)))


def test_merge_to_degree_errors():
    with Curve([(0, 0), (1, 1), (2, 1), (3, 0)]) as p, \
            Curve([(3, 0), (4, -1), (5, -1), (6, 0.5)]) as q:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, degree=2), "degree")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, degree=-1),
                     "degree = -1 is negative")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, degree=5, mu=0.0),
                     "mu")
        with pytest.raises(TypeError, match="degree must be an integer"):
            bezjoin.merge(p, q, degree=4.0)


ORIGINAL = [(0.0, 0.0), (1.0, 2.0), (3.0, 2.5), (4.0, 0.0)]


def test_pieces_of_one_curve_merge_back_into_it():
    cuts = [0.0, 0.2, 0.7, 1.0]
    parts = [segment_points(ORIGINAL, cuts[j], cuts[j + 1]) for j in range(3)]
    curves = [Curve(points) for points in parts]
    try:
        with bezjoin.merge_chain(curves, metric="l2", breakpoints=[0.2, 0.7]) as result:
            assert isinstance(result, bezjoin.ChainMergeResult)
            assert result.breakpoints == cuts
            assert close_points(result.merged.points, ORIGINAL, 1e-9)
            for piece, part in zip(result.pieces, parts):
                assert close_points(piece.points, part, 1e-9)
            assert result.metric_value <= 1e-15
            assert result.max_deviation <= 1e-9
    finally:
        for c in curves:
            c.close()


@pytest.mark.parametrize("metric", ["discrete", "l2"])
@pytest.mark.parametrize("breakpoints", ["uniform", "polygon", [0.3, 0.45, 0.8]])
def test_chain_pieces_are_the_merged_curve_between_the_breakpoints(metric, breakpoints):
    rng = random.Random(41)
    originals = [random_points(rng, 3, 2, 3.0) for _ in range(3)] + [random_points(rng, 2, 2, 3.0)]
    curves = [Curve(points) for points in originals]
    try:
        with bezjoin.merge_chain(curves, metric=metric, breakpoints=breakpoints) as result:
            t = result.breakpoints
            assert len(t) == 5 and t[0] == 0.0 and t[-1] == 1.0
            assert all(a < b for a, b in zip(t, t[1:]))
            if breakpoints == "uniform":
                assert t == pytest.approx([0, 0.25, 0.5, 0.75, 1], abs=1e-15)
            elif breakpoints == "polygon":
                lengths = [sum(distance(a, b) for a, b in zip(c, c[1:])) for c in originals]
                total = sum(lengths)
                assert t == pytest.approx([sum(lengths[:j]) / total for j in range(5)],
                                          abs=1e-12)
            else:
                assert t[1:4] == breakpoints
            assert result.merged.degree == 3  # the highest degree
            r_points = result.merged.points
            pieces = [piece.points for piece in result.pieces]
            for j, piece in enumerate(pieces):
                assert close_points(piece, segment_points(r_points, t[j], t[j + 1]), 1e-12)
            # The report: the metric summed over the pieces (inputs at the merged
            # degree) and the largest distance of piece j from curve j.
            elevated = [elevated_points(points, 3) for points in originals]
            metric_value = sum(
                METRIC_FUNCTIONS[metric](pieces[j], elevated[j], pieces[j + 1], elevated[j + 1])
                for j in (0, 2))
            assert abs(metric_value - result.metric_value) <= 1e-9 * max(1.0, metric_value)
            deviation = sampled_deviation(pieces, elevated)
            assert abs(deviation - result.max_deviation) <= 1e-9 * max(1.0, deviation)
    finally:
        for c in curves:
            c.close()


def test_chain_constraints_hold():
    rng = random.Random(7)
    originals = [random_points(rng, 3, 2, 2.0) for _ in range(3)]
    curves = [Curve(points) for points in originals]
    try:
        # The ends fixed, and curve 2 keeps its point and tangent at 0.5.
        with bezjoin.merge_chain(curves, degree=6, fix_ends=True,
                                 keep_points=[(2, 0.5, 1)]) as result:
            assert result.merged.degree == 6
            pieces = [piece.points for piece in result.pieces]
            assert distance(pieces[0][0], originals[0][0]) <= 1e-9
            assert distance(pieces[2][-1], originals[2][-1]) <= 1e-9
            for k in range(2):
                assert distance(derivative(pieces[2], 0.5, k),
                                derivative(originals[2], 0.5, k)) <= 1e-8
            t = result.breakpoints
            for j, piece in enumerate(pieces):
                assert close_points(piece, segment_points(result.merged.points, t[j], t[j + 1]),
                                    1e-12)
        # Curve 1 kept unchanged: the merged curve is its polynomial extension.
        with bezjoin.merge_chain(curves, keep=[False, True, False]) as result:
            t = result.breakpoints
            assert close_points(result.pieces[1].points, originals[1], 1e-9)
            extension = segment_points(originals[1], -t[1] / (t[2] - t[1]),
                                       (1 - t[1]) / (t[2] - t[1]))
            assert close_points(result.merged.points, extension, 1e-9)
    finally:
        for c in curves:
            c.close()


def test_merge_chain_of_two_is_merge():
    rng = random.Random(3)
    with Curve(random_points(rng, 3, 2, 2.0)) as p, Curve(random_points(rng, 3, 2, 2.0)) as q, \
            bezjoin.merge_chain([p, q], metric="l2", breakpoints=[0.4]) as chain, \
            bezjoin.merge(p, q, metric="l2", mu=0.4) as pair:
        assert close_points(chain.merged.points, pair.merged.points, 1e-12)
        assert abs(chain.metric_value - pair.metric_value) <= 1e-12 * max(1.0, pair.metric_value)


def test_merge_chain_errors():
    with Curve([(0, 0), (1, 1), (2, 1), (3, 0)]) as a, \
            Curve([(3, 0), (4, -1), (5, -1), (6, 0.5)]) as b, \
            Curve([(0, 0, 0), (1, 1, 1)]) as space:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge_chain([a]))
        error = expect_error("BZJ_ERR_INVALID_ARGUMENT",
                             lambda: bezjoin.merge_chain([a, b, a], breakpoints=[0.6, 0.4]),
                             "breakpoints[1]")
        assert "0.4" in error.message
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge_chain([a, b, a], breakpoints=[0.5]))
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.merge_chain([a, b, a], breakpoints=[0.3, math.nan]))
        expect_error("BZJ_ERR_INCONSISTENT",
                     lambda: bezjoin.merge_chain([a, b], keep=[True, True]))
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge_chain([a, b], keep=[True]), "keep has 1 flags")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge_chain([a, b], keep_points=[(5, 0.5, 0)]))
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge_chain([a, b], degree=2), "degree")
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.merge_chain([a, space]))
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge_chain([a, b], metric="x"),
                     "metric")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge_chain([a, b], breakpoints="given"), "breakpoints")
        with pytest.raises(TypeError, match="keep_points\\[0\\] must be a"):
            bezjoin.merge_chain([a, b], keep_points=[(0, 0.5)])
        with pytest.raises(TypeError, match="curves\\[1\\] must be a bezjoin.Curve"):
            bezjoin.merge_chain([a, "b"])
