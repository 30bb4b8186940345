"""connect: the end conditions (1') judged by the independent evaluator, the degree
of Theorems 1 and 2, interior constraints, and every error path."""

import math
import random

import pytest

import bezjoin
from bezjoin import Curve
from reference import derivative, distance, norm
from test_curve import expect_error, random_points


def relative_gap(actual, expected):
    return distance(actual, expected) / max(1.0, norm(expected))


@pytest.mark.parametrize("p_degree,q_degree,p_order,q_order,dim", [
    (3, 3, 3, 3, 2), (3, 3, 1, 2, 3), (5, 2, 2, 1, 2), (1, 1, 1, 1, 2), (4, 4, 0, 0, 3)])
def test_end_derivatives_are_the_scaled_curve_derivatives(p_degree, q_degree, p_order, q_order,
                                                         dim):
    rng = random.Random(p_degree * 31 + q_degree * 7 + p_order + dim)
    p_points = random_points(rng, p_degree, dim, 3.0)
    q_points = random_points(rng, q_degree, dim, 3.0)
    for u0, v0, alpha, beta in ((1.0, 0.0, 1.0, 1.0), (0.6, 0.3, 1.5, 0.7)):
        with Curve(p_points) as p, Curve(q_points) as q, \
                bezjoin.connect(p, u0, q, v0, p_order=p_order, q_order=q_order,
                                p_scale=alpha, q_scale=beta) as r:
            assert r.degree == p_order + q_order + 1
            assert r.dim == dim
            points = r.points
            for k in range(p_order + 1):
                expected = tuple(alpha ** k * x for x in derivative(p_points, u0, k))
                assert relative_gap(derivative(points, 0.0, k), expected) < 1e-10
            for k in range(q_order + 1):
                expected = tuple(beta ** k * x for x in derivative(q_points, v0, k))
                assert relative_gap(derivative(points, 1.0, k), expected) < 1e-10


def test_default_orders_are_the_degrees_as_in_the_paper():
    rng = random.Random(5)
    with Curve(random_points(rng, 3, 2)) as p, Curve(random_points(rng, 2, 2)) as q, \
            bezjoin.connect(p, 1.0, q, 0.0) as r:
        assert r.degree == 3 + 2 + 1


def test_interior_constraints_hold_and_raise_the_degree():
    rng = random.Random(9)
    p_points, q_points = random_points(rng, 3, 2, 3.0), random_points(rng, 3, 2, 3.0)
    first = (0.3, [(1.0, 2.0)])
    second = (0.7, [(4.0, -1.0), (2.0, 0.5), (0.0, 1.0)])
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.connect(p, 1.0, q, 0.0, p_order=1, q_order=1, auto_scale=False,
                            constraints=[first, second]) as r:
        assert r.degree == 1 + 1 + 1 + (0 + 1) + (2 + 1)
        for t, rows in (first, second):
            for k, row in enumerate(rows):
                assert relative_gap(derivative(r.points, t, k), row) < 1e-9
        for k in range(2):
            assert relative_gap(derivative(r.points, 0.0, k), derivative(p_points, 1.0, k)) < 1e-10
            assert relative_gap(derivative(r.points, 1.0, k), derivative(q_points, 0.0, k)) < 1e-10


def test_connect_errors():
    with Curve([(0, 0), (1, 1), (2, 0)]) as p, Curve([(3, 0), (4, 1), (5, 0)]) as q, \
            Curve([(0, 0, 0), (1, 1, 1)]) as space:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.connect(p, 1.5, q, 0.0), "u0")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.connect(p, 1.0, q, -0.5), "v0")
        expect_error("BZJ_ERR_NON_FINITE", lambda: bezjoin.connect(p, math.nan, q, 0.0), "u0")
        # An order above the degree is accepted (the contract allows any order).
        with bezjoin.connect(p, 1.0, q, 0.0, p_order=3) as above:
            assert above.degree == 3 + 2 + 1
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, q_order=-1), "q_order = -1")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, p_scale=0.0), "p_scale")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, q_scale=-2.0), "q_scale")
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, q_scale=math.inf), "q_scale")
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.connect(p, 1.0, space, 0.0))
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, constraints=[(1.2, [(0, 0)])]))
        expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, constraints=[(0.5, [(0, 0, 0)])]),
                     "constraints[0]")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, constraints=[(0.5, [])]),
                     "constraints[0] derivatives is empty")
        with pytest.raises(TypeError, match="constraints\\[0\\]"):
            bezjoin.connect(p, 1.0, q, 0.0, constraints=[0.5])
        with pytest.raises(TypeError, match="q must be a bezjoin.Curve"):
            bezjoin.connect(p, 1.0, [(0, 0)], 0.0)
    with pytest.raises(ValueError, match="closed Curve"):
        bezjoin.connect(p, 1.0, q, 0.0)


def bending_energy(points):
    """integral_0^1 |R''(t)|^2 dt by 20-point Gauss-Legendre (exact for these degrees)."""
    from test_merge import gauss_legendre

    nodes, weights = gauss_legendre(20)
    return sum(w * norm(derivative(points, x, 2)) ** 2 for x, w in zip(nodes, weights))


@pytest.mark.parametrize("seed,order", [(53, 2), (59, 1), (61, 3)])
def test_auto_scale_is_connect_at_the_best_scale_of_its_bracket(seed, order):
    rng = random.Random(seed)
    p_points, q_points = random_points(rng, 3, 2, 3.0), random_points(rng, 3, 2, 3.0)
    u0, v0 = 0.9, 0.1
    speed = (norm(derivative(p_points, u0, 1)) + norm(derivative(q_points, v0, 1))) / 2
    start = distance(derivative(q_points, v0, 0), derivative(p_points, u0, 0)) / speed
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.connect_auto_scale(p, u0, q, v0, p_order=order, q_order=order) as result:
        s = result.scale
        assert start / 100 * (1 - 1e-9) <= s <= start * 100 * (1 + 1e-9)
        assert repr(result).startswith("AutoScaledConnection(curve=Curve([")
        chosen = result.curve.points
        with bezjoin.connect(p, u0, q, v0, p_order=order, q_order=order, p_scale=s,
                             q_scale=s) as same:
            assert max(distance(a, b) for a, b in zip(chosen, same.points)) <= 1e-9
        best = bending_energy(chosen)
        energies = []
        for i in range(41):  # log-spaced over the two decades either side of start
            trial = start * 10 ** (-2 + i / 10)
            with bezjoin.connect(p, u0, q, v0, p_order=order, q_order=order, p_scale=trial,
                                 q_scale=trial) as other:
                energies.append((bending_energy(other.points), trial))
        if min(energies)[1] == energies[0][1]:
            # Least at the range's lower end (ends facing away: the blend turns
            # in kinks there): the natural scale, or the largest below it whose
            # control polygon is at most two chords (session 44).
            chord = distance(chosen[0], chosen[-1])
            polygon = sum(distance(a, b) for a, b in zip(chosen, chosen[1:]))
            assert s <= start * (1 + 1e-9)
            assert polygon <= 2 * chord * (1 + 1e-9)
        else:
            for energy, trial in energies:
                assert energy >= best * (1 - 1e-6), trial


def test_auto_scale_errors():
    with Curve([(0, 0), (1, 1), (2, 0)]) as p, Curve([(3, 0), (4, 1), (5, 0)]) as q:
        # An order above the degree is accepted (the contract allows any order).
        with bezjoin.connect_auto_scale(p, 1.0, q, 0.0, p_order=3) as above:
            assert above.curve.degree == 3 + 2 + 1
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.connect_auto_scale(p, 1.5, q, 0.0), "u0")
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.connect_auto_scale(p, math.inf, q, 0.0), "u0")
        with pytest.raises(TypeError, match="q must be a bezjoin.Curve"):
            bezjoin.connect_auto_scale(p, 1.0, "q", 0.0)


def test_balanced_connect_does_not_depend_on_the_inputs_parametrisation():
    """P given on [0, 1] (Bezier) and on [0, 50] (the same poles as a NURBS): the balanced
    blend is the same curve, its scales absorb the factor 50 and both its ends run at one
    speed; the one-s automatic scale gives another curve."""
    p_points = [(0, 0, 0), (1, 2, 1), (2, 2, 0), (3, 0, 1)]
    q_points = [(6, 0, 0), (7, -2, 1), (8, -2, 0), (9, 0, 2)]
    knots = [0.0] * 4 + [50.0] * 4
    with Curve(p_points) as p, Curve(q_points) as q, \
            Curve.nurbs(p_points, knots, 3) as slow:
        with bezjoin.connect_balanced_scale(p, 0.8, q, 0.1, p_order=2, q_order=3) as fast, \
                bezjoin.connect_balanced_scale(slow, 40.0, q, 0.1, p_order=2,
                                               q_order=3) as other, \
                bezjoin.connect(slow, 40.0, q, 0.1, p_order=2, q_order=3,
                                auto_scale="balanced") as plain, \
                bezjoin.connect(slow, 40.0, q, 0.1, p_order=2, q_order=3) as automatic, \
                bezjoin.connect(p, 0.8, q, 0.1, p_order=2, q_order=3) as automatic_fast:
            assert math.isclose(other.p_scale, 50 * fast.p_scale, rel_tol=1e-12)
            assert math.isclose(other.q_scale, fast.q_scale, rel_tol=1e-12)
            size = max(norm(x) for x in fast.curve.points)
            for a, b, c in zip(other.curve.points, fast.curve.points, plain.points):
                assert distance(a, b) <= 1e-12 * size
                assert distance(c, b) <= 1e-12 * size
            start = norm(fast.curve.derivatives(0.0, 1)[1])
            end = norm(fast.curve.derivatives(1.0, 1)[1])
            assert math.isclose(start, end, rel_tol=1e-12)
            moved = max(distance(a, b)
                        for a, b in zip(automatic.points, automatic_fast.points))
            assert moved > 1e-3 * size
