"""The ``matte`` command of the wheel: runs the ``matte`` binary shipped in this package."""
import os
import sys


def main():
    binary = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "matte")
    if not os.path.exists(binary):
        sys.exit("matte: the command-line tool is not in this installation (%s); it ships in the matte-mitsuba "
                 "wheel, or run target/release/matte in a checkout" % binary)
    os.execv(binary, [binary] + sys.argv[1:])
