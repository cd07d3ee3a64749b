//! A scene's shapes in one Embree scene, built and queried as Mitsuba 3 does for its scalar
//! variants (`src/render/scene_embree.inl`: `RTC_BUILD_QUALITY_HIGH`, no robust flag,
//! `tnear` = 0, `tfar` = the ray's `maxt`, `rtcIntersect1` / `rtcOccluded1` per ray): one
//! triangle geometry per mesh, and, unless they are left to the CWBVH, one user geometry per
//! analytic shape (sphere, disk, cylinder) whose callbacks call the shape's own exact
//! intersection, as Mitsuba's `embree_intersect` does.

use super::embree_api::{self as rtc, Api, BoundsArgs, IntersectContext, RtcRay, RtcRayHit, UserQueryArgs};
use super::hit::Hit;
use crate::geometry::Ray;
use crate::shape::{Geometry, Shape};
use glam::{Vec2, Vec3};

pub struct EmbreeScene {
    api: &'static Api,
    scene: rtc::RTCScene,
    /// Embree geometry id → index of the shape in the scene.
    shape_of_geometry: Vec<u32>,
    /// Copies of the analytic shapes the user geometries point to (never moved or resized
    /// after the build: Embree holds their addresses).
    analytic: Box<[Geometry]>,
    triangles: usize,
}

// SAFETY: a committed Embree scene is immutable and its queries are thread-safe (Embree 3
// API docs, `rtcIntersect1`: "may be called from multiple threads").
unsafe impl Send for EmbreeScene {}
unsafe impl Sync for EmbreeScene {}

impl EmbreeScene {
    /// Builds the Embree scene of every mesh in `shapes`, and of every analytic shape too
    /// when `with_analytic` (`Ok(None)` if that leaves nothing), or says why Embree is
    /// unavailable.
    pub fn build(shapes: &[Shape], with_analytic: bool) -> Result<Option<Self>, String> {
        let meshes: Vec<(u32, &crate::shape::Triangles)> = shapes
            .iter()
            .enumerate()
            .filter_map(|(i, s)| match &s.geometry {
                Geometry::Triangles(m) if !m.mesh.triangles.is_empty() => Some((i as u32, m)),
                _ => None,
            })
            .collect();
        let analytic: Vec<(u32, Geometry)> = if with_analytic {
            shapes
                .iter()
                .enumerate()
                .filter(|(_, s)| s.geometry.analytic_bounds().is_some())
                .map(|(i, s)| (i as u32, s.geometry.clone()))
                .collect()
        } else {
            Vec::new()
        };
        if meshes.is_empty() && analytic.is_empty() {
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
            let (analytic_shapes, analytic): (Vec<u32>, Vec<Geometry>) = analytic.into_iter().unzip();
            let mut this = EmbreeScene {
                api,
                scene,
                shape_of_geometry: Vec::new(),
                analytic: analytic.into_boxed_slice(),
                triangles: 0,
            };
            let attach = |this: &mut Self, geom: rtc::RTCGeometry, shape: u32| {
                (api.commit_geometry)(geom);
                let id = (api.attach_geometry)(scene, geom) as usize;
                (api.release_geometry)(geom);
                if this.shape_of_geometry.len() <= id {
                    this.shape_of_geometry.resize(id + 1, u32::MAX);
                }
                this.shape_of_geometry[id] = shape;
            };
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
                attach(&mut this, geom, shape);
                this.triangles += n_tri;
            }
            for (k, &shape) in analytic_shapes.iter().enumerate() {
                let geom = (api.new_geometry)(api.device, rtc::GEOMETRY_TYPE_USER);
                if geom.is_null() {
                    return Err(format!("Embree user geometry failed (error {})", (api.get_device_error)(api.device)));
                }
                let ptr = &this.analytic[k] as *const Geometry as *mut std::ffi::c_void;
                (api.set_geometry_user_primitive_count)(geom, 1);
                (api.set_geometry_user_data)(geom, ptr);
                (api.set_geometry_bounds_function)(geom, analytic_bounds, std::ptr::null_mut());
                (api.set_geometry_intersect_function)(geom, analytic_intersect);
                (api.set_geometry_occluded_function)(geom, analytic_occluded);
                attach(&mut this, geom, shape);
            }
            (api.commit_scene)(scene);
            match (api.get_device_error)(api.device) {
                0 => Ok(Some(this)),
                e => Err(format!("Embree scene build failed (error {e})")),
            }
        }
    }

    /// Triangles and analytic shapes in the scene.
    pub fn primitive_count(&self) -> usize {
        self.triangles + self.analytic.len()
    }

    /// Closest mesh hit along `ray` within `maxt`.
    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<Hit> {
        if !traceable(ray) {
            return None;
        }
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

    /// The closest hits of the `active` ones of eight rays in one `rtcIntersect8` call
    /// (Embree's packet query); inactive lanes get `None`.
    #[inline]
    pub fn intersect8(&self, rays: &[Ray; 8], active: [bool; 8]) -> [Option<Hit>; 8] {
        let mut p = rtc::RtcRayHit8 { f: [[0.0; 8]; 20] };
        let valid = valid_lanes(rays, active);
        for (i, r) in rays.iter().enumerate() {
            put_soa_ray(&mut p.f, i, r);
            p.f[18][i] = f32::from_bits(rtc::INVALID_GEOMETRY_ID);
        }
        let mut ctx = IntersectContext::incoherent();
        // SAFETY: a committed scene, an initialised context, a 32-byte aligned RTCRayHit8 and
        // a 32-byte aligned valid mask for its lanes.
        unsafe { (self.api.intersect8)(&valid, self.scene, &mut ctx, &mut p) };
        std::array::from_fn(|i| {
            let geom = p.f[18][i].to_bits();
            (valid.0[i] != 0 && geom != rtc::INVALID_GEOMETRY_ID).then(|| Hit {
                t: p.f[8][i],
                shape: self.shape_of_geometry[geom as usize],
                prim: p.f[17][i].to_bits(),
                bary: Vec2::new(p.f[15][i], p.f[16][i]),
            })
        })
    }

    /// Whether a mesh blocks each of the `active` ones of eight rays, in one `rtcOccluded8`
    /// call; inactive lanes give `false`.
    #[inline]
    pub fn occluded8(&self, rays: &[Ray; 8], active: [bool; 8]) -> [bool; 8] {
        let mut p = rtc::RtcRay8 { f: [[0.0; 8]; 12] };
        let valid = valid_lanes(rays, active);
        for (i, r) in rays.iter().enumerate() {
            put_soa_ray(&mut p.f, i, r);
        }
        let mut ctx = IntersectContext::incoherent();
        // SAFETY: as in `intersect8`, with a 32-byte aligned RTCRay8; Embree sets `tfar` to
        // −∞ for the blocked lanes.
        unsafe { (self.api.occluded8)(&valid, self.scene, &mut ctx, &mut p) };
        std::array::from_fn(|i| valid.0[i] != 0 && p.f[8][i] == f32::NEG_INFINITY)
    }

    /// Whether a mesh blocks `ray` before `maxt`.
    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        // An empty segment (maxt ≤ 0, or NaN) is never blocked; checked because a negative
        // `tfar` would read as Embree's "blocked" below.
        if !traceable(ray) {
            return false;
        }
        let mut r = rtc_ray(ray);
        let mut ctx = IntersectContext::incoherent();
        // SAFETY: as in `intersect`; Embree sets `tfar` to −∞ when the ray is blocked.
        unsafe { (self.api.occluded1)(self.scene, &mut ctx, &mut r) };
        r.tfar == f32::NEG_INFINITY
    }
}

/// Embree's bounds callback: the analytic shape's world-space box.
unsafe extern "C" fn analytic_bounds(args: *const BoundsArgs) {
    // SAFETY: Embree passes valid arguments; the user pointer is a `Geometry` that
    // `EmbreeScene` owns for the scene's lifetime.
    unsafe {
        let args = &*args;
        let geometry = &*(args.geometry_user_ptr as *const Geometry);
        let (lo, hi) = geometry.analytic_bounds().unwrap_or((Vec3::ZERO, Vec3::ZERO));
        *args.bounds_o = rtc::RtcBounds { lower: lo.to_array(), align0: 0.0, upper: hi.to_array(), align1: 0.0 };
    }
}

/// Ray `i` of the `n` structure-of-arrays rays at `base` (`tfar` as `maxt`).
#[inline(always)]
unsafe fn soa_ray(base: *const f32, n: usize, i: usize) -> Ray {
    // SAFETY: the caller passes Embree's ray block of `n` rays and `i < n`.
    let f = |k: usize| unsafe { *base.add(k * n + i) };
    Ray::new(Vec3::new(f(0), f(1), f(2)), Vec3::new(f(4), f(5), f(6)), f(8))
}

/// Calls `hit(i, t)` for every valid lane `i` of Embree's ray block that the analytic shape
/// hits at a distance `t` beyond the lane's `tnear`.
///
/// # Safety
/// `args` is what Embree passes to a user-geometry callback: `n` lanes of a ray (or ray-hit)
/// block, and a user pointer to a `Geometry` owned by `EmbreeScene`.
unsafe fn for_each_analytic_hit(args: &UserQueryArgs, mut hit: impl FnMut(usize, f32)) {
    // SAFETY: as the function's contract says.
    unsafe {
        let geometry = &*(args.geometry_user_ptr as *const Geometry);
        let n = args.n as usize;
        for i in 0..n {
            if *args.valid.add(i) == 0 {
                continue;
            }
            let ray = soa_ray(args.rayhit, n, i);
            let tnear = *args.rayhit.add(3 * n + i);
            if let Some(t) = geometry.intersect_analytic(&ray)
                && t > tnear
            {
                hit(i, t);
            }
        }
    }
}

/// Embree's intersect callback for an analytic shape: the shape's exact hit distance in
/// `(tnear, tfar)`; a hit shortens `tfar` and records the ids (no barycentrics).
unsafe extern "C" fn analytic_intersect(args: *const UserQueryArgs) {
    // SAFETY: Embree passes `n` valid lanes of a ray-hit block and a live context; the user
    // pointer is a `Geometry` owned by `EmbreeScene`.
    unsafe {
        let args = &*args;
        let n = args.n as usize;
        for_each_analytic_hit(args, |i, t| {
            let put = |k: usize, v: f32| *args.rayhit.add(k * n + i) = v;
            let put_u = |k: usize, v: u32| *(args.rayhit.add(k * n + i) as *mut u32) = v;
            put(8, t);
            put(15, 0.0);
            put(16, 0.0);
            put_u(17, args.prim_id);
            put_u(18, args.geom_id);
            put_u(19, (*args.context).inst_id[0]);
        });
    }
}

/// Embree's occluded callback for an analytic shape: `tfar = −∞` when the shape blocks.
unsafe extern "C" fn analytic_occluded(args: *const UserQueryArgs) {
    // SAFETY: as in `analytic_intersect`, with a ray block (no hits).
    unsafe {
        let args = &*args;
        let n = args.n as usize;
        for_each_analytic_hit(args, |i, _| *args.rayhit.add(8 * n + i) = f32::NEG_INFINITY);
    }
}

impl Drop for EmbreeScene {
    fn drop(&mut self) {
        // SAFETY: the scene was created by `build` and is released once.
        unsafe { (self.api.release_scene)(self.scene) };
    }
}

/// Embree's `|x| ≤ FLT_LARGE` bound on origins and directions (`common/math/constants.h`).
const FLT_LARGE: f32 = 1.844e18;

/// Whether Embree may be asked about `ray`: finite origin and direction within Embree's range
/// and a non-empty segment. Debian's Embree checks `ray.valid()` with an assertion that aborts
/// the process; matte's odd inputs (NaN from a broken transform, a zero-length segment) get
/// "no hit" here instead, as the CWBVH gives them.
#[inline(always)]
fn traceable(ray: &Ray) -> bool {
    // `cmple` is false for NaN (where `max_element` would skip it).
    let bound = Vec3::splat(FLT_LARGE);
    ray.o.abs().cmple(bound).all() && ray.d.abs().cmple(bound).all() && ray.maxt > 0.0
}

/// Embree's valid mask (−1 valid, 0 not) for the active lanes it may be asked about.
#[inline(always)]
fn valid_lanes(rays: &[Ray; 8], active: [bool; 8]) -> rtc::ValidMask8 {
    rtc::ValidMask8(std::array::from_fn(|i| if active[i] && traceable(&rays[i]) { -1 } else { 0 }))
}

/// Writes `r` into lane `i` of Embree's structure-of-arrays ray fields (origin, tnear = 0,
/// direction, time = 0, tfar = `maxt`, mask = all).
#[inline(always)]
fn put_soa_ray<const K: usize>(f: &mut [[f32; 8]; K], i: usize, r: &Ray) {
    let fields = [r.o.x, r.o.y, r.o.z, 0.0, r.d.x, r.d.y, r.d.z, 0.0, r.maxt, f32::from_bits(u32::MAX)];
    for (k, v) in fields.into_iter().enumerate() {
        f[k][i] = v;
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
