//! Mitsuba's `twosided` (`src/bsdfs/twosided.cpp`, v3.9.1): one or two nested BSDFs, `front`
//! for cos θi > 0 and `back` (the same BSDF when only one is nested) for the other side, with
//! both directions mirrored through the surface. A transmissive nested BSDF is refused unless
//! `allow_transmission` is true, as in Mitsuba.

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::sample::BsdfSample;
use crate::load::props::{FromProps, NestedBsdf, PluginProps};
use crate::shape::SurfaceInteraction;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `twosided`: `front` for cos θi > 0, `back` for the other side, nested BSDFs of
/// type `B` (the scene's: [`super::Bsdf`]).
#[derive(Clone, Debug)]
pub struct TwoSided<B> {
    pub front: Box<B>,
    pub back: Box<B>,
}

impl<B: NestedBsdf + Bxdf + Clone> FromProps for TwoSided<B> {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let nested = p.nested("bsdf");
        let (front, back) = match nested.as_slice() {
            [one] => {
                let f = B::from_nested(p, one)?;
                (f.clone(), f)
            }
            [f, bk] => (B::from_nested(p, f)?, B::from_nested(p, bk)?),
            _ => return Err(p.err(format!("needs one or two nested BSDFs, found {}", nested.len()))),
        };
        let allow_transmission = p.boolean("allow_transmission")?;
        for side in [&front, &back] {
            if side.flags().has(BsdfFlags::TRANSMISSION) && !allow_transmission {
                return Err(p.err(
                    "a twosided BSDF cannot wrap a transmissive BSDF unless allow_transmission is true (as in Mitsuba)",
                ));
            }
        }
        Ok(TwoSided { front: Box::new(front), back: Box::new(back) })
    }
}

/// The direction mirrored through the surface.
#[inline]
fn flip(v: Vec3) -> Vec3 {
    Vec3::new(v.x, v.y, -v.z)
}

impl<B: Bxdf> Bxdf for TwoSided<B> {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        if wi.z > 0.0 { self.front.eval_pdf(si, wi, wo) } else { self.back.eval_pdf(si, flip(wi), flip(wo)) }
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wi.z > 0.0 {
            self.front.sample(si, wi, u_lobe, u)
        } else {
            let mut s = self.back.sample(si, flip(wi), u_lobe, u)?;
            s.wo = flip(s.wo);
            Some(s)
        }
    }

    /// The front BSDF's flags on the front side, the back BSDF's on the back side.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        (self.front.flags() & !BsdfFlags::BACK_SIDE)
            | BsdfFlags::FRONT_SIDE
            | (self.back.flags() & !BsdfFlags::FRONT_SIDE)
            | BsdfFlags::BACK_SIDE
    }
}
