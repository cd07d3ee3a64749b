//! van Ginneken's microsurface (van Ginneken, Stavridi & Koenderink 1998;
//! `docs/microgeometry.md#gaussian-height-fields`): a Gaussian random height field with a
//! Gaussian autocorrelation `σ_h² exp(−r²/T²)` and Lambertian facets of albedo ρ, whose
//! per-axis rms slope is m.
//!
//! The field is one periodic realisation on an n × n grid of spacing `T / CELLS_PER_T`,
//! made by convolving white noise with a Gaussian of standard deviation T/2 (whose
//! autocorrelation is the wanted one), periodically, so the surface tiles the plane and no
//! edge is ever seen. Each grid cell is two flat triangles. The heights are then scaled so that
//! the triangles' per-axis rms slope is exactly m (the discretised field has slightly smaller
//! slopes than the continuous one). Rays march through the cells (Amanatides–Woo) across the
//! periodic copies until they hit a triangle or rise above the highest point.

use super::surface::{MicroSurface, SurfaceHit};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64Mcg;

/// Grid cells per correlation length T (T = 1).
pub const CELLS_PER_T: usize = 8;

/// One periodic realisation of the surface (correlation length T = 1).
#[derive(Clone, Debug)]
pub struct HeightField {
    n: usize,
    spacing: f64,
    heights: Vec<f64>,
    max_height: f64,
    min_height: f64,
    roughness: f64,
}

impl HeightField {
    /// A realisation with per-axis rms slope `roughness` on an `n × n` grid (period n/8 T).
    pub fn gaussian(roughness: f64, n: usize, seed: u64) -> Result<Self, String> {
        if !(roughness.is_finite() && (0.0..=2.0).contains(&roughness)) {
            return Err(format!("height-field roughness must be in [0, 2], got {roughness}"));
        }
        if !(16..=4096).contains(&n) {
            return Err(format!("height-field grid must be 16 to 4096 cells wide, got {n}"));
        }
        let spacing = 1.0 / CELLS_PER_T as f64;
        let mut rng = Pcg64Mcg::seed_from_u64(seed);
        let noise: Vec<f64> = (0..n * n).map(|_| StandardNormal.sample(&mut rng)).collect();
        // Kernel exp(−x²/(2 s²)), s = T/2, truncated at 4 s.
        let s = 0.5;
        let reach = (4.0 * s / spacing).ceil() as isize;
        let kernel: Vec<f64> =
            (-reach..=reach).map(|k| (-(k as f64 * spacing).powi(2) / (2.0 * s * s)).exp()).collect();
        let blur = |src: &[f64], along_x: bool| -> Vec<f64> {
            let mut out = vec![0.0; n * n];
            for y in 0..n {
                for x in 0..n {
                    let mut acc = 0.0;
                    for (k, w) in kernel.iter().enumerate() {
                        let o = k as isize - reach;
                        let (sx, sy) =
                            if along_x { (x as isize + o, y as isize) } else { (x as isize, y as isize + o) };
                        acc += w * src[sy.rem_euclid(n as isize) as usize * n + sx.rem_euclid(n as isize) as usize];
                    }
                    out[y * n + x] = acc;
                }
            }
            out
        };
        let mut heights = blur(&blur(&noise, true), false);
        let mean = heights.iter().sum::<f64>() / heights.len() as f64;
        heights.iter_mut().for_each(|h| *h -= mean);
        let mut field = HeightField { n, spacing, heights, max_height: 0.0, min_height: 0.0, roughness };
        let measured = field.rms_slope();
        let scale = if roughness == 0.0 || measured == 0.0 { 0.0 } else { roughness / measured };
        field.heights.iter_mut().for_each(|h| *h *= scale);
        field.max_height = field.heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        field.min_height = field.heights.iter().copied().fold(f64::INFINITY, f64::min);
        Ok(field)
    }

    pub fn roughness(&self) -> f64 {
        self.roughness
    }

    /// Standard deviation of the heights (in correlation lengths).
    pub fn height_deviation(&self) -> f64 {
        (self.heights.iter().map(|h| h * h).sum::<f64>() / self.heights.len() as f64).sqrt()
    }

    /// Period of the tiling (in correlation lengths).
    pub fn period(&self) -> f64 {
        self.n as f64 * self.spacing
    }

    fn h(&self, i: i64, j: i64) -> f64 {
        let n = self.n as i64;
        self.heights[(j.rem_euclid(n) * n + i.rem_euclid(n)) as usize]
    }

    /// Per-axis rms slope of the triangles (each has the same projected area).
    pub fn rms_slope(&self) -> f64 {
        let mut sum = 0.0;
        let n = self.n as i64;
        for j in 0..n {
            for i in 0..n {
                for t in self.cell_triangles(i, j) {
                    let nrm = (t[1] - t[0]).cross(t[2] - t[0]);
                    sum += (nrm.x * nrm.x + nrm.y * nrm.y) / (nrm.z * nrm.z);
                }
            }
        }
        (sum / (2.0 * 2.0 * (n * n) as f64)).sqrt()
    }

    /// The two triangles of cell (i, j) (unwrapped indices), counter-clockwise from above.
    fn cell_triangles(&self, i: i64, j: i64) -> [[DVec3; 3]; 2] {
        let d = self.spacing;
        let p = |a: i64, b: i64| DVec3::new(a as f64 * d, b as f64 * d, self.h(a, b));
        let (p00, p10, p01, p11) = (p(i, j), p(i + 1, j), p(i, j + 1), p(i + 1, j + 1));
        [[p00, p10, p11], [p00, p11, p01]]
    }
}

/// Möller–Trumbore: distance along the ray to the triangle, if hit from either side.
fn ray_triangle(origin: DVec3, dir: DVec3, t: &[DVec3; 3]) -> Option<(f64, DVec3)> {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - t[0];
    let u = s.dot(p) * inv;
    if !(-1e-12..=1.0 + 1e-12).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < -1e-12 || u + v > 1.0 + 1e-12 {
        return None;
    }
    let dist = e2.dot(q) * inv;
    Some((dist, e1.cross(e2).normalize()))
}

impl MicroSurface for HeightField {
    type Patch = ();

    fn sample_patch(&self, _rng: &mut impl Rng) {}

    fn entry_point(&self, _patch: &(), _direction: DVec3, rng: &mut impl Rng) -> DVec3 {
        let l = self.period();
        DVec3::new(rng.random::<f64>() * l, rng.random::<f64>() * l, self.max_height + 1e-9)
    }

    fn intersect(&self, _patch: &(), origin: DVec3, dir: DVec3) -> Option<SurfaceHit> {
        let d = self.spacing;
        let (mut i, mut j) = ((origin.x / d).floor() as i64, (origin.y / d).floor() as i64);
        let step = |c: f64| if c > 0.0 { 1 } else { -1 };
        let (si, sj) = (step(dir.x), step(dir.y));
        let next = |cell: i64, s: i64, o: f64, c: f64| {
            if c == 0.0 { f64::INFINITY } else { (((cell + (s > 0) as i64) as f64) * d - o) / c }
        };
        let (mut tx, mut ty) = (next(i, si, origin.x, dir.x), next(j, sj, origin.y, dir.y));
        let (dtx, dty) = (
            if dir.x == 0.0 { f64::INFINITY } else { d / dir.x.abs() },
            if dir.y == 0.0 { f64::INFINITY } else { d / dir.y.abs() },
        );
        loop {
            let t_exit = tx.min(ty);
            let mut best: Option<(f64, DVec3)> = None;
            for tri in self.cell_triangles(i, j) {
                if let Some((t, n)) = ray_triangle(origin, dir, &tri)
                    && t > 1e-9
                    && best.is_none_or(|(b, _)| t < b)
                {
                    best = Some((t, n));
                }
            }
            if let Some((t, n)) = best {
                let n = if n.dot(dir) > 0.0 { -n } else { n };
                return Some(SurfaceHit { point: origin + dir * t, normal: n });
            }
            // Rising and above every point of the surface: gone.
            let z_exit = origin.z + dir.z * t_exit.min(1e300);
            if dir.z > 0.0 && z_exit > self.max_height {
                return None;
            }
            if !t_exit.is_finite() || z_exit < self.min_height - 1.0 {
                // A vertical ray that missed its cell (only possible going up), or a ray that
                // slipped below the surface through a rounding gap (never seen in the tests).
                return None;
            }
            if tx < ty {
                i += si;
                tx += dtx;
            } else {
                j += sj;
                ty += dty;
            }
        }
    }
}
