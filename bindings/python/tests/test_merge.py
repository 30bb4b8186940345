"""merge: R split at mu gives P^ and Q^, the report is what it says (metric recomputed
independently, deviation resampled), the optimum beats random feasible perturbations,
constraints hold, and every error path."""

import math
import random

import pytest

import bezjoin
from bezjoin import Curve
from reference import de_casteljau, derivative, distance
from test_curve import expect_error, random_points

GAUSS_NODES = 40


def gauss_legendre(count):
    """Nodes and weights on [0, 1] (Newton on the Legendre polynomial)."""
    nodes, weights = [], []
    for i in range(1, count + 1):
        x = math.cos(math.pi * (i - 0.25) / (count + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, count + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            derivative_value = count * (x * p1 - p0) / (x * x - 1)
            step = p1 / derivative_value
            x -= step
            if abs(step) < 1e-16:
                break
        nodes.append((x + 1) / 2)
        weights.append(1.0 / ((1 - x * x) * derivative_value ** 2))
    return nodes, weights


NODES, WEIGHTS = gauss_legendre(GAUSS_NODES)


def discrete_metric(p_hat, p, q_hat, q):
    return sum(distance(a, b) ** 2 for a, b in zip(p_hat, p)) + sum(
        distance(a, b) ** 2 for a, b in zip(q_hat, q))


def integral_metric(p_hat, p, q_hat, q):
    total = 0.0
    for changed, original in ((p_hat, p), (q_hat, q)):
        total += sum(w * distance(de_casteljau(changed, x), de_casteljau(original, x)) ** 2
                     for x, w in zip(NODES, WEIGHTS))
    return total


METRIC_FUNCTIONS = {"discrete": discrete_metric, "l2": integral_metric}


def pieces_of(r_points, mu):
    with Curve(r_points) as r, r.segment(0.0, mu) as left, r.segment(mu, 1.0) as right:
        return left.points, right.points


def close_points(a, b, relative):
    # zip would stop at the shorter list: the pole counts must agree first.
    assert len(a) == len(b), f"{len(a)} poles against {len(b)}"
    assert a, "no poles"
    scale = max([1.0] + [math.sqrt(sum(x * x for x in p)) for p in b])
    return max(distance(x, y) for x, y in zip(a, b)) <= relative * scale


@pytest.mark.parametrize("metric", ["discrete", "l2"])
@pytest.mark.parametrize("mu", ["half", 0.3, 0.7])
def test_merged_curve_split_at_mu_is_p_hat_and_q_hat(metric, mu):
    rng = random.Random(17)
    p_points = random_points(rng, 4, 2, 3.0)
    q_points = random_points(rng, 4, 2, 3.0)
    q_points[0] = p_points[-1]
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.merge(p, q, metric=metric, mu=mu) as result:
        expected_mu = 0.5 if mu == "half" else mu
        assert result.mu == expected_mu
        assert result.merged.degree == 4
        left, right = pieces_of(result.merged.points, result.mu)
        assert close_points(result.p_hat.points, left, 1e-11)
        assert close_points(result.q_hat.points, right, 1e-11)
        recomputed = METRIC_FUNCTIONS[metric](result.p_hat.points, p_points,
                                              result.q_hat.points, q_points)
        assert abs(result.metric_value - recomputed) <= 1e-9 * max(1.0, recomputed)


@pytest.mark.parametrize("metric", ["discrete", "l2"])
def test_optimum_beats_random_feasible_perturbations(metric):
    rng = random.Random(23)
    p_points = random_points(rng, 3, 2, 3.0)
    q_points = random_points(rng, 3, 2, 3.0)
    function = METRIC_FUNCTIONS[metric]
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.merge(p, q, metric=metric, mu=0.4) as result:
        best = result.metric_value
        r_points = result.merged.points
    for _ in range(30):
        size = rng.choice((1e-3, 1e-1))
        moved = [tuple(x + rng.uniform(-size, size) for x in point) for point in r_points]
        left, right = pieces_of(moved, 0.4)
        assert function(left, p_points, right, q_points) >= best * (1 - 1e-12)


def test_degrees_are_made_equal_by_elevation():
    rng = random.Random(29)
    with Curve(random_points(rng, 2, 3)) as p, Curve(random_points(rng, 4, 3)) as q, \
            bezjoin.merge(p, q) as result:
        assert result.merged.degree == result.p_hat.degree == result.q_hat.degree == 4


def test_split_modes():
    rng = random.Random(31)
    p_points = random_points(rng, 3, 2, 3.0)
    q_points = random_points(rng, 3, 2, 1.0)
    polygon = [sum(distance(a[i], a[i + 1]) for i in range(len(a) - 1))
               for a in (p_points, q_points)]
    with Curve(p_points) as p, Curve(q_points) as q:
        with bezjoin.merge(p, q, mu="polygon") as result:
            assert abs(result.mu - polygon[0] / sum(polygon)) <= 1e-12
        values = {}
        for mode in ("half", "polygon", 0.2, 0.8, "optimal"):
            with bezjoin.merge(p, q, mu=mode) as result:
                values[mode] = (result.mu, result.metric_value)
        optimal_mu, optimal_value = values["optimal"]
        assert 0.0 < optimal_mu < 1.0
        for mode, (_mu, value) in values.items():
            assert optimal_value <= value * (1 + 1e-9), mode


def test_report_deviation_is_the_distance_to_p_then_q():
    rng = random.Random(37)
    p_points = random_points(rng, 3, 2, 3.0)
    q_points = random_points(rng, 3, 2, 3.0)
    with Curve(p_points) as p, Curve(q_points) as q, bezjoin.merge(p, q, mu=0.4) as result:
        r_points, mu, reported = result.merged.points, result.mu, result.max_deviation
    # R(mu u) against P(u) and R(mu + (1 - mu) v) against Q(v), both ends included
    sampled = 0.0
    for i in range(2001):
        s = i / 2000
        sampled = max(sampled,
                      distance(de_casteljau(r_points, mu * s), de_casteljau(p_points, s)),
                      distance(de_casteljau(r_points, mu + (1 - mu) * s),
                               de_casteljau(q_points, s)))
    assert sampled > 0.0
    assert abs(reported - sampled) <= 1e-3 * sampled


def test_constraints_hold():
    rng = random.Random(41)
    p_points = random_points(rng, 5, 2, 3.0)
    q_points = random_points(rng, 5, 2, 3.0)
    with Curve(p_points) as p, Curve(q_points) as q:
        with bezjoin.merge(p, q, fix_ends=True) as result:
            assert result.p_hat.points[0] == pytest.approx(p_points[0], abs=1e-12)
            assert result.q_hat.points[-1] == pytest.approx(q_points[-1], abs=1e-12)
        with bezjoin.merge(p, q, keep_p=True) as result:
            assert close_points(result.p_hat.points, p_points, 1e-12)
        with bezjoin.merge(p, q, keep_q=True) as result:
            assert close_points(result.q_hat.points, q_points, 1e-12)
        with bezjoin.merge(p, q, p_points=[(0.25, 1)], q_points=[(0.5, 0), (1.0, 0)]) as result:
            for k in range(2):
                assert distance(derivative(result.p_hat.points, 0.25, k),
                                derivative(p_points, 0.25, k)) <= 1e-10 * 100
            for v in (0.5, 1.0):
                assert distance(de_casteljau(result.q_hat.points, v),
                                de_casteljau(q_points, v)) <= 1e-10


def test_merge_errors():
    rng = random.Random(43)
    with Curve(random_points(rng, 3, 2)) as p, Curve(random_points(rng, 3, 2)) as q, \
            Curve(random_points(rng, 3, 3)) as space:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, metric="l1"),
                     "metric = 'l1'")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, mu="given"), "mu")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, mu="third"), "mu")
        for bad in (0.0, 1.0, 1.5, -0.2):
            expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.merge(p, q, mu=bad), "mu")
        expect_error("BZJ_ERR_NON_FINITE", lambda: bezjoin.merge(p, q, mu=math.nan), "mu")
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.merge(p, space))
        expect_error("BZJ_ERR_INCONSISTENT", lambda: bezjoin.merge(p, q, keep_p=True,
                                                                   keep_q=True))
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge(p, q, p_points=[(1.5, 0)]), "p_points")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.merge(p, q, q_points=[(0.5, -1)]), "q_points[0] max_order")
        with pytest.raises(TypeError, match="p_points\\[0\\]"):
            bezjoin.merge(p, q, p_points=[0.5])
        with pytest.raises(TypeError, match="mu must be a real number"):
            bezjoin.merge(p, q, mu=[0.5])


def test_result_releases_its_three_curves(monkeypatch):
    from test_curve import FreeCounter, address

    counter = FreeCounter(monkeypatch)
    rng = random.Random(47)
    with Curve(random_points(rng, 3, 2)) as p, Curve(random_points(rng, 3, 2)) as q:
        result = bezjoin.merge(p, q)
        curves = result.curves()
        assert [c is getattr(result, n) for c, n in zip(curves, ("merged", "p_hat", "q_hat"))] \
            == [True, True, True]
        where = sorted(address(c) for c in curves)
        text = repr(result)
        assert text.startswith("MergeResult(merged=Curve([") and "mu=0.5" in text
        with result:
            pass
        assert all(c.closed for c in curves)
        result.close()
        assert sorted(counter.released) == where
