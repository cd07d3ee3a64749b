//! The matte kernels (`matte_brdf`, every registered type, `tabulated_brdf` included) as renderer BSDFs: `f·cos θo` from the kernel's `f`, the kernel's own
//! sampling, reflectance per RGB channel (several models are non-linear in ρ). Direction
//! convention as in the plugin: the renderer's `wi` (towards the camera side) is the kernel's
//! given direction; every model is reciprocal.
//!
//! The numeric parameters (σ, r, α, int_ior, …) are numbers or textures, as in the Mitsuba
//! plugin (`cpp/matte_bsdf.h`). With numbers only, the model's constants are computed once
//! ([`DiffuseModel`]); with a texture, the parameters are looked up at the hit with Mitsuba's
//! `eval_1` and turned into kernel constants per hit (`matte_brdf::lane`;
//! `docs/models.md#spatially-varying-parameters`).

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::construction::{construct, is_file_parameter};
use matte_brdf::kernel;
use matte_brdf::registry::MAX_NUMERIC;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};
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
    /// `reflectance` (a texture, default 0.5), then every other property and nested texture
    /// for the kernels' construction ([`construct`], the plugin's too): numbers range-checked,
    /// textures validated with their mean and evaluated per hit.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let kind = p.object().plugin.clone();
        let reflectance = p.texture("reflectance")?;
        let nested_names = p.remaining_nested_names();
        let mut properties: Vec<(String, ParamValue)> = Vec::new();
        for prop in p.remaining_properties() {
            let value = match &prop.value {
                Value::Float(x) => ParamValue::Number(*x),
                Value::Integer(i) => ParamValue::Number(*i as f64),
                // A file (`tabulated_brdf`'s table) is resolved as every file of the scene.
                Value::String(s) if is_file_parameter(&kind, &prop.name) => {
                    ParamValue::Text(p.resolve(s).display().to_string())
                }
                Value::String(s) => ParamValue::Text(s.clone()),
                Value::Boolean(v) => ParamValue::Flag(*v),
                other => {
                    return Err(
                        p.prop_err(&prop.name, format!("must be a number or a string, not {}", other.type_name()))
                    );
                }
            };
            properties.push((prop.name.clone(), value));
        }
        let mut textures: Vec<(String, Texture)> = Vec::new();
        for name in nested_names {
            let t = p.texture(&name)?;
            properties.push((name.clone(), ParamValue::Texture { mean: t.mean() as f64 }));
            textures.push((name, t));
        }
        let c = construct(&kind, &properties).map_err(|e| p.prop_err(&e.param, e.message))?;
        if !c.is_textured() {
            return Ok(Matte::new(c.model, reflectance));
        }
        // Every numeric parameter as a texture: the given ones, numbers as constant textures.
        let all = c
            .numeric
            .iter()
            .map(|n| match textures.iter().position(|(name, _)| name == n.name) {
                Some(k) if n.textured => textures.swap_remove(k).1,
                _ => Texture::Constant(Vec3::splat(n.value as f32)),
            })
            .collect();
        Ok(Matte { model: c.model, reflectance, textured: Some(all) })
    }
}

impl Bxdf for Matte {
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
