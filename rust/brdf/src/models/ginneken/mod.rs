//! van Ginneken, Stavridi & Koenderink (Appl. Opt. 37(1), 1998), diffuse part: Lambertian
//! facets on an isotropic Gaussian surface with per-axis rms slope `m`, shadowing and masking
//! by the seed paper's eq. 5:
//!
//! `f = (ρ/π) · P_ill+vis(wi, wo) · I(wi, wo) / (μi μo)`
//!
//! with the slope integral `I` ([`slope_integral`]) and `P_ill+vis` ([`shadowing`]). There is
//! no closed form for `I`: [`Ginneken::eval_reference`] integrates it (semi-analytically, f64)
//! and [`DiffuseBrdf::eval`] assembles it from per-roughness tables of its exact split into 1-D
//! functions of each direction and the ratio of a wedge term ([`table`]). The seed's
//! text says the probability "multiplies the results from the Lambertian model using the
//! angles of eqs. 2–3", i.e. the facet-local cosines: that is the integrand of `I`.

pub mod accuracy;
mod mu_lambda_fit;
pub mod roughness_axis;
pub mod shadowing;
pub mod slope_integral;
mod split;
pub mod table;

use crate::cltc::{ClippedLtc, Sampling};
use crate::kernel::Kernel;
use crate::params::{ParamError, ParamValue};
use crate::real::{Nodes, Real, V3};
use crate::registry::{
    Evaluation, Flat, Gradients, KernelBrdf, ModelSpec, ParamSpec, Range, Registered, Values, flat_values, param,
    parameter_values,
};
use roughness_axis::{GinnekenAxisKernel, M_MAX, M_MIN, RoughnessAxisTables, clamp_roughness};
use shadowing::{
    Shadowing, azimuth_correlation, mu_lambda, visibility_denominator,
};
use slope_integral::{REFERENCE_NODES, SlopeIntegrator};
use split::{SlopeSplit, reduced_with};
pub use split::{sampler, sampler_roughness};
use std::sync::Arc;
use table::{SlopeGeometry, SlopeTable, oned_cell, oned_in, ratio_in};

/// van Ginneken's tables and options in any [`Real`], and its evaluation (the fast path).
/// The tables are built for one roughness m₀; the traced kernels may carry their `∂/∂m`
/// tables and `dm = m − m₀` (zero in value, the roughness parameter's gradient in derivative),
/// so that `F(m) ≈ F(m₀) + dm ∂F/∂m` for each tabulated `F` gives the exact value and the
/// first-order roughness gradient; μΛ is one of the tabulated functions.
#[derive(Clone, Copy)]
pub struct GinnekenKernel<'t, T: Real> {
    /// `[P0/μ², P1/μ³, H/μ, μΛ]` as 1-D cells ([`SlopeTable::oned_cells`]) and `r = K/I` as
    /// cells of trilinear coefficients ([`SlopeTable::ratio_cells`]).
    pub slope: [T::Table<'t>; 2],
    /// The ratio table's v axis: `[1/m, 1 − 1/m]` of its roughness m
    /// ([`table::ratio_axis_constants`] of the tables' m₀; constants).
    pub ratio_axis: [T; 2],
    /// `(∂/∂m of both tables, dm = m − m₀)` when the roughness gradient is wanted.
    pub roughness_derivative: Option<([T::Table<'t>; 2], T)>,
    pub shadowing: Shadowing,
    /// The sampler's roughness variable ([`sampler_roughness`] of the tables' m₀).
    pub sampler_t: T,
    /// Sample the fitted lobe ([`sampler`]) rather than the cosine (the `sampling` parameter).
    pub cltc: bool,
}

impl<'t, T: Real> SlopeSplit<T> for GinnekenKernel<'t, T> {
    /// One packet per direction: the three functions and μΛ at the tables' m₀, plus
    /// `dm · ∂/∂m` of each when the roughness gradient is wanted.
    #[inline(always)]
    fn directions(&self, g: &SlopeGeometry<T>) -> [([T; 3], T); 2] {
        [self.direction(g.x[0]), self.direction(g.x[1])]
    }

    #[inline(always)]
    fn ratio(&self, g: &SlopeGeometry<T>) -> T {
        let [v_i, v_o] = g.v(self.ratio_axis);
        let r = ratio_in(self.slope[1], v_i, v_o, g.phi);
        match self.roughness_derivative {
            Some(([_, d_ratio], dm)) => dm.fma(ratio_in(d_ratio, v_i, v_o, g.phi), r),
            None => r,
        }
    }
}

impl<'t, T: Real> GinnekenKernel<'t, T> {
    /// `([P0/μ², P1/μ³, H/μ], μΛ)` of one direction at axis coordinate `x`. (Called once per
    /// direction rather than through `array::map`, whose closure was not inlined.)
    #[inline(always)]
    fn direction(&self, x: T) -> ([T; 3], T) {
        let zero = T::c(0.0);
        let cell = oned_cell(x);
        let mut f: [T; 4] = oned_in(self.slope[0], zero, cell);
        if let Some(([d_oned, _], dm)) = self.roughness_derivative {
            let df: [T; 4] = oned_in(d_oned, zero, cell);
            f = std::array::from_fn(|j| dm.fma(df[j], f[j]));
        }
        ([f[0], f[1], f[2]], f[3])
    }
}

impl<'t, T: Real> Kernel<T> for GinnekenKernel<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        reduced_with(self.shadowing, wi, wo, rho, self)
    }

    #[inline(always)]
    fn fitted_sampler(&self) -> Option<impl Fn(T) -> ClippedLtc<T>> {
        self.cltc.then_some(move |mu| sampler(mu, self.sampler_t))
    }
}

flat_values! {
    /// van Ginneken's numeric parameter.
    pub struct GinnekenParameters {
        roughness,
    }
}

/// van Ginneken's kernel constant. For [`Evaluation::Constant`] (the tables of the model's
/// roughness m₀): `m − m₀` when gradients are needed, zero in value and the roughness's
/// gradient in derivative; absent otherwise (the tables are exact at m₀). For
/// [`Evaluation::Lane`] (the tables stacked over m): the lane's roughness, clamped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GinnekenCoefficients<T> {
    pub roughness: Option<T>,
}

impl<T: Copy> Flat<T> for GinnekenCoefficients<T> {
    const NAMES: &'static [&'static str] = &["roughness"];

    /// Empty: no roughness.
    fn from_flat(c: &[T]) -> Option<Self> {
        Some(Self { roughness: c.first().copied() })
    }

    fn to_flat(&self) -> Vec<T> {
        self.roughness.into_iter().collect()
    }

    fn map(self, mut f: impl FnMut(usize, T) -> T) -> Self {
        Self { roughness: self.roughness.map(|m| f(0, m)) }
    }
}

#[derive(Clone, Debug)]
pub struct Ginneken {
    m: f32,
    shadowing: Shadowing,
    sampling: Sampling,
    /// [`sampler_roughness`] of m.
    sampler_t: f32,
    /// [`table::ratio_axis_constants`] of m.
    ratio_axis: [f32; 2],
    table: Arc<SlopeTable>,
}

impl PartialEq for Ginneken {
    fn eq(&self, other: &Self) -> bool {
        self.m == other.m && self.shadowing == other.shadowing && self.sampling == other.sampling
    }
}

impl Ginneken {
    pub fn new(m: f64, shadowing: Shadowing) -> Result<Self, ParamError> {
        Self::with_sampling(m, shadowing, Sampling::Cosine)
    }

    pub fn with_sampling(m: f64, shadowing: Shadowing, sampling: Sampling) -> Result<Self, ParamError> {
        let m = Self::SPEC.params[0].check(m)?;
        let sampler_t = sampler_roughness(m) as f32;
        let ratio_axis = table::ratio_axis_constants(m).map(|c| c as f32);
        Ok(Self { m: m as f32, shadowing, sampling, sampler_t, ratio_axis, table: SlopeTable::shared(m) })
    }

    pub fn sampling(&self) -> Sampling {
        self.sampling
    }

    pub fn roughness(&self) -> f32 {
        self.m
    }

    pub fn shadowing(&self) -> Shadowing {
        self.shadowing
    }

    /// Reference value of `f` (f64, direct integration, ~1e-9 relative): for tests and for
    /// measuring the table's error. Slow (~10 µs).
    pub fn eval_reference(&self, wi: glam::DVec3, wo: glam::DVec3, reflectance: f64) -> f64 {
        if wi.z <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        thread_local! {
            static REFERENCE: SlopeIntegrator = SlopeIntegrator::new(REFERENCE_NODES);
        }
        let m = self.m as f64;
        let (si, so) = (wi.truncate().length(), wo.truncate().length());
        let cos_phi = if si * so > 1e-300 { ((wi.x * wo.x + wi.y * wo.y) / (si * so)).clamp(-1.0, 1.0) } else { 1.0 };
        let integral = REFERENCE.with(|r| r.integral(m, wi.z, wo.z, cos_phi.acos()));
        let den =
            visibility_denominator(self.shadowing, wi.z, wo.z, mu_lambda(wi.z, si, m), mu_lambda(wo.z, so, m), || {
                azimuth_correlation(cos_phi)
            });
        reflectance * std::f64::consts::FRAC_1_PI * integral / den
    }
}

impl Ginneken {
    /// The CPU kernel: this roughness's tables, no derivative.
    #[inline(always)]
    pub fn kernel(&self) -> GinnekenKernel<'_, f32> {
        GinnekenKernel {
            slope: [Nodes::new(self.table.oned_cells()), Nodes::new(self.table.ratio_cells())],
            ratio_axis: self.ratio_axis,
            roughness_derivative: None,
            shadowing: self.shadowing,
            sampler_t: self.sampler_t,
            cltc: self.sampling == Sampling::Cltc,
        }
    }

    /// The tables (shared between instances of the same roughness).
    pub fn table(&self) -> &SlopeTable {
        &self.table
    }
}

/// van Ginneken's kernel: on its own roughness's tables ([`GinnekenKernel`]), or with the
/// roughness per lane on the tables stacked over m ([`GinnekenAxisKernel`]).
#[derive(Clone, Copy)]
pub enum GinnekenLane<'t, T: Real> {
    Fixed(GinnekenKernel<'t, T>),
    Axis(GinnekenAxisKernel<'t, T>),
}

impl<'t, T: Real> Kernel<T> for GinnekenLane<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        match self {
            GinnekenLane::Fixed(k) => k.reduced_f(wi, wo, rho),
            GinnekenLane::Axis(k) => k.reduced_f(wi, wo, rho),
        }
    }

    #[inline(always)]
    fn cosine_sampling(&self) -> bool {
        match self {
            GinnekenLane::Fixed(k) => k.cosine_sampling(),
            GinnekenLane::Axis(k) => k.cosine_sampling(),
        }
    }

    #[inline(always)]
    fn sample_wo(&self, wi: V3<T>, u1: T, u2: T) -> (V3<T>, T) {
        match self {
            GinnekenLane::Fixed(k) => k.sample_wo(wi, u1, u2),
            GinnekenLane::Axis(k) => k.sample_wo(wi, u1, u2),
        }
    }

    #[inline(always)]
    fn pdf_wo(&self, wi: V3<T>, wo: V3<T>) -> T {
        match self {
            GinnekenLane::Fixed(k) => k.pdf_wo(wi, wo),
            GinnekenLane::Axis(k) => k.pdf_wo(wi, wo),
        }
    }
}

impl KernelBrdf for Ginneken {
    fn f32_kernel(&self) -> impl Kernel<f32> + '_ {
        self.kernel()
    }
}

impl Registered for Ginneken {
    const SPEC: ModelSpec = ModelSpec {
        name: "ginneken",
        label: "van Ginneken",
        summary: "van Ginneken et al.: Lambertian facets on a Gaussian surface, with shadowing and masking",
        params: &[
            ParamSpec::number(
                "roughness",
                0.3,
                Range::OpenClosed(0.0, 4.0),
                "be a finite rms slope in (0, 4] (1 is already a 45° mean facet tilt)",
                "per-axis rms slope m",
            )
            .with_lane_clamp(M_MIN, M_MAX)
            // m > 0; a textured m below M_MIN is clamped to it, where its gradient vanishes.
            .with_fit(M_MIN, M_MAX),
            ParamSpec::choice(
                "shadowing",
                &["vginneken", "height_correlated"],
                "vginneken",
                "the shadowing-masking term: the paper's or height-correlated Smith",
            ),
            ParamSpec::sampling("`cosine`: as `diffuse`; `cltc`: a clipped linearly transformed cosine with a uniform share fitted to the model"),
        ],
        examples: &[&[("roughness", "0.7"), ("shadowing", "height_correlated")]],
        in_study: true,
    };
    type Lane<'t, T: Real + 't> = GinnekenLane<'t, T>;

    fn build(v: &Values) -> Result<Self, ParamError> {
        let shadowing = match v.choice(param!("shadowing")) {
            "height_correlated" => Shadowing::HeightCorrelated,
            _ => Shadowing::VanGinneken,
        };
        Self::with_sampling(v.number(param!("roughness")), shadowing, Sampling::parse(v.choice(param!("sampling"))))
    }

    fn values(&self) -> Vec<ParamValue> {
        parameter_values!(roughness: self.m, shadowing: self.shadowing.as_str(), sampling: self.sampling.as_str())
    }

    type Parameters<T: Real> = GinnekenParameters<T>;
    type Coefficients<T: Real> = GinnekenCoefficients<T>;

    /// `m − m₀` if gradients are needed, else nothing ([`GinnekenCoefficients`]).
    fn constant_coefficients<T: Real>(&self, p: GinnekenParameters<T>, gradients: Gradients) -> GinnekenCoefficients<T> {
        let dm = (gradients == Gradients::Needed).then(|| p.roughness - T::c(self.m as f64));
        GinnekenCoefficients { roughness: dm }
    }

    /// The clamped roughness itself.
    fn lane_coefficients<T: Real>(&self, p: GinnekenParameters<T>) -> GinnekenCoefficients<T> {
        GinnekenCoefficients { roughness: Some(clamp_roughness(p.roughness)) }
    }

    /// `tables`: the 1-D functions, the ratio and the `∂/∂m` of both ([`Self::tables`] of the
    /// same `evaluation`). `None` also for a lane kernel without its roughness.
    fn kernel_from<'t, T: Real + 't>(
        &self,
        c: GinnekenCoefficients<T>,
        tables: &[T::Table<'t>],
        evaluation: Evaluation,
    ) -> Option<GinnekenLane<'t, T>> {
        let [oned, ratio, d_oned, d_ratio]: [T::Table<'t>; 4] = tables.get(..4)?.try_into().ok()?;
        Some(match evaluation {
            Evaluation::Lane => GinnekenLane::Axis(
                GinnekenAxisKernel::new([oned, ratio, d_oned, d_ratio], c.roughness?, self.shadowing)
                    .with_sampling(self.sampling),
            ),
            Evaluation::Constant => {
                // The sampler's roughness is the tables' m₀, a constant: the sampling density
                // is not differentiated (`docs/sampling.md#gradients`).
                GinnekenLane::Fixed(GinnekenKernel {
                    slope: [oned, ratio],
                    ratio_axis: [T::c(self.ratio_axis[0] as f64), T::c(self.ratio_axis[1] as f64)],
                    roughness_derivative: c.roughness.map(|dm| ([d_oned, d_ratio], dm)),
                    shadowing: self.shadowing,
                    sampler_t: T::c(self.sampler_t as f64),
                    cltc: self.sampling == Sampling::Cltc,
                })
            }
        })
    }

    fn tables(&self, evaluation: Evaluation) -> Vec<&[f32]> {
        match evaluation {
            Evaluation::Constant => {
                let t = &self.table;
                vec![t.oned_cells(), t.ratio_cells(), t.oned_derivative_cells(), t.ratio_derivative_cells()]
            }
            Evaluation::Lane => {
                let t = RoughnessAxisTables::shared();
                (0..4).map(|k| t.table(k)).collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::split::MIN_COS;
    use super::*;
    use crate::diffuse_brdf::DiffuseBrdf;
    use crate::frame::spherical_direction_f64;
    use glam::DVec3;
    use table::{ONED_NODES, R_NODES};

    /// The fast path written the plain way in f64 on the same tables: two-square-root axis,
    /// `acos` for Δφ, the split's terms as written in `slope_fit_results.md`, nested linear
    /// interpolations (μΛ from the 1-D cells too), [`visibility_denominator`].
    fn fast_path_f64(g: &Ginneken, wi: DVec3, wo: DVec3) -> f64 {
        let (mu_i, mu_o) = (wi.z.clamp(MIN_COS as f64, 1.0), wo.z.clamp(MIN_COS as f64, 1.0));
        let (si, so) = (wi.truncate().length(), wo.truncate().length());
        let cos_phi = if si * so > 1e-12 { ((wi.x * wo.x + wi.y * wo.y) / (si * so)).clamp(-1.0, 1.0) } else { 1.0 };
        let cell = |x: f64, n: usize| {
            let s = x.clamp(0.0, 1.0) * (n - 1) as f64;
            let i = (s.floor() as usize).min(n - 2);
            (i, s - i as f64)
        };
        let lerp = |a: f64, b: f64, t: f64| a + t * (b - a);
        let t = &g.table;
        let oned = |mu: f64, sin: f64| -> [f64; 4] {
            let (k, f) = cell(1.0 / (1.0 + mu / sin.max(1e-300)), ONED_NODES);
            let (lo, hi) = (t.oned_node(k), t.oned_node(k + 1));
            std::array::from_fn(|j| lerp(lo[j] as f64, hi[j] as f64, f))
        };
        let m = g.m as f64;
        let (p0, p1) = (oned(mu_i, si), oned(mu_o, so));
        let rest = mu_o * mu_i * mu_i * p0[0]
            + mu_i * mu_o * mu_o * p1[0]
            + so * mu_i.powi(3) * p0[1]
            + si * mu_o.powi(3) * p1[1]
            + (1.0 + cos_phi) * si * so * (mu_i * p0[2] + mu_o * p1[2]);
        let axis_m = table::ratio_axis_roughness(m);
        let v = |mu: f64, s: f64| axis_m * s / (axis_m * s + mu);
        let ((i, fi), (o, fo), (c, fc)) =
            (cell(v(mu_i, si), R_NODES), cell(v(mu_o, so), R_NODES), cell(cos_phi.acos() / std::f64::consts::PI, R_NODES));
        let at = |i: usize, o: usize| lerp(t.ratio_node(i, o, c) as f64, t.ratio_node(i, o, c + 1) as f64, fc);
        let r = lerp(lerp(at(i, o), at(i, o + 1), fo), lerp(at(i + 1, o), at(i + 1, o + 1), fo), fi);
        let (ml_i, ml_o) = (p0[3], p1[3]);
        let den = visibility_denominator(g.shadowing, mu_i, mu_o, ml_i, ml_o, || azimuth_correlation(cos_phi));
        rest / (1.0 - r) / (std::f64::consts::PI * den)
    }

    /// The f32 eval (one-root axis, atan2 angle, weighted-sum interpolation, single division)
    /// is the same function as the plain f64 evaluation of the tables to 6e-5 relative, for
    /// θ up to 89.5°. The split sums only non-negative terms and `1 − r` stays away from 0, so
    /// f32 adds rounding, not an amplified error. The tables' own error against the integral
    /// is the separate bound of `tests/kernels/ginneken_fast_path.rs`.
    #[test]
    fn fast_path_is_its_f64_evaluation_to_rounding() {
        // R3 quasi-random sequence (Roberts 2018), as in `accuracy`.
        let g3 = 1.220_744_084_605_759_5_f64;
        let alpha = [1.0 / g3, 1.0 / (g3 * g3), 1.0 / (g3 * g3 * g3)];
        for m in [0.05, 0.3, 1.0] {
            for shadowing in [Shadowing::VanGinneken, Shadowing::HeightCorrelated] {
                let model = Ginneken::new(m, shadowing).unwrap();
                let mut worst = (0.0f64, DVec3::ZERO, DVec3::ZERO);
                for k in 0..20_000 {
                    let x: Vec<f64> = alpha.iter().map(|a| (0.5 + a * (k as f64 + 1.0)).fract()).collect();
                    let (ti, to, ph) =
                        (x[0] * 89.5f64.to_radians(), x[1] * 89.5f64.to_radians(), x[2] * std::f64::consts::TAU);
                    let wi = spherical_direction_f64(ti, 0.3).as_vec3();
                    let wo = spherical_direction_f64(to, 0.3 + ph).as_vec3();
                    let got = model.eval(wi, wo, [1.0])[0] as f64;
                    let want = fast_path_f64(&model, wi.as_dvec3(), wo.as_dvec3());
                    let err = (got - want).abs() / want;
                    if err > worst.0 {
                        worst = (err, wi.as_dvec3(), wo.as_dvec3());
                    }
                }
                assert!(
                    worst.0 <= 6e-5,
                    "m = {m} {shadowing:?}: relative error {:e} at {:?}",
                    worst.0,
                    (worst.1, worst.2)
                );
            }
        }
    }
}
