//! Lobe-level efficiency of the samplers (`docs/sampling.md`): for each model and roughness,
//! the variance of the sampling weight `w = f cos θo / pdf` (ρ = 1) against the incidence,
//! under the model's own sampler and under the cosine, and the time per sample of each.
//!
//! The variance is exact up to quadrature, not estimated: `Var_p[w] = ∫ (f cos)² / p dω − E²`
//! with `E = ∫ f cos dω`, by a midpoint rule in (cos θo, φ) — no sampling noise, so small
//! differences between samplers show. Under the cosine `p = cos/π`, so the second moment is
//! `π ∫ f² cos dω`. The efficiency of a sampler is `1 / (Var × time)`; the gain is its ratio
//! to the cosine's.

use glam::{Vec2, Vec3};
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};
use std::f64::consts::PI;
use std::time::Instant;

/// The incidences (degrees) of the table and plot.
pub const THETA_I: [f64; 10] = [0.0, 15.0, 30.0, 45.0, 60.0, 70.0, 75.0, 80.0, 85.0, 89.0];

/// One model configuration at one incidence.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LobeVariance {
    pub theta_i: f64,
    /// `E(θi)` for ρ = 1.
    pub albedo: f64,
    /// `Var[w]` under the model's sampler.
    pub variance: f64,
    /// `Var[w]` under the cosine.
    pub variance_cosine: f64,
}

/// One model configuration: its variances and sample times.
#[derive(Clone, Debug, serde::Serialize)]
pub struct SamplerRow {
    /// `type` and parameters, as in a scene (`eon roughness=1`).
    pub label: String,
    pub model: String,
    pub roughness: f64,
    /// Whether the model samples its own lobe (else its own sampler is the cosine).
    pub own_sampler: bool,
    pub lobe: Vec<LobeVariance>,
    /// ns per `sample` (direction, pdf and weight) with the model's sampler and with the cosine.
    pub ns_per_sample: f64,
    pub ns_per_sample_cosine: f64,
}

/// `(E, Var_own, Var_cosine)` at `theta_i` (degrees), `n` cells in cos θo and `2n` in φ.
pub fn weight_variance(model: &DiffuseModel, theta_i: f64, n: usize) -> (f64, f64, f64) {
    let t = theta_i.to_radians();
    let wi = Vec3::new(t.sin() as f32, 0.0, t.cos() as f32);
    let (nz, nphi) = (n, 2 * n);
    let cell = 2.0 * PI / (nz * nphi) as f64;
    let (mut e, mut m_own, mut m_cos) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..nz {
        let z = (i as f64 + 0.5) / nz as f64;
        let s = (1.0 - z * z).sqrt();
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) / nphi as f64 * 2.0 * PI;
            let wo = Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
            let f = model.eval(wi, wo, [1.0])[0] as f64;
            let fc = f * z;
            e += fc;
            m_cos += PI * f * f * z;
            let p = model.pdf(wi, wo) as f64;
            if fc > 0.0 {
                m_own += if p > 0.0 { fc * fc / p } else { f64::INFINITY };
            }
        }
    }
    let e = e * cell;
    (e, (m_own * cell - e * e).max(0.0), (m_cos * cell - e * e).max(0.0))
}

/// ns per `sample` call of `model`, over `count` draws spread over incidences to 89°.
fn time_sampling(model: &DiffuseModel, count: usize) -> f64 {
    let mut rng = matte_brdf::rng::Pcg32::new(7, 11);
    let inputs: Vec<(Vec3, Vec2)> = (0..4096)
        .map(|_| {
            let z = 0.02 + 0.98 * rng.next_f32();
            let phi = 2.0 * std::f32::consts::PI * rng.next_f32();
            let s = (1.0 - z * z).sqrt();
            (Vec3::new(s * phi.cos(), s * phi.sin(), z), Vec2::new(rng.next_f32(), rng.next_f32()))
        })
        .collect();
    let mut best = f64::INFINITY;
    for _ in 0..3 {
        let start = Instant::now();
        let mut sink = 0.0f32;
        for k in 0..count {
            let (wi, u) = inputs[k % inputs.len()];
            if let Some(s) = model.sample(std::hint::black_box(wi), u, [0.8f32, 0.5, 0.2]) {
                sink += s.weight[0] + s.pdf;
            }
        }
        std::hint::black_box(sink);
        best = best.min(start.elapsed().as_secs_f64() * 1e9 / count as f64);
    }
    best
}

/// Every registered model with a numeric first parameter (its roughness) at 0.3 and 1.0,
/// and Lambert; `quick`: a coarse grid and few timed samples.
pub fn measure(quick: bool) -> Vec<SamplerRow> {
    let (n, count) = if quick { (100, 20_000) } else { (600, 2_000_000) };
    let mut rows = Vec::new();
    for spec in matte_brdf::MODELS.iter().filter(|s| s.builds_from_defaults()) {
        let roughness = spec.numeric().next().filter(|p| p.name != "int_ior").map(|p| p.name);
        let values: &[f64] = if roughness.is_some() { &[0.3, 1.0] } else { &[0.0] };
        for &r in values {
            let params: Vec<(&str, ParamValue)> = roughness.map(|name| (name, r.into())).into_iter().collect();
            // The model's own sampler where it offers one (its `sampling` choices), and the cosine.
            let own_name = spec.own_sampler();
            let with = |sampling: &str| {
                let mut p = params.clone();
                p.push(("sampling", sampling.into()));
                DiffuseModel::with(spec.name, &p).ok()
            };
            let (Some(model), Some(cosine)) = (
                own_name.map_or_else(|| DiffuseModel::with(spec.name, &params).ok(), &with),
                own_name.map_or_else(|| DiffuseModel::with(spec.name, &params).ok(), |_| with("cosine")),
            ) else {
                continue;
            };
            let own = model.own_sampler();
            let lobe = THETA_I
                .iter()
                .map(|&t| {
                    let (albedo, variance, variance_cosine) = weight_variance(&model, t, n);
                    // Without an own sampler both are the cosine's (the quadrature of the f32
                    // pdf would only add rounding).
                    let variance = if own { variance } else { variance_cosine };
                    LobeVariance { theta_i: t, albedo, variance, variance_cosine }
                })
                .collect();
            let ns_per_sample = time_sampling(&model, count);
            let ns_per_sample_cosine = if own { time_sampling(&cosine, count) } else { ns_per_sample };
            let label = match roughness {
                Some(name) => format!("{} {name}={r}", spec.name),
                None => spec.name.to_string(),
            };
            rows.push(SamplerRow {
                label,
                model: spec.name.into(),
                roughness: r,
                own_sampler: own,
                lobe,
                ns_per_sample,
                ns_per_sample_cosine,
            });
        }
    }
    rows
}

/// The Markdown table: per configuration and incidence, the weight's variance under the cosine
/// and the own sampler, their ratio, and the efficiency gain including the sample time.
pub fn table(rows: &[SamplerRow]) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "machine: {}", super::report::machine());
    let _ = writeln!(
        s,
        "\n| model | ns/sample own / cosine | θi | E | Var cosine | Var own | variance ratio | efficiency gain |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for r in rows {
        for (k, l) in r.lobe.iter().enumerate() {
            let head = if k == 0 {
                format!("{} | {:.1} / {:.1}", r.label, r.ns_per_sample, r.ns_per_sample_cosine)
            } else {
                " | ".into()
            };
            // Below 1e-6 E² a variance is quadrature rounding: the weight is constant.
            let floor = 1e-6 * l.albedo * l.albedo;
            let (ratio, gain) = if l.variance > floor && l.variance_cosine > floor {
                let ratio = l.variance_cosine / l.variance;
                (format!("{ratio:.2}"), format!("{:.2}", ratio * r.ns_per_sample_cosine / r.ns_per_sample))
            } else {
                ("—".to_string(), "—".to_string())
            };
            let var = |v: f64| if v > floor { format!("{v:.3e}") } else { "0".into() };
            let _ = writeln!(
                s,
                "| {head} | {:.0}° | {:.4} | {} | {} | {ratio} | {gain} |",
                l.theta_i,
                l.albedo,
                var(l.variance_cosine),
                var(l.variance)
            );
        }
    }
    s
}
