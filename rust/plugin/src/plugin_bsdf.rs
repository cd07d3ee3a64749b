//! [`PluginBsdf`], the Rust type behind the bridge's opaque `PluginBsdf`, in a file of its own
//! below the bridge (`bridge.rs`, which hands it to C++) and the files that implement its
//! methods (`lib.rs`: construction and the f32 entry points; `traced_entry.rs`: the traced
//! ones), so that the bridge and those files do not import each other.

use matte_brdf::DiffuseModel;

/// The Rust side of one plugin BSDF (`cpp/matte_bsdf.h` holds it): the constructed model,
/// any registered type, `tabulated_brdf` included.
pub struct PluginBsdf {
    pub(crate) model: DiffuseModel,
}
