"""Merge two curves into one Bezier curve (``bzj_merge``).

Ganchuk, Krivosheev, Mavrin, Ryzhov, "Approximation of conjugation of Bezier
curves with preservation of smoothness order and additional restrictions",
Bulletin of SUSU, 2024, 24(1) 59-69 (mathematics.md section 3).
"""

import ctypes

from ._convert import index_argument, real_argument
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


_curve_out = ctypes.POINTER(CurvePointer)
register_prototype(
    "bzj_merge",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(MergeOptionsStruct), _curve_out, _curve_out,
     _curve_out, ctypes.POINTER(MergeReportStruct)],
)


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
          p_points=(), q_points=()):
    """One Bezier curve ``R`` of the common degree whose pieces split at ``mu``
    are ``P^ = P + eps`` and ``Q^ = Q + delta``, with the change minimal in
    ``metric`` under the chosen constraints (a lower degree is elevated first).

    Args:
        metric: ``"discrete"`` or ``"l2"``.
        mu: ``"half"``, ``"polygon"`` (proportional to control-polygon
            lengths), ``"optimal"`` (minimising the metric) or a number in
            ``(0, 1)``.
        keep_p, keep_q: leave that curve unchanged.
        fix_ends: keep the first point of ``P`` and the last point of ``Q``.
        p_points, q_points: ``(param, max_order)`` pairs: keep the point at
            ``param`` with derivatives ``0..max_order``.

    Returns:
        :class:`MergeResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_INCONSISTENT`` for too many or contradictory
            constraints, ...
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    if metric not in METRICS:
        raise BezjoinError.invalid_argument(
            f"metric = {metric!r} is not one of {', '.join(map(repr, METRICS))}")
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
        METRICS[metric], split, mu_value, bool(keep_p), bool(keep_q), bool(fix_ends),
        p_array if p_count else None, p_count, q_array if q_count else None, q_count,
    )
    merged, p_hat, q_hat = CurvePointer(), CurvePointer(), CurvePointer()
    report = MergeReportStruct()
    library().call("bzj_merge", p_handle, q_handle, ctypes.byref(options), ctypes.byref(merged),
                   ctypes.byref(p_hat), ctypes.byref(q_hat), ctypes.byref(report))
    return MergeResult(Curve._adopt(merged), Curve._adopt(p_hat), Curve._adopt(q_hat),
                       report.mu, report.metric_value, report.max_deviation)
