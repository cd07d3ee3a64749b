//! The virtual gonioreflectometer against closed forms and against itself: a flat Lambertian
//! surface gives ρ/π everywhere and albedo ρ; the furnace (ρ = 1, all bounces) loses nothing;
//! the next-event BRDF estimate integrates to the independently measured albedo; and the
//! measured BRDF is reciprocal.

use glam::DVec3;
use matte::microgeometry::{Bounces, Setup, VCavities, measure};
use std::f64::consts::{FRAC_1_PI, PI};

fn direction(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn setup(reflectance: f64, wi: DVec3, wo: Vec<DVec3>, photons: u64, bounces: Bounces) -> Setup {
    Setup { reflectance, wi, wo, photons, seed: 7, bounces, max_bounces: 1000 }
}

#[test]
fn a_flat_surface_is_lambertian() {
    let flat = VCavities::new(0.0).unwrap();
    let wo: Vec<DVec3> = [(0.0, 0.0), (30.0, 90.0), (60.0, 180.0), (85.0, 45.0)].map(|(t, p)| direction(t, p)).into();
    for bounces in [Bounces::All, Bounces::First] {
        let m = measure(&flat, &setup(0.7, direction(40.0, 0.0), wo.clone(), 10_000, bounces)).unwrap();
        for e in &m.f {
            assert!((e.mean - 0.7 * FRAC_1_PI).abs() < 1e-12 && e.half_width < 1e-12, "{e:?}");
        }
        assert!((m.albedo.mean - 0.7).abs() < 1e-12, "{:?}", m.albedo);
    }
}

#[test]
fn the_furnace_loses_nothing() {
    let rough = VCavities::new(0.6).unwrap();
    let m = measure(&rough, &setup(1.0, direction(60.0, 0.0), vec![DVec3::Z], 20_000, Bounces::All)).unwrap();
    assert_eq!(m.truncated, 0.0);
    assert!((m.albedo.mean - 1.0).abs() < 1e-12, "{:?}", m.albedo);
}

/// ∫ f cos θo dωo over the hemisphere (midpoint rule in cos θo and φo) against the albedo the
/// escaping photons measure: two estimators of the same number.
#[test]
fn the_brdf_integrates_to_the_measured_albedo() {
    let rough = VCavities::new(0.5).unwrap();
    let (nu, nphi) = (24, 24);
    let mut wo = Vec::new();
    for i in 0..nu {
        let mu: f64 = (i as f64 + 0.5) / nu as f64;
        for j in 0..nphi {
            let phi = 2.0 * PI * (j as f64 + 0.5) / nphi as f64;
            wo.push(DVec3::new((1.0 - mu * mu).sqrt() * phi.cos(), (1.0 - mu * mu).sqrt() * phi.sin(), mu));
        }
    }
    for (rho, bounces) in [(0.8, Bounces::All), (0.8, Bounces::First)] {
        let m = measure(&rough, &setup(rho, direction(50.0, 0.0), wo.clone(), 100_000, bounces)).unwrap();
        let weight = 2.0 * PI / (nu * nphi) as f64; // dω cos θo = dμ dφ
        let integral: f64 = m.f.iter().zip(&wo).map(|(e, w)| e.mean * w.z * weight).sum();
        // Quadrature error of the midpoint rule plus both estimates' noise.
        assert!(
            (integral - m.albedo.mean).abs() < 0.01 + m.albedo.half_width,
            "{bounces:?}: ∫ f cos = {integral}, albedo {:?}",
            m.albedo
        );
    }
}

#[test]
fn the_measured_brdf_is_reciprocal() {
    let rough = VCavities::new(0.6).unwrap();
    let (a, b) = (direction(20.0, 0.0), direction(70.0, 130.0));
    for bounces in [Bounces::All, Bounces::First] {
        let ab = measure(&rough, &setup(0.8, a, vec![b], 400_000, bounces)).unwrap().f[0];
        let ba = measure(&rough, &Setup { seed: 99, ..setup(0.8, b, vec![a], 400_000, bounces) }).unwrap().f[0];
        let hw = ab.half_width.hypot(ba.half_width);
        assert!((ab.mean - ba.mean).abs() <= hw, "{bounces:?}: f(a,b) = {ab:?}, f(b,a) = {ba:?}");
        assert!(ab.half_width < 0.02 * ab.mean, "not enough photons to tell: {ab:?}");
    }
}

#[test]
fn the_comparison_of_a_flat_surface_finds_no_error() {
    // σ = 0: the surface is a Lambertian plane and every model reduces to ρ/π.
    let c = matte::microgeometry::comparison::compare_v_cavities(0.0, 0.6, 2_000, 1).unwrap();
    assert_eq!(c.points.len(), 4 * 9 * 3);
    for p in &c.points {
        assert!((p.simulated.mean - 0.6 * FRAC_1_PI).abs() < 1e-12, "{:?}", p.simulated);
    }
    for m in &c.summary {
        assert!(m.max_abs_relative_error < 1e-5 && m.max_abs_albedo_relative_error < 1e-3, "{}", m.model);
    }
}

mod height_field {
    use super::*;
    use matte::microgeometry::HeightField;

    #[test]
    fn a_flat_field_is_lambertian() {
        let flat = HeightField::gaussian(0.0, 32, 1).unwrap();
        let wo: Vec<DVec3> = [(0.0, 0.0), (45.0, 90.0), (80.0, 200.0)].map(|(t, p)| direction(t, p)).into();
        let m = measure(&flat, &setup(0.5, direction(30.0, 10.0), wo, 5_000, Bounces::All)).unwrap();
        for e in &m.f {
            assert!((e.mean - 0.5 * FRAC_1_PI).abs() < 1e-12, "{e:?}");
        }
        assert!((m.albedo.mean - 0.5).abs() < 1e-12);
    }

    #[test]
    fn heights_and_slopes_have_the_gaussian_surface_statistics() {
        // Continuous surface: m = √2 σ_h / T. The grid (8 cells per T) keeps slopes within a
        // few per cent of the continuum, so σ_h is close to m/√2.
        let f = HeightField::gaussian(0.5, 256, 3).unwrap();
        assert!((f.rms_slope() - 0.5).abs() < 1e-9);
        let ratio = f.height_deviation() / (0.5 / 2f64.sqrt());
        assert!((0.9..1.15).contains(&ratio), "σ_h / (m/√2) = {ratio}");
    }

    #[test]
    fn furnace_integral_and_reciprocity() {
        let rough = HeightField::gaussian(0.5, 128, 5).unwrap();
        let m = measure(&rough, &setup(1.0, direction(60.0, 0.0), vec![DVec3::Z], 20_000, Bounces::All)).unwrap();
        assert_eq!(m.truncated, 0.0);
        assert!((m.albedo.mean - 1.0).abs() < 1e-12, "{:?}", m.albedo);

        let (nu, nphi) = (16, 16);
        let mut wo = Vec::new();
        for i in 0..nu {
            let mu: f64 = (i as f64 + 0.5) / nu as f64;
            for j in 0..nphi {
                let phi = 2.0 * PI * (j as f64 + 0.5) / nphi as f64;
                wo.push(DVec3::new((1.0 - mu * mu).sqrt() * phi.cos(), (1.0 - mu * mu).sqrt() * phi.sin(), mu));
            }
        }
        let m = measure(&rough, &setup(0.8, direction(40.0, 0.0), wo.clone(), 20_000, Bounces::All)).unwrap();
        let integral: f64 = m.f.iter().zip(&wo).map(|(e, w)| e.mean * w.z * 2.0 * PI / (nu * nphi) as f64).sum();
        assert!((integral - m.albedo.mean).abs() < 0.015 + m.albedo.half_width, "{integral} vs {:?}", m.albedo);

        let (a, b) = (direction(25.0, 0.0), direction(65.0, 140.0));
        let ab = measure(&rough, &setup(0.8, a, vec![b], 200_000, Bounces::All)).unwrap().f[0];
        let ba = measure(&rough, &Setup { seed: 99, ..setup(0.8, b, vec![a], 200_000, Bounces::All) }).unwrap().f[0];
        assert!((ab.mean - ba.mean).abs() <= ab.half_width.hypot(ba.half_width), "{ab:?} vs {ba:?}");
    }
}

/// Patch independence (`docs/microgeometry.md#patch-independence`): pooled over independent
/// realisations, 16 T patches and 64 T patches measure the same BRDF within their intervals
/// (each interval from the spread of its realisations). A small-photon version of the
/// measurement recorded in the doc.
#[test]
fn two_patch_sizes_agree_within_their_realisation_intervals() {
    use matte::microgeometry::HeightField;
    use matte::microgeometry::realisations::pool;
    let (m, rho, r) = (0.6, 0.8, 6);
    let wi = direction(60.0, 0.0);
    let wo: Vec<DVec3> = [(0.0, 0.0), (40.0, 0.0), (40.0, 180.0), (70.0, 90.0)].map(|(t, p)| direction(t, p)).into();
    let measure_size = |cells: usize, seed: u64| {
        let ms: Vec<_> = (0..r as u64)
            .map(|k| {
                let s = HeightField::gaussian(m, cells, seed + k).unwrap();
                measure(&s, &Setup { seed: seed + 100 + k, ..setup(rho, wi, wo.clone(), 6_000, Bounces::All) }).unwrap()
            })
            .collect();
        let f: Vec<_> = (0..wo.len()).map(|j| pool(&ms.iter().map(|x| x.f[j]).collect::<Vec<_>>())).collect();
        (f, pool(&ms.iter().map(|x| x.albedo).collect::<Vec<_>>()))
    };
    let (small, small_albedo) = measure_size(128, 10);
    let (large, large_albedo) = measure_size(512, 20);
    for (j, (a, b)) in small.iter().zip(&large).enumerate() {
        let hw = a.half_width.hypot(b.half_width);
        assert!((a.mean - b.mean).abs() <= hw, "wo {}: 16 T {a:?}, 64 T {b:?}", wo[j]);
        assert!(hw < 0.1 * a.mean, "intervals too wide to tell: {a:?} {b:?}");
    }
    let hw = small_albedo.half_width.hypot(large_albedo.half_width);
    assert!((small_albedo.mean - large_albedo.mean).abs() <= hw, "{small_albedo:?} vs {large_albedo:?}");
}

/// van Ginneken's model is the single-scattering BRDF of a Lambertian Gaussian surface with
/// Smith-type shadowing: away from grazing angles it must match the simulated surface with its
/// interreflections cut, an oracle that shares no code with the kernel.
#[test]
fn van_ginneken_is_the_single_bounce_brdf_of_its_gaussian_surface() {
    use matte_brdf::{DiffuseBrdf, DiffuseModel, ParamValue, Params};
    let m = 0.4;
    let surface = matte::microgeometry::HeightField::gaussian(m, 128, 11).unwrap();
    let model = DiffuseModel::from_params("ginneken", Params::new().with("roughness", ParamValue::Number(m))).unwrap();
    let wi = direction(30.0, 0.0);
    let wo: Vec<DVec3> = [(0.0, 0.0), (20.0, 0.0), (40.0, 0.0), (20.0, 180.0), (40.0, 180.0), (45.0, 90.0)]
        .map(|(t, p)| direction(t, p))
        .into();
    let single = measure(&surface, &setup(0.8, wi, wo.clone(), 60_000, Bounces::First)).unwrap();
    for (e, w) in single.f.iter().zip(&wo) {
        let f = model.eval(wi.as_vec3(), w.as_vec3(), [0.8])[0] as f64;
        assert!((e.mean - f).abs() <= e.half_width + 0.01 * f, "wo {w}: simulated {e:?}, van Ginneken {f}");
    }
}
