//! The `cxx` bridge declarations (C++ side: `cpp/matte_bsdf.h` includes the generated
//! `rust/ffi/bridge.rs.h`). Implementations live in `super` (`rust/ffi/mod.rs`).

#[cxx::bridge(namespace = "matte::ffi")]
pub mod ffi {
    /// One `<float>`/`<integer>`/`<string>` property of the `<bsdf>` element.
    struct Param {
        name: String,
        is_number: bool,
        number: f64,
        text: String,
    }

    /// Per-channel values (reflectance or result) of one lane; `n` of the 4 are used (RGB 3,
    /// spectral 4, mono 1). A plain struct: no FFI call to build it, unlike a slice.
    struct Channels {
        v: [f32; 4],
        n: usize,
    }

    /// Structure-of-arrays lanes for the JIT variants: one slice per component, pointing
    /// straight into Dr.Jit's evaluated buffers (no copies). Every slice has the same length;
    /// reflectance channels beyond `channels` are empty.
    struct LanesIn<'a> {
        wi_x: &'a [f32],
        wi_y: &'a [f32],
        wi_z: &'a [f32],
        /// wo for eval/pdf; (u1, u2, unused) for sample.
        v_x: &'a [f32],
        v_y: &'a [f32],
        v_z: &'a [f32],
        rho_0: &'a [f32],
        rho_1: &'a [f32],
        rho_2: &'a [f32],
        rho_3: &'a [f32],
        channels: usize,
        /// Dr.Jit's mask (one byte per lane, 0 = inactive): inactive lanes get zeros without
        /// evaluating the model. Most lanes are inactive after a few bounces.
        active: &'a [u8],
    }

    /// Outputs into Dr.Jit-allocated buffers: per-channel values (f or weight), the pdf and,
    /// for sampling, the drawn direction.
    struct LanesOut<'a> {
        out_0: &'a mut [f32],
        out_1: &'a mut [f32],
        out_2: &'a mut [f32],
        out_3: &'a mut [f32],
        pdf: &'a mut [f32],
        wo_x: &'a mut [f32],
        wo_y: &'a mut [f32],
        wo_z: &'a mut [f32],
    }

    /// A local-frame direction.
    struct Vec3f {
        x: f32,
        y: f32,
        z: f32,
    }

    extern "Rust" {
        type Model;

        /// Builds `kind` (plugin name) from its parameters; throws `rust::Error` with a
        /// message naming the bad parameter.
        fn model_new(kind: &str, params: &[Param]) -> Result<Box<Model>>;
        fn describe_parameters(self: &Model) -> Vec<Param>;
        fn numeric_parameters(self: &Model) -> Vec<Param>;
        /// f (no cosine) into `f`; returns the pdf of sampling `wo` given `wi`.
        fn eval_pdf(self: &Model, wi: &Vec3f, wo: &Vec3f, reflectance: &Channels, f: &mut Channels) -> f32;
        fn pdf(self: &Model, wi: &Vec3f, wo: &Vec3f) -> f32;
        /// Draws `wo`, writes the weight f·cos/pdf; returns the pdf (0: no sample).
        fn sample(self: &Model, wi: &Vec3f, u1: f32, u2: f32, reflectance: &Channels, wo: &mut Vec3f, weight: &mut Channels) -> f32;
        /// f (no cosine) and pdf for every lane (JIT variants, evaluated mode).
        fn eval_pdf_lanes(self: &Model, input: &LanesIn, output: &mut LanesOut);
        /// Samples every lane: wo, weight f·cos/pdf and pdf (0 where nothing was drawn).
        fn sample_lanes(self: &Model, input: &LanesIn, output: &mut LanesOut);
    }
}

use super::{Model, model_new};
