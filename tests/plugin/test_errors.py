"""Bad input raises a Python exception naming the problem, never a crash: bad parameters at
construction, and bad values set through `mi.traverse` (checked again by the kernels)."""

import pytest
from conftest import CONFIGS  # noqa: F401  (conftest sets up the import path)
from matte_mitsuba import registry

BAD = [
    ({"type": "oren_nayar", "sigma": -0.1}, "sigma"),
    ({"type": "oren_nayar", "model": "fast"}, "model"),
    ({"type": "eon", "roughness": 1.5}, "roughness"),
    ({"type": "wolff", "int_ior": 0.9}, "int_ior"),
    ({"type": "wolff", "int_ior": "unobtainium"}, "int_ior"),
    ({"type": "wolff", "int_ior": 1.2, "ext_ior": 1.5}, "int_ior"),
    ({"type": "wolff", "normalization": "none"}, "normalization"),
    ({"type": "ginneken", "roughness": 0.0}, "roughness"),
    ({"type": "ginneken", "roughness": float("nan")}, "roughness"),
    ({"type": "ginneken", "shadowing": "smith"}, "shadowing"),
    ({"type": "lambert", "sigma": 0.3}, "sigma"),
    ({"type": "oren_nayar", "roughness": 0.3}, "roughness"),
    # matte's one magnitude limit (1e6), the same in the renderer and the CLI.
    ({"type": "oren_nayar", "sigma": 1e7}, "sigma"),
    ({"type": "roughdiffuse", "alpha": 1e7}, "alpha"),
]
# The magnitude limit for every other numeric parameter of every registered type (a new model's
# too; one with a required file, tabulated_brdf, has none).
BAD += [
    ({"type": m["name"], p["name"]: 1e7}, p["name"])
    for m in registry.MODELS
    if registry.builds_from_defaults(m)
    for p in registry.numeric_parameters(m)
    if {"type": m["name"], p["name"]: 1e7} not in [props for props, _ in BAD]
]


@pytest.mark.parametrize("props,name", BAD, ids=[f"{p['type']}-{n}" for p, n in BAD])
@pytest.mark.parametrize("mi_variant", ["scalar_rgb", "llvm_ad_rgb"], indirect=True)
def test_bad_parameters_raise_naming_the_parameter(mi_variant, props, name):
    mi = mi_variant
    with pytest.raises(Exception) as e:
        mi.load_dict(props)
    assert f'"{name}"' in str(e.value), str(e.value)


@pytest.mark.parametrize("mi_variant", ["scalar_rgb"], indirect=True)
def test_bad_parameter_in_xml_names_the_plugin(mi_variant):
    mi = mi_variant
    xml = '<scene version="3.0.0"><bsdf type="wolff"><float name="int_ior" value="0.5"/></bsdf></scene>'
    with pytest.raises(Exception) as e:
        mi.load_string(xml)
    assert "wolff" in str(e.value) and "int_ior" in str(e.value)


@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_bad_value_through_traverse_names_the_parameter(mi_variant):
    mi = mi_variant
    bsdf = mi.load_dict({"type": "oren_nayar"})
    params = mi.traverse(bsdf)
    params["sigma"] = -0.5
    with pytest.raises(Exception) as e:
        params.update()
    assert '"sigma"' in str(e.value) and "oren_nayar" in str(e.value), str(e.value)
