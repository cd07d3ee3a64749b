//! The renderable scene: shapes with their BSDFs and emitters, the acceleration structure,
//! and the queries integrators need (Mitsuba `Scene`: intersection, emitter selection with
//! the `sampling_weight` pmf, light sampling with a visibility test, emitter densities).

use crate::accel::{Accel, Hit};
use crate::bsdf::Bsdf;
use crate::emitter::{Emitter, EmitterSample, Light};
use crate::geometry::{Ray, ray};
use crate::shape::{Shape, SurfaceInteraction};
use glam::{Vec2, Vec3};

pub struct Scene {
    pub shapes: Vec<Shape>,
    pub bsdfs: Vec<Bsdf>,
    pub emitters: Vec<Emitter>,
    /// Selection probability of each emitter (Mitsuba: ∝ `sampling_weight`, default uniform).
    emitter_pmf: Vec<f32>,
    emitter_cdf: Vec<f32>,
    /// Index of the environment emitter (`constant`), if any.
    pub environment: Option<u32>,
    accel: Accel,
    /// Wall time of building `accel` (for `matte bench`'s build-vs-render share).
    accel_build_seconds: f64,
}

impl Scene {
    /// Builds the acceleration structure. `sampling_weights[i]` belongs to `emitters[i]`.
    pub fn new(shapes: Vec<Shape>, bsdfs: Vec<Bsdf>, emitters: Vec<Emitter>, sampling_weights: Vec<f32>) -> Self {
        let t0 = std::time::Instant::now();
        let accel = Accel::build(&shapes);
        let accel_build_seconds = t0.elapsed().as_secs_f64();
        let total: f32 = sampling_weights.iter().sum();
        let emitter_pmf: Vec<f32> =
            sampling_weights.iter().map(|w| if total > 0.0 { w / total } else { 0.0 }).collect();
        let mut acc = 0.0;
        let emitter_cdf = emitter_pmf
            .iter()
            .map(|p| {
                acc += p;
                acc
            })
            .collect();
        let environment = emitters.iter().position(Emitter::is_environment).map(|i| i as u32);
        Scene { shapes, bsdfs, emitters, emitter_pmf, emitter_cdf, environment, accel, accel_build_seconds }
    }

    pub fn primitive_count(&self) -> usize {
        self.accel.primitive_count()
    }

    /// Rebuilds the acceleration structure with the meshes in `backend` (for comparing
    /// backends on one loaded scene), or says why `backend` is unavailable.
    pub fn set_accel_backend(&mut self, backend: crate::accel::Backend) -> Result<(), String> {
        let t0 = std::time::Instant::now();
        self.accel = Accel::build_with(&self.shapes, backend)?;
        self.accel_build_seconds = t0.elapsed().as_secs_f64();
        Ok(())
    }

    /// The structure tracing the meshes (Embree, or the CWBVH without it).
    pub fn accel_backend(&self) -> crate::accel::Backend {
        self.accel.backend()
    }

    pub fn accel_build_seconds(&self) -> f64 {
        self.accel_build_seconds
    }

    #[inline]
    pub fn intersect(&self, ray: &Ray) -> Option<SurfaceInteraction> {
        let hit = self.accel.intersect(ray, &self.shapes)?;
        Some(self.interaction(ray, hit))
    }

    #[inline]
    pub fn occluded(&self, ray: &Ray) -> bool {
        self.accel.occluded(ray, &self.shapes)
    }

    /// The closest hits of the `active` ones of eight rays in one batched query (inactive
    /// lanes: `None`); [`Self::interaction`] turns each into what [`Self::intersect`] gives.
    #[inline]
    pub fn intersect8(&self, rays: &[Ray; 8], active: [bool; 8]) -> [Option<Hit>; 8] {
        self.accel.intersect8(rays, active, &self.shapes)
    }

    /// The surface interaction of `ray`'s hit `hit`.
    #[inline]
    pub fn interaction(&self, ray: &Ray, hit: Hit) -> SurfaceInteraction {
        self.shapes[hit.shape as usize].geometry.interaction(ray, hit.t, hit.prim, hit.bary, hit.shape)
    }

    /// [`Self::occluded`] for the `active` ones of eight rays in one batched query; inactive
    /// lanes give `false`.
    #[inline]
    pub fn occluded8(&self, rays: &[Ray; 8], active: [bool; 8]) -> [bool; 8] {
        self.accel.occluded8(rays, active, &self.shapes)
    }

    #[inline]
    pub fn bsdf(&self, si: &SurfaceInteraction) -> &Bsdf {
        &self.bsdfs[self.shapes[si.shape as usize].bsdf as usize]
    }

    /// The area emitter of the hit shape, if any.
    #[inline]
    pub fn surface_emitter(&self, si: &SurfaceInteraction) -> Option<u32> {
        self.shapes[si.shape as usize].emitter
    }

    /// Picks an emitter with `u` ∈ [0,1) and samples it from the surface point `si`. Returns
    /// the sample with `pdf` and `weight` including the selection pmf, or `None` if the light
    /// emits nothing towards `si`. Visibility is *not* tested: integrators trace the
    /// [`Self::shadow_ray`] only when the BSDF lets the light contribute, which saves the
    /// shadow rays towards lights behind the surface. Mitsuba traces the shadow ray first
    /// (`Scene::sample_emitter_direction(.., test_visibility=true)`); the estimate is the same.
    #[inline]
    pub fn sample_emitter_direction(&self, si: &SurfaceInteraction, u: Vec2) -> Option<EmitterSample> {
        let (idx, pmf, ux) = self.sample_emitter(u.x)?;
        let mut es = self.emitters[idx].sample_direction(si.p, Vec2::new(ux, u.y), &self.shapes)?;
        es.pdf *= pmf;
        es.weight /= pmf;
        Some(es)
    }

    /// Picks an emitter with `u` ∈ [0,1) by the selection pmf (Mitsuba `Scene::sample_emitter`):
    /// its index, its pmf and `u` rescaled to [0, 1) for reuse.
    #[inline]
    pub fn sample_emitter(&self, u: f32) -> Option<(usize, f32, f32)> {
        if self.emitters.is_empty() {
            return None;
        }
        let idx = self.emitter_cdf.partition_point(|&c| c <= u).min(self.emitters.len() - 1);
        let pmf = self.emitter_pmf[idx];
        if pmf <= 0.0 {
            return None;
        }
        let lo = if idx == 0 { 0.0 } else { self.emitter_cdf[idx - 1] };
        Some((idx, pmf, ((u - lo) / pmf).clamp(0.0, 1.0 - f32::EPSILON / 2.0)))
    }

    /// The shadow ray from `si` to the emitter sample `es`, spawned as Mitsuba does: towards
    /// `es.p`, or along `es.d` for lights at infinity. Nothing blocks the segment iff
    /// [`Self::occluded`] is false for it.
    #[inline]
    pub fn shadow_ray(&self, si: &SurfaceInteraction, es: &EmitterSample) -> Ray {
        if es.dist.is_finite() { ray::spawn_ray_to(si.p, si.n, es.p) } else { ray::spawn_ray(si.p, si.n, es.d) }
    }

    /// Density (with the selection pmf) with which light sampling would have picked the
    /// environment emitter `env` in direction `d`.
    #[inline]
    pub fn pdf_environment(&self, env: u32, d: Vec3) -> f32 {
        self.emitter_pmf[env as usize] * self.emitters[env as usize].pdf_environment(d)
    }

    /// Density (with the selection pmf) with which light sampling at `ref_p` would have
    /// produced the hit `si` on emitter `emitter`, or the environment direction (`si = None`).
    #[inline]
    pub fn pdf_emitter_direction(&self, ref_p: Vec3, emitter: u32, si: Option<&SurfaceInteraction>) -> f32 {
        self.emitter_pmf[emitter as usize] * self.emitters[emitter as usize].pdf_direction(ref_p, si, &self.shapes)
    }
}
