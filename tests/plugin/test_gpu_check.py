"""`python -m matte_mitsuba.gpu_check` without a GPU: the no-GPU path says so and exits 0, and the dry
run on the CPU (`--device-variant llvm_ad_rgb` against `scalar_rgb`, no timings) runs the mean
and gradient checks and passes."""

import subprocess
import sys


def run(*args):
    return subprocess.run(
        [sys.executable, "-m", "matte_mitsuba.gpu_check", *args], capture_output=True, text=True, timeout=900
    )


def test_without_the_variant_it_says_so_and_exits_0():
    p = run("--device-variant", "cuda_no_such_variant")
    assert p.returncode == 0, p.stderr
    assert "no cuda_no_such_variant variant" in p.stdout and "nothing to check" in p.stdout


def test_dry_run_on_the_cpu_runs_every_check():
    p = run(
        "--device-variant",
        "llvm_ad_rgb",
        "--reference-variant",
        "scalar_rgb",
        "--no-speed",
        "--res",
        "16",
        "--spp",
        "8",
        "--seeds",
        "8",
        "--types",
        "lambert",
        "eon",
    )
    assert p.returncode == 0, p.stdout + p.stderr
    lines = p.stdout.splitlines()
    assert sum("image mean" in line and "ok" in line for line in lines) == 3, p.stdout
    assert sum(line.strip().startswith("gradient") and "ok" in line for line in lines) == 2, p.stdout
    assert lines[-1] == "gpu_check: all checks agree"
