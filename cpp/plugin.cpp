// The plugin's one exported symbol. Mitsuba dlopens `plugins/<type>.so` (links to one file,
// see cpp/build_plugin.sh) and calls init_plugin with <type>; we register MatteBSDF for the
// variants matte supports. Unregistered variants get Mitsuba's own "could not be found" error.
#include "matte_bsdf.h"

using namespace mitsuba;

#define MATTE_REGISTER(variant, F, S)                                                         \
    fn(name, variant, MatteBSDF<F, S>::Type,                                                  \
       [](void *, const Properties &p) -> ref<Object> { return new MatteBSDF<F, S>(p); })

extern "C" MI_EXPORT void init_plugin(std::string_view name, PluginRegisterFn fn) {
    using LLVMFloat = dr::DiffArray<JitBackend::LLVM, float>;
    using ScalarRGB = Color<float, 3>;
    using ScalarSpectral = Spectrum<float, 4>;
    using LLVMRGB = Color<LLVMFloat, 3>;
    using LLVMMono = Color<LLVMFloat, 1>;
    using LLVMSpectral = Spectrum<LLVMFloat, 4>;
    MATTE_REGISTER("scalar_rgb", float, ScalarRGB);
    MATTE_REGISTER("scalar_spectral", float, ScalarSpectral);
    MATTE_REGISTER("llvm_ad_rgb", LLVMFloat, LLVMRGB);
    MATTE_REGISTER("llvm_ad_mono", LLVMFloat, LLVMMono);
    MATTE_REGISTER("llvm_ad_spectral", LLVMFloat, LLVMSpectral);
}
