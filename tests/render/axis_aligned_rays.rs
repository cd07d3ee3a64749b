//! Rays with zero direction components (the straight-down sun that cast no shadow): along ±x, ±y, ±z and with one zero
//! component, with the zeros signed both ways (`-(0, 0, -1)` is `(-0, -0, 1)`, the shadow
//! ray of a directional light pointing straight down), against every shape type, for the
//! closest hit and for occlusion. Origins sit outside, inside, on the shape's bounding-box
//! face, and on the planes of the BVH's quantisation grid (coordinate 0 of a box centred on
//! the origin).
//!
//! Expected distances are closed forms of the geometry (chord of a sphere or a circle, a
//! plane at a known distance), never the renderer's own answers.

use glam::{Affine3A, Mat4, Quat, Vec3};
use matte_render::bsdf::{Bsdf, Diffuse};
use matte_render::geometry::Ray;
use matte_render::scene::Scene;
use matte_render::shape::{Cylinder, Disk, Geometry, Shape, Sphere, Triangles};
use matte_render::texture::Texture;
use matte_scene_file::mesh::{MeshOptions, cube, rectangle};

fn scene(geometries: Vec<Geometry>) -> Scene {
    let shapes = geometries
        .into_iter()
        .map(|geometry| Shape { geometry, bsdf: 0, emitter: None, plugin: "test".into() })
        .collect();
    Scene::new(
        shapes,
        vec![Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(Vec3::splat(0.5)) })],
        vec![],
        vec![],
    )
}

/// Unit vector along axis `a` with sign `s`; the other two components are `+0` or `-0` as
/// bits 0 and 1 of `zeros` say.
fn axis_dir(a: usize, s: f32, zeros: u32) -> Vec3 {
    let mut v = [0.0f32; 3];
    let mut k = 0;
    for (i, c) in v.iter_mut().enumerate() {
        if i == a {
            *c = s;
        } else {
            *c = if zeros >> k & 1 == 1 { -0.0 } else { 0.0 };
            k += 1;
        }
    }
    Vec3::from(v)
}

/// All 24 axis directions: 3 axes × 2 signs × 4 sign patterns of the zeros.
fn axis_dirs() -> Vec<(usize, Vec3)> {
    let mut out = Vec::new();
    for a in 0..3 {
        for s in [1.0, -1.0] {
            for zeros in 0..4 {
                out.push((a, axis_dir(a, s, zeros)));
            }
        }
    }
    out
}

/// Directions in a coordinate plane with the third component ±0: (0.6, 0.8) in every sign
/// combination and both orders. Returns (zero axis, direction).
fn oblique_dirs() -> Vec<(usize, Vec3)> {
    let mut out = Vec::new();
    for zero in 0..3 {
        let (p, q) = ((zero + 1) % 3, (zero + 2) % 3);
        for (a, b) in [(0.6f32, 0.8f32), (0.8, 0.6)] {
            for sa in [1.0, -1.0] {
                for sb in [1.0, -1.0] {
                    for z in [0.0f32, -0.0] {
                        let mut v = [0.0f32; 3];
                        v[p] = sa * a;
                        v[q] = sb * b;
                        v[zero] = z;
                        out.push((zero, Vec3::from(v)));
                    }
                }
            }
        }
    }
    out
}

/// Unit vector of axis `i`.
fn e(i: usize) -> Vec3 {
    Vec3::AXES[i]
}

/// Checks the closest hit at `t` (relative tolerance 1e-5, absolute 1e-5) and that
/// occlusion is found up to just past `t` but not before it.
fn check_hit(scene: &Scene, o: Vec3, d: Vec3, t: f32, what: &str) {
    let ray = Ray::new(o, d, f32::INFINITY);
    let si = scene.intersect(&ray).unwrap_or_else(|| panic!("{what}: o = {o:?}, d = {d:?}: no hit, expected t = {t}"));
    assert!((si.t - t).abs() <= 1e-5 * t.max(1.0), "{what}: o = {o:?}, d = {d:?}: t = {}, expected {t}", si.t);
    assert!(scene.occluded(&Ray::new(o, d, f32::INFINITY)), "{what}: o = {o:?}, d = {d:?}: not occluded (unbounded)");
    assert!(scene.occluded(&Ray::new(o, d, t + 1e-3)), "{what}: o = {o:?}, d = {d:?}: not occluded before t + 1e-3");
    assert!(!scene.occluded(&Ray::new(o, d, t - 1e-3)), "{what}: o = {o:?}, d = {d:?}: occluded before t - 1e-3");
}

fn check_miss(scene: &Scene, o: Vec3, d: Vec3, what: &str) {
    let ray = Ray::new(o, d, f32::INFINITY);
    if let Some(si) = scene.intersect(&ray) {
        panic!("{what}: o = {o:?}, d = {d:?}: hit at t = {}, expected a miss", si.t);
    }
    assert!(!scene.occluded(&ray), "{what}: o = {o:?}, d = {d:?}: occluded, expected a miss");
}

/// Offsets perpendicular to axis `a` (in the two other axes): the grid plane 0 in one axis,
/// and a generic point. None lies on a face diagonal of the cube or the rectangle.
fn offsets(a: usize) -> Vec<Vec3> {
    let (p, q) = ((a + 1) % 3, (a + 2) % 3);
    vec![e(p) * 0.5, e(q) * 0.5, e(p) * 0.25 - e(q) * 0.375]
}

/// The rotation that maps +z onto axis `a` (for the disk and the rectangle).
fn z_to(a: usize) -> Quat {
    Quat::from_rotation_arc(Vec3::Z, e(a))
}

#[test]
fn sphere_axis_rays() {
    let c = Vec3::new(0.5, -0.25, 0.75);
    let r = 1.5;
    for centre in [Vec3::ZERO, c] {
        let s = scene(vec![Geometry::Sphere(Sphere::new(
            Affine3A::from_scale_rotation_translation(Vec3::splat(r), Quat::IDENTITY, centre),
            false,
        ))]);
        for (a, d) in axis_dirs() {
            let mut offs = offsets(a);
            offs.push(Vec3::ZERO);
            for off in offs {
                let half_chord = (r * r - off.length_squared()).sqrt();
                // From outside, from the bounding-box face (the origin's coordinate along the
                // ray equals the box plane), and from the centre plane (inside: far side).
                check_hit(&s, centre + off - d * 4.0, d, 4.0 - half_chord, "sphere, outside");
                if off != Vec3::ZERO {
                    check_hit(&s, centre + off - d * r, d, r - half_chord, "sphere, origin on its bbox face");
                }
                check_hit(&s, centre + off, d, half_chord, "sphere, from inside");
                check_miss(&s, centre + off + d * 4.0, d, "sphere, behind");
            }
            // Beside the sphere (outside its box in one zero axis).
            let side = e((a + 1) % 3) * (r + 0.25);
            check_miss(&s, centre + side - d * 4.0, d, "sphere, beside");
        }
        for (zero, d) in oblique_dirs() {
            let off = e(zero) * 0.5;
            let half_chord = (r * r - 0.25f32).sqrt();
            check_hit(&s, centre + off - d * 4.0, d, 4.0 - half_chord, "sphere, oblique");
        }
    }
}

#[test]
fn cube_axis_rays() {
    let centre = Vec3::new(0.5, -0.25, 0.75);
    for (to_world, c) in [(Mat4::IDENTITY, Vec3::ZERO), (Mat4::from_translation(centre), centre)] {
        let mesh = cube(&MeshOptions { to_world, ..Default::default() });
        let s = scene(vec![Geometry::Triangles(Triangles::new(mesh, false))]);
        for (a, d) in axis_dirs() {
            for off in offsets(a) {
                check_hit(&s, c + off - d * 4.0, d, 3.0, "cube, outside");
                check_hit(&s, c + off, d, 1.0, "cube, from inside");
                check_miss(&s, c + off + d * 4.0, d, "cube, behind");
            }
            check_miss(&s, c + e((a + 2) % 3) * 1.5 - d * 4.0, d, "cube, beside");
        }
        for (zero, d) in oblique_dirs() {
            // Through the centre plane: the ray leaves the cube through the face of its
            // larger component (0.8), at distance 1/0.8 from the centre line point.
            let off = e(zero) * 0.5;
            check_hit(&s, c + off - d * 4.0, d, 4.0 - 1.25, "cube, oblique");
            check_hit(&s, c + off, d, 1.25, "cube, oblique from inside");
        }
    }
}

#[test]
fn rectangle_and_disk_axis_rays() {
    let centre = Vec3::new(0.5, -0.25, 0.75);
    for a in 0..3 {
        for c in [Vec3::ZERO, centre] {
            let rot = z_to(a);
            let to_world = Mat4::from_rotation_translation(rot, c);
            let rect = Triangles::new(rectangle(&MeshOptions { to_world, ..Default::default() }), false);
            let disk = Disk::new(Affine3A::from_rotation_translation(rot, c), false);
            for (name, g) in [("rectangle", Geometry::Triangles(rect)), ("disk", Geometry::Disk(disk))] {
                let s = scene(vec![g]);
                for (axis, d) in axis_dirs() {
                    for off in offsets(a) {
                        if axis == a {
                            // Facing the shape: it lies at distance 4 from the origin.
                            check_hit(&s, c + off - d * 4.0, d, 4.0, name);
                            check_miss(&s, c + off + d * 4.0, d, name);
                        } else {
                            // Parallel to the shape's plane, off the plane: a miss.
                            check_miss(&s, c + off + e(a) * 0.5 - d * 4.0, d, name);
                        }
                    }
                }
                for (zero, d) in oblique_dirs() {
                    if d.dot(e(a)).abs() > 0.0 {
                        let off = offsets(a)[2];
                        let _ = zero;
                        check_hit(&s, c + off - d * 4.0, d, 4.0, name);
                    }
                }
            }
        }
    }
}

#[test]
fn cylinder_axis_rays() {
    // Mitsuba's cylinder: radius 1, z in [0, 1], no caps. Rotated so that its axis is `b`.
    let centre = Vec3::new(0.5, -0.25, 0.75);
    for b in 0..3 {
        for c in [Vec3::ZERO, centre] {
            let rot = z_to(b);
            let cyl = Cylinder::new(Affine3A::from_rotation_translation(rot, c), false);
            let s = scene(vec![Geometry::Cylinder(cyl)]);
            let mid = c + e(b) * 0.5;
            for (a, d) in axis_dirs() {
                if a == b {
                    // Along the axis: no wall is ever crossed.
                    check_miss(&s, mid - d * 4.0, d, "cylinder, along its axis");
                    check_miss(&s, mid, d, "cylinder, along its axis from inside");
                    continue;
                }
                let w = 3 - a - b; // the third axis
                for off in [0.0f32, 0.5, -0.625] {
                    let half_chord = (1.0 - off * off).sqrt();
                    let o = mid + e(w) * off;
                    check_hit(&s, o - d * 4.0, d, 4.0 - half_chord, "cylinder, across");
                    check_hit(&s, o, d, half_chord, "cylinder, across from inside");
                    check_miss(&s, o + d * 4.0, d, "cylinder, behind");
                }
                // Above the open end.
                check_miss(&s, mid + e(b) * 0.75 - d * 4.0, d, "cylinder, above");
            }
            for (zero, d) in oblique_dirs() {
                let along = d.dot(e(b)).abs();
                if zero == b {
                    // Perpendicular to the axis: a chord through the axis, length 2.
                    check_hit(&s, mid - d * 4.0, d, 3.0, "cylinder, oblique across");
                } else if along == 0.6 {
                    // Through the axis point at mid-height: the wall is 1/0.8 away, at
                    // height 0.5 ± 0.75 — outside [0, 1], so the ray passes the open ends.
                    check_miss(&s, mid - d * 4.0, d, "cylinder, through the open ends");
                } else {
                    // along = 0.8: the wall is at 1/0.6 along the ray, at height 0.5 ± 1.33.
                    check_miss(&s, mid - d * 4.0, d, "cylinder, steep through the ends");
                }
            }
        }
    }
}

/// The straight-down sun scene in miniature: a ground rectangle under shapes of every type, and shadow
/// rays straight up from the ground, i.e. `-(0, 0, -1)` = `(-0, -0, 1)`.
#[test]
fn shadow_rays_straight_up_find_every_occluder() {
    let ground =
        rectangle(&MeshOptions { to_world: Mat4::from_scale(Vec3::new(10.0, 10.0, 1.0)), ..Default::default() });
    let sphere = Sphere::new(
        Affine3A::from_scale_rotation_translation(Vec3::splat(0.5), Quat::IDENTITY, Vec3::new(0.0, 0.0, 1.0)),
        false,
    );
    let cube_mesh = cube(&MeshOptions {
        to_world: Mat4::from_scale_rotation_translation(Vec3::splat(0.5), Quat::IDENTITY, Vec3::new(3.0, 0.0, 1.0)),
        ..Default::default()
    });
    let disk = Disk::new(Affine3A::from_translation(Vec3::new(-3.0, 0.0, 1.0)), false);
    let cyl = Cylinder::new(
        Affine3A::from_rotation_translation(
            Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
            Vec3::new(0.0, 3.5, 2.0),
        ),
        false,
    );
    let s = scene(vec![
        Geometry::Triangles(Triangles::new(ground, false)),
        Geometry::Sphere(sphere),
        Geometry::Triangles(Triangles::new(cube_mesh, false)),
        Geometry::Disk(disk),
        Geometry::Cylinder(cyl),
    ]);
    let up = -Vec3::new(0.0, 0.0, -1.0);
    assert!(up.x.is_sign_negative() && up.y.is_sign_negative(), "the negated light direction has -0 components");
    let eps = 1e-4;
    // (x, y, distance to the occluder's lower surface from z = eps)
    let cases = [
        (0.0, 0.0, 0.5 - eps), // sphere bottom
        (0.25, 0.1, 1.0 - (0.25f32 - 0.0725).sqrt() - eps),
        (3.1, -0.2, 0.5 - eps), // cube bottom face
        (-3.0, 0.0, 1.0 - eps), // disk
        (-2.5, 0.5, 1.0 - eps),
    ];
    for &(x, y, t) in &cases {
        check_hit(&s, Vec3::new(x, y, eps), up, t, "occluder above the ground");
    }
    // Rotated by +90° about x, the cylinder's local z maps to -y: its axis runs along y at
    // x = 0, z = 2, for y in [2.5, 3.5]. Its lowest point at x is z = 2 - sqrt(1 - x²).
    for x in [0.0f32, 0.5] {
        let t = 2.0 - (1.0 - x * x).sqrt() - eps;
        check_hit(&s, Vec3::new(x, 3.0, eps), up, t, "cylinder above the ground");
    }
    // Open sky beside the occluders, and the light's own direction hits the ground.
    check_miss(&s, Vec3::new(1.5, 1.5, eps), up, "open sky");
    check_hit(&s, Vec3::new(1.5, 1.5, 5.0), Vec3::new(0.0, 0.0, -1.0), 5.0, "down to the ground");
}

/// Hits closer than `obvhs`'s fixed box-entry epsilon (1e-4): a shadow ray leaving a
/// surface next to another one (a contact, a corner) must still find it.
#[test]
fn hits_closer_than_the_traversal_epsilon() {
    let ground = rectangle(&MeshOptions::default());
    let sphere = Sphere::new(
        Affine3A::from_scale_rotation_translation(Vec3::splat(0.5), Quat::IDENTITY, Vec3::new(3.0, 0.0, 0.0)),
        false,
    );
    let s = scene(vec![Geometry::Triangles(Triangles::new(ground, false)), Geometry::Sphere(sphere)]);
    for (h, d) in [(5e-5f32, Vec3::NEG_Z), (1e-6, Vec3::NEG_Z), (5e-5, Vec3::new(0.6, 0.0, -0.8))] {
        let t = h / -d.z;
        check_hit(&s, Vec3::new(0.25, 0.125, h), d, t, "ground just below");
        assert!(!s.occluded(&Ray::new(Vec3::new(0.25, 0.125, h), d, t * 0.5)), "ground: occluded at half the distance");
    }
    // The sphere's bottom seen from just below (t = 3e-5), along +z with -0 components.
    let o = Vec3::new(3.0, 0.0, -0.5 - 3e-5);
    let si = s.intersect(&Ray::new(o, Vec3::new(-0.0, -0.0, 1.0), f32::INFINITY)).expect("sphere hit");
    assert!((si.t - 3e-5).abs() < 2e-6, "t = {}", si.t);
}
