//! The matte kernels (`crate::brdf`) as renderer BSDFs: `f·cos θo` from the kernel's `f`, the
//! kernel's own sampling, reflectance per RGB channel (several models are non-linear in ρ).
//! Direction convention as in the plugin: the renderer's `wi` (towards the camera side) is
//! the kernel's given direction; every model is reciprocal.

use super::BsdfSample;
use crate::brdf::kernel;
use crate::brdf::{DiffuseBrdf, DiffuseModel, dispatch};
use crate::render::shape::SurfaceInteraction;
use crate::render::texture::Texture;
use glam::{Vec2, Vec3};

/// `(f·cos θo, pdf)`.
#[inline]
pub fn eval_pdf(model: &DiffuseModel, rho: Vec3, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    dispatch!(model, k => {
        let f = k.eval::<3>(wi, wo, rho.to_array());
        (Vec3::from_array(f) * wo.z, k.pdf(wi, wo))
    })
}

#[inline]
pub fn sample(model: &DiffuseModel, rho: Vec3, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wi.z <= 0.0 {
        return None;
    }
    dispatch!(model, k => {
        let s = k.sample::<3>(wi, u, rho.to_array())?;
        if !(s.pdf > 0.0) {
            return None;
        }
        Some(BsdfSample { wo: s.wo, weight: Vec3::from_array(s.weight), pdf: s.pdf, delta: false, eta: 1.0 })
    })
}

/// A matte model whose numeric parameters (σ, r, α, int_ior, …) are textures, looked up at
/// the hit with Mitsuba's `eval_1` and turned into kernel constants per hit
/// (`crate::brdf::lane`; `docs/models.md#spatially-varying-parameters`). Models with only
/// constant parameters stay [`super::Bsdf::Matte`], whose constants are computed once.
#[derive(Clone, Debug)]
pub struct TexturedMatte {
    pub model: DiffuseModel,
    pub reflectance: Texture,
    /// One per numeric parameter, in the order of the model's parameters (constants as
    /// constant textures).
    pub params: Vec<Texture>,
}

impl TexturedMatte {
    /// The parameters' values at the hit (at most two: Wolff's indices).
    #[inline]
    fn values(&self, si: &SurfaceInteraction) -> ([f32; 2], usize) {
        let mut v = [0.0; 2];
        for (slot, t) in v.iter_mut().zip(&self.params) {
            *slot = t.eval_1(si);
        }
        (v, self.params.len().min(2))
    }

    #[inline]
    pub fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let (v, n) = self.values(si);
        let Some(k) = self.model.lane_kernel_f32(&v[..n]) else {
            return (Vec3::ZERO, 0.0);
        };
        let f = kernel::eval(&k, wi.into(), wo.into(), self.reflectance.eval(si).to_array());
        (Vec3::from_array(f) * wo.z, self.model.pdf(wi, wo))
    }

    #[inline]
    pub fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wi.z <= 0.0 {
            return None;
        }
        let (v, n) = self.values(si);
        let k = self.model.lane_kernel_f32(&v[..n])?;
        let (wo, weight, pdf) = kernel::sample(&k, wi.into(), u.x, u.y, self.reflectance.eval(si).to_array());
        if !(pdf > 0.0) {
            return None;
        }
        Some(BsdfSample { wo: wo.into(), weight: Vec3::from_array(weight), pdf, delta: false, eta: 1.0 })
    }
}
