"""The workbench operations as plain functions: edges and numbers in, Part shapes out.

No GUI here: the commands (``commands.py``) only collect the selection and
the parameters and call these, and the headless tests call them directly.

Edges must be Bezier curves: ``Part.BezierCurve``, a single-span
non-rational B-spline, or a line segment (see
:meth:`bezjoin.Curve.from_freecad`); anything else raises
:class:`bezjoin.UnsupportedGeometryError` naming the edge.
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


def orient_end_to_start(p, q):
    """``(p, q)`` possibly reversed so that ``p`` ends where ``q`` starts, or as
    close as the four end pairings allow. Returns new curves (the caller closes
    ``p`` and ``q`` as before; the returned ones are owned by the caller too)."""
    p_ends = (p.points[0], p.points[-1])
    q_ends = (q.points[0], q.points[-1])
    # On a tie, keep the curves as they are (end of p to start of q).
    _gap, _reversals, p_end, q_end = min(
        (_distance(p_ends[i], q_ends[j]), (i == 0) + (j == 1), i, j)
        for i in (0, 1) for j in (0, 1))
    p_oriented = p.reverse() if p_end == 0 else p.segment(0.0, 1.0)
    q_oriented = q.reverse() if q_end == 1 else q.segment(0.0, 1.0)
    return p_oriented, q_oriented


def _raised_for_order(curve, order):
    """``curve`` written with degree at least ``order`` (exact elevation), so that a
    continuity order above the degree of, say, a line segment can be asked for:
    its higher derivatives are zero and the blend matches them."""
    if order is not None and order > curve.degree:
        return curve.elevate(order)
    return curve.segment(0.0, 1.0)


def _wire(curves):
    edges = [curve.to_edge() for curve in curves]
    return Part.Wire(edges)


def blend_edges(first_edge, second_edge, *, u0=1.0, v0=0.0, p_order=None, q_order=None,
                p_scale=1.0, q_scale=1.0, auto_scale=False, orient=True):
    """The blend curve from ``first_edge`` at ``u0`` to ``second_edge`` at ``v0``
    (:func:`bezjoin.connect`), as a ``Part.Edge``.

    With ``orient`` (the default) the edges are first reversed as needed so that
    the end of the first faces the start of the second (the closest pair of
    ends), and ``u0``/``v0`` refer to these oriented curves: the defaults
    ``u0 = 1``, ``v0 = 0`` bridge the gap between the facing ends.
    ``p_order``/``q_order`` default to each curve's degree (the paper); an order
    above a curve's degree is allowed (the curve is elevated first, exactly).
    With ``auto_scale`` the scales are ignored and chosen by the library
    (:func:`bezjoin.connect_auto_scale`: least bending energy).
    """
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.segment(0.0, 1.0), q.segment(0.0, 1.0)
        with p, q, _raised_for_order(p, p_order) as p_raised, \
                _raised_for_order(q, q_order) as q_raised:
            if auto_scale:
                with bezjoin.connect_auto_scale(p_raised, u0, q_raised, v0, p_order=p_order,
                                                q_order=q_order) as result:
                    return result.curve.to_edge()
            with bezjoin.connect(p_raised, u0, q_raised, v0, p_order=p_order, q_order=q_order,
                                 p_scale=p_scale, q_scale=q_scale) as blend:
                return blend.to_edge()


def round_corner(first_edge, second_edge, *, setback, second_setback=None, p_order=None,
                 q_order=None, p_scale=1.0, q_scale=1.0, auto_scale=False,
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
    With ``auto_scale`` the scales are ignored and chosen by the library
    (:func:`bezjoin.fillet` with ``auto_scale=True``: least bending energy);
    use it when the edges are long against the setback, where scale 1 loops.
    """
    second_setback = setback if second_setback is None else second_setback
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        p_oriented, q_oriented = orient_end_to_start(p, q)
        with p_oriented, q_oriented:
            touching = _distance(p_oriented.points[-1], q_oriented.points[0]) <= (
                TOUCH_TOLERANCE * max(1.0, p.length(), q.length()))
            if touching:
                p_work, q_work = p_oriented.segment(0.0, 1.0), q_oriented.segment(0.0, 1.0)
            else:
                p_work = p.reverse() if reverse_first else p.segment(0.0, 1.0)
                q_work = q.reverse() if reverse_second else q.segment(0.0, 1.0)
        with p_work, q_work, _raised_for_order(p_work, p_order) as p_raised, \
                _raised_for_order(q_work, q_order) as q_raised, \
                bezjoin.fillet(p_raised, q_raised, p_setback=setback, q_setback=second_setback,
                               p_order=p_order, q_order=q_order, p_scale=p_scale,
                               q_scale=q_scale, auto_scale=auto_scale) as result:
            return _wire(result.curves())


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
    """One Bezier edge replacing two consecutive edges (:func:`bezjoin.merge`).

    With ``orient`` the edges are first ordered end-to-start (see
    :func:`orient_end_to_start`). Returns a :class:`MergedEdge`.
    """
    with edge_curve(first_edge, "first edge") as p, edge_curve(second_edge, "second edge") as q:
        if orient:
            p, q = orient_end_to_start(p, q)
        else:
            p, q = p.segment(0.0, 1.0), q.segment(0.0, 1.0)
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
