"""Issue 18 through the bindings.

* The defaults never loop: connect, fillet, fillet_vertex, fillet_chain (and
  fillet_deviation, see test_fillet_chain.py) use the automatic scale unless scales
  are given, and explicit scales are the paper's construction as before.
* fillet_radius_detailed, fillet_radius_chain: the arc's centre and touching points,
  the blend's distance from the arc, every corner of a wire (open and closed) rounded
  as fillet_radius rounds one, G2 joins, and the errors naming their argument.

Properties are re-measured here (pure-Python evaluation of the control points), not
copied from the library's output.
"""

import math

import pytest

import bezjoin
from bezjoin import Curve
from reference import de_casteljau, derivative, distance, norm
from test_curve import expect_error

# Two lines meeting at the origin: 40 mm along x, then 20 mm up.
LONG = [(-40.0, 0.0), (0.0, 0.0)]
SHORT = [(0.0, 0.0), (0.0, 20.0)]


def samples(points, count=2000):
    return [de_casteljau(points, i / count) for i in range(count + 1)]


def segments_cross(a, b, c, d):
    """Whether the closed segments ab and cd share a point (proper or touching)."""
    def orientation(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    o1, o2 = orientation(a, b, c), orientation(a, b, d)
    o3, o4 = orientation(c, d, a), orientation(c, d, b)
    return (o1 * o2 < 0) and (o3 * o4 < 0)


def self_intersects(points, count=600):
    """Whether the 2D Bezier curve crosses itself: two non-adjacent chords of a
    dense polyline on it cross."""
    polyline = samples(points, count)
    chords = list(zip(polyline, polyline[1:]))
    for i, (a, b) in enumerate(chords):
        for c, d in chords[i + 2:]:
            if segments_cross(a, b, c, d):
                return True
    return False


def frame(jet):
    """Unit tangent and curvature vector of a 2D jet (value, r', r'')."""
    a, b = jet[1], jet[2]
    s2 = a[0] ** 2 + a[1] ** 2
    m = a[0] * b[0] + a[1] * b[1]
    s = math.sqrt(s2)
    return ([x / s for x in a], [(b[c] * s2 - m * a[c]) / (s2 * s2) for c in range(2)])


def assert_g2(left, right):
    """``left`` ends where ``right`` starts, with the same unit tangent and curvature
    vector there (Curve objects, ends of their domains)."""
    l_end, r_start = left.domain[1], right.domain[0]
    l_jet, r_jet = left.derivatives(l_end, 2), right.derivatives(r_start, 2)
    assert distance(l_jet[0], r_jet[0]) <= 1e-9
    (t1, k1), (t2, k2) = frame(l_jet), frame(r_jet)
    assert distance(t1, t2) <= 1e-9
    assert distance(k1, k2) <= 1e-7 * max(1.0, norm(k1))


def in_corner_quadrant(points):
    """Every control point in the quadrant x <= 0, y >= 0 of the LONG/SHORT corner:
    the blend (in their convex hull) cannot pass the corner."""
    return all(x <= 1e-12 and y >= -1e-12 for x, y in points)


# -- the defaults never loop --------------------------------------------------------


def test_default_vertex_fillet_of_a_long_and_a_short_line_does_not_loop():
    """Issue 18's example: lines 40 and 20 long, setback 2. The paper's scale 1 gives a
    blend that crosses itself; the default (automatic scale) blend does not, stays in
    the corner, and is about as long as the quarter arc between the cuts."""
    quarter_arc = math.pi * 2.0 / 2  # radius 2 (setback 2 at a right angle)
    with Curve(LONG) as p, Curve(SHORT) as q:
        with bezjoin.fillet_vertex(p, q, setback=2.0, p_scale=1.0, q_scale=1.0) as paper:
            assert paper.scale is None
            assert self_intersects(paper.blend.points)
            assert paper.blend.length() > 2 * quarter_arc
        with bezjoin.fillet_vertex(p, q, setback=2.0) as result:
            assert result.scale is not None and result.scale > 0
            blend = result.blend.points
            assert not self_intersects(blend)
            assert in_corner_quadrant(blend)
            # Longer than the chord between the cuts, shorter than twice the arc.
            chord = distance(blend[0], blend[-1])
            assert chord < result.blend.length() < 2 * quarter_arc
            # The cuts are the setbacks, and the chain is C^1 with knot
            # intervals (u0, s, 1 - v0): u0 = 0.95 and v0 = 0.1 on these lines.
            assert distance(blend[0], (-2.0, 0.0)) <= 1e-12
            assert distance(blend[-1], (0.0, 2.0)) <= 1e-12
            s = result.scale
            assert distance(derivative(blend, 0.0, 1), [s * x for x in (40.0, 0.0)]) <= 1e-9
            assert distance(derivative(blend, 1.0, 1), [s * x for x in (0.0, 20.0)]) <= 1e-9


def test_default_fillet_and_chain_of_the_same_corner_do_not_loop():
    with Curve(LONG) as p, Curve(SHORT) as q:
        with bezjoin.fillet(p, q, setback=2.0) as crossing, \
                bezjoin.fillet_vertex(p, q, setback=2.0) as vertex, \
                bezjoin.fillet_chain([p, q], setback=2.0) as chain:
            for blend in (crossing.blend, chain.blends[0]):
                assert not self_intersects(blend.points)
                assert in_corner_quadrant(blend.points)
            # The same corner: one automatic scale, one blend.
            assert len(chain.scales) == 1
            assert abs(chain.scales[0] - vertex.scale) <= 1e-9 * vertex.scale
            assert abs(crossing.scale - vertex.scale) <= 1e-9 * vertex.scale
            for blend in (crossing.blend, chain.blends[0]):
                assert max(distance(a, b) for a, b in
                           zip(blend.points, vertex.blend.points)) <= 1e-9
        with bezjoin.fillet(p, q, setback=2.0, auto_scale=False) as paper:
            assert self_intersects(paper.blend.points)


def test_default_connect_is_the_automatic_scale():
    with Curve(LONG) as p, Curve(SHORT) as q:
        with bezjoin.connect(p, 0.95, q, 0.1) as default, \
                bezjoin.connect_auto_scale(p, 0.95, q, 0.1) as automatic, \
                bezjoin.connect(p, 0.95, q, 0.1, p_scale=1.0, q_scale=1.0) as paper:
            assert default.points == automatic.curve.points
            assert not self_intersects(default.points) and in_corner_quadrant(default.points)
            assert self_intersects(paper.points)
            # Explicit scales: R'(0) = alpha P'(u0), R'(1) = beta Q'(v0) (the paper).
            assert distance(derivative(paper.points, 0.0, 1), (40.0, 0.0)) <= 1e-9
            assert distance(derivative(paper.points, 1.0, 1), (0.0, 20.0)) <= 1e-9
        with bezjoin.connect(p, 0.95, q, 0.1, p_scale=0.5) as half:
            # One scale given: the other is the paper's 1.0.
            assert distance(derivative(half.points, 0.0, 1), (20.0, 0.0)) <= 1e-9
            assert distance(derivative(half.points, 1.0, 1), (0.0, 20.0)) <= 1e-9
        with bezjoin.connect(p, 0.95, q, 0.1, p_scale=0.5, auto_scale=True) as forced:
            assert forced.points == automatic_points(p, q)


def test_default_connect_of_nearly_stationary_ends_stays_in_size():
    # Reliability R1: cubics whose end poles are eps apart (|P'| = |Q'| = 3 eps).
    # The default's search was centred on chord / mean(|P'|, |Q'|), 1e10 for
    # eps = 1e-9, and gave control points of 2.7e14 on a shape 11 wide.
    for eps in (0.0, 1e-12, 1e-9, 1e-6, 1e-3):
        p_poles = [(0.0, 0.0), (3.0, 0.0), (6.0, 1.0), (6.0 + eps, 1.0)]
        q_poles = [(10.0 - eps, -1.0), (10.0, -1.0), (10.0, 3.0), (11.0, 8.0)]
        with Curve(p_poles) as p, Curve(q_poles) as q:
            with bezjoin.connect(p, 1.0, q, 0.0, p_order=2, q_order=2) as blend, \
                    bezjoin.connect_auto_scale(p, 1.0, q, 0.0, p_order=2,
                                               q_order=2) as automatic:
                assert blend.points == automatic.curve.points
                size = max(abs(x) for point in blend.points for x in point)
                assert size < 12.0, (eps, size)
                # C^2 with one scale s: R^(k)(0) = s^k P^(k)(1), R^(k)(1) = s^k Q^(k)(0).
                s = automatic.scale
                for k in (0, 1, 2):
                    for t, poles, at in ((0.0, p_poles, 1.0), (1.0, q_poles, 0.0)):
                        want = [s ** k * x for x in derivative(poles, at, k)]
                        got = derivative(blend.points, t, k)
                        assert distance(got, want) <= 1e-9 * max(1.0, norm(want)), (eps, k, t)


def automatic_points(p, q):
    with bezjoin.connect_auto_scale(p, 0.95, q, 0.1) as automatic:
        return automatic.curve.points


def test_default_chain_scales_one_per_corner_and_explicit_none():
    square = [[(0, 0), (10, 0)], [(10, 0), (10, 10)], [(10, 10), (0, 10)], [(0, 10), (0, 0)]]
    curves = [Curve(side) for side in square]
    try:
        with bezjoin.fillet_chain(curves, setback=1.0, closed=True) as closed, \
                bezjoin.fillet_chain(curves, setback=1.0) as open_chain, \
                bezjoin.fillet_chain(curves, setback=1.0, p_scale=1.0, q_scale=1.0) as paper:
            assert len(closed.scales) == 4 and len(open_chain.scales) == 3
            assert paper.scales is None
            for i, blend in enumerate(closed.blends):
                with bezjoin.fillet_vertex(curves[i], curves[(i + 1) % 4], setback=1.0) as one:
                    assert abs(closed.scales[i] - one.scale) <= 1e-9 * one.scale
                    assert max(distance(a, b) for a, b in
                               zip(blend.points, one.blend.points)) <= 1e-9
    finally:
        for c in curves:
            c.close()


def test_auto_scale_must_be_a_bool_or_none():
    with Curve(LONG) as p, Curve(SHORT) as q:
        for call in (lambda: bezjoin.fillet(p, q, setback=1.0, auto_scale="yes"),
                     lambda: bezjoin.fillet_vertex(p, q, setback=1.0, auto_scale=1),
                     lambda: bezjoin.fillet_chain([p, q], setback=1.0, auto_scale=1),
                     lambda: bezjoin.connect(p, 1.0, q, 0.0, auto_scale=0),
                     lambda: bezjoin.fillet_deviation(p, q, 0.1, auto_scale="no")):
            with pytest.raises(TypeError, match="auto_scale"):
                call()
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_vertex(p, q, setback=1.0, q_scale=-1.0), "q_scale")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_vertex(p, q, setback=50.0), "setback")
        expect_error("BZJ_ERR_NO_INTERSECTION",
                     lambda: bezjoin.fillet_vertex(q, p, setback=1.0, gap=1e-9), "gap")


def test_auto_scale_takes_numpy_bools_and_refuses_arrays_by_name():
    # Reliability F6: a numpy bool (what comparing numpy values gives) was refused,
    # and a numpy array met numpy's own ValueError instead of the argument's name.
    np = pytest.importorskip("numpy")
    with Curve(LONG) as p, Curve(SHORT) as q:
        for flag in (True, False):
            with bezjoin.connect(p, 0.95, q, 0.1, auto_scale=flag) as plain, \
                    bezjoin.connect(p, 0.95, q, 0.1, auto_scale=np.bool_(flag)) as numpy_flag:
                assert numpy_flag.points == plain.points
        for bad in (np.array([True]), np.array(["balanced"]), np.int64(1)):
            with pytest.raises(TypeError, match="auto_scale"):
                bezjoin.connect(p, 0.95, q, 0.1, auto_scale=bad)


# -- fillet by radius: detailed ------------------------------------------------------


def arc_distance(points, centre, radius, count=4000):
    return max(abs(distance(x, centre) - radius) for x in samples(points, count))


@pytest.mark.parametrize("radius", [1.0, 2.5])
def test_fillet_radius_detailed_reports_the_arc(radius):
    with Curve(LONG) as p, Curve([(0, 0), (10, 15)]) as q:
        with bezjoin.fillet_radius_detailed(p, q, radius) as detailed, \
                bezjoin.fillet_radius(p, q, radius) as plain:
            assert isinstance(detailed, bezjoin.RadiusFilletResult)
            # The same corner as fillet_radius, with the same fairness report.
            assert detailed.blend.points == plain.blend.points
            assert (detailed.energy, detailed.curvature_max, detailed.curvature_extrema) == \
                (plain.energy, plain.curvature_max, plain.curvature_extrema)
            assert detailed.report.energy == detailed.energy
            centre = detailed.arc_centre
            assert len(centre) == 2
            # The cuts are the arc's touching points: at u0 on P and v0 on Q, at
            # distance radius from the centre, the radius perpendicular to the curve.
            for curve, t, kept_end in ((p, detailed.u0, detailed.p_trimmed.points[-1]),
                                       (q, detailed.v0, detailed.q_trimmed.points[0])):
                point, tangent = curve.derivatives(t, 1)
                assert distance(point, kept_end) <= 1e-9
                assert abs(distance(point, centre) - radius) <= 1e-9 * radius
                to_centre = [c - x for c, x in zip(centre, point)]
                assert abs(sum(a * b for a, b in zip(to_centre, tangent))) <= 1e-9 * norm(tangent)
            # The centre lies inside the corner (between the two lines).
            assert centre[1] > 0 and centre[1] * 10 - centre[0] * 15 > 0
            # The reported deviation from the arc's circle is the blend's, re-measured.
            measured = arc_distance(detailed.blend.points, centre, radius)
            assert detailed.arc_deviation == detailed.report.arc_deviation
            assert abs(measured - detailed.arc_deviation) <= 0.02 * measured + 1e-12
            assert detailed.arc_deviation < radius


def test_fillet_radius_detailed_errors_name_the_argument():
    with Curve(LONG) as p, Curve(SHORT) as q, Curve([(0, 5), (4, 5)]) as away, \
            Curve([(0, 0, 0), (1, 1, 1)]) as space:
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_radius_detailed(p, q, 50.0), "radius")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_radius_detailed(p, q, -1.0), "radius")
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: bezjoin.fillet_radius_detailed(p, q, math.inf), "radius")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_radius_detailed(p, q, 1.0, order=0), "order")
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.fillet_radius_detailed(p, q, 1.0, order=-1), "order")
        expect_error("BZJ_ERR_NO_INTERSECTION",
                     lambda: bezjoin.fillet_radius_detailed(p, away, 1.0))
        expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                     lambda: bezjoin.fillet_radius_detailed(p, space, 1.0))
        with pytest.raises(TypeError, match="radius"):
            bezjoin.fillet_radius_detailed(p, q, "one")
        with pytest.raises(TypeError, match="q must be a bezjoin.Curve"):
            bezjoin.fillet_radius_detailed(p, None, 1.0)


# -- fillet by radius: chains ---------------------------------------------------------


def pentagon_sides(bulge):
    """A closed chain of five sides (cubic Bezier curves bulged outwards by
    ``bulge``), each ending where the next starts."""
    vertices = [(10 * math.cos(2 * math.pi * k / 5), 10 * math.sin(2 * math.pi * k / 5))
                for k in range(5)]
    sides = []
    for k in range(5):
        a, b = vertices[k], vertices[(k + 1) % 5]
        normal = ((b[1] - a[1]), -(b[0] - a[0]))
        inner = [tuple(a[c] + (b[c] - a[c]) * f + normal[c] * bulge for c in range(2))
                 for f in (1 / 3, 2 / 3)]
        sides.append([a, inner[0], inner[1], b])
    return sides


@pytest.mark.parametrize("bulge,order", [(0.0, 2), (0.08, 2), (0.08, 3)])
def test_closed_chain_rounds_every_corner_as_fillet_radius(bulge, order):
    radius = 1.5
    curves = [Curve(side) for side in pentagon_sides(bulge)]
    try:
        with bezjoin.fillet_radius_chain(curves, radius, order=order, closed=True) as chain:
            assert isinstance(chain, bezjoin.RadiusFilletChainResult)
            assert chain.closed and len(chain.pieces) == 10 and len(chain.reports) == 5
            assert chain.curves() == chain.pieces
            # Consecutive pieces meet G2 (G^order >= 2), also from the last blend back
            # to the first trimmed curve.
            for i in range(10):
                assert_g2(chain.pieces[i], chain.pieces[(i + 1) % 10])
            for i, report in enumerate(chain.reports):
                assert isinstance(report, bezjoin.RadiusCornerReport)
                p, q = curves[i], curves[(i + 1) % 5]
                # Each corner is the single-corner fillet by radius of its two curves.
                with bezjoin.fillet_radius_detailed(p, q, radius, order=order) as one:
                    assert max(distance(a, b) for a, b in
                               zip(chain.blends[i].points, one.blend.points)) <= 1e-9
                    assert abs(report.u0 - one.u0) <= 1e-12
                    assert abs(report.v0 - one.v0) <= 1e-12
                    assert abs(report.arc_deviation - one.arc_deviation) <= 1e-9
                    assert report.curvature_extrema == one.curvature_extrema
                # The kept pieces run between the touching points of their two corners.
                kept = chain.trimmed[(i + 1) % 5]
                assert distance(kept.evaluate(kept.domain[0]), q.evaluate(report.v0)) <= 1e-9
                assert distance(chain.trimmed[i].points[-1], p.evaluate(report.u0)) <= 1e-9
                assert 0 < report.curvature_max and report.arc_deviation < radius
    finally:
        for c in curves:
            c.close()


def test_open_chain_keeps_the_outer_ends_and_has_one_report_per_inner_corner():
    sides = pentagon_sides(0.05)
    curves = [Curve(side) for side in sides]
    try:
        with bezjoin.fillet_radius_chain(curves[:3], 1.0) as open_chain, \
                bezjoin.fillet_radius_chain(curves, 1.0, closed=True) as closed_chain:
            assert not open_chain.closed
            assert len(open_chain.pieces) == 5 and len(open_chain.reports) == 2
            assert distance(open_chain.pieces[0].points[0], sides[0][0]) <= 1e-15
            assert distance(open_chain.pieces[-1].points[-1], sides[2][-1]) <= 1e-15
            for i in range(4):
                assert_g2(open_chain.pieces[i], open_chain.pieces[i + 1])
            # Its corners are the first two of the closed chain of all five sides.
            assert len(closed_chain.reports) == 5
            assert open_chain.reports == closed_chain.reports[:2]
            for ours, theirs in zip(open_chain.blends, closed_chain.blends):
                assert ours.points == theirs.points
    finally:
        for c in curves:
            c.close()


def test_chain_corner_at_a_crossing_nearest_the_shared_end():
    # The lines overshoot each other at the corner: no shared vertex, a crossing.
    with Curve([(-10, 0), (1, 0)]) as p, Curve([(0, -1), (0, 10)]) as q, \
            bezjoin.fillet_radius_chain([p, q], 2.0) as chain:
        (report,) = chain.reports
        assert distance(p.evaluate(report.u0), (-2.0, 0.0)) <= 1e-9
        assert distance(q.evaluate(report.v0), (0.0, 2.0)) <= 1e-9
        assert_g2(chain.pieces[0], chain.pieces[1])
        assert_g2(chain.pieces[1], chain.pieces[2])


def test_chain_of_nurbs_keeps_the_kinds():
    with Curve.ellipse_arc((0, 0), (1, 0), (0, 1), 5.0, 5.0, 0.0, math.pi / 2) as arc, \
            Curve([(0, 5), (-8, -3)]) as line, \
            bezjoin.fillet_radius_chain([arc, line], 1.0) as chain:
        assert chain.trimmed[0].is_nurbs and not chain.blends[0].is_nurbs
        assert chain.trimmed[0].domain[0] == 0.0
        assert_g2(chain.pieces[0], chain.pieces[1])
        assert_g2(chain.pieces[1], chain.pieces[2])


def test_fillet_radius_chain_errors_name_the_argument():
    square = [[(0, 0), (10, 0)], [(10, 0), (10, 10)], [(10, 10), (0, 10)], [(0, 10), (0, 0)]]
    curves = [Curve(side) for side in square]
    try:
        with Curve([(0, 0, 0), (1, 1, 1)]) as space, Curve([(10, 0), (20, 0)]) as straight:
            error = expect_error("BZJ_ERR_INVALID_ARGUMENT",
                                 lambda: bezjoin.fillet_radius_chain(curves, 20.0), "radius")
            assert "corner 0" in error.message
            # Arcs of radius 6 at both ends of a 10 mm side overlap: that side is named.
            expect_error("BZJ_ERR_INVALID_ARGUMENT",
                         lambda: bezjoin.fillet_radius_chain(curves, 6.0, closed=True),
                         "curves[")
            expect_error("BZJ_ERR_INVALID_ARGUMENT",
                         lambda: bezjoin.fillet_radius_chain(curves, 0.0), "radius")
            expect_error("BZJ_ERR_NON_FINITE",
                         lambda: bezjoin.fillet_radius_chain(curves, math.nan), "radius")
            expect_error("BZJ_ERR_INVALID_ARGUMENT",
                         lambda: bezjoin.fillet_radius_chain(curves, 1.0, order=7), "order")
            expect_error("BZJ_ERR_INVALID_ARGUMENT",
                         lambda: bezjoin.fillet_radius_chain(curves[:1], 1.0), "curves")
            expect_error("BZJ_ERR_NO_INTERSECTION",
                         lambda: bezjoin.fillet_radius_chain([curves[0], curves[2]], 1.0),
                         "corner 0")
            expect_error("BZJ_ERR_NO_INTERSECTION",
                         lambda: bezjoin.fillet_radius_chain([curves[0], straight], 1.0))
            expect_error("BZJ_ERR_DIMENSION_MISMATCH",
                         lambda: bezjoin.fillet_radius_chain([curves[0], space], 1.0),
                         "curves[1]")
            with pytest.raises(TypeError, match=r"curves\[1\] must be a bezjoin.Curve"):
                bezjoin.fillet_radius_chain([curves[0], None], 1.0)
            with pytest.raises(TypeError, match="closed must be a bool"):
                bezjoin.fillet_radius_chain(curves, 1.0, closed=1)
            with pytest.raises(TypeError, match="radius"):
                bezjoin.fillet_radius_chain(curves, None)
    finally:
        for c in curves:
            c.close()
