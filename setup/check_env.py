"""Smoke test of matte's Python side (run with <repo>/.venv/bin/python).

Prints the Mitsuba / Dr.Jit versions and the variants, then renders a small
Cornell box in scalar_rgb and llvm_ad_rgb and prints the mean pixel value and
wall time of each. Exits non-zero on any failure.

Dr.Jit finds libLLVM by itself (it globs /usr/lib/x86_64-linux-gnu/libLLVM*.so.*
and, with libllvm19 installed, picks LLVM 19). To force a library set
DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1 before starting
Python; Dr.Jit 1.5.0 has no Python call to change it afterwards.
"""

import os
import sys
import time

MIN_LLVM = 16  # LLVM 15 (Debian 12's default) makes Dr.Jit 1.5.0 abort while compiling kernels


def render(mi, variant):
    mi.set_variant(variant)
    scene_dict = mi.cornell_box()
    scene_dict["sensor"]["film"]["width"] = 64
    scene_dict["sensor"]["film"]["height"] = 64
    scene_dict["sensor"]["sampler"]["sample_count"] = 16
    t0 = time.perf_counter()
    img = mi.render(mi.load_dict(scene_dict))
    import numpy as np

    arr = np.array(img)
    dt = time.perf_counter() - t0
    if arr.shape != (64, 64, 3) or not np.isfinite(arr).all() or arr.mean() <= 0:
        raise RuntimeError(f"{variant}: bad image, shape {arr.shape}, mean {arr.mean()}")
    print(f"{variant}: mean pixel {arr.mean():.6f}, {dt:.3f} s (64x64, 16 spp)")
    return float(arr.mean())


def main():
    import drjit as dr
    import mitsuba as mi

    print(f"mitsuba {mi.__version__}, drjit {dr.__version__}, python {sys.version.split()[0]}")
    print("variants:", " ".join(mi.variants()))

    means = {"scalar_rgb": render(mi, "scalar_rgb")}

    mi.set_variant("llvm_ad_rgb")
    if not dr.has_backend(dr.JitBackend.LLVM):
        raise RuntimeError(
            "Dr.Jit's LLVM backend is inactive: install libllvm19 (setup/setup_venv.sh) or set DRJIT_LIBLLVM_PATH"
        )
    llvm = dr.detail.llvm_version()
    src = os.environ.get("DRJIT_LIBLLVM_PATH") or "auto-detected"
    print(f"LLVM {'.'.join(map(str, llvm))} ({src})")
    if llvm[0] < MIN_LLVM:
        raise RuntimeError(
            f"LLVM {llvm[0]} is known to abort Dr.Jit {dr.__version__}; set "
            "DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
        )
    means["llvm_ad_rgb"] = render(mi, "llvm_ad_rgb")

    rel = abs(means["llvm_ad_rgb"] - means["scalar_rgb"]) / means["scalar_rgb"]
    print(f"scalar vs llvm mean: relative difference {rel:.4f}")
    if rel > 0.05:
        raise RuntimeError("scalar_rgb and llvm_ad_rgb disagree by more than 5%")
    print("check_env: OK")


if __name__ == "__main__":
    try:
        main()
    except Exception as e:  # noqa: BLE001 - report and fail
        print(f"check_env: FAILED: {type(e).__name__}: {e}", file=sys.stderr)
        sys.exit(1)
