"""connect_points / connect_points_auto_scale (``bzj_connect_points``): the blend's
control points without Curve objects, bit for bit those of connect on Curve
objects (the same curves, the same solve), its end conditions judged by the
independent evaluator, and the errors (the library's, naming the argument)."""

import random

import pytest

import bezjoin
from bezjoin import Curve
from reference import derivative, distance, norm
from test_curve import random_points


def through_curves(p_points, u0, q_points, v0, **options):
    with Curve(p_points) as p, Curve(q_points) as q, \
            bezjoin.connect(p, u0, q, v0, **options) as r:
        return r.points


@pytest.mark.parametrize("p_degree,q_degree,p_order,q_order,dim", [
    (3, 3, 3, 3, 3), (3, 2, 1, 2, 2), (5, 1, 2, 1, 3), (1, 1, 1, 1, 1)])
def test_the_points_of_connect_bit_for_bit(p_degree, q_degree, p_order, q_order, dim):
    rng = random.Random(1000 + 17 * p_degree + 5 * q_degree + p_order + dim)
    for _ in range(5):
        p_points = random_points(rng, p_degree, dim, 3.0)
        q_points = random_points(rng, q_degree, dim, 3.0)
        u0, v0 = rng.uniform(0.2, 1.0), rng.uniform(0.0, 0.8)
        alpha, beta = rng.uniform(0.3, 2.0), rng.uniform(0.3, 2.0)
        given = bezjoin.connect_points(p_points, u0, q_points, v0, p_order=p_order,
                                       q_order=q_order, p_scale=alpha, q_scale=beta)
        assert given == through_curves(p_points, u0, q_points, v0, p_order=p_order,
                                       q_order=q_order, p_scale=alpha, q_scale=beta)
        # The defining property: R's ends are the scaled derivatives of P and Q.
        for k in range(p_order + 1):
            want = tuple(alpha ** k * x for x in derivative(p_points, u0, k))
            assert distance(derivative(given, 0.0, k), want) <= 1e-10 * max(1.0, norm(want))
        for k in range(q_order + 1):
            want = tuple(beta ** k * x for x in derivative(q_points, v0, k))
            assert distance(derivative(given, 1.0, k), want) <= 1e-10 * max(1.0, norm(want))
        points, scale = bezjoin.connect_points_auto_scale(p_points, u0, q_points, v0,
                                                          p_order=p_order, q_order=q_order)
        with Curve(p_points) as p, Curve(q_points) as q, \
                bezjoin.connect_auto_scale(p, u0, q, v0, p_order=p_order,
                                           q_order=q_order) as auto:
            assert points == auto.curve.points
            assert scale == auto.scale
        # The default scale is the automatic one, the default orders the degrees.
        assert bezjoin.connect_points(p_points, u0, q_points, v0) == through_curves(
            p_points, u0, q_points, v0)
        assert bezjoin.connect_points(p_points, u0, q_points, v0, auto_scale=False) == \
            through_curves(p_points, u0, q_points, v0, auto_scale=False)


def test_errors_name_the_argument():
    p = [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)]
    q = [(4.0, 0.0), (5.0, 1.0)]
    cases = [
        (dict(u0=1.5), "u0"),
        (dict(v0=float("nan")), "v0"),
        (dict(p_scale=0.0), "scale"),
        (dict(p_order=20, q_order=20), "degree 41"),
    ]
    for overrides, name in cases:
        arguments = dict(u0=1.0, v0=0.0, p_scale=1.0)
        arguments.update(overrides)
        with pytest.raises(bezjoin.BezjoinError, match=name):
            bezjoin.connect_points(p, arguments.pop("u0"), q, arguments.pop("v0"), **arguments)
    with pytest.raises(bezjoin.BezjoinError, match="dimension"):
        bezjoin.connect_points(p, 1.0, [(1.0, 2.0, 3.0)], 0.0)
    with pytest.raises(bezjoin.BezjoinError, match="empty"):
        bezjoin.connect_points([], 1.0, q, 0.0)
    with pytest.raises(bezjoin.BezjoinError, match="negative"):
        bezjoin.connect_points(p, 1.0, q, 0.0, p_order=-1)
    with pytest.raises(TypeError):
        bezjoin.connect_points(p, "end", q, 0.0)
    with pytest.raises(bezjoin.BezjoinError, match=r"q_points\[1\] = inf"):
        bezjoin.connect_points_auto_scale(p, 1.0, [(4.0, float("inf"))], 0.0)
