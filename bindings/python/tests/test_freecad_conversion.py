"""The FreeCAD conversion's plain-Python parts, without FreeCAD: knots with
multiplicities, the exact conic arcs (hyperbola, parabola, and the library's
ellipse arcs) and the map between FreeCAD's conic parameter and the curve's,
judged by the conics' closed forms. The conversion of FreeCAD objects itself is
tested inside freecadcmd (freecad/tests/test_nurbs_in_freecad.py)."""

import importlib.util
import math
import random

import pytest

import bezjoin
from bezjoin import Curve, _freecad
from reference import assert_close, norm

FREECAD_IMPORTABLE = importlib.util.find_spec("Part") is not None


def tilted_frame(rng, dim=3):
    """A centre and two orthonormal axes (3D: a random plane)."""
    if dim == 2:
        angle = rng.uniform(-math.pi, math.pi)
        return ((rng.uniform(-5, 5), rng.uniform(-5, 5)), (math.cos(angle), math.sin(angle)),
                (-math.sin(angle), math.cos(angle)))
    a = [rng.uniform(-1, 1) for _ in range(3)]
    b = [rng.uniform(-1, 1) for _ in range(3)]
    a = [x / norm(a) for x in a]
    dot = sum(x * y for x, y in zip(a, b))
    b = [y - dot * x for x, y in zip(a, b)]
    b = [x / norm(b) for x in b]
    return tuple(rng.uniform(-5, 5) for _ in range(3)), tuple(a), tuple(b)


def combine(centre, x_axis, y_axis, a, b):
    return tuple(c + a * x + b * y for c, x, y in zip(centre, x_axis, y_axis))


def parameters(curve, count=97):
    """``count`` parameters over the curve's domain, ends included exactly, plus its knots."""
    first, last = curve.domain
    inner = [first + (last - first) * i / (count - 1) for i in range(1, count - 1)]
    return sorted(set([first, last] + inner + [k for k in curve.knots if first <= k <= last]))


# -- knots ---------------------------------------------------------------------------------


def test_knots_and_multiplicities_round_trip():
    rng = random.Random(5)
    for _ in range(50):
        knots = sorted(set(round(rng.uniform(-10, 10), 3) for _ in range(rng.randint(2, 8))))
        multiplicities = [rng.randint(1, 4) for _ in knots]
        flat = _freecad.expand_knots(knots, multiplicities)
        assert len(flat) == sum(multiplicities)
        assert flat == sorted(flat)
        assert _freecad.group_knots(flat) == (knots, multiplicities)


def test_group_knots_takes_exact_equality_only():
    flat = [0.0, 0.0, 1.0, 1.0 + 2.0 ** -52, 2.0, 2.0]
    assert _freecad.group_knots(flat) == ([0.0, 1.0, 1.0 + 2.0 ** -52, 2.0], [2, 1, 1, 2])
    assert _freecad.group_knots([]) == ([], [])


def test_knots_of_a_nurbs_curve_regroup_to_its_flat_vector():
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 2, 1, -0.5, 4.0) as arc:
        knots, multiplicities = _freecad.group_knots(arc.knots)
        assert multiplicities == [3, 2, 2, 3]
        assert _freecad.expand_knots(knots, multiplicities) == arc.knots


# -- conic spans -----------------------------------------------------------------------------


SWEEPS = [1e-6, 0.3, 0.5 * math.pi, 0.5 * math.pi + 1e-9, 1.0, 2.0, math.pi, 4.0,
          1.5 * math.pi, 5.0, 2.0 * math.pi]


@pytest.mark.parametrize("a0", [0.0, -1.3, 0.3, 5.0, 100.0])
@pytest.mark.parametrize("sweep", SWEEPS)
def test_conic_breaks_are_the_library_ellipse_knots_exactly(a0, sweep):
    a1 = a0 + sweep
    with Curve.ellipse_arc((0, 0, 0), (1, 0, 0), (0, 1, 0), 1, 1, a0, a1) as arc:
        distinct = sorted(set(arc.knots))
        assert _freecad.conic_breaks(a0, a1, closed_turn=True) == distinct
        assert arc.domain == (a0, a1)
    breaks = _freecad.conic_breaks(a0, a1)
    assert breaks[0] == a0 and breaks[-1] == a1
    assert len(breaks) - 1 == max(1, math.ceil(sweep / (0.5 * math.pi) - 1e-12))
    widths = [b - a for a, b in zip(breaks, breaks[1:])]
    assert max(widths) <= 0.5 * math.pi * (1 + 1e-12)
    assert max(widths) - min(widths) <= 1e-12 * max(1.0, abs(a0))


# -- parameter maps -----------------------------------------------------------------------------


@pytest.mark.parametrize("kind", ["ellipse", "hyperbola"])
def test_conic_parameter_maps_are_inverse_monotone_and_fixed_at_knots(kind):
    for first, last in ((0.0, 2 * math.pi), (-1.0, 2.5), (5.0, 5.3), (-3.0, 3.0)):
        breaks = _freecad.conic_breaks(first, last)
        for k in breaks:
            assert _freecad.conic_freecad_parameter(kind, breaks, k) == k
            assert _freecad.conic_curve_parameter(kind, breaks, k) == k
        previous = -math.inf
        for i in range(1001):
            u = first + (last - first) * i / 1000 if i < 1000 else last
            t = _freecad.conic_freecad_parameter(kind, breaks, u)
            assert first <= t <= last
            assert t > previous
            previous = t
            # the documented bound between the two parameters
            assert abs(t - u) < 0.017
            back = _freecad.conic_curve_parameter(kind, breaks, t)
            assert abs(back - u) <= 1e-13 * max(1.0, abs(u))


def test_parameter_map_of_bezier_and_nurbs_conversions():
    assert _freecad._to_freecad_parameter("affine", 2.0, 6.0, 0.25) == 3.0
    assert _freecad._to_curve_parameter("affine", 2.0, 6.0, 3.0) == 0.25
    assert _freecad._to_freecad_parameter("same", 2.0, 6.0, 4.5) == 4.5
    assert _freecad._to_curve_parameter("same", 2.0, 6.0, 4.5) == 4.5
    with pytest.raises(ValueError, match="unknown conic"):
        _freecad.conic_freecad_parameter("circle", [0.0, 1.0], 0.5)


@pytest.mark.parametrize("dim", [2, 3])
def test_ellipse_arc_points_sit_at_the_mapped_angle(dim):
    """The library's ellipse arc at ``u`` is the ellipse's point of angle ``t(u)``:
    the map the FreeCAD conversion documents for circles and ellipses."""
    rng = random.Random(11 + dim)
    for a0, a1 in ((0.0, 2 * math.pi), (0.3, 1.9), (5.0, 7.5), (-2.0, 2.5), (1.0, 1.0 + 1e-3)):
        centre, x_axis, y_axis = tilted_frame(rng, dim)
        rx, ry = rng.uniform(1, 5), rng.uniform(0.2, 1)
        with Curve.ellipse_arc(centre, x_axis, y_axis, rx, ry, a0, a1) as arc:
            breaks = sorted(set(arc.knots))
            scale = norm(centre) + rx
            for u in parameters(arc):
                t = _freecad.conic_freecad_parameter("ellipse", breaks, u)
                exact = combine(centre, x_axis, y_axis, rx * math.cos(t), ry * math.sin(t))
                assert_close(arc.evaluate(u), exact, 1e-13, scale)


def hyperbola(centre, x_axis, y_axis, a, b, t, order=0):
    """The hyperbola point (order 0) or derivative (order 1) at ``t``."""
    if order == 0:
        return combine(centre, x_axis, y_axis, a * math.cosh(t), b * math.sinh(t))
    return tuple(a * math.sinh(t) * x + b * math.cosh(t) * y for x, y in zip(x_axis, y_axis))


@pytest.mark.parametrize("dim", [2, 3])
def test_hyperbola_arc_is_exact_with_the_mapped_parameter(dim):
    rng = random.Random(23 + dim)
    for first, last in ((-2.0, 3.0), (0.1, 0.4), (-1.0, 1.0), (0.5, 4.0)):
        centre, x_axis, y_axis = tilted_frame(rng, dim)
        a, b = rng.uniform(0.5, 4), rng.uniform(0.5, 4)
        with _freecad.hyperbola_arc(Curve, centre, x_axis, y_axis, a, b, first, last) as arc:
            assert arc.is_nurbs and arc.is_rational and arc.degree == 2 and arc.dim == dim
            assert arc.domain == (first, last)
            breaks = _freecad.conic_breaks(first, last)
            assert sorted(set(arc.knots)) == breaks
            scale = norm(centre) + (a + b) * math.cosh(max(abs(first), abs(last)))
            assert arc.evaluate(first) == hyperbola(centre, x_axis, y_axis, a, b, first)
            assert arc.evaluate(last) == hyperbola(centre, x_axis, y_axis, a, b, last)
            for u in parameters(arc):
                t = _freecad.conic_freecad_parameter("hyperbola", breaks, u)
                rows = arc.derivatives(u, 1)
                assert_close(rows[0], hyperbola(centre, x_axis, y_axis, a, b, t), 1e-13, scale)
                # chain rule: dC/du = P'(t) dt/du, dt/du = sinh(w / 2) / (w / 2 (1 - x^2 tanh^2))
                if u == last:
                    continue
                index = max(i for i in range(len(breaks) - 1) if breaks[i] <= u)
                width = breaks[index + 1] - breaks[index]
                x = 2 * (u - breaks[index]) / width - 1
                q = math.tanh(width / 4)
                dt_du = (2 / width) * 2 * q / (1 - (x * q) ** 2)
                expected = tuple(dt_du * v for v in hyperbola(centre, x_axis, y_axis, a, b, t, 1))
                assert_close(rows[1], expected, 1e-11, scale)


def test_hyperbola_arc_is_tangent_continuous_at_its_knots():
    centre, x_axis, y_axis = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)
    with _freecad.hyperbola_arc(Curve, centre, x_axis, y_axis, 3.0, 1.0, -3.0, 3.0) as arc:
        breaks = sorted(set(arc.knots))
        assert len(breaks) == 5
        for k in breaks[1:-1]:
            right = arc.derivatives(k, 1)[1]
            left_piece, _right_piece = arc.split(k)
            with left_piece, _right_piece:
                left = left_piece.derivatives(k, 1)[1]
            # equal spans: even the parametric speed matches (C1)
            assert_close(left, right, 1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_parabola_arc_keeps_the_parameter_everywhere(dim):
    rng = random.Random(31 + dim)
    for first, last in ((-2.0, 3.0), (0.5, 0.75), (-40.0, -1.0)):
        vertex, x_axis, y_axis = tilted_frame(rng, dim)
        focal = rng.uniform(0.1, 3)
        with _freecad.parabola_arc(Curve, vertex, x_axis, y_axis, focal, first, last) as arc:
            assert arc.is_nurbs and not arc.is_rational and arc.degree == 2
            assert arc.domain == (first, last) and arc.pole_count == 3
            scale = norm(vertex) + max(abs(first), abs(last)) ** 2 / focal
            for u in parameters(arc):
                rows = arc.derivatives(u, 2)
                assert_close(rows[0], combine(vertex, x_axis, y_axis, u * u / (4 * focal), u),
                             1e-14, scale)
                assert_close(rows[1], combine([0.0] * dim, x_axis, y_axis, u / (2 * focal), 1.0),
                             1e-13, scale)
                assert_close(rows[2], combine([0.0] * dim, x_axis, y_axis, 1 / (2 * focal), 0.0),
                             1e-12, scale)


# -- without FreeCAD ----------------------------------------------------------------------------


@pytest.mark.skipif(FREECAD_IMPORTABLE, reason="FreeCAD is importable: covered in freecadcmd")
def test_every_freecad_entry_point_says_freecad_is_missing(rational_arc):
    with pytest.raises(bezjoin.UnsupportedGeometryError, match="Part module"):
        rational_arc.to_freecad()
    with pytest.raises(bezjoin.UnsupportedGeometryError, match="Part module"):
        rational_arc.to_edge()
    for call in (lambda: Curve.from_freecad(object()),
                 lambda: _freecad.freecad_parameter(object(), 0.5),
                 lambda: _freecad.curve_parameter(object(), 0.5)):
        with pytest.raises(bezjoin.UnsupportedGeometryError, match="Part module"):
            call()


@pytest.fixture
def rational_arc():
    with Curve.ellipse_arc((0, 0, 0), (1, 0, 0), (0, 1, 0), 2, 1, 0.0, 2.0) as arc:
        yield arc

