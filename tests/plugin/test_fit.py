"""`matte fit` end to end (python/matte_mitsuba/fit.py): a 16² plane of known Oren–Nayar
σ = 0.6 under an oblique directional light, seen in perspective (so view and light angles vary
across the image). Starting from σ = 0 (Lambert), the fit must recover σ within 0.05, and
write its outputs. The target is rendered from the truth scene at 256 spp (independent seeds
from the fit's), so the oracle is the known σ, not anything the fit computes. About 15 s.
"""

import json
import os
import subprocess
import sys

import pytest

SCENE = """<scene version="3.0.0">
    <default name="sigma" value="0"/>
    <sensor type="perspective">
        <float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, -2.2, 2.2" target="0, 0, 0" up="0, 0, 1"/></transform>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film>
    </sensor>
    <emitter type="directional">
        <vector name="direction" value="-0.8, -0.9, -0.6"/>
        <rgb name="irradiance" value="3"/>
    </emitter>
    <shape type="rectangle" id="plane">
        <bsdf type="oren_nayar">
            <float name="sigma" value="$sigma"/>
            <rgb name="reflectance" value="0.6"/>
        </bsdf>
    </shape>
</scene>
"""

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


@pytest.fixture
def scenes(tmp_path):
    start = tmp_path / "start.xml"
    truth = tmp_path / "truth.xml"
    start.write_text(SCENE)
    truth.write_text(SCENE.replace('<default name="sigma" value="0"/>', '<default name="sigma" value="0.6"/>'))
    return start, truth


def test_fit_recovers_sigma_from_a_lambert_start(scenes, tmp_path):
    from matte_mitsuba.fit import main

    start, truth = scenes
    out = tmp_path / "out"
    code = main(
        [
            str(start),
            "--target-scene",
            str(truth),
            "--param",
            "plane.bsdf.sigma",
            "--iterations",
            "60",
            "--lr",
            "0.05",
            "--spp",
            "16",
            "--max-depth",
            "2",
            "-o",
            str(out),
            "--quiet",
        ]
    )
    assert code == 0
    result = json.loads((out / "fit.json").read_text())
    sigma = result["fitted"]["plane.bsdf.sigma"]["value"][0]
    print(f"fitted sigma {sigma:.4f} (truth 0.6), loss {result['loss'][0]:.3e} -> {result['loss'][-1]:.3e}")
    assert abs(sigma - 0.6) < 0.05, sigma
    assert result["fitted"]["plane.bsdf.sigma"]["truth"] == [pytest.approx(0.6)]
    assert result["loss"][-1] < 0.2 * result["loss"][0]
    for f in ("index.html", "loss.png", "param_error.png", "render_0.png", "target_0.png"):
        assert (out / f).stat().st_size > 0, f


def test_fit_errors_are_one_line(scenes, tmp_path):
    start, truth = scenes
    run = lambda *a: subprocess.run(
        [sys.executable, "-m", "matte_mitsuba.fit", str(start), *a, "-o", str(tmp_path)], capture_output=True, text=True
    )
    p = run("--target-scene", str(truth), "--param", "plane.bsdf.nope")
    assert p.returncode == 2 and p.stderr.count("\n") == 1, p.stderr
    assert "plane.bsdf.nope" in p.stderr and "plane.bsdf.sigma" in p.stderr, p.stderr
    p = run("--target", str(tmp_path / "missing.exr"), "--param", "plane.bsdf.sigma")
    assert p.returncode == 2 and "missing.exr: no such target image" in p.stderr, p.stderr
    p = run("--target-scene", str(truth), "--param", "plane.bsdf.sigma", "--lr-factor", "plane.bsdf.sigma=-1")
    assert p.returncode == 2 and "--lr-factor plane.bsdf.sigma=-1: must be a positive number" in p.stderr, p.stderr
    p = run("--target-scene", str(truth), "--param", "plane.bsdf.sigma", "--init", "plane.bsdf.sigma=0.1,0.2,0.3")
    assert p.returncode == 2 and "3 values for a parameter of another size" in p.stderr, p.stderr


# Two BSDFs with a parameter of one name, `roughness`: EON's r in [0, 1] as a float, van
# Ginneken's rms slope m in (0, 4] as a texture (its key names the texture's data).
SAME_NAME = """<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <emitter type="constant"/>
    <shape type="rectangle" id="a">
        <transform name="to_world"><translate x="-1"/></transform>
        <bsdf type="eon"><float name="roughness" value="0.5"/></bsdf>
    </shape>
    <shape type="rectangle" id="b">
        <transform name="to_world"><translate x="1"/></transform>
        <bsdf type="ginneken">
            <texture type="checkerboard" name="roughness">
                <float name="color0" value="0.3"/>
                <float name="color1" value="0.6"/>
            </texture>
        </bsdf>
    </shape>
</scene>
"""


def test_fit_clamps_each_parameter_to_its_own_types_bounds(tmp_path):
    """The clamp range of a freed key is its type's `fit` bounds for that parameter as the Rust
    registry declares them (`matte types --json`), not another type's of the same name."""
    from matte_mitsuba.fit import main

    scene = tmp_path / "same_name.xml"
    scene.write_text(SAME_NAME)
    keys = {"eon": "a.bsdf.roughness", "ginneken": "b.bsdf.roughness.color0.value"}
    out = tmp_path / "out"
    args = [str(scene), "--target-scene", str(scene), "--iterations", "1", "--spp", "1", "--target-spp", "1"]
    assert main([*args, *(a for k in keys.values() for a in ("--param", k)), "-o", str(out), "--quiet"]) == 0
    ranges = json.loads((out / "fit.json").read_text())["ranges"]
    matte = os.path.join(os.path.dirname(sys.executable), "matte")
    declared = {
        m["name"]: p["fit"]
        for m in json.loads(subprocess.run([matte, "types", "--json"], capture_output=True, check=True).stdout)
        for p in m["params"]
        if p["name"] == "roughness"
    }
    assert declared["eon"] != declared["ginneken"], declared
    assert {kind: ranges[key] for kind, key in keys.items()} == {kind: declared[kind] for kind in keys}, ranges
