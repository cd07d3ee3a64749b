"""The study's perceptual difference (`python -m matte_mitsuba.perceptual`, `matte study`'s
HDR-FLIP values) against NVIDIA's reference implementation (`flip_evaluator.evaluate`, called
here independently) on images this test writes, and on the mean images `matte study` writes:
the same numbers to 1e-3. Plus what any difference metric must do (identical images give 0, a
larger change a larger value) and one-line errors for bad input."""

import json
import os
import subprocess
import sys

import flip_evaluator
import mitsuba as mi
import numpy as np
import pytest
from matte_mitsuba import perceptual

MATTE = os.path.join(os.path.dirname(sys.executable), "matte")
TOL = 1e-3

if mi.variant() is None:
    mi.set_variant("scalar_rgb")


def write_exr(path, img):
    mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32)).write(str(path))
    return str(path)


def read_exr(path):
    return np.array(mi.Bitmap(str(path)), dtype=np.float32)[..., :3]


def passes(tmp_path, name, base, k=4, noise=0.1, seed=0):
    """K noisy pass images around `base` (H×W×3), written as EXRs; returns (paths, images)."""
    rng = np.random.default_rng(seed)
    imgs = [np.clip(base * (1 + noise * rng.standard_normal(base.shape)), 0, None).astype(np.float32) for _ in range(k)]
    return [write_exr(tmp_path / f"{name}_{i}.exr", x) for i, x in enumerate(imgs)], imgs


def scene_like(h=48, w=64, seed=1):
    """An HDR image with a bright patch, a gradient and dark corners."""
    y, x = np.mgrid[0:h, 0:w] / max(h, w)
    rng = np.random.default_rng(seed)
    img = np.stack([0.2 + x, 0.1 + y, 0.3 + 0.2 * x * y], axis=-1) * (1 + 0.3 * rng.random((h, w, 1)))
    img[h // 4 : h // 2, w // 4 : w // 2] *= 8.0
    img[: h // 8, : w // 8] *= 0.01
    return img


def reference_flip(reference, test, params=None):
    """flip-evaluator itself: the map and its mean and 95th percentile."""
    m, mean, _ = flip_evaluator.evaluate(
        np.ascontiguousarray(reference, dtype=np.float32),
        np.ascontiguousarray(test, dtype=np.float32),
        "HDR",
        applyMagma=False,
        parameters=params or {},
    )
    return m[..., 0], float(mean), float(np.percentile(m[..., 0], 95))


def mean_of(imgs):
    return np.mean(np.stack([x.astype(np.float64) for x in imgs]), axis=0).astype(np.float32)


def test_values_match_flip_evaluator_on_fixed_images(tmp_path):
    base = scene_like()
    ref_paths, ref_imgs = passes(tmp_path, "lambert", base, seed=1)
    test_paths, test_imgs = passes(tmp_path, "model", base * 0.9, seed=2)
    surf_paths, surf_imgs = passes(tmp_path, "surface", base * 0.95, seed=3)
    job = {
        "groups": [
            {
                "name": "global",
                "exposure": ref_paths,
                "comparisons": [
                    {
                        "name": "model/lambert",
                        "reference": ref_paths,
                        "test": test_paths,
                        "map": str(tmp_path / "m.f32"),
                    },
                    {"name": "model/surface", "reference": surf_paths, "test": test_paths},
                ],
            }
        ]
    }
    (tmp_path / "job.json").write_text(json.dumps(job))
    out = tmp_path / "result.json"
    r = subprocess.run(
        [sys.executable, "-m", "matte_mitsuba.perceptual", str(tmp_path / "job.json"), "--out", str(out)],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    res = json.loads(out.read_text())
    g = res["groups"][0]
    a, b = g["comparisons"]

    # Against Lambert: flip-evaluator's own exposure range from the reference (its default).
    ref_map, ref_mean, ref_p95 = reference_flip(mean_of(ref_imgs), mean_of(test_imgs))
    assert abs(a["mean"] - ref_mean) < TOL and abs(a["p95"] - ref_p95) < TOL, (a, ref_mean, ref_p95)
    assert a["mean"] > 0.01, "a 10 % darker image is a difference"
    written = np.fromfile(tmp_path / "m.f32", dtype="<f4").reshape(ref_map.shape)
    assert np.abs(written - ref_map).max() < TOL
    _, _, params = flip_evaluator.evaluate(
        mean_of(ref_imgs), mean_of(ref_imgs), "HDR", applyMagma=False, computeMeanError=False
    )
    assert abs(g["exposure"]["start"] - params["startExposure"]) < 1e-6
    assert abs(g["exposure"]["stop"] - params["stopExposure"]) < 1e-6
    assert g["exposure"]["count"] == params["numExposures"]
    # Leave-one-out pairs: pass k left out of both images.
    for k in range(4):
        keep = [i for i in range(4) if i != k]
        _, m, p = reference_flip(mean_of([ref_imgs[i] for i in keep]), mean_of([test_imgs[i] for i in keep]))
        assert abs(a["jackknife_mean"][k] - m) < TOL and abs(a["jackknife_p95"][k] - p) < TOL

    # Against the surface: the group's exposure range (Lambert's), not the surface's own.
    same = {k: params[k] for k in ("startExposure", "stopExposure", "numExposures")}
    _, m, p = reference_flip(mean_of(surf_imgs), mean_of(test_imgs), same)
    assert abs(b["mean"] - m) < TOL and abs(b["p95"] - p) < TOL, (b, m, p)


def test_identical_images_give_zero_and_a_larger_change_a_larger_value(tmp_path):
    base = scene_like()
    ref_paths, _ = passes(tmp_path, "a", base, seed=4)
    small, _ = passes(tmp_path, "b", base * 1.02, seed=4)
    large, _ = passes(tmp_path, "c", base * 1.5, seed=4)
    res = perceptual.run(
        {
            "groups": [
                {
                    "name": "g",
                    "exposure": ref_paths,
                    "comparisons": [
                        {"name": "same", "reference": ref_paths, "test": ref_paths},
                        {"name": "small", "reference": ref_paths, "test": small},
                        {"name": "large", "reference": ref_paths, "test": large},
                    ],
                }
            ]
        }
    )
    same, s, lg = res["groups"][0]["comparisons"]
    assert same["mean"] == 0 and same["p95"] == 0 and set(same["jackknife_mean"]) == {0.0}
    assert 0 < s["mean"] < lg["mean"] and s["p95"] < lg["p95"]
    assert 0 <= lg["mean"] <= 1 and lg["p95"] <= 1


def bad_run(tmp_path, job):
    (tmp_path / "job.json").write_text(json.dumps(job) if not isinstance(job, str) else job)
    r = subprocess.run(
        [sys.executable, "-m", "matte_mitsuba.perceptual", str(tmp_path / "job.json"), "--out", str(tmp_path / "r")],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 1, r.stdout + r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("perceptual: "), r.stderr
    return lines[0]


@pytest.mark.parametrize("case", ["missing", "size", "nan", "negative", "black", "malformed", "count"])
def test_bad_input_gives_one_line(tmp_path, case):
    base = scene_like()
    a, _ = passes(tmp_path, "a", base)
    b, _ = passes(tmp_path, "b", base)
    expo = a
    if case == "missing":
        b = [str(tmp_path / "nope.exr")] * 4
    elif case == "size":
        b[2] = write_exr(tmp_path / "small.exr", base[:10, :10])
    elif case == "nan":
        bad = base.copy()
        bad[3, 3, 1] = np.nan
        b[1] = write_exr(tmp_path / "nan.exr", bad)
    elif case == "negative":
        b[0] = write_exr(tmp_path / "neg.exr", base - 10.0)
    elif case == "black":
        expo = [write_exr(tmp_path / "black.exr", np.zeros_like(base))]
    elif case == "count":
        b = b[:3]
    job = {"groups": [{"name": "g", "exposure": expo, "comparisons": [{"name": "x", "reference": a, "test": b}]}]}
    line = bad_run(tmp_path, "{not json" if case == "malformed" else job)
    expected = {
        "missing": "nope.exr",
        "size": "small.exr",
        "nan": "NaN",
        "negative": "negative",
        "black": "black",
        "malformed": "job.json",
        "count": "passes",
    }[case]
    assert expected in line, line


def test_matte_study_reports_flip_evaluators_values_with_noise_floor_and_intervals(tmp_path):
    out = tmp_path / "study"
    r = subprocess.run(
        [MATTE, "study", "cornell", "--res", "40", "--spp", "8", "--passes", "4", "--no-variants", "--no-convergence"]
        + ["-q", "-o", str(out)],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    study = json.loads((out / "study.json").read_text())
    p = study["perceptual"]
    assert p["notes"] == [] and "HDR-FLIP" in p["metric"]
    scene = p["scenes"][0]
    by = {(c["model"], c["reference"], c["lighting"]): c for c in scene["comparisons"]}
    models = [m["key"] for m in study["scenes"][0]["models"]][1:]
    for lighting in ("global", "direct"):
        floor = next(f for f in scene["noise_floor"] if f["lighting"] == lighting)
        assert 0 < floor["mean"] < 1 and floor["mean_ci99"] > 0
        for m in models:
            c = by[(m, "lambert", lighting)]
            assert len(c["jackknife_mean"]) == 4 and c["mean_ci99"] > 0 and c["p95_ci99"] >= 0
            assert c["noise_floor_mean"] == floor["mean"]
        for m, t in [
            ("eon", "truth_v_cavities"),
            ("ginneken", "truth_height_field"),
            ("oren_nayar_full", "truth_v_cavities"),
        ]:
            assert (m, t, lighting) in by
        # The study's mean images, compared by flip-evaluator itself (its exposure range from
        # Lambert's image, as the study states).
        lambert = read_exr(out / "cornell" / f"{lighting}_lambert.exr")
        _, _, params = flip_evaluator.evaluate(lambert, lambert, "HDR", applyMagma=False, computeMeanError=False)
        same = {k: params[k] for k in ("startExposure", "stopExposure", "numExposures")}
        for m, ref in [("eon", "lambert"), ("wolff_physical", "lambert"), ("eon", "truth_v_cavities")]:
            _, mean, p95 = reference_flip(
                read_exr(out / "cornell" / f"{lighting}_{ref}.exr"),
                read_exr(out / "cornell" / f"{lighting}_{m}.exr"),
                same,
            )
            c = by[(m, ref, lighting)]
            assert abs(c["mean"] - mean) < TOL and abs(c["p95"] - p95) < TOL, (m, ref, lighting, c["mean"], mean)
    answers = {(a["model"], a["reference"]): a for a in scene["answers"]}
    assert answers[("eon", "lambert")]["visibility"] in (
        "more visible",
        "less visible",
        "undecided",
        "within the noise",
    )
    assert any("Perceptual question" in a for a in study["answers"])
    html = (out / "report.html").read_text()
    # The report opens with the answer table, with its perceptual columns.
    table = html[html.index("<table") : html.index("</table>")]
    assert table.startswith('<table id="answers">') and "mean FLIP, global" in table and "ΔFLIP" in table
    assert html.index("<table") < html.index("<img")
    assert (
        "HDR-FLIP" in html and "cornell/flip_lambert_global.png" in html and "cornell/flip_surface_direct.png" in html
    )
    for part in html.split('src="')[1:]:
        assert (out / part.split('"')[0]).is_file(), part.split('"')[0]
    assert not (out / "cornell" / "perceptual_work").exists(), "the pass images are removed"
