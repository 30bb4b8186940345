"""Cubic spline whose control points lie on the curve (``bzj_lagrange_spline``).

Kovtun A.M., "Spline of third degree with control points incident to the
curve" (mathematics.md section 4).
"""

import ctypes

from ._convert import double_array, flat, point_rows, real_argument
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
    parameter_array = None
    if params is not None:
        values = [real_argument(x, f"params[{i}]") for i, x in enumerate(params)]
        if len(values) != node_count:
            raise BezjoinError.invalid_argument(
                f"params has {len(values)} values; there are {node_count} nodes")
        parameter_array, _ = double_array(values)
    node_array, _ = double_array(flat(node_rows))
    first_array, _ = double_array(flat(first_rows))
    second_array, _ = double_array(flat(second_rows))
    capacity = max(node_count - 1, 1)
    segments = (CurvePointer * capacity)()
    library().call("bzj_lagrange_spline", dim, node_count, node_array, parameter_array,
                   first_array, second_array, segments, node_count - 1)
    return [Curve._adopt(segments[i]) for i in range(node_count - 1)]
