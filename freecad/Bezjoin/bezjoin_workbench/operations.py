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

import Part

from . import ensure_bindings_importable

bezjoin = ensure_bindings_importable()

#: Ends closer than this (relative to the edge lengths, at least 1) count as one
#: vertex: FreeCAD's ``Precision::Confusion()``.
TOUCH_TOLERANCE = 1e-7


def edge_curve(edge, name):
    """The :class:`bezjoin.Curve` of ``edge``; the error names the edge (``name``)."""
    try:
        return bezjoin.Curve.from_freecad(edge)
    except bezjoin.UnsupportedGeometryError as error:
        raise bezjoin.UnsupportedGeometryError(f"{name}: {error}") from None


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
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.copy(), q.copy()
        with p, q:
            u, v = _at_fraction(p, u0), _at_fraction(q, v0)
            with bezjoin.connect(p, u, q, v, p_order=p_order, q_order=q_order,
                                 p_scale=p_scale, q_scale=q_scale,
                                 auto_scale=auto_scale) as blend:
                return blend.to_edge()


def round_corner(first_edge, second_edge, *, setback, second_setback=None, p_order=None,
                 q_order=None, p_scale=None, q_scale=None, auto_scale=None,
                 reverse_first=False, reverse_second=False):
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
    """
    second_setback = setback if second_setback is None else second_setback
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        p_oriented, q_oriented = orient_end_to_start(p, q)
        with p_oriented, q_oriented:
            gap = TOUCH_TOLERANCE * max(1.0, p.length(), q.length())
            touching = _distance(_ends(p_oriented)[1], _ends(q_oriented)[0]) <= gap
            options = dict(p_setback=setback, q_setback=second_setback, p_order=p_order,
                           q_order=q_order, p_scale=p_scale, q_scale=q_scale,
                           auto_scale=auto_scale)
            if touching:
                # The vertex itself, whatever other crossings the edges have.
                with bezjoin.fillet_vertex(p_oriented, q_oriented, gap=gap,
                                           **options) as result:
                    return _wire(result.curves())
        with (p.reverse() if reverse_first else p.copy()) as p_work, \
                (q.reverse() if reverse_second else q.copy()) as q_work, \
                bezjoin.fillet(p_work, q_work, **options) as result:
            return _wire(result.curves())


class RoundedWire:
    """A wire with every corner rounded by radius (:func:`round_wire_by_radius`):
    the ``shape`` (a ``Part.Wire``), whether it is ``closed``, and one
    :class:`bezjoin.RadiusCornerReport` per corner in ``reports`` (corner ``i``
    between edge ``i`` and the next one, in the wire's order)."""

    def __init__(self, shape, closed, reports):
        self.shape = shape
        self.closed = closed
        self.reports = reports

    @property
    def max_arc_deviation(self):
        """The largest distance of a blend from its corner's arc."""
        return max(report.arc_deviation for report in self.reports)

    def describe(self):
        """One line for the report view."""
        kind = "closed" if self.closed else "open"
        return (f"{len(self.reports)} corners of the {kind} wire rounded; largest distance "
                f"of a blend from its arc {self.max_arc_deviation:.6g}")


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
        with bezjoin.fillet_radius_chain(curves, radius, order=order,
                                         closed=bool(closed)) as result:
            return RoundedWire(_wire(result.pieces), bool(closed), list(result.reports))
    finally:
        for curve in curves:
            curve.close()


class MergedEdge:
    """The merged edge and the merge report (``mu``, ``metric_value``, ``max_deviation``)."""

    def __init__(self, shape, mu, metric_value, max_deviation):
        self.shape = shape
        self.mu = mu
        self.metric_value = metric_value
        self.max_deviation = max_deviation

    def describe(self):
        """One line for the report view."""
        return (f"merged at mu = {self.mu:.6g}; metric {self.metric_value:.6g}; "
                f"largest deviation from the two edges {self.max_deviation:.6g}")


def merge_edges(first_edge, second_edge, *, metric="discrete", mu="half", fix_ends=False,
                keep_first=False, keep_second=False, orient=True):
    """One edge replacing two consecutive edges (:func:`bezjoin.merge`): a Bezier
    edge for two Bezier edges; for B-spline edges (lines and other polynomial
    curves too) one B-spline edge with both edges' knots mapped and none at the
    join (mathematics.md, "Merge: B-splines"). Rational edges (arcs, conics) are
    refused with the edge named.

    With ``orient`` the edges are first ordered end-to-start (see
    :func:`orient_end_to_start`). Returns a :class:`MergedEdge`.
    """
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.copy(), q.copy()
        with p, q, bezjoin.merge(p, q, metric=metric, mu=mu, fix_ends=fix_ends,
                                 keep_p=keep_first, keep_q=keep_second) as result:
            return MergedEdge(result.merged.to_edge(), result.mu, result.metric_value,
                              result.max_deviation)


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
