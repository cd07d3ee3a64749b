//! The diffuse BRDF kernels: one file per model (`models/`), pure functions over local-frame directions,
//! no renderer or FFI types. [`DiffuseModel`] is the closed set of models matte offers, constructed
//! from the plugin names and parameters of the README's model table. Each model is written
//! once over the scalar trait [`real::Real`] ([`kernel`]): f32 on the CPU, traced into Dr.Jit
//! by the Mitsuba plugin (`matte_plugin::traced`).

pub mod approx;
pub mod cltc;
pub mod construction;
pub mod diffuse_brdf;
pub mod dual;
pub mod frame;
pub mod fresnel;
pub mod fresnel_fit;
pub mod kernel;
pub mod lane;
pub mod params;
pub mod quadrature;
pub mod real;
pub mod reference_values;
pub mod registry;
pub mod rng;
pub mod sampler_fits;
pub mod sampling;
pub mod simd;
pub mod wide;

pub mod models;

pub use diffuse_brdf::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf};
pub use models::*;

/// The registered types that build from their defaults alone, in the README's order: every
/// model but `tabulated_brdf`, whose table file is required. The sweeps over every model at
/// its defaults (tests, `matte bench`, the study's scenes) run these.
pub fn default_models() -> impl Iterator<Item = &'static str> {
    MODELS.iter().filter(|s| s.builds_from_defaults()).map(|s| s.name)
}
pub use models::oren_nayar::OrenNayarForm;
pub use models::wolff::WolffNormalization;
pub use params::{ParamError, ParamValue, Params};

use glam::{Vec2, Vec3};

impl DiffuseModel {
    /// The plugin name.
    pub fn kind(&self) -> &'static str {
        self.spec().name
    }

    /// Whether the model, as configured, draws directions with its own sampler rather than the
    /// cosine (`docs/sampling.md`).
    pub fn own_sampler(&self) -> bool {
        use kernel::Kernel;
        use registry::KernelBrdf;
        dispatch!(self, m => !m.f32_kernel().cosine_sampling())
    }

    /// f and the density together, in one dispatch (the renderer's `eval_pdf`).
    #[inline]
    pub fn eval_pdf<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> ([f32; N], f32) {
        dispatch!(self, b => (b.eval(wi, wo, reflectance), b.pdf(wi, wo)))
    }

    /// The effective parameters (defaults filled in), for printing and `to_string`.
    pub fn parameters(&self) -> Vec<(&'static str, ParamValue)> {
        use registry::Registered;
        let values = dispatch!(self, m => m.values());
        self.spec().params.iter().map(|p| p.name).zip(values).collect()
    }
}

impl DiffuseBrdf for DiffuseModel {
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        dispatch!(self, b => b.eval(wi, wo, reflectance))
    }

    #[inline]
    fn pdf(&self, wi: Vec3, wo: Vec3) -> f32 {
        dispatch!(self, b => b.pdf(wi, wo))
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        dispatch!(self, b => b.sample(wi, u, reflectance))
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        dispatch!(self, b => b.albedo(cos_theta_i, reflectance))
    }
}
