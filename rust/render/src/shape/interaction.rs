//! A ray–surface hit with everything shading needs (Mitsuba `SurfaceInteraction3f`).

use crate::geometry::Frame;
use glam::{Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub struct SurfaceInteraction {
    pub t: f32,
    pub p: Vec3,
    /// Geometric normal (never flipped towards the ray, as in Mitsuba).
    pub n: Vec3,
    /// Shading frame; `sh_frame.n` is the interpolated normal for smooth meshes.
    pub sh_frame: Frame,
    pub uv: Vec2,
    /// Index of the shape in the scene.
    pub shape: u32,
    /// Direction towards the ray origin, in the shading frame.
    pub wi: Vec3,
    /// Triangle index and barycentrics `(b1, b2)` of the hit on a mesh (0 and zero on the
    /// analytic shapes): what `mesh_attribute` textures interpolate with.
    pub prim: u32,
    pub bary: Vec2,
    /// World-space ∂p/∂u and ∂p/∂v (Mitsuba `si.dp_du`, `si.dp_dv`; `bumpmap` reads them).
    /// Computed for meshes only (zero on the analytic shapes, where `bumpmap` is refused).
    pub dp_du: Vec3,
    pub dp_dv: Vec3,
}

impl SurfaceInteraction {
    /// A hit on an analytic shape (sphere, disk, cylinder): shading frame from the normal `n`
    /// and Mitsuba's ∂p/∂u (for the tangent only), no triangle, and ∂p/∂u, ∂p/∂v left zero
    /// (`bumpmap` is refused on these shapes). `d` is the ray direction.
    #[inline]
    pub fn analytic(t: f32, p: Vec3, n: Vec3, dp_du: Vec3, uv: Vec2, shape: u32, d: Vec3) -> Self {
        let sh_frame = Frame::from_normal_dpdu(n, dp_du);
        SurfaceInteraction {
            t,
            p,
            n,
            sh_frame,
            uv,
            shape,
            wi: sh_frame.to_local(-d),
            prim: 0,
            bary: Vec2::ZERO,
            dp_du: Vec3::ZERO,
            dp_dv: Vec3::ZERO,
        }
    }

    /// A hit at the origin with the identity shading frame and the given uv, for looking up
    /// textures and BSDFs outside a scene (tests, pointwise comparisons).
    pub fn at_uv(uv: Vec2) -> Self {
        let sh_frame = Frame { s: Vec3::X, t: Vec3::Y, n: Vec3::Z };
        SurfaceInteraction {
            t: 0.0,
            p: Vec3::ZERO,
            n: Vec3::Z,
            sh_frame,
            uv,
            shape: 0,
            wi: Vec3::Z,
            prim: 0,
            bary: Vec2::ZERO,
            dp_du: Vec3::X,
            dp_dv: Vec3::Y,
        }
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.sh_frame.to_world(v)
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        self.sh_frame.to_local(v)
    }
}

/// A point sampled on a shape's surface, seen from a reference point (Mitsuba
/// `DirectionSample3f`).
#[derive(Clone, Copy, Debug)]
pub struct DirectionSample {
    pub p: Vec3,
    /// Normal at `p` (shading normal for smooth meshes), after `flip_normals`.
    pub n: Vec3,
    pub uv: Vec2,
    /// Unit direction from the reference point to `p`.
    pub d: Vec3,
    pub dist: f32,
    /// Solid-angle density at the reference point (without the emitter-selection pmf).
    pub pdf: f32,
}
