"""Checks an installed matte-mitsuba wheel the way a Mitsuba user would use it, outside the
checkout (run it with the Python of the environment the wheel is installed in, from any
folder): `wolff` and `roughdiffuse` render in llvm_ad_rgb with Dr.Jit's defaults and in
scalar_rgb; `roughdiffuse` with alpha = a evaluates as `oren_nayar` with sigma = a/√2, full
model; `mitsuba -a "$(python -m matte_mitsuba)" scene.xml` renders with the tool's defaults;
`matte brdf --bsdf roughdiffuse` answers; every packaged ground-truth table loads as a
`tabulated_brdf` (`matte_mitsuba.ground_truth_path`) and evaluates to a positive value. Prints one line per check; exits non-zero on failure.

    python tests/plugin/wheel_checks.py
"""

import json
import math
import os
import random
import subprocess
import sys
import tempfile

SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/></film>
    </sensor>
    <shape type="sphere">
        <transform name="to_world"><translate x="-0.6"/><scale value="0.5"/></transform>
        <bsdf type="wolff"><float name="int_ior" value="1.5"/></bsdf>
    </shape>
    <shape type="sphere">
        <transform name="to_world"><translate x="0.6"/><scale value="0.5"/></transform>
        <bsdf type="roughdiffuse"><float name="alpha" value="0.5"/></bsdf>
    </shape>
    <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
</scene>
"""


def check(what, ok, detail=""):
    print(("ok    " if ok else "FAIL  ") + what + (f" ({detail})" if detail else ""), flush=True)
    if not ok:
        sys.exit(1)


def main():
    work = tempfile.mkdtemp(prefix="matte-wheel-")
    os.chdir(work)  # nothing from a checkout
    scene_file = os.path.join(work, "scene.xml")
    with open(scene_file, "w") as f:
        f.write(SCENE)
    import drjit as dr
    import matte_mitsuba
    import mitsuba as mi

    check(
        "matte_mitsuba imported from the installation",
        "site-packages" in matte_mitsuba.PLUGIN_ROOT,
        matte_mitsuba.PLUGIN_ROOT,
    )
    for variant in ("llvm_ad_rgb", "scalar_rgb"):
        mi.set_variant(variant)
        img = mi.render(mi.load_file(scene_file)).array  # no numpy in a bare Mitsuba environment
        mean = dr.mean(img, axis=None)
        mean = float(mean[0] if dr.is_jit_v(mean) else mean)
        finite = bool(dr.all(dr.isfinite(img)))
        check(f"{variant}: wolff and roughdiffuse render", finite and mean > 0.05, f"mean {mean:.4f}")
    mi.set_variant("llvm_ad_rgb")
    check("llvm_ad_rgb ran in symbolic mode", dr.flag(dr.JitFlag.SymbolicLoops) and dr.flag(dr.JitFlag.SymbolicCalls))
    a = 0.5
    rd = mi.load_dict({"type": "roughdiffuse", "alpha": a})
    on = mi.load_dict({"type": "oren_nayar", "sigma": a / math.sqrt(2), "model": "full"})
    rng = random.Random(1)
    n = 10000

    def dirs():
        z = [rng.uniform(0.01, 1) for _ in range(n)]
        p = [rng.uniform(0, 2 * math.pi) for _ in range(n)]
        r = [math.sqrt(1 - c * c) for c in z]
        return mi.Vector3f([r[k] * math.cos(p[k]) for k in range(n)], [r[k] * math.sin(p[k]) for k in range(n)], z)

    si = dr.zeros(mi.SurfaceInteraction3f, n)
    si.wi = dirs()
    wo = dirs()
    x, y = rd.eval(mi.BSDFContext(), si, wo), on.eval(mi.BSDFContext(), si, wo)
    err = dr.max(dr.abs(x - y) / dr.maximum(dr.abs(y), 1e-6), axis=None)
    err = float(err[0] if dr.is_jit_v(err) else err)
    check(
        "roughdiffuse alpha=0.5 evaluates as oren_nayar sigma=0.5/sqrt(2), model=full",
        err <= 2e-6,
        f"max relative difference {err:.1e}",
    )
    root = subprocess.run(
        [sys.executable, "-m", "matte_mitsuba"], capture_output=True, text=True, check=True
    ).stdout.strip()
    tool = os.path.join(os.path.dirname(sys.executable), "mitsuba")
    out = os.path.join(work, "cli.exr")
    run = subprocess.run([tool, "-a", root, "-o", out, scene_file], capture_output=True, text=True)
    check(
        'mitsuba -a "$(python -m matte_mitsuba)" scene.xml (the tool\'s defaults)',
        run.returncode == 0 and os.path.exists(out),
        (run.stdout + run.stderr).strip().splitlines()[-1] if run.returncode else out,
    )
    matte = os.path.join(os.path.dirname(sys.executable), "matte")
    run = subprocess.run(
        [
            matte,
            "brdf",
            "--bsdf",
            "roughdiffuse",
            "--param",
            "alpha=0.5",
            "--reflectance",
            "0.8",
            "--theta-i",
            "60",
            "--theta-o",
            "60",
            "--phi",
            "180",
        ],
        capture_output=True,
        text=True,
    )
    ok = run.returncode == 0 and json.loads(run.stdout)["bsdf"] == "roughdiffuse"
    check("matte brdf --bsdf roughdiffuse answers", ok, run.stdout.strip() if ok else run.stderr.strip())
    mi.set_variant("scalar_rgb")
    names = sorted(f[:-5] for f in os.listdir(matte_mitsuba.GROUND_TRUTH) if f.endswith(".json"))
    si = dr.zeros(mi.SurfaceInteraction3f)
    si.wi = mi.Vector3f(0.5, 0, 0.75**0.5)
    values = [
        mi.load_dict(
            {"type": "tabulated_brdf", "filename": matte_mitsuba.ground_truth_path(n), "reflectance": 0.8}
        ).eval(mi.BSDFContext(), si, mi.Vector3f(-0.5, 0, 0.75**0.5))[0]
        for n in names
    ]
    check(
        f"the {len(names)} packaged ground-truth tables load as tabulated_brdf",
        len(names) == 12 and all(math.isfinite(v) and v > 0 for v in values),
        ", ".join(names),
    )


if __name__ == "__main__":
    main()
