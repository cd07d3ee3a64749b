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
use bridge::ffi::{Channels, LanesIn, LanesOut, Param, Vec3f};
use rayon::prelude::*;
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

/// Runs a kernel call generic over the channel count with the lane's `n` channels.
#[inline]
fn per_channels(c: &Channels, f: impl Fn(&[f32]) -> [f32; MAX_CHANNELS]) -> [f32; MAX_CHANNELS] {
    f(&c.v[..c.n.min(MAX_CHANNELS)])
}

/// Evaluates `bsdf` for 1, 3 or 4 channels (Mitsuba's mono, RGB and spectral variants).
#[inline]
fn eval_channels(bsdf: &Bsdf, wi: Vec3, wo: Vec3, rho: &[f32]) -> [f32; MAX_CHANNELS] {
    match *rho {
        [a] => {
            let [x] = bsdf.eval(wi, wo, [a]);
            [x, 0.0, 0.0, 0.0]
        }
        [a, b, c] => {
            let [x, y, z] = bsdf.eval(wi, wo, [a, b, c]);
            [x, y, z, 0.0]
        }
        _ => {
            let mut r = [0.0; MAX_CHANNELS];
            r[..rho.len()].copy_from_slice(rho);
            bsdf.eval(wi, wo, r)
        }
    }
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

    /// `f(wi, wo)` without the cosine, per channel; returns the pdf.
    fn eval_pdf(&self, wi: &Vec3f, wo: &Vec3f, reflectance: &Channels, f: &mut Channels) -> f32 {
        let (wi, wo) = (v3(wi), v3(wo));
        f.v = per_channels(reflectance, |rho| eval_channels(&self.bsdf, wi, wo, rho));
        f.n = reflectance.n;
        self.bsdf.pdf(wi, wo)
    }

    fn pdf(&self, wi: &Vec3f, wo: &Vec3f) -> f32 {
        self.bsdf.pdf(v3(wi), v3(wo))
    }

    /// Samples `wo`; writes it and the weight `f cos θo / pdf`; returns the pdf (0: no sample).
    fn sample(&self, wi: &Vec3f, u1: f32, u2: f32, reflectance: &Channels, wo: &mut Vec3f, weight: &mut Channels) -> f32 {
        let wi = v3(wi);
        weight.n = reflectance.n;
        let Some((dir, pdf)) = self.bsdf.sample_direction(wi, Vec2::new(u1, u2)) else {
            weight.v = [0.0; MAX_CHANNELS];
            return 0.0;
        };
        *wo = Vec3f { x: dir.x, y: dir.y, z: dir.z };
        let scale = dir.z / pdf;
        weight.v = per_channels(reflectance, |rho| eval_channels(&self.bsdf, wi, dir, rho)).map(|x| x * scale);
        pdf
    }

    /// [`Self::eval_pdf`] for every lane of a JIT wavefront (evaluated mode), in parallel.
    fn eval_pdf_lanes(&self, input: &LanesIn, output: &mut LanesOut) {
        self.for_each_lane(input, output, false);
    }

    /// [`Self::sample`] for every lane: `v_x`, `v_y` hold the two uniform numbers.
    fn sample_lanes(&self, input: &LanesIn, output: &mut LanesOut) {
        self.for_each_lane(input, output, true);
    }

    fn for_each_lane(&self, input: &LanesIn, output: &mut LanesOut, sample: bool) {
        let n = output.pdf.len();
        let channels = input.channels.min(MAX_CHANNELS);
        let rho_in = [input.rho_0, input.rho_1, input.rho_2, input.rho_3];
        let inputs_ok = channels >= 1
            && [input.wi_x, input.wi_y, input.wi_z, input.v_x, input.v_y].iter().all(|s| s.len() == n)
            && (sample || input.v_z.len() == n)
            && rho_in[..channels].iter().all(|s| s.len() == n);
        let outputs_ok = [&output.out_0, &output.out_1, &output.out_2, &output.out_3][..channels].iter().all(|s| s.len() == n)
            && (!sample || [&output.wo_x, &output.wo_y, &output.wo_z].iter().all(|s| s.len() == n));
        if !inputs_ok || !outputs_ok {
            // A bug in the C++ caller; never panic across the boundary: give zero (no
            // contribution, no sample) wherever we can write.
            output.pdf.iter_mut().for_each(|p| *p = 0.0);
            return;
        }
        // Disjoint chunks of every output, processed in parallel (Dr.Jit's own threads are
        // idle while it waits for us).
        const CHUNK: usize = 8192;
        fn split(s: &mut [f32], n: usize) -> Vec<&mut [f32]> {
            if s.is_empty() { (0..n.div_ceil(CHUNK)).map(|_| Default::default()).collect() } else { s.chunks_mut(CHUNK).collect() }
        }
        let LanesOut { out_0, out_1, out_2, out_3, pdf, wo_x, wo_y, wo_z } = output;
        let mut outs: Vec<[&mut [f32]; 8]> = Vec::new();
        let mut parts = [out_0, out_1, out_2, out_3, pdf, wo_x, wo_y, wo_z]
            .map(|s| split(s, n))
            .map(|v| v.into_iter());
        while let Some(p) = parts[4].next() {
            let mut next = |k: usize| parts[k].next().unwrap_or_default();
            let (o0, o1, o2, o3) = (next(0), next(1), next(2), next(3));
            let (x, y, z) = (next(5), next(6), next(7));
            outs.push([o0, o1, o2, o3, p, x, y, z]);
        }
        outs.into_par_iter().enumerate().for_each(|(chunk, o)| {
            let base = chunk * CHUNK;
            for i in 0..o[4].len() {
                let k = base + i;
                let wi = Vec3::new(input.wi_x[k], input.wi_y[k], input.wi_z[k]);
                let mut rho = [0.0f32; MAX_CHANNELS];
                for c in 0..channels {
                    rho[c] = rho_in[c][k];
                }
                let rho = &rho[..channels];
                let (values, pdf) = if sample {
                    match self.bsdf.sample_direction(wi, Vec2::new(input.v_x[k], input.v_y[k])) {
                        Some((wo, pdf)) => {
                            o[5][i] = wo.x;
                            o[6][i] = wo.y;
                            o[7][i] = wo.z;
                            let scale = wo.z / pdf;
                            (eval_channels(&self.bsdf, wi, wo, rho).map(|x| x * scale), pdf)
                        }
                        None => {
                            o[5][i] = 0.0;
                            o[6][i] = 0.0;
                            o[7][i] = 1.0;
                            ([0.0; MAX_CHANNELS], 0.0)
                        }
                    }
                } else {
                    let wo = Vec3::new(input.v_x[k], input.v_y[k], input.v_z[k]);
                    (eval_channels(&self.bsdf, wi, wo, rho), self.bsdf.pdf(wi, wo))
                };
                for c in 0..channels {
                    o[c][i] = values[c];
                }
                o[4][i] = pdf;
            }
        });
    }
}
