//! Renderer-side BSDFs: Mitsuba's `diffuse`, `twosided`, `dielectric`, `conductor`,
//! `roughconductor`, and the matte diffuse kernels, all in the local shading frame.

pub mod sample;

pub use sample::BsdfSample;
