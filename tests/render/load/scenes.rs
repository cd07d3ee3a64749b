//! The bundled scenes (`mitsuba_scenes/`): with random edits each loads or fails with one line
//! (never a panic); `sun_straight_down.xml`, `envmap_sky.xml` and `orthographic_instances.xml`
//! render, and the sun casts its shadow.

use std::path::PathBuf;

use glam::{Vec2, Vec3};
use matte_render::emitter::Light;
use matte_render::geometry::Ray;
use matte_render::load::{load_file, load_str};

/// Every bundled scene with random edits (characters deleted, duplicated or replaced by XML
/// syntax, digits or signs; a seeded stream): loading never panics, and an error is one line
/// that starts with a file name.
#[test]
fn mutated_bundled_scenes_load_or_fail_with_one_line() {
    use rand::{Rng, SeedableRng};
    let dir = crate::common::repo().join("mitsuba_scenes");
    let mut rng = rand_pcg::Pcg64::seed_from_u64(0x5eed);
    let alphabet = b"<>/=\"' -0123456789.e$#&;abnrxyzIN";
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "xml"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 20);
    let (mut loaded, mut failed) = (0, 0);
    for scene in &scenes {
        let text = std::fs::read(scene).unwrap();
        for trial in 0..40 {
            let mut v = text.clone();
            for _ in 0..rng.random_range(1..4) {
                let i = rng.random_range(0..v.len());
                match rng.random_range(0..3) {
                    0 => drop(v.drain(i..(i + rng.random_range(1..6)).min(v.len()))),
                    1 => {
                        let piece: Vec<u8> = v[i..(i + rng.random_range(1..12)).min(v.len())].to_vec();
                        v.splice(i..i, piece);
                    }
                    _ => v[i] = alphabet[rng.random_range(0..alphabet.len())],
                }
            }
            let Ok(xml) = String::from_utf8(v) else { continue };
            let r = std::panic::catch_unwind(|| load_str(&xml, scene, &[("spp".into(), "1".into())]));
            match r.unwrap_or_else(|_| panic!("{} trial {trial}: the loader panicked on\n{xml}", scene.display())) {
                Ok(_) => loaded += 1,
                Err(e) => {
                    let t = e.to_string();
                    assert!(!t.trim_end().contains('\n') && t.starts_with('/'), "{}: {t}", scene.display());
                    failed += 1;
                }
            }
        }
    }
    // Both outcomes occur: the edits are neither all harmless nor all fatal.
    assert!(loaded > 50 && failed > 200, "loaded {loaded}, failed {failed}");
}

/// The bundled scenes of the directional sun, the envmap, the orthographic sensor and instancing
/// load, render without NaN, and the sun scene's sphere shadows the ground straight below it
/// (the straight-down sun regression).
#[test]
fn bundled_element_scenes_render() {
    let root = crate::common::repo().join("mitsuba_scenes");
    for name in ["sun_straight_down.xml", "envmap_sky.xml", "orthographic_instances.xml"] {
        let s = load_file(&root.join(name), &[("res".into(), "8".into())]).unwrap_or_else(|e| panic!("{name}: {e}"));
        let (img, _) = matte_render::renderer::render(
            &s.scene,
            &s.integrator,
            &s.camera,
            s.film.clone(),
            s.sampling.with_spp(4).with_seed(0),
            &|_, _| {},
        );
        assert!(img.pixels.iter().all(|p| p.is_finite()), "{name}: non-finite pixel");
        assert!(img.pixels.iter().any(|p| p.max_element() > 0.0), "{name}: black image");
    }
    let s = load_file(&root.join("sun_straight_down.xml"), &[]).unwrap();
    let light = &s.scene.emitters[0];
    let ground = s
        .scene
        .intersect(&Ray::new(Vec3::new(-0.8, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("sphere top");
    assert!((ground.p.z - 1.8).abs() < 1e-4, "the ray down meets the sphere first");
    let below = s
        .scene
        .intersect(&Ray::new(Vec3::new(-0.8, 0.0, 0.5), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("ground");
    let es = light.sample_direction(below.p, Vec2::ZERO, &s.scene.shapes).unwrap();
    assert!(s.scene.occluded(&s.scene.shadow_ray(&below, &es)), "the ground below the sphere is lit");
    let open = s
        .scene
        .intersect(&Ray::new(Vec3::new(0.2, -1.5, 0.5), Vec3::new(0.0, 0.0, -1.0), f32::INFINITY))
        .expect("ground");
    let es = light.sample_direction(open.p, Vec2::ZERO, &s.scene.shapes).unwrap();
    assert!(!s.scene.occluded(&s.scene.shadow_ray(&open, &es)), "open ground is shadowed");
}
