//! Constructor checks shared by the specular BSDFs: bad parameters become an `Err` naming the
//! plugin and the parameter, never a panic or a NaN later in the per-sample code.

use glam::Vec3;

/// Colour parameters must be finite and non-negative. (The scene parser enforces Mitsuba's
/// [0, 1] range for bounded textures, docs/renderer-semantics.md §2; this guards direct construction.)
pub(crate) fn check_colour(bsdf: &str, name: &str, v: Vec3) -> Result<(), String> {
    if v.is_finite() && v.min_element() >= 0.0 {
        Ok(())
    } else {
        Err(format!("{bsdf}: {name} must be finite and non-negative, got {v}"))
    }
}

/// Unbounded colour parameters (conductor `eta`, `k`) only need to be finite.
pub(crate) fn check_finite(bsdf: &str, name: &str, v: Vec3) -> Result<(), String> {
    if v.is_finite() { Ok(()) } else { Err(format!("{bsdf}: {name} must be finite, got {v}")) }
}
