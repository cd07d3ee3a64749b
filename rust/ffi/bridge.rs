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
        fn kind(self: &Model) -> String;
        fn describe_parameters(self: &Model) -> Vec<Param>;
        fn numeric_parameters(self: &Model) -> Vec<Param>;
        fn eval(self: &Model, wi: &Vec3f, wo: &Vec3f, reflectance: &[f32], out: &mut [f32]);
        fn pdf(self: &Model, wi: &Vec3f, wo: &Vec3f) -> f32;
        fn sample(self: &Model, wi: &Vec3f, u1: f32, u2: f32, reflectance: &[f32], wo: &mut Vec3f, weight: &mut [f32]) -> f32;
        fn eval_pdf_batch(self: &Model, wi: &[f32], wo: &[f32], reflectance: &[f32], channels: usize, f_out: &mut [f32], pdf_out: &mut [f32]);
        fn sample_batch(self: &Model, wi: &[f32], u: &[f32], reflectance: &[f32], channels: usize, wo_out: &mut [f32], weight_out: &mut [f32], pdf_out: &mut [f32]);
    }
}

use super::{Model, model_new};
