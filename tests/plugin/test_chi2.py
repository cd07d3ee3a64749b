"""Mitsuba's own `mitsuba.chi2.ChiSquareTest` with `BSDFAdapter` for every type at incidence
0°, 45° and 80° in llvm_ad_rgb with Dr.Jit's default (symbolic) mode: the chi2 test is
vectorised, and Mitsuba's own BSDF tests run it on the vectorised variants too."""

import numpy as np
import pytest
from conftest import CONFIGS, config_id

ANGLES = [0.0, 45.0, 80.0]


def xml_params(params):
    out = ""
    for k, v in params.items():
        tag = "float" if isinstance(v, (int, float)) else "string"
        out += f'<{tag} name="{k}" value="{v}"/>'
    return out


@pytest.mark.parametrize("theta", ANGLES)
@pytest.mark.parametrize("cfg", CONFIGS, ids=config_id)
@pytest.mark.parametrize("mi_variant", ["llvm_ad_rgb"], indirect=True)
def test_chi2(mi_variant, cfg, theta):
    mi = mi_variant
    kind, params = cfg
    t = np.radians(theta)
    wi = [float(np.sin(t)), 0.0, float(np.cos(t))]
    sample_func, pdf_func = mi.chi2.BSDFAdapter(kind, xml_params(params), wi=wi)
    chi2 = mi.chi2.ChiSquareTest(
        domain=mi.chi2.SphericalDomain(), sample_func=sample_func, pdf_func=pdf_func, sample_dim=3
    )
    assert chi2.run(test_count=len(CONFIGS) * len(ANGLES)), chi2.messages
