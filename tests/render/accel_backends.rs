//! The three ray-query arrangements (`render::accel::Backend`: everything in Embree, meshes in
//! Embree with analytic shapes in the CWBVH, everything in the CWBVH) answer the same queries
//! on path-tracer rays of the bundled scenes. The CWBVH with its own Möller–Trumbore test is
//! the second method; Embree's triangle test rounds differently, so distances agree to a
//! relative 1e-4 and a ray may only disagree on *which* surface it hits when it grazes an
//! edge (at most 0.05 % of rays; 0 in practice on these scenes, measured below).

use matte_render::accel::{Accel, Backend};
use matte_render::load;

fn scene(file: &str, defines: &[(&str, &str)]) -> load::LoadedScene {
    let root = crate::common::repo().join("mitsuba_scenes");
    let defines: Vec<(String, String)> = defines.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    load::load_file(&root.join(file), &defines).unwrap()
}

fn compare_backends(name: &str, loaded: &load::LoadedScene) {
    let (rays, shadow) = loaded.walk_rays(3000);
    let shapes = &loaded.scene.shapes;
    let reference = Accel::build_with(shapes, Backend::CwBvh).unwrap();
    for backend in [Backend::Embree, Backend::EmbreeMeshes] {
        let accel = Accel::build_with(shapes, backend).unwrap_or_else(|e| panic!("{name}: Embree unavailable: {e}"));
        assert_eq!(accel.primitive_count(), reference.primitive_count(), "{name} {}", backend.name());
        let mut differ = 0usize;
        for r in &rays {
            let (a, b) = (accel.intersect(r, shapes), reference.intersect(r, shapes));
            match (a, b) {
                (Some(a), Some(b)) if a.shape == b.shape && a.prim == b.prim => {
                    assert!(
                        (a.t - b.t).abs() <= 1e-4 * b.t.max(1.0),
                        "{name} {}: t {} vs {} on {r:?}",
                        backend.name(),
                        a.t,
                        b.t
                    );
                    assert!((a.bary - b.bary).abs().max_element() <= 1e-3, "{name}: bary {:?} vs {:?}", a.bary, b.bary);
                }
                (None, None) => {}
                _ => differ += 1,
            }
        }
        // Eight rays per call (Embree's rtcIntersect8 with `embree`) give the one-ray answers;
        // inactive lanes (every fifth ray) give no hit.
        for (k, c) in rays.chunks_exact(8).enumerate() {
            let packet: [matte_render::geometry::Ray; 8] = std::array::from_fn(|i| c[i]);
            let active: [bool; 8] = std::array::from_fn(|i| (8 * k + i) % 5 != 0);
            let one_ray = c.iter().zip(active).map(|(r, a)| if a { accel.intersect(r, shapes) } else { None });
            for (r, (a, b)) in c.iter().zip(accel.intersect8(&packet, active, shapes).into_iter().zip(one_ray)) {
                match (a, b) {
                    (Some(a), Some(b)) => {
                        assert!(
                            a.shape == b.shape && a.prim == b.prim,
                            "{name} {}: packet hit {a:?} vs {b:?} on {r:?}",
                            backend.name()
                        );
                        assert!((a.t - b.t).abs() <= 1e-4 * b.t.max(1.0), "{name}: packet t {} vs {}", a.t, b.t);
                    }
                    (None, None) => {}
                    (a, b) => panic!("{name} {}: packet {a:?} vs one ray {b:?} on {r:?}", backend.name()),
                }
            }
        }
        let blocked_differ =
            shadow.iter().filter(|r| accel.occluded(r, shapes) != reference.occluded(r, shapes)).count();
        // Eight shadow rays per call (rtcOccluded8) give the one-ray answers; inactive lanes
        // (every third ray) are unblocked.
        for (k, c) in shadow.chunks_exact(8).enumerate() {
            let packet: [matte_render::geometry::Ray; 8] = std::array::from_fn(|i| c[i]);
            let active: [bool; 8] = std::array::from_fn(|i| (8 * k + i) % 3 != 0);
            let blocked8 = accel.occluded8(&packet, active, shapes);
            for i in 0..8 {
                let one = active[i] && accel.occluded(&c[i], shapes);
                assert_eq!(blocked8[i], one, "{name} {}: occluded8 lane {i} on {:?}", backend.name(), c[i]);
            }
        }
        let (n, m) = (rays.len(), shadow.len());
        eprintln!(
            "{name} {}: {differ} of {n} closest hits, {blocked_differ} of {m} shadow rays differ",
            backend.name()
        );
        assert!(differ * 2000 <= n, "{name} {}: {differ} of {n} closest hits differ", backend.name());
        assert!(blocked_differ * 2000 <= m, "{name} {}: {blocked_differ} of {m} shadow rays differ", backend.name());
        let blocked = shadow.iter().filter(|r| reference.occluded(r, shapes)).count();
        assert!(
            blocked > m / 100 && blocked < m,
            "{name}: {blocked} of {m} shadow rays blocked: the test needs both kinds"
        );
    }
}

#[test]
fn embree_and_cwbvh_agree_on_the_cornell_box() {
    compare_backends("cornell", &scene("cornell_box.xml", &[("res", "32")]));
}

#[test]
fn embree_and_cwbvh_agree_on_the_bunny() {
    compare_backends("bunny", &scene("study/bunny.xml", &[("res", "32"), ("bsdf", "diffuse")]));
}

/// Meshes, spheres and cylinders together: Embree's user geometries call the analytic shapes.
#[test]
fn embree_and_cwbvh_agree_on_the_room() {
    compare_backends("room", &scene("study/room.xml", &[("res", "32"), ("bsdf", "diffuse")]));
}
