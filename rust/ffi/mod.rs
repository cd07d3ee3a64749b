//! The boundary the Mitsuba plugin (`cpp/`) calls through `cxx`. The bridge declarations
//! are in [`bridge`]; this module implements them on top of the kernels.
//!
//! Panic policy: a Rust panic must never unwind into Mitsuba. Construction (the only place
//! with non-trivial logic: parameter parsing, table building) runs under `catch_unwind` and
//! turns a panic into a `rust::Error` exception the plugin rethrows as a Mitsuba exception.
//! The per-sample functions do not panic: lane slices are validated once per call (a
//! mismatch yields "no contribution", not a panic), table coordinates are clamped; were one
//! to panic anyway, cxx's generated shim aborts the process instead of unwinding across the
//! FFI boundary.

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

/// The used channels of a [`Channels`].
#[inline]
fn used(c: &Channels) -> &[f32] {
    &c.v[..c.n.min(MAX_CHANNELS)]
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
        f.v = eval_channels(&self.bsdf, wi, wo, used(reflectance));
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
        weight.v = eval_channels(&self.bsdf, wi, dir, used(reflectance)).map(|x| x * scale);
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
        if !lanes_are_consistent(input, output, n, sample) {
            // A bug in the C++ caller; never panic across the boundary: no contribution and
            // no sample anywhere.
            output.pdf.iter_mut().for_each(|p| *p = 0.0);
            return;
        }
        // Disjoint chunks of every output, processed in parallel (Dr.Jit's own threads are
        // idle while it waits for us).
        split_outputs(output, n).into_par_iter().enumerate().for_each(|(k, out)| {
            let range = k * CHUNK..k * CHUNK + out.pdf.len();
            let mut scratch = ChunkScratch::default();
            self.run_chunk(&ChunkIn::new(input, range, sample, &mut scratch), out, sample);
        });
    }

    /// The lanes of one chunk: zeros for inactive lanes, the kernels for the others.
    fn run_chunk(&self, input: &ChunkIn, out: ChunkOut, sample: bool) {
        let channels = input.channels;
        let ChunkOut { values, pdf: pdf_out, wo: [wo_x, wo_y, wo_z] } = out;
        for i in 0..pdf_out.len() {
            let (f, pdf, wo) = if input.active[i] == 0 {
                ([0.0; MAX_CHANNELS], 0.0, Vec3::Z)
            } else {
                let wi = Vec3::new(input.wi[0][i], input.wi[1][i], input.wi[2][i]);
                let mut rho = [0.0f32; MAX_CHANNELS];
                for c in 0..channels {
                    rho[c] = input.rho[c][i];
                }
                let rho = &rho[..channels];
                if sample {
                    match self.bsdf.sample_direction(wi, Vec2::new(input.v[0][i], input.v[1][i])) {
                        Some((wo, pdf)) => {
                            let scale = wo.z / pdf;
                            (eval_channels(&self.bsdf, wi, wo, rho).map(|x| x * scale), pdf, wo)
                        }
                        None => ([0.0; MAX_CHANNELS], 0.0, Vec3::Z),
                    }
                } else {
                    let wo = Vec3::new(input.v[0][i], input.v[1][i], input.v[2][i]);
                    (eval_channels(&self.bsdf, wi, wo, rho), self.bsdf.pdf(wi, wo), wo)
                }
            };
            for c in 0..channels {
                values[c][i] = f[c];
            }
            pdf_out[i] = pdf;
            if sample {
                (wo_x[i], wo_y[i], wo_z[i]) = (wo.x, wo.y, wo.z);
            }
        }
    }
}


/// Lanes per parallel work item.
const CHUNK: usize = 8192;

/// Every input has width n or 1 (a Dr.Jit literal such as a uniform reflectance, broadcast
/// here rather than materialised n times by the caller); every used output has width n.
fn lanes_are_consistent(input: &LanesIn, output: &LanesOut, n: usize, sample: bool) -> bool {
    let channels = input.channels;
    let fits = |len: usize| len == n || len == 1;
    let rho = [input.rho_0, input.rho_1, input.rho_2, input.rho_3];
    let values = [&output.out_0, &output.out_1, &output.out_2, &output.out_3];
    (1..=MAX_CHANNELS).contains(&channels)
        && [input.wi_x, input.wi_y, input.wi_z, input.v_x, input.v_y].iter().all(|s| fits(s.len()))
        && (sample || fits(input.v_z.len()))
        && fits(input.active.len())
        && rho[..channels].iter().all(|s| fits(s.len()))
        && values[..channels].iter().all(|s| s.len() == n)
        && (!sample || [&output.wo_x, &output.wo_y, &output.wo_z].iter().all(|s| s.len() == n))
}

/// One chunk's share of the outputs (unused outputs are empty slices).
struct ChunkOut<'a> {
    values: [&'a mut [f32]; MAX_CHANNELS],
    pdf: &'a mut [f32],
    wo: [&'a mut [f32]; 3],
}

/// Splits every output into `CHUNK`-lane pieces, grouped per chunk.
fn split_outputs<'a>(output: &'a mut LanesOut, n: usize) -> Vec<ChunkOut<'a>> {
    let chunks = n.div_ceil(CHUNK);
    let split = |s: &'a mut [f32]| -> std::vec::IntoIter<&'a mut [f32]> {
        let parts: Vec<&'a mut [f32]> =
            if s.is_empty() { (0..chunks).map(|_| Default::default()).collect() } else { s.chunks_mut(CHUNK).collect() };
        parts.into_iter()
    };
    let LanesOut { out_0, out_1, out_2, out_3, pdf, wo_x, wo_y, wo_z } = output;
    let mut values = [split(out_0), split(out_1), split(out_2), split(out_3)];
    let mut wo = [split(wo_x), split(wo_y), split(wo_z)];
    split(pdf)
        .map(|pdf| ChunkOut {
            values: values.each_mut().map(|it| it.next().unwrap_or_default()),
            pdf,
            wo: wo.each_mut().map(|it| it.next().unwrap_or_default()),
        })
        .collect()
}

/// Buffers for broadcasting width-1 inputs over a chunk.
#[derive(Default)]
struct ChunkScratch {
    floats: [Vec<f32>; 6 + MAX_CHANNELS],
    active: Vec<u8>,
}

/// One chunk's inputs as slices of equal length, so the lane loop indexes without
/// per-access branches.
struct ChunkIn<'a> {
    wi: [&'a [f32]; 3],
    /// wo (eval) or the 2-D sample (sample; third slice empty).
    v: [&'a [f32]; 3],
    rho: [&'a [f32]; MAX_CHANNELS],
    channels: usize,
    active: &'a [u8],
}

impl<'a> ChunkIn<'a> {
    fn new(input: &LanesIn<'a>, range: std::ops::Range<usize>, sample: bool, scratch: &'a mut ChunkScratch) -> Self {
        fn local<'s, T: Copy>(s: &'s [T], range: &std::ops::Range<usize>, buf: &'s mut Vec<T>) -> &'s [T] {
            if s.len() == 1 {
                buf.resize(range.len(), s[0]);
                buf
            } else {
                &s[range.clone()]
            }
        }
        let channels = input.channels;
        let [b0, b1, b2, b3, b4, b5, r0, r1, r2, r3] = &mut scratch.floats;
        let rho_in = [input.rho_0, input.rho_1, input.rho_2, input.rho_3];
        let mut rho = [&[][..]; MAX_CHANNELS];
        for (c, buf) in [r0, r1, r2, r3].into_iter().enumerate().take(channels) {
            rho[c] = local(rho_in[c], &range, buf);
        }
        ChunkIn {
            wi: [local(input.wi_x, &range, b0), local(input.wi_y, &range, b1), local(input.wi_z, &range, b2)],
            v: [
                local(input.v_x, &range, b3),
                local(input.v_y, &range, b4),
                if sample { &[][..] } else { local(input.v_z, &range, b5) },
            ],
            rho,
            channels,
            active: local(input.active, &range, &mut scratch.active),
        }
    }
}
