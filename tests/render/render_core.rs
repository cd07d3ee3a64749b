//! Renderer core without files: shapes, the BVH, emitter sampling densities and the
//! integrators on analytic scenes with known answers (white furnace, point light over a
//! plane). Oracles are closed forms and numerical integration, never the renderer itself.

use glam::{Affine3A, Vec2, Vec3};
use matte_render::bsdf::{Bsdf, Diffuse, Matte};
use matte_render::emitter::{Area, Constant, Emitter, Point};
use matte_render::geometry::Ray;
use matte_render::integrator::{DirectIntegrator, Integrator, PathIntegrator};
use matte_render::sampler::Sampler;
use matte_render::scene::Scene;
use matte_render::shape::{Cylinder, Disk, Geometry, Shape, Sphere, Triangles};
use matte_render::texture::Texture;
use matte_scene_file::mesh::TriangleMesh;
use std::f32::consts::PI;

fn shape(geometry: Geometry, bsdf: u32, emitter: Option<u32>) -> Shape {
    Shape { geometry, bsdf, emitter, plugin: "test".into() }
}

fn diffuse(r: f32) -> Bsdf {
    Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(Vec3::splat(r)) })
}

/// A square [−s, s]² in z = h, counter-clockwise seen from +z.
fn square(s: f32, h: f32) -> Triangles {
    let mesh = TriangleMesh {
        positions: vec![Vec3::new(-s, -s, h), Vec3::new(s, -s, h), Vec3::new(s, s, h), Vec3::new(-s, s, h)],
        normals: vec![],
        uvs: vec![],
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        attributes: vec![],
    };
    Triangles::new(mesh, false)
}

fn path(max_depth: u32) -> Integrator {
    Integrator::Path(PathIntegrator { max_depth, rr_depth: 5, hide_emitters: false })
}

/// Mean and standard error of `n` estimates of one pixel's radiance along `ray`.
fn estimate(scene: &Scene, integrator: &Integrator, ray: Ray, n: usize, seed: u64) -> (Vec3, Vec3) {
    let mut sampler = Sampler::for_pixel(seed, 7);
    let (mut s, mut s2) = (Vec3::ZERO, Vec3::ZERO);
    for _ in 0..n {
        let l = integrator.li(scene, &mut sampler, ray);
        assert!(l.is_finite(), "non-finite radiance {l}");
        s += l;
        s2 += l * l;
    }
    let mean = s / n as f32;
    let var = (s2 / n as f32 - mean * mean).max(Vec3::ZERO);
    (mean, (var / n as f32).map(f32::sqrt))
}

#[test]
fn triangle_hit_reports_distance_and_barycentrics() {
    let tri = square(1.0, 0.0);
    let scene = Scene::new(vec![shape(Geometry::Triangles(tri), 0, None)], vec![diffuse(0.5)], vec![], vec![]);
    // Point (0.5, -0.5) lies in triangle (0,1,2) with barycentrics b1 = 0.5, b2 = 0.25
    // (p = b0 p0 + b1 p1 + b2 p2); without file uvs Mitsuba's uv is (b1, b2).
    let ray = Ray::new(Vec3::new(0.5, -0.5, 3.0), Vec3::NEG_Z, f32::INFINITY);
    let si = scene.intersect(&ray).expect("hit");
    assert!((si.t - 3.0).abs() < 1e-5);
    assert!((si.p - Vec3::new(0.5, -0.5, 0.0)).length() < 1e-5, "p = {}", si.p);
    assert!((si.uv - Vec2::new(0.5, 0.25)).length() < 1e-5, "uv = {}", si.uv);
    assert!((si.n - Vec3::Z).length() < 1e-6, "CCW faces +z: n = {}", si.n);
    assert!(si.wi.z > 0.99, "wi towards the camera, local +z");
    // A ray beside the square misses; one going away misses.
    assert!(scene.intersect(&Ray::new(Vec3::new(1.5, 0.0, 3.0), Vec3::NEG_Z, f32::INFINITY)).is_none());
    assert!(scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), Vec3::Z, f32::INFINITY)).is_none());
    // maxt is respected.
    assert!(scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.0), Vec3::NEG_Z, 2.9)).is_none());
}

#[test]
fn analytic_shapes_hit_where_geometry_says() {
    let sphere = Sphere::new(
        Affine3A::from_scale_rotation_translation(Vec3::splat(2.0), Default::default(), Vec3::new(0.0, 0.0, -1.0)),
        false,
    );
    let disk = Disk::new(Affine3A::from_translation(Vec3::new(10.0, 0.0, 0.0)), false);
    let cyl = Cylinder::new(Affine3A::from_translation(Vec3::new(-10.0, 0.0, 0.0)), false);
    let scene = Scene::new(
        vec![
            shape(Geometry::Sphere(sphere), 0, None),
            shape(Geometry::Disk(disk), 0, None),
            shape(Geometry::Cylinder(cyl), 0, None),
        ],
        vec![diffuse(0.5)],
        vec![],
        vec![],
    );
    let si = scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY)).unwrap();
    assert!((si.t - 4.0).abs() < 1e-5 && (si.n - Vec3::Z).length() < 1e-6);
    // From inside, the normal still points outward (`docs/renderer-semantics.md` §8).
    let si = scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, -1.0), Vec3::X, f32::INFINITY)).unwrap();
    assert!((si.t - 2.0).abs() < 1e-5 && (si.n - Vec3::X).length() < 1e-5 && si.wi.z < 0.0);
    let si = scene.intersect(&Ray::new(Vec3::new(10.5, 0.0, 2.0), Vec3::NEG_Z, f32::INFINITY)).unwrap();
    assert!((si.t - 2.0).abs() < 1e-5 && (si.n - Vec3::Z).length() < 1e-6);
    assert!((si.uv.x - 0.5).abs() < 1e-5, "disk uv.x = r");
    let si = scene.intersect(&Ray::new(Vec3::new(-10.0, -5.0, 0.5), Vec3::Y, f32::INFINITY)).unwrap();
    assert!((si.t - 4.0).abs() < 1e-5 && (si.n - Vec3::NEG_Y).length() < 1e-5);
    assert!((si.uv - Vec2::new(0.75, 0.5)).length() < 1e-5, "cylinder uv = (φ/2π, z): {}", si.uv);
    // No caps: along the axis the ray passes through.
    assert!(scene.intersect(&Ray::new(Vec3::new(-10.0, 0.0, 5.0), Vec3::NEG_Z, f32::INFINITY)).is_none());
}

/// For every emitter shape, the density a light sample reports equals the density
/// `pdf_direction` gives for the same point found by tracing towards it, and for planar
/// shapes and the sphere seen from outside the density integrates to 1 over the directions
/// that reach the shape (numerical integration over the sphere of directions).
#[test]
fn emitter_sampling_densities_are_consistent_and_normalised() {
    let cases: Vec<(&str, Geometry, bool)> = vec![
        ("square", Geometry::Triangles(square(0.7, 1.5)), true),
        (
            "sphere",
            Geometry::Sphere(Sphere::new(
                Affine3A::from_scale_rotation_translation(
                    Vec3::splat(0.8),
                    Default::default(),
                    Vec3::new(0.3, 0.2, 2.5),
                ),
                false,
            )),
            true,
        ),
        (
            "disk",
            Geometry::Disk(Disk::new(
                Affine3A::from_scale_rotation_translation(
                    Vec3::new(1.0, 0.5, 1.0),
                    glam::Quat::from_rotation_x(0.3),
                    Vec3::new(0.0, 0.0, 2.0),
                ),
                false,
            )),
            true,
        ),
        (
            "cylinder",
            Geometry::Cylinder(Cylinder::new(
                Affine3A::from_scale_rotation_translation(
                    Vec3::new(0.5, 0.5, 2.0),
                    glam::Quat::from_rotation_x(1.2),
                    Vec3::new(0.0, 1.0, 2.0),
                ),
                false,
            )),
            false,
        ),
    ];
    let ref_p = Vec3::new(0.1, -0.2, 0.0);
    for (name, geometry, integrates_to_one) in cases {
        let scene = Scene::new(vec![shape(geometry.clone(), 0, None)], vec![diffuse(0.5)], vec![], vec![]);
        let mut rng = Sampler::for_pixel(1, 2);
        let mut checked = 0;
        let mut misses = 0;
        for _ in 0..2000 {
            let Some(ds) = geometry.sample_direction(ref_p, rng.next_2d()) else { continue };
            let Some(si) = scene.intersect(&Ray::new(ref_p, ds.d, f32::INFINITY)) else {
                misses += 1; // only at the silhouette, by rounding
                continue;
            };
            if (si.p - ds.p).length() > 1e-3 || ds.d.dot(ds.n).abs() < 0.1 {
                continue; // hidden behind another part of the shape, or too grazing to compare
            }
            let pdf = geometry.pdf_direction(ref_p, &si);
            assert!((pdf - ds.pdf).abs() <= 2e-3 * ds.pdf, "{name}: sampled pdf {} vs pdf_direction {pdf}", ds.pdf);
            checked += 1;
        }
        assert!(checked > 500 && misses < 10, "{name}: only {checked} visible samples, {misses} misses");
        if integrates_to_one {
            // ∫ pdf dω over directions hitting the shape, midpoint rule in (cos θ, φ).
            let (nt, np) = (600, 1200);
            let mut sum = 0.0f64;
            for i in 0..nt {
                let z = 1.0 - 2.0 * (i as f32 + 0.5) / nt as f32;
                let r = (1.0 - z * z).sqrt();
                for j in 0..np {
                    let phi = 2.0 * PI * (j as f32 + 0.5) / np as f32;
                    let d = Vec3::new(r * phi.cos(), r * phi.sin(), z);
                    if let Some(si) = scene.intersect(&Ray::new(ref_p, d, f32::INFINITY)) {
                        sum += geometry.pdf_direction(ref_p, &si) as f64;
                    }
                }
            }
            let integral = sum * 4.0 * std::f64::consts::PI / (nt * np) as f64;
            assert!((integral - 1.0).abs() < 5e-3, "{name}: ∫pdf = {integral}");
        }
    }
}

/// White furnace: a sphere with reflectance 1 inside a constant environment of radiance 1
/// reflects exactly 1 whatever the path length (Lambert: energy is conserved exactly).
#[test]
fn white_furnace_returns_the_environment_radiance() {
    let sphere = Sphere::new(Affine3A::IDENTITY, false);
    for bsdf in [
        diffuse(1.0),
        Bsdf::Matte(Matte::new(matte_brdf::DiffuseModel::Lambert(matte_brdf::Lambert), Texture::Constant(Vec3::ONE))),
    ] {
        let scene = Scene::new(
            vec![shape(Geometry::Sphere(sphere.clone()), 0, None)],
            vec![bsdf],
            vec![Emitter::Constant(Constant { radiance: Vec3::ONE })],
            vec![1.0],
        );
        for (x, y) in [(0.0, 0.0), (0.6, 0.3), (0.0, 0.97)] {
            let ray = Ray::new(Vec3::new(x, y, 5.0), Vec3::NEG_Z, f32::INFINITY);
            let (mean, se) = estimate(&scene, &path(u32::MAX), ray, 40_000, 3);
            for c in 0..3 {
                assert!((mean[c] - 1.0).abs() < 4.0 * se[c] + 1e-4, "furnace at ({x},{y}): {mean} ± {se}");
            }
        }
    }
}

/// A Lambertian plane (ρ = 0.5) under a point light of intensity I at height h: every
/// point gets L = ρ/π · I cos θ / d², with `path` (any depth ≥ 2) and `direct` alike. The
/// `direct` quirk (delta-light samples not divided by Ne, `docs/renderer-semantics.md` §7)
/// multiplies it by Ne.
/// Checked against Mitsuba 3.9.1 (scalar_rgb) by validation/verify_semantics.py -k §9.
#[test]
fn plane_under_point_light_matches_closed_form() {
    let (i, h, rho) = (10.0f32, 2.0f32, 0.5f32);
    let scene = Scene::new(
        vec![shape(Geometry::Triangles(square(50.0, 0.0)), 0, None)],
        vec![diffuse(rho)],
        vec![Emitter::Point(Point { position: Vec3::new(0.0, 0.0, h), intensity: Vec3::splat(i) })],
        vec![1.0],
    );
    let direct =
        |ne, nb| Integrator::Direct(DirectIntegrator { emitter_samples: ne, bsdf_samples: nb, hide_emitters: false });
    for x in [0.0f32, 1.0, 3.0] {
        let p = Vec3::new(x, if x == 0.0 { 0.0 } else { 0.5 }, 0.0);
        let d2 = (Vec3::new(0.0, 0.0, h) - p).length_squared();
        let expected = rho / PI * i * (h / d2.sqrt()) / d2;
        assert!(x != 0.0 || (expected - 0.3979).abs() < 1e-3, "docs/renderer-semantics.md §9 value");
        let ray = Ray::new(p + Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY);
        for (integrator, factor) in [(path(2), 1.0), (path(u32::MAX), 1.0), (direct(1, 1), 1.0), (direct(4, 1), 4.0)] {
            let (mean, _) = estimate(&scene, &integrator, ray, 64, 5);
            assert!(
                (mean.x - expected * factor).abs() < 1e-4 * expected * factor,
                "x={x} {integrator:?}: {} vs {}",
                mean.x,
                expected * factor
            );
        }
    }
}

/// `max_depth` counts segments: a closed emissive cube (inward normals, ρ = 0.5, Le = 1)
/// gives 1, 1.5, 1.75 for depths 1, 2, 3 and 2 unbounded (`docs/renderer-semantics.md` §7,
/// verified in Mitsuba).
/// Checked against Mitsuba 3.9.1 (scalar_rgb) by validation/verify_semantics.py -k §7.
#[test]
fn max_depth_counts_segments_in_a_closed_emissive_box() {
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    // Six inward-facing squares of the cube [−1, 1]³.
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let base = pos.len() as u32;
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for (a, b) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let mut p = Vec3::ZERO;
                p[axis] = sign;
                p[u] = a;
                p[v] = b;
                pos.push(p);
            }
            // Normal of (u,v) order is +axis; inward needs −sign·axis.
            if sign < 0.0 {
                tris.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]])
            } else {
                tris.extend([[base, base + 2, base + 1], [base, base + 3, base + 2]])
            }
        }
    }
    let mesh = TriangleMesh { positions: pos, normals: vec![], uvs: vec![], triangles: tris, attributes: vec![] };
    let scene = Scene::new(
        vec![shape(Geometry::Triangles(Triangles::new(mesh, false)), 0, Some(0))],
        vec![diffuse(0.5)],
        vec![Emitter::Area(Area { shape: 0, radiance: Texture::Constant(Vec3::ONE) })],
        vec![1.0],
    );
    let ray = Ray::new(Vec3::new(0.1, 0.2, 0.0), Vec3::new(0.3, -0.2, 1.0).normalize(), f32::INFINITY);
    for (depth, expected) in [(1u32, 1.0f32), (2, 1.5), (3, 1.75), (u32::MAX, 2.0)] {
        let (mean, se) = estimate(&scene, &path(depth), ray, 20_000, 11);
        assert!(
            (mean.x - expected).abs() < 4.0 * se.x + 1e-4,
            "max_depth {depth}: {} ± {} vs {expected}",
            mean.x,
            se.x
        );
    }
}

/// Mitsuba's `mask` (`src/bsdfs/mask.cpp`, docs/renderer-semantics.md §10) over a diffuse
/// ρ = 0.5 with opacity α = 0.3, as a plane in a constant environment of 1: the pixel is
/// α·ρ + (1 − α) = 0.85 unbounded and with max_depth 2, but 0 with max_depth 1, because the
/// pass-through counts as a path segment (`src/integrators/path.cpp`; Mitsuba 3.9.1 renders
/// 0.8511, 0, 0.8511). Shadow rays do not see through a mask: a diffuse floor under a mask
/// plane lit only by a point light above both gets nothing (Mitsuba: 0; a see-through
/// shadow ray would give (1 − α)·ρ/π·I/d²).
/// Checked against Mitsuba 3.9.1 (scalar_rgb) by validation/verify_semantics.py -k §10.
#[test]
fn mask_passes_rays_through_as_a_bounce_but_blocks_shadow_rays() {
    let mask = Bsdf::Mask(matte_render::bsdf::Mask {
        opacity: Texture::Constant(Vec3::splat(0.3)),
        nested: Box::new(diffuse(0.5)),
    });
    let env = Scene::new(
        vec![shape(Geometry::Triangles(square(50.0, 0.0)), 0, None)],
        vec![mask.clone()],
        vec![Emitter::Constant(Constant { radiance: Vec3::ONE })],
        vec![1.0],
    );
    let down = Ray::new(Vec3::new(0.1, 0.2, 5.0), Vec3::NEG_Z, f32::INFINITY);
    for (depth, expected) in [(u32::MAX, 0.85f32), (2, 0.85), (1, 0.0)] {
        let (mean, se) = estimate(&env, &path(depth), down, 40_000, 11);
        assert!((mean.x - expected).abs() < 4.0 * se.x + 1e-5, "max_depth {depth}: {mean} ± {se}, expected {expected}");
    }
    let shadowed = Scene::new(
        vec![
            shape(Geometry::Triangles(square(50.0, 0.0)), 0, None),
            shape(Geometry::Triangles(square(50.0, -1.0)), 1, None),
        ],
        vec![mask, diffuse(0.5)],
        vec![Emitter::Point(Point { position: Vec3::new(0.0, 0.0, 2.0), intensity: Vec3::splat(10.0) })],
        vec![1.0],
    );
    let between = Ray::new(Vec3::new(0.0, 0.0, -0.5), Vec3::NEG_Z, f32::INFINITY);
    let (mean, _) = estimate(&shadowed, &path(u32::MAX), between, 4_000, 12);
    assert_eq!(mean, Vec3::ZERO, "the point light reached the floor through the mask");
}
