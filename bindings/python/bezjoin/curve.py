"""The Bezier curve: an owned ``BzjCurve`` handle with a Pythonic face."""

import ctypes
import threading

from . import _freecad
from ._convert import double_array, flat, index_argument, point_rows, real_argument, rows_of
from ._library import CurvePointer, library

_close_lock = threading.Lock()


class Curve:
    """A polynomial Bezier curve of degree ``n >= 0`` in dimension ``dim >= 1``.

    ``Curve(points)`` takes the ``n + 1`` control points, each a sequence of
    ``dim`` real numbers (tuples, lists, FreeCAD vectors, numpy rows). The
    curve is immutable; every operation returns new curves.

    The library handle is released by :meth:`close` (or leaving a ``with``
    block); ``__del__`` releases it too if neither happened. Closing twice is
    harmless; using a closed curve raises ``ValueError``.
    """

    def __init__(self, points):
        self._handle = None
        rows, dim = point_rows(points, "points")
        array, length = double_array(flat(rows))
        handle = CurvePointer()
        library().call("bzj_curve_new", dim, len(rows) - 1, array, length, ctypes.byref(handle))
        self._handle = handle

    @classmethod
    def _adopt(cls, handle):
        """Wrap a handle the library returned (ownership passes to the new object)."""
        curve = cls.__new__(cls)
        curve._handle = handle
        return curve

    @classmethod
    def from_freecad(cls, edge_or_curve):
        """The Bezier curve of a FreeCAD edge or curve (3D; the poles are copied exactly).

        Accepted: ``Part.BezierCurve`` (non-rational), ``Part.BSplineCurve``
        with a single span (non-rational, non-periodic: it IS a Bezier curve,
        parametrised over its two knots), ``Part.Line``/``Part.LineSegment``
        (degree 1), a ``Part.Edge`` on any of these (an edge trimmed to a part
        of its curve gives that part, exactly, by :meth:`segment`), or a shape
        holding exactly one edge. The direction is that of the underlying
        curve's parameter.

        Raises:
            UnsupportedGeometryError: for anything else, saying why.
        """
        points, first, last = _freecad.bezier_poles(edge_or_curve)
        curve = cls(points)
        if (first, last) == (0.0, 1.0):
            return curve
        with curve:
            return curve.segment(first, last)

    def to_freecad(self):
        """This curve as a ``Part.BezierCurve`` (dim 3, or dim 2 placed at z = 0).

        Raises:
            UnsupportedGeometryError: for dim other than 2 or 3, degree 0, or a
                degree above OpenCASCADE's maximum of 25.
        """
        return _freecad.bezier_curve(self.points, self.degree, self.dim)

    def to_edge(self):
        """This curve as a ``Part.Edge`` (see :meth:`to_freecad`)."""
        return _freecad.edge(self.to_freecad())

    # -- handle lifetime ---------------------------------------------------

    def close(self):
        """Release the library handle now (idempotent)."""
        with _close_lock:
            handle, self._handle = self._handle, None
        if handle:
            library().function("bzj_curve_free")(handle)

    def copy(self):
        """An independent curve with the same control points (its own handle)."""
        return Curve(self.points)

    def __copy__(self):
        # A shallow copy would share the handle and free it twice.
        return self.copy()

    def __deepcopy__(self, memo):
        return self.copy()

    def __reduce__(self):
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
        """The degree ``n`` (``n + 1`` control points)."""
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
        """The control points, a list of ``degree + 1`` tuples of ``dim`` floats."""
        handle = self._live()
        count, dim = self.degree + 1, self.dim
        buffer = (ctypes.c_double * (count * dim))()
        library().call("bzj_curve_points", handle, buffer, count * dim)
        return rows_of(buffer, count, dim)

    def __repr__(self):
        if self.closed:
            return "Curve(<closed>)"
        return f"Curve({self.points!r})"

    # -- evaluation ----------------------------------------------------------

    def derivatives(self, t, max_order):
        """Value and derivatives ``0..max_order`` at ``t`` (any finite ``t``).

        Returns a list of ``max_order + 1`` tuples: item ``k`` is the k-th
        derivative with respect to the curve's parameter.
        """
        handle = self._live()
        t = real_argument(t, "t")
        max_order = index_argument(max_order, "max_order")
        dim = self.dim
        length = (max_order + 1) * dim
        buffer = (ctypes.c_double * length)()
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
        buffer = (ctypes.c_double * length)()
        library().call("bzj_curve_eval_many", handle, params, len(ts), max_order, buffer, length)
        rows = rows_of(buffer, len(ts) * (max_order + 1), dim)
        return [rows[i * (max_order + 1):(i + 1) * (max_order + 1)] for i in range(len(ts))]

    def evaluate(self, t):
        """The point at ``t`` (outside ``[0, 1]`` the polynomial is continued)."""
        return self.derivatives(t, 0)[0]

    __call__ = evaluate

    def length(self, a=0.0, b=1.0):
        """Signed arc length from parameter ``a`` to ``b`` (adaptive Gauss-Legendre,
        absolute accuracy ``1e-13 * max(1, control polygon length)``)."""
        out = ctypes.c_double()
        library().call(
            "bzj_curve_length", self._live(), real_argument(a, "a"), real_argument(b, "b"),
            ctypes.byref(out),
        )
        return out.value

    # -- exact operations ------------------------------------------------------

    def elevate(self, new_degree):
        """The same curve written with degree ``new_degree >= degree``."""
        out = CurvePointer()
        library().call(
            "bzj_curve_elevate", self._live(), index_argument(new_degree, "new_degree"),
            ctypes.byref(out),
        )
        return Curve._adopt(out)

    def split(self, t):
        """The pieces on ``[0, t]`` and ``[t, 1]`` (``t`` in ``[0, 1]``), each over ``[0, 1]``."""
        left, right = CurvePointer(), CurvePointer()
        library().call(
            "bzj_curve_split", self._live(), real_argument(t, "t"), ctypes.byref(left),
            ctypes.byref(right),
        )
        return Curve._adopt(left), Curve._adopt(right)

    def segment(self, a, b):
        """The curve ``s -> self(a + (b - a) s)`` for any finite ``a``, ``b``."""
        out = CurvePointer()
        library().call(
            "bzj_curve_segment", self._live(), real_argument(a, "a"), real_argument(b, "b"),
            ctypes.byref(out),
        )
        return Curve._adopt(out)

    def reverse(self):
        """The curve traversed backwards, ``s -> self(1 - s)``."""
        out = CurvePointer()
        library().call("bzj_curve_reverse", self._live(), ctypes.byref(out))
        return Curve._adopt(out)


def handle_of(curve, name):
    """The live handle of a :class:`Curve` argument named ``name``."""
    if not isinstance(curve, Curve):
        raise TypeError(f"{name} must be a bezjoin.Curve, not {type(curve).__name__}")
    return curve._live()
