"""Bad input raises a Python exception naming the problem, never a crash: bad parameters,
unsupported variants, and the llvm variants used in Dr.Jit's symbolic mode."""
import pytest

from conftest import CONFIGS  # noqa: F401  (conftest sets up the import path)

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


def test_unsupported_variant_is_mitsubas_not_found_error():
    import mitsuba as mi
    mi.set_variant("scalar_spectral_polarized")
    import matte_mitsuba
    matte_mitsuba.register()
    with pytest.raises(Exception) as e:
        mi.load_dict({"type": "wolff"})
    assert "could not be found" in str(e.value)


def test_symbolic_mode_raises_with_instructions():
    import drjit as dr
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import matte_mitsuba
    matte_mitsuba.register()
    dr.set_flag(dr.JitFlag.SymbolicLoops, True)
    dr.set_flag(dr.JitFlag.SymbolicCalls, True)
    d = mi.cornell_box()
    d["sensor"]["film"]["width"] = d["sensor"]["film"]["height"] = 16
    d["white"]["type"] = "ginneken"
    scene = mi.load_dict(d)
    with pytest.raises(Exception) as e:
        mi.render(scene, spp=1)
    chain, c = [], e.value
    while c is not None:
        chain.append(str(c))
        c = c.__cause__ or c.__context__
    text = "\n".join(chain)
    assert "SymbolicLoops" in text and "SymbolicCalls" in text and "ginneken" in text, text
