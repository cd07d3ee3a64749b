//! The matte kernels (`matte_brdf`, every registered model) as renderer BSDFs: `f·cos θo` from the kernel's `f`, the kernel's own
//! sampling, reflectance per RGB channel (several models are non-linear in ρ). Direction
//! convention as in the plugin: the renderer's `wi` (towards the camera side) is the kernel's
//! given direction; every model is reciprocal.
//!
//! The numeric parameters (σ, r, α, int_ior, …) are numbers or textures, as in the Mitsuba
//! plugin (`cpp/matte_bsdf.h`). With numbers only, the model's constants are computed once
//! ([`DiffuseModel`]); with a texture, the parameters are looked up at the hit with Mitsuba's
//! `eval_1` and turned into kernel constants per hit (`matte_brdf::lane`;
//! `docs/models.md#spatially-varying-parameters`).

use super::{BsdfFlags, BsdfModel, BsdfSample};
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::kernel;
use matte_brdf::registry::MAX_NUMERIC;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, Params};
use matte_scene_file::SceneError;
use matte_scene_file::xml::Value;

/// A matte model with its reflectance and numeric parameters.
#[derive(Clone, Debug)]
pub struct Matte {
    /// The model, with the numeric parameters' values (a textured parameter's: a placeholder
    /// in its valid range, see [`matte_brdf::lane::textured_placeholder`]).
    pub model: DiffuseModel,
    pub reflectance: Texture,
    /// When a numeric parameter is a texture: every numeric parameter as a texture (numbers
    /// as constant textures), in the order of the model's parameters. `None`: all are numbers
    /// and the model's precomputed constants serve every hit.
    pub textured: Option<Box<[Texture]>>,
}

impl Matte {
    /// A model whose parameters are all numbers.
    #[must_use]
    pub fn new(model: DiffuseModel, reflectance: Texture) -> Self {
        Matte { model, reflectance, textured: None }
    }

    /// Whether a numeric parameter is a texture (evaluated per hit).
    #[must_use]
    pub fn is_textured(&self) -> bool {
        self.textured.is_some()
    }

    /// The textured parameters' values at the hit, in a fixed array (no allocation per hit;
    /// the registry holds every model to `MAX_NUMERIC` numeric parameters).
    #[inline]
    fn values(params: &[Texture], si: &SurfaceInteraction) -> ([f32; MAX_NUMERIC], usize) {
        let mut v = [0.0; MAX_NUMERIC];
        for (slot, t) in v.iter_mut().zip(params) {
            *slot = t.eval_1(si);
        }
        (v, params.len().min(MAX_NUMERIC))
    }
}

impl FromProps for Matte {
    /// `reflectance` (a texture, default 0.5), then every other property for the kernels'
    /// parameter parser (numbers and strings; numbers are range-checked there, as in every
    /// front end), and nested textures for numeric parameters.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let obj = p.object();
        let kind = obj.plugin.as_str();
        let reflectance = p.texture("reflectance")?;
        let nested_names = p.remaining_nested_names();
        let mut params = Params::new();
        for prop in p.remaining_properties() {
            let value = match &prop.value {
                Value::Float(x) => ParamValue::Number(*x),
                Value::Integer(i) => ParamValue::Number(*i as f64),
                Value::String(s) => ParamValue::Text(s.clone()),
                Value::Boolean(v) => ParamValue::Text(v.to_string()),
                other => {
                    return Err(
                        p.prop_err(&prop.name, format!("must be a number or a string, not {}", other.type_name()))
                    );
                }
            };
            params.push(&prop.name, value);
        }
        // Numeric parameters given as nested textures (sigma, roughness, alpha, int_ior, …):
        // the model is validated with each texture's mean, then evaluated per hit.
        let mut textured: Vec<(String, Texture)> = Vec::new();
        for name in nested_names {
            if !matte_brdf::lane::numeric_parameter_names(kind).contains(&name.as_str()) {
                return Err(p.prop_err(&name, "is not a numeric parameter of this model, so it cannot be a texture"));
            }
            let t = p.texture(&name)?;
            textured.push((name, t));
        }
        // A textured parameter stands for a number when the model is built: its mean,
        // clamped into the per-lane range (any texture is accepted; values clamp per hit).
        let number = |n: &str| match obj.properties.get(n).map(|p| &p.value) {
            Some(Value::Float(x)) => Some(*x),
            Some(Value::Integer(i)) => Some(*i as f64),
            Some(Value::String(s)) => matte_brdf::params::lookup_ior(s),
            _ => None,
        };
        for (name, tex) in &textured {
            let v = matte_brdf::lane::textured_placeholder(kind, name, tex.mean() as f64, number);
            params.push(name, ParamValue::Number(v));
        }
        let model = DiffuseModel::from_params(kind, params).map_err(|e| p.prop_err(&e.param, e.message))?;
        if textured.is_empty() {
            return Ok(Matte::new(model, reflectance));
        }
        // Every other numeric parameter becomes a constant texture of its value.
        let mut all = Vec::new();
        for (name, value) in model.parameters() {
            let ParamValue::Number(x) = value else { continue };
            match textured.iter().position(|(n, _)| n == name) {
                Some(k) => all.push(textured.swap_remove(k).1),
                None => all.push(Texture::Constant(Vec3::splat(x as f32))),
            }
        }
        if let Some((name, _)) = textured.first() {
            return Err(p.prop_err(name, "is not a numeric parameter of this model, so it cannot be a texture"));
        }
        Ok(Matte { model, reflectance, textured: Some(all.into_boxed_slice()) })
    }
}

impl BsdfModel for Matte {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let rho = self.reflectance.eval(si);
        match &self.textured {
            None => {
                let (f, pdf) = self.model.eval_pdf::<3>(wi, wo, rho.to_array());
                (Vec3::from_array(f) * wo.z, pdf)
            }
            Some(params) => {
                let (v, n) = Self::values(params, si);
                let Some(k) = self.model.lane_kernel_f32(&v[..n]) else {
                    return (Vec3::ZERO, 0.0);
                };
                let (f_cos, pdf) = kernel::eval_cos_pdf(&k, wi.into(), wo.into(), rho.to_array());
                (Vec3::from_array(f_cos), pdf)
            }
        }
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wi.z <= 0.0 {
            return None;
        }
        match &self.textured {
            None => {
                let rho = self.reflectance.eval(si);
                let s = self.model.sample::<3>(wi, u, rho.to_array())?;
                if !(s.pdf > 0.0) {
                    return None;
                }
                Some(BsdfSample { wo: s.wo, weight: Vec3::from_array(s.weight), pdf: s.pdf, delta: false, eta: 1.0 })
            }
            Some(params) => {
                let (v, n) = Self::values(params, si);
                let k = self.model.lane_kernel_f32(&v[..n])?;
                let (wo, weight, pdf) = kernel::sample(&k, wi.into(), u.x, u.y, self.reflectance.eval(si).to_array());
                if !(pdf > 0.0) {
                    return None;
                }
                Some(BsdfSample { wo: wo.into(), weight: Vec3::from_array(weight), pdf, delta: false, eta: 1.0 })
            }
        }
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}
