//! Model variants (README "The study", model variants): how the results change with Wolff's normalisation
//! and with the Oren–Nayar model. Each variant is one property in the `$bsdf` element, set
//! through a derived scene ([`super::variant_scene`]) that both renderers load like any
//! scene. The variants that are the plugins' defaults are the main run itself; the others
//! are rendered with the main run's seeds and budget, so their ratio to Lambert is paired
//! with the Lambert passes already rendered.
//!
//! What the variants mean: `docs/models.md#oren-nayar-qualitative`, `#oren-nayar-full` and
//! `#wolff-normalisations` (Wolff's constant K), with matte's choices.

use super::variant_scene::{self, Derivation, Property};
use super::{Lighting, Options, SceneStudy, metrics, strip};
use crate::render::film::Image;
use crate::render::image_io;
use std::path::PathBuf;

/// One variant: a plugin and one property value.
#[derive(Clone, Copy, Debug)]
pub struct Variant {
    /// File-name key, e.g. `wolff_raw`.
    pub key: &'static str,
    pub bsdf: &'static str,
    pub label: &'static str,
    /// Short label for the strips (5×7 font).
    pub tile: &'static str,
    /// The property (name, value) in the `<bsdf>`.
    pub property: (&'static str, &'static str),
    /// The plugin's default: the main run already rendered it.
    pub main: bool,
    /// What it means, for the report.
    pub meaning: &'static str,
}

pub const VARIANTS: [Variant; 5] = [
    Variant {
        key: "wolff_physical",
        bsdf: "wolff",
        label: "Wolff, physical (default)",
        tile: "Wolff phys",
        property: ("normalization", "physical"),
        main: true,
        meaning: "K = ρ / (π n² (1 − ρ F_dr,int)): isotropic radiance inside the body, internally reflected light scattered again (Mitsuba 0.6 plastic's diffuse lobe). ρ is the internal albedo; the albedo at normal incidence is (1 − F(0)) ρ (1 − F_dr,int) / (1 − ρ F_dr,int), below ρ for ρ < 1.",
    },
    Variant {
        key: "wolff_normal",
        bsdf: "wolff",
        label: "Wolff, normal",
        tile: "Wolff normal",
        property: ("normalization", "normal"),
        main: false,
        meaning: "K = ρ / (π (1 − F(0)) (1 − F_dr,ext)): scaled so that the albedo at normal incidence is ρ, as for Lambert (an equal-albedo comparison). Only the angular shape differs from Lambert, which is Fresnel dimming towards grazing.",
    },
    Variant {
        key: "wolff_raw",
        bsdf: "wolff",
        label: "Wolff, raw",
        tile: "Wolff raw",
        property: ("normalization", "raw"),
        main: false,
        meaning: "K = ρ / π: Lambert's constant times the two Fresnel transmissions, with no energy normalisation. The albedo at normal incidence is ρ (1 − F(0)) (1 − F_dr,ext).",
    },
    Variant {
        key: "oren_nayar_qualitative",
        bsdf: "oren_nayar",
        label: "Oren–Nayar, qualitative (default)",
        tile: "O-N qual",
        property: ("model", "qualitative"),
        main: true,
        meaning: "The 1994 qualitative model (ρ/π)(A + B max(0, cos Δφ) sin α tan β), as in the seed paper. It loses energy at normal incidence (E(0) = A) and is retro-reflective.",
    },
    Variant {
        key: "oren_nayar_full",
        bsdf: "oren_nayar",
        label: "Oren–Nayar, full",
        tile: "O-N full",
        property: ("model", "full"),
        main: false,
        meaning: "The full 1994 model: the C1–C3 terms, which darken forward scattering, plus the interreflection term f2 = 0.17 (ρ²/π) σ²/(σ² + 0.13) (1 − cos Δφ (2β/π)²). f2 grows with ρ², so bright surfaces gain the most.",
    },
];

/// One variant in one lighting setting.
pub struct VariantResult {
    pub variant: Variant,
    pub lighting: Lighting,
    /// Image-mean luminance ratio to Lambert (paired passes) and its 99 % half-width.
    pub ratio: (f64, f64),
    /// Per named region: ratio to Lambert and its 99 % half-width.
    pub regions: Vec<(String, f64, f64)>,
    /// Render time; `None` for the main run's images.
    pub seconds: Option<f64>,
    /// Mean image (EXR), relative to the output folder.
    pub exr: PathBuf,
    /// The derived scene, relative to the output folder (`None` for the main run's).
    pub scene_file: Option<PathBuf>,
}

pub struct VariantStudy {
    pub scene_name: String,
    pub results: Vec<VariantResult>,
    /// Image strip and heatmap strip per lighting, relative to the output folder.
    pub strips: Vec<(Lighting, PathBuf, PathBuf, f32)>,
}

impl VariantStudy {
    pub fn result(&self, key: &str, lighting: Lighting) -> Option<&VariantResult> {
        self.results.iter().find(|r| r.variant.key == key && r.lighting == lighting)
    }
}

/// Passes the variants of one scene render (for the progress bar).
pub fn pass_count(passes: u32) -> u64 {
    (VARIANTS.iter().filter(|v| !v.main).count() * 2) as u64 * passes as u64
}

/// Renders the non-default variants of `study`'s scene in both lightings, paired with its
/// Lambert passes, and writes the derived scenes, EXRs and strips.
pub fn run(study: &SceneStudy, opts: &Options, progress: &dyn Fn(&str, u32)) -> Result<VariantStudy, String> {
    let rel_dir = PathBuf::from(&study.name).join("variants");
    let dir = opts.out.join(&rel_dir);
    let regions = super::load_regions(&study.scene)?;
    let mut results = Vec::new();
    let mut strips = Vec::new();
    for lighting in [Lighting::Global, Lighting::Direct] {
        let lambert = study.lambert(lighting).ok_or("the main run has no Lambert passes")?;
        let lambert_img = lambert.moments.mean_image();
        let mut images: Vec<(&str, Image)> = vec![("Lambert", lambert_img.clone())];
        for v in VARIANTS {
            let (ratio, regs, seconds, exr, scene_file, mean) = if v.main {
                let r =
                    study.result(v.bsdf, lighting).ok_or_else(|| format!("the main run has no {} image", v.bsdf))?;
                (r.ratio, r.regions.clone(), None, r.exr.clone(), None, r.mean.clone())
            } else {
                let scene_file = rel_dir.join(format!("{}.xml", v.key));
                let derivation = Derivation {
                    bsdf: Some(v.bsdf.into()),
                    bsdf_properties: vec![Property::string(v.property.0, v.property.1)],
                    ..Default::default()
                };
                variant_scene::write_derived(&study.scene, &opts.out.join(&scene_file), &derivation)?;
                let what = format!("{} {} {}", study.name, lighting.name(), v.label);
                let defines = super::image_defines(opts, v.bsdf, lighting);
                let side = super::render_side(
                    &opts.out.join(&scene_file),
                    opts,
                    defines,
                    &regions,
                    &dir.join("work"),
                    &|k| progress(&what, k),
                )?;
                let regs = regions
                    .iter()
                    .enumerate()
                    .map(|(i, r)| {
                        let (m, hw) =
                            metrics::paired_luminance_ratio(&side.region_pass_means[i], &lambert.region_pass_means[i]);
                        (r.name.clone(), m, hw)
                    })
                    .collect();
                let mean = side.moments.mean_image();
                let exr = rel_dir.join(format!("{}_{}.exr", lighting.name(), v.key));
                image_io::write_exr(&opts.out.join(&exr), &mean)?;
                (
                    metrics::luminance_ratio(&side.moments, &lambert.moments),
                    regs,
                    Some(side.seconds),
                    exr,
                    Some(scene_file),
                    mean,
                )
            };
            images.push((v.tile, mean));
            results.push(VariantResult { variant: v, lighting, ratio, regions: regs, seconds, exr, scene_file });
        }
        let rels: Vec<Vec<f32>> =
            images.iter().map(|(_, m)| metrics::relative_difference(m, &lambert_img, 1e-4)).collect();
        let range = metrics::heatmap_range(&rels[1..]);
        let tiles: Vec<strip::Tile> = images.iter().map(|(l, m)| strip::Tile::from_image(l, m)).collect();
        let diff_tiles: Vec<strip::Tile> = images
            .iter()
            .zip(&rels)
            .map(|((l, m), rel)| strip::Tile::from_difference(l, m.width, m.height, rel, range))
            .collect();
        let strip_path = rel_dir.join(format!("strip_{}.png", lighting.name()));
        let diff_path = rel_dir.join(format!("difference_{}.png", lighting.name()));
        strip::write_strip(&opts.out.join(&strip_path), &tiles)?;
        strip::write_strip(&opts.out.join(&diff_path), &diff_tiles)?;
        strips.push((lighting, strip_path, diff_path, range));
    }
    Ok(VariantStudy { scene_name: study.name.clone(), results, strips })
}
