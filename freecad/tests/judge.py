"""FreeCAD's own geometry (OpenCASCADE underneath) as the judge of bezjoin's results.

Nothing here uses bezjoin: the pieces are Part.BezierCurve objects, derivatives
come from ``getDN``, joins are judged on a ``Part.BSplineCurve`` built from
poles, knots and multiplicities with ``removeKnot``.
"""

import math

import FreeCAD
import Part


def bezier(points):
    """A Part.BezierCurve from 3D (or 2D, placed at z = 0) points."""
    curve = Part.BezierCurve()
    curve.setPoles([FreeCAD.Vector(*(tuple(p) + (0.0,) * (3 - len(p)))) for p in points])
    return curve


def poles(curve):
    """The poles as tuples."""
    return [tuple(p) for p in curve.getPoles()]


def size(curves):
    """The largest pole distance from the origin over ``curves`` (at least 1)."""
    return max([1.0] + [math.sqrt(sum(x * x for x in p)) for c in curves for p in poles(c)])


def gap(a, b):
    """Distance between two points/vectors."""
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def chain_bspline(pieces, intervals):
    """The B-spline made of Bezier ``pieces`` over consecutive parameter ``intervals``.

    All pieces are raised to the highest degree with FreeCAD's ``increase``
    (exact); the end pole of each piece is shared with the next one, so the
    joins must already meet (checked by the caller). Interior knots get
    multiplicity ``degree`` (C0 as built); ``removeKnot`` then tells how
    smooth each join really is.
    """
    degree = max(piece.Degree for piece in pieces)
    chain_poles = []
    for i, piece in enumerate(pieces):
        raised = piece.copy()
        if raised.Degree < degree:
            raised.increase(degree)
        piece_poles = raised.getPoles()
        chain_poles.extend(piece_poles if i == 0 else piece_poles[1:])
    knots = [0.0]
    for width in intervals:
        knots.append(knots[-1] + width)
    multiplicities = [degree + 1] + [degree] * (len(pieces) - 1) + [degree + 1]
    spline = Part.BSplineCurve()
    spline.buildFromPolesMultsKnots(chain_poles, multiplicities, knots, False, degree)
    return spline


def lowest_multiplicity(spline, index, tolerance):
    """The lowest multiplicity ``removeKnot`` reaches for knot ``index`` (1-based)
    without moving the curve by more than ``tolerance``. A join of a degree-d
    spline is C^k exactly when this is ``<= d - k``."""
    current = spline.getMultiplicity(index)
    lowest = current
    for target in range(current - 1, -1, -1):
        trial = spline.copy()
        if not trial.removeKnot(index, target, tolerance):
            break
        lowest = target
    return lowest


def smoothness_by_knot_removal(spline, index, tolerance):
    """The continuity order ``k`` of the join at knot ``index`` proven by knot removal."""
    return spline.Degree - lowest_multiplicity(spline, index, tolerance)


def one_sided_derivatives(piece, width, at_end, max_order):
    """Derivatives ``0..max_order`` of ``piece`` at its end (``at_end``) or start,
    with respect to a global parameter in which the piece spans ``width``."""
    t = 1.0 if at_end else 0.0
    rows = [tuple(piece.value(t))]
    for k in range(1, max_order + 1):
        rows.append(tuple(x / width ** k for x in piece.getDN(t, k)))
    return rows


def derivative_jumps(left, left_width, right, right_width, max_order):
    """``|left^(k)(end) - right^(k)(start)| / max(1, |left^(k)|)`` for ``k = 0..max_order``
    (derivatives in the global parameter, from FreeCAD's ``getDN``)."""
    from_left = one_sided_derivatives(left, left_width, True, max_order)
    from_right = one_sided_derivatives(right, right_width, False, max_order)
    jumps = []
    for a, b in zip(from_left, from_right):
        scale = max(1.0, math.sqrt(sum(x * x for x in a)))
        jumps.append(gap(a, b) / scale)
    return jumps
