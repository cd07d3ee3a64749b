//! Mitsuba's `blendbsdf` (`src/bsdfs/blendbsdf.cpp`, v3.9.1): `(1 − w)·first + w·second` with
//! the blend weight w = `weight`'s `eval_1`, clipped to [0, 1] (a float or a texture; it has
//! no default). docs/renderer-semantics.md §10 (blendbsdf).
//!
//! * `eval` and `pdf` are the blends of the two.
//! * `sample` picks the first BSDF when `u_lobe > w` (with `(u_lobe − w)/(1 − w)`), else the
//!   second (with `u_lobe/w`), and then — pitfall — returns the **blended** sample: pdf
//!   `w·pdf₂ + (1 − w)·pdf₁` and weight `(w·f₂ + (1 − w)·f₁)/pdf`, where the picked BSDF's
//!   `f` is its sample weight times its pdf and the other's is evaluated in the sampled
//!   direction (one-sample MIS over the two). The picked sample's Dirac flag and η are kept.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, NestedBsdf, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `blendbsdf`: `(1 − weight)·first + weight·second`, over nested BSDFs of type `B`
/// (the scene's: [`super::Bsdf`]).
#[derive(Clone, Debug)]
pub struct Blend<B> {
    pub weight: Texture,
    pub first: Box<B>,
    pub second: Box<B>,
}

impl<B: NestedBsdf> FromProps for Blend<B> {
    /// Two nested BSDFs and `weight` (a float or a texture; required).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let nested = p.nested("bsdf");
        let [first, second] = nested.as_slice() else {
            return Err(p.err(format!("needs exactly two nested BSDFs, found {}", nested.len())));
        };
        if !p.has("weight") {
            return Err(p.err("missing the blend \"weight\" (a float or a texture)"));
        }
        let weight = p.texture("weight")?;
        Ok(Blend { weight, first: Box::new(B::from_nested(p, first)?), second: Box::new(B::from_nested(p, second)?) })
    }
}

impl<B> Blend<B> {
    /// w at the hit, clipped to [0, 1] (NaN → 0).
    #[inline]
    pub fn weight(&self, si: &SurfaceInteraction) -> f32 {
        let w = self.weight.eval_1(si);
        if w >= 1.0 {
            1.0
        } else if w > 0.0 {
            w
        } else {
            0.0
        }
    }
}

impl<B: Bxdf> Bxdf for Blend<B> {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        let w = self.weight(si);
        let (f0, p0) = self.first.eval_pdf(si, wi, wo);
        let (f1, p1) = self.second.eval_pdf(si, wi, wo);
        (f0 * (1.0 - w) + f1 * w, p0 * (1.0 - w) + p1 * w)
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let w = self.weight(si);
        // Mitsuba: the first BSDF where u_lobe > w, the second where u_lobe ≤ w (w = 0 and
        // u_lobe = 0 would divide 0 by 0 there; the first BSDF is the only one that counts).
        let pick_first = u_lobe > w || w == 0.0;
        let (picked, other, w_picked, u_rescaled) = if pick_first {
            (&self.first, &self.second, 1.0 - w, ((u_lobe - w) / (1.0 - w)).clamp(0.0, ONE_MINUS_EPSILON))
        } else {
            (&self.second, &self.first, w, (u_lobe / w).min(ONE_MINUS_EPSILON))
        };
        let mut s = picked.sample(si, wi, u_rescaled, u)?;
        let (f_other, pdf_other) = other.eval_pdf(si, wi, s.wo);
        let pdf = w_picked * s.pdf + (1.0 - w_picked) * pdf_other;
        let f = w_picked * s.weight * s.pdf + (1.0 - w_picked) * f_other;
        s.weight = if pdf > 0.0 { f / pdf } else { Vec3::ZERO };
        s.pdf = pdf;
        Some(s)
    }

    /// Both nested BSDFs'.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.first.flags() | self.second.flags()
    }
}

/// The largest f32 below 1 (keeps a rescaled lobe number in [0, 1)).
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;
