//! Mitsuba's `thinlens` sensor (`src/sensors/thinlens.cpp`): the `perspective` projection
//! (no principal point offset) with a circular aperture of radius `aperture_radius` at the
//! camera origin, focused at `focus_distance` (default: far_clip, `ProjectiveCamera`,
//! `src/render/sensor.cpp`). For film position s the near-plane point of the perspective
//! projection is scaled onto the focal plane z = focus_distance; the aperture point is
//! `aperture_radius · square_to_uniform_disk_concentric(u)` on z = 0, u the second 2-D
//! sample of the camera sample (`SamplingIntegrator::render_sample` draws it right after the
//! film position, `src/render/integrator.cpp`); the ray leaves the aperture point towards
//! the focal point, starts where it crosses z = near_clip and ends at z = far_clip. Its
//! weight is 1.

use super::projective::{FovAxis, clip_range, field_of_view, rigid_to_world, x_half_tan};
use crate::geometry::Ray;
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec2, Vec3};
use matte_brdf::sampling::square_to_uniform_disk_concentric;
use matte_scene_file::SceneError;

#[derive(Clone, Debug)]
pub struct ThinLensCamera {
    to_world: Affine3A,
    /// tan(x_fov / 2).
    tan_half: f32,
    aspect: f32,
    film_size: Vec2,
    aperture_radius: f32,
    focus_distance: f32,
    near_clip: f32,
    far_clip: f32,
}

impl ThinLensCamera {
    /// Reads `thinlens`: as `perspective` without the principal point, plus `aperture_radius`
    /// (no default in Mitsuba, `props.get<float>`; matte also rejects a negative or non-finite
    /// radius) and `focus_distance`. The camera is made for the full film size by the returned
    /// function (the sensor's film is read after it).
    pub(crate) fn from_props(p: &mut PluginProps) -> Result<impl FnOnce((u32, u32)) -> Self + use<>, SceneError> {
        let to_world = rigid_to_world(p)?;
        let (fov_deg, axis) = field_of_view(p)?;
        let (near, far, focus) = clip_range(p)?;
        let radius = p
            .float_opt("aperture_radius")?
            .ok_or_else(|| p.err("needs the property \"aperture_radius\" (as in Mitsuba, it has no default)"))?;
        if !(radius >= 0.0 && radius.is_finite()) {
            return Err(p.prop_err("aperture_radius", format!("must be a finite radius ≥ 0, got {radius}")));
        }
        Ok(move |film| ThinLensCamera::new(to_world, fov_deg, axis, film, radius as f32, focus, near, far))
    }

    /// `fov_deg` along `axis`; `film` is the full film size in pixels. An aperture radius of
    /// 0 becomes 2⁻²⁴ (Mitsuba: "Can't have a zero aperture radius", `dr::Epsilon<float>`).
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        to_world: Affine3A,
        fov_deg: f64,
        axis: FovAxis,
        film: (u32, u32),
        aperture_radius: f32,
        focus_distance: f32,
        near_clip: f32,
        far_clip: f32,
    ) -> Self {
        let aspect = film.0 as f64 / film.1 as f64;
        ThinLensCamera {
            to_world,
            tan_half: x_half_tan(fov_deg, axis, aspect) as f32,
            aspect: aspect as f32,
            film_size: Vec2::new(film.0 as f32, film.1 as f32),
            aperture_radius: if aperture_radius == 0.0 { f32::EPSILON / 2.0 } else { aperture_radius },
            focus_distance,
            near_clip,
            far_clip,
        }
    }

    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left)
    /// from aperture sample `u` ∈ [0, 1)².
    #[inline]
    pub fn ray(&self, film_pos: Vec2, u: Vec2) -> Ray {
        let s = film_pos / self.film_size;
        // The perspective direction with z = 1: the focal point is it times focus_distance.
        let local = Vec3::new((1.0 - 2.0 * s.x) * self.tan_half, (1.0 - 2.0 * s.y) * self.tan_half / self.aspect, 1.0);
        let focus_p = local * self.focus_distance;
        let a = self.aperture_radius * square_to_uniform_disk_concentric(u);
        let aperture_p = Vec3::new(a.x, a.y, 0.0);
        let dl = (focus_p - aperture_p).normalize();
        // Normalised as matte's `perspective` does (`to_world` may deviate from a rotation by 1e-3).
        let d = self.to_world.transform_vector3(dl).normalize();
        let inv_z = 1.0 / dl.z;
        let (near_t, far_t) = (self.near_clip * inv_z, self.far_clip * inv_z);
        let o = self.to_world.transform_point3(aperture_p) + d * near_t;
        Ray::new(o, d, far_t - near_t)
    }
}
