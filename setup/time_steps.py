#!/usr/bin/env python3
"""Where the minutes of `make main` and `make test` go: runs each step of their recipes (as
`make -n` prints them, in a checkout) one after the other, as `make` would, and prints a table
of wall times. Run it in a fresh clone to time what a newcomer waits for:

    git clone <repo> /tmp/fresh && cd /tmp/fresh && python3 setup/time_steps.py [main test]

A step that fails stops it, naming the step (its output is shown)."""

import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def steps(target):
    """The commands `make -n <target>` prints; a sub-make of the recipe is expanded into its own."""
    out = subprocess.run(["make", "-n", "--no-print-directory", target], cwd=ROOT, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"time_steps: make -n {target} failed:\n{out.stderr}")
    lines, joined = [], ""
    for line in out.stdout.splitlines():
        joined += line[:-1] + " " if line.endswith("\\") else line
        if not line.endswith("\\"):
            lines.append(joined.strip())
            joined = ""
    # A sub-make's line (`make … plugin dist`) is followed by the commands it runs: time those.
    return [line for line in lines if line and not line.startswith(("#", "make "))]


def main():
    targets = sys.argv[1:] or ["main", "test"]
    rows, total = [], 0.0
    for target in targets:
        for cmd in steps(target):
            t = time.monotonic()
            r = subprocess.run(["bash", "-c", cmd], cwd=ROOT, capture_output=True, text=True)
            dt = time.monotonic() - t
            total += dt
            label = cmd if len(cmd) < 90 else cmd[:87] + "..."
            rows.append((target, label, dt))
            print(f"{dt:8.1f} s  [{target}] {label}", flush=True)
            if r.returncode != 0:
                print(r.stdout[-3000:], r.stderr[-3000:], sep="\n")
                sys.exit(f"time_steps: [{target}] failed: {cmd}")
    print(f"\n{'step':<100} seconds")
    for target, label, dt in rows:
        print(f"[{target}] {label:<92} {dt:7.1f}")
    for target in targets:
        print(f"make {target}: {sum(dt for t, _, dt in rows if t == target) / 60:.1f} min")
    print(f"all: {total / 60:.1f} min")


if __name__ == "__main__":
    main()
