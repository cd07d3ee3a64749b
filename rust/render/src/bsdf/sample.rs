//! What every renderer-side BSDF returns, in the local shading frame (z = shading normal).
//! Direction convention as Mitsuba's `BSDF::eval(ctx, si, wo)`: `wi` points from the surface
//! towards the previous path vertex (the camera side), `wo` towards the next one (the light).

use glam::Vec3;

/// A sampled outgoing direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Unit direction in the local shading frame.
    pub wo: Vec3,
    /// Path throughput factor per RGB channel: `f·|cos θo| / pdf` for smooth lobes, the lobe's
    /// own weight (e.g. Fresnel-selected reflection = specular_reflectance) for delta lobes.
    pub weight: Vec3,
    /// Solid-angle density for smooth lobes; for delta lobes the discrete lobe probability
    /// (only used for MIS bookkeeping, which ignores it because `delta` is set).
    pub pdf: f32,
    /// A Dirac lobe (mirror or refraction): no light sampling, no MIS.
    pub delta: bool,
    /// Relative index of refraction crossed (Mitsuba `bs.eta`): 1 for reflection, `η_t/η_i`
    /// for refraction. Russian roulette multiplies the throughput by η² of the path.
    pub eta: f32,
}
