//! The diffuse BRDF kernels: one file per model, pure functions over local-frame directions,
//! no renderer or FFI types. [`DiffuseModel`] is the closed set of models matte offers, constructed
//! from the plugin names and parameters of the README's model table. Each model is written
//! once over the scalar trait [`real::Real`] ([`kernel`]): f32 on the CPU, traced into Dr.Jit
//! by the Mitsuba plugin (`crate::ffi::traced`).

pub mod approx;
pub mod dual;
pub mod eon;
pub mod frame;
pub mod fresnel;
pub mod fresnel_fit;
pub mod ginneken;
pub mod kernel;
pub mod lambert;
pub mod lane;
pub mod model;
pub mod oren_nayar;
pub mod params;
pub mod quadrature;
pub mod real;
pub mod rough_diffuse;
pub mod sampling;
pub mod simd;
pub mod tabulated;
pub mod wolff;

pub use eon::Eon;
pub use ginneken::Ginneken;
pub use lambert::Lambert;
pub use model::{Albedo, AlbedoMethod, BrdfSample, DiffuseBrdf};
pub use oren_nayar::{OrenNayar, OrenNayarModel};
pub use params::{ParamError, ParamValue, Params};
pub use rough_diffuse::RoughDiffuse;
pub use wolff::{Wolff, WolffNormalization};

use glam::{Vec2, Vec3};

/// The plugin names, in the order of the README's model table.
pub const BSDF_TYPES: &[&str] = &["lambert", "oren_nayar", "eon", "wolff", "ginneken", "roughdiffuse"];

/// One of matte's diffuse models with its (validated) parameters.
#[derive(Clone, Debug, PartialEq)]
pub enum DiffuseModel {
    Lambert(Lambert),
    OrenNayar(OrenNayar),
    Eon(Eon),
    Wolff(Wolff),
    Ginneken(Ginneken),
    RoughDiffuse(RoughDiffuse),
}

/// `dispatch!(bsdf, k => expr)`: evaluates `expr` with `k` bound to the concrete model (static
/// dispatch; the renderer uses it too).
macro_rules! dispatch {
    ($self:expr, $b:ident => $e:expr) => {
        match $self {
            $crate::brdf::DiffuseModel::Lambert($b) => $e,
            $crate::brdf::DiffuseModel::OrenNayar($b) => $e,
            $crate::brdf::DiffuseModel::Eon($b) => $e,
            $crate::brdf::DiffuseModel::Wolff($b) => $e,
            $crate::brdf::DiffuseModel::Ginneken($b) => $e,
            $crate::brdf::DiffuseModel::RoughDiffuse($b) => $e,
        }
    };
}
pub(crate) use dispatch;

impl DiffuseModel {
    /// Builds the model `kind` (a plugin name) from its parameters. `reflectance` is not a
    /// model parameter here: it is per channel and per call (textures). Unknown names,
    /// unknown parameters and out-of-range values are errors naming the parameter.
    pub fn from_params(kind: &str, mut params: Params) -> Result<Self, ParamError> {
        let (bsdf, known): (DiffuseModel, &[&str]) = match kind {
            "lambert" => (DiffuseModel::Lambert(Lambert), &[]),
            "oren_nayar" => (DiffuseModel::OrenNayar(OrenNayar::from_params(&mut params)?), &["sigma", "model"]),
            "eon" => (DiffuseModel::Eon(Eon::from_params(&mut params)?), &["roughness"]),
            "wolff" => {
                (DiffuseModel::Wolff(Wolff::from_params(&mut params)?), &["int_ior", "ext_ior", "normalization"])
            }
            "ginneken" => (DiffuseModel::Ginneken(Ginneken::from_params(&mut params)?), &["roughness", "shadowing"]),
            "roughdiffuse" => {
                (DiffuseModel::RoughDiffuse(RoughDiffuse::from_params(&mut params)?), &["alpha", "use_fast_approx"])
            }
            other => {
                return Err(ParamError::new(
                    "type",
                    format!("unknown bsdf type \"{other}\" (known: {})", BSDF_TYPES.join(", ")),
                ));
            }
        };
        params.finish(kind, known)?;
        Ok(bsdf)
    }

    /// The plugin name.
    pub fn kind(&self) -> &'static str {
        match self {
            DiffuseModel::Lambert(_) => "lambert",
            DiffuseModel::OrenNayar(_) => "oren_nayar",
            DiffuseModel::Eon(_) => "eon",
            DiffuseModel::Wolff(_) => "wolff",
            DiffuseModel::Ginneken(_) => "ginneken",
            DiffuseModel::RoughDiffuse(_) => "roughdiffuse",
        }
    }

    /// The effective parameters (defaults filled in), for printing and `to_string`.
    pub fn parameters(&self) -> Vec<(&'static str, ParamValue)> {
        use ParamValue::{Number, Text};
        match self {
            DiffuseModel::Lambert(_) => vec![],
            DiffuseModel::OrenNayar(b) => {
                vec![("sigma", Number(b.sigma() as f64)), ("model", Text(b.model().as_str().into()))]
            }
            DiffuseModel::Eon(b) => vec![("roughness", Number(b.roughness() as f64))],
            DiffuseModel::Wolff(b) => vec![
                ("int_ior", Number(b.int_ior() as f64)),
                ("ext_ior", Number(b.ext_ior() as f64)),
                ("normalization", Text(b.normalization().as_str().into())),
            ],
            DiffuseModel::Ginneken(b) => {
                vec![("roughness", Number(b.roughness() as f64)), ("shadowing", Text(b.shadowing().as_str().into()))]
            }
            DiffuseModel::RoughDiffuse(b) => {
                vec![("alpha", Number(b.alpha() as f64)), ("use_fast_approx", Text(b.use_fast_approx().to_string()))]
            }
        }
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
    fn sample_direction(&self, wi: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
        dispatch!(self, b => b.sample_direction(wi, u))
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        dispatch!(self, b => b.sample(wi, u, reflectance))
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        dispatch!(self, b => b.albedo(cos_theta_i, reflectance))
    }
}
