"""Makes Mitsuba 3 find matte's BSDF plugins.

    import mitsuba as mi
    mi.set_variant('scalar_rgb')
    import matte_mitsuba            # registers the plugin folder with Mitsuba's file resolver
    mi.load_file('scene.xml')       # <bsdf type="wolff"/> etc. now load

Mitsuba resolves ``<bsdf type="NAME">`` to ``plugins/NAME.so`` through its process-wide
file resolver; this package's folder holds ``plugins/{lambert,oren_nayar,eon,wolff,
ginneken}.so`` (built by ``cpp/build_plugin.sh``), so prepending it is all that is needed.
For the ``mitsuba`` command-line tool use ``-a``: ``mitsuba -a <this folder> scene.xml``
(``python -m matte_mitsuba`` prints the folder).

Every variant of the Mitsuba wheel is supported, scalar, llvm and cuda, in Dr.Jit's default
(symbolic) mode: the JIT variants trace the Rust kernels into Dr.Jit, so they run in
symbolic loops and calls, and ``reflectance`` and the numeric parameters are differentiable.
"""

import os as _os

#: Folder to add to Mitsuba's search path (it contains ``plugins/``).
PLUGIN_ROOT = _os.path.dirname(_os.path.abspath(__file__))

#: The ``<bsdf type=...>`` names this package provides.
BSDF_TYPES = ("lambert", "oren_nayar", "eon", "wolff", "ginneken", "roughdiffuse")



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


register()
