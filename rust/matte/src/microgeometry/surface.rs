//! What the gonioreflectometer needs from a simulated microsurface: random patches of it (one
//! V-cavity, one height-field tile) and the first facet a ray meets. Facets are Lambertian;
//! the macro-surface is the plane z = 0 with normal +z, and every patch lies below it.

use glam::DVec3;
use rand::Rng;

/// A facet point a ray reached: where, and the facet's normal (unit, facing the ray).
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    pub point: DVec3,
    pub normal: DVec3,
}

pub trait MicroSurface: Sync {
    /// One random piece of the surface, drawn per photon (for V-cavities, a cavity's slope and
    /// orientation), distributed as the surface's pieces are per unit macro area.
    type Patch;

    fn sample_patch(&self, rng: &mut impl Rng) -> Self::Patch;

    /// Where a photon travelling along `direction` (downwards) crosses the macro plane: uniform
    /// over the macro area the patch stands for.
    fn entry_point(&self, patch: &Self::Patch, direction: DVec3, rng: &mut impl Rng) -> DVec3;

    /// The first facet hit by the ray `origin + t·direction`, t > 0; `None` when the ray leaves
    /// the surface (escapes above the macro plane).
    fn intersect(&self, patch: &Self::Patch, origin: DVec3, direction: DVec3) -> Option<SurfaceHit>;
}
