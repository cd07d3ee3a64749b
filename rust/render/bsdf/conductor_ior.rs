//! RGB complex indices of Mitsuba's named conductor `material`s in `scalar_rgb`.
//!
//! Mitsuba (`complex_ior_from_file` in `include/mitsuba/render/ior.h`) integrates the
//! spectral `data/ior/<mat>.{eta,k}.spd` against the CIE 1931 curves **without** D65
//! weighting and converts to linear sRGB (`spectrum_list_to_srgb(bounded = false, d65 =
//! false)`). The values below are that computation's result, verified against Mitsuba 3.9.1
//! to ~1e-5 (semantics doc §10 table); Au gives the verified normal-incidence furnace values
//! (0.96668, 0.80201, 0.32412).

use glam::Vec3;

/// `(material, eta, k)`; "none" is Mitsuba's default: η = 0, k = 1, Fresnel ≡ 1.
const MATERIALS: &[(&str, [f32; 3], [f32; 3])] = &[
    ("none", [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]),
    ("Au", [0.143036, 0.375307, 1.442045], [3.982997, 2.385556, 1.603359]),
    ("Cu", [0.201005, 0.923750, 1.102215], [3.913262, 2.453045, 2.14209]),
    ("Ag", [0.155276, 0.116728, 0.138388], [4.828355, 3.122222, 2.146901]),
    ("Al", [1.657501, 0.880405, 0.521244], [9.223811, 6.269502, 4.837004]),
];

/// RGB `(eta, k)` of a named conductor as Mitsuba computes it in RGB mode. Names are
/// case-sensitive, as Mitsuba's file names are. Any other name → `Err` listing the supported
/// ones (Mitsuba knows more materials; their spectra are not tabulated here).
pub fn conductor_material(name: &str) -> Result<(Vec3, Vec3), String> {
    MATERIALS
        .iter()
        .find(|(n, _, _)| *n == name)
        .map(|(_, eta, k)| (Vec3::from(*eta), Vec3::from(*k)))
        .ok_or_else(|| {
            let names: Vec<&str> = MATERIALS.iter().map(|(n, _, _)| *n).collect();
            format!("unsupported conductor material \"{name}\"; supported: {}", names.join(", "))
        })
}
