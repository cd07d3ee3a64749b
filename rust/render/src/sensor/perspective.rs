//! Mitsuba's `perspective` sensor (`src/sensors/perspective.cpp`, docs/renderer-semantics.md §4): x_fov from
//! `fov_axis` with the full-film aspect; image x grows towards local −x and y downwards;
//! the ray starts on the near plane. [`Camera`] is any of the sensors. The reads the sensors
//! share are here too: the clip range and focus distance of Mitsuba's `ProjectiveCamera`
//! ([`clip_range`]), the field of view (`parse_fov`, [`field_of_view`], also read by the
//! `projector` emitter) and a rigid `to_world` ([`rigid_to_world`]).

use crate::geometry::Ray;
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;

/// The sensor: `perspective`, `orthographic` or `thinlens`.
#[derive(Clone, Debug)]
pub enum Camera {
    Perspective(PerspectiveCamera),
    Orthographic(super::orthographic::OrthographicCamera),
    ThinLens(super::thinlens::ThinLensCamera),
}

impl Camera {
    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left),
    /// drawing the aperture sample from `sampler` if the sensor needs one (`thinlens`: the
    /// 2-D dimension right after the film position's, as Mitsuba's
    /// `SamplingIntegrator::render_sample` draws it).
    #[inline]
    pub fn sample_ray(&self, film_pos: Vec2, sampler: &mut crate::sampler::Sampler) -> Ray {
        match self {
            Camera::Perspective(c) => c.ray(film_pos),
            Camera::Orthographic(c) => c.ray(film_pos),
            Camera::ThinLens(c) => c.ray(film_pos, sampler.next_2d()),
        }
    }

    /// The primary ray through `film_pos` for sensors without an aperture sample; a
    /// `thinlens` traces from its aperture's centre.
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        match self {
            Camera::Perspective(c) => c.ray(film_pos),
            Camera::Orthographic(c) => c.ray(film_pos),
            Camera::ThinLens(c) => c.ray(film_pos, Vec2::splat(0.5)),
        }
    }
}

/// A connection from a scene point to the camera (Mitsuba's sensor `DirectionSample3f`).
#[derive(Clone, Copy, Debug)]
pub struct SensorSample {
    /// Full-film pixel position the point projects to.
    pub film_pos: Vec2,
    /// The camera's position.
    pub p: Vec3,
    /// Importance over squared distance.
    pub weight: f32,
}

#[derive(Clone, Debug)]
pub struct PerspectiveCamera {
    to_world: Affine3A,
    to_local: Affine3A,
    /// tan(x_fov / 2).
    tan_half: f32,
    aspect: f32,
    film_size: Vec2,
    principal_offset: Vec2,
    near_clip: f32,
    far_clip: f32,
}

/// Which axis `fov` refers to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    X,
    Y,
    Diagonal,
    Smaller,
    Larger,
}

/// tan(x_fov / 2) for `fov_deg` along `axis` on an image of aspect width/height (Mitsuba
/// `parse_fov`, `src/render/sensor.cpp`).
pub fn x_half_tan(fov_deg: f64, axis: FovAxis, aspect: f64) -> f64 {
    let half = (fov_deg.to_radians() * 0.5).tan();
    match axis {
        FovAxis::X => half,
        FovAxis::Y => half * aspect,
        FovAxis::Diagonal => half / (1.0 + 1.0 / (aspect * aspect)).sqrt(),
        FovAxis::Smaller => {
            if aspect > 1.0 {
                half * aspect
            } else {
                half
            }
        }
        FovAxis::Larger => {
            if aspect > 1.0 {
                half
            } else {
                half * aspect
            }
        }
    }
}

impl PerspectiveCamera {
    /// Reads `perspective`: a rigid `to_world`, the field of view, the clip range and the
    /// principal point offsets. The camera is made for the full film size by the returned
    /// function (the sensor's film is read after the camera's properties).
    pub(crate) fn from_props(p: &mut PluginProps) -> Result<impl FnOnce((u32, u32)) -> Self + use<>, SceneError> {
        let to_world = rigid_to_world(p)?;
        let (fov_deg, axis) = field_of_view(p)?;
        let (near, far, _) = clip_range(p)?;
        let ppo = Vec2::new(
            principal_point_offset(p, "principal_point_offset_x")?,
            principal_point_offset(p, "principal_point_offset_y")?,
        );
        Ok(move |film| PerspectiveCamera::new(to_world, fov_deg, axis, film, ppo, near, far))
    }

    /// `fov_deg` along `axis`; `film` is the full film size in pixels.
    pub fn new(
        to_world: Affine3A,
        fov_deg: f64,
        axis: FovAxis,
        film: (u32, u32),
        principal_offset: Vec2,
        near_clip: f32,
        far_clip: f32,
    ) -> Self {
        let aspect = film.0 as f64 / film.1 as f64;
        let x_half = x_half_tan(fov_deg, axis, aspect);
        PerspectiveCamera {
            to_world,
            to_local: to_world.inverse(),
            tan_half: x_half as f32,
            aspect: aspect as f32,
            film_size: Vec2::new(film.0 as f32, film.1 as f32),
            principal_offset,
            near_clip,
            far_clip,
        }
    }

    /// The x fov in degrees for a `focal_length` in mm (on the 36×24 frame, diagonal).
    pub fn focal_length_to_diagonal_fov(mm: f64) -> f64 {
        2.0 * ((36.0f64 * 36.0 + 24.0 * 24.0).sqrt() / (2.0 * mm)).atan().to_degrees()
    }

    /// Mitsuba's `PerspectiveCamera::sample_direction` (`src/sensors/perspective.cpp`): the
    /// connection from world point `p` to the camera, for the particle tracer. `None` outside
    /// the clip range or the film. Returns the full-film pixel position, the camera position
    /// and the importance `W(d)/dist²`, W = 1/(A·cos³θ) with A the image rectangle's area at
    /// unit distance.
    #[inline]
    pub fn sample_direction(&self, p: Vec3) -> Option<SensorSample> {
        let local = self.to_local.transform_point3(p);
        if !(local.z >= self.near_clip && local.z <= self.far_clip) {
            return None;
        }
        let s = Vec2::new(
            0.5 * (1.0 - local.x / (local.z * self.tan_half)),
            0.5 * (1.0 - local.y * self.aspect / (local.z * self.tan_half)),
        ) - self.principal_offset;
        if !(s.cmpge(Vec2::ZERO).all() && s.cmple(Vec2::ONE).all()) {
            return None;
        }
        let dist2 = local.length_squared();
        let cos = local.z / dist2.sqrt();
        let area = 4.0 * self.tan_half * self.tan_half / self.aspect;
        let importance = 1.0 / (area * cos * cos * cos);
        Some(SensorSample {
            film_pos: s * self.film_size,
            p: self.to_world.transform_point3(Vec3::ZERO),
            weight: importance / dist2,
        })
    }

    /// The primary ray through full-film pixel position `film_pos` (pixels, origin top-left).
    #[inline]
    pub fn ray(&self, film_pos: Vec2) -> Ray {
        let s = film_pos / self.film_size + self.principal_offset;
        let local = Vec3::new((1.0 - 2.0 * s.x) * self.tan_half, (1.0 - 2.0 * s.y) * self.tan_half / self.aspect, 1.0);
        let dl = local.normalize();
        let d = self.to_world.transform_vector3(dl).normalize();
        let inv_z = 1.0 / dl.z;
        let o = self.to_world.transform_point3(Vec3::ZERO) + d * (self.near_clip * inv_z);
        Ray::new(o, d, (self.far_clip - self.near_clip) * inv_z)
    }
}

/// A principal point offset (a fraction of the film size). Mitsuba takes any float; a NaN or
/// one so large that the ray direction overflows f32 would give NaN camera rays, so matte
/// requires a finite value within ±10⁶ film sizes.
fn principal_point_offset(p: &mut PluginProps, name: &str) -> Result<f32, SceneError> {
    let v = p.float(name)?;
    if v.is_nan() || v.abs() > 1e6 {
        return Err(p.prop_err(name, format!("must be a finite fraction of the film size within ±1e6, got {v}")));
    }
    Ok(v as f32)
}

/// `ProjectiveCamera`'s properties (`src/render/sensor.cpp`): near_clip, far_clip and
/// focus_distance (default far_clip; a positive finite distance), which every sensor reads and
/// only `thinlens` uses.
pub(crate) fn clip_range(p: &mut PluginProps) -> Result<(f32, f32, f32), SceneError> {
    let near = p.positive("near_clip")? as f32;
    let far = p.positive("far_clip")? as f32;
    if far <= near {
        return Err(p.err(format!("far_clip ({far}) must exceed near_clip ({near})")));
    }
    let focus = p.float_or("focus_distance", far as f64)?;
    if !(focus > 0.0 && focus.is_finite()) {
        return Err(p.prop_err("focus_distance", format!("must be a positive distance, got {focus}")));
    }
    Ok((near, far, focus as f32))
}

/// `to_world` of `perspective` and `thinlens`: a rotation and translation.
pub(crate) fn rigid_to_world(p: &mut PluginProps) -> Result<Affine3A, SceneError> {
    let to_world = p.transform("to_world")?;
    if has_scale(&to_world) {
        return Err(p.prop_err(
            "to_world",
            "contains a scale or shear; scale factors are not allowed in a camera transform (as in Mitsuba)",
        ));
    }
    Ok(to_world)
}

/// Mitsuba's `Transform::has_scale` (`include/mitsuba/core/transform.h`), used by the
/// perspective sensor: the rows of the linear part must be orthonormal to 1e-3
/// (|Σₖ mᵢₖ mⱼₖ − δᵢⱼ| ≤ 1e-3). So a shear is a scale, and a mirror is not.
fn has_scale(m: &Affine3A) -> bool {
    let rows = [m.matrix3.row(0), m.matrix3.row(1), m.matrix3.row(2)];
    (0..3).any(|i| (i..3).any(|j| (rows[i].dot(rows[j]) - if i == j { 1.0 } else { 0.0 }).abs() > 1e-3))
}

/// The field of view as `perspective` reads it (`src/render/sensor.cpp`, `parse_fov`), also
/// read by the `projector` emitter: `fov` in degrees with `fov_axis` (default x), or
/// `focal_length` (default "50mm", a diagonal field of view), never both.
pub(crate) fn field_of_view(p: &mut PluginProps) -> Result<(f64, FovAxis), SceneError> {
    let fov = p.float_opt("fov")?;
    let focal = p.string_opt("focal_length")?;
    match (fov, focal) {
        (Some(_), Some(_)) => Err(p.err("give either fov or focal_length, not both")),
        (Some(f), None) => {
            if !(f > 0.0 && f < 180.0) {
                return Err(p.prop_err("fov", format!("must be in (0, 180) degrees, got {f}")));
            }
            Ok((f, FovAxis::from_props(p)?))
        }
        (None, _) => Ok((PerspectiveCamera::focal_length_to_diagonal_fov(focal_length_mm(p)?), FovAxis::Diagonal)),
    }
}

/// `focal_length` (default "50mm") in millimetres.
fn focal_length_mm(p: &mut PluginProps) -> Result<f64, SceneError> {
    let text = p.string("focal_length")?;
    text.trim()
        .strip_suffix("mm")
        .unwrap_or(&text)
        .trim()
        .parse()
        .ok()
        .filter(|v: &f64| *v > 0.0)
        .ok_or_else(|| p.prop_err("focal_length", format!("must look like \"50mm\", got \"{text}\"")))
}

impl FovAxis {
    /// `fov_axis` (default x): x, y, diagonal, smaller or larger.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        Ok(match p.string("fov_axis")?.to_lowercase().as_str() {
            "x" => FovAxis::X,
            "y" => FovAxis::Y,
            "diagonal" => FovAxis::Diagonal,
            "smaller" => FovAxis::Smaller,
            "larger" => FovAxis::Larger,
            other => {
                let message = format!("must be x, y, diagonal, smaller or larger, got \"{other}\"");
                return Err(p.prop_err("fov_axis", message));
            }
        })
    }
}
