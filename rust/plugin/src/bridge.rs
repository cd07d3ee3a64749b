//! The `cxx` bridge declarations (C++ side: `cpp/matte_bsdf.h` includes the generated
//! `rust/plugin/src/bridge.rs.h`). The Rust type it exports is [`PluginBsdf`]
//! (`rust/plugin/src/plugin_bsdf.rs`), whose methods are implemented in `rust/plugin/src/lib.rs`
//! (construction, f32 entry points) and `rust/plugin/src/traced_entry.rs` (traced entry
//! points); the free functions are [`bsdf_new`] here and `matte_brdf`'s `is_file_parameter`.

// The C++-facing signatures pass every traced operand separately.
#[allow(clippy::too_many_arguments)]
#[cxx::bridge(namespace = "matte::ffi")]
pub mod ffi {
    /// The type of a [`Param`] as the C++ property has it (`matte_brdf::ParamValue`).
    enum PropertyType {
        /// `<float>` or `<integer>`: `number`.
        Number,
        /// `<string>`: `text`.
        Text,
        /// `<boolean>`: `number` is 1 or 0 (from Rust, `text` is `true` or `false` too).
        Flag,
        /// A nested `<texture>`: `number` is its mean.
        Texture,
    }

    /// One property of the `<bsdf>` element (to Rust), or one parameter of a model with its
    /// effective value (from Rust: `Number`, `Text` or `Flag`).
    struct Param {
        name: String,
        kind: PropertyType,
        number: f64,
        text: String,
    }

    /// Per-channel values (reflectance or result) of one lane; `n` of the 4 are used (RGB 3,
    /// spectral 4, mono 1). A plain struct: no FFI call to build it, unlike a slice.
    struct Channels {
        v: [f32; 4],
        n: usize,
    }

    /// A local-frame direction.
    struct Vec3f {
        x: f32,
        y: f32,
        z: f32,
    }

    unsafe extern "C++" {
        include!("matte/cpp/arena.h");

        /// The Dr.Jit value store of one trace (cpp/arena.h); see `super::traced`.
        #[namespace = "matte"]
        type Arena;

        fn lit(self: &Arena, v: f32) -> u32;
        fn add(self: &Arena, a: u32, b: u32) -> u32;
        fn sub(self: &Arena, a: u32, b: u32) -> u32;
        fn mul(self: &Arena, a: u32, b: u32) -> u32;
        fn div(self: &Arena, a: u32, b: u32) -> u32;
        fn minimum(self: &Arena, a: u32, b: u32) -> u32;
        fn maximum(self: &Arena, a: u32, b: u32) -> u32;
        fn neg(self: &Arena, a: u32) -> u32;
        fn abs(self: &Arena, a: u32) -> u32;
        fn sqrt(self: &Arena, a: u32) -> u32;
        fn floor(self: &Arena, a: u32) -> u32;
        fn fma(self: &Arena, a: u32, b: u32, c: u32) -> u32;
        fn sincos(self: &Arena, a: u32, s: &mut u32, c: &mut u32);
        fn exp(self: &Arena, a: u32) -> u32;
        fn lt(self: &Arena, a: u32, b: u32) -> u32;
        fn le(self: &Arena, a: u32, b: u32) -> u32;
        fn gt(self: &Arena, a: u32, b: u32) -> u32;
        fn eq(self: &Arena, a: u32, b: u32) -> u32;
        fn mask_lit(self: &Arena, v: bool) -> u32;
        fn mask_and(self: &Arena, a: u32, b: u32) -> u32;
        fn mask_or(self: &Arena, a: u32, b: u32) -> u32;
        fn mask_not(self: &Arena, a: u32) -> u32;
        fn select(self: &Arena, m: u32, t: u32, f: u32) -> u32;
        fn gather(self: &Arena, table: u32, idx: u32, offset: u32) -> u32;
        fn gather8(self: &Arena, table: u32, idx: u32) -> u32;
    }

    extern "Rust" {
        type PluginBsdf;

        /// Builds `kind` (plugin name) from the element's properties, textures given by their
        /// mean (`matte_brdf::construction::construct`, the renderer's construction too);
        /// throws `rust::Error` with a message naming the bad parameter.
        fn bsdf_new(kind: &str, properties: &[Param]) -> Result<Box<PluginBsdf>>;
        fn describe_parameters(self: &PluginBsdf) -> Vec<Param>;
        /// Whether `name` names a file of the model `kind` (`tabulated_brdf`'s `filename`),
        /// which the plugin resolves with Mitsuba's file resolver before handing it over.
        fn is_file_parameter(kind: &str, name: &str) -> bool;
        /// The numeric parameters with their effective values (a textured one's: the number it
        /// stands for), in the order per-lane values are given.
        fn numeric_parameters(self: &PluginBsdf) -> Vec<Param>;
        // Every evaluation takes the model's parameters one of two ways: its own constants, or
        // per-lane values of its numeric parameters (textures, in the order of
        // `numeric_parameters`; clamped into range, matte_brdf::lane).

        /// f (no cosine) into `f`; returns the pdf of sampling `wo` given `wi`. `params`: the
        /// numeric parameters' values for this call, empty for the model's own constants.
        fn eval_pdf(
            self: &PluginBsdf,
            params: &[f32],
            wi: &Vec3f,
            wo: &Vec3f,
            reflectance: &Channels,
            f: &mut Channels,
        ) -> f32;
        /// The pdf of sampling `wo` given `wi`; `params` as in `eval_pdf`.
        fn pdf(self: &PluginBsdf, params: &[f32], wi: &Vec3f, wo: &Vec3f) -> f32;
        /// Draws `wo`, writes the weight f·cos/pdf; returns the pdf (0: no sample). `params` as
        /// in `eval_pdf`.
        fn sample(
            self: &PluginBsdf,
            params: &[f32],
            wi: &Vec3f,
            u1: f32,
            u2: f32,
            reflectance: &Channels,
            wo: &mut Vec3f,
            weight: &mut Channels,
        ) -> f32;

        // ---- traced (JIT variants): arguments and results are arena indices; `lane`: per-lane
        // parameter values (textures) instead of the model's constants ----
        /// How many tables the traced kernel gathers from (van Ginneken: 4), and their
        /// contents (uploaded once): the constants' tables, or with `lane` the tables per-lane
        /// values need (van Ginneken's roughness-axis stacks).
        fn table_count(self: &PluginBsdf, lane: bool) -> usize;
        fn table(self: &PluginBsdf, k: usize, lane: bool) -> &[f32];
        /// The kernel's coefficients from the traced numeric parameters (in the order of
        /// `numeric_parameters`): once per parameter change, or with `lane` per call from the
        /// textures' values. `differentiable`: a parameter carries a gradient (van Ginneken
        /// then adds its roughness-derivative tables to the kernel). Empty if `params` is short.
        fn traced_coefficients(
            self: &PluginBsdf,
            arena: &Arena,
            params: &[u32],
            lane: bool,
            differentiable: bool,
        ) -> Vec<u32>;
        /// f·cos θo per channel into `value`; returns the pdf.
        fn traced_eval_pdf(
            self: &PluginBsdf,
            arena: &Arena,
            coefficients: &[u32],
            lane: bool,
            wi: &[u32],
            wo: &[u32],
            rho: &[u32],
            value: &mut [u32],
        ) -> u32;
        /// Draws wo (into `wo`), the weight f·cos θo/pdf (into `weight`); returns the pdf.
        fn traced_sample(
            self: &PluginBsdf,
            arena: &Arena,
            coefficients: &[u32],
            lane: bool,
            wi: &[u32],
            u1: u32,
            u2: u32,
            rho: &[u32],
            wo: &mut [u32],
            weight: &mut [u32],
        ) -> u32;
    }
}

use super::plugin_bsdf::PluginBsdf;
use matte_brdf::construction::is_file_parameter;

/// `ffi::bsdf_new`: [`PluginBsdf::new`], boxed for C++.
fn bsdf_new(kind: &str, properties: &[ffi::Param]) -> Result<Box<PluginBsdf>, String> {
    PluginBsdf::new(kind, properties).map(Box::new)
}
