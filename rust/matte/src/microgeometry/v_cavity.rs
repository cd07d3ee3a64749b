//! Oren–Nayar's microsurface (Oren & Nayar 1994, §3; `docs/microgeometry.md#v-cavities`): long
//! symmetric V-cavities side by side, each with two planar Lambertian facets of slope angle θa
//! and opposite azimuths. Per unit macro area, θa is Gaussian with zero mean and standard
//! deviation σ (radians), folded to θa ≥ 0 and truncated below 90°; the cavity's azimuth is
//! uniform. The model's own derivation treats cavities as independent, so a photon meets
//! exactly one cavity: it enters through the cavity's opening and leaves through it.
//!
//! A cavity is infinitely long, so light moves in its cross-section: with `u` the horizontal
//! direction across the cavity, a point is (s, z) = (p·u, p.z). The opening is s ∈ [−1, 1] at
//! z = 0 and the bottom is (0, −tan θa).

use super::surface::{MicroSurface, SurfaceHit};
use glam::DVec3;
use rand::Rng;
use rand_distr::{Distribution, Normal};
use std::f64::consts::{FRAC_PI_2, PI};

/// V-cavities with slope-angle standard deviation `sigma` (radians; 0 is a flat plane).
#[derive(Clone, Copy, Debug)]
pub struct VCavities {
    sigma: f64,
}

/// One cavity: the horizontal direction across it, tan θa, and its facets' normals (left facet
/// s < 0, right facet s > 0).
#[derive(Clone, Copy, Debug)]
pub struct Cavity {
    across: DVec3,
    tan_slope: f64,
    normals: [DVec3; 2],
}

/// Photons start this far above the macro plane, so that a flat facet (σ = 0) lies ahead.
const ENTRY_HEIGHT: f64 = 1e-9;
/// Relative tolerance of a hit's position on a facet segment.
const EDGE: f64 = 1e-12;

impl VCavities {
    pub fn new(sigma: f64) -> Result<Self, String> {
        if sigma.is_finite() && (0.0..=1.5).contains(&sigma) {
            Ok(VCavities { sigma })
        } else {
            Err(format!("V-cavity sigma must be in [0, 1.5] radians, got {sigma}"))
        }
    }

    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// The cavity with slope angle `slope` and azimuth `azimuth` (radians).
    pub fn cavity(slope: f64, azimuth: f64) -> Cavity {
        let across = DVec3::new(azimuth.cos(), azimuth.sin(), 0.0);
        let (sin, cos) = slope.sin_cos();
        Cavity {
            across,
            tan_slope: slope.tan(),
            normals: [across * sin + DVec3::Z * cos, -across * sin + DVec3::Z * cos],
        }
    }
}

impl MicroSurface for VCavities {
    type Patch = Cavity;

    fn sample_patch(&self, rng: &mut impl Rng) -> Cavity {
        let azimuth = rng.random::<f64>() * PI;
        if self.sigma == 0.0 {
            return Self::cavity(0.0, azimuth);
        }
        let normal = Normal::new(0.0, self.sigma).expect("sigma checked in new");
        loop {
            let slope = normal.sample(rng).abs();
            if slope < FRAC_PI_2 - 1e-6 {
                return Self::cavity(slope, azimuth);
            }
        }
    }

    fn entry_point(&self, cavity: &Cavity, _direction: DVec3, rng: &mut impl Rng) -> DVec3 {
        let s = 2.0 * rng.random::<f64>() - 1.0;
        cavity.across * s + DVec3::Z * ENTRY_HEIGHT
    }

    fn intersect(&self, cavity: &Cavity, origin: DVec3, direction: DVec3) -> Option<SurfaceHit> {
        let t = cavity.tan_slope;
        let (s0, z0) = (origin.dot(cavity.across), origin.z);
        let (ds, dz) = (direction.dot(cavity.across), direction.z);
        let mut best: Option<(f64, usize)> = None;
        // Left facet z = −t (s + 1), s ∈ [−1, 0]; right facet z = t (s − 1), s ∈ [0, 1].
        for (k, sign) in [(0usize, 1.0f64), (1, -1.0)] {
            if direction.dot(cavity.normals[k]) >= 0.0 {
                continue; // the ray leaves this facet's plane (or runs along it)
            }
            let lambda = (-t * (sign * s0 + 1.0) - z0) / (dz + sign * t * ds);
            if !(lambda > 0.0) || best.is_some_and(|(b, _)| lambda >= b) {
                continue;
            }
            let s = sign * (s0 + lambda * ds); // mirrored onto the left facet's range
            if (-1.0 - EDGE..=EDGE).contains(&s) {
                best = Some((lambda, k));
            }
        }
        best.map(|(lambda, k)| SurfaceHit { point: origin + direction * lambda, normal: cavity.normals[k] })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_vertical_ray_hits_the_facet_below_it() {
        let surface = VCavities::new(0.5).unwrap();
        let cavity = VCavities::cavity(0.5, 0.0);
        let hit = surface.intersect(&cavity, DVec3::new(-0.5, 0.0, 1e-9), -DVec3::Z).expect("hit");
        assert!((hit.point.z + 0.5 * 0.5f64.tan()).abs() < 1e-9, "{hit:?}");
        assert!((hit.normal - cavity.normals[0]).length() < 1e-12);
        // From there straight up, the ray leaves the cavity.
        assert!(surface.intersect(&cavity, hit.point, DVec3::Z).is_none());
        // Towards the other facet, it hits it.
        let across = surface.intersect(&cavity, hit.point, DVec3::new(1.0, 0.0, 0.1).normalize()).expect("hit");
        assert!((across.normal - cavity.normals[1]).length() < 1e-12 && across.point.x > 0.0);
    }

    #[test]
    fn a_flat_surface_is_hit_where_the_photon_enters() {
        let surface = VCavities::new(0.0).unwrap();
        let cavity = VCavities::cavity(0.0, 1.0);
        let d = DVec3::new(0.3, 0.2, -1.0).normalize();
        let hit = surface.intersect(&cavity, DVec3::new(0.2, 0.1, 1e-9), d).expect("hit");
        assert!(hit.point.z.abs() < 1e-12 && (hit.normal - DVec3::Z).length() < 1e-12);
        assert!(surface.intersect(&cavity, hit.point, DVec3::new(0.1, 0.0, 1.0).normalize()).is_none());
    }
}
