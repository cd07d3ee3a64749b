"""The README's examples. The plugin example, as written there: `llvm_ad_rgb` with Dr.Jit's
defaults renders the bundled `all_types.xml`, its filter of the traversed keys finds every
matte parameter of the scene (per BSDF its reflectance and its type's numeric parameters in
the registry), and `dr.backward` through a `prb` render gives each a finite, non-zero
gradient. The shell examples run verbatim as a user of the installed package would, outside the
checkout, with the environment's `bin/` on `PATH` (the mitsuba tool, `matte validate`, `matte
render`) on a small scene of the user's."""

import os
import re
import subprocess
import sys
from xml.etree import ElementTree

import numpy as np
import pytest
from conftest import REPO
from matte_mitsuba import registry


def scene_parameters(path):
    """The traversal keys of the differentiable matte parameters of the scene file `path`: per
    `<bsdf type id>`, its `reflectance.value` and its type's numeric parameters."""
    keys = []
    for bsdf in ElementTree.parse(path).iter("bsdf"):
        keys.append(bsdf.get("id") + ".reflectance.value")
        keys += [bsdf.get("id") + "." + p["name"] for p in registry.numeric_parameters(bsdf.get("type"))]
    return keys


def test_readme_example(monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    import drjit as dr
    import mitsuba as mi

    mi.set_variant("llvm_ad_rgb")  # Dr.Jit's defaults: symbolic loops and calls
    import matte_mitsuba  # noqa: F401  registers matte's BSDFs in every variant

    assert dr.flag(dr.JitFlag.SymbolicLoops) and dr.flag(dr.JitFlag.SymbolicCalls)

    scene = mi.load_file(os.path.join(matte_mitsuba.SCENES, "all_types.xml"), res=32, spp=4)
    image = mi.render(scene)
    assert np.isfinite(np.array(image)).all()

    params = mi.traverse(scene)
    numeric = {p["name"] for m in registry.MODELS for p in registry.numeric_parameters(m)}
    keys = [k for k in params.keys() if k.endswith(".reflectance.value") or k.rsplit(".", 1)[-1] in numeric]
    for k in keys:
        dr.enable_grad(params[k])
    params.update()
    image = mi.render(scene, params, integrator=mi.load_dict({"type": "prb"}), spp=16)
    dr.backward(dr.mean(image, axis=None))
    # The example's filter finds every matte parameter of the scene: each BSDF's reflectance and
    # the numeric parameters the registry declares for its type (the scene's own elements).
    assert sorted(keys) == sorted(scene_parameters(os.path.join(matte_mitsuba.SCENES, "all_types.xml"))), keys
    for k in keys:
        g = np.array(dr.grad(params[k]))
        assert np.isfinite(g).all() and np.any(g != 0), (k, g)
    assert matte_mitsuba.SCENES.startswith(sys.prefix), matte_mitsuba.SCENES  # the installed package's


# The README's shell examples, verbatim, run in a scratch folder with the environment's `bin/`
# first on PATH (an activated virtual environment) and a small scene of the user's, copied
# from the bundled Cornell box at 24² pixels.
SHELL_EXAMPLES = [
    ('mitsuba -a "$(python -m matte_mitsuba)" scene.xml', ["scene.exr"]),
    ("matte validate my_scene.xml", ["validate_out/report.html", "validate_out/summary.json"]),
    ("matte render my_scene.xml -o my_scene.exr --png", ["my_scene.exr", "my_scene.png"]),
]


def readme_shell_lines():
    text = open(os.path.join(REPO, "README.md")).read()
    blocks = re.findall(r"```sh\n(.*?)```", text, re.S)
    return [line.split("  #")[0].strip() for b in blocks for line in b.splitlines()]


@pytest.mark.parametrize("command,outputs", SHELL_EXAMPLES, ids=["mitsuba tool", "matte validate", "matte render"])
def test_readme_shell_example(tmp_path, command, outputs):
    assert command in readme_shell_lines(), f"not in the README any more: {command}"
    import matte_mitsuba

    cornell = open(os.path.join(matte_mitsuba.SCENES, "cornell_box.xml")).read()
    small = re.sub(r'<default name="res" value="\d+"/>', '<default name="res" value="24"/>', cornell)
    small = re.sub(r'<default name="spp" value="\d+"/>', '<default name="spp" value="4"/>', small)
    assert small != cornell
    for name in ("scene.xml", "my_scene.xml"):
        (tmp_path / name).write_text(small)
    env = {k: v for k, v in os.environ.items() if not k.startswith("MATTE")}
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env["PATH"]
    r = subprocess.run(["bash", "-c", command], cwd=tmp_path, capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    for out in outputs:
        assert (tmp_path / out).is_file() and (tmp_path / out).stat().st_size > 0, out
