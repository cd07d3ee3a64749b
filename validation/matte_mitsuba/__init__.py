"""Makes Mitsuba 3 find matte's BSDF plugins.

    import mitsuba as mi
    mi.set_variant('scalar_rgb')
    import matte_mitsuba            # registers the plugin folder with Mitsuba's file resolver
    mi.load_file('scene.xml')       # <bsdf type="wolff"/> etc. now load

Mitsuba resolves ``<bsdf type="NAME">`` to ``plugins/NAME.so`` through its process-wide
file resolver; this package's folder holds ``plugins/{lambert,oren_nayar,eon,wolff,
ginneken}.so`` (built by ``cpp/build_plugin.sh``), so prepending it is all that is needed.
For the ``mitsuba`` command-line tool use ``-a`` and a scalar variant or evaluated mode:
``mitsuba -a <this folder> -m scalar_rgb scene.xml`` or ``mitsuba -a <this folder> -W -W
scene.xml`` (``python -m matte_mitsuba`` prints the folder).

Supported variants: scalar_rgb, scalar_spectral, llvm_ad_rgb, llvm_ad_mono and
llvm_ad_spectral. The llvm variants need Dr.Jit's evaluated mode; see ``evaluated_mode``.
"""

import os as _os

#: Folder to add to Mitsuba's search path (it contains ``plugins/``).
PLUGIN_ROOT = _os.path.dirname(_os.path.abspath(__file__))

#: The ``<bsdf type=...>`` names this package provides.
BSDF_TYPES = ("lambert", "oren_nayar", "eon", "wolff", "ginneken")

#: Variants the plugins are built for.
VARIANTS = ("scalar_rgb", "scalar_spectral", "llvm_ad_rgb", "llvm_ad_mono", "llvm_ad_spectral")


def _check_built():
    missing = [t for t in BSDF_TYPES if not _os.path.exists(_os.path.join(PLUGIN_ROOT, "plugins", t + ".so"))]
    if missing:
        raise ImportError(
            "matte_mitsuba: plugins %s are not built in %s; run 'make plugin' (or 'make test') "
            "in the matte repository" % (", ".join(missing), _os.path.join(PLUGIN_ROOT, "plugins")))


def register():
    """Adds the plugin folder to Mitsuba's file resolver (idempotent). Called on import."""
    import mitsuba as mi
    _check_built()
    resolver = mi.file_resolver()
    if PLUGIN_ROOT not in [str(p) for p in resolver]:
        resolver.prepend(PLUGIN_ROOT)


def evaluated_mode():
    """Switches Dr.Jit to evaluated loops and calls, which matte's llvm variants need
    (a Rust kernel cannot be traced into a Dr.Jit kernel)."""
    import drjit as dr
    dr.set_flag(dr.JitFlag.SymbolicLoops, False)
    dr.set_flag(dr.JitFlag.SymbolicCalls, False)


register()
