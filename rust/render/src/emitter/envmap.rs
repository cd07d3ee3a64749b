//! Mitsuba 3.9.1's `envmap` emitter (`src/emitters/envmap.cpp`) in RGB: a latitude–longitude
//! image of W×H linear RGB texels around the scene, times `scale`, rotated by `to_world`.
//!
//! * Directions: local d = (sin φ sin θ, cos θ, −cos φ sin θ) with θ = π v, φ = 2π u; so +y
//!   is up (v = 0) and u = 0 looks along −z.
//! * Lookup: periodic in u with texel-centred columns (column i at u = (i + ½)/W), rows
//!   aligned to the corners (row j at v = j/(H − 1)), bilinear.
//! * Sampling (`rebuild_distribution` + `Hierarchical2D<0>`): a piecewise-bilinear density
//!   over a (W+1)×H vertex grid whose values are luminance·sin θ_j (vertex column W repeats
//!   column 0; `scale` does not enter), normalised so that it integrates to 1 over the unit
//!   square; a sample's u is then shifted by half a texel, 1/(2W). The solid-angle density is
//!   pdf_uv / (2π² sin θ). Only this density matters for the estimate (MIS weights and
//!   sample weights), so matte draws from it with its own inversion (cell by its integral,
//!   then the bilinear patch), not Mitsuba's hierarchical warp: same expectation, the noise
//!   differs.
//! * `mis_compensation` (Karlík et al. 2019) subtracts the mean luminance from the sampling
//!   values unless the map is nearly constant.
//! * Properties: `filename` (found through the scene's search folders), `scale` (default 1),
//!   `to_world` (invertible), `mis_compensation` (default false). Mitsuba's `bitmap` property
//!   (an in-memory image) has no XML form.

use super::emitter_sample::EmitterSample;
use super::flags::EmitterFlags;
use super::light::Light;
use super::projector::scale_and_to_world;
use crate::load::props::{FromProps, PluginProps};
use crate::shape::Shape;
use crate::texture::{BitmapOptions, BitmapTexture};
use glam::{Affine3A, Vec2, Vec3};
use matte_scene_file::SceneError;
use std::f32::consts::PI;

/// Rec. 709 luminance, as Mitsuba's `luminance()` for RGB.
const LUMINANCE: Vec3 = Vec3::new(0.212_671, 0.715_160, 0.072_169);

/// `dr::Epsilon<float>`.
const EPSILON: f32 = 1.0 / 16_777_216.0;

#[derive(Clone, Debug)]
pub struct EnvMap {
    width: usize,
    height: usize,
    /// Linear RGB, row-major, top row (v = 0) first.
    texels: Vec<Vec3>,
    scale: f32,
    to_world: Affine3A,
    to_local: Affine3A,
    /// The normalised sampling density at the (W+1)×H vertices.
    density: Vec<f32>,
    /// Cumulative probabilities of the W×(H−1) cells, row-major.
    cell_cdf: Vec<f32>,
}

impl EnvMap {
    /// `texels` as loaded (linear), `width` ≥ 2, `height` ≥ 3 (Mitsuba pads smaller images).
    pub fn new(
        width: usize,
        height: usize,
        texels: Vec<Vec3>,
        scale: f32,
        to_world: Affine3A,
        mis_compensation: bool,
    ) -> Result<Self, String> {
        if width < 2 || height < 3 || texels.len() != width * height {
            return Err(format!("an environment map needs at least 2×3 texels (got {width}×{height})"));
        }
        if texels.iter().any(|t| !t.is_finite() || t.min_element() < 0.0) {
            return Err("the environment map has negative or non-finite texels".into());
        }
        let nx = width + 1;
        let mut lum: Vec<f32> = (0..height)
            .flat_map(|y| (0..nx).map(move |x| (y, x % width)))
            .map(|(y, x)| texels[y * width + x].dot(LUMINANCE))
            .collect();
        if mis_compensation {
            let (mut min, mut sum) = (f32::INFINITY, 0.0f64);
            for y in 0..height {
                for x in 0..width {
                    min = min.min(lum[y * nx + x]);
                    sum += lum[y * nx + x] as f64;
                }
            }
            let offset = (sum / (width * height) as f64) as f32;
            if offset - min > 0.01 * offset {
                lum.iter_mut().for_each(|l| *l = (*l - offset).max(0.0));
            }
        }
        let theta_scale = PI / (height - 1) as f32;
        for y in 0..height {
            let s = (y as f32 * theta_scale).sin();
            lum[y * nx..(y + 1) * nx].iter_mut().for_each(|l| *l = l.max(0.0) * s);
        }
        // Cell integrals (mean of the 4 corners), as Hierarchical2D normalises.
        let mut cells = Vec::with_capacity(width * (height - 1));
        let mut sum = 0.0f64;
        for y in 0..height - 1 {
            for x in 0..width {
                let avg =
                    0.25 * (lum[y * nx + x] + lum[y * nx + x + 1] + lum[(y + 1) * nx + x] + lum[(y + 1) * nx + x + 1]);
                sum += avg as f64;
                cells.push(sum);
            }
        }
        if !(sum > 0.0) {
            return Err("the environment map is black everywhere (nothing to sample)".into());
        }
        let n_cells = (width * (height - 1)) as f64;
        let density = lum.iter().map(|&l| (l as f64 * n_cells / sum) as f32).collect();
        let cell_cdf = cells.iter().map(|&c| (c / sum) as f32).collect();
        Ok(EnvMap { width, height, texels, scale, to_world, to_local: to_world.inverse(), density, cell_cdf })
    }

    /// Texture uv of a local direction (`direction_to_uv`).
    #[inline]
    fn direction_to_uv(v: Vec3) -> Vec2 {
        Vec2::new(v.x.atan2(-v.z) / (2.0 * PI), v.y.clamp(-1.0, 1.0).acos() / PI)
    }

    /// Radiance at texture coordinates `uv` (`eval_spectrum`).
    #[inline]
    pub fn eval_uv(&self, uv: Vec2) -> Vec3 {
        let (w, h) = (self.width, self.height);
        let u = uv.x - uv.x.floor();
        let v = if uv.y.is_nan() { 0.0 } else { uv.y.clamp(0.0, 1.0) };
        let px = u * w as f32 - 0.5;
        let py = v * (h - 1) as f32;
        let (fx, fy) = (px.floor(), py.floor());
        let (tx, ty) = (px - fx, py - fy);
        let x0 = (fx as i64).rem_euclid(w as i64) as usize;
        let x1 = (x0 + 1) % w;
        let y0 = (fy.max(0.0) as usize).min(h - 1);
        let y1 = (y0 + 1).min(h - 1);
        let t = |x: usize, y: usize| self.texels[y * w + x];
        let top = t(x0, y0) * (1.0 - tx) + t(x1, y0) * tx;
        let bottom = t(x0, y1) * (1.0 - tx) + t(x1, y1) * tx;
        (top * (1.0 - ty) + bottom * ty) * self.scale
    }

    /// Radiance arriving from world direction `d` (towards the environment).
    #[inline]
    pub fn eval(&self, d: Vec3) -> Vec3 {
        self.eval_uv(Self::direction_to_uv(self.to_local.transform_vector3(d)))
    }

    /// Bilinear sampling density at warp coordinates `p` ∈ [0, 1]².
    #[inline]
    fn density_at(&self, p: Vec2) -> f32 {
        let nx = self.width + 1;
        let x = (p.x * self.width as f32).clamp(0.0, self.width as f32);
        let y = (p.y * (self.height - 1) as f32).clamp(0.0, (self.height - 1) as f32);
        let x0 = (x.floor() as usize).min(self.width - 1);
        let y0 = (y.floor() as usize).min(self.height - 2);
        let (tx, ty) = (x - x0 as f32, y - y0 as f32);
        let d = |i: usize, j: usize| self.density[j * nx + i];
        (d(x0, y0) * (1.0 - tx) + d(x0 + 1, y0) * tx) * (1.0 - ty)
            + (d(x0, y0 + 1) * (1.0 - tx) + d(x0 + 1, y0 + 1) * tx) * ty
    }

    /// Solid-angle density of [`Self::sample`] for world direction `d`.
    #[inline]
    pub fn pdf(&self, d: Vec3) -> f32 {
        let v = self.to_local.transform_vector3(d);
        let mut uv = Self::direction_to_uv(v);
        uv.x -= 0.5 / self.width as f32;
        uv -= uv.floor();
        let inv_sin_theta = 1.0 / (v.x * v.x + v.z * v.z).max(EPSILON * EPSILON).sqrt();
        self.density_at(uv) * inv_sin_theta / (2.0 * PI * PI)
    }

    /// A direction (world, unit), its radiance and its solid-angle density; `None` where the
    /// density vanishes.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let n = self.cell_cdf.len();
        let cell = self.cell_cdf.partition_point(|&c| c <= u.x).min(n - 1);
        let lo = if cell == 0 { 0.0 } else { self.cell_cdf[cell - 1] };
        let p = self.cell_cdf[cell] - lo;
        if !(p > 0.0) {
            return None;
        }
        let ux = ((u.x - lo) / p).clamp(0.0, 1.0);
        let (cx, cy) = (cell % self.width, cell / self.width);
        let nx = self.width + 1;
        let d = |i: usize, j: usize| self.density[j * nx + i];
        let (v00, v10, v01, v11) = (d(cx, cy), d(cx + 1, cy), d(cx, cy + 1), d(cx + 1, cy + 1));
        // Marginal in y (linear), then x given y (linear).
        let ty = sample_linear(0.5 * (v00 + v10), 0.5 * (v01 + v11), u.y);
        let tx = sample_linear(v00 * (1.0 - ty) + v01 * ty, v10 * (1.0 - ty) + v11 * ty, ux);
        let warp = Vec2::new((cx as f32 + tx) / self.width as f32, (cy as f32 + ty) / (self.height - 1) as f32);
        let pdf_uv = self.density_at(warp);
        let uv = Vec2::new(warp.x + 0.5 / self.width as f32, warp.y);
        let (theta, phi) = (uv.y * PI, uv.x * 2.0 * PI);
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let local = Vec3::new(sp * st, ct, -cp * st);
        let pdf = pdf_uv / (st.max(EPSILON) * 2.0 * PI * PI);
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let dir = self.to_world.transform_vector3(local).normalize();
        Some((dir, self.eval_uv(uv), pdf))
    }
}

impl FromProps for EnvMap {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let path = p.file("filename")?;
        let (scale, to_world) = scale_and_to_world(p)?;
        let mis_compensation = p.boolean("mis_compensation")?;
        let tex =
            BitmapTexture::load(&path, &BitmapOptions::default()).map_err(|e| p.file_err("filename", &path, &e))?;
        let [w, h] = tex.resolution();
        EnvMap::new(w as usize, h as usize, tex.texels().to_vec(), scale as f32, to_world, mis_compensation)
            .map_err(|e| p.file_err("filename", &path, &e))
    }
}

impl Light for EnvMap {
    #[inline]
    fn flags(&self) -> EmitterFlags {
        EmitterFlags::INFINITE
    }

    #[inline]
    fn sample_direction(&self, ref_p: Vec3, u: Vec2, _shapes: &[Shape]) -> Option<EmitterSample> {
        let (d, radiance, pdf) = self.sample(u)?;
        Some(EmitterSample { d, dist: f32::INFINITY, pdf, delta: false, weight: radiance / pdf, p: ref_p + d, n: -d })
    }

    #[inline]
    fn eval_environment(&self, d: Vec3) -> Vec3 {
        self.eval(d)
    }

    #[inline]
    fn pdf_environment(&self, d: Vec3) -> f32 {
        self.pdf(d)
    }
}

/// Inverts the CDF of the density on [0, 1] that is linear from `a` at 0 to `b` at 1.
#[inline]
fn sample_linear(a: f32, b: f32, u: f32) -> f32 {
    let denom = a + (a * a + (b * b - a * a) * u).max(0.0).sqrt();
    if denom > 0.0 { ((a + b) * u / denom).clamp(0.0, 1.0) } else { u }
}
