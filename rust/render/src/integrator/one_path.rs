//! The reference driver: one path at a time, every query on its own (the renderer before
//! [`super::wavefront`]; `matte bench` times both on the same scenes).

use super::sample_integrator::{SampleIntegrator, ShadowTest, TileJob};
use crate::film::ImageBlock;
use crate::geometry::Ray;
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::{Vec2, Vec3};

/// Renders `job.sampling.spp` samples of every pixel of `block`'s tile into `block`, pixel by
/// pixel with each pixel's sampler stream (advanced after each sample); returns how many
/// samples were not finite (splatted as zero).
pub fn render_tile<I: SampleIntegrator>(integrator: &I, job: &TileJob, block: &mut ImageBlock) -> u64 {
    let tile = block.tile();
    let mut bad = 0;
    // One buffer for the shadow rays of every sample of the tile (no allocation per sample).
    let mut shadows = Vec::new();
    for py in tile.offset[1]..tile.offset[1] + tile.size[1] {
        for px in tile.offset[0]..tile.offset[0] + tile.size[0] {
            let mut sampler = job.sampling.sampler(py as u64 * job.width + px as u64);
            let pixel = Vec2::new(px as f32, py as f32);
            for _ in 0..job.sampling.spp {
                let pos = pixel + sampler.next_2d();
                let ray = job.camera.sample_ray(pos, &mut sampler);
                let mut l = li_with(integrator, job.scene, &mut sampler, ray, &mut shadows);
                sampler.advance();
                if !l.is_finite() {
                    l = Vec3::ZERO;
                    bad += 1;
                }
                block.put(pos, l);
            }
        }
    }
    bad
}

/// Radiance along a camera ray, one query at a time: `integrator`'s state machine with each
/// shadow ray tested as soon as it is asked for.
#[inline]
pub fn li<I: SampleIntegrator>(integrator: &I, scene: &Scene, sampler: &mut Sampler, camera_ray: Ray) -> Vec3 {
    li_with(integrator, scene, sampler, camera_ray, &mut Vec::new())
}

/// [`li`] with a caller's (empty) buffer for the shadow rays.
#[inline]
fn li_with<I: SampleIntegrator>(
    integrator: &I,
    scene: &Scene,
    sampler: &mut Sampler,
    camera_ray: Ray,
    shadows: &mut Vec<ShadowTest>,
) -> Vec3 {
    let Some((mut state, mut ray)) = integrator.start(camera_ray) else { return Vec3::ZERO };
    loop {
        let next = integrator.advance(scene, sampler, &mut state, scene.intersect(&ray), shadows);
        for test in shadows.drain(..) {
            if !scene.occluded(&test.ray) {
                *I::radiance(&mut state) += test.contribution;
            }
        }
        match next {
            Some(r) => ray = r,
            None => return *I::radiance(&mut state),
        }
    }
}
