"""The ``matte`` command of the wheel: runs the ``matte`` binary shipped in this package, telling
it this Python (``MATTE_LAUNCHER_PYTHON``), which then runs the Mitsuba side of its commands
unless ``--python`` or ``MATTE_PYTHON`` names another; ``matte fit`` runs
:mod:`matte_mitsuba.fit` in this Python directly (the binary's own ``fit`` forwards to ``python
-m matte_mitsuba.fit`` as well)."""

import os
import sys


def main():
    if sys.argv[1:2] == ["fit"]:
        from .fit import main as fit_main

        sys.exit(fit_main(sys.argv[2:]))
    binary = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "matte")
    if not os.path.exists(binary):
        sys.exit(
            "matte: the command-line tool is not in this installation (%s); it ships in the matte-mitsuba "
            "wheel, or run target/release/matte in a checkout" % binary
        )
    os.environ["MATTE_LAUNCHER_PYTHON"] = sys.executable
    os.execv(binary, [binary] + sys.argv[1:])
