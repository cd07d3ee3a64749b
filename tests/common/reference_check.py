"""What the reference generators beside the tests share (`tests/*/*/generate_reference.py`):
`check` prints the oracle's value beside what the test holds and records a mismatch;
`finish` prints the count and exits 1 if there was any."""

import sys

import numpy as np

FAILED = []


def check(label, got, want, tol=0.0, precision=7, threshold=1000):
    """`got` (the oracle's) against `want` (the test's) within `tol`, elementwise."""
    got, want = np.asarray(got, dtype=np.float64), np.asarray(want, dtype=np.float64)
    ok = got.shape == want.shape and bool(np.all(np.abs(got - want) <= tol))
    if not ok:
        FAILED.append(label)
    shown = np.array2string(
        got.ravel() if got.ndim > 1 else got,
        precision=precision,
        separator=", ",
        max_line_width=10**6,
        threshold=threshold,
    )
    print(
        f"{'OK      ' if ok else 'MISMATCH'} {label}: Mitsuba {shown}" + ("" if ok else f", test holds {want.tolist()}")
    )


def check_true(label, ok, shown=""):
    """A yes/no fact about the oracle."""
    if not ok:
        FAILED.append(label)
    print(f"{'OK      ' if ok else 'MISMATCH'} {label}" + (f": {shown}" if shown else ""))


def finish():
    print(f"{len(FAILED)} mismatches")
    sys.exit(1 if FAILED else 0)
