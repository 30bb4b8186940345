"""Independent reference evaluation (pure Python, no bezjoin): de Casteljau and hodographs."""

import math


def de_casteljau(points, t):
    """The point at ``t`` by repeated linear interpolation."""
    work = [list(p) for p in points]
    n = len(work) - 1
    for r in range(1, n + 1):
        for i in range(n - r + 1):
            work[i] = [(1 - t) * a + t * b for a, b in zip(work[i], work[i + 1])]
    return tuple(work[0])


def hodograph(points):
    """Control points of the derivative curve: ``n (P_{i+1} - P_i)``."""
    n = len(points) - 1
    return [tuple(n * (b - a) for a, b in zip(points[i], points[i + 1])) for i in range(n)]


def derivative(points, t, order):
    """The ``order``-th derivative at ``t`` (zero vector beyond the degree)."""
    dim = len(points[0])
    for _ in range(order):
        if len(points) == 1:
            return tuple(0.0 for _ in range(dim))
        points = hodograph(points)
    return de_casteljau(points, t)


def distance(a, b):
    """Euclidean distance."""
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def norm(a):
    """Euclidean norm."""
    return math.sqrt(sum(x * x for x in a))


def assert_close(actual, expected, relative=1e-12, scale=None):
    """``|actual - expected| <= relative * max(1, |expected|, scale)`` for points/vectors."""
    size = max(1.0, norm(expected), scale or 0.0)
    gap = distance(actual, expected)
    assert gap <= relative * size, f"{actual} != {expected} (distance {gap:.3e})"
