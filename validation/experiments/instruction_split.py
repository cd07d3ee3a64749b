"""Where the instructions of one render go, in matte and in Mitsuba 3.9.1, counted by
callgrind on the scenes of `matte bench` (docs/performance.md: "what bounds the rest").

    .venv/bin/python validation/experiments/instruction_split.py [--jobs bench_out/mitsuba_jobs.json]
        [--res 64] [--spp 16] [--scenes cornell bunny room] [--variants llvm_ad_rgb scalar_rgb]
        [--drivers one-path wavefront]
        [-o bench_out/instructions.json]

The jobs (scene files and parameters) are the ones `matte bench` wrote; `--res` and `--spp`
replace their resolution and sample count, so that a render takes seconds under valgrind.
Each program's instructions are split into Embree's (the same library in both: matte loads
Debian's libembree3, Mitsuba its own build of it) and everything else:
- matte: `matte render --threads 1 --driver D` for each tile driver, counted only inside
  `Integrator::render_tile` (scene loading and BVH building excluded), with the instructions
  of its BSDF calls (`Bsdf::eval_pdf`, `Bsdf::sample` and all they call) as a separate column;
- Mitsuba: a process that loads the scene, renders it once to compile (llvm) and warm up, then
  renders n more times; one render's count is the difference between n = 2 and n = 1, so
  loading, start-up and JIT compilation cancel (a first process, not counted, fills Dr.Jit's
  kernel cache). For `llvm_ad_rgb` the rest is further split into
  the kernels Dr.Jit compiled (code without a file, `???` in callgrind) and the rest.
Counting instructions takes out the shared machine's timing noise; an 8-wide AVX2 instruction
counts once, which is the point: it shows how much of the gap is Embree (the same code per
ray in both) and how much is shading.
Needs valgrind (Debian's `valgrind`; installed here if missing, as setup_venv.sh does).
Prints a Markdown table; writes the numbers as JSON.
"""

import argparse
import json
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LINE = re.compile(r"^\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(.*)$")


def ensure_valgrind():
    if shutil.which("valgrind") and shutil.which("callgrind_annotate"):
        return
    sudo = [] if subprocess.run(["id", "-u"], capture_output=True, text=True).stdout.strip() == "0" else ["sudo"]
    subprocess.run(sudo + ["apt-get", "install", "-y", "-q", "valgrind"], check=True)


def classify(name):
    """Embree, Dr.Jit's compiled kernels (code with no file or object) or the rest."""
    if "embree" in name.lower():
        return "embree"
    if re.search(r"\?\?\?:0x[0-9a-f]+(')?\d* \[\?\?\?\]", name):
        return "jit"
    return "rest"


def annotate(out_file, inclusive):
    """`callgrind_annotate`'s function listing of a callgrind output file."""
    return subprocess.run(
        [
            "callgrind_annotate",
            "--threshold=100",
            f"--inclusive={'yes' if inclusive else 'no'}",
            "--auto=no",
            str(out_file),
        ],
        capture_output=True,
        text=True,
        check=True,
    ).stdout


def listing(text):
    """(instructions, file:function) of each function line of `callgrind_annotate` output."""
    for line in text.split("file:function", 1)[-1].splitlines():
        m = LINE.match(line)
        if m:
            yield int(m.group(1).replace(",", "")), m.group(2)


def split(out_file):
    """Instructions per class in a callgrind output file (self cost of every function)."""
    return split_listing(annotate(out_file, inclusive=False))


def split_listing(text):
    """Instructions per class in `callgrind_annotate --inclusive=no --auto=no` output."""
    totals = {"embree": 0, "jit": 0, "rest": 0}
    for count, name in listing(text):
        totals[classify(name)] += count
    return totals


def bsdf_inclusive(out_file):
    """Instructions spent in matte's BSDF calls (`Bsdf::eval_pdf` and `Bsdf::sample` with
    everything they call): what 8-wide BSDF kernels could shorten."""
    # A function's inclusive total is its largest line (the others are its inlined parts).
    most = {"eval_pdf": 0, "sample": 0}
    for count, name in listing(annotate(out_file, inclusive=True)):
        f = re.search(r":matte_render::bsdf::Bsdf::(eval_pdf|sample)( \[.*\])?$", name)
        if f:
            most[f.group(1)] = max(most[f.group(1)], count)
    return sum(most.values())


def callgrind(cmd, out_file, extra=()):
    subprocess.run(
        ["valgrind", "--tool=callgrind", "--smc-check=all", f"--callgrind-out-file={out_file}", *extra, *cmd],
        check=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.DEVNULL,
    )
    return split(out_file)


def defines(job, res):
    d = dict(job["defines"])
    d["res"] = str(res)
    return d


def matte_split(job, driver, res, spp, work):
    cmd = [
        str(ROOT / "target/release/matte"),
        "render",
        job["scene"],
        "--spp",
        str(spp),
        "--threads",
        "1",
        "-q",
        "--driver",
        driver,
        "-o",
        str(work / "matte.exr"),
    ]
    for k, v in defines(job, res).items():
        cmd += ["-D", f"{k}={v}"]
    counts = callgrind(cmd, work / "cg.matte", ["--collect-atstart=no", "--toggle-collect=*Integrator::render_tile*"])
    return {**counts, "bsdf": bsdf_inclusive(work / "cg.matte")}


def mitsuba_split(job, variant, res, spp, work):
    counts = []
    # n = 0 first, not counted: under valgrind Dr.Jit sees another CPU, so its kernel cache is
    # filled there, and n = 1 and n = 2 both load the kernels from it.
    for n in (0, 1, 2):
        cmd = [
            sys.executable,
            __file__,
            "--child",
            json.dumps({"job": job, "variant": variant, "res": res, "spp": spp, "renders": n}),
        ]
        counts.append(callgrind(cmd, work / f"cg.{variant}.{n}"))
    return {k: counts[2][k] - counts[1][k] for k in counts[0]}


def child(spec):
    """Loads the scene, renders once to warm up, then `renders` more times."""
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(spec["variant"])
    job = spec["job"]
    scene = mi.load_file(job["scene"], **defines(job, spec["res"]))
    for seed in range(1 + spec["renders"]):
        image = mi.render(scene, spp=spec["spp"], seed=seed)
        dr.eval(image)
        dr.sync_thread()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--jobs", default=str(ROOT / "bench_out/mitsuba_jobs.json"))
    ap.add_argument("--res", type=int, default=64)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument(
        "--variants",
        nargs="*",
        default=["llvm_ad_rgb", "scalar_rgb"],
        help="Mitsuba variants to count (none: matte only)",
    )
    ap.add_argument("--drivers", nargs="+", default=["one-path", "wavefront"], help="matte's tile drivers")
    ap.add_argument("--scenes", nargs="*", help="only these jobs (default: all)")
    ap.add_argument("-o", "--output", default=str(ROOT / "bench_out/instructions.json"))
    ap.add_argument("--child", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.child:
        return child(json.loads(a.child))
    jobs_file = Path(a.jobs)
    if not jobs_file.exists():
        sys.exit(f"{jobs_file}: not found; `make bench` (or `matte bench`) writes it")
    jobs = [j for j in json.loads(jobs_file.read_text()) if not a.scenes or j["name"] in a.scenes]
    ensure_valgrind()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for job in jobs:
            for driver in a.drivers:
                print(f"callgrind: {job['name']}: matte --driver {driver}", file=sys.stderr, flush=True)
                rows.append(
                    {
                        "scene": job["name"],
                        "program": f"matte, {driver}",
                        **matte_split(job, driver, a.res, a.spp, work),
                    }
                )
            for variant in a.variants:
                print(f"callgrind: {job['name']}: mitsuba {variant}", file=sys.stderr, flush=True)
                rows.append(
                    {
                        "scene": job["name"],
                        "program": f"mitsuba {variant}",
                        **mitsuba_split(job, variant, a.res, a.spp, work),
                    }
                )
    Path(a.output).parent.mkdir(parents=True, exist_ok=True)
    Path(a.output).write_text(json.dumps({"res": a.res, "spp": a.spp, "rows": rows}, indent=1))
    print(
        f"\n| scene ({a.res}², {a.spp} spp) | program | instructions / render (M) | Embree (M) | "
        f"Dr.Jit kernels (M) | rest (M) | of it in BSDF calls (M) | Embree share | total / Mitsuba llvm's |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        total = r["embree"] + r["jit"] + r["rest"]
        bsdf = f"{r['bsdf'] / 1e6:.0f}" if "bsdf" in r else "–"
        llvm = next((x for x in rows if x["scene"] == r["scene"] and x["program"] == "mitsuba llvm_ad_rgb"), None)
        ratio = f"{total / sum(llvm[k] for k in ('embree', 'jit', 'rest')):.2f}" if llvm else "–"
        print(
            f"| {r['scene']} | {r['program']} | {total / 1e6:.0f} | {r['embree'] / 1e6:.0f} | "
            f"{r['jit'] / 1e6:.0f} | {r['rest'] / 1e6:.0f} | {bsdf} | {r['embree'] / total:.0%} | {ratio} |"
        )


if __name__ == "__main__":
    main()
