"""The README's plugin example, as written there: `llvm_ad_rgb` with Dr.Jit's defaults renders
`all_types.xml`, and `dr.backward` through a `prb` render gives every matte parameter a finite,
non-zero gradient."""
import os

import numpy as np

from conftest import REPO


def test_readme_example(monkeypatch):
    monkeypatch.chdir(REPO)
    import drjit as dr
    import mitsuba as mi
    mi.set_variant('llvm_ad_rgb')            # Dr.Jit's defaults: symbolic loops and calls
    import matte_mitsuba                     # noqa: F401  registers matte's BSDFs in every variant
    assert dr.flag(dr.JitFlag.SymbolicLoops) and dr.flag(dr.JitFlag.SymbolicCalls)

    scene = mi.load_file('mitsuba_scenes/all_types.xml', res=32, spp=4)
    image = mi.render(scene)
    assert np.isfinite(np.array(image)).all()

    params = mi.traverse(scene)
    keys = [k for k in params.keys() if k.endswith(('.sigma', '.roughness', '.int_ior', '.ext_ior', 'reflectance.value'))]
    for k in keys:
        dr.enable_grad(params[k])
    params.update()
    image = mi.render(scene, params, integrator=mi.load_dict({'type': 'prb'}), spp=16)
    dr.backward(dr.mean(image, axis=None))
    # every matte parameter of the scene: 8 reflectances, 2 sigma, 3 roughness, 2×2 IORs
    assert len(keys) == 17, keys
    for k in keys:
        g = np.array(dr.grad(params[k]))
        assert np.isfinite(g).all() and np.any(g != 0), (k, g)
    assert os.path.exists(os.path.join(REPO, 'mitsuba_scenes', 'all_types.xml'))
