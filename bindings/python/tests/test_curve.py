"""Curve: construction, evaluation and the exact operations, judged by an independent
pure-Python evaluator (tests/reference.py); every error path; handle lifetime."""

import gc
import math
import random

import pytest

import bezjoin
from bezjoin import BezjoinError, Curve, _library
from reference import assert_close, de_casteljau, derivative

SAMPLES = [i / 16 for i in range(17)]


def random_points(rng, degree, dim, spread=10.0):
    return [tuple(rng.uniform(-spread, spread) for _ in range(dim)) for _ in range(degree + 1)]


@pytest.fixture
def rng():
    return random.Random(20261122)


# -- construction and inspection ----------------------------------------------


@pytest.mark.parametrize("degree,dim", [(0, 1), (1, 2), (3, 2), (5, 3), (7, 4), (12, 3)])
def test_points_round_trip_exactly(rng, degree, dim):
    points = random_points(rng, degree, dim)
    with Curve(points) as curve:
        assert curve.degree == degree
        assert curve.dim == dim
        assert curve.points == points


def test_accepts_any_sequence_of_points():
    class Vector:  # a FreeCAD-like vector: iterable of coordinates
        def __init__(self, *coordinates):
            self.coordinates = coordinates

        def __iter__(self):
            return iter(self.coordinates)

    with Curve([Vector(0, 0, 0), [1, 2, 3], (4.5, 5, 6)]) as curve:
        assert curve.points == [(0.0, 0.0, 0.0), (1.0, 2.0, 3.0), (4.5, 5.0, 6.0)]


def test_repr_shows_points_and_closed_state():
    curve = Curve([(0, 1), (2, 3)])
    assert repr(curve) == "Curve([(0.0, 1.0), (2.0, 3.0)])"
    curve.close()
    assert repr(curve) == "Curve(<closed>)"


# -- evaluation -----------------------------------------------------------------


@pytest.mark.parametrize("degree,dim", [(0, 2), (1, 1), (3, 2), (6, 3), (10, 2)])
def test_evaluate_matches_de_casteljau(rng, degree, dim):
    points = random_points(rng, degree, dim)
    with Curve(points) as curve:
        for t in SAMPLES + [-0.5, 1.7]:
            assert_close(curve.evaluate(t), de_casteljau(points, t), 1e-12, scale=100.0)
            assert curve(t) == curve.evaluate(t)


@pytest.mark.parametrize("degree,dim", [(2, 2), (4, 3), (7, 2)])
def test_derivatives_match_hodographs(rng, degree, dim):
    points = random_points(rng, degree, dim)
    with Curve(points) as curve:
        for t in SAMPLES:
            rows = curve.derivatives(t, degree + 2)
            assert len(rows) == degree + 3
            for k, row in enumerate(rows):
                expected = derivative(points, t, k)
                size = math.factorial(degree) / math.factorial(max(degree - k, 0)) * 100
                assert_close(row, expected, 1e-12, scale=size)
            assert rows[-1] == tuple(0.0 for _ in range(dim))


def test_derivatives_many_is_derivatives_at_every_parameter(rng):
    curve = Curve(random_points(rng, 5, 3))
    ts = [-0.5, 0.0, 0.125, 0.7, 1.0, 1.5]
    for max_order in (0, 2, 7):
        many = curve.derivatives_many(ts, max_order)
        assert len(many) == len(ts)
        for t, rows in zip(ts, many):
            assert rows == curve.derivatives(t, max_order)
    assert curve.derivatives_many([], 3) == []


def test_derivatives_many_names_the_bad_parameter(rng):
    # Closed by the with block: the lambda and the traceback make a reference
    # cycle, which the garbage collector would otherwise break (and release the
    # handle) at an arbitrary later moment, e.g. inside test_close_releases_once.
    with Curve(random_points(rng, 3, 2)) as curve:
        expect_error("BZJ_ERR_NON_FINITE",
                     lambda: curve.derivatives_many([0.1, 0.2, math.nan], 1), "ts[2]")


def test_derivatives_agree_with_finite_differences(rng):
    points = random_points(rng, 5, 2)
    with Curve(points) as curve:
        step = 1e-6
        for t in (0.2, 0.5, 0.8):
            first = curve.derivatives(t, 1)[1]
            before, after = curve.evaluate(t - step), curve.evaluate(t + step)
            central = tuple((a - b) / (2 * step) for a, b in zip(after, before))
            assert_close(first, central, 1e-6, scale=100.0)


# -- exact operations -------------------------------------------------------------


def test_split_pieces_are_the_curve_on_each_part(rng):
    points = random_points(rng, 5, 3)
    with Curve(points) as curve:
        for t in (0.0, 0.3, 0.5, 1.0):
            left, right = curve.split(t)
            with left, right:
                assert left.degree == right.degree == 5
                assert left.points[-1] == right.points[0]
                for s in SAMPLES:
                    assert_close(left.evaluate(s), curve.evaluate(t * s), 1e-12, 100.0)
                    assert_close(right.evaluate(s), curve.evaluate(t + (1 - t) * s), 1e-12, 100.0)


def test_elevate_keeps_the_curve(rng):
    points = random_points(rng, 3, 2)
    with Curve(points) as curve:
        for new_degree in (3, 4, 9):
            with curve.elevate(new_degree) as elevated:
                assert elevated.degree == new_degree
                assert elevated.points[0] == points[0] and elevated.points[-1] == points[-1]
                for s in SAMPLES:
                    assert_close(elevated.evaluate(s), curve.evaluate(s), 1e-12, 100.0)


def test_segment_reparametrises_including_extrapolation(rng):
    points = random_points(rng, 4, 2)
    with Curve(points) as curve:
        for a, b in ((0.2, 0.7), (0.0, 1.5), (-0.4, 0.3), (0.9, 0.1), (0.5, 0.5)):
            with curve.segment(a, b) as piece:
                for s in SAMPLES:
                    assert_close(piece.evaluate(s), de_casteljau(points, a + (b - a) * s),
                                 1e-11, 1000.0)


def test_reverse_runs_backwards_and_twice_is_identity(rng):
    points = random_points(rng, 6, 3)
    with Curve(points) as curve, curve.reverse() as backwards:
        assert backwards.points == points[::-1]
        for s in SAMPLES:
            assert_close(backwards.evaluate(s), curve.evaluate(1 - s), 1e-12, 100.0)
        with backwards.reverse() as again:
            assert again.points == points


def test_length_of_a_segment_and_a_parabola():
    with Curve([(1, 2, 3), (4, 6, 3)]) as line:
        assert abs(line.length() - 5.0) <= 1e-13 * 5
    # y = x^2 on [0, 1]: x(t) = t, exact length sqrt(5)/2 + asinh(2)/4.
    with Curve([(0, 0), (0.5, 0), (1, 1)]) as parabola:
        exact = math.sqrt(5) / 2 + math.asinh(2) / 4
        assert abs(parabola.length() - exact) <= 1e-13 * exact
        assert parabola.length(1, 0) == -parabola.length(0, 1)
        parts = parabola.length(0, 0.3) + parabola.length(0.3, 1)
        assert abs(parts - exact) <= 1e-13 * exact
        # x from 0 to 2 (extrapolation): sqrt(17) + asinh(4)/4.
        beyond = math.sqrt(17) + math.asinh(4) / 4
        assert abs(parabola.length(0, 2) - beyond) <= 1e-13 * beyond


# -- error paths ------------------------------------------------------------------


def expect_error(status_name, call, *match):
    with pytest.raises(BezjoinError) as caught:
        call()
    error = caught.value
    assert error.status_name == status_name
    assert error.status == {v: k for k, v in bezjoin.STATUS_NAMES.items()}[status_name]
    assert str(error).startswith(status_name + ": ")
    for text in match:
        assert text in error.message, error.message
    return error


def test_construction_errors():
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve([]), "points is empty")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve([()]), "points[0]")
    expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: Curve([(0, 0), (1, 1, 1)]), "points[1]")
    expect_error("BZJ_ERR_NON_FINITE", lambda: Curve([(0, 0), (math.nan, 1)]), "NaN")
    expect_error("BZJ_ERR_NON_FINITE", lambda: Curve([(0, math.inf)]))
    # A bad coordinate is named by point and coordinate, as the caller gave it, not by
    # its index in the flat array the library sees (user testing, session 40).
    expect_error("BZJ_ERR_NON_FINITE", lambda: Curve([(0, 0, 0), (1, 1, 1), (2, math.nan, 0)]),
                 "points[2][1] = NaN")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: Curve.nurbs([(0, 0), (1, math.inf), (2, 0)], [0, 0, 0, 1, 1, 1], 2),
                 "poles[1][1] = inf")
    expect_error("BZJ_ERR_NON_FINITE",
                 lambda: bezjoin.lagrange_spline([(0, 0), (1, math.nan), (2, 0)],
                                                 [(0.3, 0.1), (0.6, 0.1)], [(1.6, 0.1)]),
                 "nodes[1][1] = NaN")
    with pytest.raises(TypeError, match="sequence of points"):
        Curve([(0, "x")])
    with pytest.raises(TypeError):
        Curve(5)


def test_evaluation_errors():
    with Curve([(0, 0), (1, 1)]) as curve:
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.evaluate(math.nan), "t")
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.derivatives(math.inf, 2), "t")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.derivatives(0.5, -1),
                     "max_order = -1")
        with pytest.raises(TypeError, match="max_order"):
            curve.derivatives(0.5, 1.5)
        with pytest.raises(TypeError, match="max_order"):
            curve.derivatives(0.5, True)
        with pytest.raises(TypeError, match="t must be a real number"):
            curve.evaluate("half")
        with pytest.raises(TypeError, match="t must be a real number"):
            curve.evaluate(False)
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.length(0, math.inf))
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.length(math.nan, 1))


def test_operation_errors():
    with Curve([(0, 0), (1, 2), (3, 1)]) as curve:
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.split(1.5), "t = 1.5")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.split(-0.1), "t")
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.split(math.nan), "t")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.elevate(1), "new_degree")
        expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.elevate(-3), "new_degree = -3")
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.segment(0, math.nan), "b")
        expect_error("BZJ_ERR_NON_FINITE", lambda: curve.segment(-math.inf, 1), "a")


def test_errors_carry_the_library_message_of_this_call():
    with Curve([(0, 0), (1, 1)]) as curve:
        first = expect_error("BZJ_ERR_INVALID_ARGUMENT", lambda: curve.split(2.0))
        assert curve.evaluate(0.5) == (0.5, 0.5)
        second = expect_error("BZJ_ERR_NON_FINITE", lambda: curve.segment(math.nan, 1))
        assert first.message != second.message


# -- handle lifetime ----------------------------------------------------------------


class FreeCounter:
    """Wraps bzj_curve_free to count releases per handle address."""

    def __init__(self, monkeypatch):
        self.released = []
        library = _library.library()
        real = library.function("bzj_curve_free")

        def counting_free(handle):
            self.released.append(_library.ctypes.addressof(handle.contents))
            real(handle)

        monkeypatch.setitem(library._functions, "bzj_curve_free", counting_free)


def address(curve):
    return _library.ctypes.addressof(curve._handle.contents)


def test_close_releases_once(monkeypatch):
    counter = FreeCounter(monkeypatch)
    curve = Curve([(0, 0), (1, 1)])
    where = address(curve)
    curve.close()
    curve.close()
    del curve
    gc.collect()
    assert counter.released == [where]


def test_with_block_releases_and_then_use_fails(monkeypatch):
    counter = FreeCounter(monkeypatch)
    with Curve([(0, 0), (1, 1)]) as curve:
        where = address(curve)
        assert not curve.closed
    assert curve.closed
    assert counter.released == [where]
    for use in (lambda: curve.degree, lambda: curve.points, lambda: curve.evaluate(0.5),
                lambda: curve.split(0.5), lambda: curve.reverse(), lambda: curve.length(),
                lambda: curve.elevate(3), lambda: curve.segment(0, 1)):
        with pytest.raises(ValueError, match="closed Curve"):
            use()
    with pytest.raises(ValueError, match="closed Curve"):
        with curve:
            pass


def test_garbage_collection_releases(monkeypatch):
    counter = FreeCounter(monkeypatch)
    curve = Curve([(0, 0), (1, 1)])
    left, right = curve.split(0.5)
    where = sorted(address(c) for c in (curve, left, right))
    del curve, left, right
    gc.collect()
    assert sorted(counter.released) == where


def test_failed_construction_releases_nothing(monkeypatch):
    counter = FreeCounter(monkeypatch)
    with pytest.raises(BezjoinError):
        Curve([(math.nan, 0)])
    gc.collect()
    assert counter.released == []


def test_handle_of_checks_type():
    from bezjoin.curve import handle_of

    with pytest.raises(TypeError, match="p must be a bezjoin.Curve"):
        handle_of([(0, 0)], "p")


def test_freecad_conversion_without_freecad_is_a_clear_error():
    import importlib.util

    if importlib.util.find_spec("Part") is not None:
        pytest.skip("FreeCAD is importable here; covered by the freecadcmd tests")
    with Curve([(0, 0, 0), (1, 1, 1)]) as curve:
        with pytest.raises(bezjoin.UnsupportedGeometryError, match="Part module"):
            curve.to_freecad()
    with pytest.raises(bezjoin.UnsupportedGeometryError, match="Part module"):
        Curve.from_freecad(object())


def test_each_thread_gets_its_own_error_message():
    import threading

    barrier = threading.Barrier(4)
    messages = {}

    def fail(index):
        with Curve([(0.0, 0.0), (1.0, 1.0)]) as curve:
            barrier.wait()
            for _ in range(200):
                try:
                    curve.split(2.0 + index)
                except BezjoinError as error:
                    messages.setdefault(index, set()).add(error.message)

    threads = [threading.Thread(target=fail, args=(i,)) for i in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for index in range(4):
        assert messages[index] == {f"t = {2 + index} is outside [0, 1]"}


def test_copies_and_pickles_own_their_handle(monkeypatch):
    import copy
    import pickle

    counter = FreeCounter(monkeypatch)
    curve = Curve([(0.0, 1.0), (2.0, 3.5), (4.0, -1.0)])
    twins = [curve.copy(), copy.copy(curve), copy.deepcopy(curve),
             pickle.loads(pickle.dumps(curve))]
    addresses = {address(c) for c in [curve] + twins}
    assert len(addresses) == 5
    for twin in twins:
        assert twin.points == curve.points
    for c in [curve] + twins:
        c.close()
    assert sorted(counter.released) == sorted(addresses)
