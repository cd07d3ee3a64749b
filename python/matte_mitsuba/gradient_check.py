"""d(image mean)/d(parameter) two ways, for the gradient checks (`tests/plugin/test_gradients.py`,
`tests/plugin/test_textured_parameters.py`, `python/matte_mitsuba/gpu_check.py`):

* `adjoint_gradient`: Mitsuba's automatic differentiation, the adjoint pass of the scene's
  integrator (e.g. `prb`) run with the primal's seed, so that it is the exact derivative of
  the estimate that finite differences measure;
* `central_difference`: (mean(p + h) − mean(p − h)) / 2h of renders with the same seed
  (`shifted` moves a colour or float parameter).
"""

import numpy as np


def image_mean(mi, scene, params, spp, seed):
    """The mean of the rendered image (all pixels and channels), in float64."""
    return float(np.array(mi.render(scene, params, spp=spp, seed=seed), dtype=np.float64).mean())


def adjoint_gradient(mi, scene, params, key, spp, seed):
    """d(image mean)/d(params[key]) by the adjoint pass, flattened to float64 (one entry per
    component of the parameter: a colour's channels, a texture's texels)."""
    import drjit as dr

    dr.enable_grad(params[key])
    params.update()
    img = mi.render(scene, params, spp=spp, seed=seed)
    n = int(np.prod(img.shape))
    grad_in = mi.TensorXf(dr.full(mi.Float, 1.0 / n, n), img.shape)
    scene.integrator().render_backward(scene, params, grad_in, sensor=0, seed=seed, spp=spp)
    return np.array(dr.grad(params[key]), dtype=np.float64).ravel()


def shifted(mi, params, key):
    """`value(delta)`: the parameter `params[key]` as it is now, moved by delta (every channel of
    a colour, the value of a float), for `central_difference`; a copy of the current value,
    since assigning to `params` updates it in place."""
    base = np.array(params[key]).ravel().copy()
    if key.endswith("value"):
        return lambda delta: mi.Color3f(*[float(x) + delta for x in base])
    return lambda delta: mi.Float(float(base[0]) + delta)


def central_difference(mi, scene, params, key, value, h, spp, seed):
    """(mean(+h) − mean(−h)) / 2h, where `value(delta)` is the parameter's value moved by
    delta; the parameter is left at `value(0)`."""
    means = []
    for delta in (h, -h):
        params[key] = value(delta)
        params.update()
        means.append(image_mean(mi, scene, params, spp, seed))
    params[key] = value(0.0)
    params.update()
    return (means[0] - means[1]) / (2 * h)
