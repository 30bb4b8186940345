"""lagrange_spline: every given point lies on its segment at its local parameter, the
chain is C1 in the global parameter, and every error path."""

import math

import pytest

import bezjoin
from reference import de_casteljau, derivative, distance, norm
from test_curve import expect_error

NODES = [(0.0, 0.0), (1.0, 1.0), (2.5, 0.5), (4.0, 2.0)]
FIRST_INNER = [(0.3, 0.5), (0.7, 0.9)]
SECOND_INNER = [(2.0, 0.9), (3.6, 1.4)]


def check_spline(segments, nodes, first_inner, second_inner, widths):
    assert len(segments) == len(nodes) - 1
    points = [s.points for s in segments]
    for i, segment in enumerate(points):
        assert len(segment) == 4
        assert distance(de_casteljau(segment, 0.0), nodes[i]) <= 1e-12
        assert distance(de_casteljau(segment, 1.0), nodes[i + 1]) <= 1e-12
    assert distance(de_casteljau(points[0], 1 / 3), first_inner[0]) <= 1e-12
    assert distance(de_casteljau(points[0], 2 / 3), first_inner[1]) <= 1e-12
    for i, point in enumerate(second_inner, start=1):
        assert distance(de_casteljau(points[i], 2 / 3), point) <= 1e-12
    for i in range(1, len(points)):
        left = tuple(x / widths[i - 1] for x in derivative(points[i - 1], 1.0, 1))
        right = tuple(x / widths[i] for x in derivative(points[i], 0.0, 1))
        assert distance(left, right) <= 1e-12 * max(1.0, norm(left))


def test_given_parameters():
    params = [0.0, 1.0, 3.0, 3.5]
    segments = bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER, params=params)
    try:
        check_spline(segments, NODES, FIRST_INNER, SECOND_INNER,
                     [params[i + 1] - params[i] for i in range(3)])
    finally:
        for s in segments:
            s.close()


def test_chord_length_parameters():
    segments = bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER)
    try:
        check_spline(segments, NODES, FIRST_INNER, SECOND_INNER,
                     [distance(NODES[i], NODES[i + 1]) for i in range(3)])
    finally:
        for s in segments:
            s.close()


def test_single_segment_is_the_lagrange_cubic():
    segments = bezjoin.lagrange_spline(NODES[:2], FIRST_INNER, [])
    assert len(segments) == 1
    check_spline(segments, NODES[:2], FIRST_INNER, [], [1.0])
    segments[0].close()


def test_lagrange_errors():
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: bezjoin.lagrange_spline(NODES, FIRST_INNER[:1], SECOND_INNER),
                 "first_inner")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER[:1]),
                 "second_inner")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER,
                                                 params=[0, 1, 2]), "params")
    expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                 lambda: bezjoin.lagrange_spline(NODES, [(0, 0, 0), (1, 1, 1)], SECOND_INNER),
                 "first_inner")
    expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                 lambda: bezjoin.lagrange_spline(NODES, FIRST_INNER, [(0, 0, 0), (1, 1, 1)]),
                 "second_inner")
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: bezjoin.lagrange_spline(NODES[:1], FIRST_INNER, []))
    expect_error("BZJ_ERR_INVALID_ARGUMENT",
                 lambda: bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER,
                                                 params=[0, 2, 1, 3]), "params")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: bezjoin.lagrange_spline(NODES, [(math.nan, 0), (1, 1)], SECOND_INNER))
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.lagrange_spline([], FIRST_INNER, []),
                 "nodes is empty")
    with pytest.raises(TypeError, match="params\\[1\\]"):
        bezjoin.lagrange_spline(NODES, FIRST_INNER, SECOND_INNER, params=[0, "x", 2, 3])
