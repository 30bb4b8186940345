"""How the cost of connect, merge and fillet grows with degree, through the C ABI
from Python (ctypes; ~10 us of call overhead per call included).

Issue 20's "How cost grows with degree" table. Random planar pairs from a
fixed seed (the same pairs every run):

- connect: P at u0 = 1 to Q at v0 = 0, C^min(n, 15) at both ends, with the
  paper's scale 1 and with the default automatic scale;
- merge: P ending where Q starts, plus a small random gap; discrete metric
  with mu = 1/2, and the L2 metric with the optimal mu;
- fillet: P roughly along the x axis, Q roughly along the y axis, one
  crossing near the origin; setback 0.1, C2 at both ends.

Each cell is the median over 7 batches of the time per call; a refused call
prints its status instead. Run (the library from `cargo build --release -p
bezjoin-ffi`):

    BEZJOIN_LIBRARY=target/release/libbezjoin.so python3 bindings/python/bench/degree_growth.py
"""

import os
import random
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

import bezjoin  # noqa: E402

DEGREES = [3, 7, 15, 23, 31]
BATCHES = 7


def per_call(function, budget=0.05):
    """Median seconds per call over BATCHES batches sized to ~budget each."""
    function()
    calls = 1
    while True:
        start = time.perf_counter()
        for _ in range(calls):
            function()
        elapsed = time.perf_counter() - start
        if elapsed > budget / 4 or calls > 1 << 20:
            break
        calls *= 2
    samples = []
    for _ in range(BATCHES):
        start = time.perf_counter()
        for _ in range(calls):
            function()
        samples.append((time.perf_counter() - start) / calls)
    return statistics.median(samples)


def show(seconds):
    if seconds >= 1e-3:
        return f"{seconds * 1e3:.3g} ms"
    return f"{seconds * 1e6:.3g} us"


def cell(function):
    try:
        return show(per_call(function))
    except bezjoin.BezjoinError as error:
        return f"refused ({error.status_name if hasattr(error, 'status_name') else error})"


def random_curve(rng, n, start, end, wiggle):
    points = [start]
    for i in range(1, n):
        t = i / n
        points.append((start[0] + (end[0] - start[0]) * t + rng.uniform(-wiggle, wiggle),
                       start[1] + (end[1] - start[1]) * t + rng.uniform(-wiggle, wiggle)))
    points.append(end)
    return bezjoin.Curve(points)


def main():
    rng = random.Random(20)
    print("| degree | connect C^min(n,15) | connect, automatic scale | merge discrete, mu = 1/2 "
          "| merge L2, optimal mu | fillet C2 (automatic scale) |")
    print("|---|---|---|---|---|---|")
    for n in DEGREES:
        p = random_curve(rng, n, (-2.0, 0.0), (-0.5, 0.3), 0.3)
        q = random_curve(rng, n, (0.5, 0.2), (2.0, -0.1), 0.3)
        k = min(n, 15)
        connect = cell(lambda: bezjoin.connect(p, 1.0, q, 0.0, p_order=k, q_order=k,
                                               auto_scale=False))
        automatic = cell(lambda: bezjoin.connect(p, 1.0, q, 0.0, p_order=k, q_order=k))
        mp = random_curve(rng, n, (-2.0, 0.0), (0.0, 0.0), 0.3)
        mq = random_curve(rng, n, (0.01, 0.02), (2.0, 0.3), 0.3)
        discrete = cell(lambda: bezjoin.merge(mp, mq, metric="discrete", mu=0.5))
        l2 = cell(lambda: bezjoin.merge(mp, mq, metric="l2", mu="optimal"))
        fp = random_curve(rng, n, (-1.0, 0.05), (1.0, -0.05), 0.05)
        fq = random_curve(rng, n, (0.05, -1.0), (-0.05, 1.0), 0.05)
        fillet = cell(lambda: bezjoin.fillet(fp, fq, setback=0.1, p_order=2, q_order=2))
        print(f"| {n} | {connect} | {automatic} | {discrete} | {l2} | {fillet} |", flush=True)


if __name__ == "__main__":
    main()
