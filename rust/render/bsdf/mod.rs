//! Renderer-side BSDFs: Mitsuba's `diffuse`, `twosided`, `dielectric`, `conductor`,
//! `roughconductor`, and the matte diffuse kernels, all in the local shading frame.

pub mod conductor;
pub mod conductor_ior;
pub mod dielectric;
pub mod fresnel;
pub mod microfacet;
pub mod rough_conductor;
pub mod sample;
mod validate;
pub mod vndf;

pub use conductor::Conductor;
pub use conductor_ior::conductor_material;
pub use dielectric::Dielectric;
pub use fresnel::fresnel_conductor;
pub use microfacet::MicrofacetDistribution;
pub use rough_conductor::RoughConductor;
pub use sample::BsdfSample;
