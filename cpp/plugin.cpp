// The plugin library (libmatte_bsdfs.so): registers MatteBSDF under a plugin name in every
// variant the wheel was built with (scalar, llvm_ad_* and cuda_ad_*: rgb, mono, spectral and
// the polarized ones); the name selects the model. Mitsuba loads `plugins/<type>.so`, a small
// stub (cpp/plugin_stub.cpp) whose init_plugin forwards here.
#include "matte_bsdf.h"

using namespace mitsuba;

extern "C" MI_EXPORT void matte_register(std::string_view name, PluginRegisterFn fn) {
    MI_REGISTER_PLUGIN(fn, name, MatteBSDF);
}
