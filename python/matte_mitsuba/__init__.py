"""matte's diffuse BSDFs for Mitsuba 3: importing this package registers them.

    import mitsuba as mi
    import matte_mitsuba            # before or after mi.set_variant
    mi.set_variant('llvm_ad_rgb')
    mi.load_file('scene.xml')       # <bsdf type="wolff"/> etc. now load

Mitsuba resolves ``<bsdf type="NAME">`` to ``plugins/NAME.so`` through its process-wide file
resolver (the same for every variant); this package's folder holds one small ``NAME.so`` per
type and the library they share (``libmatte_bsdfs.so``), so prepending the folder is all that
is needed. For the ``mitsuba`` command-line tool use ``-a``: ``mitsuba -a "$(python -m
matte_mitsuba)" scene.xml``.

Every variant of the Mitsuba wheel is supported, scalar, llvm and cuda, in Dr.Jit's default
(symbolic) mode: the JIT variants trace the Rust kernels into Dr.Jit, so they run in symbolic
loops and calls, and ``reflectance`` and the numeric parameters are differentiable.

The plugins are compiled against one Mitsuba version (its C++ ABI); another version is refused
at import with an error naming both.

The package also holds what the ``matte`` command-line tool needs at run time: the Mitsuba
side of its commands (``python -m matte_mitsuba.passes`` for ``matte validate`` and ``matte
study``, ``.bench`` for ``matte bench``, ``.fit`` for ``matte fit``), the plugin benchmark
(``python -m matte_mitsuba.bench_plugin``), the GPU check (``python -m matte_mitsuba.gpu_check``),
and its data: the bundled scenes (:data:`SCENES`, what ``matte validate --all`` and ``matte
study`` render) and the simulated surfaces' tables (:data:`GROUND_TRUTH`).
"""

import os as _os

#: Folder to add to Mitsuba's search path (it contains ``plugins/``).
PLUGIN_ROOT = _os.path.dirname(_os.path.abspath(__file__))

_PLUGINS = _os.path.join(PLUGIN_ROOT, "plugins")
_LIBRARY = "libmatte_bsdfs.so"


def _built_plugins():
    if not _os.path.exists(_os.path.join(_PLUGINS, _LIBRARY)):
        raise ImportError(
            "matte_mitsuba: the plugins are not built in %s; run 'make plugin' in the matte "
            "repository, or install the matte-mitsuba wheel" % _PLUGINS
        )
    return tuple(sorted(f[:-3] for f in _os.listdir(_PLUGINS) if f.endswith(".so") and f != _LIBRARY))


#: The ``<bsdf type=...>`` names this package provides (the plugin files the build wrote).
BSDF_TYPES = _built_plugins()

#: Folder of the simulated microsurfaces' BRDF tables, files for ``tabulated_brdf``
#: (``v_cavities_sigma<σ>.json``, ``height_field_m<m>.json``; matte's docs/microgeometry.md).
#: Since the import adds :data:`PLUGIN_ROOT` to Mitsuba's file resolver, a scene may name a
#: table as ``ground_truth/v_cavities_sigma0.3.json``.
GROUND_TRUTH = _os.path.join(PLUGIN_ROOT, "ground_truth")

#: Folder of the bundled scenes (``matte validate --all`` renders its ``*.xml``, ``matte
#: study`` its ``study/*.xml``), with their assets.
SCENES = _os.path.join(PLUGIN_ROOT, "scenes")


def ground_truth_path(name):
    """The path of the packaged table ``name`` (e.g. ``"v_cavities_sigma0.3"``, ``.json``
    optional), for ``tabulated_brdf``'s ``filename``. Raises ``ValueError`` naming the tables
    there are if there is none of that name."""
    path = _os.path.join(GROUND_TRUTH, name if name.endswith(".json") else name + ".json")
    if not _os.path.isfile(path):
        have = (
            sorted(f[:-5] for f in _os.listdir(GROUND_TRUTH) if f.endswith(".json"))
            if _os.path.isdir(GROUND_TRUTH)
            else []
        )
        raise ValueError(
            "matte_mitsuba: no ground-truth table %r in %s (there are: %s)"
            % (name, GROUND_TRUTH, ", ".join(have) or "none")
        )
    return path


def numeric_parameters(model):
    """The parameters of ``model`` (an entry of :data:`MODELS`) a texture may give, in order."""
    return [p for p in model["params"] if p["kind"]["type"] in ("number", "ior")]


def _check_mitsuba_version(mi):
    from ._build import MITSUBA_VERSION

    if mi.__version__ != MITSUBA_VERSION:
        raise ImportError(
            "matte_mitsuba: its plugins were compiled against Mitsuba %s, but Mitsuba %s is "
            "installed; install mitsuba==%s (or rebuild matte against %s)"
            % (MITSUBA_VERSION, mi.__version__, MITSUBA_VERSION, mi.__version__)
        )


def register():
    """Adds the plugin folder to Mitsuba's file resolver (idempotent). Called on import."""
    import mitsuba as mi

    _check_mitsuba_version(mi)
    resolver = mi.file_resolver()
    if PLUGIN_ROOT not in [str(p) for p in resolver]:
        resolver.prepend(PLUGIN_ROOT)


register()


def _models():
    import json

    from ._build import MODELS_JSON

    return json.loads(MODELS_JSON)


#: Every model's declaration, as ``matte types --json`` prints it: ``name``, ``summary``,
#: ``params`` (each with ``name``, ``kind`` (``type``: number, ior, choice or flag, and its
#: ``default``), ``range``, ``lane_clamp``) and ``examples`` (parameter sets the tests sweep).
MODELS = _models()
