"""The curve: an owned ``BzjCurve`` handle (a Bezier or a NURBS curve) with a
Pythonic face."""

import ctypes
import math
import threading

from . import _freecad
from ._convert import (double_array, double_buffer, flat, index_argument, point_indices,
                       point_rows, real_argument, rows_of)
from ._library import CurvePointer, library, register_prototype
from .errors import BezjoinError

_close_lock = threading.Lock()

_size = ctypes.c_size_t
_double_pointer = ctypes.POINTER(ctypes.c_double)
_size_pointer = ctypes.POINTER(ctypes.c_size_t)
_bool_pointer = ctypes.POINTER(ctypes.c_bool)
_curve_out = ctypes.POINTER(CurvePointer)

register_prototype(
    "bzj_nurbs_new",
    ctypes.c_int32,
    [_size, _size, _double_pointer, _size, _double_pointer, _size, _double_pointer, _size,
     _curve_out],
)
register_prototype("bzj_curve_is_nurbs", ctypes.c_int32, [CurvePointer, _bool_pointer])
register_prototype("bzj_curve_is_rational", ctypes.c_int32, [CurvePointer, _bool_pointer])
register_prototype("bzj_curve_pole_count", ctypes.c_int32, [CurvePointer, _size_pointer])
register_prototype(
    "bzj_curve_knots", ctypes.c_int32, [CurvePointer, _double_pointer, _size, _size_pointer]
)
register_prototype("bzj_curve_weights", ctypes.c_int32, [CurvePointer, _double_pointer, _size])
register_prototype(
    "bzj_curve_domain", ctypes.c_int32, [CurvePointer, _double_pointer, _double_pointer]
)
register_prototype("bzj_curve_to_nurbs", ctypes.c_int32, [CurvePointer, _curve_out])
register_prototype(
    "bzj_curve_bezier_spans", ctypes.c_int32, [CurvePointer, _curve_out, _size, _size_pointer]
)
register_prototype(
    "bzj_nurbs_ellipse_arc",
    ctypes.c_int32,
    [_size, _double_pointer, _double_pointer, _double_pointer, ctypes.c_double,
     ctypes.c_double, ctypes.c_double, ctypes.c_double, _curve_out],
)


def _rebuild_nurbs(poles, knots, degree, weights):
    """Unpickling of a NURBS curve (``Curve.__reduce__``)."""
    return Curve.nurbs(poles, knots, degree, weights)


class Curve:
    """A curve in dimension ``dim >= 1``: a polynomial Bezier curve of degree
    ``n >= 0`` on ``[0, 1]``, or a NURBS curve (a B-spline of degree ``p >= 1``,
    polynomial or rational, of one or many spans) on its :attr:`domain`.

    ``Curve(points)`` makes the Bezier curve with the ``n + 1`` control points,
    each a sequence of ``dim`` real numbers (tuples, lists, FreeCAD vectors,
    numpy rows); :meth:`nurbs` and :meth:`ellipse_arc` make NURBS curves. The
    curve is immutable; every operation returns new curves. A NURBS curve's
    operations work in its own parameters: :meth:`evaluate` takes parameters
    in its domain, :meth:`split` and :meth:`segment` keep them.

    The library handle is released by :meth:`close` (or leaving a ``with``
    block); ``__del__`` releases it too if neither happened. Closing twice is
    harmless; using a closed curve raises ``ValueError``.
    """

    def __init__(self, points):
        self._handle = None
        rows, dim = point_rows(points, "points")
        array, length = double_array(flat(rows))
        handle = CurvePointer()
        with point_indices(dim, "points"):
            library().call("bzj_curve_new", dim, len(rows) - 1, array, length,
                           ctypes.byref(handle))
        self._handle = handle
        self._bezier_shape = (len(rows) - 1, dim)

    #: ``(degree, dim)`` of a Bezier curve when the code that made it knows them
    #: (the curve is immutable), else ``None``: spares :meth:`to_freecad` the
    #: ``is_nurbs``, ``degree`` and ``dim`` calls across the C ABI.
    _bezier_shape = None

    @classmethod
    def _adopt(cls, handle, bezier_shape=None):
        """Wrap a handle the library returned (ownership passes to the new object);
        ``bezier_shape``: ``(degree, dim)`` when it is known to be a Bezier curve."""
        curve = cls.__new__(cls)
        curve._handle = handle
        if bezier_shape is not None:
            curve._bezier_shape = bezier_shape
        return curve

    @classmethod
    def nurbs(cls, poles, knots, degree, weights=None):
        """The NURBS curve of degree ``degree >= 1`` with the given poles (each a
        sequence of ``dim`` numbers, Cartesian), flat knot vector (``len(poles) +
        degree + 1`` non-decreasing values: interior multiplicity ``<= degree``,
        end multiplicity ``<= degree + 1``) and weights (``len(poles)`` values
        ``> 0``; ``None`` for a polynomial B-spline) (``bzj_nurbs_new``). The
        domain is ``[knots[degree], knots[len(poles)]]``.

            >>> with Curve.nurbs([(0, 0), (1, 1), (2, 0)], [0, 0, 0, 2, 2, 2], 2) as c:
            ...     c.domain, c.evaluate(1.0)
            ((0.0, 2.0), (1.0, 0.5))

        Raises:
            BezjoinError: naming the argument (``poles``, ``knots``,
                ``weights[i]``, ``degree``...).
        """
        rows, dim = point_rows(poles, "poles")
        degree = index_argument(degree, "degree")
        pole_array, pole_length = double_array(flat(rows))
        knot_values = [real_argument(k, f"knots[{i}]") for i, k in enumerate(knots)]
        knot_array, knot_length = double_array(knot_values)
        if weights is None:
            weight_array, weight_length = None, 0
        else:
            weight_values = [real_argument(w, f"weights[{i}]") for i, w in enumerate(weights)]
            if not weight_values:
                raise BezjoinError.invalid_argument(
                    "weights is empty (None gives a polynomial B-spline)"
                )
            weight_array, weight_length = double_array(weight_values)
        handle = CurvePointer()
        with point_indices(dim, "poles"):
            library().call(
                "bzj_nurbs_new", dim, degree, pole_array, pole_length, weight_array,
                weight_length, knot_array, knot_length, ctypes.byref(handle),
            )
        return cls._adopt(handle)

    @classmethod
    def ellipse_arc(cls, centre, x_axis, y_axis, x_radius, y_radius, a0=0.0, a1=2.0 * math.pi):
        """The exact elliptic arc ``centre + x_radius cos(a) x_axis + y_radius sin(a)
        y_axis``, ``a`` from ``a0`` to ``a1`` (radians, ``a0 < a1 <= a0 + 2 pi``;
        default a full turn), as a rational quadratic NURBS curve in dimension 2
        or 3 on the domain ``[a0, a1]`` (``bzj_nurbs_ellipse_arc``). The axes are
        orthogonal unit vectors; a circle is ``x_radius == y_radius``.

            >>> with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 1, 1, 0, math.pi / 2) as c:
            ...     [round(x, 12) for x in c.evaluate(math.pi / 2)]
            [0.0, 1.0]

        Raises:
            BezjoinError: naming the argument (``dim``, ``x_axis``, ``x_radius``,
                ``a1``...).
        """
        centre_values = [real_argument(x, "centre coordinate") for x in centre]
        dim = len(centre_values)
        arrays = []
        for name, vector in (("centre", centre_values), ("x_axis", x_axis),
                             ("y_axis", y_axis)):
            values = [real_argument(x, f"{name} coordinate") for x in vector]
            if len(values) != dim:
                # The C function reads dim values of each: a shorter one would be overread.
                raise BezjoinError.dimension_mismatch(
                    f"{name} has {len(values)} coordinates but centre has {dim}"
                )
            arrays.append(double_array(values)[0])
        handle = CurvePointer()
        library().call(
            "bzj_nurbs_ellipse_arc", dim, arrays[0], arrays[1], arrays[2],
            real_argument(x_radius, "x_radius"), real_argument(y_radius, "y_radius"),
            real_argument(a0, "a0"), real_argument(a1, "a1"), ctypes.byref(handle),
        )
        return cls._adopt(handle)

    @classmethod
    def from_freecad(cls, edge_or_curve, nurbs=False):
        """The curve of a FreeCAD edge or curve, exactly (3D; poles copied as they are).

        Takes a ``Part.Edge`` (its ``[FirstParameter, LastParameter]`` trims
        the curve; a closed circle edge is the whole turn), a shape holding
        exactly one edge, or a bounded Part curve (``Part.ArcOfCircle``,
        ``Part.Circle``, ``Part.BSplineCurve``...: its own parameter range
        ``[first, last]``). The direction is that of the curve's parameter (an
        edge's ``Orientation`` is not applied). What each FreeCAD curve
        becomes, and how FreeCAD's parameter ``t`` maps to the curve's ``u``:

        - ``Part.LineSegment``/``Part.Line`` edge: the degree-1 Bezier curve
          from ``value(first)`` to ``value(last)``, ``t = first + (last -
          first) u``.
        - ``Part.BezierCurve``, polynomial: the Bezier curve with its poles,
          ``u = t``; an edge on part of it gives that part (:meth:`segment`),
          ``t = first + (last - first) u``. Rational: a one-span NURBS curve
          with its poles and weights, knots 0 and 1, trimmed to ``[first,
          last]``, ``u = t``.
        - ``Part.BSplineCurve``: the NURBS curve with its poles, weights and
          knots (multiplicities expanded), trimmed to ``[first, last]`` by
          knot insertion, ``u = t``. Periodic: first made the clamped,
          non-periodic curve on ``[first, last]`` (FreeCAD's ``segment``, also
          across the seam), ``u = t``; unclamped: clamped by the trim. A
          polynomial, clamped, non-periodic B-spline of ONE span is a Bezier
          curve, as before (STEP files carry Bezier curves so): ``t = first +
          (last - first) u``.
        - ``Part.Parabola`` arcs: the polynomial quadratic NURBS curve on
          ``[first, last]``, ``u = t`` everywhere (the curve FreeCAD's
          ``toBSpline(first, last)`` gives).
        - ``Part.Circle``, ``Part.Ellipse`` (arcs, full turns): the rational
          quadratic :meth:`ellipse_arc` on ``[first, last]`` (centre, ``XAxis``,
          ``YAxis``, radii from FreeCAD); ``Part.Hyperbola`` arcs: the same
          construction with ``cosh``/``sinh``. ``n = ceil((last - first) / (pi
          / 2))`` spans of equal width ``w``; at the knots ``first + i w``,
          ``u = t`` exactly. No rational curve is parametrised by angle, so
          inside a span ``[k, k + w]`` (middle ``m``, ``x = 2 (u - k) / w - 1``)
          ``t = m + 2 atan(x tan(w / 4))`` (circle, ellipse) or ``t = m + 2
          atanh(x tanh(w / 4))`` (hyperbola), and ``|t - u| < 0.017``. This
          is the parametrization of FreeCAD's exact ``edge.toNurbs()``, which
          gives this very curve for an arc of at most a quarter turn (a
          hyperbola arc of width ``<= pi / 2``) but cuts longer arcs into
          other spans (a full circle into three). FreeCAD 0.20's curve
          ``toBSpline``/``toNurbs`` of these conics are polynomial
          approximations, about 1e-8 off.

        With ``nurbs=True`` lines, polynomial Bezier curves and one-span
        B-splines are NURBS curves too, on ``[first, last]`` with ``u = t``:
        then every type but the circle, ellipse and hyperbola keeps FreeCAD's
        parameter, and ``Curve.from_freecad(c.to_freecad(), nurbs=True)``
        gives ``c`` back, pole for pole, for a clamped NURBS curve ``c`` in 3D
        (weights all equal come back as 1).

        ``bezjoin._freecad.freecad_parameter(obj, u, nurbs)`` and
        ``curve_parameter(obj, t, nurbs)`` compute the map for an object.
        Every conversion is checked against FreeCAD's own points before it is
        returned.

        Raises:
            UnsupportedGeometryError: for geometry without an exact NURBS form
                (``Part.OffsetCurve``, ...: the message says how to
                approximate it), 2D ``Part.Geom2d`` curves, unbounded curves, a
                shape with other than one edge, or outside FreeCAD.
        """
        if not nurbs:
            fast = _freecad.native()
            if fast is not None:
                # The compiled route (bezjoin/_native.c) of the verbatim fast path.
                curve = fast.curve_new(edge_or_curve, cls)
                if curve is not None:
                    return curve
                return _freecad.curve_from_freecad(cls, edge_or_curve, nurbs, True)
        return _freecad.curve_from_freecad(cls, edge_or_curve, nurbs)

    def to_freecad(self):
        """This curve as FreeCAD geometry (dim 3, or dim 2 placed at z = 0): a
        Bezier curve as a ``Part.BezierCurve`` (same poles, parameter on
        ``[0, 1]``), a NURBS curve as a non-periodic ``Part.BSplineCurve`` with
        the same poles, weights (for a rational curve), degree and knots (as
        distinct knots and multiplicities), so with the same parameters
        (FreeCAD's ``FirstParameter``/``LastParameter`` are the :attr:`domain`).

        Raises:
            UnsupportedGeometryError: dim other than 2 or 3, degree 0, a degree
                above OpenCASCADE's maximum of 25, or outside FreeCAD.
        """
        shape = self._bezier_shape
        if shape is None:
            if self.is_nurbs:
                weights = self.weights if self.is_rational else None
                return _freecad.bspline_curve(self.points, self.knots, self.degree, weights,
                                              self.dim)
            shape = self.degree, self.dim
        # A Bezier curve has degree + 1 points: no pole_count call.
        degree, dim = shape
        if dim == 3:
            fast = _freecad.native()
            if fast is not None:
                curve = fast.bezier_curve(self._live(), degree)
                if curve is not None:
                    return curve
        return _freecad.bezier_curve(self._read_points(degree + 1, dim), degree, dim)

    def to_edge(self):
        """This curve as a ``Part.Edge`` on its :attr:`domain` (see :meth:`to_freecad`)."""
        first, last = self.domain
        return _freecad.edge(self.to_freecad(), first, last)

    # -- handle lifetime ---------------------------------------------------

    def close(self):
        """Release the library handle now (idempotent)."""
        with _close_lock:
            handle, self._handle = self._handle, None
        if handle:
            fast = _freecad.native_module()
            if fast is not None:
                fast.curve_free(handle)
            else:
                library().function("bzj_curve_free")(handle)

    def copy(self):
        """An independent curve with the same control points (its own handle; a
        NURBS curve stays a NURBS curve)."""
        if self.is_nurbs:
            return self.to_nurbs()
        return Curve(self.points)

    def __copy__(self):
        # A shallow copy would share the handle and free it twice.
        return self.copy()

    def __deepcopy__(self, memo):
        return self.copy()

    def __reduce__(self):
        if self.is_nurbs:
            weights = self.weights if self.is_rational else None
            return (_rebuild_nurbs, (self.points, self.knots, self.degree, weights))
        return (Curve, (self.points,))

    @property
    def closed(self):
        """Whether :meth:`close` has released the handle."""
        return not self._handle

    def __enter__(self):
        self._live()
        return self

    def __exit__(self, *exception):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown: the library may be gone
            pass

    def _live(self):
        handle = self._handle
        if not handle:
            raise ValueError("operation on a closed Curve")
        return handle

    # -- inspection ----------------------------------------------------------

    @property
    def degree(self):
        """The degree (a Bezier curve of degree ``n`` has ``n + 1`` control points)."""
        out = ctypes.c_size_t()
        library().call("bzj_curve_degree", self._live(), ctypes.byref(out))
        return out.value

    @property
    def dim(self):
        """The dimension of the space the curve lives in."""
        out = ctypes.c_size_t()
        library().call("bzj_curve_dim", self._live(), ctypes.byref(out))
        return out.value

    @property
    def points(self):
        """The control points (``degree + 1`` of a Bezier curve) or poles (of a NURBS
        curve, Cartesian): a list of :attr:`pole_count` tuples of ``dim`` floats."""
        return self._read_points(self.pole_count, self.dim)

    def _read_points(self, count, dim):
        handle = self._live()
        buffer = (ctypes.c_double * max(count * dim, 1))()
        library().call("bzj_curve_points", handle, buffer, count * dim)
        return rows_of(buffer, count, dim)

    @property
    def is_nurbs(self):
        """Whether this is a NURBS curve (``False``: a Bezier curve)."""
        out = ctypes.c_bool()
        library().call("bzj_curve_is_nurbs", self._live(), ctypes.byref(out))
        return out.value

    @property
    def is_rational(self):
        """Whether this is a NURBS curve whose weights are not all equal."""
        out = ctypes.c_bool()
        library().call("bzj_curve_is_rational", self._live(), ctypes.byref(out))
        return out.value

    @property
    def pole_count(self):
        """The number of poles (``degree + 1`` for a Bezier curve)."""
        out = ctypes.c_size_t()
        library().call("bzj_curve_pole_count", self._live(), ctypes.byref(out))
        return out.value

    @property
    def knots(self):
        """The flat knot vector, ``pole_count + degree + 1`` floats (a Bezier curve:
        0 and 1, each ``degree + 1`` times)."""
        handle = self._live()
        count = ctypes.c_size_t()
        library().call("bzj_curve_knots", handle, None, 0, ctypes.byref(count))
        buffer = (ctypes.c_double * max(count.value, 1))()
        library().call("bzj_curve_knots", handle, buffer, count.value, ctypes.byref(count))
        return list(buffer[:count.value])

    @property
    def weights(self):
        """The ``pole_count`` weights (all 1.0 unless :attr:`is_rational`)."""
        handle = self._live()
        count = self.pole_count
        buffer = (ctypes.c_double * max(count, 1))()
        library().call("bzj_curve_weights", handle, buffer, count)
        return list(buffer[:count])

    @property
    def domain(self):
        """The parameter domain ``(first, last)``: ``(0.0, 1.0)`` for a Bezier curve."""
        first, last = ctypes.c_double(), ctypes.c_double()
        library().call("bzj_curve_domain", self._live(), ctypes.byref(first),
                       ctypes.byref(last))
        return first.value, last.value

    def __repr__(self):
        if self.closed:
            return "Curve(<closed>)"
        if self.is_nurbs:
            weights = self.weights if self.is_rational else None
            return (f"Curve.nurbs({self.points!r}, {self.knots!r}, {self.degree!r}, "
                    f"weights={weights!r})")
        return f"Curve({self.points!r})"

    # -- evaluation ----------------------------------------------------------

    def derivatives(self, t, max_order):
        """Value and derivatives ``0..max_order`` at ``t`` (any order; a Bezier curve
        takes any finite ``t``, a NURBS curve ``t`` in its :attr:`domain`, from the
        span on the right of an interior knot).

        Returns a list of ``max_order + 1`` tuples: item ``k`` is the k-th
        derivative with respect to the curve's parameter.
        """
        handle = self._live()
        t = real_argument(t, "t")
        max_order = index_argument(max_order, "max_order")
        dim = self.dim
        length = (max_order + 1) * dim
        buffer = double_buffer(length, "max_order")
        library().call("bzj_curve_eval", handle, t, max_order, buffer, length)
        return rows_of(buffer, max_order + 1, dim)

    def derivatives_many(self, ts, max_order=0):
        """Value and derivatives ``0..max_order`` at every parameter of ``ts``
        in one library call (for tessellation).

        Returns a list with one item per parameter, each as
        :meth:`derivatives` returns it.
        """
        handle = self._live()
        ts = [real_argument(t, f"ts[{i}]") for i, t in enumerate(ts)]
        max_order = index_argument(max_order, "max_order")
        dim = self.dim
        block = (max_order + 1) * dim
        length = len(ts) * block
        params = (ctypes.c_double * len(ts))(*ts)
        buffer = double_buffer(length, "max_order")
        library().call("bzj_curve_eval_many", handle, params, len(ts), max_order, buffer, length)
        rows = rows_of(buffer, len(ts) * (max_order + 1), dim)
        return [rows[i * (max_order + 1):(i + 1) * (max_order + 1)] for i in range(len(ts))]

    def evaluate(self, t):
        """The point at ``t`` (a Bezier curve: outside ``[0, 1]`` the polynomial is
        continued; a NURBS curve: ``t`` in its :attr:`domain`)."""
        return self.derivatives(t, 0)[0]

    __call__ = evaluate

    def length(self, a=None, b=None):
        """Signed arc length from parameter ``a`` to ``b`` (default: the ends of the
        :attr:`domain`, ``0`` and ``1`` for a Bezier curve; a NURBS curve takes both
        in its domain), to an absolute accuracy of ``1e-13 * max(1, control
        polygon length)``."""
        handle = self._live()
        if a is None or b is None:
            first, last = self.domain
            a = first if a is None else a
            b = last if b is None else b
        out = ctypes.c_double()
        library().call(
            "bzj_curve_length", handle, real_argument(a, "a"), real_argument(b, "b"),
            ctypes.byref(out),
        )
        return out.value

    # -- exact operations ------------------------------------------------------

    def elevate(self, new_degree):
        """The same curve written with degree ``new_degree >= degree`` (a NURBS curve:
        every span raised, same domain)."""
        out = CurvePointer()
        library().call(
            "bzj_curve_elevate", self._live(), index_argument(new_degree, "new_degree"),
            ctypes.byref(out),
        )
        return Curve._adopt(out)

    def split(self, t):
        """The pieces on ``[0, t]`` and ``[t, 1]`` (``t`` in ``[0, 1]``), each over
        ``[0, 1]``; a NURBS curve: ``t`` inside its domain ``(first, last)``, the
        pieces on ``[first, t]`` and ``[t, last]`` with the original parameters."""
        left, right = CurvePointer(), CurvePointer()
        library().call(
            "bzj_curve_split", self._live(), real_argument(t, "t"), ctypes.byref(left),
            ctypes.byref(right),
        )
        return Curve._adopt(left), Curve._adopt(right)

    def segment(self, a, b):
        """The curve ``s -> self(a + (b - a) s)`` for any finite ``a``, ``b``; a NURBS
        curve: the piece on ``[a, b]`` (``first <= a < b <= last``) with the
        original parameters."""
        out = CurvePointer()
        library().call(
            "bzj_curve_segment", self._live(), real_argument(a, "a"), real_argument(b, "b"),
            ctypes.byref(out),
        )
        return Curve._adopt(out)

    def reverse(self):
        """The curve traversed backwards, ``s -> self(1 - s)``; a NURBS curve:
        ``u -> self(first + last - u)`` on the same domain."""
        out = CurvePointer()
        library().call("bzj_curve_reverse", self._live(), ctypes.byref(out))
        return Curve._adopt(out)

    # -- NURBS -------------------------------------------------------------------

    def to_nurbs(self):
        """The same curve as a NURBS curve (a Bezier curve: one span on ``[0, 1]``,
        a point raised to degree 1; a NURBS curve: a copy)."""
        out = CurvePointer()
        library().call("bzj_curve_to_nurbs", self._live(), ctypes.byref(out))
        return Curve._adopt(out)

    def bezier_spans(self):
        """The Bezier spans in order, a list of new curves: a polynomial span as a
        Bezier curve (the span reparametrised to ``[0, 1]``), a rational span as a
        one-span NURBS curve with the original parameters. Span ``i`` covers
        ``[k_i, k_(i+1)]``, the distinct knots of the domain."""
        handle = self._live()
        count = ctypes.c_size_t()
        library().call("bzj_curve_bezier_spans", handle, None, 0, ctypes.byref(count))
        slots = (CurvePointer * max(count.value, 1))()
        library().call("bzj_curve_bezier_spans", handle, slots, count.value,
                       ctypes.byref(count))
        return [Curve._adopt(slots[i]) for i in range(count.value)]


def handle_of(curve, name):
    """The live handle of a :class:`Curve` argument named ``name``."""
    if not isinstance(curve, Curve):
        raise TypeError(f"{name} must be a bezjoin.Curve, not {type(curve).__name__}")
    return curve._live()
