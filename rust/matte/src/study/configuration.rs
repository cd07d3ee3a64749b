//! Every model configuration the study renders, in one table: the plugin, the one property
//! that distinguishes a variant, and the names the report, the strips and study.json use.
//! The main run ([`main_run`]: the paper's models, then every other registered model marked
//! `in_study`), the model variants ([`VARIANTS`]) and the convergence series ([`SERIES`]) are
//! lists of these configurations. The true surfaces ([`TRUTHS`]: the simulated microsurfaces
//! as `tabulated_brdf` tables, `docs/microgeometry.md`) are configurations too, rendered
//! beside the main run; [`Configuration::true_surface`] names each model's own.
//!
//! What the variants mean: `docs/models.md#oren-nayar-qualitative`, `#oren-nayar-full` and
//! `#wolff-normalisations` (Wolff's constant K).

/// One model with its parameters as the study sets them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Configuration {
    Lambert,
    WolffPhysical,
    WolffNormal,
    WolffRaw,
    OrenNayarQualitative,
    OrenNayarFull,
    Ginneken,
    Eon,
    /// Another registered model (`matte_brdf::MODELS`, by plugin name) at its defaults.
    Registered(&'static str),
    /// The true surface of Oren–Nayar and EON: V-cavities, σ = 0.3, as a `tabulated_brdf`.
    TruthVCavities,
    /// The true surface of van Ginneken: a Gaussian height field, m = 0.3, as a `tabulated_brdf`.
    TruthHeightField,
}

/// The paper's four models (its column order) and EON as a fifth, each with the plugin's
/// defaults; Lambert first, as every ratio's denominator.
pub const PAPER_RUN: [Configuration; 5] = [
    Configuration::Lambert,
    Configuration::WolffPhysical,
    Configuration::OrenNayarQualitative,
    Configuration::Ginneken,
    Configuration::Eon,
];

/// The main run: [`PAPER_RUN`], then every registered model marked `in_study` whose plugin
/// none of those renders, at its defaults.
pub fn main_run() -> Vec<Configuration> {
    let mut run = PAPER_RUN.to_vec();
    for spec in matte_brdf::MODELS.iter().filter(|s| s.in_study) {
        if !PAPER_RUN.iter().any(|c| c.bsdf() == spec.name) {
            run.push(Configuration::Registered(spec.name));
        }
    }
    run
}

/// Wolff's normalisations and the two Oren–Nayar models.
pub const VARIANTS: [Configuration; 5] = [
    Configuration::WolffPhysical,
    Configuration::WolffNormal,
    Configuration::WolffRaw,
    Configuration::OrenNayarQualitative,
    Configuration::OrenNayarFull,
];

/// The convergence series: Lambert (the denominator), then the models whose region ratio is
/// tracked over spp.
pub const SERIES: [Configuration; 3] =
    [Configuration::Lambert, Configuration::OrenNayarQualitative, Configuration::OrenNayarFull];

/// The simulated surfaces the study renders beside the models (`python/matte_mitsuba/ground_truth/`).
pub const TRUTHS: [Configuration; 2] = [Configuration::TruthVCavities, Configuration::TruthHeightField];

/// The models that describe a simulated surface, each compared with its own
/// ([`Configuration::true_surface`]); Lambert and Wolff describe none.
pub const WITH_TRUTH: [Configuration; 4] =
    [Configuration::OrenNayarQualitative, Configuration::OrenNayarFull, Configuration::Eon, Configuration::Ginneken];

struct Entry {
    key: &'static str,
    bsdf: &'static str,
    label: &'static str,
    tile: &'static str,
    property: Option<(&'static str, &'static str)>,
    meaning: &'static str,
}

impl Configuration {
    fn entry(self) -> Entry {
        use Configuration::*;
        match self {
            Lambert => Entry {
                key: "lambert",
                bsdf: "lambert",
                label: "Lambert",
                tile: "Lambert",
                property: None,
                meaning: "f = ρ/π.",
            },
            WolffPhysical => Entry {
                key: "wolff_physical",
                bsdf: "wolff",
                label: "Wolff (physical)",
                tile: "Wolff",
                property: Some(("normalization", "physical")),
                meaning: "K = ρ / (π n² (1 − ρ F_dr,int)): isotropic radiance inside the body, internally reflected light scattered again (Mitsuba 0.6 plastic's diffuse lobe). ρ is the internal albedo; the albedo at normal incidence is (1 − F(0)) ρ (1 − F_dr,int) / (1 − ρ F_dr,int), below ρ for ρ < 1.",
            },
            WolffNormal => Entry {
                key: "wolff_normal",
                bsdf: "wolff",
                label: "Wolff (normal)",
                tile: "Wolff normal",
                property: Some(("normalization", "normal")),
                meaning: "K = ρ / (π (1 − F(0)) (1 − F_dr,ext)): scaled so that the albedo at normal incidence is ρ, as for Lambert (an equal-albedo comparison). Only the angular shape differs from Lambert, which is Fresnel dimming towards grazing.",
            },
            WolffRaw => Entry {
                key: "wolff_raw",
                bsdf: "wolff",
                label: "Wolff (raw)",
                tile: "Wolff raw",
                property: Some(("normalization", "raw")),
                meaning: "K = ρ / π: Lambert's constant times the two Fresnel transmissions, with no energy normalisation. The albedo at normal incidence is ρ (1 − F(0)) (1 − F_dr,ext).",
            },
            OrenNayarQualitative => Entry {
                key: "oren_nayar_qualitative",
                bsdf: "oren_nayar",
                label: "Oren–Nayar (qualitative)",
                tile: "Oren–Nayar qual.",
                property: Some(("model", "qualitative")),
                meaning: "The 1994 qualitative model (ρ/π)(A + B max(0, cos Δφ) sin α tan β), as in the seed paper. It loses energy at normal incidence (E(0) = A) and is retro-reflective.",
            },
            OrenNayarFull => Entry {
                key: "oren_nayar_full",
                bsdf: "oren_nayar",
                label: "Oren–Nayar (full)",
                tile: "Oren–Nayar full",
                property: Some(("model", "full")),
                meaning: "The full 1994 model: the C1–C3 terms, which darken forward scattering, plus the interreflection term f2 = 0.17 (ρ²/π) σ²/(σ² + 0.13) (1 − cos Δφ (2β/π)²). f2 grows with ρ², so bright surfaces gain the most.",
            },
            Ginneken => Entry {
                key: "ginneken",
                bsdf: "ginneken",
                label: "van Ginneken",
                tile: "van Ginneken",
                property: None,
                meaning: "Lambertian facets on a Gaussian random surface, with shadowing and masking.",
            },
            Eon => Entry {
                key: "eon",
                bsdf: "eon",
                label: "EON",
                tile: "EON",
                property: None,
                meaning: "Energy-preserving Oren–Nayar (Portsmouth et al. 2025).",
            },
            TruthVCavities => Entry {
                key: "truth_v_cavities",
                bsdf: "tabulated_brdf",
                label: "V-cavities σ=0.3",
                tile: "V-cavities",
                property: None,
                meaning: "Oren & Nayar's surface, simulated: long symmetric V-cavities with Lambertian facets, Gaussian slope angles σ = 0.3, all interreflections (python/matte_mitsuba/ground_truth/v_cavities_sigma0.3.json).",
            },
            TruthHeightField => Entry {
                key: "truth_height_field",
                bsdf: "tabulated_brdf",
                label: "height field m=0.3",
                tile: "height field",
                property: None,
                meaning: "van Ginneken's surface, simulated: a Gaussian random height field with Lambertian facets, rms slope m = 0.3, all interreflections (python/matte_mitsuba/ground_truth/height_field_m0.3.json).",
            },
            Registered(name) => {
                let spec = matte_brdf::spec(name).expect("a registered model");
                Entry {
                    key: spec.name,
                    bsdf: spec.name,
                    label: spec.label,
                    tile: spec.label,
                    property: None,
                    meaning: spec.summary,
                }
            }
        }
    }

    /// File-name and study.json key, e.g. `wolff_raw`.
    pub fn key(self) -> &'static str {
        self.entry().key
    }

    /// The plugin name (`<bsdf type="…">`).
    pub fn bsdf(self) -> &'static str {
        self.entry().bsdf
    }

    /// The name in tables and sentences.
    pub fn label(self) -> &'static str {
        self.entry().label
    }

    /// The short name in the strips.
    pub fn tile(self) -> &'static str {
        self.entry().tile
    }

    /// The `<bsdf>` property (name, value) that selects this configuration, if any.
    pub fn property(self) -> Option<(&'static str, &'static str)> {
        self.entry().property
    }

    /// What the configuration means, for the report.
    pub fn meaning(self) -> &'static str {
        self.entry().meaning
    }

    /// The table file of a true surface, in `python/matte_mitsuba/ground_truth/`.
    pub fn table(self) -> Option<&'static str> {
        match self {
            Configuration::TruthVCavities => Some("v_cavities_sigma0.3.json"),
            Configuration::TruthHeightField => Some("height_field_m0.3.json"),
            _ => None,
        }
    }

    /// Whether this is a simulated surface rather than a model.
    pub fn is_truth(self) -> bool {
        self.table().is_some()
    }

    /// The simulated surface this model describes, at the study's roughness 0.3 (σ, m, r).
    pub fn true_surface(self) -> Option<Configuration> {
        use Configuration::*;
        match self {
            OrenNayarQualitative | OrenNayarFull | Eon => Some(TruthVCavities),
            Ginneken => Some(TruthHeightField),
            _ => None,
        }
    }

    /// Whether the plugin's defaults give this configuration, so the main run already
    /// rendered it (no derived scene needed).
    pub fn is_main_run(self) -> bool {
        main_run().contains(&self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn main_run_configurations_are_the_plugin_defaults() {
        // The main run renders `<bsdf type="…"/>` with no property: a configuration with a
        // property is in it only when that property is the plugin's default.
        for c in main_run() {
            if let Some((name, value)) = c.property() {
                let bsdf = matte_brdf::DiffuseModel::from_params(c.bsdf(), matte_brdf::Params::default()).unwrap();
                let default = bsdf.parameters().into_iter().find(|(n, _)| *n == name).map(|(_, v)| v);
                assert_eq!(default, Some(matte_brdf::ParamValue::Text(value.into())), "{c:?}");
            }
        }
    }

    #[test]
    fn models_with_a_truth_are_those_whose_surface_is_simulated() {
        for c in [main_run().as_slice(), &VARIANTS].concat() {
            assert_eq!(c.true_surface().is_some(), WITH_TRUTH.contains(&c), "{c:?}");
        }
        for t in TRUTHS {
            assert!(t.is_truth() && t.true_surface().is_none() && !main_run().contains(&t));
            assert!(t.table().is_some(), "{t:?}"); // the file exists: tests/tools/study.rs
        }
    }

    #[test]
    fn keys_are_unique() {
        let all = [main_run().as_slice(), &VARIANTS, &SERIES, &TRUTHS].concat();
        for a in &all {
            for b in &all {
                assert!(a == b || a.key() != b.key(), "{a:?} and {b:?} share a key");
            }
        }
    }
}
