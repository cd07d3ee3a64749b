// The plugin's one exported symbol. Mitsuba dlopens `plugins/<type>.so` (links to one file,
// see cpp/build_plugin.sh) and calls init_plugin with <type>; MI_EXPORT_PLUGIN registers
// MatteBSDF under that name in every variant the wheel was built with (scalar, llvm_ad_* and
// cuda_ad_*: rgb, mono, spectral and the polarized ones), and the name selects the model.
#include "matte_bsdf.h"

using namespace mitsuba;

MI_EXPORT_PLUGIN(MatteBSDF)
