"""intersect_detailed: the kind of every hit (crossing, touching, overlap with its range),
the hits are common points, the options reach the library, and every error path;
intersect keeps returning the plain (u, v) pairs of the same search."""

import math

import pytest

import bezjoin
from bezjoin import Curve, Intersection
from reference import distance
from test_curve import expect_error

WAVE = [(0, -1), (1, 3), (2, -3), (3, 1)]
LINE = [(-0.5, 0.1), (3.5, -0.1)]


def test_crossings_are_common_points_of_kind_crossing():
    with Curve(WAVE) as p, Curve(LINE) as q:
        hits = bezjoin.intersect_detailed(p, q)
        assert len(hits) == 3
        assert [h.u for h in hits] == sorted(h.u for h in hits)
        for hit in hits:
            assert isinstance(hit, Intersection)
            assert hit.kind == "crossing"
            assert (hit.u_end, hit.v_end) == (hit.u, hit.v)
            gap = distance(p.evaluate(hit.u), q.evaluate(hit.v))
            assert gap <= 1e-11
            assert abs(hit.distance - gap) <= 1e-12
        # intersect is the same search, returning the (u, v) pairs only
        assert bezjoin.intersect(p, q) == [(h.u, h.v) for h in hits]


def test_a_tangent_contact_is_touching():
    # y = (1 - 2t)^2 touches the x axis at t = 1/2, the point (0, 0)
    with Curve([(-1, 1), (0, -1), (1, 1)]) as p, Curve([(-2, 0), (2, 0)]) as q:
        (hit,) = bezjoin.intersect_detailed(p, q)
        assert hit.kind == "touching"
        assert abs(hit.u - 0.5) <= 1e-6 and abs(hit.v - 0.5) <= 1e-6
        assert distance(p.evaluate(hit.u), q.evaluate(hit.v)) <= 1e-9
        assert bezjoin.intersect(p, q) == [(hit.u, hit.v)]


@pytest.mark.parametrize("q_points,v,v_end", [
    ([(1, 0), (3, 0)], 0.0, 0.5),      # same direction
    ([(3, 0), (1, 0)], 1.0, 0.5),      # opposite direction: v decreases along the overlap
])
def test_an_overlap_reports_its_range(q_points, v, v_end):
    with Curve([(0, 0), (2, 0)]) as p, Curve(q_points) as q:
        (hit,) = bezjoin.intersect_detailed(p, q)
        assert hit.kind == "overlap"
        assert hit.u == pytest.approx(0.5, abs=1e-9)
        assert hit.u_end == pytest.approx(1.0, abs=1e-9)
        assert hit.v == pytest.approx(v, abs=1e-9)
        assert hit.v_end == pytest.approx(v_end, abs=1e-9)
        # both ends of the range are common points
        assert distance(p.evaluate(hit.u), q.evaluate(hit.v)) <= 1e-9
        assert distance(p.evaluate(hit.u_end), q.evaluate(hit.v_end)) <= 1e-9
        assert bezjoin.intersect(p, q) == [(hit.u, hit.v)]


def test_the_distance_tolerance_option_reaches_the_library():
    # Q starts 1e-6 above P: no hit at the default relative tolerance 1e-9,
    # one hit when the tolerance allows it.
    with Curve([(0, 0), (2, 0)]) as p, Curve([(1, 1e-6), (3, 1)]) as q:
        assert bezjoin.intersect_detailed(p, q) == []
        (hit,) = bezjoin.intersect_detailed(p, q, relative_distance_tolerance=1e-3)
        assert 1e-6 * (1 - 1e-9) <= hit.distance <= 1e-3 * 3
        assert abs(distance(p.evaluate(hit.u), q.evaluate(hit.v)) - hit.distance) <= 1e-15


def test_the_work_bounds_reach_the_library():
    with Curve(WAVE) as p, Curve(LINE) as q:
        assert len(bezjoin.intersect_detailed(p, q, max_hits=3)) == 3
        expect_error("BZJ_ERR_ILL_CONDITIONED",
                     lambda: bezjoin.intersect_detailed(p, q, max_hits=2))
        expect_error("BZJ_ERR_ILL_CONDITIONED",
                     lambda: bezjoin.intersect_detailed(p, q, max_box_pairs=1))


def test_more_hits_than_the_first_request_holds(monkeypatch):
    import bezjoin._fillet as fillet_module

    with Curve(WAVE) as p, Curve(LINE) as q:
        expected = bezjoin.intersect_detailed(p, q)
        monkeypatch.setattr(fillet_module, "FIRST_CAPACITY", 1)
        assert bezjoin.intersect_detailed(p, q) == expected
        assert len(expected) == 3


def test_no_meeting_is_an_empty_list():
    with Curve([(0, 0), (1, 0)]) as p, Curve([(0, 1), (1, 1)]) as q:
        assert bezjoin.intersect_detailed(p, q) == []


def test_intersect_detailed_errors():
    with Curve(WAVE) as p, Curve(LINE) as q, Curve([(0, 0, 0), (1, 1, 1)]) as space, \
            Curve([(0,), (1,)]) as flat, Curve([(1,), (0,)]) as flat2:
        for name, bad in (("relative_distance_tolerance", 0.0),
                          ("relative_distance_tolerance", 1.0),
                          ("tangent_tolerance", 1.0),
                          ("tangent_tolerance", -0.1),
                          ("max_box_pairs", 0)):
            expect_error("BZJ_ERR_INVALID_ARGUMENT",
                         lambda: bezjoin.intersect_detailed(p, q, **{name: bad}), name)
        for name in ("relative_distance_tolerance", "tangent_tolerance"):
            expect_error("BZJ_ERR_NON_FINITE",
                         lambda: bezjoin.intersect_detailed(p, q, **{name: math.nan}), name)
        # negative counts would wrap around in size_t: rejected before the call
        expect_error("BZJ_ERR_INVALID_ARGUMENT",
                     lambda: bezjoin.intersect_detailed(p, q, max_depth=-1), "max_depth")
        with pytest.raises(TypeError, match="max_hits must be an integer"):
            bezjoin.intersect_detailed(p, q, max_hits=2.5)
        with pytest.raises(TypeError, match="tangent_tolerance must be a real number"):
            bezjoin.intersect_detailed(p, q, tangent_tolerance="small")
        with pytest.raises(TypeError):
            bezjoin.intersect_detailed(p, q, 1e-6)  # options are keyword-only
        expect_error("BZJ_ERR_DIMENSION_MISMATCH", lambda: bezjoin.intersect_detailed(p, space))
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: bezjoin.intersect_detailed(flat, flat2))
        with pytest.raises(TypeError):
            bezjoin.intersect_detailed(None, q)
