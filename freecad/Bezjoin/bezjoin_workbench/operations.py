"""The workbench operations as plain functions: edges and numbers in, Part shapes out.

No GUI here: the commands (``commands.py``) only collect the selection and
the parameters and call these, and the headless tests call them directly.

Edges may be any curve with an exact NURBS form (lines, circles and arcs,
ellipses, parabola and hyperbola arcs, Bezier curves, B-splines: see
:meth:`bezjoin.Curve.from_freecad`); anything else (offset curves, ...)
raises :class:`bezjoin.UnsupportedGeometryError` naming the edge. A NURBS
curve keeps the edge's own parameter range (its domain), so positions along
an edge are given here as fractions of that range (0 = start, 1 = end).
"""

import math
import re

import FreeCAD
import Part

from . import ensure_bindings_importable

bezjoin = ensure_bindings_importable()

#: Ends closer than this (relative to the edge lengths, at least 1) count as one
#: vertex: FreeCAD's ``Precision::Confusion()``.
TOUCH_TOLERANCE = 1e-7


#: The highest degree of a Bezier edge OpenCASCADE builds (``Geom_BezierCurve::MaxDegree``);
#: a blend of orders ``p`` and ``q`` has degree ``p + q + 1``.
MAX_BEZIER_DEGREE = 25

#: Merging two edges whose tangents turn by more than this many degrees at the join is
#: refused (:func:`merge_edges`, keyword ``max_angle``): one edge cannot follow a corner.
MAX_MERGE_ANGLE_DEGREES = 30.0

#: A join of a wire whose tangents turn by less than this many degrees is smooth (a
#: line running tangentially into an arc, two collinear lines): :func:`round_wire` and
#: :func:`round_wire_by_radius` leave it as it is and round the wire's other corners.
#: Above the library's own "tangential" limit (a sine of 1e-6, 5.7e-5 degrees), so no
#: join the library would refuse as smooth is passed to it.
SMOOTH_JOIN_DEGREES = 1e-3

#: Points sampled along each edge (the merged edge and both sources) for the merge's
#: geometric deviation (:func:`edge_deviation`, :class:`MergedEdge`).
DEVIATION_SAMPLES = 200

#: The default setback of :func:`round_corner` (and of the command's form): this
#: fraction of the shorter edge's length, so it scales with the model.
DEFAULT_SETBACK_FRACTION = 0.1

_ARTICLE = re.compile(r"\b([Aa]) (?=[AEIOUaeiou])")


def with_articles(message):
    """``message`` with "a" before a vowel written "an" ("an Ellipse")."""
    return _ARTICLE.sub(lambda m: m.group(1) + "n ", message)


def edge_curve(edge, name):
    """The :class:`bezjoin.Curve` of ``edge``; the error names the edge (``name``)."""
    try:
        return bezjoin.Curve.from_freecad(edge)
    except bezjoin.UnsupportedGeometryError as error:
        raise bezjoin.UnsupportedGeometryError(with_articles(f"{name}: {error}")) from None


def _invalid(message):
    return bezjoin.BezjoinError.invalid_argument(message)


def same_edge(first_edge, second_edge, tolerance=TOUCH_TOLERANCE):
    """Whether two edges are the same edge (the same FreeCAD shape, or the same ends and
    middle point, in either direction)."""
    try:
        if first_edge.isSame(second_edge):
            return True
    except (AttributeError, TypeError):
        pass
    try:
        def samples(edge):
            first, last = edge.FirstParameter, edge.LastParameter
            return [edge.valueAt(first + f * (last - first)) for f in (0.0, 0.5, 1.0)]
        a, b = samples(first_edge), samples(second_edge)
    except Exception:  # noqa: BLE001 (a degenerate edge: not comparable, not the same)
        return False
    size = max(1.0, first_edge.Length, second_edge.Length)
    limit = tolerance * size
    return (all(_distance(x, y) <= limit for x, y in zip(a, b))
            or all(_distance(x, y) <= limit for x, y in zip(a, reversed(b))))


def check_edges(edges):
    """Refuse edges no operation can take, before any form is shown: each must convert
    (:class:`bezjoin.UnsupportedGeometryError` naming "first edge"/"second edge" for a
    pair, else "edge i"), and no edge may be
    given twice (:class:`bezjoin.BezjoinError`)."""
    edges = list(edges)
    names = (["first edge", "second edge"] if len(edges) == 2
             else [f"edge {i + 1}" for i in range(len(edges))])
    for name, edge in zip(names, edges):
        edge_curve(edge, name).close()
    for i in range(len(edges)):
        for j in range(i + 1, len(edges)):
            if same_edge(edges[i], edges[j]):
                raise _invalid(f"the {names[i]} and the {names[j]} are the same edge: select "
                               "different edges")
    return edges


def _check_orders(p_order, q_order, p, q):
    """Refuse orders whose blend (degree ``p_order + q_order + 1``) OpenCASCADE cannot
    hold, before building it."""
    p_order = p.degree if p_order is None else p_order
    q_order = q.degree if q_order is None else q_order
    degree = p_order + q_order + 1
    if degree > MAX_BEZIER_DEGREE:
        raise _invalid(
            f"orders {p_order} and {q_order} give a blend of degree {degree}, above "
            f"OpenCASCADE's maximum Bezier degree {MAX_BEZIER_DEGREE}: keep p_order + q_order "
            f"at most {MAX_BEZIER_DEGREE - 1}")


def _size(*curves):
    return max([1.0] + [c.length() for c in curves])


def placement_to_model(obj):
    """The placement taking ``obj.Shape`` (local to its containers: Body, Part) to model
    (global) coordinates: the containers' placements."""
    return obj.getGlobalPlacement().multiply(obj.Placement.inverse())


def model_shape(obj, subnames=()):
    """``obj``'s shape, or its sub-elements named in ``subnames`` ("Edge1", ...), in model
    (global) coordinates: a sketch or feature inside a placed Body or Part is moved by
    the containers' placements (FreeCAD's ``obj.Shape`` leaves them out). One name gives
    that element; several give a list."""
    shape = obj.Shape.copy()
    shape.Placement = placement_to_model(obj).multiply(shape.Placement)
    if not subnames:
        return shape
    if isinstance(subnames, str):
        return shape.getElement(subnames)
    return [shape.getElement(name) for name in subnames]


def path_edges(shape):
    """The edges of a path in order: a ``Part.Wire`` (its ``OrderedEdges``), a shape
    holding one wire (a sketch's shape), a shape of loose edges that form one path
    (sorted into path order), or a sequence of edges (taken as given)."""
    if isinstance(shape, (list, tuple)):
        return list(shape)
    if getattr(shape, "ShapeType", None) == "Wire":
        return list(shape.OrderedEdges)
    if getattr(shape, "ShapeType", None) == "Edge":
        return [shape]
    wires = getattr(shape, "Wires", [])
    if len(wires) == 1 and len(wires[0].Edges) == len(shape.Edges):
        return list(wires[0].OrderedEdges)
    edges = list(getattr(shape, "Edges", []))
    if not edges:
        raise _invalid("the shape has no edges to round")
    sorted_groups = Part.sortEdges(edges)
    if len(sorted_groups) != 1:
        raise _invalid(f"the edges form {len(sorted_groups)} separate paths, not one wire")
    return list(sorted_groups[0])


def _distance(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)))


def _ends(curve):
    """The curve's first and last points (at the ends of its domain)."""
    first, last = curve.domain
    return curve.evaluate(first), curve.evaluate(last)


def _at_fraction(curve, fraction):
    """The parameter at ``fraction`` (0 = start, 1 = end) of the curve's domain."""
    first, last = curve.domain
    if fraction == 1.0:
        return last
    return first + fraction * (last - first)


def orient_end_to_start(p, q):
    """``(p, q)`` possibly reversed so that ``p`` ends where ``q`` starts, or as
    close as the four end pairings allow. Returns new curves (the caller closes
    ``p`` and ``q`` as before; the returned ones are owned by the caller too)."""
    p_ends = _ends(p)
    q_ends = _ends(q)
    # On a tie, keep the curves as they are (end of p to start of q).
    _gap, _reversals, p_end, q_end = min(
        (_distance(p_ends[i], q_ends[j]), (i == 0) + (j == 1), i, j)
        for i in (0, 1) for j in (0, 1))
    p_oriented = p.reverse() if p_end == 0 else p.copy()
    q_oriented = q.reverse() if q_end == 1 else q.copy()
    return p_oriented, q_oriented


def _wire(curves):
    edges = [curve.to_edge() for curve in curves]
    return Part.Wire(edges)


def _fraction(value):
    """The parameter of ``_at_fraction`` on the domain [0, 1] of a Bezier curve, the
    same float, when ``value`` is a plain number (not a bool); else ``None``."""
    if type(value) not in (float, int):
        return None
    return 1.0 if value == 1.0 else 0.0 + value * (1.0 - 0.0)


def _polygon_length(values):
    """The length of the control polygon of the 3D poles with flat coordinates ``values``:
    at least the length of the Bezier curve."""
    rows = [values[i:i + 3] for i in range(0, len(values), 3)]
    return sum(_distance(a, b) for a, b in zip(rows, rows[1:]))


def _blend_bezier_edges(first_edge, second_edge, u0, v0, p_order, q_order, p_scale,
                        q_scale, auto_scale, orient):
    """:func:`blend_edges` by :func:`bezjoin.connect_edges` (the fast path) when both
    edges lie on the whole of polynomial ``Part.BezierCurve``s that
    :meth:`bezjoin.Curve.from_freecad` copies verbatim, the orientation keeps them as
    they are and the blend's ends are clearly apart: then the general path makes
    the same curve (same poles, same parameter [0, 1]: ``connect_edges`` is
    ``connect`` of these curves bit for bit) and passes its checks. Otherwise
    ``None``: the general path decides and words any error."""
    verbatim = bezjoin._freecad._verbatim_values
    u, v = _fraction(u0), _fraction(v0)
    p_found = u is not None and v is not None and verbatim(first_edge, Part)
    q_found = p_found and verbatim(second_edge, Part)
    if not q_found:
        return None
    (p_values, p_degree), (q_values, q_degree) = p_found, q_found
    orders = [p_degree if p_order is None else p_order, q_degree if q_order is None else q_order]
    if any(type(order) is not int or order < 0 for order in orders) \
            or sum(orders) + 1 > MAX_BEZIER_DEGREE:
        return None
    if orient:
        # orient_end_to_start on the exact end points (the first and last poles).
        p_ends, q_ends = (p_values[:3], p_values[-3:]), (q_values[:3], q_values[-3:])
        pairing = min((_distance(p_ends[i], q_ends[j]), (i == 0) + (j == 1), i, j)
                      for i in (0, 1) for j in (0, 1))
        if pairing[2:] != (1, 0):
            return None
    # Both edges run on [0, 1] (verbatim), so ``u``, ``v`` are their parameters.
    if _automatic(p_scale, q_scale, auto_scale) and _speeds_differ(
            first_edge.derivative1At(u).Length, second_edge.derivative1At(v).Length):
        return None  # the general path balances the end speeds (auto_scale="balanced")
    try:
        curve = bezjoin.connect_edges(first_edge, u, second_edge, v, p_order=orders[0],
                                      q_order=orders[1], p_scale=p_scale, q_scale=q_scale,
                                      auto_scale=auto_scale)
    except Exception:  # noqa: BLE001 (the general path words it)
        return None
    poles = curve.getPoles()
    start, end = tuple(poles[0]), tuple(poles[-1])
    # The general path refuses a gap <= TOUCH_TOLERANCE * max(1, lengths); the
    # control polygons bound the lengths from above, the margin covers rounding.
    size = max(1.0, _polygon_length(p_values), _polygon_length(q_values))
    reach = max(map(abs, p_values + q_values))
    if not _distance(start, end) > TOUCH_TOLERANCE * size * (1.0 + 1e-9) + 1e-12 * reach:
        return None
    return Part.Edge(curve, 0.0, 1.0)


def blend_edges(first_edge, second_edge, *, u0=1.0, v0=0.0, p_order=None, q_order=None,
                p_scale=None, q_scale=None, auto_scale=None, orient=True):
    """The blend curve from ``first_edge`` at ``u0`` to ``second_edge`` at ``v0``
    (:func:`bezjoin.connect`), as a ``Part.Edge``.

    ``u0`` and ``v0`` are fractions of each edge's parameter range (0 = start,
    1 = end). With ``orient`` (the default) the edges are first reversed as
    needed so that the end of the first faces the start of the second (the
    closest pair of ends), and ``u0``/``v0`` refer to these oriented curves:
    the defaults ``u0 = 1``, ``v0 = 0`` bridge the gap between the facing ends.
    ``p_order``/``q_order`` default to each curve's degree (the paper); any
    order is allowed (a line's derivatives above the first are zero, a
    circle has every order).

    The scale is automatic by default (:func:`bezjoin.connect` without scales:
    least bending energy), so the blend never loops; ``p_scale``/``q_scale``
    (or ``auto_scale=False`` for the paper's 1.0) give the raw construction,
    and ``auto_scale=True`` ignores given scales (the rule of
    :func:`bezjoin.connect`).
    """
    if same_edge(first_edge, second_edge):
        raise _invalid("the first and the second edge are the same edge: select two "
                       "different edges")
    fast = _blend_bezier_edges(first_edge, second_edge, u0, v0, p_order, q_order, p_scale,
                               q_scale, auto_scale, orient)
    if fast is not None:
        return fast
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        _check_orders(p_order, q_order, p, q)
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.copy(), q.copy()
        with p, q:
            u, v = _at_fraction(p, u0), _at_fraction(q, v0)
            start, end = p.evaluate(u), q.evaluate(v)
            if _distance(start, end) <= TOUCH_TOLERANCE * _size(p, q):
                # A blend between two coincident points is a closed loop: never wanted.
                raise _invalid(
                    "the blend would start and end at the same point "
                    f"({', '.join(f'{x:.6g}' for x in start)}): the edges share a vertex "
                    "there. Use Round corner to round that corner, or choose positions "
                    "u0/v0 apart")
            # The automatic scale leaves both edges at one speed (the library's
            # balanced scale): with one s for both, lines 1000 and 10 long blended
            # across a gap of 2 at 90 degrees peaked at curvature 6472, lines 10 and
            # 10 at 0.67 (user testing, session 40). Where the speeds agree it is the
            # one-s scale, the bits of the fast path (connect_edges).
            balanced = "balanced" if _automatic(p_scale, q_scale, auto_scale) else auto_scale
            with bezjoin.connect(p, u, q, v, p_order=p_order, q_order=q_order,
                                 p_scale=p_scale, q_scale=q_scale,
                                 auto_scale=balanced) as blend:
                return blend.to_edge()


def default_setback(edges):
    """The default setback: ``DEFAULT_SETBACK_FRACTION`` of the shortest edge's length."""
    return DEFAULT_SETBACK_FRACTION * min(edge.Length for edge in edges)


def _snapped_start(q, point):
    """``q`` (a Bezier or clamped NURBS curve) with its first pole moved to ``point``:
    closes a solver's tiny gap at a vertex. A new curve (the caller closes it)."""
    poles = [tuple(point)] + [tuple(x) for x in q.points[1:]]
    if q.is_nurbs:
        return bezjoin.Curve.nurbs(poles, q.knots, q.degree,
                                  q.weights if q.is_rational else None)
    return bezjoin.Curve(poles)


def _round_corner_by_radius(first_edge, second_edge, radius, order, reverse_first,
                            reverse_second):
    if same_edge(first_edge, second_edge):
        raise _invalid("the first and the second edge are the same edge: select two "
                       "different edges")
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        p_oriented, q_oriented = orient_end_to_start(p, q)
        with p_oriented, q_oriented:
            gap = TOUCH_TOLERANCE * _size(p, q)
            p_end = _ends(p_oriented)[1]
            if _distance(p_end, _ends(q_oriented)[0]) <= gap:
                # The shared vertex (whatever other crossings): q starts exactly there.
                with _snapped_start(q_oriented, p_end) as q_snapped, \
                        bezjoin.fillet_radius(p_oriented, q_snapped, radius,
                                              order=order) as result:
                    return _wire(result.curves())
        with (p.reverse() if reverse_first else p.copy()) as p_work, \
                (q.reverse() if reverse_second else q.copy()) as q_work, \
                bezjoin.fillet_radius(p_work, q_work, radius, order=order) as result:
            return _wire(result.curves())


def round_corner(first_edge, second_edge, *, setback=None, second_setback=None, p_order=None,
                 q_order=None, p_scale=None, q_scale=None, auto_scale=None,
                 reverse_first=False, reverse_second=False, radius=None, order=2):
    """The rounded path "along the first edge to the corner, then along the second"
    as a ``Part.Wire`` of three edges (kept part of the first edge, the blend,
    kept part of the second edge), by :func:`bezjoin.fillet`.

    Two cases:

    * the edges meet at an end (a corner of a path): they are oriented so that
      the first ends at the corner and the second starts there (the crossing
      is then at ``u = 1``, ``v = 0``);
    * the edges cross: the corner rounded is "from the start of the first edge
      to the first crossing, then to the end of the second edge"; reach the
      other corners with ``reverse_first`` / ``reverse_second``.

    ``setback`` is the arc length kept off the corner along the first edge,
    ``second_setback`` (default: the same) along the second. Orders above an
    edge's degree are allowed (the edge is elevated first, exactly).
    The scale is automatic by default (least bending energy:
    :func:`bezjoin.fillet_vertex` / :func:`bezjoin.fillet` without scales), so
    the blend never loops, also when the edges are long against the setback,
    where the paper's scale 1 does; ``p_scale``/``q_scale`` (or
    ``auto_scale=False`` for 1.0) give the raw construction, and
    ``auto_scale=True`` ignores given scales.

    Edges that meet at an end are rounded at that shared vertex (also when they
    cross elsewhere too), with a gap up to ``TOUCH_TOLERANCE`` times the model
    size (the longer edge, at least 1) allowed there, as sketch solvers leave.

    ``setback`` defaults to ``DEFAULT_SETBACK_FRACTION`` of the shorter edge's
    length. With ``radius`` instead, the corner is cut where the circular fillet
    of that radius touches the edges and blended G^``order`` (default 2; 1..6) by
    :func:`bezjoin.fillet_radius` (no setbacks, scales or orders then).
    """
    if radius is not None:
        if setback is not None or second_setback is not None:
            raise TypeError("give either radius or setback, not both")
        return _round_corner_by_radius(first_edge, second_edge, radius, order,
                                       reverse_first, reverse_second)
    if same_edge(first_edge, second_edge):
        raise _invalid("the first and the second edge are the same edge: select two "
                       "different edges")
    if setback is None:
        setback = default_setback([first_edge, second_edge])
    second_setback = setback if second_setback is None else second_setback
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        _check_orders(p_order, q_order, p, q)
        p_oriented, q_oriented = orient_end_to_start(p, q)
        with p_oriented, q_oriented:
            gap = TOUCH_TOLERANCE * _size(p, q)
            touching = _distance(_ends(p_oriented)[1], _ends(q_oriented)[0]) <= gap
            options = dict(p_setback=setback, q_setback=second_setback, p_order=p_order,
                           q_order=q_order)
            # The automatic scale leaves both edges at one speed (the library's
            # balanced scale): with one s for both, a 90-degree corner of lines
            # 1000 and 10 long (setback 1) peaked at curvature 1.29e4, lines 10 and
            # 10 at 1.33 (user testing, session 40).
            balanced = "balanced" if _automatic(p_scale, q_scale, auto_scale) else auto_scale
            scales = dict(p_scale=p_scale, q_scale=q_scale, auto_scale=balanced)
            if touching:
                # The vertex itself, whatever other crossings the edges have.
                with bezjoin.fillet_vertex(p_oriented, q_oriented, gap=gap, **options,
                                           **scales) as result:
                    return _wire(result.curves())
        with (p.reverse() if reverse_first else p.copy()) as p_work, \
                (q.reverse() if reverse_second else q.copy()) as q_work:
            with bezjoin.fillet(p_work, q_work, **options, **scales) as result:
                return _wire(result.curves())


def _automatic(p_scale, q_scale, auto_scale):
    """Whether the library would choose the scale (the bindings' rule): asked for, or
    nothing said and no scale given."""
    return bool(auto_scale) or (auto_scale is None and p_scale is None and q_scale is None)


def _speeds_differ(p_speed, q_speed):
    """Whether the balanced scale differs from the one-s automatic scale: finite
    positive speeds more than 1e-9 apart (relative), the library's rule."""
    return (p_speed > 0 and q_speed > 0 and math.isfinite(p_speed * q_speed)
            and abs(p_speed - q_speed) > 1e-9 * max(p_speed, q_speed))


def _at_unit_speed(curve):
    """``curve`` as a NURBS curve whose parameter runs over ``[0, its length]`` (the
    knots mapped linearly; a Bezier curve as its one-span B-spline): the same points,
    at unit speed on average, exactly for lines and circular arcs. Degenerate lengths
    keep the curve as it is."""
    length = curve.length()
    if not (length > 0.0 and math.isfinite(length)):
        return curve.copy()
    degree = curve.degree
    if curve.is_nurbs:
        first, last = curve.domain
        knots = [(k - first) / (last - first) * length for k in curve.knots]
        weights = curve.weights if curve.is_rational else None
    else:
        knots = [0.0] * (degree + 1) + [length] * (degree + 1)
        weights = None
    return bezjoin.Curve.nurbs(curve.points, knots, degree, weights)


def _piece_edge(piece):
    """The edge of a chain piece: a straight piece (degree 1, two poles, not rational: a
    kept part of a line, also of one given at unit speed by :func:`_at_unit_speed`) as a
    line segment again, not a degree-1 Bezier curve or B-spline (user testing, session
    44: B8); any other as :meth:`bezjoin.Curve.to_edge` makes it. The curves of FreeCAD
    edges are 3D."""
    if piece.degree == 1 and piece.pole_count == 2 and not piece.is_rational:
        return Part.makeLine(*(tuple(point) for point in piece.points))
    return piece.to_edge()


class RoundedWire:
    """A wire with every corner rounded by radius (:func:`round_wire_by_radius`):
    the ``shape`` (a ``Part.Wire``), whether it is ``closed``, one
    :class:`bezjoin.RadiusCornerReport` per rounded corner in ``reports`` (in path
    order), and ``smooth_joins``: the joins left as they are because they are smooth
    (join ``i`` between edge ``i + 1`` and the next one along the path, edges numbered
    from 1; the closing join of a closed wire is the last one)."""

    def __init__(self, shape, closed, reports, smooth_joins=()):
        self.shape = shape
        self.closed = closed
        self.reports = reports
        self.smooth_joins = list(smooth_joins)

    @property
    def max_arc_deviation(self):
        """The largest distance of a blend from its corner's arc."""
        return max(report.arc_deviation for report in self.reports)

    def describe(self):
        """One line for the report view."""
        kind = "closed" if self.closed else "open"
        smooth = (f" ({len(self.smooth_joins)} smooth joins left as they are)"
                  if self.smooth_joins else "")
        return (f"{len(self.reports)} corners of the {kind} wire rounded{smooth}; largest "
                f"distance of a blend from its arc {self.max_arc_deviation:.6g}")


def _corner_runs(curves, closed):
    """The path ``curves`` (oriented, see :func:`_path_curves`) cut at its smooth joins
    (tangents turning by less than ``SMOOTH_JOIN_DEGREES``): ``(runs, closes, smooth)``.
    ``runs`` are lists of curve indices along the path, each rounded as one chain (a
    run of one curve is kept whole); ``closes``: whether the single run is closed (only
    when ``closed`` and no join is smooth); ``smooth``: the indices ``i`` of the smooth
    joins (between curve ``i`` and the next, the last one closing a closed path). A
    closed path with a smooth join is opened there: its runs start after that join."""
    count = len(curves)
    joins = count if closed else count - 1
    smooth = [i for i in range(joins)
              if _is_smooth_join(curves[i], curves[(i + 1) % count])]
    if not smooth:
        return [list(range(count))], closed, []
    start = (smooth[0] + 1) % count if closed else 0
    order = [(start + k) % count for k in range(count)]
    runs = [[order[0]]]
    for index in order[1:]:
        if runs[-1][-1] in smooth:
            runs.append([index])
        else:
            runs[-1].append(index)
    return runs, False, smooth


def _is_smooth_join(p, q):
    """Whether ``p``'s end tangent and ``q``'s start tangent turn by less than
    ``SMOOTH_JOIN_DEGREES``; a zero tangent is no smooth join (the library judges it)."""
    angle = _turn_at_join(p, q)
    return angle is not None and angle < SMOOTH_JOIN_DEGREES


#: ``corner i`` and ``curves[i]`` in a chain function's message (also read by the
#: features, which name the sketch edges behind them).
PATH_INDEX = re.compile(r"\b(corner |curves\[)(\d+)(\]?)")


def _is_straight(curve):
    """Whether ``curve`` is a straight segment as FreeCAD's lines arrive (degree 1, two
    poles, not rational)."""
    return curve.degree == 1 and curve.pole_count == 2 and not curve.is_rational


def _merge_collinear_lines(curves):
    """The path ``curves`` with every run of consecutive straight curves that meet in
    smooth joins (a line split into collinear pieces, as sketches often have it) as ONE
    line from the run's first start to its last end: ``(merged, groups, splits)``,
    ``groups[j]`` the indices of ``curves`` merged into ``merged[j]``, ``splits`` the
    joins where they met, as ``(join, point)`` (join ``i + 1`` after ``curves[i]``, as
    :class:`RoundedWire` numbers them). A corner next to a short piece can then take its fillet
    from the whole line, as it would from the unsplit line (user testing, session 44:
    B7). The closing join of a closed path is not merged across. Merged lines are new
    curves; the others are the given ones."""
    groups = [[0]]
    for i in range(1, len(curves)):
        previous = curves[groups[-1][-1]]
        if _is_straight(previous) and _is_straight(curves[i]) and \
                _is_smooth_join(previous, curves[i]):
            groups[-1].append(i)
        else:
            groups.append([i])
    merged, splits = [], []
    for group in groups:
        if len(group) == 1:
            merged.append(curves[group[0]])
            continue
        merged.append(bezjoin.Curve([_ends(curves[group[0]])[0],
                                     _ends(curves[group[-1]])[1]]))
        splits.extend((i + 1, _ends(curves[i])[1]) for i in group[:-1])
    return merged, groups, splits


def _split_at_points(edges, points, tolerance):
    """``edges`` with every straight edge (as long as its chord: a line segment, or a
    kept piece of one as a degree-1 curve) cut at the ``points`` that lie on it, more
    than ``tolerance`` from its ends (the split vertices of merged lines that the
    rounding kept), in path order."""
    def ends_of(edge):
        return edge.valueAt(edge.FirstParameter), edge.valueAt(edge.LastParameter)

    def nearness(point, edge):
        return min(point.distanceToPoint(e) for e in ends_of(edge))

    result = []
    for index, edge in enumerate(edges):
        start, end = ends_of(edge)
        length = start.distanceToPoint(end)
        if length == 0.0 or abs(edge.Length - length) > tolerance:
            result.append(edge)
            continue
        direction = (end - start) * (1.0 / length)
        cuts = []
        for point in points:
            offset = FreeCAD.Vector(*point) - start
            along = offset.dot(direction)
            if (offset - direction * along).Length <= tolerance and \
                    tolerance < along < length - tolerance:
                cuts.append(along)
        if not cuts:
            result.append(edge)
            continue
        stops = [start] + [start + direction * a for a in sorted(cuts)] + [end]
        # The pieces in path order: from the end that meets the previous edge (or away
        # from the end that meets the next one).
        if result:
            backwards = nearness(end, result[-1]) < nearness(start, result[-1])
        else:
            following = edges[index + 1] if index + 1 < len(edges) else None
            backwards = following is not None and \
                nearness(start, following) < nearness(end, following)
        if backwards:
            stops.reverse()
        result.extend(Part.makeLine(a, b) for a, b in zip(stops, stops[1:]))
    return result


def _round_runs(curves, closed, round_chain, edge_of=None):
    """Every corner of the path ``curves`` rounded by ``round_chain(run_curves,
    closed)`` (a library chain call, whose result has ``pieces`` and may have
    ``reports``), run by run between the smooth joins (:func:`_corner_runs`), which are
    left as they are; ``edge_of(piece)`` makes each piece's edge (default
    :meth:`bezjoin.Curve.to_edge`). Straight curves in smooth joins are rounded as one
    line (:func:`_merge_collinear_lines`) and cut again where they met if the rounding
    kept those points. Returns ``(wire, reports, smooth)``; a run's error is re-raised
    with its ``corner i`` / ``curves[i]`` numbered along the whole path, as a call on
    the whole path would number them."""
    curves, groups, splits = _merge_collinear_lines(curves)
    merged_lines = [curve for curve, group in zip(curves, groups) if len(group) > 1]
    try:
        # The tolerance of the split points: the merged lines' size, as the path's.
        size = max([1.0] + [line.length() for line in merged_lines])
        wire, reports, smooth = _round_merged_runs(curves, closed, round_chain, edge_of, groups)
    finally:
        for line in merged_lines:
            line.close()
    if splits:
        tolerance = TOUCH_TOLERANCE * size
        wire = Part.Wire(_split_at_points(wire.OrderedEdges, [p for _, p in splits], tolerance))
        # The kept split vertices are smooth joins left as they are.
        kept = [join for join, point in splits
                if any(_distance(point, tuple(v.Point)) <= tolerance for v in wire.Vertexes)]
        smooth = sorted(set(smooth) | set(kept))
    return wire, reports, smooth


def _round_merged_runs(curves, closed, round_chain, edge_of, groups):
    """:func:`_round_runs` on the path with its collinear lines merged (``groups``: the
    original curves behind each, for the numbers in messages and in ``smooth``)."""
    def original_index(local, last=True):
        group = groups[local] if local < len(groups) else [local]
        return group[-1] if last else group[0]

    runs, closes, smooth = _corner_runs(curves, closed)
    if all(len(run) == 1 for run in runs):
        raise _invalid(
            f"every join of the wire is smooth (its tangents turn by less than "
            f"{SMOOTH_JOIN_DEGREES:g} degrees): there is no corner to round")
    edges, reports = [], []
    for run in runs:
        if len(run) == 1:
            edges.append(curves[run[0]].to_edge())
            continue
        try:
            result = round_chain([curves[i] for i in run], closes)
        except bezjoin.BezjoinError as error:
            if not smooth and all(len(group) == 1 for group in groups):
                raise
            # The run's corner j and curves[j] are the path's corner / curve run[j]
            # (of the merged path: a merged line's corner is at its last piece, the
            # curve its first): say them as a call on the whole path would.
            def path_index(m):
                local = int(m.group(2))
                index = run[local] if local < len(run) else local
                index = original_index(index, last=m.group(1) == "corner ")
                return f"{m.group(1)}{index}{m.group(3)}"

            message = PATH_INDEX.sub(path_index, error.message)
            raise bezjoin.BezjoinError(error.status, error.status_name, message) from error
        with result:
            edges.extend(piece.to_edge() if edge_of is None else edge_of(piece)
                         for piece in result.pieces)
            reports.extend(getattr(result, "reports", []))
    return Part.Wire(edges), reports, [original_index(i) + 1 for i in smooth]


def _path_curves(edges):
    """The curves of ``edges`` (in path order) each oriented to run from the end of the
    previous one (the first one towards the second), and whether the path closes.
    The caller closes the curves."""
    curves = []
    try:
        for i, edge in enumerate(edges):
            curves.append(edge_curve(edge, f"edge {i + 1}"))
        if len(curves) < 2:
            raise bezjoin.BezjoinError.invalid_argument(
                f"a wire to round needs at least 2 edges, {len(curves)} given")
        size = max([1.0] + [c.length() for c in curves])
        oriented = []
        # The first curve runs towards the second: its end is the closer of its ends.
        first_start, first_end = _ends(curves[0])
        second_ends = _ends(curves[1])
        if min(_distance(first_start, e) for e in second_ends) < \
                min(_distance(first_end, e) for e in second_ends):
            oriented.append(curves[0].reverse())
        else:
            oriented.append(curves[0].copy())
        for i, curve in enumerate(curves[1:], start=1):
            previous_end = _ends(oriented[-1])[1]
            start, end = _ends(curve)
            if _distance(end, previous_end) < _distance(start, previous_end):
                oriented.append(curve.reverse())
            else:
                oriented.append(curve.copy())
            if min(_distance(previous_end, start), _distance(previous_end, end)) > \
                    TOUCH_TOLERANCE * size:
                for c in oriented:
                    c.close()
                raise bezjoin.BezjoinError.invalid_argument(
                    f"edge {i + 1} does not start where edge {i} ends: the edges are not "
                    "one path")
        closed = _distance(_ends(oriented[-1])[1], _ends(oriented[0])[0]) <= \
            TOUCH_TOLERANCE * size
        return oriented, closed
    finally:
        for curve in curves:
            curve.close()


def round_wire_by_radius(edges, radius, *, order=2, closed=None):
    """Every corner of a path of edges rounded like the circular fillet of ``radius``,
    with a fair G^order blend at each (:func:`bezjoin.fillet_radius_chain`;
    default G2): a ``Part.Wire`` whose edges are the kept parts of the edges and
    the blends, in path order. Blends by radius have no scales and never loop.

    ``edges``: a ``Part.Wire`` (its ``OrderedEdges``) or edges in path order
    (each starting where the previous ends, in either direction; they are
    oriented along the path). ``closed``: round the corner from the last edge
    back to the first too; default: whether the path closes. Returns a
    :class:`RoundedWire`.

    Raises:
        bezjoin.BezjoinError: when the arc of ``radius`` does not fit a corner
            (the message names the corner and ``radius``), arcs overlap on an
            edge, the edges are not one path, ...
    """
    if hasattr(edges, "OrderedEdges"):
        edges = edges.OrderedEdges
    curves, path_closes = _path_curves(list(edges))
    closed = path_closes if closed is None else closed
    try:
        wire, reports, smooth = _round_runs(
            curves, bool(closed),
            lambda run, closes: bezjoin.fillet_radius_chain(run, radius, order=order,
                                                            closed=closes),
            edge_of=_piece_edge)
        return RoundedWire(wire, bool(closed), list(reports), smooth)
    finally:
        for curve in curves:
            curve.close()


def _continuity_order(continuity):
    """``"G2"`` (or ``2``) -> 2; orders 1..6."""
    text = str(continuity).strip().upper()
    if text.startswith(("G", "C")):
        text = text[1:]
    try:
        order = int(text)
    except ValueError:
        raise _invalid(f"continuity {continuity!r} is not G1..G6") from None
    if not 1 <= order <= 6:
        raise _invalid(f"continuity {continuity!r} is not G1..G6")
    return order


def round_wire(shape, *, radius=None, setback=None, continuity="G2", closed=None):
    """Every corner of a wire rounded at once, as ONE ``Part.Wire`` (kept parts of the
    edges and the blends in path order): a closed wire stays closed, so ``Part.Face``
    of a closed planar result works.

    ``shape``: a ``Part.Wire``, a sketch's shape (one wire, or edges forming one
    path), or edges in path order (see :func:`path_edges`); in model coordinates
    (:func:`model_shape` for a sketch inside a placed Body or Part).

    Give exactly one of ``radius`` (each corner cut where the circular fillet of that
    radius touches its edges, blended G^k: :func:`bezjoin.fillet_radius_chain`) or
    ``setback`` (arc length kept off each corner along both edges, C^k blends with
    the automatic scale, which never loops: :func:`bezjoin.fillet_chain`).
    ``continuity``: ``"G1"`` .. ``"G6"`` (default G2). ``closed``: round the corner
    from the last edge back to the first too; default: whether the path closes.

    Nothing partial: when a fillet does not fit at some corner, the library's
    :class:`bezjoin.BezjoinError` names it (``corner i`` between ``curves[i]`` and
    the next curve, ``curves[i]`` being edge ``i + 1`` along the path) and nothing
    is built.
    """
    if (radius is None) == (setback is None):
        raise TypeError("round_wire needs exactly one of radius and setback")
    # The library names its own argument (p_setback) and words the range for
    # programmers: say it here in the wire's terms (user testing, session 43).
    if setback is not None and not 0.0 < setback < math.inf:
        raise _invalid(f"setback (Setback) must be a length above 0, not {setback:.6g}: it is "
                       "the arc length kept off each corner along both edges")
    order = _continuity_order(continuity)
    curves, path_closes = _path_curves(path_edges(shape))
    closed = bool(path_closes if closed is None else closed)
    # closed=True on an open path rounds a corner between its last and first edges,
    # which must cross; a refusal there said only "the curves do not cross" (user
    # testing, session 43): it now says the path is open, and how far.
    open_gap = None if path_closes else _distance(_ends(curves[-1])[1], _ends(curves[0])[0])
    try:
        if radius is not None:
            def round_chain(run, closes):
                return bezjoin.fillet_radius_chain(run, radius, order=order, closed=closes)
        else:
            def round_chain(run, closes):
                # Every curve at unit speed, so that each corner's automatic scale sees
                # the same speed on both sides (as the balanced scale does for one
                # corner): a 1000 x 10 rectangle peaked at curvature 521 at its
                # corners, a 10 x 10 square at 1.19 (user testing, session 40).
                unit = [_at_unit_speed(curve) for curve in run]
                try:
                    return bezjoin.fillet_chain(unit, setback=setback, p_order=order,
                                                q_order=order, closed=closes)
                finally:
                    for curve in unit:
                        curve.close()
        wire, _, _ = _round_runs(curves, closed, round_chain, edge_of=_piece_edge)
    except bezjoin.BezjoinError as error:
        if not (closed and open_gap is not None):
            raise
        raise bezjoin.BezjoinError(
            error.status, error.status_name,
            f"{error.message} (closed=True, but the path is open: its ends are "
            f"{open_gap:.6g} apart; the corner from its last edge to its first needs them "
            "to cross)") from None
    finally:
        for curve in curves:
            curve.close()
    if closed and not wire.isClosed():
        raise _invalid("the rounded wire did not close (internal error); nothing was built")
    return wire


def edge_deviation(edge, others, samples=DEVIATION_SAMPLES):
    """The largest distance between ``edge`` and the edges ``others``, both ways: from
    ``samples`` points along ``edge`` (:func:`_points_along`: equally spaced in arc length)
    to the nearest point of any of ``others``, and from as many points along each of
    ``others`` to the nearest point of ``edge``: the Hausdorff distance, sampled.

    Each distance is exact at its point (``distToShape``: OCCT's extrema on the edge's
    own range, ends included; it agreed with a golden-section search along the edge to
    about 1e-14), so only a bulge between two samples can be missed: with 200 samples
    the maximum came out within 1e-5 (relative) of 2000 samples on curved test edges."""
    target = Part.Compound(list(others))
    worst = max(target.distToShape(Part.Vertex(point))[0]
                for point in _points_along(edge, samples))
    for other in others:
        worst = max(worst, max(edge.distToShape(Part.Vertex(point))[0]
                               for point in _points_along(other, samples)))
    return worst


def _points_along(edge, count):
    """``count`` points along ``edge``, its ends included: equally spaced in arc length,
    or in parameter where OCCT's arc length sampler refuses the edge ("Discretization of
    edge failed" for a 1e-9 mm edge, which the merge takes)."""
    try:
        return edge.discretize(Number=count)
    except Part.OCCError:
        first, last = edge.FirstParameter, edge.LastParameter
        return [edge.valueAt(first + (last - first) * k / (count - 1)) for k in range(count)]


def _as_edge(source):
    """``source`` (an edge, a shape of one edge or a bounded Part curve, as
    :meth:`bezjoin.Curve.from_freecad` takes them) as an edge."""
    if isinstance(source, Part.Shape):
        return source if source.ShapeType == "Edge" else source.Edges[0]
    return source.toShape()


class MergedEdge:
    """The merged edge and the merge report: ``mu``, ``metric_value``, ``max_deviation``
    (the geometric distance between the merged edge and the two edges, both ways:
    :func:`edge_deviation`) and ``parametric_deviation`` (the library's
    ``max_deviation``: the largest ``|R(mu t) - P(t)|``, ``|R(mu + (1 - mu) t) - Q(t)|``,
    point against point at the same parameter; it also counts how the points slide
    along the curve, so it is often several times the geometric distance, and it is
    not what a CAD user measures)."""

    def __init__(self, shape, mu, metric_value, max_deviation, parametric_deviation=None):
        self.shape = shape
        self.mu = mu
        self.metric_value = metric_value
        self.max_deviation = max_deviation
        self.parametric_deviation = parametric_deviation

    def describe(self):
        """One line for the report view."""
        return (f"merged at mu = {self.mu:.6g}; metric {self.metric_value:.6g}; "
                f"largest distance from the two edges {self.max_deviation:.6g}")


def _turn_at_join(p, q):
    """The angle in degrees between ``p``'s tangent at its end and ``q``'s at its start,
    ``None`` when either tangent is zero."""
    a = p.derivatives(p.domain[1], 1)[1]
    b = q.derivatives(q.domain[0], 1)[1]
    na, nb = math.sqrt(sum(x * x for x in a)), math.sqrt(sum(x * x for x in b))
    if na == 0.0 or nb == 0.0:
        return None
    cosine = max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b)) / (na * nb)))
    return math.degrees(math.acos(cosine))


def _angle_at_join(p, q):
    """:func:`_turn_at_join`, 0 for a zero tangent (the merge's limit then passes)."""
    angle = _turn_at_join(p, q)
    return 0.0 if angle is None else angle


def merge_edges(first_edge, second_edge, *, metric="discrete", mu="optimal", fix_ends=True,
                keep_first=False, keep_second=False, orient=True,
                max_angle=MAX_MERGE_ANGLE_DEGREES, max_gap="touching"):
    """One edge replacing two consecutive edges (:func:`bezjoin.merge`): a Bezier
    edge for two Bezier edges; for B-spline edges (lines and other polynomial
    curves too) one B-spline edge with both edges' knots mapped and none at the
    join (mathematics.md, "Merge: B-splines"). Rational edges (arcs, conics) are
    refused with the edge named.

    With ``orient`` the edges are first ordered end-to-start (see
    :func:`orient_end_to_start`). Returns a :class:`MergedEdge`.

    Defaults: the outer end points are kept (``fix_ends=True``) and the split ``mu``
    is the optimal one. Edges whose tangents turn by more than ``max_angle`` degrees
    at the join (default ``MAX_MERGE_ANGLE_DEGREES``, 30) are refused with the angle
    in the message: one smooth edge cannot follow such a corner (``max_angle=None``
    or 180 allows any). Edges that do not meet are refused with their gap in the
    message: the merge would bridge it, moving geometry nobody asked to move.
    ``max_gap``: ``"touching"`` (default: the ends within ``TOUCH_TOLERANCE`` of the
    edges' size, as for wires), a length in model units, or ``None`` for any gap.
    """
    if same_edge(first_edge, second_edge):
        raise _invalid("the first and the second edge are the same edge: select two "
                       "different edges")
    # A NaN limit would pass every comparison below and switch the guard off.
    if max_angle is not None and not 0.0 <= max_angle <= 180.0:
        raise _invalid(f"max_angle (MaxAngle) must be an angle from 0 to 180 degrees, "
                       f"not {max_angle:.6g}; None (Python) allows any angle")
    if max_gap not in (None, "touching") and not 0.0 <= max_gap < math.inf:
        raise _invalid(f"max_gap (MaxGap) must be a length of 0 or more, not {max_gap:.6g}; "
                       "None (Python) allows any gap")
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.copy(), q.copy()
        gap = _distance(_ends(p)[1], _ends(q)[0])
        limit = (TOUCH_TOLERANCE * max(1.0, p.length(), q.length())
                 if max_gap == "touching" else max_gap)
        if limit is not None and not gap <= limit:
            p.close()
            q.close()
            raise _invalid(
                f"the edges do not meet: their nearest ends are {gap:.6g} apart, more than "
                f"max_gap = {limit:.6g}; merging them would bridge the gap (a larger "
                "MaxGap in the feature or the form, max_gap in Python, merges them anyway)")
        # Named by edge here, not as the library's p and q (user testing, session 43).
        for curve, name in ((p, "first"), (q, "second")):
            if curve.is_rational:
                p.close()
                q.close()
                raise _invalid(
                    f"the {name} edge is rational (an arc or a conic, its weights differ): a "
                    "merge makes one polynomial edge, which cannot follow it exactly; "
                    "approximate that edge by a B-spline first (Part's toBSpline or "
                    "approximate) to merge it")
        angle = _angle_at_join(p, q)
        if max_angle is not None and angle > max_angle:
            p.close()
            q.close()
            raise _invalid(
                f"the edges turn by {angle:.4g} degrees at the join, more than the "
                f"{max_angle:g} degrees allowed (max_angle): merging them into one edge "
                "would lose that corner")
        with p, q, bezjoin.merge(p, q, metric=metric, mu=mu, fix_ends=fix_ends,
                                 keep_p=keep_first, keep_q=keep_second) as result:
            shape = result.merged.to_edge()
            return MergedEdge(shape, result.mu, result.metric_value,
                              edge_deviation(shape, [_as_edge(first_edge),
                                                     _as_edge(second_edge)]),
                              parametric_deviation=result.max_deviation)


def spline_through_points(points, params=None):
    """The C1 cubic spline whose Bezier segments pass through the given points
    (:func:`bezjoin.lagrange_spline`), as a ``Part.Wire``.

    ``points`` are all on the curve, in order: for ``m`` segments there are
    ``2 m + 2`` of them: node 0, the points at 1/3 and 2/3 of segment 0,
    node 1, then for every later segment its point at 2/3 and its end node.
    ``params`` are the ``m + 1`` node parameters (default: chord length).
    """
    rows = [tuple(point) for point in points]
    if len(rows) < 4 or len(rows) % 2:
        raise bezjoin.BezjoinError.invalid_argument(
            f"{len(rows)} points given; a spline of m segments takes 2 m + 2 points "
            "(node, two inner points, node, then inner point and node per segment)")
    nodes = [rows[0], rows[3]] + rows[5::2]
    first_inner = rows[1:3]
    second_inner = rows[4::2]
    segments = bezjoin.lagrange_spline(nodes, first_inner, second_inner, params=params)
    try:
        return _wire(segments)
    finally:
        for segment in segments:
            segment.close()


def add_feature(document, name, shape, properties=None):
    """A ``Part::Feature`` named ``name`` holding ``shape`` in ``document``;
    ``properties`` maps extra float property names to values (group "Bezjoin")."""
    feature = document.addObject("Part::Feature", name)
    feature.Shape = shape
    for property_name, value in (properties or {}).items():
        feature.addProperty("App::PropertyFloat", property_name, "Bezjoin")
        setattr(feature, property_name, value)
    return feature
