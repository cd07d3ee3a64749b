//! The van Ginneken fast path (tables) against the reference integral over the whole domain.
//! Stated bound: 0.5 % for θi, θo ≤ 80° (20,000 configurations: max 0.077 % at m = 0.3,
//! 0.12 % at m = 0.5; `matte tables` prints the numbers). Also: smooth limit m → 0 is Lambert.

use crate::common;
use matte_brdf::frame::spherical_direction;
use matte_brdf::ginneken::accuracy::fast_path_accuracy;
use matte_brdf::{DiffuseBrdf, DiffuseModel};

#[test]
fn fast_path_within_half_a_percent_away_from_grazing() {
    for m in ["0.1", "0.3", "0.5", "1.0"] {
        for shadowing in ["vginneken", "height_correlated"] {
            let DiffuseModel::Ginneken(g) = common::model("ginneken", &[("roughness", m), ("shadowing", shadowing)])
            else {
                unreachable!()
            };
            let e = fast_path_accuracy(&g, 80.0, 1500);
            assert!(
                e.max_relative < 5e-3,
                "m={m} {shadowing}: max relative error {:.3} % at {:?}",
                100.0 * e.max_relative,
                e.worst
            );
        }
    }
}

#[test]
fn vanishing_roughness_is_lambert() {
    let g = common::model("ginneken", &[("roughness", "0.001")]);
    for (ti, to, ph) in [(0.0f32, 0.0f32, 0.0f32), (30.0, 60.0, 90.0), (70.0, 70.0, 180.0)] {
        let f = g.eval(
            spherical_direction(ti.to_radians(), 0.0),
            spherical_direction(to.to_radians(), ph.to_radians()),
            [1.0],
        )[0];
        assert!((f - std::f32::consts::FRAC_1_PI).abs() < 2e-4, "{ti}/{to}/{ph}: {f}");
    }
}

/// The traced kernels' roughness gradient (∂/∂m tables) against central differences of the
/// reference integral: the error of ∂ln f/∂ln m stays below 0.01 for θ ≤ 80° (measured at
/// 600 configurations: max 1.7e-4, 1.4e-3, 3.3e-3 at m = 0.1, 0.3, 0.7; mean ≤ 2.2e-4).
#[test]
fn roughness_gradient_matches_the_reference_derivative() {
    use matte_brdf::ginneken::accuracy::roughness_gradient_accuracy;
    for m in ["0.1", "0.3", "0.7"] {
        for shadowing in ["vginneken", "height_correlated"] {
            let DiffuseModel::Ginneken(g) = common::model("ginneken", &[("roughness", m), ("shadowing", shadowing)])
            else {
                unreachable!()
            };
            let e = roughness_gradient_accuracy(&g, 80.0, 600);
            println!(
                "m={m} {shadowing}: ∂ln f/∂ln m error max {:.2e} mean {:.2e} at {:?}",
                e.max_log_error, e.mean_log_error, e.worst
            );
            assert!(e.max_log_error < 0.01, "m={m} {shadowing}: {e:?}");
        }
    }
}

/// The roughness-axis tables (a textured roughness: the slope tables stacked over m, cubic
/// Hermite in u = m/(1+m) with the ∂/∂m tables as slopes) against the reference integral at
/// roughnesses between the axis nodes, θ ≤ 80°: f within 0.6 % and ∂ln f/∂ln m within 0.02
/// (`docs/models.md#van-ginneken-with-a-textured-roughness` has the measured numbers).
#[test]
fn roughness_axis_matches_the_reference_between_nodes() {
    use matte_brdf::ginneken::accuracy::axis_accuracy;
    use matte_brdf::ginneken::shadowing::Shadowing;
    for m in [0.05, 0.13, 0.45, 0.8] {
        for shadowing in [Shadowing::VanGinneken, Shadowing::HeightCorrelated] {
            let e = axis_accuracy(m, shadowing, 80.0, 800);
            println!(
                "m={m} {shadowing:?}: f max {:.2e} mean {:.2e}; ∂ln f/∂ln m max {:.2e} mean {:.2e}",
                e.max_relative, e.mean_relative, e.max_log_derivative, e.mean_log_derivative
            );
            assert!(e.max_relative < 6e-3 && e.max_log_derivative < 0.02, "m={m} {shadowing:?}: {e:?}");
        }
    }
}
