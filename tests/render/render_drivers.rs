//! The renderer's two tile drivers give the same image: the wavefront (many paths per thread,
//! batched ray queries) and one path at a time draw the same numbers for every sample, so the
//! images differ only by the order in which the samples reach the film (float sums: a few
//! ulps). The one-path driver is the integrators' plain loop (`Integrator::li`), the oracle
//! here (and the profiled wavefront is checked the same way); the scenes cover `path` (bounded and unbounded, hidden emitters, an environment),
//! `direct` (several light and BSDF samples, delta lights), matte's models, textures and
//! analytic shapes.

use matte_render::film::Image;
use matte_render::integrator::{Driver, Integrator};
use matte_render::load::{LoadedScene, load_file};
use matte_render::renderer::render_with;

/// A bundled scene, loaded as Mitsuba loads it after `import matte_mitsuba`: the package folder
/// (here the source tree's `python/matte_mitsuba`, which holds `ground_truth/`) on the file
/// resolver, as `<path>` folders of a copy beside the scene's own folder.
fn load(file: &str, defines: &[(&str, &str)]) -> LoadedScene {
    let scenes = crate::common::repo().join("mitsuba_scenes");
    let text = std::fs::read_to_string(scenes.join(file)).unwrap();
    load_text(file, &text, scenes.join(file).parent().unwrap(), defines)
}

/// The scene `text` under the name `file`, with `folder` and the package folder on the file
/// resolver (see [`load`]).
fn load_text(file: &str, text: &str, folder: &std::path::Path, defines: &[(&str, &str)]) -> LoadedScene {
    let open = text.find("<scene").and_then(|i| text[i..].find('>').map(|j| i + j + 1)).expect("<scene ...>");
    let paths = format!(
        "<path value=\"{}\"/><path value=\"{}\"/>",
        folder.display(),
        crate::common::repo().join("python/matte_mitsuba").display()
    );
    let path = std::env::temp_dir().join(format!("matte_render_drivers_{}", std::process::id())).join(file);
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(&path, format!("{}{paths}{}", &text[..open], &text[open..])).unwrap();
    let defines: Vec<(String, String)> = defines.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    load_file(&path, &defines).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The largest per-channel difference between two images, relative to the first (floored at
/// 1e-3). Two renders with the same driver differ too: tiles reach the film in the order
/// threads finish them, and neighbouring tiles' borders overlap.
fn largest_relative_difference(a: &Image, b: &Image) -> f32 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| ((*x - *y).abs() / x.abs().max(glam::Vec3::splat(1e-3))).max_element())
        .fold(0.0, f32::max)
}

/// Renders `loaded` with both drivers and compares pixel by pixel.
fn assert_same_image(name: &str, loaded: &LoadedScene, spp: u32) {
    let run = |driver| {
        render_with(
            &loaded.scene,
            &loaded.integrator,
            &loaded.camera,
            loaded.film.clone(),
            loaded.sampling.with_spp(spp).with_seed(7),
            driver,
            &|_, _| {},
        )
    };
    let (a, sa) = run(Driver::OnePath);
    let (b, sb) = run(Driver::Wavefront);
    // Counting the stages changes nothing in the image, and counts every stage.
    let (c, sc) = run(Driver::WavefrontProfiled);
    let profiled = largest_relative_difference(&b, &c);
    assert!(profiled <= 1e-4, "{name}: the profiled wavefront differs by {profiled} (relative)");
    let ticks = sc.stage_ticks.unwrap_or_else(|| panic!("{name}: no stage ticks"));
    assert!(ticks.trace > 0 && ticks.shading > 0 && ticks.film > 0, "{name}: {ticks:?}");
    assert!(sb.stage_ticks.is_none(), "{name}: the plain wavefront counted stages");
    assert_eq!((sa.samples, sa.rays, sa.invalid_samples), (sb.samples, sb.rays, sb.invalid_samples), "{name}");
    assert_eq!((a.width, a.height), (b.width, b.height), "{name}");
    let worst = largest_relative_difference(&a, &b);
    eprintln!("{name}: largest relative difference {worst:e}");
    assert!(worst <= 1e-4, "{name}: drivers differ by {worst} (relative) somewhere");
    let mean = a.pixels.iter().map(|v| v.element_sum() as f64 / 3.0).sum::<f64>() / a.pixels.len() as f64;
    assert!(mean > 1e-4, "{name}: black image ({mean}), the comparison says nothing");
}

#[test]
fn path_integrator_scenes() {
    assert_same_image("cornell", &load("cornell_box.xml", &[("res", "48"), ("max_depth", "-1")]), 8);
    assert_same_image("envmap", &load("envmap_sky.xml", &[("res", "32")]), 4);
    // Every registered model (the registry's scene; the wheel's all_types.xml is written at build time).
    let all_types = crate::common::all_types_scene();
    let scenes = crate::common::repo().join("mitsuba_scenes");
    assert_same_image("all_types", &load_text("all_types.xml", &all_types, &scenes, &[("res", "32")]), 4);
    assert_same_image("textured", &load("textured_parameters.xml", &[("res", "32")]), 4);
    assert_same_image("room", &load("study/room.xml", &[("res", "32"), ("bsdf", "ginneken")]), 4);
}

#[test]
fn path_with_hidden_emitters_and_short_paths() {
    for (max_depth, hide) in [(1, false), (2, true), (u32::MAX, true)] {
        let mut loaded = load("cornell_box.xml", &[("res", "32")]);
        let Integrator::Path(p) = &mut loaded.integrator else { panic!("cornell_box.xml renders with path") };
        p.max_depth = max_depth;
        p.hide_emitters = hide;
        p.rr_depth = 2;
        assert_same_image(&format!("cornell max_depth {max_depth} hide_emitters {hide}"), &loaded, 4);
    }
}

#[test]
fn direct_integrator_scenes() {
    assert_same_image("direct point lights", &load("direct_point_lights.xml", &[("res", "32")]), 4);
    assert_same_image("sun", &load("sun_straight_down.xml", &[("res", "32")]), 4);
    assert_same_image("bunny", &load("study/bunny.xml", &[("res", "32")]), 4);
    // Several light and BSDF samples per camera hit, emitters hidden.
    let mut loaded = load("cornell_box.xml", &[("res", "32")]);
    let integrator =
        matte_render::integrator::DirectIntegrator { emitter_samples: 3, bsdf_samples: 2, hide_emitters: true };
    loaded.integrator = Integrator::Direct(integrator);
    assert_same_image("cornell direct 3+2 hidden", &loaded, 4);
}

/// `matte render --driver` names: the two drivers, and a clear error for anything else.
#[test]
fn driver_names_parse() {
    assert_eq!(Driver::parse("one-path"), Ok(Driver::OnePath));
    assert_eq!(Driver::parse("wavefront"), Ok(Driver::Wavefront));
    let err = Driver::parse("wave").unwrap_err();
    assert!(err.contains("\"wave\"") && err.contains("one-path or wavefront"), "{err}");
}
