//! Reconstruction filters and their 31-bin discretisation (`docs/renderer-semantics.md`
//! §6; `include/mitsuba/core/rfilter.h`, `src/core/rfilter.cpp`, `src/rfilters/*.cpp`).
//!
//! Pitfall reproduced on purpose: Mitsuba's scalar variants never evaluate the kernel per
//! sample. They splat with `eval_discretized`, a piecewise-constant, left-endpoint table:
//! `table[k] = eval(r·k/31)` for k = 0..30, `table[31] = 0`, looked up at
//! `min(trunc(|x|·31/r), 31)`.
//!
//! [`ReconstructionFilter`] reads the `<rfilter>` plugins' properties ([`FromProps`]).

use crate::load::props::{FromProps, PluginProps};
use matte_scene_file::SceneError;

/// Number of bins of the discretised kernel (`MI_FILTER_RESOLUTION`).
pub const FILTER_RESOLUTION: usize = 31;

/// `math::RayEpsilon<float>` = 1500·2⁻²⁴, used by Mitsuba's border-size rule.
const RAY_EPSILON: f32 = 1500.0 / 16_777_216.0;

/// How a sample's splat weights are computed from the filter. Mitsuba 3.9.1 does it two ways
/// (`ImageBlock::put`, `src/render/imageblock.cpp`): its scalar variants use the step table
/// (`eval_discretized`), its JIT variants (`llvm_*`, `cuda_*`) the kernel itself (`eval`). The
/// two images differ measurably at sharp edges: the table overweights the Gaussian's tail, so
/// at 1024 spp the pixel just outside the Cornell box's light is ~5 % brighter with the table
/// (`docs/validation.md`). The box filter has no weights and is unaffected.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SplatWeights {
    /// The 31-bin step table: Mitsuba's `scalar_*` variants (matte's default).
    #[default]
    Discretized,
    /// The continuous kernel: Mitsuba's `llvm_*` and `cuda_*` variants.
    Exact,
}

impl SplatWeights {
    /// The weighting Mitsuba's `variant` uses (`scalar_rgb` → table, `llvm_ad_rgb` → exact).
    pub fn of_mitsuba_variant(variant: &str) -> SplatWeights {
        if variant.starts_with("scalar_") { SplatWeights::Discretized } else { SplatWeights::Exact }
    }

    /// Parses `discretized` or `exact` (the CLI's spelling).
    pub fn parse(name: &str) -> Result<SplatWeights, String> {
        match name {
            "discretized" => Ok(SplatWeights::Discretized),
            "exact" => Ok(SplatWeights::Exact),
            other => Err(format!("unknown splat weighting {other:?} (expected discretized or exact)")),
        }
    }
}

/// The film's pixel reconstruction filter (`<rfilter type="...">`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReconstructionFilter {
    /// Radius 0.5, with Mitsuba's fast path: each sample goes to the pixel containing it with
    /// weight 1, so a pixel is the plain mean of its own samples.
    Box,
    /// `max(0, 1 − |x|/r)`; Mitsuba's default radius is 1.
    Tent { radius: f32 },
    /// Truncated at 4σ and shifted to reach 0 there (evaluated through Mitsuba's polynomial
    /// fit, see [`ReconstructionFilter::eval`]); Mitsuba's default σ is 0.5 (the film's
    /// default filter).
    Gaussian { stddev: f32 },
    /// Mitchell–Netravali cubic (`src/rfilters/mitchell.cpp`): radius 2, parameters `B`, `C`
    /// (Mitsuba's defaults 1/3, 1/3); negative lobes.
    Mitchell { b: f32, c: f32 },
    /// Catmull–Rom (`src/rfilters/catmullrom.cpp`): the Mitchell–Netravali cubic with B = 0,
    /// C = 1/2, radius 2, evaluated as Mitsuba evaluates it.
    CatmullRom,
    /// Lanczos-windowed sinc (`src/rfilters/lanczos.cpp`): radius = `lobes` (default 3).
    Lanczos { lobes: u32 },
}

impl Default for ReconstructionFilter {
    /// `hdrfilm` without an `<rfilter>`: Gaussian, σ = 0.5 (§6).
    fn default() -> Self {
        ReconstructionFilter::Gaussian { stddev: 0.5 }
    }
}

impl FromProps for ReconstructionFilter {
    /// `box`, `tent` (radius), `gaussian` (stddev), `mitchell` (B, C), `catmullrom`, `lanczos`
    /// (lobes), with Mitsuba 3.9.1's defaults (`src/rfilters/*.cpp`).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        Ok(match p.object().plugin.as_str() {
            "tent" => ReconstructionFilter::Tent { radius: filter_size(p, "radius", 1.0)? },
            "gaussian" => ReconstructionFilter::Gaussian { stddev: filter_size(p, "stddev", 4.0)? },
            // Mitsuba's defaults are `1.f / 3.f`.
            "mitchell" => ReconstructionFilter::Mitchell {
                b: p.finite_or("B", 1.0 / 3.0)? as f32,
                c: p.finite_or("C", 1.0 / 3.0)? as f32,
            },
            "catmullrom" => ReconstructionFilter::CatmullRom,
            "lanczos" => {
                ReconstructionFilter::Lanczos { lobes: p.integer("lobes", 1..=MAX_FILTER_RADIUS as i64)? as u32 }
            }
            _ => ReconstructionFilter::Box,
        })
    }
}

/// Widest reconstruction filter matte accepts, in pixels. Mitsuba has no limit, but every
/// image block carries a border of the filter radius on each side, so a radius like 1e30
/// cannot be allocated (and would overflow the block size).
const MAX_FILTER_RADIUS: f64 = 1024.0;

/// A filter parameter (positive, the harvested default) whose support radius is
/// `radius_per_unit` times it.
fn filter_size(p: &mut PluginProps, name: &str, radius_per_unit: f64) -> Result<f32, SceneError> {
    let v = p.positive(name)?;
    if v * radius_per_unit > MAX_FILTER_RADIUS {
        let radius = v * radius_per_unit;
        let message = format!("gives a filter radius of {radius} pixels; matte allows at most {MAX_FILTER_RADIUS}");
        return Err(p.prop_err(name, message));
    }
    Ok(v as f32)
}

impl ReconstructionFilter {
    /// Mitsuba's default tent (radius 1).
    pub const TENT: ReconstructionFilter = ReconstructionFilter::Tent { radius: 1.0 };
    /// Mitsuba's default Gaussian (σ = 0.5, radius 2).
    pub const GAUSSIAN: ReconstructionFilter = ReconstructionFilter::Gaussian { stddev: 0.5 };

    /// Support radius in pixels: box 0.5, tent `radius`, Gaussian 4σ, the cubics 2, Lanczos
    /// `lobes`.
    pub fn radius(&self) -> f32 {
        match *self {
            ReconstructionFilter::Box => 0.5,
            ReconstructionFilter::Tent { radius } => radius,
            ReconstructionFilter::Gaussian { stddev } => 4.0 * stddev,
            ReconstructionFilter::Mitchell { .. } | ReconstructionFilter::CatmullRom => 2.0,
            ReconstructionFilter::Lanczos { lobes } => lobes as f32,
        }
    }

    /// Parameters must be finite and positive (a zero radius would divide by zero).
    pub fn validate(&self) -> Result<(), String> {
        let (name, v) = match *self {
            ReconstructionFilter::Box | ReconstructionFilter::CatmullRom => return Ok(()),
            ReconstructionFilter::Mitchell { b, c } => {
                return if b.is_finite() && c.is_finite() {
                    Ok(())
                } else {
                    Err(format!("invalid reconstruction filter: mitchell B and C must be finite, got {b}, {c}"))
                };
            }
            ReconstructionFilter::Lanczos { lobes } => ("lanczos lobes", lobes as f32),
            ReconstructionFilter::Tent { radius } => ("tent radius", radius),
            ReconstructionFilter::Gaussian { stddev } => ("gaussian stddev", stddev),
        };
        if v.is_finite() && v > 0.0 && self.radius().is_finite() {
            Ok(())
        } else {
            Err(format!("invalid reconstruction filter: {name} must be a positive number, got {v}"))
        }
    }

    /// The continuous kernel, as the table is built from it.
    ///
    /// Gaussian: like Mitsuba (`src/rfilters/gaussian.cpp`), not the exact
    /// `exp(−x²/2σ²) − exp(−r²/2σ²)` but its polynomial stand-in `max(0, p(t) − p(16))`,
    /// t = x²/σ², with `p` the minimax fit [`GAUSSIAN_FIT`], evaluated as Mitsuba does (f32
    /// coefficients scaled by σ^−2i, Estrin's scheme with fused multiply-adds). The table then
    /// equals Mitsuba's bit for bit (checked for σ = 0.3, 0.5, 0.77, 1 against `rfilter.eval`);
    /// the exact expression would differ by up to 4.2e-4 (§6) and shift pixels by ~1e-4.
    /// 0 for |x| ≥ r.
    pub fn eval(&self, x: f32) -> f32 {
        match *self {
            ReconstructionFilter::Box => {
                if (-0.5..0.5).contains(&x) {
                    1.0
                } else {
                    0.0
                }
            }
            ReconstructionFilter::Tent { radius } => (1.0 - (x * (1.0 / radius)).abs()).max(0.0),
            ReconstructionFilter::Gaussian { stddev } => {
                if x.abs() >= self.radius() {
                    return 0.0;
                }
                estrin_fma(x * x, &gaussian_coefficients(stddev)).max(0.0)
            }
            ReconstructionFilter::Mitchell { b, c } => mitchell_netravali(x, b, c),
            ReconstructionFilter::CatmullRom => mitchell_netravali(x, 0.0, 0.5),
            ReconstructionFilter::Lanczos { lobes } => {
                let (x, r) = (x.abs(), lobes as f32);
                if x < f32::EPSILON {
                    return 1.0;
                }
                if x > r {
                    return 0.0;
                }
                let x1 = std::f32::consts::PI * x;
                let x2 = x1 / r;
                (x1.sin() * x2.sin()) / (x1 * x2)
            }
        }
    }

    /// Pixels a sample can reach beyond its own: `ceil(r − 0.5 − 2·RayEpsilon)`
    /// (`init_discretization`). Box: 0, tent(1): 1, Gaussian(0.5): 2.
    pub fn border_size(&self) -> u32 {
        match self {
            ReconstructionFilter::Box => 0,
            _ => (self.radius() - 0.5 - 2.0 * RAY_EPSILON).ceil().max(0.0) as u32,
        }
    }

    /// The discretised kernel used for splatting.
    pub fn table(&self) -> FilterTable {
        let radius = self.radius();
        let mut values = [0.0; FILTER_RESOLUTION + 1];
        for (k, v) in values.iter_mut().take(FILTER_RESOLUTION).enumerate() {
            *v = self.eval((radius * k as f32) / FILTER_RESOLUTION as f32);
        }
        FilterTable { values, scale: FILTER_RESOLUTION as f32 / radius, radius }
    }
}

/// The Mitchell–Netravali cubic with parameters (B, C) at |x|, 0 from 2 on, with Mitsuba's
/// coefficients and operation order (`fmadd`s over x, x², x³).
fn mitchell_netravali(x: f32, b: f32, c: f32) -> f32 {
    let x = x.abs();
    let (x2, x3) = (x * x, x * x * x);
    let near = x3.mul_add(12.0 - 9.0 * b - 6.0 * c, x2.mul_add(-18.0 + 12.0 * b + 6.0 * c, 6.0 - 2.0 * b));
    let far =
        x3.mul_add(-b - 6.0 * c, x2.mul_add(6.0 * b + 30.0 * c, x.mul_add(-12.0 * b - 48.0 * c, 8.0 * b + 24.0 * c)));
    if x >= 2.0 { 0.0 } else { (1.0 / 6.0) * if x < 1.0 { near } else { far } }
}

/// Coefficients (ascending powers of t) of the degree-9 polynomial p(t) that minimises the
/// maximum RELATIVE error to exp(−t/2) on t ∈ [0, 16] (|relative error| ≤ 4.04e-4).
///
/// This is the approximation Mitsuba's Gaussian filter evaluates (its source states the
/// problem: a degree-(9, 0) `MiniMaxApproximation` of exp(−x/2) on [0, 16]); the minimax
/// polynomial is unique, and these values were derived independently by a Remez exchange
/// (11 alternation points, 50-digit arithmetic, converged to 1e-30 in the points). They agree
/// with the 10-digit coefficients in Mitsuba's comment.
pub const GAUSSIAN_FIT: [f64; 10] = [
    0.999_595_815_008,
    -0.497_702_524_696,
    0.122_224_855_004,
    -0.019_324_062_818_1,
    0.002_136_713_060_83,
    -0.000_167_987_386_003,
    9.202_145_247_68e-6,
    -3.329_417_433_09e-7,
    7.128_382_793_63e-9,
    -6.821_193_280_46e-11,
];

/// The f32 coefficients of `p(x²/σ²) − p(16)` as a polynomial in x² (Mitsuba's `m_coeff`):
/// the constant is shifted in f64 first, the powers of 1/σ² applied in f64, each coefficient
/// rounded to f32, and the f32 residual at x² = r² subtracted once more.
fn gaussian_coefficients(stddev: f32) -> [f32; 10] {
    let mut c = GAUSSIAN_FIT;
    c[0] -= c.iter().enumerate().map(|(i, &ci)| ci * 16f64.powi(i as i32)).sum::<f64>();
    let inv_var = 1.0 / (stddev as f64 * stddev as f64);
    let mut scale = 1.0;
    let mut out = [0.0f32; 10];
    for (o, &ci) in out.iter_mut().zip(&c) {
        *o = (ci * scale) as f32;
        scale *= inv_var;
    }
    let r = 4.0 * stddev;
    out[0] -= estrin_fma(r * r, &out);
    out
}

/// Estrin's scheme in f32 with fused multiply-adds (Dr.Jit's `estrin_impl`): pairs
/// `fma(x, c[2i+1], c[2i])`, then the same on the results with x², x⁴, ...
fn estrin_fma(x: f32, coeff: &[f32; 10]) -> f32 {
    let mut c = *coeff;
    let (mut n, mut x) = (c.len(), x);
    while n > 1 {
        for i in 0..n / 2 {
            c[i] = x.mul_add(c[2 * i + 1], c[2 * i]);
        }
        if n % 2 == 1 {
            c[n / 2] = c[n - 1];
        }
        n = n.div_ceil(2);
        x *= x;
    }
    c[0]
}

/// A filter's 31 (+1 zero) bins, `ReconstructionFilter::eval_discretized` in Mitsuba.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FilterTable {
    values: [f32; FILTER_RESOLUTION + 1],
    /// 31 / radius.
    scale: f32,
    radius: f32,
}

impl FilterTable {
    /// Weight at offset `x` (pixels) from the sample: `table[min(trunc(|x|·31/r), 31)]`.
    #[inline]
    pub fn eval(&self, x: f32) -> f32 {
        let k = ((x * self.scale).abs() as u32).min(FILTER_RESOLUTION as u32);
        self.values[k as usize]
    }

    /// The 32 bins (the last is 0).
    pub fn values(&self) -> &[f32; FILTER_RESOLUTION + 1] {
        &self.values
    }

    pub fn radius(&self) -> f32 {
        self.radius
    }
}
