//! Measures the fast path (tables) against the reference integral over the whole domain of
//! directions up to a maximum polar angle, at quasi-random configurations (R3 sequence:
//! deterministic, evenly spread, no RNG dependency).

use super::roughness_axis::{GinnekenAxisKernel, RoughnessAxisTables};
use super::shadowing::Shadowing;
use super::{Ginneken, GinnekenKernel};
use crate::dual::Dual;
use crate::frame::spherical_direction_f64;
use crate::kernel::Kernel;
use crate::diffuse_brdf::DiffuseBrdf;
use crate::real::{Nodes, Real, V3};

#[derive(Clone, Copy, Debug)]
pub struct FastPathAccuracy {
    /// Largest |fast − reference| / reference.
    pub max_relative: f64,
    /// Mean of the same.
    pub mean_relative: f64,
    /// (θi, θo, Δφ) in degrees where the maximum occurs.
    pub worst: (f64, f64, f64),
    pub samples: usize,
}

/// Compares [`DiffuseBrdf::eval`] with [`Ginneken::eval_reference`] at `samples` configurations
/// with θi, θo uniform in [0, max_theta_deg] and Δφ uniform in [0°, 180°].
pub fn fast_path_accuracy(model: &Ginneken, max_theta_deg: f64, samples: usize) -> FastPathAccuracy {
    // R3 quasi-random sequence (Roberts 2018): additive recurrence with powers of 1/φ₃.
    let g = 1.220_744_084_605_759_5_f64;
    let alpha = [1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g)];
    let (mut max_rel, mut sum_rel, mut worst) = (0.0f64, 0.0f64, (0.0, 0.0, 0.0));
    for k in 0..samples {
        let x: Vec<f64> = alpha.iter().map(|a| (0.5 + a * (k as f64 + 1.0)).fract()).collect();
        let (ti, to, ph) = (x[0] * max_theta_deg, x[1] * max_theta_deg, x[2] * 180.0);
        let wi = spherical_direction_f64(ti.to_radians(), 0.0);
        let wo = spherical_direction_f64(to.to_radians(), ph.to_radians());
        let reference = model.eval_reference(wi, wo, 1.0);
        let fast = model.eval(wi.as_vec3(), wo.as_vec3(), [1.0])[0] as f64;
        let rel = (fast - reference).abs() / reference;
        sum_rel += rel;
        if rel > max_rel {
            max_rel = rel;
            worst = (ti, to, ph);
        }
    }
    FastPathAccuracy { max_relative: max_rel, mean_relative: sum_rel / samples as f64, worst, samples }
}

/// How well the traced kernels' roughness gradient (the slope tables' `∂/∂m` tables, first
/// order around the table's m₀, and μΛ's closed form) matches the true derivative.
#[derive(Clone, Copy, Debug)]
pub struct RoughnessGradientAccuracy {
    /// Largest error of the elasticity `∂ ln f / ∂ ln m` (the derivative's error relative to
    /// `f/m`, so it is finite where the derivative crosses zero).
    pub max_log_error: f64,
    /// Mean of the same.
    pub mean_log_error: f64,
    /// (θi, θo, Δφ) in degrees where the maximum occurs.
    pub worst: (f64, f64, f64),
    pub samples: usize,
}

/// The kernel's `∂f/∂m` (the slope tables' derivative tables, μΛ's closed form), evaluated
/// with dual numbers ([`Dual`]: the same code the plugin traces, `m − m₀` as the variable), against
/// central differences (`m (1 ± 10⁻³)`) of [`Ginneken::eval_reference`], at `samples`
/// quasi-random configurations with θi, θo ≤ `max_theta_deg`.
pub fn roughness_gradient_accuracy(model: &Ginneken, max_theta_deg: f64, samples: usize) -> RoughnessGradientAccuracy {
    let m = model.roughness() as f64;
    let h = 1e-3 * m;
    let plus = Ginneken::new(m + h, model.shadowing()).expect("valid roughness");
    let minus = Ginneken::new(m - h, model.shadowing()).expect("valid roughness");
    let t = model.table();
    let kernel = GinnekenKernel::<Dual> {
        slope: [Nodes::new(t.oned_cells()), Nodes::new(t.ratio_cells())],
        ratio_axis: super::table::ratio_axis_constants(m).map(Dual::c),
        roughness_derivative: Some((
            [Nodes::new(t.oned_derivative_cells()), Nodes::new(t.ratio_derivative_cells())],
            Dual::variable(0.0),
        )),
        shadowing: model.shadowing(),
        sampler_t: Dual::c(super::sampler_roughness(m)),
        cltc: false,
    };
    let g = 1.220_744_084_605_759_5_f64;
    let alpha = [1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g)];
    let (mut max_err, mut sum_err, mut worst) = (0.0f64, 0.0f64, (0.0, 0.0, 0.0));
    for k in 0..samples {
        let x: Vec<f64> = alpha.iter().map(|a| (0.5 + a * (k as f64 + 1.0)).fract()).collect();
        let (ti, to, ph) = (x[0] * max_theta_deg, x[1] * max_theta_deg, x[2] * 180.0);
        let wi = spherical_direction_f64(ti.to_radians(), 0.0);
        let wo = spherical_direction_f64(to.to_radians(), ph.to_radians());
        let dual = |w: glam::DVec3| V3::new(Dual::c(w.x), Dual::c(w.y), Dual::c(w.z));
        let reduced = kernel.reduced_f(dual(wi), dual(wo), [Dual::c(1.0)])[0];
        let d_table = reduced.d * std::f64::consts::FRAC_1_PI;
        let f = model.eval_reference(wi, wo, 1.0);
        let d_ref = (plus.eval_reference(wi, wo, 1.0) - minus.eval_reference(wi, wo, 1.0)) / (2.0 * h);
        let err = (d_table - d_ref).abs() * m / f;
        sum_err += err;
        if err > max_err {
            max_err = err;
            worst = (ti, to, ph);
        }
    }
    RoughnessGradientAccuracy { max_log_error: max_err, mean_log_error: sum_err / samples as f64, worst, samples }
}

/// How well the roughness-axis kernel matches the reference integral at one roughness.
#[derive(Clone, Copy, Debug)]
pub struct AxisAccuracy {
    /// Largest and mean |axis − reference| / reference of f.
    pub max_relative: f64,
    pub mean_relative: f64,
    /// Largest and mean error of the elasticity `∂ ln f / ∂ ln m` (kernel derivative by dual
    /// numbers against central differences of the reference, `m (1 ± 10⁻³)`).
    pub max_log_derivative: f64,
    pub mean_log_derivative: f64,
    pub samples: usize,
}

/// The axis kernel at roughness `m` (f64 evaluation of the same interpolation, with dual
/// numbers for `∂f/∂m`) against [`Ginneken::eval_reference`] at `samples` quasi-random
/// configurations (R3 sequence) with θi, θo ≤ `max_theta_deg`, Δφ ∈ [0°, 180°].
pub fn axis_accuracy(m: f64, shadowing: Shadowing, max_theta_deg: f64, samples: usize) -> AxisAccuracy {
    use crate::dual::Dual;
    let tables = RoughnessAxisTables::shared();
    let kernel = GinnekenAxisKernel::<Dual>::new(tables.nodes(), Dual::variable(m), shadowing);
    let (reference, plus, minus) = (
        Ginneken::new(m, shadowing).expect("valid roughness"),
        Ginneken::new(m * (1.0 + 1e-3), shadowing).expect("valid roughness"),
        Ginneken::new(m * (1.0 - 1e-3), shadowing).expect("valid roughness"),
    );
    let g = 1.220_744_084_605_759_5_f64;
    let alpha = [1.0 / g, 1.0 / (g * g), 1.0 / (g * g * g)];
    let (mut max_rel, mut sum_rel, mut max_d, mut sum_d) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for k in 0..samples {
        let x: Vec<f64> = alpha.iter().map(|a| (0.5 + a * (k as f64 + 1.0)).fract()).collect();
        let (ti, to, ph) = (x[0] * max_theta_deg, x[1] * max_theta_deg, x[2] * 180.0);
        let wi = spherical_direction_f64(ti.to_radians(), 0.0);
        let wo = spherical_direction_f64(to.to_radians(), ph.to_radians());
        let dual = |w: glam::DVec3| V3::new(Dual::c(w.x), Dual::c(w.y), Dual::c(w.z));
        let f = kernel.reduced_f(dual(wi), dual(wo), [Dual::c(1.0)])[0];
        let (value, d) = (f.v * std::f64::consts::FRAC_1_PI, f.d * std::f64::consts::FRAC_1_PI);
        let want = reference.eval_reference(wi, wo, 1.0);
        let d_want = (plus.eval_reference(wi, wo, 1.0) - minus.eval_reference(wi, wo, 1.0)) / (2e-3 * m);
        let rel = (value - want).abs() / want;
        let d_err = (d - d_want).abs() * m / want;
        (sum_rel, sum_d) = (sum_rel + rel, sum_d + d_err);
        (max_rel, max_d) = (max_rel.max(rel), max_d.max(d_err));
    }
    AxisAccuracy {
        max_relative: max_rel,
        mean_relative: sum_rel / samples as f64,
        max_log_derivative: max_d,
        mean_log_derivative: sum_d / samples as f64,
        samples,
    }
}
