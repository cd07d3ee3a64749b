//! Ground truth for the rough diffuse models: a virtual gonioreflectometer that traces light
//! through the explicit microgeometry a model claims to describe, and measures its BRDF with
//! confidence intervals (`docs/microgeometry.md`).
//!
//! * [`surface`]: what a simulated surface provides (random patches, ray intersection).
//! * [`v_cavity`]: Oren–Nayar's surface, long symmetric V-cavities with Lambertian facets and a
//!   Gaussian slope-angle distribution.
//! * [`height_field`]: van Ginneken's surface, a periodic Gaussian random height field of
//!   Lambertian triangles with per-axis rms slope m.
//! * [`gonioreflectometer`]: photons from a distant source, next-event estimates of f toward
//!   every sensor direction, all bounces or the first only, and the directional albedo.
//! * [`comparison`]: every rough model against both simulated surfaces.
//! * [`realisations`]: one measurement pooled over independent realisations of a random surface.
//! * [`eon_fit`]: EON's roughness that fits a simulated surface best.
//! * [`tabulation`]: the simulated BRDF as a tabulated BSDF file (`matte_brdf::tabulated`).
//! * [`estimate`]: running means with 99 % intervals.

pub mod comparison;
pub mod eon_fit;
pub mod estimate;
pub mod gonioreflectometer;
pub mod height_field;
pub mod realisations;
pub mod surface;
pub mod tabulation;
pub mod v_cavity;

pub use estimate::{Estimate, RunningMean};
pub use gonioreflectometer::{Bounces, Measurement, Setup, measure, measure_reflectances};
pub use height_field::HeightField;
pub use surface::{MicroSurface, SurfaceHit};
pub use v_cavity::VCavities;
