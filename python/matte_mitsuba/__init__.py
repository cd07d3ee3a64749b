"""matte's diffuse BSDFs for Mitsuba 3: importing this package registers them.

    import mitsuba as mi
    import matte_mitsuba            # before or after mi.set_variant
    mi.set_variant('llvm_ad_rgb')
    mi.load_file('scene.xml')       # <bsdf type="wolff"/> etc. now load

Mitsuba resolves ``<bsdf type="NAME">`` to ``plugins/NAME.so`` (``.dylib`` on macOS, ``.dll`` on
Windows) through its process-wide file resolver (the same for every variant). The package holds
one plugin folder per supported Mitsuba release (``releases/<release>/plugins/``: one small
``NAME.so`` per type and the release's C++ layer they share, ``libmatte_bsdfs.so``) and the Rust
kernels every layer calls, once (``lib/libmatte_kernels.so``; on Windows they are inside each
layer). Importing it prepends the folder of the running release
(:data:`PLUGIN_ROOT`) to the resolver. For the ``mitsuba`` command-line tool use ``-a``:
``mitsuba -a "$(python -m matte_mitsuba)" scene.xml``.

Every variant of the Mitsuba wheel is supported, scalar, llvm and cuda, in Dr.Jit's default
(symbolic) mode: the JIT variants trace the Rust kernels into Dr.Jit, so they run in symbolic
loops and calls, and ``reflectance`` and the numeric parameters are differentiable.

Supported Mitsuba releases: :data:`MITSUBA_RELEASES` (3.7.0 to 3.9.1 on Linux x86_64, 3.8.0 to
3.9.1 on Linux aarch64, whose first Mitsuba wheels are 3.8.0's; each layer is compiled against
that release's headers, libraries, instruction set and C++ ABI). Another release is refused at
import with one line naming the supported ones and how to build matte for it: the source
distribution builds a layer for the installed Mitsuba when it is none of these.

The package also holds what the ``matte`` command-line tool needs at run time: the Mitsuba
side of its commands (``python -m matte_mitsuba.passes`` for ``matte validate`` and ``matte
study``, ``.bench`` for ``matte bench``, ``.fit`` for ``matte fit``), the plugin benchmark
(``python -m matte_mitsuba.bench_plugin``), the GPU check (``python -m matte_mitsuba.gpu_check``),
its data: the bundled scenes (:data:`SCENES`, what ``matte validate --all`` and ``matte
study`` render) and the simulated surfaces' tables (:data:`GROUND_TRUTH`), and the model
registry as the Rust side declares it (``matte_mitsuba.registry``: the types, their parameters,
defaults, examples and fit ranges; :data:`MODELS` and :func:`numeric_parameters` are its).
"""

import os as _os
import sys as _sys

#: The package's folder: its data (``ground_truth/``, ``scenes/``), the ``matte`` binary
#: (``bin/``) and the plugins of every release (``releases/``).
PACKAGE_ROOT = _os.path.dirname(_os.path.abspath(__file__))

#: What Mitsuba appends to a plugin's name on this platform (its src/core/plugin.cpp).
PLUGIN_SUFFIX = {"darwin": ".dylib", "win32": ".dll"}.get(_sys.platform, ".so")
# The layer the plugin files share, in each release's plugins/.
_LIBRARY = ("matte_bsdfs" if _sys.platform == "win32" else "libmatte_bsdfs") + PLUGIN_SUFFIX


def _releases():
    try:
        from ._build import MITSUBA_RELEASES
    except ImportError:
        raise ImportError(
            "matte_mitsuba: the plugins are not built in %s; run 'make plugin' in the matte "
            "repository, or install the matte-mitsuba wheel" % PACKAGE_ROOT
        ) from None
    return MITSUBA_RELEASES


#: The Mitsuba releases this installation has plugins for (oldest first).
MITSUBA_RELEASES = _releases()


def _release_key(version):
    return tuple(int(x) if x.isdigit() else 0 for x in version.split("."))


def _own_version():
    try:
        from importlib.metadata import version

        return version("matte-mitsuba")
    except Exception:
        return "<version>"


def _release_root(version):
    """The folder holding ``plugins/`` for Mitsuba ``version``; ImportError (one line naming
    the supported releases) when this installation has none for it."""
    root = _os.path.join(PACKAGE_ROOT, "releases", version)
    if version not in MITSUBA_RELEASES or not _os.path.isfile(_os.path.join(root, "plugins", _LIBRARY)):
        *older, newest = MITSUBA_RELEASES
        supported = ", ".join(older) + " and " + newest if older else newest
        message = (
            f"matte_mitsuba: Mitsuba {version} is installed, but matte's plugins support Mitsuba {supported} "
            f"only; install one of them (pip install 'mitsuba>={MITSUBA_RELEASES[0]},<={MITSUBA_RELEASES[-1]}')"
        )
        if _release_key(version) > _release_key(MITSUBA_RELEASES[-1]):
            # A newer release: the sdist builds a layer for it from its own headers.
            message += (
                f", or build matte for Mitsuba {version} from its source distribution "
                f"(pip install matte_mitsuba-{_own_version()}.tar.gz, with cargo and g++)"
            )
        raise ImportError(message)
    return root


def _mitsuba_version():
    import mitsuba

    return mitsuba.__version__


#: Folder to add to Mitsuba's search path: it contains ``plugins/``, built for the running
#: Mitsuba release.
PLUGIN_ROOT = _release_root(_mitsuba_version())

#: The ``<bsdf type=...>`` names this package provides (the plugin files the build wrote).
BSDF_TYPES = tuple(
    sorted(
        f[: -len(PLUGIN_SUFFIX)]
        for f in _os.listdir(_os.path.join(PLUGIN_ROOT, "plugins"))
        if f.endswith(PLUGIN_SUFFIX) and f != _LIBRARY
    )
)

if _sys.platform == "win32":
    # Mitsuba loads a plugin file with LoadLibraryW, which looks for the layer it imports
    # (matte_bsdfs.dll) among the modules already loaded, not in the plugin's own folder.
    import ctypes as _ctypes

    _ctypes.WinDLL(_os.path.join(PLUGIN_ROOT, "plugins", _LIBRARY))

#: Folder of the simulated microsurfaces' BRDF tables, files for ``tabulated_brdf``
#: (``v_cavities_sigma<σ>.json``, ``height_field_m<m>.json``; matte's docs/microgeometry.md).
#: Since the import adds :data:`PACKAGE_ROOT` to Mitsuba's file resolver, a scene may name a
#: table as ``ground_truth/v_cavities_sigma0.3.json``.
GROUND_TRUTH = _os.path.join(PACKAGE_ROOT, "ground_truth")

#: Folder of the bundled scenes (``matte validate --all`` renders its ``*.xml``, ``matte
#: study`` its ``study/*.xml``), with their assets.
SCENES = _os.path.join(PACKAGE_ROOT, "scenes")


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


def register():
    """Adds the running release's plugin folder and the package folder (for relative paths to
    its tables) to Mitsuba's file resolver (idempotent). Called on import."""
    import mitsuba as mi

    resolver = mi.file_resolver()
    present = [str(p) for p in resolver]
    for folder in (PACKAGE_ROOT, PLUGIN_ROOT):
        if folder not in present:
            resolver.prepend(folder)


register()


# The model registry (`registry`: which types there are, their parameters, defaults, examples
# and fit ranges); `MODELS` and `numeric_parameters` stay here for the callers that used them.
from .registry import MODELS, numeric_parameters  # noqa: E402,F401
