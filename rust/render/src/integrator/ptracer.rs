//! Mitsuba's particle tracer `ptracer` (`src/integrators/ptracer.cpp` and
//! `AdjointIntegrator::render` in `src/render/integrator.cpp`, v3.9.1): paths start at the
//! emitters and every vertex is connected to the camera, splatting into the film.
//! docs/renderer-semantics.md §7 (ptracer).
//!
//! * spp × (full-film pixel count) light paths, each splatting `value·sample_scale` into the
//!   pixel its connection projects to (box filter only), sample_scale = crop pixels /
//!   (spp · film pixels); the film divides by nothing.
//! * Per path, unless `hide_emitters` (or max_depth 0): one emitter is picked by the
//!   selection pmf; an area emitter gives a uniform point connected to the camera
//!   (`L·A/pmf · W/dist² · max(0, cos)`), the others nothing (Dirac emitters are never seen).
//! * Then a light ray (`Emitter::sample_ray`, weight / pmf) is traced: at each hit with
//!   depth < max_depth (the first hit is depth 1), the vertex is connected to the camera with
//!   `β · f(wi → camera) · W/dist²`, the BSDF is sampled, and β is multiplied by the sample
//!   weight; both get the shading-normal correction |cos_s(wi)·cos_g(wo)/(cos_s(wo)·cos_g(wi))|
//!   and vanish where the shading and geometric normals disagree about a side. Russian
//!   roulette from depth > rr_depth with q = min(max(β)·η², 0.95).
//!
//! BSDFs are evaluated as for radiance (matte has no importance-transport mode), so the loader
//! refuses scenes whose BSDFs refract (those differ by η² between the two modes).

use crate::bsdf::Bxdf;
use crate::emitter::Light;
use crate::film::{Film, Image};
use crate::geometry::ray;
use crate::load::props::{FromProps, PluginProps};
use crate::sampler::{Sampler, Sampling};
use crate::scene::Scene;
use crate::sensor::Camera;
use glam::{Vec2, Vec3};
use matte_scene_file::SceneError;
use rayon::prelude::*;

#[derive(Clone, Debug, PartialEq)]
pub struct ParticleTracer {
    /// Maximum number of path segments; `u32::MAX` for Mitsuba's −1.
    pub max_depth: u32,
    pub rr_depth: u32,
    pub hide_emitters: bool,
}

impl FromProps for ParticleTracer {
    /// `samples_per_pass` (default −1, an expression in Mitsuba) is read and ignored.
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let (max_depth, rr_depth) = super::sample_integrator::depths(p)?;
        let _ = p.integer_or("samples_per_pass", -1, -1..=u32::MAX as i64)?;
        Ok(ParticleTracer { max_depth, rr_depth, hide_emitters: p.boolean("hide_emitters")? })
    }
}

/// Light paths per parallel work item (each has its own sampler stream).
const CHUNK: u64 = 4096;

/// The film being splatted into: crop-sized sums.
struct Splats {
    width: u32,
    height: u32,
    offset: Vec2,
    sum: Vec<Vec3>,
    invalid: u64,
}

impl Splats {
    #[inline]
    fn put(&mut self, film_pos: Vec2, v: Vec3) {
        if !v.is_finite() {
            self.invalid += 1;
            return;
        }
        let p = (film_pos - self.offset).floor();
        if p.x >= 0.0 && p.y >= 0.0 && (p.x as u32) < self.width && (p.y as u32) < self.height {
            self.sum[(p.y as u32 * self.width + p.x as u32) as usize] += v;
        }
    }
}

impl ParticleTracer {
    /// Renders `sampling.spp`·(film pixels) light paths; returns the image and the number of
    /// non-finite contributions dropped. The camera must be perspective (the loader checks).
    /// Each work item of [`CHUNK`] light paths is one sampler stream whose sample index
    /// advances per light path (Mitsuba seeds one sampler per work item and calls `advance`
    /// per sample, `AdjointIntegrator::render`).
    pub fn render(&self, scene: &Scene, camera: &Camera, film: &Film, sampling: Sampling) -> (Image, u64) {
        let spp = sampling.spp;
        let crop = film.crop();
        let (w, h) = (crop.size[0], crop.size[1]);
        let film_pixels = film.width() as u64 * film.height() as u64;
        let total = spp as u64 * film_pixels;
        let sample_scale = (w as f64 * h as f64 / total.max(1) as f64) as f32;
        let Camera::Perspective(cam) = camera else { panic!("ptracer needs a perspective camera (checked at load)") };
        let empty = || Splats {
            width: w,
            height: h,
            offset: Vec2::new(crop.offset[0] as f32, crop.offset[1] as f32),
            sum: vec![Vec3::ZERO; (w * h) as usize],
            invalid: 0,
        };
        let chunks = total.div_ceil(CHUNK);
        let splats = if scene.emitters.is_empty() {
            empty()
        } else {
            (0..chunks)
                .into_par_iter()
                .fold(empty, |mut acc, c| {
                    let mut sampler = sampling.sampler(c);
                    for _ in c * CHUNK..((c + 1) * CHUNK).min(total) {
                        self.sample(scene, cam, &mut sampler, &mut acc, sample_scale);
                        sampler.advance();
                    }
                    acc
                })
                .reduce(empty, |mut a, b| {
                    a.sum.iter_mut().zip(&b.sum).for_each(|(x, y)| *x += *y);
                    a.invalid += b.invalid;
                    a
                })
        };
        let mut img = Image::new(w, h);
        for y in 0..h {
            for x in 0..w {
                img.set(x, y, splats.sum[(y * w + x) as usize]);
            }
        }
        (img, splats.invalid)
    }

    /// One light path (Mitsuba `ParticleTracerIntegrator::sample`).
    fn sample(
        &self,
        scene: &Scene,
        cam: &crate::sensor::PerspectiveCamera,
        sampler: &mut Sampler,
        out: &mut Splats,
        scale: f32,
    ) {
        if self.max_depth != 0 && !self.hide_emitters {
            self.visible_emitter(scene, cam, sampler, out, scale);
        }
        let Some((idx, pmf, _)) = scene.sample_emitter(sampler.next_1d()) else { return };
        let (u_pos, u_dir) = (sampler.next_2d(), sampler.next_2d());
        let Some(lr) = scene.emitters[idx].sample_ray(u_pos, u_dir, &scene.shapes) else { return };
        let mut beta = lr.weight / pmf;
        if !(beta.max_element() > 0.0) || self.max_depth <= 1 {
            return;
        }
        let mut r = match lr.n {
            Some(n) => ray::spawn_ray(lr.o, n, lr.d),
            None => crate::geometry::Ray::new(lr.o, lr.d, f32::INFINITY),
        };
        let mut eta = 1.0f32;
        let mut depth = 1u32;
        while let Some(si) = scene.intersect(&r) {
            let bsdf = scene.bsdf(&si);
            // Connect this vertex to the camera.
            if let Some(cs) = cam.sample_direction(si.p) {
                let to_cam = ray::spawn_ray_to(si.p, si.n, cs.p);
                if !scene.occluded(&to_cam) {
                    let local_d = si.to_local(to_cam.d);
                    let wi_geo = si.n.dot(si.to_world(si.wi));
                    let wo_geo = si.n.dot(to_cam.d);
                    if wi_geo * si.wi.z > 0.0 && wo_geo * local_d.z > 0.0 {
                        let correction = (si.wi.z * wo_geo / (local_d.z * wi_geo)).abs();
                        let (f, _) = bsdf.eval_pdf(&si, si.wi, local_d);
                        out.put(cs.film_pos, beta * f * (cs.weight * correction * scale));
                    }
                }
            }
            let u_lobe = sampler.next_1d();
            let Some(bs) = bsdf.sample(&si, si.wi, u_lobe, sampler.next_2d()) else { break };
            let wo = si.to_world(bs.wo);
            let wi_geo = si.n.dot(-r.d);
            let wo_geo = si.n.dot(wo);
            if !(wi_geo * si.wi.z > 0.0 && wo_geo * bs.wo.z > 0.0) {
                break;
            }
            let correction = (si.wi.z * wo_geo / (bs.wo.z * wi_geo)).abs();
            beta *= bs.weight * correction;
            eta *= bs.eta;
            if !(beta.max_element() > 0.0) {
                break;
            }
            depth += 1;
            if depth >= self.max_depth {
                break;
            }
            if depth > self.rr_depth {
                let q = (beta.max_element() * eta * eta).min(0.95);
                if !(sampler.next_1d() < q) {
                    break;
                }
                beta /= q;
            }
            r = ray::spawn_ray(si.p, si.n, wo);
        }
    }

    /// Mitsuba `sample_visible_emitters`: a point on a (non-Dirac) emitter seen by the camera.
    fn visible_emitter(
        &self,
        scene: &Scene,
        cam: &crate::sensor::PerspectiveCamera,
        sampler: &mut Sampler,
        out: &mut Splats,
        scale: f32,
    ) {
        let Some((idx, pmf, _)) = scene.sample_emitter(sampler.next_1d()) else { return };
        let u = sampler.next_2d();
        let Some(ep) = scene.emitters[idx].sample_position(u, &scene.shapes) else { return };
        let Some(cs) = cam.sample_direction(ep.p) else { return };
        let to_cam = ray::spawn_ray_to(ep.p, ep.n, cs.p);
        let cos = ep.n.dot(to_cam.d);
        if cos > 0.0 && !scene.occluded(&to_cam) {
            out.put(cs.film_pos, ep.weight * (cos * cs.weight * scale / pmf));
        }
    }
}
