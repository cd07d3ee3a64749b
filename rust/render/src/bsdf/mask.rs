//! Mitsuba's `mask` BSDF (`src/bsdfs/mask.cpp`, v3.9.1): a nested BSDF blended with a
//! pass-through ("null") component by an `opacity` α (a float or a texture's `eval_1`,
//! default 0.5, clipped to [0, 1]). docs/renderer-semantics.md §10 (mask).
//!
//! * `eval` and `pdf` are the nested BSDF's times α.
//! * `sample` picks the nested BSDF when `u_lobe < α` (and samples it with `u_lobe/α`; its
//!   weight is unchanged, its pdf times α), else the null component: `wo = −wi`, weight 1,
//!   pdf 1 − α, a Dirac sample (Mitsuba's `Null` is part of `Delta`).
//!
//! The null sample is an ordinary path vertex for the integrators, as in Mitsuba's `path`:
//! it counts as a bounce (depth and Russian roulette), an emitter it reaches is weighted as
//! after a Dirac sample, and there is no light sampling through it. Shadow rays do not see
//! through masks (Mitsuba's `Scene::ray_test` only tests geometry).

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, NestedBsdf, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `mask`: the nested BSDF (of type `B`, the scene's: [`super::Bsdf`]) with
/// probability `opacity`, else pass-through.
#[derive(Clone, Debug)]
pub struct Mask<B> {
    pub opacity: Texture,
    pub nested: Box<B>,
}

impl<B: NestedBsdf> FromProps for Mask<B> {
    /// One nested BSDF and `opacity` (a texture, default 0.5).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let nested = p.nested("bsdf");
        let [inner] = nested.as_slice() else {
            return Err(p.err(format!("needs exactly one nested BSDF, found {}", nested.len())));
        };
        let opacity = p.texture("opacity")?;
        Ok(Mask { opacity, nested: Box::new(B::from_nested(p, inner)?) })
    }
}

impl<B> Mask<B> {
    /// α at the hit, clipped to [0, 1] (NaN becomes 0: a texel that is not a number lets
    /// everything through rather than poisoning the path).
    #[inline]
    pub fn opacity(&self, si: &SurfaceInteraction) -> f32 {
        let a = self.opacity.eval_1(si);
        if a >= 1.0 {
            1.0
        } else if a > 0.0 {
            a
        } else {
            0.0
        }
    }
}

impl<B: Bxdf> Bxdf for Mask<B> {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        let a = self.opacity(si);
        let (f, pdf) = self.nested.eval_pdf(si, wi, wo);
        (f * a, pdf * a)
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let a = self.opacity(si);
        if u_lobe < a {
            let mut s = self.nested.sample(si, wi, (u_lobe / a).min(ONE_MINUS_EPSILON), u)?;
            s.pdf *= a;
            Some(s)
        } else {
            Some(BsdfSample { wo: -wi, weight: Vec3::ONE, pdf: 1.0 - a, delta: true, eta: 1.0 })
        }
    }

    /// The nested BSDF's and the null (pass-through) component's.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.nested.flags() | BsdfFlags::NULL | BsdfFlags::FRONT_SIDE | BsdfFlags::BACK_SIDE
    }
}

/// The largest f32 below 1 (keeps a rescaled lobe number in [0, 1)).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;
