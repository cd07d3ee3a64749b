//! The boundary the Mitsuba plugin (`cpp/`) calls through `cxx`. The bridge declarations
//! are in [`bridge`]; this module implements them on top of the kernels.
//!
//! Panic policy: a Rust panic must never unwind into Mitsuba. Construction (the only place
//! with non-trivial logic: parameter parsing, table building) runs under `catch_unwind` and
//! turns a panic into a `rust::Error` exception the plugin rethrows as a Mitsuba exception.
//! The per-sample functions are panic-free by construction (no allocation, no indexing that
//! can go out of bounds, clamped table coordinates); were one to panic anyway, cxx's
//! generated shim aborts the process instead of unwinding across the FFI boundary.

mod bridge;

use crate::brdf::{Bsdf, DiffuseBrdf, ParamValue, Params};
use bridge::ffi::{Param, Vec3f};
use glam::{Vec2, Vec3};
use std::panic::{AssertUnwindSafe, catch_unwind};

pub use bridge::ffi;

/// A constructed model as the plugin holds it.
pub struct Model {
    bsdf: Bsdf,
}

/// Largest number of spectral channels a variant uses (Mitsuba's spectral variants: 4).
const MAX_CHANNELS: usize = 4;

#[inline]
fn v3(v: &Vec3f) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

fn model_new(kind: &str, params: &[Param]) -> Result<Box<Model>, String> {
    let built = catch_unwind(AssertUnwindSafe(|| {
        let mut p = Params::new();
        for param in params {
            let value = if param.is_number { ParamValue::Number(param.number) } else { ParamValue::Text(param.text.clone()) };
            p.push(&param.name, value);
        }
        Bsdf::from_params(kind, p).map_err(|e| e.to_string())
    }));
    match built {
        Ok(Ok(bsdf)) => Ok(Box::new(Model { bsdf })),
        Ok(Err(message)) => Err(message),
        Err(_) => Err(format!("internal error while constructing bsdf \"{kind}\" (a bug in matte; please report it)")),
    }
}

/// Calls `f` with the reflectance as a fixed-size array of the variant's channel count.
#[inline]
fn with_channels(reflectance: &[f32], out: &mut [f32], f: impl Fn([f32; MAX_CHANNELS]) -> [f32; MAX_CHANNELS]) {
    let n = reflectance.len().min(out.len()).min(MAX_CHANNELS);
    let mut rho = [0.0f32; MAX_CHANNELS];
    rho[..n].copy_from_slice(&reflectance[..n]);
    let r = f(rho);
    out[..n].copy_from_slice(&r[..n]);
}

impl Model {
    fn kind(&self) -> String {
        self.bsdf.kind().to_string()
    }

    /// Numeric parameters with their effective values (defaults filled in), for `traverse`.
    fn numeric_parameters(&self) -> Vec<Param> {
        self.describe_parameters().into_iter().filter(|p| p.is_number).collect()
    }

    fn describe_parameters(&self) -> Vec<Param> {
        self.bsdf
            .parameters()
            .into_iter()
            .map(|(name, value)| match value {
                ParamValue::Number(x) => Param { name: name.into(), is_number: true, number: x, text: String::new() },
                ParamValue::Text(s) => Param { name: name.into(), is_number: false, number: 0.0, text: s },
            })
            .collect()
    }

    /// `f(wi, wo)` without the cosine, per channel.
    fn eval(&self, wi: &Vec3f, wo: &Vec3f, reflectance: &[f32], out: &mut [f32]) {
        let (wi, wo) = (v3(wi), v3(wo));
        match reflectance.len() {
            1 => out[..1].copy_from_slice(&self.bsdf.eval(wi, wo, [reflectance[0]])),
            3 if out.len() >= 3 => out[..3].copy_from_slice(&self.bsdf.eval(wi, wo, [reflectance[0], reflectance[1], reflectance[2]])),
            _ => with_channels(reflectance, out, |rho| self.bsdf.eval(wi, wo, rho)),
        }
    }

    fn pdf(&self, wi: &Vec3f, wo: &Vec3f) -> f32 {
        self.bsdf.pdf(v3(wi), v3(wo))
    }

    /// Samples `wo`; writes it and the weight `f cos θo / pdf`; returns the pdf (0: no sample).
    fn sample(&self, wi: &Vec3f, u1: f32, u2: f32, reflectance: &[f32], wo: &mut Vec3f, weight: &mut [f32]) -> f32 {
        let wi = v3(wi);
        let Some((dir, pdf)) = self.bsdf.sample_direction(wi, Vec2::new(u1, u2)) else {
            weight.iter_mut().for_each(|w| *w = 0.0);
            return 0.0;
        };
        *wo = Vec3f { x: dir.x, y: dir.y, z: dir.z };
        let scale = dir.z / pdf;
        self.eval(&Vec3f { x: wi.x, y: wi.y, z: wi.z }, wo, reflectance, weight);
        weight.iter_mut().take(reflectance.len()).for_each(|w| *w *= scale);
        pdf
    }

    /// Batch form of [`Self::eval`] + [`Self::pdf`] for the JIT variants (evaluated mode):
    /// structure-of-arrays inputs of `n` lanes; `reflectance` and `f_out` are channel-major
    /// (`channels × n`). Returns f without the cosine.
    #[allow(clippy::too_many_arguments)]
    fn eval_pdf_batch(&self, wi: &[f32], wo: &[f32], reflectance: &[f32], channels: usize, f_out: &mut [f32], pdf_out: &mut [f32]) {
        let n = pdf_out.len();
        if channels == 0 || wi.len() < 3 * n || wo.len() < 3 * n || reflectance.len() < channels * n || f_out.len() < channels * n {
            return;
        }
        let mut rho = [0.0f32; MAX_CHANNELS];
        for k in 0..n {
            let a = Vec3::new(wi[k], wi[n + k], wi[2 * n + k]);
            let b = Vec3::new(wo[k], wo[n + k], wo[2 * n + k]);
            for c in 0..channels.min(MAX_CHANNELS) {
                rho[c] = reflectance[c * n + k];
            }
            let f = self.bsdf.eval(a, b, rho);
            for c in 0..channels.min(MAX_CHANNELS) {
                f_out[c * n + k] = f[c];
            }
            pdf_out[k] = self.bsdf.pdf(a, b);
        }
    }

    /// Batch form of [`Self::sample`]: `u` is `2 × n`, `wo_out` is `3 × n`, `weight_out`
    /// channel-major; `pdf_out` 0 where no direction was drawn.
    #[allow(clippy::too_many_arguments)]
    fn sample_batch(&self, wi: &[f32], u: &[f32], reflectance: &[f32], channels: usize, wo_out: &mut [f32], weight_out: &mut [f32], pdf_out: &mut [f32]) {
        let n = pdf_out.len();
        if channels == 0 || wi.len() < 3 * n || u.len() < 2 * n || reflectance.len() < channels * n || wo_out.len() < 3 * n || weight_out.len() < channels * n {
            return;
        }
        let mut rho = [0.0f32; MAX_CHANNELS];
        for k in 0..n {
            let a = Vec3::new(wi[k], wi[n + k], wi[2 * n + k]);
            for c in 0..channels.min(MAX_CHANNELS) {
                rho[c] = reflectance[c * n + k];
            }
            match self.bsdf.sample(a, Vec2::new(u[k], u[n + k]), rho) {
                Some(s) => {
                    wo_out[k] = s.wo.x;
                    wo_out[n + k] = s.wo.y;
                    wo_out[2 * n + k] = s.wo.z;
                    for c in 0..channels.min(MAX_CHANNELS) {
                        weight_out[c * n + k] = s.weight[c];
                    }
                    pdf_out[k] = s.pdf;
                }
                None => {
                    for c in 0..channels.min(MAX_CHANNELS) {
                        weight_out[c * n + k] = 0.0;
                    }
                    wo_out[k] = 0.0;
                    wo_out[n + k] = 0.0;
                    wo_out[2 * n + k] = 1.0;
                    pdf_out[k] = 0.0;
                }
            }
        }
    }
}
