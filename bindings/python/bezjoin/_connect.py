"""Connect two curves with a Bezier curve of prescribed end continuity (``bzj_connect``).

Krivosheev, Mavrin, Starkova, "Bezier curve conjugation for smooth curve
joining and corner rounding", Omsk Scientific Bulletin, 2025 (mathematics.md
section 1).
"""

import ctypes

from . import _freecad
from ._convert import (BALANCED, _array_type, automatic_scale, double_array, flat,
                       index_argument, point_rows, real_argument)
from ._library import CurvePointer, function, library, register_prototype
from .curve import Curve, handle_of
from .errors import BezjoinError
from .results import CurveGroup


class PointConstraintStruct(ctypes.Structure):
    """``BzjPointConstraint`` (layout fixed by the C contract)."""

    _fields_ = [
        ("t", ctypes.c_double),
        ("max_order", ctypes.c_size_t),
        ("values", ctypes.POINTER(ctypes.c_double)),
    ]


class ConnectOptionsStruct(ctypes.Structure):
    """``BzjConnectOptions`` (layout fixed by the C contract)."""

    _fields_ = [
        ("p_order", ctypes.c_size_t),
        ("q_order", ctypes.c_size_t),
        ("p_scale", ctypes.c_double),
        ("q_scale", ctypes.c_double),
        ("constraints", ctypes.POINTER(PointConstraintStruct)),
        ("constraint_count", ctypes.c_size_t),
    ]


register_prototype(
    "bzj_connect_auto_scale",
    ctypes.c_int32,
    [CurvePointer, ctypes.c_double, CurvePointer, ctypes.c_double,
     ctypes.POINTER(ConnectOptionsStruct), ctypes.POINTER(CurvePointer),
     ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_connect_balanced_scale",
    ctypes.c_int32,
    [CurvePointer, ctypes.c_double, CurvePointer, ctypes.c_double,
     ctypes.POINTER(ConnectOptionsStruct), ctypes.POINTER(CurvePointer),
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)],
)
register_prototype(
    "bzj_connect",
    ctypes.c_int32,
    [CurvePointer, ctypes.c_double, CurvePointer, ctypes.c_double,
     ctypes.POINTER(ConnectOptionsStruct), ctypes.POINTER(CurvePointer)],
)


def connect(p, u0, q, v0, *, p_order=None, q_order=None, p_scale=None, q_scale=None,
            constraints=(), auto_scale=None):
    """The Bezier curve ``R`` from ``P(u0)`` to ``Q(v0)`` with

    ``R^(k)(0) = p_scale^k P^(k)(u0)`` for ``k = 0..p_order`` and
    ``R^(k)(1) = q_scale^k Q^(k)(v0)`` for ``k = 0..q_order``,

    of degree ``p_order + q_order + 1 + sum(K_j + 1)`` (Theorems 1 and 2).
    The chain ``P|[0,u0]``, ``R``, ``Q|[v0,1]`` is a C^min(p_order, q_order)
    B-spline with knot intervals ``(u0, p_scale, (1 - v0) p_scale / q_scale)``.

    By default the scale is automatic: ``p_scale = q_scale = s`` chosen by the
    library to minimise the fairness energy (``bzj_connect_auto_scale``; use
    :func:`connect_auto_scale` to learn ``s``), so a short gap between fast
    curves does not loop as the paper's scale 1 can. Give ``p_scale`` and/or
    ``q_scale`` (or ``auto_scale=False`` for the paper's 1.0) for the raw
    construction, exactly as before.

    ``p`` and ``q`` may be Bezier or NURBS curves; ``R`` is a Bezier curve. At
    a knot of a NURBS curve, P's derivatives are taken from the left of ``u0``
    and Q's from the right of ``v0``.

    Args:
        p, q: :class:`Curve` objects of the same dimension.
        u0, v0: parameters in the domains of ``p`` and ``q`` (``[0, 1]`` for a
            Bezier curve).
        p_order, q_order: continuity orders, any (above a polynomial's degree
            its derivatives are 0); default: the curve's degree, as in the
            paper.
        p_scale, q_scale: explicit shape scales ``alpha, beta > 0`` (1.0 = the
            paper; a missing one is 1.0 when the other is given). Giving
            either turns the automatic scale off.
        constraints: ``(t, derivatives)`` pairs: ``R`` passes at ``t`` in
            ``(0, 1)`` with ``R^(k)(t) = derivatives[k]``, ``k = 0..K``.
        auto_scale: ``None`` (default): automatic unless a scale is given;
            ``True``: automatic, given scales are ignored; ``False``: the given
            scales (1.0 when none are given); ``"balanced"``: the blend leaves
            both curves at one speed (:func:`connect_balanced_scale`), the same
            blend however fast either curve runs in its own parameter.

    Raises:
        BezjoinError: with the library's status and message.
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale, balanced=True)
    options, _keep_alive = _options(p, q, p_order, q_order, p_scale, q_scale, constraints)
    out = CurvePointer()
    if automatic == BALANCED:
        library().call("bzj_connect_balanced_scale", p_handle, real_argument(u0, "u0"),
                       q_handle, real_argument(v0, "v0"), ctypes.byref(options),
                       ctypes.byref(out), None, None)
    elif automatic:
        library().call("bzj_connect_auto_scale", p_handle, real_argument(u0, "u0"), q_handle,
                       real_argument(v0, "v0"), ctypes.byref(options), ctypes.byref(out), None)
    else:
        library().call("bzj_connect", p_handle, real_argument(u0, "u0"), q_handle,
                       real_argument(v0, "v0"), ctypes.byref(options), ctypes.byref(out))
    # R is a Bezier curve of degree p_order + q_order + 1 (no constraints) in P's
    # dimension: known without asking when P's dimension is.
    known = p._bezier_shape
    shape = None
    if known is not None and options.constraint_count == 0:
        shape = (options.p_order + options.q_order + 1, known[1])
    return Curve._adopt(out, shape)


class AutoScaledConnection(CurveGroup):
    """The connecting ``curve`` and the ``scale`` ``s = alpha = beta`` chosen for it."""

    _curve_fields = ("curve",)

    def __init__(self, curve, scale):
        self.curve = curve
        self.scale = scale

    def _fields(self):
        return self._curve_fields + ("scale",)


def connect_auto_scale(p, u0, q, v0, *, p_order=None, q_order=None, constraints=()):
    """:func:`connect` with ``p_scale = q_scale = s`` chosen by the library to minimise
    the fairness energy ``integral_0^1 |R''(t)|^2 dt`` (bounded search over two
    decades either side of ``|Q(v0) - P(u0)| / mean(|P'(u0)|, |Q'(v0)|)``, each speed raised
    to its floor where the end turns within 1 % of the chord). Where that energy is least
    at the range's lower end (ends facing away, whose blend there turns in kinks) and no
    floor applies: the natural scale, or the largest smaller one whose control polygon is
    at most two chords long (docs/mathematics.md).

    Returns:
        :class:`AutoScaledConnection` (``curve``, ``scale``).

    Raises:
        BezjoinError: as :func:`connect`; ``BZJ_ERR_INVALID_ARGUMENT`` naming ``v0``
            where ``Q(v0)`` is within 1e-9 of their largest coordinate from ``P(u0)``
            (between coincident points every blend is a loop).
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    options, _keep_alive = _options(p, q, p_order, q_order, 1.0, 1.0, constraints)
    out = CurvePointer()
    scale = ctypes.c_double()
    library().call("bzj_connect_auto_scale", p_handle, real_argument(u0, "u0"), q_handle,
                   real_argument(v0, "v0"), ctypes.byref(options), ctypes.byref(out),
                   ctypes.byref(scale))
    return AutoScaledConnection(Curve._adopt(out), scale.value)


class BalancedConnection(CurveGroup):
    """The connecting ``curve`` and the scales ``p_scale = sigma / |P'(u0)|``,
    ``q_scale = sigma / |Q'(v0)|`` chosen for it (both ends at the speed ``sigma``)."""

    _curve_fields = ("curve",)

    def __init__(self, curve, p_scale, q_scale):
        self.curve = curve
        self.p_scale = p_scale
        self.q_scale = q_scale

    def _fields(self):
        return self._curve_fields + ("p_scale", "q_scale")


def connect_balanced_scale(p, u0, q, v0, *, p_order=None, q_order=None, constraints=()):
    """:func:`connect` with the blend leaving both curves at one speed ``sigma``
    (``bzj_connect_balanced_scale``): ``p_scale = sigma / |P'(u0)|``, ``q_scale =
    sigma / |Q'(v0)|``, ``sigma`` minimising the fairness energy ``integral_0^1
    |R''(t)|^2 dt`` over two decades either side of the chord ``|Q(v0) - P(u0)|``.
    The blend does not depend on how fast either curve runs in its own parameter
    (a line on ``[0, 1]`` or on ``[0, length]``); with :func:`connect_auto_scale`'s one
    ``s`` a fast curve next to a slow one gets a near-kink at the slow end. The rule at the
    range's lower end and the refusal of coincident ends are
    :func:`connect_auto_scale`'s.

    Returns:
        :class:`BalancedConnection` (``curve``, ``p_scale``, ``q_scale``).
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    options, _keep_alive = _options(p, q, p_order, q_order, 1.0, 1.0, constraints)
    out = CurvePointer()
    alpha, beta = ctypes.c_double(), ctypes.c_double()
    library().call("bzj_connect_balanced_scale", p_handle, real_argument(u0, "u0"), q_handle,
                   real_argument(v0, "v0"), ctypes.byref(options), ctypes.byref(out),
                   ctypes.byref(alpha), ctypes.byref(beta))
    return BalancedConnection(Curve._adopt(out), alpha.value, beta.value)


def _options(p, q, p_order, q_order, p_scale, q_scale, constraints):
    """The C options and the arrays they point into (keep both alive for the call)."""
    p_order = p.degree if p_order is None else index_argument(p_order, "p_order")
    q_order = q.degree if q_order is None else index_argument(q_order, "q_order")
    keep_alive = []
    structs = []
    constraints = list(constraints)
    p_dim = p.dim if constraints else None
    for j, constraint in enumerate(constraints):
        try:
            t, derivatives = constraint
        except (TypeError, ValueError):
            raise TypeError(f"constraints[{j}] must be a (t, derivatives) pair") from None
        rows, dim = point_rows(derivatives, f"constraints[{j}] derivatives")
        if dim != p_dim:
            # The C struct carries no length: a short row would be read past its end.
            raise BezjoinError.dimension_mismatch(
                f"constraints[{j}] derivatives have dimension {dim} but p has dimension {p_dim}"
            )
        array, _length = double_array(flat(rows))
        keep_alive.append(array)
        structs.append(PointConstraintStruct(real_argument(t, f"constraints[{j}] t"),
                                             len(rows) - 1, array))
    constraint_array = (PointConstraintStruct * len(structs))(*structs) if structs else None
    options = ConnectOptionsStruct(
        p_order, q_order, real_argument(p_scale, "p_scale"), real_argument(q_scale, "q_scale"),
        constraint_array, len(structs),
    )
    return options, (keep_alive, constraint_array)


_double_pointer = ctypes.POINTER(ctypes.c_double)
_size = ctypes.c_size_t

register_prototype(
    "bzj_connect_points",
    ctypes.c_int32,
    [_size, _double_pointer, _size, ctypes.c_double, _double_pointer, _size, ctypes.c_double,
     _size, _size, ctypes.c_double, ctypes.c_double, _double_pointer, _size],
)
register_prototype(
    "bzj_connect_points_auto_scale",
    ctypes.c_int32,
    [_size, _double_pointer, _size, ctypes.c_double, _double_pointer, _size, ctypes.c_double,
     _size, _size, _double_pointer, _size, _double_pointer],
)


def _order(value, name, default):
    if value is None:
        return default
    # The common case (a non-negative int) without the general conversion.
    return value if type(value) is int and value >= 0 else index_argument(value, name)


def _real(value, name):
    return value if type(value) is float else real_argument(value, name)


def _connect_flat(dim, p_values, q_values, u0, v0, p_order, q_order, automatic, p_scale,
                  q_scale):
    """``bzj_connect_points`` (``automatic``: ``bzj_connect_points_auto_scale``) on the
    flat coordinate sequences ``p_values`` and ``q_values``: ``(status, values,
    scale)`` with ``values`` the flat tuple of R's control points and ``scale`` the
    scale chosen (``None`` for given scales); on a failure ``values`` is ``None``
    (the caller reads the message, in this thread, right away). One call across the
    ABI; each array is made by one copy of packed doubles."""
    p_length, q_length = len(p_values), len(q_values)
    p_type, p_packer = _array_type(p_length)
    q_type, q_packer = _array_type(q_length)
    p_array = p_type.from_buffer_copy(p_packer.pack(*p_values))
    q_array = q_type.from_buffer_copy(q_packer.pack(*q_values))
    out_length = (p_order + q_order + 2) * dim if p_order + q_order < 64 else 0
    out_type, out_packer = _array_type(max(out_length, 1))
    out = out_type()
    if automatic:
        scale = ctypes.c_double()
        status = function("bzj_connect_points_auto_scale")(
            dim, p_array, p_length, u0, q_array, q_length, v0, p_order, q_order, out,
            out_length, ctypes.byref(scale))
        scale = scale.value
    else:
        scale = None
        status = function("bzj_connect_points")(
            dim, p_array, p_length, u0, q_array, q_length, v0, p_order, q_order, p_scale,
            q_scale, out, out_length)
    if status:
        return status, None, None
    return status, out_packer.unpack_from(out), scale


def _raise(status):
    lib = library()
    raise BezjoinError(status, lib.status_name(status), lib.last_error())


def connect_points(p_points, u0, q_points, v0, *, p_order=None, q_order=None, p_scale=None,
                   q_scale=None, auto_scale=None):
    """:func:`connect` of the Bezier curves with control points ``p_points`` and
    ``q_points`` without making :class:`Curve` objects: the control points of ``R``
    (a list of tuples), the same, bit for bit, as ``connect(Curve(p_points), u0,
    Curve(q_points), v0, ...).points`` (``bzj_connect_points``,
    ``bzj_connect_points_auto_scale``: one call into the library). No interior
    constraints; the scale rule and the order defaults (each curve's degree) are
    those of :func:`connect`. :func:`connect_points_auto_scale` also returns the
    automatic scale.

    Raises:
        BezjoinError: with the library's status and message.
    """
    points, _scale = _connect_rows(p_points, u0, q_points, v0, p_order, q_order,
                                   *automatic_scale(auto_scale, p_scale, q_scale))
    return points


def connect_points_auto_scale(p_points, u0, q_points, v0, *, p_order=None, q_order=None):
    """:func:`connect_points` with the automatic scale: ``(points, scale)``, ``scale``
    the ``s = alpha = beta`` chosen (as :func:`connect_auto_scale`)."""
    return _connect_rows(p_points, u0, q_points, v0, p_order, q_order, True, 1.0, 1.0)


def _connect_rows(p_points, u0, q_points, v0, p_order, q_order, automatic, p_scale, q_scale):
    p_rows, dim = point_rows(p_points, "p_points")
    q_rows, q_dim = point_rows(q_points, "q_points")
    if q_dim != dim:
        raise BezjoinError.dimension_mismatch(
            f"q_points have dimension {q_dim} but p_points have dimension {dim}")
    p_order = _order(p_order, "p_order", len(p_rows) - 1)
    q_order = _order(q_order, "q_order", len(q_rows) - 1)
    status, values, scale = _connect_flat(
        dim, flat(p_rows), flat(q_rows), real_argument(u0, "u0"), real_argument(v0, "v0"),
        p_order, q_order, automatic, p_scale, q_scale)
    if status:
        _raise(status)
    return [values[i:i + dim] for i in range(0, len(values), dim)], scale


def connect_edges(p_edge, u0, q_edge, v0, *, p_order=None, q_order=None, p_scale=None,
                  q_scale=None, auto_scale=None):
    """The blend of two FreeCAD edges (or curves) as a ``Part.BezierCurve``: the curve
    of ``connect(Curve.from_freecad(p_edge), u0, Curve.from_freecad(q_edge), v0,
    ...).to_freecad()``, the same poles bit for bit, with the same arguments (``u0``,
    ``v0`` in the converted curves' parameters: ``[0, 1]`` for a Bezier edge), the
    same defaults and the same errors.

    For the common edge, on the whole of a polynomial ``Part.BezierCurve`` (the
    fast path of :meth:`Curve.from_freecad`), FreeCAD's poles go to the library and
    the blend's poles come back in one call (``bzj_connect_points``) with no
    :class:`Curve` made; anything else (and any error) takes the composition
    above.
    """
    fast = _freecad.native()
    if fast is not None:
        # The compiled route (bezjoin/_native.c): the same reads, checks and call.
        curve = fast.connect_edges(p_edge, u0, q_edge, v0, p_order, q_order, p_scale,
                                   q_scale, auto_scale)
        if curve is None:
            return _compose_edges(p_edge, u0, q_edge, v0, p_order, q_order,
                                  *automatic_scale(auto_scale, p_scale, q_scale))
        if curve is not NotImplemented:
            return curve
    part = _freecad._part()
    automatic, p_scale, q_scale = automatic_scale(auto_scale, p_scale, q_scale)
    p_found = _freecad._verbatim_values(p_edge, part)
    q_found = p_found and _freecad._verbatim_values(q_edge, part)
    if q_found:
        p_values, p_degree = p_found
        q_values, q_degree = q_found
        p_order = _order(p_order, "p_order", p_degree)
        q_order = _order(q_order, "q_order", q_degree)
        status, values, _scale = _connect_flat(3, p_values, q_values, _real(u0, "u0"),
                                               _real(v0, "v0"), p_order, q_order, automatic,
                                               p_scale, q_scale)
        if not status:
            return _freecad.bezier_curve_from_values(values, p_order + q_order + 1)
    # Not both fast, or an error: the composition words the error.
    return _compose_edges(p_edge, u0, q_edge, v0, p_order, q_order, automatic, p_scale,
                          q_scale)


def _compose_edges(p_edge, u0, q_edge, v0, p_order, q_order, automatic, p_scale, q_scale):
    """``connect(from_freecad(p_edge), u0, from_freecad(q_edge), v0, ...).to_freecad()``."""
    with Curve.from_freecad(p_edge) as p, Curve.from_freecad(q_edge) as q:
        scales = {} if automatic else {"p_scale": p_scale, "q_scale": q_scale}
        with connect(p, u0, q, v0, p_order=p_order, q_order=q_order,
                     auto_scale=automatic, **scales) as blend:
            return blend.to_freecad()


class GeometricOptionsStruct(ctypes.Structure):
    """``BzjGeometricOptions`` (layout fixed by the C contract)."""

    _fields_ = [
        ("p_order", ctypes.c_size_t),
        ("q_order", ctypes.c_size_t),
        ("p_shape", ctypes.POINTER(ctypes.c_double)),
        ("q_shape", ctypes.POINTER(ctypes.c_double)),
    ]


class FairnessReportStruct(ctypes.Structure):
    """``BzjFairnessReport`` (layout fixed by the C contract)."""

    _fields_ = [
        ("energy", ctypes.c_double),
        ("curvature_min", ctypes.c_double),
        ("curvature_max", ctypes.c_double),
        ("curvature_extrema", ctypes.c_size_t),
    ]


register_prototype(
    "bzj_connect_geometric",
    ctypes.c_int32,
    [CurvePointer, ctypes.c_double, CurvePointer, ctypes.c_double,
     ctypes.POINTER(GeometricOptionsStruct), ctypes.POINTER(CurvePointer),
     ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
     ctypes.POINTER(FairnessReportStruct)],
)


class GeometricConnection(CurveGroup):
    """The G^k connecting ``curve``, the shape values used at each end
    (``p_shape``, ``q_shape``: ``beta_1..beta_k``) and the fairness report:
    ``energy`` (``L^3 integral (d kappa/ds)^2 ds``), ``curvature_min``,
    ``curvature_max`` and ``curvature_extrema`` (interior local extrema)."""

    _curve_fields = ("curve",)

    def __init__(self, curve, p_shape, q_shape, report):
        self.curve = curve
        self.p_shape = p_shape
        self.q_shape = q_shape
        # Without a report (``report=False``) the four fields are None.
        self.energy = report.energy if report else None
        self.curvature_min = report.curvature_min if report else None
        self.curvature_max = report.curvature_max if report else None
        self.curvature_extrema = report.curvature_extrema if report else None

    def _fields(self):
        return self._curve_fields + ("p_shape", "q_shape", "energy", "curvature_min",
                                     "curvature_max", "curvature_extrema")


def connect_geometric(p, u0, q, v0, *, p_order=2, q_order=2, p_shape=None, q_shape=None,
                      report=True):
    """The Bezier curve from ``P(u0)`` to ``Q(v0)`` meeting ``P`` with G^p_order and
    ``Q`` with G^q_order (``bzj_connect_geometric``; mathematics.md section 7):
    C^k after a reparametrisation with shape values ``beta_1 > 0, beta_2, ...``
    per end (the beta-constraints, Faa di Bruno's formula).

    Args:
        p, q: :class:`Curve` objects (Bezier or NURBS) of the same dimension.
        u0, v0: parameters in the domains of ``p`` and ``q``.
        p_order, q_order: geometric continuity orders (up to 6; default G2).
        p_shape, q_shape: ``p_order`` / ``q_order`` shape values per end;
            ``None`` (the default): chosen by the library to minimise the
            blend's fairness energy among blends at most ``MAX_LENGTH_RATIO``
            (10) times the gap ``|Q(v0) - P(u0)|`` long, so the default never
            loops on a corner between long edges, and where the ends face away
            from each other (every blend must turn around) the loop stays
            within ten gaps.
        report: compute the fairness report (energy, curvature range and
            extrema, sampled along the blend); ``False`` skips it (the
            report costs far more than a solve with given shapes) and
            leaves those fields None.

    Returns:
        :class:`GeometricConnection`.

    Raises:
        BezjoinError: ``BZJ_ERR_ILL_CONDITIONED`` when an end's tangent is zero, or
            when its unit tangent and curvature vector are not known to 1e-6 of
            themselves (``GEOMETRIC_CONDITION_LIMIT``: an end whose last poles
            nearly coincide, one next to a cusp, or a blend whose poles are too
            far from the origin to hold its curvature; mathematics.md,
            "Numerically stationary ends"); the message names the end and gives
            the estimate. G3's curvature derivative is not estimated.
    """
    p_handle, q_handle = handle_of(p, "p"), handle_of(q, "q")
    p_order = index_argument(p_order, "p_order")
    q_order = index_argument(q_order, "q_order")
    keep_alive = []

    def shape_array(values, order, name):
        if values is None:
            return None
        values = [real_argument(v, f"{name}[{i}]") for i, v in enumerate(values)]
        if len(values) != order:
            raise BezjoinError.invalid_argument(
                f"{name} has {len(values)} values but the order is {order}")
        array, _length = double_array(values)
        keep_alive.append(array)
        return array

    options = GeometricOptionsStruct(p_order, q_order,
                                     shape_array(p_shape, p_order, "p_shape"),
                                     shape_array(q_shape, q_order, "q_shape"))
    p_out = (ctypes.c_double * max(p_order, 1))()
    q_out = (ctypes.c_double * max(q_order, 1))()
    fairness = FairnessReportStruct() if report else None
    out = CurvePointer()
    library().call("bzj_connect_geometric", p_handle, real_argument(u0, "u0"), q_handle,
                   real_argument(v0, "v0"), ctypes.byref(options), ctypes.byref(out),
                   p_out, q_out, ctypes.byref(fairness) if report else None)
    return GeometricConnection(Curve._adopt(out), list(p_out)[:p_order],
                               list(q_out)[:q_order], fairness)
