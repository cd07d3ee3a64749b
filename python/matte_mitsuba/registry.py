"""matte's model registry on the Python side: which BSDF types there are and what their
parameters are, as the Rust registry declares them (``rust/brdf/src/registry/``; ``matte types
--json`` prints it, and the wheel's build writes that JSON into ``_build.py``).

Every Python caller (the package's commands, the tests, ``validation/``) asks this module
instead of re-deriving a property from the JSON:

    from matte_mitsuba import registry

    registry.NAMES                          # ('lambert', 'oren_nayar', ...), the README's order
    registry.model("eon")                   # the declaration (a dict, as the JSON has it)
    registry.numeric_parameters("eon")      # the parameters a texture may give, in order
    registry.builds_from_defaults("eon")    # no required parameter (a file)
    registry.examples("eon")                # the declared example configurations
    registry.fit_range("eon", "roughness")  # where ``matte fit`` searches it

Functions taking a model take its name or its declaration (an entry of :data:`MODELS`).
"""

import json
import math

from ._build import MODELS_JSON

#: Every model's declaration, in the README's order, as ``matte types --json`` prints it:
#: ``name``, ``label``, ``summary``, ``params`` (each with ``name``; ``kind``: ``type`` (number,
#: ior, choice, flag or file) and its ``default``, a choice's ``choices``; ``range``;
#: ``lane_clamp`` and ``fit``, ``[lo, hi]`` with ``null`` for an infinite bound; ``what``,
#: ``doc``), ``examples`` (parameter sets the tests sweep, ``[name, value]`` pairs as written in
#: a scene), ``in_study``, ``samplers`` and ``sampler`` (the default's).
MODELS = json.loads(MODELS_JSON)

#: The plugin names (``<bsdf type="...">``), in the README's order.
NAMES = tuple(m["name"] for m in MODELS)

#: Where a fit may search a reflectance, of any type: an albedo per channel.
REFLECTANCE_FIT = (0.0, 1.0)

_NUMERIC = ("number", "ior")


def model(name_or_model):
    """The declaration of a model given by name (``KeyError`` naming the registered types if
    there is none) or the declaration itself."""
    if isinstance(name_or_model, dict):
        return name_or_model
    for m in MODELS:
        if m["name"] == name_or_model:
            return m
    raise KeyError(f"matte_mitsuba: no model {name_or_model!r} (registered: {', '.join(NAMES)})")


def parameter(name_or_model, name):
    """The declaration of the parameter ``name`` of a model (``KeyError`` naming its parameters
    if it has none of that name)."""
    m = model(name_or_model)
    for p in m["params"]:
        if p["name"] == name:
            return p
    known = ", ".join(p["name"] for p in m["params"]) or "none"
    raise KeyError(f"matte_mitsuba: {m['name']} has no parameter {name!r} (its parameters: {known})")


def is_numeric(param):
    """Whether a parameter (a declaration) is a number or an index of refraction: texturable
    and differentiable."""
    return param["kind"]["type"] in _NUMERIC


def numeric_parameters(name_or_model):
    """The parameters of a model a texture may give (numbers and indices of refraction), in
    order: the order of their per-lane values."""
    return [p for p in model(name_or_model)["params"] if is_numeric(p)]


def file_parameters(name_or_model):
    """The parameters of a model that name a file it reads (required: no default)."""
    return [p for p in model(name_or_model)["params"] if p["kind"]["type"] == "file"]


def builds_from_defaults(name_or_model):
    """Whether a model builds from its defaults alone: no required parameter (a file). The
    sweeps over every model at its defaults run these."""
    return not file_parameters(name_or_model)


def default(param):
    """A parameter's default as written in a scene (a choice's word, a flag's ``true`` or
    ``false``, a number's value); ``None`` for a required parameter."""
    kind = param["kind"]
    if "default" not in kind:
        return None
    value = kind["default"]
    return ("true" if value else "false") if isinstance(value, bool) else value


def examples(name_or_model):
    """The model's declared example configurations, each a dict of parameter values as written
    in a scene (text: ``{"sigma": "0.8", "model": "full"}``), in order."""
    return [dict(pairs) for pairs in model(name_or_model)["examples"]]


def own_samplers(name_or_model):
    """The samplers a model offers besides the cosine (the choices of its ``sampling``
    parameter, ``docs/sampling.md``)."""
    return [s for s in model(name_or_model)["samplers"] if s != "cosine"]


def _bound(x, infinite):
    return infinite if x is None else float(x)


def lane_clamp(name_or_model, name):
    """``(lo, hi)``: per-lane (textured) values of a numeric parameter are clamped into it, NaN
    to ``lo`` (``docs/models.md#spatially-varying-parameters``)."""
    lo, hi = parameter(name_or_model, name)["lane_clamp"]
    return _bound(lo, -math.inf), _bound(hi, math.inf)


def fit_range(name_or_model, name):
    """``(lo, hi)``: where a fit (``matte fit``) may search the parameter ``name`` of a model,
    its values clamped into it after every step; :data:`REFLECTANCE_FIT` for ``reflectance``.
    The Rust declaration gives the bounds and their reasons (a stationary point avoided, an
    upper bound for an open range). ``KeyError`` if ``name`` is not a numeric parameter of the
    model."""
    m = model(name_or_model)
    if name == "reflectance":
        return REFLECTANCE_FIT
    p = parameter(m, name)
    if not is_numeric(p):
        raise KeyError(f"matte_mitsuba: {m['name']}'s {name!r} is a {p['kind']['type']}, not a number a fit searches")
    lo, hi = p["fit"]
    return _bound(lo, -math.inf), _bound(hi, math.inf)
