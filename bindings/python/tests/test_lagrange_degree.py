"""lagrange_spline_degree: every given point lies on its segment at its local parameter
u = j / degree, the chain is C^continuity in the global parameter, the flags start from
the other end or mirror the free points, degree 3 C1 is lagrange_spline, and every
error path."""

import math

import pytest

import bezjoin
from reference import de_casteljau, derivative, distance, norm
from test_curve import expect_error


def helix(x):
    return (math.cos(x), math.sin(x), 0.3 * x)


PARAMS = [0.0, 0.8, 1.5, 2.4, 3.0]
NODES = [helix(x) for x in PARAMS]


def inner_points(segment, us):
    """The helix at local parameters ``us`` of segment ``segment``."""
    a, b = PARAMS[segment], PARAMS[segment + 1]
    return [helix(a + (b - a) * u) for u in us]


def check_spline(segments, degree, continuity, given):
    """``given``: ``(segment, u, point)`` triples that must lie on the segments."""
    points = [s.points for s in segments]
    assert len(points) == len(PARAMS) - 1
    for i, segment in enumerate(points):
        assert len(segment) == degree + 1
        assert distance(segment[0], NODES[i]) <= 1e-12
        assert distance(segment[-1], NODES[i + 1]) <= 1e-12
    for segment, u, point in given:
        assert distance(de_casteljau(points[segment], u), point) <= 1e-12, (segment, u)
    widths = [b - a for a, b in zip(PARAMS, PARAMS[1:])]
    for i in range(1, len(points)):
        for k in range(1, continuity + 1):
            left = tuple(x / widths[i - 1] ** k for x in derivative(points[i - 1], 1.0, k))
            right = tuple(x / widths[i] ** k for x in derivative(points[i], 0.0, k))
            assert distance(left, right) <= 1e-9 * max(1.0, norm(left)), (i, k)
    return points


@pytest.mark.parametrize("degree,continuity", [(3, 1), (4, 1), (4, 2), (5, 1), (5, 2), (5, 3)])
def test_given_points_on_the_curve_and_continuity(degree, continuity):
    n = degree
    start_us = [j / n for j in range(1, n)]
    free_us = [j / n for j in range(continuity + 1, n)]  # derived: u = 1/n .. continuity/n
    start = inner_points(0, start_us)
    free = [p for s in range(1, len(PARAMS) - 1) for p in inner_points(s, free_us)]
    given = [(0, u, p) for u, p in zip(start_us, start)]
    given += [(s, u, p) for s in range(1, len(PARAMS) - 1)
              for u, p in zip(free_us, inner_points(s, free_us))]
    segments = bezjoin.lagrange_spline_degree(NODES, start, free, degree=degree,
                                              continuity=continuity, params=PARAMS)
    try:
        check_spline(segments, degree, continuity, given)
    finally:
        for s in segments:
            s.close()


def test_backward_starts_from_the_last_segment():
    last = len(PARAMS) - 2
    start = inner_points(last, [1 / 3, 2 / 3])
    free = [inner_points(s, [1 / 3])[0] for s in range(last)]  # derived: u = 2/3
    given = [(last, 1 / 3, start[0]), (last, 2 / 3, start[1])]
    given += [(s, 1 / 3, p) for s, p in enumerate(free)]
    segments = bezjoin.lagrange_spline_degree(NODES, start, free, degree=3, continuity=1,
                                              params=PARAMS, backward=True)
    try:
        check_spline(segments, 3, 1, given)
    finally:
        for s in segments:
            s.close()


def test_mirrored_gives_the_points_near_the_join():
    start = inner_points(0, [1 / 3, 2 / 3])
    free = [inner_points(s, [1 / 3])[0] for s in range(1, len(PARAMS) - 1)]  # derived: 2/3
    given = [(0, 1 / 3, start[0]), (0, 2 / 3, start[1])]
    given += [(s, 1 / 3, p) for s, p in enumerate(free, start=1)]
    segments = bezjoin.lagrange_spline_degree(NODES, start, free, degree=3, continuity=1,
                                              params=PARAMS, mirrored=True)
    try:
        check_spline(segments, 3, 1, given)
    finally:
        for s in segments:
            s.close()


def test_degree_3_c1_is_lagrange_spline():
    start = inner_points(0, [1 / 3, 2 / 3])
    free = [inner_points(s, [2 / 3])[0] for s in range(1, len(PARAMS) - 1)]
    for params in (PARAMS, None):
        general = bezjoin.lagrange_spline_degree(NODES, start, free, degree=3, continuity=1,
                                                 params=params)
        cubic = bezjoin.lagrange_spline(NODES, start, free, params=params)
        try:
            assert [s.points for s in general] == [s.points for s in cubic]
        finally:
            for s in general + cubic:
                s.close()


def test_long_mirrored_chain_is_refused():
    count = 60
    nodes = [(math.sin(0.3 * i),) for i in range(count)]
    free = [(0.5 * (nodes[i + 1][0] + nodes[i + 2][0]),) for i in range(count - 2)]
    params = list(range(count))
    expect_error("BZJ_ERR_ILL_CONDITIONED",
                 lambda: bezjoin.lagrange_spline_degree(nodes, [(0.1,), (0.2,)], free, degree=3,
                                                        continuity=1, params=params,
                                                        mirrored=True))
    segments = bezjoin.lagrange_spline_degree(nodes, [(0.1,), (0.2,)], free, degree=3,
                                              continuity=1, params=params)
    assert len(segments) == count - 1
    for s in segments:
        s.close()


def test_lagrange_spline_degree_errors():
    start = inner_points(0, [0.2, 0.4, 0.6, 0.8])
    free = [p for s in range(1, 4) for p in inner_points(s, [0.6, 0.8])]

    def call(**changes):
        arguments = dict(nodes=NODES, start_inner=start, free_inner=free, degree=5,
                         continuity=2, params=PARAMS)
        arguments.update(changes)
        return bezjoin.lagrange_spline_degree(**arguments)

    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(degree=6), "degree")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(degree=2), "degree")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(continuity=4), "continuity")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(continuity=0), "continuity")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(start_inner=start[:3]),
                 "start_inner has 3 points")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(free_inner=free[:-1]),
                 "free_inner has 5 points")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(params=PARAMS[:-1]), "params")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(params=[0, 1, 0.5, 2, 3]), "params")
    expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                 lambda: call(free_inner=[(0, 0)] * 6), "free_inner")
    expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                 lambda: call(start_inner=[(0, 0)] * 4), "start_inner")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: call(start_inner=[(math.nan, 0, 0)] + start[1:]))
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(nodes=NODES[:1], params=None))
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: call(degree=-5), "degree = -5 is negative")
    with pytest.raises(TypeError, match="continuity must be an integer"):
        call(continuity=1.5)
