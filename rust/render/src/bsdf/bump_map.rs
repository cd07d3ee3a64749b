//! Mitsuba's `bumpmap` (`src/bsdfs/bumpmap.cpp`, v3.9.1): a wrapper that evaluates its nested
//! BSDF in a shading frame tilted by the gradient of a height texture.
//!
//! With g = `scale`·∇_uv h (the texture's `eval_1_grad`: bilinear luminance derivative) and
//! the shading normal n_s, the displaced tangents are ∂p/∂u + n_s·(g_u − n_s·∂p/∂u) and
//! likewise for v; their normalised cross product, turned to the geometric normal's side and
//! expressed in the shading frame, is the perturbed normal n̂ (with `flip_invalid_normals`,
//! default true, its tangential part is negated when wi is on the other side of n̂). The
//! tangent is ŝ = normalize(∂p/∂u − n̂(n̂·∂p/∂u)) — Mitsuba mixes the local n̂ with the
//! world-space ∂p/∂u here, and matte does the same so that images agree. Values and weights
//! get the shadow-terminator term of `normalmap` (`use_shadowing_function`, default true;
//! both wrappers share [`super::perturbed_frame`]).
//!
//! The hit geometry comes from the [`SurfaceInteraction`]; matte's meshes compute ∂p/∂u and
//! ∂p/∂v as Mitsuba's do, its analytic shapes do not, so the loader accepts `bumpmap` on
//! meshes only. [`BumpMap::eval_pdf_at`] and [`BumpMap::sample_at`] take the geometry
//! explicitly (tested against Mitsuba at given geometry).

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

/// What `bumpmap` reads from Mitsuba's `SurfaceInteraction3f`, in world space.
#[derive(Clone, Copy, Debug)]
pub struct HitGeometry {
    pub dp_du: Vec3,
    pub dp_dv: Vec3,
    /// Geometric normal.
    pub n: Vec3,
    pub sh_frame: Frame,
}

/// Mitsuba's `bumpmap` wrapper around a nested BSDF of type `B` (the scene's: [`super::Bsdf`]).
#[derive(Clone, Debug)]
pub struct BumpMap<B> {
    pub height: Texture,
    pub nested: Box<B>,
    pub scale: f32,
    pub flip_invalid_normals: bool,
    pub use_shadowing_function: bool,
}

impl HitGeometry {
    #[inline]
    pub fn of(si: &SurfaceInteraction) -> Self {
        HitGeometry { dp_du: si.dp_du, dp_dv: si.dp_dv, n: si.n, sh_frame: si.sh_frame }
    }
}

impl<B: NestedBsdf> FromProps for BumpMap<B> {
    /// One nested BSDF, one nested `bitmap` texture of any name (the height map, as Mitsuba
    /// takes the one texture child), `scale` (default 1), `flip_invalid_normals` and
    /// `use_shadowing_function` (default true). The BSDF is built for its shape, which must be
    /// a mesh.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let nested = p.nested("bsdf");
        let [inner] = nested.as_slice() else {
            return Err(p.err(format!("needs exactly one nested BSDF, found {}", nested.len())));
        };
        let textures = p.nested("texture");
        let [height] = textures.as_slice() else {
            return Err(p.err(format!("needs exactly one nested texture (the height map), found {}", textures.len())));
        };
        if height.plugin != "bitmap" {
            return Err(crate::load::err(
                height,
                "a bumpmap needs a bitmap height texture (Mitsuba's other textures have no gradient)",
            ));
        }
        let height = p.build_texture(height)?;
        let b = p.builder();
        b.shape_dependent.set(true);
        if b.shape.as_ref().is_some_and(|s| !s.is_mesh) {
            return Err(p.err(
                "bumpmap is supported on meshes only (obj, ply, rectangle, cube): matte's analytic shapes have no ∂p/∂u, ∂p/∂v",
            ));
        }
        let scale = p.float("scale")? as f32;
        let flip_invalid_normals = p.boolean("flip_invalid_normals")?;
        let use_shadowing_function = p.boolean("use_shadowing_function")?;
        Ok(BumpMap {
            height,
            nested: Box::new(B::from_nested(p, inner)?),
            scale,
            flip_invalid_normals,
            use_shadowing_function,
        })
    }
}

impl<B: Bxdf> Bxdf for BumpMap<B> {
    /// `(f·|cos θo|, pdf)` at the hit `si`.
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        self.eval_pdf_at(si, &HitGeometry::of(si), wi, wo)
    }

    /// Samples the nested BSDF in the perturbed frame at the hit `si`.
    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.sample_at(si, &HitGeometry::of(si), wi, u_lobe, u)
    }

    /// The nested BSDF's.
    #[inline]
    fn flags(&self) -> BsdfFlags {
        self.nested.flags()
    }
}

impl<B: Bxdf> BumpMap<B> {
    /// Mitsuba's `BumpMap::frame`, relative to the shading frame (`wi` local).
    pub fn frame(&self, si: &SurfaceInteraction, wi: Vec3, g: &HitGeometry) -> Frame {
        let grad = self.height.eval_1_grad(si) * self.scale;
        let ns = g.sh_frame.n;
        let dp_du = g.dp_du + ns * (grad.x - ns.dot(g.dp_du));
        let dp_dv = g.dp_dv + ns * (grad.y - ns.dot(g.dp_dv));
        let mut n = dp_du.cross(dp_dv).normalize();
        if g.n.dot(n) < 0.0 {
            n = -n;
        }
        let mut n = g.sh_frame.to_local(n);
        if self.flip_invalid_normals && wi.z * wi.dot(n) <= 0.0 {
            n = Vec3::new(-n.x, -n.y, n.z);
        }
        let s = (g.dp_du - n * n.dot(g.dp_du)).normalize();
        Frame { s, t: n.cross(s), n }
    }

    /// `(f·|cos θo|, pdf)` at a hit with geometry `g`.
    pub fn eval_pdf_at(&self, si: &SurfaceInteraction, g: &HitGeometry, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        let frame = self.frame(si, wi, g);
        perturbed_frame::eval_pdf(&*self.nested, &frame, self.use_shadowing_function, si, wi, wo)
    }

    /// Samples the nested BSDF in the perturbed frame.
    pub fn sample_at(
        &self,
        si: &SurfaceInteraction,
        g: &HitGeometry,
        wi: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<BsdfSample> {
        let frame = self.frame(si, wi, g);
        perturbed_frame::sample(&*self.nested, &frame, self.use_shadowing_function, si, wi, u_lobe, u)
    }
}
