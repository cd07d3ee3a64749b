//! `matte bench` machinery (quick mode, matte only: the timings themselves are the bench's
//! output, not something a test can judge on a shared machine).

use matte::bench::report::{SpeedTarget, targets};
use matte::bench::{BenchOptions, run};
use std::process::Command;

#[test]
fn quick_bench_measures_every_scene_kernel_and_spp() {
    let out = std::env::temp_dir().join("matte_bench_test");
    let scenes = crate::common::repo().join("mitsuba_scenes");
    let m = run(&BenchOptions { quick: true, repeats: 1, mitsuba: false, out, scenes }, &|_| {}).unwrap();
    let names: Vec<&str> = m.jobs.iter().map(|(j, _)| j.name.as_str()).collect();
    assert_eq!(names, ["cornell", "bunny", "room"]);
    for (job, t) in &m.jobs {
        assert!(t.seconds > 0.0 && t.accel_build_seconds >= 0.0, "{}", job.name);
        let pixels = 32 * 32;
        assert_eq!(t.samples, pixels * job.spp as u64, "{}", job.name);
        // At least the camera ray of every sample is traced.
        assert!(t.rays >= t.samples, "{}: {} rays for {} samples", job.name, t.rays, t.samples);
        assert!(t.other_driver_seconds > 0.0, "{}", job.name);
        // The profiled render split its time into the stages (path and direct scenes).
        let f = t.stage_fractions.unwrap_or_else(|| panic!("{}: no stage split", job.name));
        assert!((f.iter().sum::<f64>() - 1.0).abs() < 1e-9 && f.iter().all(|&x| x > 0.0), "{}: {f:?}", job.name);
    }
    // Every model's render time against Lambert's, as targets.
    let models: Vec<&str> = m.models.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(models, matte::bench::render::models());
    assert!(m.models.iter().all(|(_, s)| *s > 0.0 && s.is_finite()));
    let models: Vec<&str> = m.kernels.iter().map(|k| k.model).collect();
    assert_eq!(models, matte_brdf::default_models().collect::<Vec<_>>());
    assert!(m.kernels.iter().all(|k| k.ns_per_eval.is_finite() && k.ns_per_eval > 0.0));
    assert_eq!(m.scaling.len(), 2);
    // Every arrangement of the ray queries on every scene's rays (Embree is installed by the
    // set-up), and every model's kernel in f32 and 8-wide.
    assert_eq!(m.traversal.len(), 3);
    for (scene, times) in &m.traversal {
        let names: Vec<&str> = times.iter().map(|t| t.backend.name()).collect();
        assert_eq!(names, ["embree", "embree-meshes", "cwbvh"], "{scene}");
        assert!(times.iter().all(|t| t.rays > 0 && t.shadow_rays > 0 && t.ns_per_ray > 0.0), "{scene}");
    }
    let wide: Vec<&str> = m.wide_kernels.iter().map(|k| k.model).collect();
    assert_eq!(wide, matte_brdf::default_models().collect::<Vec<_>>());
    // Without Mitsuba: no renderer ratios, but the spp, BVH and kernel targets.
    let t = targets(&m);
    assert!(t.iter().all(|t| !t.what.contains("scalar_rgb") && !t.what.contains("llvm")));
    assert!(t.iter().any(|t| t.what.starts_with("bunny: BVH build")));
    assert_eq!(
        t.iter().filter(|t| t.what.contains("/ with lambert")).count(),
        matte::bench::render::models().len() - 1
    );
    assert_eq!(t.iter().filter(|t| t.what.starts_with("kernel ")).count(), matte_brdf::default_models().count() - 1);
    let json = matte::bench::report::json(&m);
    assert_eq!(json.renders.len(), 3);
}

#[test]
fn targets_compare_in_the_stated_direction() {
    let at_most = SpeedTarget { what: "x".into(), measured: 0.5, limit: 0.4, at_least: false };
    assert!(!at_most.met());
    let at_least = SpeedTarget { what: "y".into(), measured: 0.95, limit: 0.9, at_least: true };
    assert!(at_least.met());
}

#[test]
fn zero_repeats_is_a_usage_error() {
    let out =
        Command::new(env!("CARGO_BIN_EXE_matte")).args(["bench", "--repeats", "0", "--no-mitsuba"]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--repeats"));
}

/// The fitted samplers do what they were fitted for (`docs/sampling.md`): at roughness 1 and
/// θi ≥ 45° the weight's variance is at least 3× below the cosine's (the fits give 4–40×), and
/// near normal incidence at roughness 0.3 it is not above it. Exact variances by quadrature
/// (`matte bench --sampling`'s, on a coarse grid).
#[test]
fn the_fitted_samplers_lower_the_weight_variance() {
    use matte::bench::sampling::weight_variance;
    // (type, other parameters, the roughness parameter)
    type Case = (&'static str, &'static [(&'static str, &'static str)], &'static str);
    let cases: [Case; 6] = [
        ("oren_nayar", &[], "sigma"),
        ("oren_nayar", &[("model", "full")], "sigma"),
        ("roughdiffuse", &[], "alpha"),
        ("ginneken", &[], "roughness"),
        ("ginneken", &[("shadowing", "height_correlated")], "roughness"),
        ("burley", &[], "roughness"),
    ];
    for (kind, words, roughness) in cases {
        // roughdiffuse's α = √2 σ.
        let (rough, smooth) = if kind == "roughdiffuse" { ("1.4142", "0.4243") } else { ("1.0", "0.3") };
        let at = |r: &str| {
            let mut p = words.to_vec();
            p.push((roughness, r));
            p.push(("sampling", "cltc"));
            crate::common::model(kind, &p)
        };
        for ti in [45.0, 60.0, 85.0] {
            let (_, own, cosine) = weight_variance(&at(rough), ti, 120);
            assert!(
                own * 3.0 <= cosine,
                "{kind} {words:?} {roughness}={rough} θi={ti}: Var {own:.3e} vs cosine {cosine:.3e}"
            );
        }
        let (_, own, cosine) = weight_variance(&at(smooth), 15.0, 120);
        assert!(own <= cosine, "{kind} {words:?} {roughness}={smooth} θi=15: Var {own:.3e} vs cosine {cosine:.3e}");
    }
}
