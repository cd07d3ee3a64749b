//! The models: one file or folder each, and the one list of them. The `models!` call below
//! declares each model's module and generates everything that lists the models
//! ([`DiffuseModel`], [`LaneKernel`], [`MODELS`], [`BSDF_TYPES`], the static dispatch);
//! `docs/adding-a-model.md` walks through adding one.

// The models, in the README's order: one line each.
crate::registry::models! {
    Lambert: lambert::Lambert,
    OrenNayar: oren_nayar::OrenNayar,
    Eon: eon::Eon,
    Wolff: wolff::Wolff,
    Ginneken: ginneken::Ginneken,
    RoughDiffuse: rough_diffuse::RoughDiffuse,
    Burley: burley::Burley,
    Tabulated: tabulated::Tabulated,
}
