//! Orthonormal frames (Mitsuba `Frame3f`): `s`, `t`, `n` with `n` the local +z.

use glam::Vec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// A frame around `n` with Mitsuba's `coordinate_system` (Duff et al. 2017, "Building an
    /// orthonormal basis, revisited"), so tangents agree with Mitsuba's where that matters
    /// (anisotropic lobes).
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let (s, t) = coordinate_system(n);
        Frame { s, t, n }
    }

    /// Mitsuba's shading frame (`SurfaceInteraction::initialize_sh_frame`,
    /// `include/mitsuba/render/interaction.h`): `s` is `dp_du` made orthogonal to `n` and
    /// normalised, `t = n × s`; where `dp_du` is zero (or parallel to `n`), `s` comes from
    /// [`coordinate_system`]. Anisotropic BSDFs and tangent-space normal maps depend on it.
    #[inline]
    pub fn from_normal_dpdu(n: Vec3, dp_du: Vec3) -> Self {
        let s = (dp_du - n * n.dot(dp_du)).normalize_or_zero();
        let s = if s == Vec3::ZERO { coordinate_system(n).0 } else { s };
        Frame { s, t: n.cross(s), n }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

/// Two unit tangents completing `n` to a right-handed orthonormal basis (Duff et al. 2017).
#[inline]
pub fn coordinate_system(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(n.x * n.x * a * sign + 1.0, b * sign, -n.x * sign), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}
