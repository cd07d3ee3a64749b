"""Perceptual side of `matte study`: HDR-FLIP (Andersson et al. 2020, 2021; NVIDIA's
`flip-evaluator` package, the reference implementation) between pairs of rendered images, with
jackknife replicates over the passes. It only measures: which pairs, the intervals and the
verdicts are the Rust study's (`rust/matte/src/study/perceptual.rs`).

    python -m matte_mitsuba.perceptual JOB.json --out RESULT.json

JOB.json names groups of comparisons that share one exposure range:

    {"groups": [{"name": "global",
                 "exposure": ["lambert_0.exr", ...],
                 "comparisons": [{"name": "eon", "reference": ["lambert_0.exr", ...],
                                  "test": ["eon_0.exr", ...], "map": "eon.f32"}]}]}

Each list holds the K pass images (RGB EXR, linear, read with Mitsuba's Bitmap) of one configuration, in seed order. An
image is the mean of its passes. The group's exposure range (HDR-FLIP's start and stop
exposures and their count, ACES tone mapping, 67 pixels per degree) is the one HDR-FLIP
derives from the mean of the `exposure` passes. Every comparison of the group uses that
range, for both of its images and for every replicate. Per comparison the result holds the
mean and the 95th percentile of the per-pixel FLIP map of the two full means. It also holds
the same two numbers for each of the K leave-one-out pairs, where pass k is left out of both
images (the pairs share seeds); the Rust side turns these into jackknife intervals. `map`
receives the full map as float32, row-major (height × width). A bad input gives one line on
stderr and exit status 1.
"""

import argparse
import json
import os
import sys

# flip-evaluator's OpenMP threads cost more than they give on the study's images (a fixed
# start-up per exposure, worst on a busy machine); `matte study` runs one process per lighting.
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

#: Percentile of the per-pixel map reported beside its mean.
PERCENTILE = 95.0


def read_exr(path):
    """An EXR image as float64 H×W×C, read by Mitsuba's Bitmap (flip-evaluator's own loader,
    tinyexr, crashes on some valid files, such as those the Rust `exr` crate writes)."""
    import mitsuba as mi

    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    try:
        bmp = mi.Bitmap(path)
    except Exception as e:  # Mitsuba raises RuntimeError with its own message
        raise ValueError(
            f"{path}: cannot read the image ({str(e).splitlines()[0] if str(e) else type(e).__name__})"
        ) from e
    return np.array(bmp, dtype=np.float64)


def load_passes(paths):
    """The K pass images (float64, H×W×3), checked: same size, finite, nonnegative."""
    if not paths:
        raise ValueError("a comparison needs at least one pass image")
    images = []
    for p in paths:
        img = read_exr(p)
        if img.ndim == 2:
            img = img[..., None]
        if img.ndim != 3 or img.shape[2] < 3:
            raise ValueError(f"{p}: expected an RGB image, got shape {img.shape}")
        img = img[..., :3]
        if images and img.shape != images[0].shape:
            raise ValueError(
                f"{p}: {img.shape[1]}x{img.shape[0]}, the other passes are {images[0].shape[1]}x{images[0].shape[0]}"
            )
        if not np.all(np.isfinite(img)):
            raise ValueError(f"{p}: the image has NaN or infinite values")
        if np.any(img < 0):
            raise ValueError(f"{p}: the image has negative values (HDR-FLIP needs nonnegative radiance)")
        images.append(img)
    return np.stack(images)


def as_image(x):
    return np.ascontiguousarray(x, dtype=np.float32)


def exposure_parameters(reference):
    """HDR-FLIP's exposure range for `reference` (H×W×3): the start and stop exposures and
    their count that flip-evaluator computes from it, with its tone mapper and viewing
    distance. Raises ValueError for a black image (no exposure range)."""
    import flip_evaluator

    if not np.any(reference > 0):
        raise ValueError("the exposure reference is black: HDR-FLIP has no exposure range for it")
    img = as_image(reference)
    _, _, params = flip_evaluator.evaluate(img, img, "HDR", applyMagma=False, computeMeanError=False)
    keep = ("startExposure", "stopExposure", "numExposures", "tonemapper", "ppd")
    out = {k: params[k] for k in keep}
    if not all(np.isfinite(float(out[k])) for k in ("startExposure", "stopExposure", "ppd")):
        raise ValueError(f"HDR-FLIP's exposure range is not finite: {out}")
    return out


def flip_map(reference, test, parameters):
    """The per-pixel HDR-FLIP map (H×W, float32) of `test` against `reference` with the
    given exposure range."""
    import flip_evaluator

    m, _, _ = flip_evaluator.evaluate(
        as_image(reference),
        as_image(test),
        "HDR",
        applyMagma=False,
        computeMeanError=False,
        parameters=dict(parameters),
    )
    return np.asarray(m, dtype=np.float32)[..., 0]


def summary(m):
    """Mean and 95th percentile of a FLIP map."""
    return float(np.mean(m, dtype=np.float64)), float(np.percentile(m, PERCENTILE))


def compare(reference_passes, test_passes, parameters):
    """HDR-FLIP of the mean images, and of each leave-one-out pair (pass k left out of both).
    Returns (result dict, full map)."""
    if reference_passes.shape != test_passes.shape:
        raise ValueError(
            f"the reference has {reference_passes.shape[0]} passes of {reference_passes.shape[2]}x{reference_passes.shape[1]}, "
            f"the test {test_passes.shape[0]} of {test_passes.shape[2]}x{test_passes.shape[1]}"
        )
    k = reference_passes.shape[0]
    ref_sum, test_sum = reference_passes.sum(axis=0), test_passes.sum(axis=0)
    full = flip_map(ref_sum / k, test_sum / k, parameters)
    mean, p95 = summary(full)
    jack_mean, jack_p95 = [], []
    if k >= 2:
        for i in range(k):
            m = flip_map((ref_sum - reference_passes[i]) / (k - 1), (test_sum - test_passes[i]) / (k - 1), parameters)
            a, b = summary(m)
            jack_mean.append(a)
            jack_p95.append(b)
    return {"mean": mean, "p95": p95, "jackknife_mean": jack_mean, "jackknife_p95": jack_p95}, full


def run(job):
    """Evaluates a job (the parsed JOB.json); returns the result document."""
    import flip_evaluator  # noqa: F401  (fails here, with its own message, when missing)

    groups = job.get("groups") if isinstance(job, dict) else None
    if not isinstance(groups, list):
        raise ValueError('the job must be {"groups": [...]}')
    out = [run_group(g) for g in groups]
    return {"metric": "HDR-FLIP", "implementation": "flip-evaluator " + flip_version(), "groups": out}


def run_group(g):
    """One group of the job: its exposure range and its comparisons."""
    if not isinstance(g, dict):
        raise ValueError("each group must be an object")
    name = g.get("name", "?")
    try:
        params = exposure_parameters(load_passes(g["exposure"]).mean(axis=0))
        cache = {}

        def passes(paths, cache=cache):
            key = tuple(paths)
            if key not in cache:
                cache[key] = load_passes(paths)
            return cache[key]

        results = []
        for c in g["comparisons"]:
            r, full = compare(passes(c["reference"]), passes(c["test"]), params)
            if c.get("map"):
                full.astype("<f4").tofile(c["map"])
            results.append({"name": c.get("name", ""), "width": full.shape[1], "height": full.shape[0], **r})
    except KeyError as e:
        raise ValueError(f"group {name}: missing {e}") from e
    except ValueError as e:
        raise ValueError(f"group {name}: {e}") from e
    return {
        "name": name,
        "exposure": {
            "start": float(params["startExposure"]),
            "stop": float(params["stopExposure"]),
            "count": int(params["numExposures"]),
            "tonemapper": str(params["tonemapper"]),
            "pixels_per_degree": float(params["ppd"]),
        },
        "comparisons": results,
    }


def flip_version():
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("flip-evaluator")
    except PackageNotFoundError:
        return "(version unknown)"


def main(argv=None):
    ap = argparse.ArgumentParser(description="HDR-FLIP between rendered images, with jackknife replicates over passes")
    ap.add_argument("job")
    ap.add_argument("--out", required=True)
    a = ap.parse_args(argv)
    try:
        try:
            import flip_evaluator  # noqa: F401
        except ImportError as e:
            raise ValueError(f"flip-evaluator is not installed in {sys.executable} (pip install flip-evaluator)") from e
        try:
            with open(a.job) as f:
                job = json.load(f)
        except (OSError, json.JSONDecodeError) as e:
            raise ValueError(f"{a.job}: {e}") from e
        result = run(job)
        with open(a.out, "w") as f:
            json.dump(result, f)
    except (ValueError, OSError) as e:
        print(f"perceptual: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
