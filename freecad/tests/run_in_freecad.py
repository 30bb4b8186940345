"""Run the FreeCAD-side tests under ``freecadcmd`` and report the outcome reliably.

freecadcmd prints an uncaught exception and still exits with 0, so this
script catches everything itself, exits non-zero on any failure, and writes
``OK <tests run>`` to the marker file named by ``BEZJOIN_FREECAD_MARKER`` only
when every test passed (the shell side checks both).

    BEZJOIN_FREECAD_MARKER=/tmp/marker freecadcmd freecad/tests/run_in_freecad.py
"""

import os
import sys
import traceback
import unittest

TESTS = os.path.dirname(os.path.abspath(__file__))
REPOSITORY = os.path.dirname(os.path.dirname(TESTS))
for folder in (TESTS, os.path.join(REPOSITORY, "freecad", "Bezjoin"),
               os.path.join(REPOSITORY, "bindings", "python")):
    if folder not in sys.path:
        sys.path.insert(0, folder)


def run():
    """Discover and run ``test_*.py`` here; return (tests run, success)."""
    suite = unittest.defaultTestLoader.discover(TESTS, pattern="test_*.py", top_level_dir=TESTS)
    result = unittest.TextTestRunner(stream=sys.stdout, verbosity=2).run(suite)
    return result.testsRun, result.wasSuccessful()


def main():
    marker = os.environ.get("BEZJOIN_FREECAD_MARKER", "")
    if marker and os.path.exists(marker):
        os.remove(marker)
    try:
        count, success = run()
    except BaseException:  # noqa: BLE001 (freecadcmd would swallow it)
        traceback.print_exc(file=sys.stdout)
        count, success = 0, False
    success = success and count > 0
    print(f"bezjoin FreeCAD tests: {count} run, {'OK' if success else 'FAILED'}")
    sys.stdout.flush()
    if success and marker:
        with open(marker, "w", encoding="utf-8") as handle:
            handle.write(f"OK {count}\n")
    sys.exit(0 if success else 1)


main()
