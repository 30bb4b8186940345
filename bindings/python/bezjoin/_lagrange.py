"""Cubic spline whose control points lie on the curve (``bzj_lagrange_spline``), and
its generalisation to degrees 4 and 5 with C^2 / C^3 joins (``bzj_lagrange_spline_degree``).

Kovtun A.M., "Spline of third degree with control points incident to the
curve" (mathematics.md section 4).
"""

import ctypes

from ._convert import (double_array, flat, index_argument, point_indices, point_rows,
                       real_argument)
from ._library import CurvePointer, library, register_prototype
from .curve import Curve
from .errors import BezjoinError

register_prototype(
    "bzj_lagrange_spline",
    ctypes.c_int32,
    [ctypes.c_size_t, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(CurvePointer), ctypes.c_size_t],
)

register_prototype(
    "bzj_lagrange_spline_degree",
    ctypes.c_int32,
    [ctypes.c_size_t, ctypes.c_size_t, ctypes.c_size_t, ctypes.c_uint32, ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(CurvePointer), ctypes.c_size_t],
)

#: ``BZJ_LAGRANGE_BACKWARD``: build from the last segment backwards.
LAGRANGE_BACKWARD = 1
#: ``BZJ_LAGRANGE_MIRRORED``: derive the inner points farthest from the join.
LAGRANGE_MIRRORED = 2


def lagrange_spline(nodes, first_inner, second_inner, params=None):
    """The C1 chain of cubic Bezier segments through on-curve points.

    Segment ``i`` runs from ``nodes[i]`` to ``nodes[i + 1]`` and passes through
    its inner points at local parameters ``1/3`` and ``2/3``: both are given
    for segment 0 (``first_inner``); for every later segment the ``2/3``
    point is given (``second_inner[i - 1]``) and the ``1/3`` point follows
    from C1 continuity with respect to the global parameter.

    Args:
        nodes: ``node_count >= 2`` points.
        first_inner: the two inner points of segment 0.
        second_inner: ``node_count - 2`` points.
        params: ``node_count`` increasing global parameters, or ``None`` for
            chord length.

    Returns:
        A list of ``node_count - 1`` cubic :class:`Curve` segments.
    """
    node_rows, dim = point_rows(nodes, "nodes")
    node_count = len(node_rows)
    first_rows, first_dim = point_rows(first_inner, "first_inner")
    # The C function reads lengths implied by node_count and dim: check them here.
    if len(first_rows) != 2:
        raise BezjoinError.invalid_argument(
            f"first_inner has {len(first_rows)} points; segment 0 has exactly 2 inner points")
    if first_dim != dim:
        raise BezjoinError.dimension_mismatch(
            f"first_inner has dimension {first_dim} but nodes have dimension {dim}")
    second_rows = list(second_inner)
    if second_rows:
        second_rows, second_dim = point_rows(second_rows, "second_inner")
        if second_dim != dim:
            raise BezjoinError.dimension_mismatch(
                f"second_inner has dimension {second_dim} but nodes have dimension {dim}")
    if len(second_rows) != max(node_count - 2, 0):
        raise BezjoinError.invalid_argument(
            f"second_inner has {len(second_rows)} points; {node_count} nodes need "
            f"{max(node_count - 2, 0)}")
    parameter_array = _parameter_array(params, node_count)
    node_array, _ = double_array(flat(node_rows))
    first_array, _ = double_array(flat(first_rows))
    second_array, _ = double_array(flat(second_rows))
    capacity = max(node_count - 1, 1)
    segments = (CurvePointer * capacity)()
    with point_indices(dim, "nodes", "first_inner", "second_inner"):
        library().call("bzj_lagrange_spline", dim, node_count, node_array, parameter_array,
                       first_array, second_array, segments, node_count - 1)
    return [Curve._adopt(segments[i]) for i in range(node_count - 1)]


def lagrange_spline_degree(nodes, start_inner, free_inner, *, degree, continuity, params=None,
                           backward=False, mirrored=False):
    """The generalisation of :func:`lagrange_spline` (``bzj_lagrange_spline_degree``):
    segments of degree ``degree`` (3, 4 or 5) through points ON them at local
    parameters ``u = j / degree``, joined C^``continuity`` (``1 .. degree - 2``) in
    the global parameter at every node.

    Segment ``i`` runs from ``nodes[i]`` to ``nodes[i + 1]``. The starting
    segment (segment 0, or the last one with ``backward``) has all its inner
    points given (``start_inner``); every other segment has ``degree - 1 -
    continuity`` inner points given (``free_inner``), the rest follow from the
    continuity. Without flags the derived points are ``u = 1/n .. continuity/n``
    and the given ones the rest (degree 5, C^2: give ``u = 3/5, 4/5``);
    ``mirrored`` or ``backward`` alone swaps the two ends, both together restore
    it. ``degree=3, continuity=1`` without flags is :func:`lagrange_spline`.

    Args:
        nodes: ``node_count >= 2`` points.
        start_inner: the ``degree - 1`` inner points of the starting segment, in
            increasing ``u``.
        free_inner: ``(node_count - 2) * (degree - 1 - continuity)`` points: for
            every other segment in increasing segment order, its given inner
            points in increasing ``u``.
        degree, continuity: see above.
        params: ``node_count`` increasing global parameters, or ``None`` for
            chord length.
        backward: ``BZJ_LAGRANGE_BACKWARD``: start from the last segment.
        mirrored: ``BZJ_LAGRANGE_MIRRORED``: derive the inner points farthest
            from the join (errors grow fast: short chains only).

    Returns:
        A list of ``node_count - 1`` :class:`Curve` segments of degree ``degree``.

    Raises:
        BezjoinError: ``BZJ_ERR_ILL_CONDITIONED`` when the recurrence amplifies
            rounding beyond 1e-9, ``BZJ_ERR_INVALID_ARGUMENT`` for a degree,
            continuity or point count out of range, ...
    """
    degree = index_argument(degree, "degree")
    continuity = index_argument(continuity, "continuity")
    node_rows, dim = point_rows(nodes, "nodes")
    node_count = len(node_rows)
    flags = (LAGRANGE_BACKWARD if backward else 0) | (LAGRANGE_MIRRORED if mirrored else 0)
    start_rows = _rows_of_dimension(start_inner, "start_inner", dim)
    free_rows = _rows_of_dimension(free_inner, "free_inner", dim)
    # The C function reads as many points as degree, continuity and node_count
    # imply: check the counts here when those are in range (otherwise the library
    # refuses them before reading anything).
    if 3 <= degree <= 5 and 1 <= continuity <= degree - 2 and node_count >= 2:
        for name, rows, wanted in (
                ("start_inner", start_rows, degree - 1),
                ("free_inner", free_rows, (node_count - 2) * (degree - 1 - continuity))):
            if len(rows) != wanted:
                raise BezjoinError.invalid_argument(
                    f"{name} has {len(rows)} points; degree {degree}, C^{continuity} and "
                    f"{node_count} nodes need {wanted}")
    parameter_array = _parameter_array(params, node_count)
    node_array, _ = double_array(flat(node_rows))
    start_array, _ = double_array(flat(start_rows))
    free_array, free_length = double_array(flat(free_rows))
    capacity = max(node_count - 1, 1)
    segments = (CurvePointer * capacity)()
    with point_indices(dim, "nodes", "start_inner", "free_inner"):
        library().call("bzj_lagrange_spline_degree", dim, degree, continuity, flags,
                       node_count, node_array, parameter_array, start_array,
                       free_array if free_length else None, segments, node_count - 1)
    return [Curve._adopt(segments[i]) for i in range(node_count - 1)]


def _rows_of_dimension(points, name, dim):
    """Point rows of ``points`` (possibly none), each of dimension ``dim``."""
    rows = list(points)
    if not rows:
        return []
    rows, row_dim = point_rows(rows, name)
    if row_dim != dim:
        raise BezjoinError.dimension_mismatch(
            f"{name} has dimension {row_dim} but nodes have dimension {dim}")
    return rows


def _parameter_array(params, node_count):
    """The ``node_count`` global parameters as a C array, or None (chord length)."""
    if params is None:
        return None
    values = [real_argument(x, f"params[{i}]") for i, x in enumerate(params)]
    if len(values) != node_count:
        raise BezjoinError.invalid_argument(
            f"params has {len(values)} values; there are {node_count} nodes")
    return double_array(values)[0]
