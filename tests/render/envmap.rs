//! The `envmap` emitter against Mitsuba 3.9.1's definitions (`src/emitters/envmap.cpp`):
//! direction ↔ uv mapping d = (sin φ sin θ, cos θ, −cos φ sin θ), θ = π v, φ = 2π u; texel i
//! of row j sits at u = (i + ½)/W, v = j/(H − 1); the sampling density integrates to 1 over
//! the sphere (quadrature), sampled directions carry the density `pdf` reports, and the
//! light-sampling estimate of ∫ L dω agrees with quadrature; through the loader, `scale`,
//! `to_world` and `<path>` apply. None of the expected values comes from the code under test.

use crate::common::{SENSOR, assert_err_at, scene, write_exr};
use glam::{Affine3A, Vec2, Vec3};
use matte_render::emitter::{EnvMap, Light};
use matte_render::load::load_file;
use std::f64::consts::PI;
use std::path::PathBuf;

const W: usize = 8;
const H: usize = 5;

/// A deterministic, strongly varying map (one bright texel) so that importance sampling
/// matters.
fn texels() -> Vec<Vec3> {
    (0..W * H)
        .map(|k| {
            let (i, j) = (k % W, k / W);
            let base = Vec3::new(0.1 + 0.05 * i as f32, 0.2 + 0.1 * j as f32, 0.3 + 0.02 * (i * j) as f32);
            if (i, j) == (5, 2) { base * 40.0 } else { base }
        })
        .collect()
}

fn dir(u: f64, v: f64) -> Vec3 {
    let (theta, phi) = (PI * v, 2.0 * PI * u);
    Vec3::new((phi.sin() * theta.sin()) as f32, theta.cos() as f32, (-phi.cos() * theta.sin()) as f32)
}

fn map(scale: f32, to_world: Affine3A) -> EnvMap {
    EnvMap::new(W, H, texels(), scale, to_world, false).unwrap()
}

#[test]
fn texel_centres_return_the_texels_times_scale() {
    let t = texels();
    let e = map(2.5, Affine3A::IDENTITY);
    for j in 1..H - 1 {
        for i in 0..W {
            let d = dir((i as f64 + 0.5) / W as f64, j as f64 / (H - 1) as f64);
            let got = e.eval(d);
            let want = t[j * W + i] * 2.5;
            assert!((got - want).length() <= 1e-4 * want.length(), "texel ({i}, {j}): {got} vs {want}");
        }
    }
    // Straight up (+y) reads row 0 only, straight down the last row (a mix of neighbouring
    // texels of that row, whatever u is there).
    for (d, j) in [(Vec3::Y, 0), (Vec3::NEG_Y, H - 1)] {
        let got = e.eval(d) / 2.5;
        let row = &t[j * W..(j + 1) * W];
        let (lo, hi) = row.iter().fold((Vec3::splat(f32::MAX), Vec3::ZERO), |(l, h), v| (l.min(*v), h.max(*v)));
        assert!(got.cmpge(lo - 1e-5).all() && got.cmple(hi + 1e-5).all(), "{d}: {got} outside row {j}");
    }
    // Halfway between two texel centres of a row: the mean of the two (bilinear), also
    // across the seam u = 0 (periodic): columns W−1 and 0.
    let j = 2;
    let mid = e.eval(dir(1.0 / W as f64, j as f64 / (H - 1) as f64));
    assert!((mid - 2.5 * 0.5 * (t[j * W] + t[j * W + 1])).length() < 1e-4);
    let seam = e.eval(dir(0.0, j as f64 / (H - 1) as f64));
    assert!((seam - 2.5 * 0.5 * (t[j * W] + t[j * W + W - 1])).length() < 1e-4);
}

#[test]
fn to_world_rotates_the_map() {
    // Rotating by +90° about x maps local +y (row 0) to world +z.
    let rot = Affine3A::from_rotation_x(std::f32::consts::FRAC_PI_2);
    let plain = map(1.0, Affine3A::IDENTITY);
    let rotated = map(1.0, rot);
    for (u, v) in [(0.3, 0.4), (0.81, 0.62), (0.05, 0.3)] {
        let d = dir(u, v);
        let dw = rot.transform_vector3(d);
        assert!((plain.eval(d) - rotated.eval(dw)).length() < 1e-4);
        assert!((plain.pdf(d) - rotated.pdf(dw)).abs() < 1e-4 * plain.pdf(d));
    }
}

/// ∫ f dω over the sphere by the midpoint rule in (θ, φ).
fn sphere_integral(f: impl Fn(Vec3) -> f64) -> f64 {
    let (nt, np) = (600, 1200);
    let mut s = 0.0;
    for a in 0..nt {
        let theta = PI * (a as f64 + 0.5) / nt as f64;
        for b in 0..np {
            let phi = 2.0 * PI * (b as f64 + 0.5) / np as f64;
            let d = Vec3::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32);
            s += f(d) * theta.sin();
        }
    }
    s * (PI / nt as f64) * (2.0 * PI / np as f64)
}

#[test]
fn density_integrates_to_one_and_matches_the_samples() {
    for comp in [false, true] {
        let e = EnvMap::new(W, H, texels(), 1.0, Affine3A::from_rotation_z(0.3), comp).unwrap();
        let total = sphere_integral(|d| e.pdf(d) as f64);
        assert!((total - 1.0).abs() < 2e-3, "mis_compensation {comp}: ∫pdf = {total}");
        let mut rng = 0x2545F4914F6CDD1Du64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 40) as f32 / (1u64 << 24) as f32
        };
        for _ in 0..2000 {
            let u = Vec2::new(next(), next());
            let Some((d, radiance, pdf)) = e.sample(u) else { continue };
            assert!((d.length() - 1.0).abs() < 1e-5);
            let p = e.pdf(d);
            assert!((p - pdf).abs() <= 2e-3 * pdf.max(1e-3), "sampled pdf {pdf} vs pdf(d) {p} at {d}");
            assert!((radiance - e.eval(d)).length() <= 1e-4 * radiance.length().max(1.0));
        }
    }
}

#[test]
fn light_sampling_estimates_the_integral_of_radiance() {
    let e = map(1.0, Affine3A::IDENTITY);
    let lum = |v: Vec3| v.dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
    let exact = sphere_integral(|d| lum(e.eval(d)));
    let n = 400_000;
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    let mut k = 0u64;
    for a in 0..n {
        // A stratified 2-D sequence (R2), deterministic.
        k += 1;
        let u = Vec2::new(
            (0.5 + k as f64 * 0.7548776662466927).fract() as f32,
            (0.5 + k as f64 * 0.5698402909980532).fract() as f32,
        );
        let _ = a;
        let x = match e.sample(u) {
            Some((_, radiance, pdf)) => lum(radiance) / pdf as f64,
            None => 0.0,
        };
        s += x;
        s2 += x * x;
    }
    let mean = s / n as f64;
    let se = ((s2 / n as f64 - mean * mean) / n as f64).sqrt();
    assert!((mean - exact).abs() < 5.0 * se + 1e-3 * exact, "estimate {mean} ± {se} vs quadrature {exact}");
}

#[test]
fn invalid_maps_are_refused() {
    assert!(EnvMap::new(W, H, vec![Vec3::ZERO; W * H], 1.0, Affine3A::IDENTITY, false).is_err());
    assert!(EnvMap::new(1, 3, vec![Vec3::ONE; 3], 1.0, Affine3A::IDENTITY, false).is_err());
    let mut t = texels();
    t[3] = Vec3::new(f32::NAN, 0.0, 0.0);
    assert!(EnvMap::new(W, H, t, 1.0, Affine3A::IDENTITY, false).is_err());
}

/// A fresh folder for tests that write files.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_envmap_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `envmap` through the loader: `scale` and `to_world` apply, the file is found through
/// `<path>`, and it is the scene's environment.
#[test]
fn envmap_loads_as_the_environment() {
    let dir = temp_dir("envmap");
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    write_exr(&dir.join("tex/sky.exr"), 8, 5, |i, j| Vec3::new(0.1 * (i + 1) as f32, 0.2 * (j + 1) as f32, 0.5));
    let file = dir.join("s.xml");
    std::fs::write(
        &file,
        scene(&format!(
            "<path value=\"tex\"/>\n{SENSOR}\n<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/><float name=\"scale\" value=\"2\"/>\
             <transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/></transform></emitter>"
        )),
    )
    .unwrap();
    let s = load_file(&file, &[]).unwrap();
    let env = s.scene.environment.expect("an environment");
    // Row 2 (v = ½, the horizon), column 3 at u = 3.5/8: local d = (sin φ, 0, −cos φ);
    // rotating +90° about x maps local (x, y, z) to (x, −z, y).
    let phi = 2.0 * std::f32::consts::PI * 3.5 / 8.0;
    let local = Vec3::new(phi.sin(), 0.0, -phi.cos());
    let world = Vec3::new(local.x, -local.z, local.y);
    let got = s.scene.emitters[env as usize].eval_environment(world);
    assert!((got - 2.0 * Vec3::new(0.4, 0.6, 0.5)).length() < 1e-4, "{got}");
    std::fs::write(&file, scene(&format!("{SENSOR}\n<emitter type=\"constant\"/>\n<emitter type=\"envmap\"><string name=\"filename\" value=\"tex/sky.exr\"/></emitter>"))).unwrap();
    assert_err_at(load_file(&file, &[]), &file, 4, "only one environment emitter");
    std::fs::write(
        &file,
        scene(&format!("{SENSOR}\n<emitter type=\"envmap\"><string name=\"filename\" value=\"nope.exr\"/></emitter>")),
    )
    .unwrap();
    assert_err_at(load_file(&file, &[]), &file, 3, "nope.exr");
    let _ = std::fs::remove_dir_all(&dir);
}
