"""The README's examples. The plugin example, as written there: `llvm_ad_rgb` with Dr.Jit's
defaults renders `all_types.xml`, and `dr.backward` through a `prb` render gives every matte
parameter a finite, non-zero gradient. The shell examples that name the checkout's files run
verbatim (the mitsuba tool, `matte validate`, `matte render`)."""
import os
import re
import subprocess

import numpy as np
import pytest

from conftest import REPO


def test_readme_example(monkeypatch):
    monkeypatch.chdir(REPO)
    import drjit as dr
    import mitsuba as mi
    mi.set_variant('llvm_ad_rgb')            # Dr.Jit's defaults: symbolic loops and calls
    import matte_mitsuba                     # noqa: F401  registers matte's BSDFs in every variant
    assert dr.flag(dr.JitFlag.SymbolicLoops) and dr.flag(dr.JitFlag.SymbolicCalls)

    scene = mi.load_file('mitsuba_scenes/all_types.xml', res=32, spp=4)
    image = mi.render(scene)
    assert np.isfinite(np.array(image)).all()

    params = mi.traverse(scene)
    keys = [k for k in params.keys() if k.endswith(('.sigma', '.roughness', '.alpha', '.int_ior', '.ext_ior', 'reflectance.value'))]
    for k in keys:
        dr.enable_grad(params[k])
    params.update()
    image = mi.render(scene, params, integrator=mi.load_dict({'type': 'prb'}), spp=16)
    dr.backward(dr.mean(image, axis=None))
    # every matte parameter of the scene: 11 reflectances, 2 sigma, 4 roughness, 1 alpha, 2×2 IORs
    assert len(keys) == 22, keys
    for k in keys:
        g = np.array(dr.grad(params[k]))
        assert np.isfinite(g).all() and np.any(g != 0), (k, g)
    assert os.path.exists(os.path.join(REPO, 'mitsuba_scenes', 'all_types.xml'))


# The README's shell examples that name files of the checkout, verbatim, run in a scratch folder
# that links the checkout's .venv, target, mitsuba_scenes and validation (the scenes' tables), so
# that outputs land there.
SHELL_EXAMPLES = [
    ('.venv/bin/mitsuba -a "$(.venv/bin/python -m matte_mitsuba)" -o all_types.exr mitsuba_scenes/all_types.xml',
     ["all_types.exr"]),
    ("./target/release/matte validate mitsuba_scenes/cornell_box.xml --quick --variant scalar_rgb",
     ["validate_out/report.html"]),
    ("./target/release/matte render mitsuba_scenes/cornell_box.xml -o cornell.exr --png",
     ["cornell.exr", "cornell.png"]),
]


def readme_shell_lines():
    text = open(os.path.join(REPO, "README.md")).read()
    blocks = re.findall(r"```sh\n(.*?)```", text, re.S)
    return [line.split("  #")[0].strip() for b in blocks for line in b.splitlines()]


@pytest.mark.parametrize("command,outputs", SHELL_EXAMPLES, ids=["mitsuba tool", "matte validate", "matte render"])
def test_readme_shell_example(tmp_path, command, outputs):
    assert command in readme_shell_lines(), f"not in the README any more: {command}"
    for name in (".venv", "target", "mitsuba_scenes", "validation"):
        (tmp_path / name).symlink_to(os.path.join(REPO, name))
    r = subprocess.run(["bash", "-c", command], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    for out in outputs:
        assert (tmp_path / out).is_file() and (tmp_path / out).stat().st_size > 0, out
