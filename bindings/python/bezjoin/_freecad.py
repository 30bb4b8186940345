"""Conversion between FreeCAD's Part geometry and Bezier control points.

``Part`` is imported only when a conversion is asked for, so the package
works without FreeCAD.
"""

from .errors import UnsupportedGeometryError

#: OpenCASCADE's ``Geom_BezierCurve::MaxDegree()``.
MAXIMUM_FREECAD_DEGREE = 25


def _part():
    try:
        import Part  # noqa: PLC0415 (FreeCAD only)
    except ImportError as error:
        raise UnsupportedGeometryError(
            "FreeCAD's Part module is not importable (run inside FreeCAD or freecadcmd)"
        ) from error
    return Part


def _vector(x, y, z):
    import FreeCAD  # noqa: PLC0415 (FreeCAD only)

    return FreeCAD.Vector(x, y, z)


def _describe(obj):
    return type(obj).__name__


def bezier_poles(obj):
    """``(poles, a, b)``: the Bezier poles of ``obj``'s curve and the part of it
    in use, as parameters ``a < b`` of that Bezier curve over ``[0, 1]``.

    See :meth:`bezjoin.Curve.from_freecad` for what is accepted.
    """
    part = _part()
    if isinstance(obj, part.Edge):
        edge = obj
    elif isinstance(obj, part.Shape):
        edges = obj.Edges
        if len(edges) != 1:
            raise UnsupportedGeometryError(
                f"the shape has {len(edges)} edges; select exactly one edge"
            )
        edge = edges[0]
    else:
        edge = None
    curve = edge.Curve if edge is not None else obj
    if isinstance(curve, (part.Line, part.LineSegment)):
        if edge is None:
            if isinstance(curve, part.Line):
                raise UnsupportedGeometryError("an unbounded Part.Line is not a Bezier curve")
            first, last = curve.FirstParameter, curve.LastParameter
        else:
            first, last = edge.FirstParameter, edge.LastParameter
        start, end = curve.value(first), curve.value(last)
        return [tuple(start), tuple(end)], 0.0, 1.0
    if isinstance(curve, part.BezierCurve):
        if curve.isRational():
            raise UnsupportedGeometryError(
                "the Bezier curve is rational (weights differ); bezjoin handles polynomial curves"
            )
        start, end = 0.0, 1.0
    elif isinstance(curve, part.BSplineCurve):
        if curve.isPeriodic():
            raise UnsupportedGeometryError("the B-spline is periodic; only single-span clamped "
                                           "B-splines are Bezier curves")
        if curve.NbKnots != 2:
            raise UnsupportedGeometryError(
                f"the B-spline has {curve.NbKnots - 1} spans; only a single-span B-spline "
                "is a Bezier curve (split it into its Bezier pieces first)"
            )
        if curve.isRational():
            raise UnsupportedGeometryError(
                "the B-spline is rational (weights differ); bezjoin handles polynomial curves"
            )
        start, end = curve.getKnots()
    else:
        raise UnsupportedGeometryError(
            f"a {_describe(curve)} is not a Bezier curve; bezjoin takes Bezier curves, "
            "single-span B-splines and line segments"
        )
    poles = [tuple(pole) for pole in curve.getPoles()]
    if edge is None:
        return poles, 0.0, 1.0
    first, last = edge.FirstParameter, edge.LastParameter
    if (first, last) == (start, end):
        return poles, 0.0, 1.0
    width = end - start
    return poles, (first - start) / width, (last - start) / width


def bezier_curve(points, degree, dim):
    """A ``Part.BezierCurve`` with these control points (dim 2 is placed at z = 0)."""
    part = _part()
    if dim not in (2, 3):
        raise UnsupportedGeometryError(f"a curve of dimension {dim} has no FreeCAD form (2 or 3)")
    if degree == 0:
        raise UnsupportedGeometryError("a degree-0 curve (one point) has no Part.BezierCurve form")
    if degree > MAXIMUM_FREECAD_DEGREE:
        raise UnsupportedGeometryError(
            f"degree {degree} is above OpenCASCADE's maximum Bezier degree "
            f"{MAXIMUM_FREECAD_DEGREE}"
        )
    vectors = [_vector(p[0], p[1], p[2] if dim == 3 else 0.0) for p in points]
    curve = part.BezierCurve()
    curve.setPoles(vectors)
    return curve


def edge(curve):
    """A ``Part.Edge`` on ``curve``."""
    return _part().Edge(curve)
