//! Mitsuba 0.6's `roughdiffuse` (`src/bsdfs/roughdiffuse.cpp`): Oren–Nayar with σ = α/√2, the
//! full model unless `use_fast_approx`, sampled with Oren–Nayar's fitted sampler. (0.6-style
//! XML, `useFastApprox` in version 0.6.0, is tested in `tests/render/matte_bsdf.rs`.)

use crate::common;
use glam::Vec3;
use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue};

#[test]
fn alpha_is_oren_nayar_sigma_times_one_over_sqrt2() {
    for (fast, model) in [("false", "full"), ("true", "qualitative")] {
        for alpha in [0.0, 0.2, 0.45, 1.3] {
            let rd = common::model("roughdiffuse", &[("alpha", &alpha.to_string()), ("use_fast_approx", fast)]);
            let sigma = (alpha / std::f64::consts::SQRT_2).to_string();
            let on = common::model("oren_nayar", &[("sigma", &sigma), ("model", model)]);
            for k in 0..2000 {
                let t = k as f32 * 0.618_034;
                let wi =
                    Vec3::new((t * 3.1).sin() * 0.6, (t * 1.7).cos() * 0.5, (t * 0.9).sin().abs() + 0.01).normalize();
                let wo =
                    Vec3::new((t * 2.3).cos() * 0.7, (t * 0.7).sin() * 0.4, (t * 1.3).cos().abs() + 0.01).normalize();
                assert_eq!(
                    rd.eval(wi, wo, [0.3, 0.7, 1.0]),
                    on.eval(wi, wo, [0.3, 0.7, 1.0]),
                    "alpha {alpha} fast {fast}"
                );
                // Oren–Nayar's sampler too.
                assert_eq!(rd.pdf(wi, wo), on.pdf(wi, wo), "alpha {alpha} fast {fast}: pdf");
            }
        }
    }
}

#[test]
fn defaults_are_mitsuba_0_6s() {
    let rd = common::model("roughdiffuse", &[]);
    assert_eq!(
        rd.parameters(),
        vec![
            ("alpha", ParamValue::Number(0.2f32 as f64)),
            ("use_fast_approx", ParamValue::Flag(false)),
            ("sampling", ParamValue::Text("cosine".into()))
        ]
    );
}

#[test]
fn bad_alpha_names_the_parameter() {
    let e =
        DiffuseModel::from_params("roughdiffuse", matte_brdf::Params::new().with("alpha", ParamValue::Number(-0.1)))
            .unwrap_err();
    assert_eq!(e.param, "alpha");
    let e = DiffuseModel::from_params(
        "roughdiffuse",
        matte_brdf::Params::new().with("use_fast_approx", ParamValue::Text("maybe".into())),
    )
    .unwrap_err();
    assert_eq!(e.param, "use_fast_approx");
}
