//! Builds what C++ needs: the `cxx` bridge glue (`rust/plugin/src/bridge.rs`) that the Mitsuba
//! plugin in `cpp/` calls. It is bundled into this package's staticlib (`libmatte_plugin.a`, the kernels of `matte-brdf` and the bridge), which
//! `cpp/build_plugin.py` links with the plugin object into the Mitsuba plugin. The plugin's
//! own C++ needs Mitsuba's headers from the virtual environment, so it is compiled there,
//! not here: `cargo build` and `cargo test` work without Mitsuba installed.

fn main() {
    // C++ includes the bridge as "matte/rust/plugin/src/bridge.rs.h" and the arena as "matte/cpp/arena.h"
    // (the repository as `matte/`), whatever the package is called.
    cxx_build::CFG.include_prefix = "matte";
    cxx_build::bridge("rust/plugin/src/bridge.rs").std("c++17").flag_if_supported("-fPIC").compile("matte-ffi");
    println!("cargo:rerun-if-changed=rust/plugin/src/bridge.rs");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=cpp/arena.h");
}
