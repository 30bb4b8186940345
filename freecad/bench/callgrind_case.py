"""One case of bench_conversions.py, called BEZJOIN_CG_N times (after 50 warm-up calls),
for instruction counts under callgrind (freecad/bench/callgrind.sh runs it).

    BEZJOIN_CG_CASE=ours_edges_given BEZJOIN_CG_N=1000 freecadcmd freecad/bench/callgrind_case.py
"""

import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BENCH = os.path.join(HERE, "bench_conversions.py")

try:
    with open(BENCH, encoding="utf-8") as handle:
        source = handle.read()
    # The bench's edges and case functions, without running its main().
    source = source[:source.index("\ntry:\n    main()")]
    names = {"__name__": "bench_conversions", "__file__": BENCH}
    exec(compile(source, BENCH, "exec"), names)  # noqa: S102 (our own file)
    case = names[os.environ["BEZJOIN_CG_CASE"]]
    for _ in range(50):
        case()
    for _ in range(int(os.environ["BEZJOIN_CG_N"])):
        case()
    sys.stdout.flush()
except BaseException:  # noqa: BLE001 (freecadcmd would swallow it and exit 0)
    import traceback

    traceback.print_exc(file=sys.stdout)
    sys.stdout.flush()
    os._exit(1)
