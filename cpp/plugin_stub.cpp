// `plugins/<type>.so` for every matte type (lambert, oren_nayar, …): Mitsuba resolves
// `<bsdf type="NAME">` to `plugins/NAME.so` and calls its init_plugin with NAME. Each stub is
// this same small file, linked against libmatte_bsdfs.so next to it (rpath $ORIGIN), so the
// kernels exist once however many names there are (wheels cannot hold symbolic links).
#include <mitsuba/core/object.h>

extern "C" void matte_register(std::string_view name, mitsuba::PluginRegisterFn fn);

extern "C" MI_EXPORT void init_plugin(std::string_view name, mitsuba::PluginRegisterFn fn) { matte_register(name, fn); }
