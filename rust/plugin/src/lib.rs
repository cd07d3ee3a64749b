//! The boundary the Mitsuba plugin (`cpp/`) calls through `cxx`. The bridge declarations
//! are in [`bridge`], the Rust type it hands to C++, [`PluginBsdf`], in `plugin_bsdf.rs`; this
//! module implements its construction and the f32 entry points (scalar variants) on top of
//! the kernels, [`traced_entry`] the traced ones (JIT variants), which run the same generic
//! kernels with [`traced::Traced`] so that they are recorded into Dr.Jit.
//!
//! Panic policy: a Rust panic must never unwind into Mitsuba. Construction (the only place
//! with non-trivial logic: parameter parsing, table building) runs under `catch_unwind` and
//! turns a panic into a `rust::Error` exception the plugin rethrows as a Mitsuba exception.
//! The per-sample and per-trace functions do not panic: slices of the wrong length give "no
//! contribution" (zeros), table coordinates are clamped; were one to panic anyway, cxx's
//! generated shim aborts the process instead of unwinding across the FFI boundary.

mod bridge;
mod plugin_bsdf;
pub mod traced;
mod traced_entry;

use bridge::ffi::{Channels, Param, PropertyType, Vec3f};
use glam::{Vec2, Vec3};
use matte_brdf::construction::construct;
use matte_brdf::kernel;
use matte_brdf::{DiffuseBrdf, ParamValue};
use std::panic::{AssertUnwindSafe, catch_unwind};

pub use bridge::ffi;
pub use plugin_bsdf::PluginBsdf;

/// A property as [`construct`] takes it.
fn property(p: &Param) -> (&str, ParamValue) {
    let value = match p.kind {
        PropertyType::Text => ParamValue::Text(p.text.clone()),
        PropertyType::Flag => ParamValue::Flag(p.number != 0.0),
        PropertyType::Texture => ParamValue::Texture { mean: p.number },
        _ => ParamValue::Number(p.number),
    };
    (p.name.as_str(), value)
}

/// Largest number of spectral channels a variant uses (Mitsuba's spectral variants: 4).
const MAX_CHANNELS: usize = 4;

#[inline]
fn v3(v: &Vec3f) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

/// The used channels of a [`Channels`], zero-padded to [`MAX_CHANNELS`].
#[inline]
fn padded(c: &Channels) -> [f32; MAX_CHANNELS] {
    let mut r = [0.0; MAX_CHANNELS];
    let used = used(c);
    r[..used.len()].copy_from_slice(used);
    r
}

/// The used channels of a [`Channels`].
#[inline]
fn used(c: &Channels) -> &[f32] {
    &c.v[..c.n.min(MAX_CHANNELS)]
}

/// Evaluates `bsdf` for 1, 3 or 4 channels (Mitsuba's mono, RGB and spectral variants).
#[inline]
fn eval_channels(bsdf: &impl DiffuseBrdf, wi: Vec3, wo: Vec3, rho: &[f32]) -> [f32; MAX_CHANNELS] {
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

impl PluginBsdf {
    /// Builds `kind` (plugin name) from the element's properties (the bridge's `bsdf_new`); the
    /// error names the bad parameter. A panic during construction becomes an error too.
    fn new(kind: &str, properties: &[Param]) -> Result<Self, String> {
        let built = catch_unwind(AssertUnwindSafe(|| {
            let properties: Vec<(&str, ParamValue)> = properties.iter().map(property).collect();
            construct(kind, &properties).map(|c| c.model).map_err(|e| e.to_string())
        }));
        match built {
            Ok(Ok(model)) => Ok(PluginBsdf { model }),
            Ok(Err(message)) => Err(message),
            Err(_) => {
                Err(format!("internal error while constructing bsdf \"{kind}\" (a bug in matte; please report it)"))
            }
        }
    }

    /// Numeric parameters with their effective values (defaults filled in), for `traverse`.
    fn numeric_parameters(&self) -> Vec<Param> {
        self.describe_parameters().into_iter().filter(|p| p.kind == PropertyType::Number).collect()
    }

    fn describe_parameters(&self) -> Vec<Param> {
        self.model
            .parameters()
            .into_iter()
            .map(|(name, value)| {
                let (kind, number, text) = match value {
                    ParamValue::Number(x) | ParamValue::Texture { mean: x } => (PropertyType::Number, x, String::new()),
                    ParamValue::Text(s) => (PropertyType::Text, 0.0, s),
                    ParamValue::Flag(b) => (PropertyType::Flag, f64::from(u8::from(b)), b.to_string()),
                };
                Param { name: name.into(), kind, number, text }
            })
            .collect()
    }

    /// `f(wi, wo)` without the cosine, per channel; returns the pdf. `params`: the numeric
    /// parameters' values for this call (in the order of `numeric_parameters`: a texture's
    /// value at the hit, or the constant), clamped into range (`matte_brdf::lane`); empty for
    /// the model's own constants.
    fn eval_pdf(&self, params: &[f32], wi: &Vec3f, wo: &Vec3f, reflectance: &Channels, f: &mut Channels) -> f32 {
        let (wi, wo) = (v3(wi), v3(wo));
        f.n = reflectance.n;
        if params.is_empty() {
            f.v = eval_channels(&self.model, wi, wo, used(reflectance));
            return self.model.pdf(wi, wo);
        }
        f.v = [0.0; MAX_CHANNELS];
        let Some(k) = self.model.lane_kernel_f32(params) else {
            return 0.0;
        };
        f.v = kernel::eval(&k, wi.into(), wo.into(), padded(reflectance));
        kernel::pdf(&k, wi.into(), wo.into())
    }

    fn pdf(&self, params: &[f32], wi: &Vec3f, wo: &Vec3f) -> f32 {
        let (wi, wo) = (v3(wi), v3(wo));
        if params.is_empty() {
            return self.model.pdf(wi, wo);
        }
        self.model.lane_kernel_f32(params).map_or(0.0, |k| kernel::pdf(&k, wi.into(), wo.into()))
    }

    /// Samples `wo`; writes it and the weight `f cos θo / pdf`; returns the pdf (0: no sample).
    /// `params` as in [`Self::eval_pdf`].
    #[allow(clippy::too_many_arguments)] // the bridge's shape: parameters, inputs, outputs
    fn sample(
        &self,
        params: &[f32],
        wi: &Vec3f,
        u1: f32,
        u2: f32,
        reflectance: &Channels,
        wo: &mut Vec3f,
        weight: &mut Channels,
    ) -> f32 {
        let (wi, u) = (v3(wi), Vec2::new(u1, u2));
        weight.n = reflectance.n;
        weight.v = [0.0; MAX_CHANNELS];
        let drawn = if params.is_empty() {
            match *used(reflectance) {
                [a] => self.model.sample(wi, u, [a]).map(|s| (s.wo, s.pdf, [s.weight[0], 0.0, 0.0, 0.0])),
                [a, b, c] => self
                    .model
                    .sample(wi, u, [a, b, c])
                    .map(|s| (s.wo, s.pdf, [s.weight[0], s.weight[1], s.weight[2], 0.0])),
                _ => self.model.sample(wi, u, padded(reflectance)).map(|s| (s.wo, s.pdf, s.weight)),
            }
        } else {
            self.model.lane_kernel_f32(params).and_then(|k| {
                let (dir, w, pdf) = kernel::sample(&k, wi.into(), u1, u2, padded(reflectance));
                (pdf > 0.0).then_some((dir.into(), pdf, w))
            })
        };
        let Some((dir, pdf, w)) = drawn else {
            return 0.0;
        };
        *wo = Vec3f { x: dir.x, y: dir.y, z: dir.z };
        weight.v = w;
        pdf
    }
}
