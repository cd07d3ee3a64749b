#!/usr/bin/env python3
"""The README's picture: one rough sphere per model, side by side, rendered by `matte render`
under the same light, with the models' names and parameters written below.

    .venv/bin/python validation/generators/models_strip.py [--out docs/models_strip.png] [--spp 256]

Each panel is the same scene: a sphere of reflectance 0.8 on a grey ground, lit by a small
area light above and to the right of the camera and a dim environment, path traced: the rough
models flatten the shading towards the light (the "full moon" look Oren and Nayar describe),
Wolff's Fresnel factors darken the limb.
Needs the release `matte` binary (`make main` or `cargo build --release`) and matplotlib (the
venv's).
"""

import argparse
import os
import subprocess
import sys
import tempfile

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MATTE = os.path.join(REPO, "target", "release", "matte")

# (label, <bsdf> element)
MODELS = [
    ("lambert", '<bsdf type="lambert">{rho}</bsdf>'),
    ("oren_nayar σ=0.6", '<bsdf type="oren_nayar">{rho}<float name="sigma" value="0.6"/></bsdf>'),
    (
        "oren_nayar full σ=0.6",
        '<bsdf type="oren_nayar">{rho}<float name="sigma" value="0.6"/><string name="model" value="full"/></bsdf>',
    ),
    ("eon r=1", '<bsdf type="eon">{rho}<float name="roughness" value="1"/></bsdf>'),
    ("ginneken m=0.6", '<bsdf type="ginneken">{rho}<float name="roughness" value="0.6"/></bsdf>'),
    ("wolff n=1.5", '<bsdf type="wolff">{rho}<float name="int_ior" value="1.5"/></bsdf>'),
]

SCENE = """<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="6"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="26"/>
        <transform name="to_world"><lookat origin="0, 0.9, 4.2" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>
        <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/>
            <rfilter type="gaussian"/></film>
    </sensor>
    <shape type="sphere">
        <point name="center" x="0" y="0.5" z="0"/><float name="radius" value="0.5"/>
        {bsdf}
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="4"/><rotate x="1" angle="-90"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.35"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><scale value="0.25"/><lookat origin="2.2, 1.6, 3.4" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <emitter type="area"><rgb name="radiance" value="60"/></emitter>
    </shape>
    <emitter type="constant"><rgb name="radiance" value="0.02"/></emitter>
</scene>
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(REPO, "docs", "models_strip.png"))
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--res", type=int, default=192)
    a = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    panels = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, (label, bsdf) in enumerate(MODELS):
            xml = os.path.join(tmp, f"m{i}.xml")
            with open(xml, "w") as f:
                f.write(
                    SCENE.format(spp=a.spp, res=a.res, bsdf=bsdf.format(rho='<rgb name="reflectance" value="0.8"/>'))
                )
            exr = os.path.join(tmp, f"m{i}.exr")
            subprocess.run([MATTE, "render", xml, "-o", exr, "--png", "-q"], check=True, stdout=subprocess.DEVNULL)
            panels.append((label, mpimg.imread(exr[:-4] + ".png")))
    fig, axes = plt.subplots(1, len(panels), figsize=(2.0 * len(panels), 2.35), dpi=100)
    for ax, (label, img) in zip(axes, panels):
        ax.imshow(img)
        ax.set_axis_off()
        ax.set_title(label, fontsize=9, y=-0.13)
    fig.subplots_adjust(left=0.005, right=0.995, top=0.99, bottom=0.1, wspace=0.03)
    fig.savefig(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    sys.exit(main())
