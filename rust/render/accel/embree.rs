//! The triangle meshes of a scene in one Embree scene (one Embree triangle geometry per mesh
//! shape), built and queried as Mitsuba 3 does for its scalar variants
//! (`src/render/scene_embree.inl`: `RTC_BUILD_QUALITY_HIGH`, no robust flag, `tnear` = 0,
//! `tfar` = the ray's `maxt`, `rtcIntersect1` / `rtcOccluded1` per ray).

use super::Hit;
use super::embree_api::{self as rtc, Api, IntersectContext, RtcRay, RtcRayHit};
use crate::render::geometry::Ray;
use crate::render::shape::{Geometry, Shape};
use glam::Vec2;

pub struct EmbreeMeshes {
    api: &'static Api,
    scene: rtc::Scene,
    /// Embree geometry id → index of the shape in the scene.
    shape_of_geometry: Vec<u32>,
    triangles: usize,
}

// SAFETY: a committed Embree scene is immutable and its queries are thread-safe (Embree 3
// API docs, `rtcIntersect1`: "may be called from multiple threads").
unsafe impl Send for EmbreeMeshes {}
unsafe impl Sync for EmbreeMeshes {}

impl EmbreeMeshes {
    /// Builds the Embree scene of every mesh in `shapes` (`Ok(None)` if there is none), or
    /// says why Embree is unavailable.
    pub fn build(shapes: &[Shape]) -> Result<Option<Self>, String> {
        let meshes: Vec<(u32, &crate::render::shape::Triangles)> = shapes
            .iter()
            .enumerate()
            .filter_map(|(i, s)| match &s.geometry {
                Geometry::Triangles(m) if !m.mesh.triangles.is_empty() => Some((i as u32, m)),
                _ => None,
            })
            .collect();
        if meshes.is_empty() {
            return Ok(None);
        }
        let api = rtc::api().map_err(str::to_string)?;
        // SAFETY: every call below follows the Embree 3 API: buffers are written within the
        // sizes requested from `rtcSetNewGeometryBuffer`, geometries are committed before the
        // scene, and released once attached (the scene keeps its reference).
        unsafe {
            let scene = (api.new_scene)(api.device);
            if scene.is_null() {
                return Err(format!("rtcNewScene failed (error {})", (api.get_device_error)(api.device)));
            }
            (api.set_scene_build_quality)(scene, rtc::BUILD_QUALITY_HIGH);
            (api.set_scene_flags)(scene, rtc::SCENE_FLAG_NONE);
            let mut this = EmbreeMeshes { api, scene, shape_of_geometry: Vec::new(), triangles: 0 };
            for (shape, m) in meshes {
                let geom = (api.new_geometry)(api.device, rtc::GEOMETRY_TYPE_TRIANGLE);
                let n_vert = m.mesh.positions.len();
                let n_tri = m.mesh.triangles.len();
                let vb = (api.set_new_geometry_buffer)(geom, rtc::BUFFER_TYPE_VERTEX, 0, rtc::FORMAT_FLOAT3, 12, n_vert)
                    as *mut [f32; 3];
                let ib = (api.set_new_geometry_buffer)(geom, rtc::BUFFER_TYPE_INDEX, 0, rtc::FORMAT_UINT3, 12, n_tri)
                    as *mut [u32; 3];
                if geom.is_null() || vb.is_null() || ib.is_null() {
                    return Err(format!(
                        "Embree geometry allocation failed (error {})",
                        (api.get_device_error)(api.device)
                    ));
                }
                for (i, p) in m.mesh.positions.iter().enumerate() {
                    *vb.add(i) = p.to_array();
                }
                for (i, t) in m.mesh.triangles.iter().enumerate() {
                    *ib.add(i) = *t;
                }
                (api.commit_geometry)(geom);
                let id = (api.attach_geometry)(scene, geom);
                (api.release_geometry)(geom);
                let id = id as usize;
                if this.shape_of_geometry.len() <= id {
                    this.shape_of_geometry.resize(id + 1, u32::MAX);
                }
                this.shape_of_geometry[id] = shape;
                this.triangles += n_tri;
            }
            (api.commit_scene)(scene);
            match (api.get_device_error)(api.device) {
                0 => Ok(Some(this)),
                e => Err(format!("Embree scene build failed (error {e})")),
            }
        }
    }

    pub fn triangle_count(&self) -> usize {
        self.triangles
    }

    /// Closest mesh hit along `ray` within `maxt`.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut rh = RtcRayHit { ray: rtc_ray(ray), ..Default::default() };
        rh.hit.geom_id = rtc::INVALID_GEOMETRY_ID;
        let mut ctx = IntersectContext::incoherent();
        // SAFETY: a committed scene, an initialised context and a 16-byte aligned RTCRayHit.
        unsafe { (self.api.intersect1)(self.scene, &mut ctx, &mut rh) };
        if rh.hit.geom_id == rtc::INVALID_GEOMETRY_ID {
            return None;
        }
        Some(Hit {
            t: rh.ray.tfar,
            shape: self.shape_of_geometry[rh.hit.geom_id as usize],
            prim: rh.hit.prim_id,
            bary: Vec2::new(rh.hit.u, rh.hit.v),
        })
    }

    /// Whether a mesh blocks `ray` before `maxt`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        let mut r = rtc_ray(ray);
        let mut ctx = IntersectContext::incoherent();
        // SAFETY: as in `intersect`; Embree sets `tfar` to −∞ when the ray is blocked.
        unsafe { (self.api.occluded1)(self.scene, &mut ctx, &mut r) };
        r.tfar < 0.0
    }
}

impl Drop for EmbreeMeshes {
    fn drop(&mut self) {
        // SAFETY: the scene was created by `build` and is released once.
        unsafe { (self.api.release_scene)(self.scene) };
    }
}

/// The Embree ray for `ray`: `tnear` = 0 and `tfar` = `maxt`, as Mitsuba passes them.
#[inline(always)]
fn rtc_ray(ray: &Ray) -> RtcRay {
    RtcRay {
        org: ray.o.to_array(),
        tnear: 0.0,
        dir: ray.d.to_array(),
        time: 0.0,
        tfar: ray.maxt,
        mask: u32::MAX,
        id: 0,
        flags: 0,
    }
}
