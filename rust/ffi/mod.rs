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
        // Inputs are width n or width 1 (a Dr.Jit literal such as a uniform reflectance, which
        // is broadcast here rather than materialised n times by the caller).
        let fits = |len: usize| len == n || len == 1;
        let inputs_ok = channels >= 1
            && [input.wi_x, input.wi_y, input.wi_z, input.v_x, input.v_y].iter().all(|s| fits(s.len()))
            && (sample || fits(input.v_z.len()))
            && fits(input.active.len())
            && rho_in[..channels].iter().all(|s| fits(s.len()));
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
            let [o0, o1, o2, o3, pdf_out, wo_x, wo_y, wo_z] = o;
            let len = pdf_out.len();
            let range = chunk * CHUNK..chunk * CHUNK + len;
            // Chunk-local views of equal length (width-1 inputs expanded into a chunk buffer),
            // so that the loop below indexes without per-access branches or bounds checks.
            fn local<'s>(s: &'s [f32], range: &std::ops::Range<usize>, buf: &'s mut Vec<f32>) -> &'s [f32] {
                if s.len() == 1 {
                    buf.resize(range.len(), s[0]);
                    buf
                } else {
                    &s[range.clone()]
                }
            }
            let mut bufs: [Vec<f32>; 6 + MAX_CHANNELS] = Default::default();
            let [b0, b1, b2, b3, b4, b5, r0, r1, r2, r3] = &mut bufs;
            let wi_x = local(input.wi_x, &range, b0);
            let wi_y = local(input.wi_y, &range, b1);
            let wi_z = local(input.wi_z, &range, b2);
            let v_x = local(input.v_x, &range, b3);
            let v_y = local(input.v_y, &range, b4);
            let v_z = if sample { &[][..] } else { local(input.v_z, &range, b5) };
            let active_buf;
            let active = if input.active.len() == 1 {
                active_buf = vec![input.active[0]; len];
                &active_buf[..]
            } else {
                &input.active[range.clone()]
            };
            let rho_local = [
                local(rho_in[0], &range, r0),
                if channels > 1 { local(rho_in[1], &range, r1) } else { &[][..] },
                if channels > 2 { local(rho_in[2], &range, r2) } else { &[][..] },
                if channels > 3 { local(rho_in[3], &range, r3) } else { &[][..] },
            ];
            let outs = [o0, o1, o2, o3];
            for i in 0..len {
                let (values, pdf, wo) = if active[i] == 0 {
                    ([0.0; MAX_CHANNELS], 0.0, Vec3::Z)
                } else {
                    let wi = Vec3::new(wi_x[i], wi_y[i], wi_z[i]);
                    let mut rho = [0.0f32; MAX_CHANNELS];
                    for c in 0..channels {
                        rho[c] = rho_local[c][i];
                    }
                    let rho = &rho[..channels];
                    if sample {
                        match self.bsdf.sample_direction(wi, Vec2::new(v_x[i], v_y[i])) {
                            Some((wo, pdf)) => {
                                let scale = wo.z / pdf;
                                (eval_channels(&self.bsdf, wi, wo, rho).map(|x| x * scale), pdf, wo)
                            }
                            None => ([0.0; MAX_CHANNELS], 0.0, Vec3::Z),
                        }
                    } else {
                        let wo = Vec3::new(v_x[i], v_y[i], v_z[i]);
                        (eval_channels(&self.bsdf, wi, wo, rho), self.bsdf.pdf(wi, wo), wo)
                    }
                };
                for c in 0..channels {
                    outs[c][i] = values[c];
                }
                pdf_out[i] = pdf;
                if sample {
                    wo_x[i] = wo.x;
                    wo_y[i] = wo.y;
                    wo_z[i] = wo.z;
                }
            }
        });
    }
}

