"""Speed of the FreeCAD conversions and of a blend of two edges (issue 19, item 7).

Run under FreeCAD's command-line interpreter from the repository root:

    cargo build --release -p bezjoin-ffi
    freecadcmd freecad/bench/bench_conversions.py

Environment: ``BEZJOIN_LIBRARY`` (default: the repository's
``target/release/libbezjoin.so``, as ``freecad/run-tests.sh`` sets it),
``BEZJOIN_BENCH_BINDINGS`` (default: ``bindings/python`` of this tree),
``BEZJOIN_BENCH_REPEAT`` (repeats, default 15), ``BEZJOIN_BENCH_SECONDS``
(about how long one repeat of one case runs, default 0.002: on a shared machine
short repeats find windows without preemption, so the minimum is steadier than with
20 ms repeats, which gave ratios from 0.45 to 1.3 between runs at load 10).

Every time is the minimum over the repeats of (repeat time / calls), so a
loaded machine inflates it less than a mean would. The blend is measured
side by side with FreeCAD's own: the end derivatives of the same two edges by
``Curve.getDN`` (times ``scale^k``), the Hermite-type Bezier curve through them
by ``Part.BezierCurve.interpolate`` (the C^k blend CurvesWB and FreeCAD users
write); the cases run interleaved, repeat by repeat.
"""

import os
import sys
import timeit

HERE = os.path.dirname(os.path.abspath(__file__))
REPOSITORY = os.path.dirname(os.path.dirname(HERE))
# As freecad/tests/run_in_freecad.py: the bindings from the source tree
# (BEZJOIN_BENCH_BINDINGS: another folder holding a ``bezjoin`` package, e.g. an
# older copy, for before/after figures).
BINDINGS = os.environ.get("BEZJOIN_BENCH_BINDINGS") or os.path.join(REPOSITORY, "bindings",
                                                                    "python")
if BINDINGS not in sys.path:
    sys.path.insert(0, BINDINGS)
os.environ.setdefault("BEZJOIN_LIBRARY",
                      os.path.join(REPOSITORY, "target", "release", "libbezjoin.so"))

import FreeCAD  # noqa: E402
import Part  # noqa: E402

import bezjoin  # noqa: E402
from bezjoin import _freecad  # noqa: E402

V = FreeCAD.Vector
ORDER = 3          # C^3 at both ends: the degree-7 blend of two cubics
SCALE = 0.8        # the given scale (p_scale = q_scale)
U0, V0 = 1.0, 0.0  # end of P, start of Q


def cubic_edge(points):
    curve = Part.BezierCurve()
    curve.setPoles([V(*p) for p in points])
    return curve.toShape()


EDGE_P = cubic_edge([(0, 0, 0), (1, 1, 0.2), (2, 1, 0.1), (3, 0, 0)])
EDGE_Q = cubic_edge([(4, 0.5, 0), (5, 0, 0.3), (6, 1, 0.2), (7, 0, 0)])
CUBIC = bezjoin.Curve([(0, 0, 0), (1, 1, 0.2), (2, 1, 0.1), (3, 0, 0)])
TUPLES_4 = [(0.0, 0.0, 0.0), (1.0, 1.0, 0.2), (2.0, 1.0, 0.1), (3.0, 0.0, 0.0)]
TUPLES_8 = TUPLES_4 + TUPLES_4


def ours_from():
    return bezjoin.Curve.from_freecad(EDGE_P)


def ours_to():
    return CUBIC.to_freecad()


def ours_points():
    return CUBIC.points


def ours_blend_given():
    p = bezjoin.Curve.from_freecad(EDGE_P)
    q = bezjoin.Curve.from_freecad(EDGE_Q)
    blend = bezjoin.connect(p, U0, q, V0, p_order=ORDER, q_order=ORDER,
                            p_scale=SCALE, q_scale=SCALE)
    return blend.to_freecad()


def ours_edges_given():
    return bezjoin.connect_edges(EDGE_P, U0, EDGE_Q, V0, p_order=ORDER, q_order=ORDER,
                                 p_scale=SCALE, q_scale=SCALE)


def ctypes_route(function):
    """``function`` run with the compiled fast path (bezjoin._native) switched off: the
    ctypes route, measured in the same process; the result is released inside."""

    def run():
        saved = _freecad._native_module
        _freecad._native_module = None
        try:
            function()
        finally:
            _freecad._native_module = saved

    return run


def ours_edges_auto():
    return bezjoin.connect_edges(EDGE_P, U0, EDGE_Q, V0, p_order=ORDER, q_order=ORDER)


def freecad_reads():
    """What any blend from poles must ask FreeCAD for: per edge its curve, its
    parameter range, whether it is degenerated or rational, and the poles; then one
    Part.BezierCurve with the 8 poles of the blend (here P's poles twice, as
    tuples). The floor of a blend that reads the poles (no Python, no library)."""
    p_curve, q_curve = EDGE_P.Curve, EDGE_Q.Curve
    EDGE_P.Degenerated, EDGE_Q.Degenerated
    EDGE_P.ParameterRange, EDGE_Q.ParameterRange
    p_curve.isRational(), q_curve.isRational()
    poles = p_curve.getPoles(), q_curve.getPoles()
    blend = Part.BezierCurve()
    blend.setPoles(TUPLES_8)
    return poles, blend


def freecad_curve_reads():
    """FreeCAD's reads of one cubic edge in from_freecad's fast path."""
    curve = EDGE_P.Curve
    return EDGE_P.Degenerated, EDGE_P.ParameterRange, curve.isRational(), curve.getPoles()


def freecad_bezier_out():
    """FreeCAD's part of to_freecad: a Part.BezierCurve and one setPoles of 4 tuples."""
    curve = Part.BezierCurve()
    curve.setPoles(TUPLES_4)
    return curve


def ours_blend_auto():
    p = bezjoin.Curve.from_freecad(EDGE_P)
    q = bezjoin.Curve.from_freecad(EDGE_Q)
    blend = bezjoin.connect(p, U0, q, V0, p_order=ORDER, q_order=ORDER)
    return blend.to_freecad()


def freecad_ends(edge, u, scale):
    curve = edge.Curve
    row = [curve.value(u)]
    factor = 1.0
    for k in range(1, ORDER + 1):
        factor *= scale
        row.append(curve.getDN(u, k) * factor)
    return row


def freecad_blend(scale=SCALE):
    blend = Part.BezierCurve()
    blend.interpolate([freecad_ends(EDGE_P, U0, scale), freecad_ends(EDGE_Q, V0, scale)],
                      [0.0, 1.0])
    return blend


AUTO_SCALE = None


def freecad_blend_auto_scale():
    """FreeCAD's blend with the scale our automatic choice found (FreeCAD has no
    such choice: the same curve, for the record; its time is that of the given scale)."""
    return freecad_blend(AUTO_SCALE)


def pole_distance(a, b):
    pa, pb = a.getPoles(), b.getPoles()
    assert len(pa) == len(pb), (len(pa), len(pb))
    return max((x - y).Length for x, y in zip(pa, pb))


def measure(cases, repeat, seconds):
    """``{name: seconds per call}``, min over ``repeat`` interleaved repeats."""
    numbers = {}
    for name, function in cases:
        timer = timeit.Timer(function)
        count, elapsed = timer.autorange()
        numbers[name] = max(1, int(count * seconds / max(elapsed, 1e-9)))
    best = {name: float("inf") for name, _ in cases}
    for _ in range(repeat):
        for name, function in cases:
            elapsed = timeit.Timer(function).timeit(numbers[name])
            best[name] = min(best[name], elapsed / numbers[name])
    return best


def main():
    global AUTO_SCALE
    repeat = int(os.environ.get("BEZJOIN_BENCH_REPEAT", "15"))
    seconds = float(os.environ.get("BEZJOIN_BENCH_SECONDS", "0.002"))

    # Same curves both ways.
    given = ours_blend_given()
    theirs = freecad_blend()
    with bezjoin.Curve.from_freecad(EDGE_P) as p, bezjoin.Curve.from_freecad(EDGE_Q) as q:
        auto = bezjoin.connect_auto_scale(p, U0, q, V0, p_order=ORDER, q_order=ORDER)
        AUTO_SCALE = auto.scale
        auto.close()
    checks = {
        "given scale: ours vs FreeCAD, max pole distance": pole_distance(given, theirs),
        "auto scale: ours vs FreeCAD at that scale, max pole distance":
            pole_distance(ours_blend_auto(), freecad_blend_auto_scale()),
        "connect_edges vs from_freecad+connect+to_freecad, given scale (must be 0)":
            pole_distance(ours_edges_given(), given),
        "connect_edges vs from_freecad+connect+to_freecad, auto scale (must be 0)":
            pole_distance(ours_edges_auto(), ours_blend_auto()),
    }

    cases = [
        ("from_freecad(cubic Bezier edge)", ours_from),
        ("to_freecad(cubic)", ours_to),
        ("Curve.points (cubic, 3D)", ours_points),
        ("blend, ours, given scale", ours_blend_given),
        ("blend, ours, automatic scale", ours_blend_auto),
        ("blend, FreeCAD getDN + BezierCurve.interpolate", freecad_blend),
        ("blend, ours connect_edges, given scale", ours_edges_given),
        ("blend, ours connect_edges, automatic scale", ours_edges_auto),
        ("ctypes route: from_freecad(cubic Bezier edge)", ctypes_route(ours_from)),
        ("ctypes route: to_freecad(cubic)", ctypes_route(ours_to)),
        ("ctypes route: blend, connect_edges, given scale", ctypes_route(ours_edges_given)),
        ("floor: FreeCAD reads of one cubic edge", freecad_curve_reads),
        ("floor: Part.BezierCurve + setPoles(4 tuples)", freecad_bezier_out),
        ("floor: FreeCAD reads + output of a blend", freecad_reads),
    ]
    best = measure(cases, repeat, seconds)

    print(f"bezjoin {bezjoin.library_version()} ({bezjoin.library_path()}), "
          f"bindings {os.path.dirname(os.path.dirname(os.path.abspath(bezjoin.__file__)))}, "
          f"FreeCAD {'.'.join(FreeCAD.Version()[:3])}, Python {sys.version.split()[0]}")
    fast = _freecad.native()
    print("compiled fast path: " + (fast.__file__ if fast is not None else
                                    "absent (ctypes route only)"))
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} "
          f"{os.getloadavg()[2]:.2f}")
    print(f"min of {repeat} repeats; degree-7 C^{ORDER} blend of two cubic edges, "
          f"given scale {SCALE}, automatic scale {AUTO_SCALE:.6g}")
    for name, value in checks.items():
        print(f"  check  {name}: {value:.3g}")
    width = max(len(name) for name, _ in cases)
    for name, _ in cases:
        print(f"  {name:<{width}}  {best[name] * 1e6:8.2f} us")
    reference = best["blend, FreeCAD getDN + BezierCurve.interpolate"]
    for name in ("blend, ours, given scale", "blend, ours, automatic scale",
                 "blend, ours connect_edges, given scale",
                 "blend, ours connect_edges, automatic scale",
                 "ctypes route: blend, connect_edges, given scale"):
        print(f"  {name} / FreeCAD's blend: {best[name] / reference:.2f}")
    sys.stdout.flush()


try:
    main()
except BaseException:  # noqa: BLE001 (freecadcmd would swallow it and exit 0)
    import traceback

    traceback.print_exc(file=sys.stdout)
    sys.stdout.flush()
    os._exit(1)
