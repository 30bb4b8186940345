"""Conversion between FreeCAD's Part geometry and bezjoin curves.

``Part`` is imported only when a conversion is asked for, so the package
works without FreeCAD. The knot bookkeeping, the exact conic arcs and the
parameter maps below are plain Python (tested without FreeCAD).

What is accepted and how parameters map: :meth:`bezjoin.Curve.from_freecad`.
:func:`freecad_parameter` and :func:`curve_parameter` compute the map for a
given FreeCAD object, in both directions.
"""

import bisect
import ctypes
import itertools
import math
import os
from collections import namedtuple

from . import _library
from ._convert import _array_type
from ._library import CurvePointer, function, library
from .errors import STATUS_OK, BezjoinError, UnsupportedGeometryError

#: OpenCASCADE's ``Geom_BezierCurve::MaxDegree()`` and ``Geom_BSplineCurve::MaxDegree()``.
MAXIMUM_FREECAD_DEGREE = 25

#: FreeCAD gives unbounded curves (``Part.Line``, ``Part.Parabola``...) the
#: parameter range ``[-2e100, 2e100]``; a range reaching this far is unbounded.
UNBOUNDED = 1e99

#: Widest span of a converted conic arc, in FreeCAD's parameter: a quarter turn
#: of a circle or an ellipse (as :meth:`bezjoin.Curve.ellipse_arc`), the same
#: width of a hyperbola's parameter.
CONIC_SPAN = 0.5 * math.pi

#: A converted curve must reproduce FreeCAD's points to this (relative to the
#: curve's size) at its ends and span middles, or the conversion is refused.
#: The conversions are exact (about 1e-15); this only catches a convention
#: of FreeCAD's geometry that differs from the one assumed here.
SELF_CHECK_TOLERANCE = 1e-9

_TURN = 2.0 * math.pi

_chain = itertools.chain.from_iterable

#: How a FreeCAD object becomes a curve: ``mapping`` is ``"affine"`` (a Bezier
#: curve on [0, 1] for FreeCAD's [first, last]), ``"same"`` (a NURBS curve on
#: FreeCAD's own parameters), ``"ellipse"`` or ``"hyperbola"`` (a rational
#: quadratic NURBS on [first, last], FreeCAD's parameter at the knots);
#: ``build(cls)`` makes the curve; ``value(t)`` is FreeCAD's point at ``t``
#: (``edge.valueAt`` or the Part curve's ``value``), the judge of the result.
_Plan = namedtuple("_Plan", "mapping first last build value description")


# -- plain Python: knots, conic arcs, parameter maps ------------------------------------


def expand_knots(knots, multiplicities):
    """The flat knot vector of OpenCASCADE's distinct knots and multiplicities.

        >>> expand_knots([0.0, 1.0, 3.0], [3, 1, 3])
        [0.0, 0.0, 0.0, 1.0, 3.0, 3.0, 3.0]
    """
    flat = []
    for knot, multiplicity in zip(knots, multiplicities):
        flat.extend([float(knot)] * int(multiplicity))
    return flat


def group_knots(flat):
    """``(knots, multiplicities)``: the distinct values of a flat knot vector (equal
    values, exactly, are one knot) and how often each occurs.

        >>> group_knots([0.0, 0.0, 0.0, 1.0, 3.0, 3.0, 3.0])
        ([0.0, 1.0, 3.0], [3, 1, 3])
    """
    knots, multiplicities = [], []
    for knot in flat:
        if knots and knot == knots[-1]:
            multiplicities[-1] += 1
        else:
            knots.append(float(knot))
            multiplicities.append(1)
    return knots, multiplicities


def conic_breaks(first, last, closed_turn=False):
    """The distinct knots of a converted conic arc on ``[first, last]``: the arc is
    cut into ``n = ceil((last - first) / (pi / 2))`` spans of equal width, knots
    at ``first + i (last - first) / n`` (the same floating-point values as
    :meth:`bezjoin.Curve.ellipse_arc`; ``closed_turn``: a sweep just above a full
    turn is taken as one turn, as there).

        >>> [round(k, 12) for k in conic_breaks(0.0, math.pi)]
        [0.0, 1.570796326795, 3.14159265359]
    """
    sweep = last - first
    if closed_turn:
        sweep = min(sweep, _TURN)
    pieces = max(1, int(math.ceil(sweep / CONIC_SPAN - 1e-12)))
    width = sweep / pieces
    # start + width with start = first + i width, as the library computes them
    return [first] + [(first + i * width) + width for i in range(pieces - 1)] + [last]


def _span(breaks, x):
    index = bisect.bisect_right(breaks, x) - 1
    return min(max(index, 0), len(breaks) - 2)


def conic_freecad_parameter(kind, breaks, u):
    """FreeCAD's parameter (the angle of an ellipse, the hyperbolic parameter of a
    hyperbola) of the converted arc's point at its parameter ``u``.

    ``kind`` is ``"ellipse"`` (circles too) or ``"hyperbola"``, ``breaks`` the
    arc's distinct knots (:func:`conic_breaks`). On the span ``[k, k + w]``
    with middle ``m = k + w / 2`` and ``x = 2 (u - k) / w - 1`` in ``[-1, 1]``:
    ``t = m + 2 atan(x tan(w / 4))`` (ellipse), ``t = m + 2 atanh(x tanh(w / 4))``
    (hyperbola). At the knots ``t = u`` exactly.
    """
    index = _span(breaks, u)
    start, end = breaks[index], breaks[index + 1]
    if u in (start, end):
        return u
    width = end - start
    x = 2.0 * (u - start) / width - 1.0
    middle = 0.5 * (start + end)
    if kind == "ellipse":
        return middle + 2.0 * math.atan(x * math.tan(0.25 * width))
    if kind == "hyperbola":
        return middle + 2.0 * math.atanh(x * math.tanh(0.25 * width))
    raise ValueError(f"unknown conic kind {kind!r}")


def conic_curve_parameter(kind, breaks, t):
    """The converted arc's parameter of FreeCAD's parameter ``t`` (the inverse of
    :func:`conic_freecad_parameter`): ``u = k + w (1 + x) / 2`` with
    ``x = tan((t - m) / 2) / tan(w / 4)`` (``tanh`` for a hyperbola)."""
    index = _span(breaks, t)
    start, end = breaks[index], breaks[index + 1]
    if t in (start, end):
        return t
    width = end - start
    middle = 0.5 * (start + end)
    if kind == "ellipse":
        x = math.tan(0.5 * (t - middle)) / math.tan(0.25 * width)
    elif kind == "hyperbola":
        x = math.tanh(0.5 * (t - middle)) / math.tanh(0.25 * width)
    else:
        raise ValueError(f"unknown conic kind {kind!r}")
    return start + 0.5 * width * (1.0 + x)


def _affine(centre, x_axis, y_axis, a, b):
    return tuple(c + a * x + b * y for c, x, y in zip(centre, x_axis, y_axis))


def hyperbola_arc(cls, centre, x_axis, y_axis, major_radius, minor_radius, first, last):
    """The exact arc ``centre + major cosh(t) x_axis + minor sinh(t) y_axis``,
    ``first <= t <= last`` (FreeCAD's ``Part.Hyperbola``), as a rational quadratic
    NURBS curve of class ``cls`` on ``[first, last]``: spans as
    :func:`conic_breaks`, each with end weights 1 and middle weight
    ``cosh(w / 2)``, its middle pole where the end tangents meet; FreeCAD's
    parameter at the knots (:func:`conic_freecad_parameter` between them)."""
    breaks = conic_breaks(first, last)

    def at(t, stretch):
        return _affine(centre, x_axis, y_axis, stretch * major_radius * math.cosh(t),
                       stretch * minor_radius * math.sinh(t))

    poles, weights = [], []
    for start, end in zip(breaks, breaks[1:]):
        middle_weight = math.cosh(0.5 * (end - start))
        poles.append(at(start, 1.0))
        weights.append(1.0)
        poles.append(at(0.5 * (start + end), 1.0 / middle_weight))
        weights.append(middle_weight)
    poles.append(at(last, 1.0))
    weights.append(1.0)
    knots = [first] * 3 + [k for k in breaks[1:-1] for _ in range(2)] + [last] * 3
    return cls.nurbs(poles, knots, 2, weights)


def parabola_arc(cls, vertex, x_axis, y_axis, focal, first, last):
    """The exact arc ``vertex + t^2 / (4 focal) x_axis + t y_axis``,
    ``first <= t <= last`` (FreeCAD's ``Part.Parabola``), as a polynomial quadratic
    one-span NURBS curve of class ``cls`` on ``[first, last]``: the parabola is a
    quadratic polynomial in ``t``, so the parameter is FreeCAD's everywhere."""
    four_focal = 4.0 * focal
    poles = [
        _affine(vertex, x_axis, y_axis, first * first / four_focal, first),
        _affine(vertex, x_axis, y_axis, first * last / four_focal, 0.5 * (first + last)),
        _affine(vertex, x_axis, y_axis, last * last / four_focal, last),
    ]
    return cls.nurbs(poles, [first] * 3 + [last] * 3, 2)


def _to_freecad_parameter(mapping, first, last, u):
    if mapping == "affine":
        return first + (last - first) * u
    if mapping == "same":
        return u
    return conic_freecad_parameter(mapping, conic_breaks(first, last, mapping == "ellipse"), u)


def _to_curve_parameter(mapping, first, last, t):
    if mapping == "affine":
        return (t - first) / (last - first)
    if mapping == "same":
        return t
    return conic_curve_parameter(mapping, conic_breaks(first, last, mapping == "ellipse"), t)


# -- FreeCAD -------------------------------------------------------------------------------


_part_module = None


def _part():
    """FreeCAD's ``Part`` module (imported on the first conversion, then kept)."""
    global _part_module
    if _part_module is None:
        try:
            import Part  # noqa: PLC0415 (FreeCAD only)
        except ImportError as error:
            raise UnsupportedGeometryError(
                "FreeCAD's Part module is not importable (run inside FreeCAD or freecadcmd)"
            ) from error
        _part_module = Part
    return _part_module


_vector_class = None


def _vector_type():
    """``FreeCAD.Vector`` (looked up once)."""
    global _vector_class
    if _vector_class is None:
        import FreeCAD  # noqa: PLC0415 (FreeCAD only)

        _vector_class = FreeCAD.Vector
    return _vector_class


def _vector(x, y, z):
    return _vector_type()(x, y, z)


def _describe(obj):
    module = getattr(type(obj), "__module__", "") or ""
    name = type(obj).__name__
    return f"{module}.{name}" if module.startswith("Part") else name


def _bounded(first, last):
    return all(math.isfinite(x) and abs(x) < UNBOUNDED for x in (first, last))


_APPROXIMATE = ("approximate it by a B-spline first, e.g. "
                "Part.Edge(edge.Curve.toBSpline(edge.FirstParameter, edge.LastParameter)) "
                "(same parameters) or curve.approximateBSpline(tolerance, max_segments, "
                "max_degree), and check that the deviation suits you")


def _curve_base(part):
    """``Part.Curve``, the base class of Part's 3D curves (FreeCAD 0.20 does not
    export its name: found through ``Part.Circle``'s bases)."""
    base = getattr(part, "Curve", None)
    if base is None:
        base = next(c for c in part.Circle.__mro__ if c.__name__ == "Curve")
    return base


def _edge_of(obj, part):
    """``(edge, first, last, value)``: the ``Part.Edge`` whose curve is converted
    (``obj`` itself, the one edge of a shape, or an edge made of a bounded Part
    curve), the parameter range and FreeCAD's point at a parameter. A Part curve
    keeps its own range (``toShape`` may shift an arc's by a turn) and is
    evaluated by its own ``value``."""
    if isinstance(obj, part.Shape):
        if isinstance(obj, part.Edge):
            edge = obj
        else:
            edges = obj.Edges
            if len(edges) != 1:
                raise UnsupportedGeometryError(
                    f"the shape has {len(edges)} edges; select exactly one edge"
                )
            edge = edges[0]
        return edge, edge.FirstParameter, edge.LastParameter, edge.valueAt
    geom2d = getattr(part, "Geom2d", None)
    if geom2d is not None and isinstance(obj, geom2d.Geometry2d):
        raise UnsupportedGeometryError(
            f"a {_describe(obj)} is a 2D (Geom2d) curve; make a 3D edge of it first "
            "(curve.toShape() places it in the XY plane, curve.toShape(surface) on a "
            "surface) and convert that edge"
        )
    if isinstance(obj, _curve_base(part)):
        first, last = obj.FirstParameter, obj.LastParameter
        if not _bounded(first, last):
            raise UnsupportedGeometryError(
                f"a {_describe(obj)} is unbounded (parameters {first:g} to {last:g}); convert "
                "an edge on a finite part of it, Part.Edge(curve, first, last), or a "
                "trimmed curve (Part.LineSegment, Part.ArcOfParabola, ...)"
            )
        try:
            return obj.toShape(), first, last, obj.value
        except Exception as error:  # noqa: BLE001 (FreeCAD raises its own types)
            raise UnsupportedGeometryError(
                f"FreeCAD could not make an edge of the {_describe(obj)}: {error}"
            ) from None
    raise UnsupportedGeometryError(
        f"a {_describe(obj)} is not FreeCAD geometry; pass a Part.Edge, a shape with "
        "one edge, or a Part curve (Part.Circle, Part.BSplineCurve, ...)"
    )


def _poles(curve):
    return [tuple(pole) for pole in curve.getPoles()]


def _nurbs_plan(poles, flat, degree, weights, first, last, value, description):
    """The NURBS curve with these poles, flat knots and weights, trimmed to
    ``[first, last]`` (and clamped) by knot insertion: FreeCAD's parameters."""
    clamped = len(set(flat[:degree + 1])) == 1 and len(set(flat[-degree - 1:])) == 1

    def build(cls):
        nurbs = cls.nurbs(poles, flat, degree, weights)
        if (first, last) == nurbs.domain and clamped:
            return nurbs
        with nurbs:
            return nurbs.segment(first, last)

    return _Plan("same", first, last, build, value, description)


def _bezier_plan(poles, start, end, first, last, value, description):
    """The Bezier curve with these poles over FreeCAD's ``[start, end]``, the part
    on ``[first, last]`` by :meth:`segment` (over ``[0, 1]``: the affine map)."""

    def build(cls):
        bezier = cls(poles)
        if (first, last) == (start, end):
            return bezier
        with bezier:
            width = end - start
            return bezier.segment((first - start) / width, (last - start) / width)

    return _Plan("affine", first, last, build, value, description)


def _bspline_plan(curve, value, first, last, nurbs):
    name = _describe(curve)
    if curve.isPeriodic():
        # OpenCASCADE's segment of a periodic B-spline is the clamped, non-periodic
        # curve on [first, last] with the same parameters (also across the seam).
        source = curve.copy()
        try:
            source.segment(first, last)
        except Exception as error:  # noqa: BLE001
            raise UnsupportedGeometryError(
                f"FreeCAD could not make the periodic {name} clamped on "
                f"[{first!r}, {last!r}]: {error}"
            ) from None
        description = f"periodic {name} (clamped by its segment on the edge's range)"
    else:
        source = curve
        description = name
    degree = source.Degree
    knots, multiplicities = source.getKnots(), source.getMultiplicities()
    rational = source.isRational()
    poles = _poles(source)
    weights = list(source.getWeights()) if rational else None
    clamped = multiplicities[0] == degree + 1 and multiplicities[-1] == degree + 1
    if len(knots) == 2 and clamped and not rational and not curve.isPeriodic() and not nurbs:
        # One polynomial span: a Bezier curve, as bezjoin has always taken it.
        return _bezier_plan(poles, knots[0], knots[1], first, last, value, f"one-span {name}")
    return _nurbs_plan(poles, expand_knots(knots, multiplicities), degree, weights, first, last,
                       value, description)


def _plan(obj, nurbs=False):
    """How ``obj`` is converted (:class:`_Plan`), or UnsupportedGeometryError;
    ``nurbs``: as a NURBS curve even where a Bezier curve would do."""
    part = _part()
    edge, first, last, value = _edge_of(obj, part)
    if edge.Degenerated:
        raise UnsupportedGeometryError("the edge is degenerated (a single point)")
    try:
        curve = edge.Curve
    except Exception as error:  # noqa: BLE001
        raise UnsupportedGeometryError(f"the edge has no 3D curve FreeCAD can give: {error}") \
            from None
    name = _describe(curve)
    if not _bounded(first, last):
        raise UnsupportedGeometryError(
            f"the edge on a {name} is unbounded (parameters {first:g} to {last:g}); "
            "trim it to a finite range first"
        )
    if not first < last:
        raise UnsupportedGeometryError(
            f"the edge on a {name} has an empty parameter range [{first!r}, {last!r}]"
        )
    if isinstance(curve, (part.Line, part.LineSegment)):
        ends = [tuple(value(first)), tuple(value(last))]
        if nurbs:
            return _nurbs_plan(ends, [first, first, last, last], 1, None, first, last, value,
                               name)
        return _bezier_plan(ends, first, last, first, last, value, name)
    if isinstance(curve, part.BezierCurve):
        poles = _poles(curve)
        if curve.isRational() or nurbs:
            degree = curve.Degree
            weights = list(curve.getWeights()) if curve.isRational() else None
            knots = [0.0] * (degree + 1) + [1.0] * (degree + 1)
            kind = "rational " if weights else ""
            return _nurbs_plan(poles, knots, degree, weights, first, last, value, kind + name)
        return _bezier_plan(poles, 0.0, 1.0, first, last, value, name)
    if isinstance(curve, part.BSplineCurve):
        return _bspline_plan(curve, value, first, last, nurbs)
    if isinstance(curve, (part.Circle, part.Ellipse)):
        if last - first > _TURN * (1.0 + 4.0 * 2.220446049250313e-16):
            raise UnsupportedGeometryError(
                f"the edge on a {name} runs over more than one turn "
                f"([{first!r}, {last!r}])"
            )
        if isinstance(curve, part.Circle):
            x_radius = y_radius = curve.Radius
        else:
            x_radius, y_radius = curve.MajorRadius, curve.MinorRadius
        centre, x_axis, y_axis = tuple(curve.Center), tuple(curve.XAxis), tuple(curve.YAxis)
        return _Plan(
            "ellipse", first, last,
            lambda cls: cls.ellipse_arc(centre, x_axis, y_axis, x_radius, y_radius, first, last),
            value, name)
    if isinstance(curve, part.Hyperbola):
        centre, x_axis, y_axis = tuple(curve.Center), tuple(curve.XAxis), tuple(curve.YAxis)
        radii = curve.MajorRadius, curve.MinorRadius
        return _Plan(
            "hyperbola", first, last,
            lambda cls: hyperbola_arc(cls, centre, x_axis, y_axis, *radii, first, last),
            value, name)
    if isinstance(curve, part.Parabola):
        vertex, x_axis, y_axis = tuple(curve.Location), tuple(curve.XAxis), tuple(curve.YAxis)
        focal = curve.Focal
        return _Plan(
            "same", first, last,
            lambda cls: parabola_arc(cls, vertex, x_axis, y_axis, focal, first, last),
            value, name)
    if isinstance(curve, part.OffsetCurve):
        raise UnsupportedGeometryError(
            f"a {name} has no exact NURBS form; {_APPROXIMATE}"
        )
    raise UnsupportedGeometryError(
        f"a {name} has no exact NURBS form bezjoin knows; {_APPROXIMATE}"
    )


def _distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def _self_check(curve, plan):
    """Refuse the conversion unless the curve meets FreeCAD's edge at the ends and
    span middles (see :data:`SELF_CHECK_TOLERANCE`)."""
    first, last = curve.domain
    breaks = sorted(set(curve.knots))
    breaks = [k for k in breaks if first <= k <= last]
    params = list(breaks) + [0.5 * (a + b) for a, b in zip(breaks, breaks[1:])]
    ours = [rows[0] for rows in curve.derivatives_many(params, 0)]
    theirs = [tuple(plan.value(_to_freecad_parameter(plan.mapping, plan.first,
                                                              plan.last, u)))
              for u in params]
    size = max([1.0] + [math.sqrt(sum(x * x for x in p)) for p in theirs])
    worst = max(_distance(a, b) for a, b in zip(ours, theirs))
    if not worst <= SELF_CHECK_TOLERANCE * size:
        raise UnsupportedGeometryError(
            f"the {plan.description} converted does not reproduce FreeCAD's points "
            f"(off by {worst:.3g} for a size of {size:.3g}); its conventions differ from "
            "those bezjoin assumes: please report it"
        )


def _verbatim_ratio(degree):
    """How far (max-norm) the poles of a degree-``degree`` Bezier curve may reach,
    relative to ``max(1, |P_0|, |P_n|)``, for its sampled self-check to be sure
    to pass. Assumed: both evaluations (ours, OpenCASCADE's) err at most as
    one through the power basis does (coefficients up to ``3^n max |P_i|``):
    ``4 n eps 3^n sqrt(3) max |P_i|``, kept 8 times below
    :data:`SELF_CHECK_TOLERANCE` times the size (at least the end points,
    which are sampled). About 1000 for a cubic, 5 at degree 7; 0 (no fast
    path) from degree 9. (OpenCASCADE's evaluation is off enough for the check
    to refuse random Bezier edges from degree 16 on.)"""
    bound = 8.0 * 4.0 * degree * 2.220446049250313e-16 * 3.0 ** degree * math.sqrt(3.0)
    ratio = SELF_CHECK_TOLERANCE / bound
    return ratio if ratio >= 1.0 else 0.0


_VERBATIM_RATIOS = [0.0] + [_verbatim_ratio(n) for n in range(1, MAXIMUM_FREECAD_DEGREE + 1)]

#: Coordinates below this size cannot overflow in either evaluation.
_VERBATIM_LIMIT = 1e150


def _verbatim_values(obj, part):
    """The fast path of the most common edge: ``(values, degree)`` with ``values``
    the flat tuple of the poles' coordinates (3D), or ``None`` (then the general
    path runs, with the same result or error). It applies to a ``Part.Edge`` on
    the whole of a polynomial ``Part.BezierCurve`` (FreeCAD's ``[0, 1]``) of low
    degree whose poles stay near its ends (:func:`_verbatim_ratio`). Its curve
    is the Bezier curve with FreeCAD's poles, copied bit for bit, on the same
    parameter (the plan "affine" with ``first, last = 0, 1``): the same
    Bernstein polynomial, and the sampled self-check is skipped because the
    bound above proves it would pass (it compares two evaluations of one
    polynomial). Values that are not finite are left to the library, which
    refuses them (the caller then takes the general path)."""
    if not isinstance(obj, part.Edge) or obj.Degenerated:
        return None
    try:
        curve = obj.Curve
        whole = obj.ParameterRange == (0.0, 1.0)
    except Exception:  # noqa: BLE001 (the general path words it)
        return None
    if not whole or type(curve) is not part.BezierCurve or curve.isRational():
        return None
    values = tuple(_chain(curve.getPoles()))
    degree = len(values) // 3 - 1
    if not 1 <= degree <= MAXIMUM_FREECAD_DEGREE:
        return None
    # A NaN compares False everywhere: the library refuses it later.
    reach = max(map(abs, values))
    ratio = _VERBATIM_RATIOS[degree]
    if reach <= ratio:
        # max(1, |P_0|, |P_n|) >= 1: no need to look at the ends.
        return values, degree
    if not reach < _VERBATIM_LIMIT:
        return None
    ends = max(1.0, abs(values[0]), abs(values[1]), abs(values[2]),
               abs(values[-3]), abs(values[-2]), abs(values[-1]))
    if not reach <= ratio * ends:
        return None
    return values, degree


# -- the optional compiled fast path (bezjoin/_native.c) ----------------------------------

#: Set to ``0`` to keep the compiled module unused (the ctypes route only).
NATIVE_VARIABLE = "BEZJOIN_NATIVE"

_UNBOUND = object()
_native_module = _UNBOUND
_native_library = None
_native_enabled = None


def _bind_native():
    """Import ``bezjoin._native`` (built by ``bindings/python/build-native.sh``) and hand
    it the loaded library's functions, FreeCAD's types and the verbatim bounds; ``None``
    when it is absent, disabled or does not fit (the ctypes route then runs)."""
    global _native_module, _native_library, _native_enabled
    lib = library()
    module = None
    if _native_enabled is None:
        _native_enabled = os.environ.get(NATIVE_VARIABLE, "1") != "0"
    names = ("bzj_curve_new", "bzj_curve_free", "bzj_curve_points", "bzj_connect_points",
             "bzj_connect_points_auto_scale")
    if _native_enabled and all(lib.has(name) for name in names):
        try:
            from . import _native as module  # noqa: PLC0415
        except ImportError:
            module = None
        if module is not None:
            try:
                part = _part()
            except UnsupportedGeometryError:  # outside FreeCAD: nothing to speed up
                part = module = None
        if module is not None:
            addresses = [ctypes.cast(getattr(lib._cdll, name), ctypes.c_void_p).value
                         for name in names]
            module.bind(*addresses, CurvePointer, part.Edge, part.BezierCurve,
                        _VERBATIM_RATIOS, _VERBATIM_LIMIT)
    _native_module, _native_library = module, lib
    return module


def native():
    """The compiled fast path bound to the loaded library, or ``None`` (absent, disabled
    by ``BEZJOIN_NATIVE=0`` or :func:`use_native`)."""
    module = _native_module
    if module is not _UNBOUND and _library._library is _native_library:
        return module
    return _bind_native()


def native_module():
    """The compiled module when it is bound to the loaded library, else ``None``; never
    binds it (:meth:`bezjoin.Curve.close` releases through it)."""
    module = _native_module
    if module is not _UNBOUND and _library._library is _native_library:
        return module
    return None


def use_native(enabled):
    """Use the compiled fast path when it is present (``True``) or the ctypes route only
    (``False``); returns the previous setting. Both give the same results bit for bit."""
    global _native_enabled, _native_module
    previous = native() is not None
    _native_enabled = bool(enabled)
    _native_module = _UNBOUND
    return previous


def _verbatim_bezier(cls, obj, part):
    """The curve of :func:`_verbatim_values`' fast path, or ``None``."""
    fast = native()
    if fast is not None:
        return fast.curve_new(obj, cls)
    found = _verbatim_values(obj, part)
    if found is None:
        return None
    values, degree = found
    length = len(values)
    array_type, packer = _array_type(length)
    array = array_type.from_buffer_copy(packer.pack(*values))
    handle = CurvePointer()
    status = function("bzj_curve_new")(3, degree, array, length, ctypes.byref(handle))
    if status != STATUS_OK or not handle:
        return None
    return cls._adopt(handle, (degree, 3))


def curve_from_freecad(cls, obj, nurbs=False, verbatim_tried=False):
    """The curve of class ``cls`` for a FreeCAD object (:meth:`bezjoin.Curve.from_freecad`);
    ``verbatim_tried``: the caller found that the verbatim fast path does not apply."""
    if not nurbs and not verbatim_tried:
        fast = _verbatim_bezier(cls, obj, _part())
        if fast is not None:
            return fast
    plan = _plan(obj, nurbs)
    try:
        curve = plan.build(cls)
    except BezjoinError as error:
        raise UnsupportedGeometryError(
            f"the {plan.description} on [{plan.first!r}, {plan.last!r}] could not be "
            f"converted: {error}"
        ) from error
    try:
        _self_check(curve, plan)
    except BaseException:
        curve.close()
        raise
    return curve


def freecad_parameter(obj, u, nurbs=False):
    """FreeCAD's parameter (of ``obj``'s curve, as ``edge.valueAt`` takes it) of the
    point at parameter ``u`` of ``Curve.from_freecad(obj, nurbs)``.

    ``u`` runs over that curve's domain: ``[0, 1]`` when it is a Bezier curve,
    the edge's ``[FirstParameter, LastParameter]`` otherwise.
    """
    plan = _plan(obj, nurbs)
    return _to_freecad_parameter(plan.mapping, plan.first, plan.last, u)


def curve_parameter(obj, t, nurbs=False):
    """The parameter of ``Curve.from_freecad(obj, nurbs)`` at the point of FreeCAD's
    parameter ``t`` (the inverse of :func:`freecad_parameter`)."""
    plan = _plan(obj, nurbs)
    return _to_curve_parameter(plan.mapping, plan.first, plan.last, t)


def _check_exportable(dim, degree, kind):
    if dim not in (2, 3):
        raise UnsupportedGeometryError(f"a curve of dimension {dim} has no FreeCAD form (2 or 3)")
    if degree == 0:
        raise UnsupportedGeometryError(f"a degree-0 curve (one point) has no {kind} form")
    if degree > MAXIMUM_FREECAD_DEGREE:
        raise UnsupportedGeometryError(
            f"degree {degree} is above OpenCASCADE's maximum {kind} degree "
            f"{MAXIMUM_FREECAD_DEGREE}"
        )


def _vectors(points, dim):
    vector = _vector_type()
    if dim == 3:
        return [vector(p[0], p[1], p[2]) for p in points]
    return [vector(p[0], p[1], 0.0) for p in points]


def bezier_curve(points, degree, dim):
    """A ``Part.BezierCurve`` with these control points (dim 2 is placed at z = 0)."""
    part = _part()
    _check_exportable(dim, degree, "Part.BezierCurve")
    curve = part.BezierCurve()
    # setPoles takes 3-tuples as it takes vectors (the same poles), without
    # making a Vector of each first.
    curve.setPoles(points if dim == 3 and all(type(p) is tuple for p in points)
                   else _vectors(points, dim))
    return curve


def bezier_curve_from_values(values, degree):
    """A ``Part.BezierCurve`` of degree ``degree`` with the 3D poles whose coordinates
    are the flat sequence ``values`` (one ``setPoles`` of tuples)."""
    part = _part()
    _check_exportable(3, degree, "Part.BezierCurve")
    curve = part.BezierCurve()
    coordinates = iter(values)
    # zip of one iterator three times: the rows (x, y, z), no slicing.
    curve.setPoles(list(zip(coordinates, coordinates, coordinates)))
    return curve


def bspline_curve(points, flat_knots, degree, weights, dim):
    """A non-periodic ``Part.BSplineCurve`` with these poles (dim 2 is placed at
    z = 0), flat knots (given to FreeCAD as distinct knots and multiplicities) and
    weights (``None``: polynomial)."""
    part = _part()
    _check_exportable(dim, degree, "Part.BSplineCurve")
    knots, multiplicities = group_knots(flat_knots)
    curve = part.BSplineCurve()
    arguments = [_vectors(points, dim), multiplicities, knots, False, degree]
    if weights is not None:
        arguments.append([float(w) for w in weights])
    try:
        curve.buildFromPolesMultsKnots(*arguments)
    except Exception as error:  # noqa: BLE001 (Part.OCCError and friends)
        raise UnsupportedGeometryError(
            f"FreeCAD refused the B-spline (degree {degree}, knots {knots}, "
            f"multiplicities {multiplicities}): {error}"
        ) from None
    return curve


def edge(curve, first=None, last=None):
    """A ``Part.Edge`` on ``curve`` (on ``[first, last]`` when given)."""
    part = _part()
    if first is None or last is None:
        return part.Edge(curve)
    return part.Edge(curve, first, last)
