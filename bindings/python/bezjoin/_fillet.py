"""Round the corner where two curves cross (``bzj_fillet``, ``bzj_fillet_auto_scale``;
``bzj_fillet_deviation`` sized by the distance from the corner; ``bzj_fillet_chain``
for every corner of a chain) and find where they meet (``bzj_intersect``, and
``bzj_intersect_detailed`` for the kind of each hit).

Krivosheev, Mavrin, Starkova, "Bezier curve conjugation for smooth curve
joining and corner rounding", Omsk Scientific Bulletin, 2025, Fig. 2
(mathematics.md section 2).
"""

import ctypes
from collections import namedtuple

from ._convert import BALANCED, automatic_scale, index_argument, real_argument
from ._library import CurvePointer, library, register_prototype
from .curve import Curve, handle_of
from .errors import BezjoinError
from .results import CurveGroup


class FilletOptionsStruct(ctypes.Structure):
    """``BzjFilletOptions`` (layout fixed by the C contract)."""

    _fields_ = [
        ("p_setback", ctypes.c_double),
        ("q_setback", ctypes.c_double),
        ("p_order", ctypes.c_size_t),
        ("q_order", ctypes.c_size_t),
        ("p_scale", ctypes.c_double),
        ("q_scale", ctypes.c_double),
    ]


_curve_out = ctypes.POINTER(CurvePointer)
register_prototype(
    "bzj_fillet",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), _curve_out, _curve_out,
     _curve_out],
)
register_prototype(
    "bzj_fillet_auto_scale",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), _curve_out, _curve_out,
     _curve_out, ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_vertex",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), ctypes.c_double,
     _curve_out, _curve_out, _curve_out],
)
register_prototype(
    "bzj_fillet_vertex_auto_scale",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), ctypes.c_double,
     _curve_out, _curve_out, _curve_out, ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_balanced_scale",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), _curve_out, _curve_out,
     _curve_out, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_vertex_balanced_scale",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(FilletOptionsStruct), ctypes.c_double,
     _curve_out, _curve_out, _curve_out, ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_intersect",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(ctypes.c_double), ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_size_t)],
)


class IntersectOptionsStruct(ctypes.Structure):
    """``BzjIntersectOptions`` (layout fixed by the C header)."""

    _fields_ = [
        ("relative_distance_tolerance", ctypes.c_double),
        ("tangent_tolerance", ctypes.c_double),
        ("max_depth", ctypes.c_size_t),
        ("max_box_pairs", ctypes.c_size_t),
        ("max_hits", ctypes.c_size_t),
    ]


class IntersectionStruct(ctypes.Structure):
    """``BzjIntersection`` (layout fixed by the C header)."""

    _fields_ = [
        ("u", ctypes.c_double),
        ("v", ctypes.c_double),
        ("u_end", ctypes.c_double),
        ("v_end", ctypes.c_double),
        ("distance", ctypes.c_double),
        ("kind", ctypes.c_int32),
    ]


register_prototype(
    "bzj_intersect_options_default",
    ctypes.c_int32,
    [ctypes.POINTER(IntersectOptionsStruct)],
)
register_prototype(
    "bzj_intersect_detailed",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(IntersectOptionsStruct),
     ctypes.POINTER(IntersectionStruct), ctypes.c_size_t, ctypes.POINTER(ctypes.c_size_t)],
)


#: Crossings asked for in the first call of :func:`intersect` and
#: :func:`intersect_detailed`; when there are more, they ask again with room for all.
FIRST_CAPACITY = 16

#: ``BzjIntersectionKind`` values and their names in :class:`Intersection`.
INTERSECTION_KINDS = {0: "crossing", 1: "touching", 2: "overlap"}

Intersection = namedtuple("Intersection", "u v u_end v_end distance kind")
Intersection.__doc__ = """One place where two curves meet (``BzjIntersection``).

``kind`` is ``"crossing"``, ``"touching"`` or ``"overlap"``. ``u``, ``v``: the
parameters on P and Q (for an overlap, of its start); ``u_end``, ``v_end``: the
end of an overlap (P(u_end) = Q(v_end)), equal to ``u``, ``v`` otherwise;
``distance = |P(u) - Q(v)|``."""


class FilletResult(CurveGroup):
    """The rounded corner: ``p_trimmed = P|[0,u0]``, ``blend``, ``q_trimmed = Q|[v0,1]``,
    each over ``[0, 1]``; together a C^min(p_order, q_order) B-spline with knot
    intervals ``(u0, p_scale, (1 - v0) p_scale / q_scale)``. ``scale`` is the
    ``s = p_scale = q_scale`` the library chose when the scale was automatic (the
    default, see :func:`fillet`), else ``None`` (explicit or balanced scales).
    ``scales`` is ``(p_scale, q_scale)`` as used: the given ones, ``(s, s)``, or the
    balanced scales ``(sigma / |P'(u0)|, sigma / |Q'(v0)|)``.

    ``u0`` and ``v0`` are not reported by the C function; they are the
    parameters where the kept parts end/start, recoverable from the setbacks.
    """

    _curve_fields = ("p_trimmed", "blend", "q_trimmed")

    def __init__(self, p_trimmed, blend, q_trimmed, scale=None, scales=None):
        self.p_trimmed = p_trimmed
        self.blend = blend
        self.q_trimmed = q_trimmed
        self.scale = scale
        self.scales = (scale, scale) if scales is None and scale is not None else scales


def _corner(automatic, handles, options, gap, given):
    """``bzj_fillet`` (``gap`` None) or ``bzj_fillet_vertex``, or their automatic or
    balanced variant, as a :class:`FilletResult`."""
    p_trimmed, blend, q_trimmed = CurvePointer(), CurvePointer(), CurvePointer()
    arguments = [*handles, ctypes.byref(options)] + ([] if gap is None else [gap])
    arguments += [ctypes.byref(p_trimmed), ctypes.byref(blend), ctypes.byref(q_trimmed)]
    call = library().call
    scale, scales = None, given
    if automatic == BALANCED:
        alpha, beta = ctypes.c_double(), ctypes.c_double()
        outs = (ctypes.byref(alpha), ctypes.byref(beta))
        if gap is None:
            call("bzj_fillet_balanced_scale", *arguments, *outs)
        else:
            call("bzj_fillet_vertex_balanced_scale", *arguments, *outs)
        scales = (alpha.value, beta.value)
    elif automatic:
        s = ctypes.c_double()
        if gap is None:
            call("bzj_fillet_auto_scale", *arguments, ctypes.byref(s))
        else:
            call("bzj_fillet_vertex_auto_scale", *arguments, ctypes.byref(s))
        scale, scales = s.value, (s.value, s.value)
    elif gap is None:
        call("bzj_fillet", *arguments)
    else:
        call("bzj_fillet_vertex", *arguments)
    return FilletResult(Curve._adopt(p_trimmed), Curve._adopt(blend), Curve._adopt(q_trimmed),
                        scale, scales)


def _fillet_options(function, p, q, setback, p_setback, q_setback, p_order, q_order, p_scale,
                    q_scale):
    """``BzjFilletOptions`` from the keyword arguments of :func:`fillet`."""
    if setback is not None:
        if p_setback is not None or q_setback is not None:
            raise TypeError("give either setback or p_setback/q_setback, not both")
        p_setback = q_setback = setback
    if p_setback is None or q_setback is None:
        raise TypeError(f"{function} needs setback, or both p_setback and q_setback")
    p_order = p.degree if p_order is None else index_argument(p_order, "p_order")
    q_order = q.degree if q_order is None else index_argument(q_order, "q_order")
    return FilletOptionsStruct(
        real_argument(p_setback, "p_setback"), real_argument(q_setback, "q_setback"),
        p_order, q_order, real_argument(p_scale, "p_scale"), real_argument(q_scale, "q_scale"),
    )


def fillet(p, q, *, setback=None, p_setback=None, q_setback=None, p_order=None, q_order=None,
           p_scale=None, q_scale=None, auto_scale=None):
    """Round the corner "along ``p`` up to the first crossing ``X``, then along ``q``".

    The crossing is the one with the smallest parameter on ``p``. ``p`` is
    kept on ``[0, u0]`` with ``len(p; u0..u*) = p_setback`` and ``q`` on
    ``[v0, 1]`` with ``len(q; v*..v0) = q_setback`` (arc lengths from ``X``);
    the blend is :func:`bezjoin.connect` of those ends. Other corners of the
    crossing: reverse ``p`` and/or ``q`` first.

    By default the scale is automatic (``bzj_fillet_auto_scale``): ``p_scale =
    q_scale = s`` minimising the blend's fairness energy, returned as
    ``result.scale``. The paper's scale 1 loops past the corner when the curves
    are fast against the setback (two lines 40 and 20 long with setback 2 give
    a self-intersecting blend); the default never does that. Pass
    ``p_scale``/``q_scale`` (or ``auto_scale=False`` for the paper's 1.0) for
    the raw construction, exactly as before.

    Args:
        setback: both setbacks (symmetric rounding); or give ``p_setback``
            and ``q_setback`` (asymmetric).
        p_order, q_order: continuity orders (default: the curve's degree).
        p_scale, q_scale: explicit shape scales ``alpha, beta > 0`` (1.0 = the
            paper; a missing one is 1.0 when the other is given). Giving
            either turns the automatic scale off.
        auto_scale: ``None`` (default): automatic unless a scale is given;
            ``True``: automatic, given scales are ignored; ``False``: the
            given scales (1.0 when none are given); ``"balanced"``: the blend
            leaves both curves at one speed (``bzj_fillet_balanced_scale``,
            ``result.scales``), so it does not depend on how fast either curve
            runs in its own parameter (lines 1000 and 10 long get the blend of
            lines 10 and 10; with ``True`` the short one's end is a near-kink).

    Raises:
        BezjoinError: ``BZJ_ERR_NO_INTERSECTION`` when the curves do not cross
            (or only touch), ``BZJ_ERR_INVALID_ARGUMENT`` for a setback longer
            than the curve part, ...
    """
    handles = (handle_of(p, "p"), handle_of(q, "q"))
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale, balanced=True)
    options = _fillet_options("fillet", p, q, setback, p_setback, q_setback, p_order, q_order,
                              p_scale, q_scale)
    return _corner(automatic, handles, options, None, (p_scale, q_scale))


def fillet_vertex(p, q, *, setback=None, p_setback=None, q_setback=None, p_order=None,
                  q_order=None, p_scale=None, q_scale=None, auto_scale=None, gap=1e-7):
    """Round the corner at the vertex where ``p`` ends and ``q`` starts
    (``bzj_fillet_vertex``): a wire's or a sketch's vertex, whatever other
    crossings ``p`` and ``q`` have. ``p``'s last point and ``q``'s first
    point must lie within ``gap`` (absolute; sketch solvers leave 1e-7 and
    more). Setbacks are arc lengths back from ``p``'s end and on from
    ``q``'s start; the other arguments are those of :func:`fillet`, with the
    same default: the automatic scale (``bzj_fillet_vertex_auto_scale``,
    ``result.scale``), which never loops, unless ``p_scale``/``q_scale`` are
    given (or ``auto_scale=False``); ``auto_scale="balanced"``
    (``bzj_fillet_vertex_balanced_scale``) leaves both edges at one speed, so the
    blend depends on the corner and the setbacks only, not on the edges' lengths
    or parametrisations. NURBS inputs give NURBS pieces with their
    own parameters; the blend is a Bezier curve.

    Raises:
        BezjoinError: ``BZJ_ERR_NO_INTERSECTION`` when the ends are more
            than ``gap`` apart (the message gives the distance) or the path
            doubles back at the vertex (opposite tangents: a cusp, no corner),
            ``BZJ_ERR_INVALID_ARGUMENT`` for a setback longer than a curve.
    """
    handles = (handle_of(p, "p"), handle_of(q, "q"))
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale, balanced=True)
    options = _fillet_options("fillet_vertex", p, q, setback, p_setback, q_setback, p_order,
                              q_order, p_scale, q_scale)
    gap = real_argument(gap, "gap")
    return _corner(automatic, handles, options, gap, (p_scale, q_scale))


def intersect(p, q):
    """All crossings of ``p`` and ``q`` as ``(u, v)`` pairs ordered by ``u``."""
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    buffer, count = _all_hits(
        lambda capacity: (ctypes.c_double * (2 * capacity))(),
        lambda buffer, capacity, count: library().call(
            "bzj_intersect", p_handle, q_handle, buffer, capacity, count))
    return [(buffer[2 * i], buffer[2 * i + 1]) for i in range(count)]


def _all_hits(make_buffer, call):
    """Call ``call(buffer, capacity, count_pointer)`` with a buffer from
    ``make_buffer(capacity)``, first with room for :data:`FIRST_CAPACITY` hits and,
    when the library reports more, once more with room for all; return the buffer
    and the number of hits."""
    capacity = FIRST_CAPACITY
    while True:
        buffer = make_buffer(capacity)
        count = ctypes.c_size_t()
        call(buffer, capacity, ctypes.byref(count))
        if count.value <= capacity:
            return buffer, count.value
        capacity = count.value


def intersect_detailed(p, q, *, relative_distance_tolerance=None, tangent_tolerance=None,
                       max_depth=None, max_box_pairs=None, max_hits=None):
    """All places where ``p`` and ``q`` meet, ordered by ``u``, as :class:`Intersection`
    tuples that say what each hit is: a crossing, a touching point, or an overlap
    with its range (``bzj_intersect_detailed``).

    The keyword options are those of ``BzjIntersectOptions``; ``None`` keeps the
    library's default (``bzj_intersect_options_default``). :func:`intersect` is the
    same search with the default options, returning only the ``(u, v)`` pairs.

    Raises:
        BezjoinError: ``BZJ_ERR_INVALID_ARGUMENT`` for an option out of its range or
            curves of dimension 1, ``BZJ_ERR_NON_FINITE`` for a NaN or infinite
            tolerance, ``BZJ_ERR_DIMENSION_MISMATCH``, ``BZJ_ERR_ILL_CONDITIONED``
            when a work bound is reached.
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    options = IntersectOptionsStruct()
    library().call("bzj_intersect_options_default", ctypes.byref(options))
    for name, value, convert in (
            ("relative_distance_tolerance", relative_distance_tolerance, real_argument),
            ("tangent_tolerance", tangent_tolerance, real_argument),
            ("max_depth", max_depth, index_argument),
            ("max_box_pairs", max_box_pairs, index_argument),
            ("max_hits", max_hits, index_argument)):
        if value is not None:
            setattr(options, name, convert(value, name))
    buffer, count = _all_hits(
        lambda capacity: (IntersectionStruct * capacity)(),
        lambda buffer, capacity, count: library().call(
            "bzj_intersect_detailed", p_handle, q_handle, ctypes.byref(options),
            buffer, capacity, count))
    hits = []
    for hit in buffer[:count]:
        if hit.kind not in INTERSECTION_KINDS:
            raise RuntimeError(f"libbezjoin returned intersection kind {hit.kind}, "
                               "unknown to these bindings")
        hits.append(Intersection(hit.u, hit.v, hit.u_end, hit.v_end, hit.distance,
                                 INTERSECTION_KINDS[hit.kind]))
    return hits


class DeviationFilletOptionsStruct(ctypes.Structure):
    """``BzjDeviationFilletOptions`` (layout fixed by the C header)."""

    _fields_ = [
        ("max_deviation", ctypes.c_double),
        ("setback_ratio", ctypes.c_double),
        ("p_order", ctypes.c_size_t),
        ("q_order", ctypes.c_size_t),
        ("p_scale", ctypes.c_double),
        ("q_scale", ctypes.c_double),
    ]


class DeviationFilletReportStruct(ctypes.Structure):
    """``BzjDeviationFilletReport`` (layout fixed by the C header)."""

    _fields_ = [
        ("p_setback", ctypes.c_double),
        ("q_setback", ctypes.c_double),
        ("deviation", ctypes.c_double),
        ("u0", ctypes.c_double),
        ("v0", ctypes.c_double),
    ]


register_prototype(
    "bzj_fillet_deviation",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(DeviationFilletOptionsStruct), _curve_out,
     _curve_out, _curve_out, ctypes.POINTER(DeviationFilletReportStruct)],
)
register_prototype(
    "bzj_fillet_deviation_auto_scale",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.POINTER(DeviationFilletOptionsStruct), _curve_out,
     _curve_out, _curve_out, ctypes.POINTER(DeviationFilletReportStruct),
     ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_chain",
    ctypes.c_int32,
    [ctypes.POINTER(CurvePointer), ctypes.c_size_t, ctypes.POINTER(FilletOptionsStruct),
     ctypes.c_int32, ctypes.POINTER(CurvePointer), ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_size_t)],
)
register_prototype(
    "bzj_fillet_chain_auto_scale",
    ctypes.c_int32,
    [ctypes.POINTER(CurvePointer), ctypes.c_size_t, ctypes.POINTER(FilletOptionsStruct),
     ctypes.c_int32, ctypes.POINTER(CurvePointer), ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_chain_balanced_scale",
    ctypes.c_int32,
    [ctypes.POINTER(CurvePointer), ctypes.c_size_t, ctypes.POINTER(FilletOptionsStruct),
     ctypes.c_int32, ctypes.POINTER(CurvePointer), ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(ctypes.c_double)],
)


class DeviationFilletResult(FilletResult):
    """The corner rounded by :func:`fillet_deviation`: ``p_trimmed``, ``blend``,
    ``q_trimmed`` as in :class:`FilletResult`, and the report: the setbacks found
    (``p_setback``, ``q_setback = setback_ratio * p_setback``, arc lengths from the
    crossing), the ``deviation`` achieved (``min_t |R(t) - X|``) and the cut
    parameters ``u0`` on P and ``v0`` on Q. ``scale``: the ``s = p_scale = q_scale``
    used when the scale was automatic (the default), else ``None``."""

    def __init__(self, p_trimmed, blend, q_trimmed, report, scale=None):
        super().__init__(p_trimmed, blend, q_trimmed, scale)
        self.p_setback = report.p_setback
        self.q_setback = report.q_setback
        self.deviation = report.deviation
        self.u0 = report.u0
        self.v0 = report.v0

    def _fields(self):
        return self._curve_fields + ("p_setback", "q_setback", "deviation", "u0", "v0", "scale")


def _deviation_call(p_handle, q_handle, options, automatic):
    """``bzj_fillet_deviation`` (or ``bzj_fillet_deviation_auto_scale`` when
    ``automatic``) with ``options``: the three handles (adopted), the report and the
    scale chosen (``None`` unless automatic)."""
    p_trimmed, blend, q_trimmed = CurvePointer(), CurvePointer(), CurvePointer()
    report = DeviationFilletReportStruct()
    outs = (ctypes.byref(p_trimmed), ctypes.byref(blend), ctypes.byref(q_trimmed))
    if automatic:
        scale = ctypes.c_double()
        library().call("bzj_fillet_deviation_auto_scale", p_handle, q_handle,
                       ctypes.byref(options), *outs, ctypes.byref(report), ctypes.byref(scale))
        chosen = scale.value
    else:
        library().call("bzj_fillet_deviation", p_handle, q_handle, ctypes.byref(options),
                       *outs, ctypes.byref(report))
        chosen = None
    curves = (Curve._adopt(p_trimmed), Curve._adopt(blend), Curve._adopt(q_trimmed))
    return curves, report, chosen


def fillet_deviation(p, q, max_deviation, *, setback_ratio=1.0, p_order=None, q_order=None,
                     p_scale=None, q_scale=None, auto_scale=None):
    """Round the corner at the first crossing ``X`` so that the blend passes within
    ``max_deviation`` of ``X``, using nearly all of it (``bzj_fillet_deviation``):
    ``max_deviation (1 - 1e-9) <= min_t |R(t) - X| <= max_deviation (1 - 2.5e-10)``,
    never above. The setbacks ``dp`` and ``dq = setback_ratio * dp`` are found by
    the library; the blend is that of :func:`fillet` with them.

    By default the scale is automatic (``bzj_fillet_deviation_auto_scale``), so the
    blend does not loop past the corner as the paper's scale 1 does when the curves
    are fast against the setbacks: at every setback the library tries,
    ``p_scale = q_scale = s`` is chosen as :func:`fillet` chooses it (least fairness
    energy); the ``s`` of the result is ``result.scale``. The deviation bound is the
    same. Give ``p_scale``/``q_scale`` (or ``auto_scale=False`` for the paper's
    1.0) for those scales (``bzj_fillet_deviation``), as before.

    Args:
        max_deviation: the largest distance allowed between ``X`` and the blend, > 0.
        setback_ratio: ``dq / dp`` > 0 (1.0 = symmetric rounding).
        p_order, q_order: continuity orders (default: the curve's degree).
        p_scale, q_scale, auto_scale: as for :func:`fillet`.

    Returns:
        :class:`DeviationFilletResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_INVALID_ARGUMENT`` when ``max_deviation`` cannot be
            reached even with the longest setbacks (the message gives the largest
            possible), ``BZJ_ERR_NO_INTERSECTION`` when the curves do not cross, ...
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale)
    p_order = p.degree if p_order is None else index_argument(p_order, "p_order")
    q_order = q.degree if q_order is None else index_argument(q_order, "q_order")
    options = DeviationFilletOptionsStruct(
        real_argument(max_deviation, "max_deviation"),
        real_argument(setback_ratio, "setback_ratio"), p_order, q_order, p_scale, q_scale,
    )
    curves, report, scale = _deviation_call(p_handle, q_handle, options, automatic)
    return DeviationFilletResult(*curves, report, scale)


class FilletChainResult(CurveGroup):
    """Every corner of a chain rounded (:func:`fillet_chain`): ``pieces`` in path
    order, trimmed curve 0, blend 0, trimmed curve 1, ... (``2n - 1`` curves for an
    open chain of ``n`` curves, ``2n`` for a closed one, ending with the blend back
    to the start). ``trimmed`` and ``blends`` are the two kinds, each in order.
    ``scales``: the scale ``s`` chosen at every corner (corner ``i`` at index ``i``)
    when the scale was automatic (the default), else ``None``. ``corner_scales``:
    ``(p_scale, q_scale)`` used at every corner, whatever chose them (given, ``(s,
    s)``, or the balanced ``(sigma / |P'(u0)|, sigma / |Q'(v0)|)`` of
    ``auto_scale="balanced"``). ``close()`` releases them all."""

    _curve_fields = ("pieces",)

    def __init__(self, pieces, closed, scales=None, corner_scales=None):
        self.pieces = pieces
        self.closed = closed
        self.scales = scales
        if corner_scales is None and scales is not None:
            corner_scales = [(s, s) for s in scales]
        self.corner_scales = corner_scales

    @property
    def trimmed(self):
        """The kept part of every curve, in chain order."""
        return self.pieces[0::2]

    @property
    def blends(self):
        """The blend of every corner, in chain order."""
        return self.pieces[1::2]

    def _fields(self):
        return self._curve_fields + ("closed", "scales")


def _chain_handles(curves, closed):
    """The curves as a list, their handles as a C array (errors name ``curves[i]``),
    and ``closed`` checked to be a bool."""
    curves = list(curves)
    handles = [handle_of(c, f"curves[{i}]") for i, c in enumerate(curves)]
    if not isinstance(closed, bool):
        raise TypeError(f"closed must be a bool, not {type(closed).__name__}")
    return curves, (CurvePointer * max(len(handles), 1))(*handles), len(handles)


def _corner_count(curve_count, closed):
    return curve_count if closed else max(curve_count - 1, 0)


def fillet_chain(curves, *, setback=None, p_setback=None, q_setback=None, p_order=None,
                 q_order=None, p_scale=None, q_scale=None, auto_scale=None, closed=False):
    """Round every corner of a chain of curves in one call (``bzj_fillet_chain``).

    Corner ``i`` lies between ``curves[i]`` and ``curves[i + 1]`` (and, with
    ``closed=True``, between the last curve and the first); its crossing is the
    one nearest the shared end, rounded as :func:`fillet` rounds one corner, with
    the same options at every corner (``p`` is the curve before the corner, ``q``
    the one after). Each curve is kept between the cuts of its two corners.

    By default every corner gets its automatic scale
    (``bzj_fillet_chain_auto_scale``; ``result.scales``), which never loops;
    giving ``p_scale``/``q_scale`` (or ``auto_scale=False``) uses those scales
    at every corner, exactly as before (see :func:`fillet`).
    ``auto_scale="balanced"`` (``bzj_fillet_chain_balanced_scale``;
    ``result.corner_scales``) leaves both curves of every corner at one speed,
    so a 1000 x 10 rectangle of lines gets the corners of a 10 x 10 square.

    Args:
        curves: at least two :class:`Curve` objects of one dimension.
        setback, p_setback, q_setback, p_scale, q_scale, auto_scale: as for
            :func:`fillet`.
        p_order, q_order: continuity orders (default: the lowest degree of the
            curves).
        closed: round the corner from the last curve back to the first too.

    Returns:
        :class:`FilletChainResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_NO_INTERSECTION`` naming the corner whose curves do
            not cross, ``BZJ_ERR_INVALID_ARGUMENT`` for a setback too long at a
            corner or fewer than two curves, ...
    """
    curves, array, curve_count = _chain_handles(curves, closed)
    if setback is not None:
        if p_setback is not None or q_setback is not None:
            raise TypeError("give either setback or p_setback/q_setback, not both")
        p_setback = q_setback = setback
    if p_setback is None or q_setback is None:
        raise TypeError("fillet_chain needs setback, or both p_setback and q_setback")
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale, balanced=True)
    lowest = min((c.degree for c in curves), default=0)
    p_order = lowest if p_order is None else index_argument(p_order, "p_order")
    q_order = lowest if q_order is None else index_argument(q_order, "q_order")
    options = FilletOptionsStruct(
        real_argument(p_setback, "p_setback"), real_argument(q_setback, "q_setback"),
        p_order, q_order, p_scale, q_scale,
    )
    count = ctypes.c_size_t()
    corners = _corner_count(curve_count, closed)
    names = {False: "bzj_fillet_chain", True: "bzj_fillet_chain_auto_scale",
             BALANCED: "bzj_fillet_chain_balanced_scale"}
    extra = () if automatic is False else (None,)
    # The count-only query checks the curves and `closed` the way the real call does.
    library().call(names[automatic], array, curve_count, ctypes.byref(options), int(closed),
                   None, 0, ctypes.byref(count), *extra)
    pieces = (CurvePointer * max(count.value, 1))()
    arguments = (array, curve_count, ctypes.byref(options), int(closed), pieces, count.value,
                 ctypes.byref(count))

    def result(**scales):
        return FilletChainResult([Curve._adopt(pieces[i]) for i in range(count.value)], closed,
                                 **scales)

    if automatic == BALANCED:
        scales = (ctypes.c_double * max(2 * corners, 1))()
        library().call("bzj_fillet_chain_balanced_scale", *arguments, scales)
        return result(corner_scales=[(scales[2 * i], scales[2 * i + 1]) for i in range(corners)])
    if automatic:
        scales = (ctypes.c_double * max(corners, 1))()
        library().call("bzj_fillet_chain_auto_scale", *arguments, scales)
        return result(scales=list(scales)[:corners])
    library().call("bzj_fillet_chain", *arguments)
    return result(corner_scales=[(p_scale, q_scale)] * corners)


from ._connect import FairnessReportStruct  # noqa: E402  (defined with connect_geometric)

register_prototype(
    "bzj_fillet_radius",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.c_double, ctypes.c_size_t,
     ctypes.POINTER(CurvePointer), ctypes.POINTER(CurvePointer), ctypes.POINTER(CurvePointer),
     ctypes.POINTER(FairnessReportStruct)],
)


class RadiusFilletReportStruct(ctypes.Structure):
    """``BzjRadiusFilletReport`` (layout fixed by the C header)."""

    _fields_ = [
        ("fairness", FairnessReportStruct),
        ("arc_deviation", ctypes.c_double),
        ("u0", ctypes.c_double),
        ("v0", ctypes.c_double),
    ]


register_prototype(
    "bzj_fillet_radius_detailed",
    ctypes.c_int32,
    [CurvePointer, CurvePointer, ctypes.c_double, ctypes.c_size_t,
     ctypes.POINTER(CurvePointer), ctypes.POINTER(CurvePointer), ctypes.POINTER(CurvePointer),
     ctypes.POINTER(RadiusFilletReportStruct), ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_fillet_radius_chain",
    ctypes.c_int32,
    [ctypes.POINTER(CurvePointer), ctypes.c_size_t, ctypes.c_double, ctypes.c_size_t,
     ctypes.c_int32, ctypes.POINTER(CurvePointer), ctypes.c_size_t,
     ctypes.POINTER(ctypes.c_size_t), ctypes.POINTER(RadiusFilletReportStruct)],
)


class RadiusFilletResult(CurveGroup):
    """:func:`fillet_radius`'s corner: ``p_trimmed``, the G^k ``blend`` and
    ``q_trimmed`` (NURBS pieces keep their parameters), with the blend's fairness
    report: ``energy``, ``curvature_min``, ``curvature_max`` and
    ``curvature_extrema``."""

    _curve_fields = ("p_trimmed", "blend", "q_trimmed")

    def __init__(self, p_trimmed, blend, q_trimmed, report):
        self.p_trimmed = p_trimmed
        self.blend = blend
        self.q_trimmed = q_trimmed
        self.energy = report.energy
        self.curvature_min = report.curvature_min
        self.curvature_max = report.curvature_max
        self.curvature_extrema = report.curvature_extrema

    def _fields(self):
        return self._curve_fields + ("energy", "curvature_min", "curvature_max",
                                     "curvature_extrema")


def fillet_radius(p, q, radius, *, order=2):
    """Round the corner of ``p`` and ``q`` like the circular fillet of ``radius``
    (cut where that arc touches them), with a G^order blend of fair shape
    (``bzj_fillet_radius``): at the shared vertex when ``p`` ends where ``q``
    starts, else at the first crossing. Default G2. There are no scales: the
    blend is sized by the arc and never loops. :func:`fillet_radius_detailed`
    also returns the arc's centre, the blend's distance from the arc and the cut
    parameters; :func:`fillet_radius_chain` rounds every corner of a wire.

    Returns:
        :class:`RadiusFilletResult`.
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    outs = (CurvePointer(), CurvePointer(), CurvePointer())
    report = FairnessReportStruct()
    library().call("bzj_fillet_radius", p_handle, q_handle, real_argument(radius, "radius"),
                   index_argument(order, "order"), *(ctypes.byref(o) for o in outs),
                   ctypes.byref(report))
    return RadiusFilletResult(*(Curve._adopt(o) for o in outs), report)


RadiusCornerReport = namedtuple(
    "RadiusCornerReport",
    "energy curvature_min curvature_max curvature_extrema arc_deviation u0 v0")
RadiusCornerReport.__doc__ = """What a fillet by radius found at one corner
(``BzjRadiusFilletReport``): the blend's fairness report (``energy``,
``curvature_min``, ``curvature_max``, ``curvature_extrema``), its largest distance
``arc_deviation`` from the circle of the G1 arc of the same radius in that corner,
and the arc's touching points ``u0`` on the curve before the corner and ``v0`` on
the curve after it (where they are cut)."""


def _corner_report(report):
    fairness = report.fairness
    return RadiusCornerReport(fairness.energy, fairness.curvature_min, fairness.curvature_max,
                              fairness.curvature_extrema, report.arc_deviation, report.u0,
                              report.v0)


class DetailedRadiusFilletResult(RadiusFilletResult):
    """:func:`fillet_radius_detailed`'s corner: everything of
    :class:`RadiusFilletResult`, plus ``arc_centre`` (the centre of the G1 arc of
    that radius, a tuple of ``dim`` coordinates), ``arc_deviation`` (the blend's
    largest distance from that arc's circle), ``u0`` and ``v0`` (the arc's touching
    points: where ``p`` and ``q`` are cut), and ``report`` (the same as a
    :class:`RadiusCornerReport`)."""

    def __init__(self, p_trimmed, blend, q_trimmed, report, arc_centre):
        super().__init__(p_trimmed, blend, q_trimmed, report.fairness)
        self.report = _corner_report(report)
        self.arc_deviation = report.arc_deviation
        self.u0 = report.u0
        self.v0 = report.v0
        self.arc_centre = tuple(arc_centre)

    def _fields(self):
        return super()._fields() + ("arc_centre", "arc_deviation", "u0", "v0")


def fillet_radius_detailed(p, q, radius, *, order=2):
    """:func:`fillet_radius` with more of what the library found
    (``bzj_fillet_radius_detailed``): the arc's centre, the blend's largest
    distance from the arc's circle and the cut parameters ``u0``, ``v0``.

    Returns:
        :class:`DetailedRadiusFilletResult`.

    Raises:
        BezjoinError: as :func:`fillet_radius` (``BZJ_ERR_INVALID_ARGUMENT`` naming
            ``radius`` when the arc does not fit or ``radius`` is not > 0, or
            ``order`` when it is 0 or above 6; ``BZJ_ERR_NO_INTERSECTION`` when
            there is no corner).
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    radius = real_argument(radius, "radius")
    order = index_argument(order, "order")
    outs = (CurvePointer(), CurvePointer(), CurvePointer())
    report = RadiusFilletReportStruct()
    centre = (ctypes.c_double * max(p.dim, 1))()
    library().call("bzj_fillet_radius_detailed", p_handle, q_handle, radius, order,
                   *(ctypes.byref(o) for o in outs), ctypes.byref(report), centre)
    return DetailedRadiusFilletResult(*(Curve._adopt(o) for o in outs), report,
                                      list(centre)[:p.dim])


class RadiusFilletChainResult(FilletChainResult):
    """Every corner of a chain rounded by radius (:func:`fillet_radius_chain`):
    ``pieces``, ``trimmed``, ``blends`` and ``closed`` as in
    :class:`FilletChainResult`, and ``reports``: one :class:`RadiusCornerReport`
    per corner (corner ``i``, between ``curves[i]`` and the next curve, at index
    ``i``). ``close()`` releases every curve."""

    def __init__(self, pieces, closed, reports):
        super().__init__(pieces, closed)
        self.reports = reports

    def _fields(self):
        return self._curve_fields + ("closed", "reports")


def fillet_radius_chain(curves, radius, *, order=2, closed=False):
    """Round every corner of a chain of curves (a wire) like the G1 arc of ``radius``,
    with a fair G^order blend at each (``bzj_fillet_radius_chain``; default G2).

    Corner ``i`` lies between ``curves[i]`` and ``curves[i + 1]`` (and, with
    ``closed=True``, between the last curve and the first): their shared vertex
    when one ends where the next starts (within 1e-9 of their coordinate size),
    else their crossing nearest the shared end. Each is rounded as
    :func:`fillet_radius` rounds one corner; there are no scales, and the blends
    never loop.

    Args:
        curves: at least two :class:`Curve` objects (Bezier or NURBS) of one
            dimension.
        radius: the radius of the arc every corner is sized like, > 0.
        order: the geometric continuity order of the blends (1..6).
        closed: round the corner from the last curve back to the first too.

    Returns:
        :class:`RadiusFilletChainResult`.

    Raises:
        BezjoinError: ``BZJ_ERR_INVALID_ARGUMENT`` when the arc does not fit a
            corner (naming the corner and ``radius``), the arcs at a curve's two
            ends overlap (naming ``curves[i]``), fewer than two curves are
            given or ``order`` is out of range; ``BZJ_ERR_NO_INTERSECTION``
            naming a corner without vertex or crossing, or one where the curves
            meet tangent (nothing to round: round a wire with tangent joins in
            its runs between them, as the FreeCAD workbench does), ...
    """
    curves, array, curve_count = _chain_handles(curves, closed)
    radius = real_argument(radius, "radius")
    order = index_argument(order, "order")
    count = ctypes.c_size_t()
    # The count-only query checks the curves and `closed` the way the real call does.
    library().call("bzj_fillet_radius_chain", array, curve_count, radius, order, int(closed),
                   None, 0, ctypes.byref(count), None)
    pieces = (CurvePointer * max(count.value, 1))()
    corners = _corner_count(curve_count, closed)
    reports = (RadiusFilletReportStruct * max(corners, 1))()
    library().call("bzj_fillet_radius_chain", array, curve_count, radius, order, int(closed),
                   pieces, count.value, ctypes.byref(count), reports)
    return RadiusFilletChainResult([Curve._adopt(pieces[i]) for i in range(count.value)],
                                   closed, [_corner_report(r) for r in reports[:corners]])
