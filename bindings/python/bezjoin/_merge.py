"""Merge two curves into one Bezier curve (``bzj_merge``, ``bzj_merge_to_degree``), or a
chain of curves (``bzj_merge_chain``).

Ganchuk, Krivosheev, Mavrin, Ryzhov, "Approximation of conjugation of Bezier
curves with preservation of smoothness order and additional restrictions",
Bulletin of SUSU, 2024, 24(1) 59-69 (mathematics.md section 3).
"""

import ctypes

from ._convert import double_array, index_argument, real_argument
from ._library import CurvePointer, library, register_prototype
from .curve import Curve, handle_of
from .errors import BezjoinError
from .results import CurveGroup

METRICS = {"discrete": 0, "l2": 1}
"""``BzjMetric``: ``"discrete"`` = sum of squared control-point changes,
``"l2"`` = integral of the squared change of each curve over its own parameter."""

SPLIT_MODES = {"given": 0, "half": 1, "polygon": 2, "optimal": 3}
"""``BzjSplit``: how ``mu`` is chosen (a number passed as ``mu`` means ``"given"``)."""


class KeepPointStruct(ctypes.Structure):
    """``BzjKeepPoint`` (layout fixed by the C contract)."""

    _fields_ = [("param", ctypes.c_double), ("max_order", ctypes.c_size_t)]


class MergeOptionsStruct(ctypes.Structure):
    """``BzjMergeOptions`` (layout fixed by the C contract; the enums are ``int32_t``)."""

    _fields_ = [
        ("metric", ctypes.c_int32),
        ("split", ctypes.c_int32),
        ("mu", ctypes.c_double),
        ("keep_p", ctypes.c_bool),
        ("keep_q", ctypes.c_bool),
        ("fix_ends", ctypes.c_bool),
        ("p_points", ctypes.POINTER(KeepPointStruct)),
        ("p_point_count", ctypes.c_size_t),
        ("q_points", ctypes.POINTER(KeepPointStruct)),
        ("q_point_count", ctypes.c_size_t),
    ]


class MergeReportStruct(ctypes.Structure):
    """``BzjMergeReport`` (layout fixed by the C contract)."""

    _fields_ = [
        ("mu", ctypes.c_double),
        ("metric_value", ctypes.c_double),
        ("max_deviation", ctypes.c_double),
    ]


class ChainKeepPointStruct(ctypes.Structure):
    """``BzjChainKeepPoint`` (layout fixed by the C header)."""

    _fields_ = [
        ("curve", ctypes.c_size_t),
        ("param", ctypes.c_double),
        ("max_order", ctypes.c_size_t),
    ]


class ChainMergeOptionsStruct(ctypes.Structure):
    """``BzjChainMergeOptions`` (layout fixed by the C header; the enums are ``int32_t``)."""

    _fields_ = [
        ("metric", ctypes.c_int32),
        ("split", ctypes.c_int32),
        ("breakpoints", ctypes.POINTER(ctypes.c_double)),
        ("breakpoint_count", ctypes.c_size_t),
        ("degree", ctypes.c_size_t),
        ("fix_ends", ctypes.c_bool),
        ("keep", ctypes.POINTER(ctypes.c_bool)),
        ("keep_points", ctypes.POINTER(ChainKeepPointStruct)),
        ("keep_point_count", ctypes.c_size_t),
    ]


class ChainMergeReportStruct(ctypes.Structure):
    """``BzjChainMergeReport`` (layout fixed by the C header)."""

    _fields_ = [
        ("metric_value", ctypes.c_double),
        ("max_deviation", ctypes.c_double),
    ]


_curve_out = ctypes.POINTER(CurvePointer)
register_prototype(
    "bzj_merge",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(MergeOptionsStruct), _curve_out, _curve_out,
     _curve_out, ctypes.POINTER(MergeReportStruct)],
)
register_prototype(
    "bzj_merge_to_degree",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(MergeOptionsStruct), ctypes.c_size_t,
     _curve_out, _curve_out, _curve_out, ctypes.POINTER(MergeReportStruct)],
)
register_prototype(
    "bzj_merge_chain",
    ctypes.c_int32,
    [ctypes.POINTER(CurvePointer), ctypes.c_size_t, ctypes.POINTER(ChainMergeOptionsStruct),
     _curve_out, _curve_out, ctypes.c_size_t, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t,
     ctypes.POINTER(ChainMergeReportStruct)],
)

CHAIN_SPLIT_MODES = {"given": 0, "uniform": 1, "polygon": 2}
"""``BzjChainSplit``: how the breakpoints of :func:`merge_chain` are chosen (a
sequence passed as ``breakpoints`` means ``"given"``)."""


class MergeResult(CurveGroup):
    """``merged`` (``R``), the changed inputs ``p_hat = R|[0,mu]`` and
    ``q_hat = R|[mu,1]``, and the report: ``mu`` used, ``metric_value`` (the
    minimised metric) and ``max_deviation`` (largest distance between ``R``
    and ``P`` then ``Q``, sampled densely)."""

    _curve_fields = ("merged", "p_hat", "q_hat")

    def __init__(self, merged, p_hat, q_hat, mu, metric_value, max_deviation):
        self.merged = merged
        self.p_hat = p_hat
        self.q_hat = q_hat
        self.mu = mu
        self.metric_value = metric_value
        self.max_deviation = max_deviation

    def _fields(self):
        return self._curve_fields + ("mu", "metric_value", "max_deviation")


def _metric(metric):
    if metric not in METRICS:
        raise BezjoinError.invalid_argument(
            f"metric = {metric!r} is not one of {', '.join(map(repr, METRICS))}")
    return METRICS[metric]


def _keep_points(points, name):
    structs = []
    for j, point in enumerate(points):
        try:
            param, max_order = point
        except (TypeError, ValueError):
            raise TypeError(f"{name}[{j}] must be a (param, max_order) pair") from None
        structs.append(KeepPointStruct(real_argument(param, f"{name}[{j}] param"),
                                       index_argument(max_order, f"{name}[{j}] max_order")))
    return (KeepPointStruct * max(len(structs), 1))(*structs), len(structs)


def merge(p, q, *, metric="discrete", mu="half", keep_p=False, keep_q=False, fix_ends=False,
          p_points=(), q_points=(), degree=None):
    """One Bezier curve ``R`` of the common degree whose pieces split at ``mu``
    are ``P^ = P + eps`` and ``Q^ = Q + delta``, with the change minimal in
    ``metric`` under the chosen constraints (a lower degree is elevated first;
    with ``degree``, both are elevated to it: ``bzj_merge_to_degree``).

    NURBS curves (polynomial B-splines; a rational one is refused by name):
    ``R`` is a NURBS curve on ``[0, 1]`` with ``P``'s interior knots mapped into
    ``(0, mu)``, ``Q``'s into ``(mu, 1)`` and no knot at ``mu``; ``P^`` and ``Q^``
    keep ``P``'s and ``Q``'s knots and parameters, and keep-point parameters are
    in each curve's domain (mathematics.md section 6).

    Args:
        metric: ``"discrete"`` or ``"l2"``.
        mu: ``"half"``, ``"polygon"`` (proportional to control-polygon
            lengths), ``"optimal"`` (minimising the metric) or a number in
            ``(0, 1)``.
        keep_p, keep_q: leave that curve unchanged.
        fix_ends: keep the first point of ``P`` and the last point of ``Q``.
        p_points, q_points: ``(param, max_order)`` pairs: keep the point at
            ``param`` with derivatives ``0..max_order``.
        degree: the degree of ``R``, at least both curves' degrees (``None``:
            the higher of the two). A higher degree leaves more freedom, so a
            smaller change; keep-point orders may go up to it.

    Returns:
        :class:`MergeResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_INCONSISTENT`` for too many or contradictory
            constraints, ...
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    metric_value = _metric(metric)
    if degree is not None:
        degree = index_argument(degree, "degree")
    if isinstance(mu, str):
        if mu not in SPLIT_MODES or mu == "given":
            raise BezjoinError.invalid_argument(
                f"mu = {mu!r} is not a number nor one of 'half', 'polygon', 'optimal'")
        split, mu_value = SPLIT_MODES[mu], 0.5
    else:
        split, mu_value = SPLIT_MODES["given"], real_argument(mu, "mu")
    p_array, p_count = _keep_points(p_points, "p_points")
    q_array, q_count = _keep_points(q_points, "q_points")
    options = MergeOptionsStruct(
        metric_value, split, mu_value, bool(keep_p), bool(keep_q), bool(fix_ends),
        p_array if p_count else None, p_count, q_array if q_count else None, q_count,
    )
    merged, p_hat, q_hat = CurvePointer(), CurvePointer(), CurvePointer()
    report = MergeReportStruct()
    outputs = (ctypes.byref(merged), ctypes.byref(p_hat), ctypes.byref(q_hat),
               ctypes.byref(report))
    if degree is None:
        library().call("bzj_merge", p_handle, q_handle, ctypes.byref(options), *outputs)
    else:
        library().call("bzj_merge_to_degree", p_handle, q_handle, ctypes.byref(options), degree,
                       *outputs)
    return MergeResult(Curve._adopt(merged), Curve._adopt(p_hat), Curve._adopt(q_hat),
                       report.mu, report.metric_value, report.max_deviation)


class ChainMergeResult(CurveGroup):
    """:func:`merge_chain`'s ``merged`` curve ``R``, the changed curves ``pieces``
    (piece ``j`` is ``R`` on ``[t_j, t_{j+1}]``, over ``[0, 1]``), the
    ``breakpoints`` ``t_0 = 0 < ... < t_N = 1``, and the report: ``metric_value``
    (the sum of the pieces' metrics) and ``max_deviation`` (largest distance
    between piece ``j`` of ``R`` and curve ``j``, each in its own parameter)."""

    _curve_fields = ("merged", "pieces")

    def __init__(self, merged, pieces, breakpoints, metric_value, max_deviation):
        self.merged = merged
        self.pieces = pieces
        self.breakpoints = breakpoints
        self.metric_value = metric_value
        self.max_deviation = max_deviation

    def _fields(self):
        return self._curve_fields + ("breakpoints", "metric_value", "max_deviation")


def merge_chain(curves, *, metric="discrete", breakpoints="uniform", degree=None,
                fix_ends=False, keep=None, keep_points=()):
    """**Beyond the paper**: merge ``N >= 2`` consecutive curves into one Bezier
    curve ``R`` (``bzj_merge_chain``): with breakpoints ``0 = t_0 < ... < t_N = 1``,
    curve ``j`` is changed as little as possible (sum of the metrics) into the
    piece of ``R`` on ``[t_j, t_{j+1}]``. With two curves this is :func:`merge`.

    Args:
        curves: the :class:`Curve` objects, in path order.
        metric: ``"discrete"`` or ``"l2"``, summed over the pieces.
        breakpoints: ``"uniform"`` (``t_j = j / N``), ``"polygon"`` (proportional
            to the control-polygon lengths) or the ``N - 1`` interior values,
            strictly increasing in ``(0, 1)``, every piece at least ``1e-6`` of the
            range.
        degree: the degree of ``R`` (``None``: the highest degree of the curves).
        fix_ends: keep the first point of the first curve and the last point of
            the last.
        keep: ``None``, or one flag per curve: keep that curve unchanged.
        keep_points: ``(curve, param, max_order)`` triples: keep the point at
            ``param`` of curve number ``curve`` with derivatives ``0..max_order``.

    Returns:
        :class:`ChainMergeResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_INCONSISTENT`` for too many or contradictory
            constraints, ``BZJ_ERR_INVALID_ARGUMENT`` for bad breakpoints, ...
    """
    curves = list(curves)
    handles = [handle_of(c, f"curves[{i}]") for i, c in enumerate(curves)]
    count = len(handles)
    metric_value = _metric(metric)
    if isinstance(breakpoints, str):
        if breakpoints not in CHAIN_SPLIT_MODES or breakpoints == "given":
            raise BezjoinError.invalid_argument(
                f"breakpoints = {breakpoints!r} is not a sequence of numbers nor one of "
                "'uniform', 'polygon'")
        split, values = CHAIN_SPLIT_MODES[breakpoints], []
    else:
        split = CHAIN_SPLIT_MODES["given"]
        values = [real_argument(x, f"breakpoints[{i}]") for i, x in enumerate(breakpoints)]
    breakpoint_array, _ = double_array(values)
    keep_array = None
    if keep is not None:
        flags = [bool(flag) for flag in keep]
        if len(flags) != count:
            # The C function reads one flag per curve.
            raise BezjoinError.invalid_argument(
                f"keep has {len(flags)} flags; there are {count} curves")
        keep_array = (ctypes.c_bool * max(count, 1))(*flags)
    structs = []
    for j, point in enumerate(keep_points):
        try:
            curve, param, max_order = point
        except (TypeError, ValueError):
            raise TypeError(f"keep_points[{j}] must be a (curve, param, max_order) triple") \
                from None
        structs.append(ChainKeepPointStruct(
            index_argument(curve, f"keep_points[{j}] curve"),
            real_argument(param, f"keep_points[{j}] param"),
            index_argument(max_order, f"keep_points[{j}] max_order")))
    keep_point_array = (ChainKeepPointStruct * max(len(structs), 1))(*structs)
    options = ChainMergeOptionsStruct(
        metric_value, split, breakpoint_array if values else None, len(values),
        0 if degree is None else index_argument(degree, "degree"), bool(fix_ends),
        keep_array, keep_point_array if structs else None, len(structs),
    )
    array = (CurvePointer * max(count, 1))(*handles)
    merged = CurvePointer()
    pieces = (CurvePointer * max(count, 1))()
    breakpoints_out = (ctypes.c_double * (count + 1))()
    report = ChainMergeReportStruct()
    library().call("bzj_merge_chain", array, count, ctypes.byref(options), ctypes.byref(merged),
                   pieces, count, breakpoints_out, count + 1, ctypes.byref(report))
    return ChainMergeResult(Curve._adopt(merged), [Curve._adopt(pieces[j]) for j in range(count)],
                            list(breakpoints_out), report.metric_value, report.max_deviation)
