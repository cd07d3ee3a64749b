#!/usr/bin/env python3
"""Mitsuba's own verdict on the harvested property list (validation/generators/harvest_mitsuba_properties.py).

    MATTE_DUMP_WALK=/tmp/walk cargo test -p matte-render --test render every_harvested
    .venv/bin/python validation/check_harvest.py /tmp/walk

The walk test of tests/render/load/walk.rs builds, for every property Mitsuba 3.9.1 reads in every
plugin matte renders, a small scene holding that property; with MATTE_DUMP_WALK it writes
them out. This script loads each in Mitsuba (scalar_rgb) and reports the scenes Mitsuba
refuses, with its reason: a property harvested wrongly, or one Mitsuba reads only in a branch
the scene does not take. Exit status 1 if any is refused for an unreferenced property.
"""

import os
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)


def main():
    d = sys.argv[1]
    files = sorted(f for f in os.listdir(d) if f.endswith(".xml"))
    unreferenced, other = [], []
    for f in files:
        try:
            mi.load_file(os.path.join(d, f))
        except Exception as e:  # noqa: BLE001 - Mitsuba raises RuntimeError and others
            msg = " ".join(str(e).split())
            (unreferenced if "unreferenced propert" in msg else other).append((f, msg[:300]))
    print(
        f"{len(files)} scenes: Mitsuba loads {len(files) - len(unreferenced) - len(other)}, "
        f"refuses {len(unreferenced)} for an unreferenced property, {len(other)} for another reason"
    )
    for f, m in unreferenced + other:
        print(f"  {f}: {m}")
    return 1 if unreferenced else 0


if __name__ == "__main__":
    sys.exit(main())
