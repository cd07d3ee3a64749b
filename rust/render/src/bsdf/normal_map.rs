//! Mitsuba's `normalmap` (`src/bsdfs/normalmap.cpp` and `normalmap_helpers.h`, v3.9.1): a
//! wrapper that evaluates its nested BSDF in a shading frame perturbed by a normal-map texture.
//!
//! The texture's RGB at the hit's uv maps to a normal n = 2·rgb − 1 **in the shading frame**
//! (x along the shading tangent `s`, z along the shading normal). With
//! `flip_invalid_normals` (default true) n's tangential part is negated when wi lies on the
//! other side of n than of the shading normal. The perturbed frame is n̂ = normalize(n),
//! ŝ = normalize(x − n̂·n̂ₓ), t̂ = n̂ × ŝ; wi and wo are expressed in it, and the result is zero
//! when wo is on different sides of the two normals. With `use_shadowing_function` (default
//! true) values and sample weights are multiplied by Estevez et al.'s shadow-terminator
//! term ([`super::perturbed_frame`], shared with `bumpmap`).
//!
//! Only the local shading frame is involved, so the result depends on the shape's tangent
//! orientation exactly as in Mitsuba (`sh_frame.s` along ∂p/∂u there).

use super::bxdf::Bxdf;
use super::flags::BsdfFlags;
use super::perturbed_frame;
use super::sample::BsdfSample;
use crate::geometry::Frame;
use crate::load::props::{FromProps, NestedBsdf, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;

/// Mitsuba's `normalmap` wrapper around a nested BSDF of type `B` (the scene's: [`super::Bsdf`]).
#[derive(Clone, Debug)]
pub struct NormalMap<B> {
    pub normals: Texture,
    pub nested: Box<B>,
    pub flip_invalid_normals: bool,
    pub use_shadowing_function: bool,
}

impl<B: NestedBsdf> FromProps for NormalMap<B> {
    /// One nested BSDF, the `normalmap` texture (required), `flip_invalid_normals` and
    /// `use_shadowing_function` (default true).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let nested = p.nested("bsdf");
        let [inner] = nested.as_slice() else {
            return Err(p.err(format!("needs exactly one nested BSDF, found {}", nested.len())));
        };
        if !p.has("normalmap") {
            return Err(p.err("missing the \"normalmap\" texture"));
        }
        let normals = p.texture("normalmap")?;
        let flip_invalid_normals = p.boolean("flip_invalid_normals")?;
        let use_shadowing_function = p.boolean("use_shadowing_function")?;
        Ok(NormalMap {
            normals,
            nested: Box::new(B::from_nested(p, inner)?),
            flip_invalid_normals,
            use_shadowing_function,
        })
    }
}

impl<B> NormalMap<B> {
    /// The perturbed frame in the coordinates of the unperturbed shading frame.
    #[inline]
    pub fn frame(&self, si: &SurfaceInteraction, wi: Vec3) -> Frame {
        let mut n = self.normals.eval(si) * 2.0 - Vec3::ONE;
        if self.flip_invalid_normals && wi.z * wi.dot(n) <= 0.0 {
            n = Vec3::new(-n.x, -n.y, n.z);
        }
        let n = n.normalize();
        let s = (Vec3::X - n * n.x).normalize();
        Frame { s, t: n.cross(s), n }
    }
}

impl<B: Bxdf> Bxdf for NormalMap<B> {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        let frame = self.frame(si, wi);
        perturbed_frame::eval_pdf(&*self.nested, &frame, self.use_shadowing_function, si, wi, wo)
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let frame = self.frame(si, wi);
        perturbed_frame::sample(&*self.nested, &frame, self.use_shadowing_function, si, wi, u_lobe, u)
    }

    /// The nested BSDF's.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.nested.flags()
    }
}
