//! Shading frames as Mitsuba 3.9.1 builds them (`SurfaceInteraction::initialize_sh_frame`):
//! `s` along dp/du projected onto the tangent plane, `t = n × s`, with each shape's dp/du
//! (`src/render/mesh.cpp`, `src/shapes/{sphere,disk,cylinder}.cpp`). Anisotropic BSDFs and
//! tangent-space normal maps are oriented by `s`. Expected tangents are worked out by hand.

use glam::{Affine3A, Quat, Vec2, Vec3};
use matte_render::bsdf::{Bsdf, Diffuse};
use matte_render::geometry::Ray;
use matte_render::scene::Scene;
use matte_render::shape::{Cylinder, Disk, Geometry, Shape, Sphere, SurfaceInteraction, Triangles};
use matte_render::texture::Texture;
use matte_scene_file::mesh::TriangleMesh;

fn hit(g: Geometry, o: Vec3, d: Vec3) -> SurfaceInteraction {
    let shapes = vec![Shape { geometry: g, bsdf: 0, emitter: None, plugin: "test".into() }];
    let scene = Scene::new(
        shapes,
        vec![Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(Vec3::splat(0.5)) })],
        vec![],
        vec![],
    );
    scene.intersect(&Ray::new(o, d, f32::INFINITY)).expect("hit")
}

fn assert_frame(si: &SurfaceInteraction, s: Vec3, what: &str) {
    let f = si.sh_frame;
    assert!((f.s - s).length() < 1e-5, "{what}: s = {}, expected {s}", f.s);
    assert!((f.t - f.n.cross(s)).length() < 1e-5, "{what}: t = {}", f.t);
    assert!(f.s.dot(f.n).abs() < 1e-6 && (f.s.length() - 1.0).abs() < 1e-6);
}

fn triangle(uvs: Vec<Vec2>) -> Geometry {
    // p0 = 0, p1 = 2y, p2 = −x: face normal (p1 − p0) × (p2 − p0) = +z.
    let mesh = TriangleMesh {
        positions: vec![Vec3::ZERO, Vec3::new(0.0, 2.0, 0.0), Vec3::new(-1.0, 0.0, 0.0)],
        normals: vec![],
        uvs,
        triangles: vec![[0, 1, 2]],
        attributes: vec![],
    };
    Geometry::Triangles(Triangles::new(mesh, false))
}

#[test]
fn mesh_frames_follow_dp_du() {
    let (o, d) = (Vec3::new(-0.2, 0.3, 1.0), Vec3::NEG_Z);
    // No texture coordinates: dp_du = p1 − p0 = +y.
    assert_frame(&hit(triangle(vec![]), o, d), Vec3::Y, "no uv");
    // uv0 = (0,0), uv1 = (0,1), uv2 = (1,0): u grows towards p2, so dp_du = p2 − p0 = −x.
    assert_frame(&hit(triangle(vec![Vec2::ZERO, Vec2::Y, Vec2::X]), o, d), Vec3::NEG_X, "uv");
    // Degenerate uvs: coordinate_system(+z).s = (1, 0, 0) (Duff et al. with n = +z).
    assert_frame(&hit(triangle(vec![Vec2::ZERO, Vec2::ZERO, Vec2::ZERO]), o, d), Vec3::X, "degenerate uv");
}

#[test]
fn analytic_frames_follow_dp_du() {
    // Sphere: dp_du ∝ to_world·(−y, x, 0) of the local point; at local +x that is +y.
    let s = Geometry::Sphere(Sphere::new(Affine3A::IDENTITY, false));
    assert_frame(&hit(s, Vec3::new(3.0, 0.0, 0.0), Vec3::NEG_X), Vec3::Y, "sphere");
    // Rotated by 90° about z: local +x sits at world +y and its tangent is world −x.
    let r = Geometry::Sphere(Sphere::new(
        Affine3A::from_rotation_translation(Quat::from_rotation_z(std::f32::consts::FRAC_PI_2), Vec3::ZERO),
        false,
    ));
    assert_frame(&hit(r, Vec3::new(0.0, 3.0, 0.0), Vec3::NEG_Y), Vec3::NEG_X, "rotated sphere");
    // Cylinder: dp_du ∝ (−y, x, 0); at local (1, 0, ½) that is +y.
    let c = Geometry::Cylinder(Cylinder::new(Affine3A::IDENTITY, false));
    assert_frame(&hit(c, Vec3::new(3.0, 0.0, 0.5), Vec3::NEG_X), Vec3::Y, "cylinder");
    // Disk: dp_du = (cos φ, sin φ, 0), radial.
    let dk = || Geometry::Disk(Disk::new(Affine3A::IDENTITY, false));
    assert_frame(&hit(dk(), Vec3::new(0.5, 0.0, 1.0), Vec3::NEG_Z), Vec3::X, "disk on +x");
    assert_frame(&hit(dk(), Vec3::new(0.0, 0.5, 1.0), Vec3::NEG_Z), Vec3::Y, "disk on +y");
}
