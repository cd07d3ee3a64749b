//! Helpers shared by the integration tests above the kernels: those of the kernel tests
//! ([`kernels`]: PCG32 draws, the model catalogue, the chi-square test), the chi-square test
//! of a renderer BSDF, and the pieces of the scene-file tests (a small scene around a body,
//! `file:line` error checks, EXR textures).
#![allow(dead_code)]
// `!(x > 0.0)` is meant: it also rejects NaN, which `x <= 0.0` would let through.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod kernels;

pub use kernels::*;

use glam::Vec3;
use matte_render::bsdf::Bxdf;
use matte_render::shape::SurfaceInteraction;
use matte_scene_file::SceneError;
use std::path::Path;

/// [`chi2_sampling_ires`] for a renderer BSDF at the hit `si` and incidence `wi` (shading
/// frame). The lobe choice comes from its own generator (`Pcg32::new(seed, 3)`); Dirac samples
/// count as no sample (their mass is exactly what the smooth pdf misses). The shading normal
/// is rotated onto the test's +y axis: the (φ, cos θ) grid has the plane φ ∈ {0, ±π} on cell
/// boundaries but the plane z = 0 mid-row, and its trapezoid rule per cell cannot integrate
/// the pdf's jump to 0 at the horizon there (densities are invariant under the rotation).
#[allow(dead_code)]
pub fn chi2_render_bsdf<B: Bxdf>(
    bsdf: &B,
    si: &SurfaceInteraction,
    wi: Vec3,
    seed: u64,
    ires: usize,
) -> Result<Chi2Outcome, String> {
    // Test frame → shading frame (rotation by −90° about x: test +y ↦ shading +z), and back.
    let to_shading = |h: Vec3| Vec3::new(h.x, -h.z, h.y);
    let to_test = |l: Vec3| Vec3::new(l.x, l.z, -l.y);
    let mut lobe = Pcg32::new(seed, 3);
    let sample = |u| {
        let s = bsdf.sample(si, wi, lobe.next_f32(), u)?;
        (!s.delta).then(|| (to_test(s.wo), s.weight.element_sum()))
    };
    chi2_test(sample, |wo| bsdf.eval_pdf(si, wi, to_shading(wo)).1, seed, ires)
}

// ------------------------------------------------------------------------------------------
// Scene files

/// A 4×2 film, so that tests that do not care about the camera stay tiny.
pub const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#;

/// `<scene>` on line 1, `body` from line 2 on.
pub fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

/// The error is one line, starts with `file:line:` and contains `needle`.
pub fn assert_error_at(e: &SceneError, file: &Path, line: u32, needle: &str) {
    let text = e.to_string();
    assert!(!text.contains('\n'), "multi-line error: {text}");
    let prefix = format!("{}:{line}", file.display());
    assert!(text.starts_with(&format!("{prefix}:")), "expected {prefix} in: {text}");
    assert!(text.contains(needle), "expected {needle:?} in: {text}");
}

/// [`assert_error_at`] for a result that must be an error.
pub fn assert_err_at<T>(r: Result<T, SceneError>, file: &Path, line: u32, needle: &str) {
    let Err(e) = r else { panic!("expected an error containing {needle:?}") };
    assert_error_at(&e, file, line, needle);
}

/// Every registered model in one scene, from the registry: a sphere per configuration, each
/// model at its defaults and at each example it declares, a file parameter given the packaged
/// V-cavity table (`ground_truth/…`, found through a `<path>` to `python/matte_mitsuba`), in
/// rows in front of a white wall above a white floor, lit by an area light and a dim
/// environment; `$res`, `$spp`. (The wheel's `all_types.xml` is the same idea in Mitsuba's
/// Cornell box, written from the registry when the package is built:
/// `python/matte_mitsuba/all_types_scene.py`.)
pub fn all_types_scene() -> String {
    use matte_brdf::registry::ParamKind;
    const COLOURS: [&str; 5] = ["0.8, 0.8, 0.5", "0.2, 0.5, 0.8", "0.8, 0.6, 0.3", "0.5, 0.8, 0.7", "0.6, 0.6, 0.8"];
    const COLUMNS: usize = 6;
    let mut configurations: Vec<(&str, Vec<(&str, &str)>)> = Vec::new();
    for spec in matte_brdf::MODELS {
        let files = spec.params.iter().filter(|p| p.kind == ParamKind::File);
        configurations.push((spec.name, files.map(|p| (p.name, "ground_truth/v_cavities_sigma0.3.json")).collect()));
        configurations.extend(spec.examples.iter().map(|e| (spec.name, e.to_vec())));
    }
    let mut body = String::new();
    for (i, (kind, params)) in configurations.iter().enumerate() {
        let spec = matte_brdf::spec(kind).expect("a registered model");
        let mut bsdf =
            format!(r#"<bsdf type="{kind}"><rgb name="reflectance" value="{}"/>"#, COLOURS[i % COLOURS.len()]);
        for (name, value) in params {
            let p = spec.param(name).expect("a declared parameter");
            let tag = match p.kind {
                ParamKind::Flag { .. } => "boolean",
                _ if p.is_numeric() && value.parse::<f64>().is_ok() => "float",
                _ => "string",
            };
            bsdf += &format!(r#"<{tag} name="{name}" value="{value}"/>"#);
        }
        let (x, y) = (-0.75 + 0.3 * (i % COLUMNS) as f64, -0.75 + 0.3 * (i / COLUMNS) as f64);
        body += &format!(
            "    <shape type=\"sphere\"><point name=\"center\" x=\"{x}\" y=\"{y}\" z=\"0.3\"/><float name=\"radius\" value=\"0.12\"/>{bsdf}</bsdf></shape>\n"
        );
    }
    format!(
        r#"<scene version="3.0.0">
    <default name="spp" value="64"/>
    <default name="res" value="128"/>
    <path value="{package}"/>
    <integrator type="path"><integer name="max_depth" value="8"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="39.3077"/>
        <transform name="to_world"><lookat origin="0, 0, 3.9" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/><rfilter type="box"/></film>
    </sensor>
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><translate y="-1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><translate z="-1"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.885809, 0.698859, 0.666422"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale x="0.5" y="0.5"/><rotate x="1" angle="90"/><translate y="1.2" z="1"/></transform>
        <emitter type="area"><rgb name="radiance" value="18.387, 13.9873, 6.75357"/></emitter></shape>
    <emitter type="constant"><rgb name="radiance" value="0.05"/></emitter>
{body}</scene>
"#,
        package = repo().join("python/matte_mitsuba").display()
    )
}

/// Writes a W×H EXR whose texel (i, j) is `f(i, j)`.
pub fn write_exr(path: &Path, w: u32, h: u32, f: impl Fn(u32, u32) -> Vec3) {
    let mut img = matte_render::film::Image::new(w, h);
    for j in 0..h {
        for i in 0..w {
            img.set(i, j, f(i, j));
        }
    }
    matte_render::image_io::write_exr(path, &img).unwrap();
}

/// Environment variables for a `matte` run whose Python side is the checkout's source package
/// (`python/matte_mitsuba`, which holds the ground-truth tables), found through the documented
/// rule (`MATTE_PYTHON`): the machine's `python3` (on Windows `python`) with `python/` on its
/// path. That Python has no Mitsuba, so the commands run matte's side only and say that Mitsuba
/// was not run.
pub fn source_package_env() -> [(&'static str, String); 2] {
    let python = if cfg!(windows) { "python" } else { "python3" };
    [("MATTE_PYTHON", python.into()), ("PYTHONPATH", repo().join("python").display().to_string())]
}
