//! The four scenes of the seed paper's study (`mitsuba_scenes/study/`): each loads and renders
//! with every matte model through `-D bsdf=...`, every diffuse surface really uses `$bsdf`,
//! the bunny's path tracing with max_depth 2 is direct lighting (the `direct` integrator is
//! the second method), and the generated meshes are closed, face outward and have the
//! volumes of their closed forms.

use glam::Vec3;
use matte_render::film::Image;
use matte_render::load::{load_file, load_str};
use matte_render::renderer::render;
use matte_scene_file::mesh::{MeshOptions, TriangleMesh, load_obj, load_ply};
use std::collections::HashSet;
use std::f64::consts::PI;
use std::path::PathBuf;

const SCENES: &[&str] = &["bunny", "cornell", "room", "curved"];

fn study_dir() -> PathBuf {
    crate::common::repo().join("mitsuba_scenes/study")
}

fn defines(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect()
}

fn mean(img: &Image) -> Vec3 {
    img.pixels.iter().copied().sum::<Vec3>() / img.pixels.len() as f32
}

/// Whether the models `a` and `b` at their defaults have the same `f` and pdf at quasi-random
/// direction pairs (then they render the same image with the same seed).
fn same_brdf(a: &str, b: &str) -> bool {
    use matte_brdf::{DiffuseBrdf, DiffuseModel};
    let (a, b) = (DiffuseModel::with::<f64>(a, &[]).unwrap(), DiffuseModel::with::<f64>(b, &[]).unwrap());
    (0..256).all(|k| {
        let u = |c: f64| (0.5 + c * (k as f64 + 1.0)).fract() as f32;
        let d = |t: f32, p: f32| Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
        let (wi, wo) = (
            d(u(0.7548776662) * 1.55, u(0.4302966531) * std::f32::consts::TAU),
            d(u(0.5698402910) * 1.55, u(0.2327856400) * std::f32::consts::TAU),
        );
        a.eval(wi, wo, [0.7]) == b.eval(wi, wo, [0.7]) && a.pdf(wi, wo) == b.pdf(wi, wo)
    })
}

#[test]
fn every_scene_renders_with_every_model() {
    for scene in SCENES {
        let path = study_dir().join(format!("{scene}.xml"));
        let mut images = Vec::new();
        for t in matte_brdf::default_models() {
            let s = load_file(&path, &defines(&[("bsdf", t), ("res", "32")]))
                .unwrap_or_else(|e| panic!("{scene} with {t}: {e}"));
            let (img, stats) = render(
                &s.scene,
                &s.integrator,
                &s.camera,
                s.film.clone(),
                s.sampling.with_spp(2).with_seed(0),
                &|_, _| {},
            );
            assert_eq!((img.width, img.height), (32, 32), "{scene}: res sets a square film");
            assert_eq!(stats.invalid_samples, 0, "{scene} with {t}: non-finite samples");
            for p in &img.pixels {
                assert!(p.is_finite() && p.min_element() >= 0.0, "{scene} with {t}: pixel {p}");
            }
            assert!(mean(&img).min_element() > 1e-3, "{scene} with {t}: image is black ({})", mean(&img));
            images.push(img);
        }
        // Same seed, same camera: the images differ only through the BSDF, so identical
        // images would mean `$bsdf` does not reach the surfaces (unless the model is Lambert's
        // function at its defaults, as a copy of it would be: then it renders like lambert).
        let first = matte_brdf::default_models().next().expect("a model");
        for (i, t) in matte_brdf::default_models().enumerate().skip(1) {
            if !same_brdf(first, t) {
                assert_ne!(images[0].pixels, images[i].pixels, "{scene}: {t} renders like {first}");
            }
        }
    }
}

#[test]
fn defaults_and_direct_only_override() {
    for scene in SCENES {
        let path = study_dir().join(format!("{scene}.xml"));
        let s = load_file(&path, &[]).unwrap_or_else(|e| panic!("{scene}: {e}"));
        assert_eq!(
            (s.film.width(), s.film.height(), s.sampling.spp),
            (256, 256, 64),
            "{scene}: defaults res 256, spp 64"
        );
        // The study renders "direct only" with max_depth 2, and full paths with -1.
        for depth in ["2", "-1"] {
            load_file(&path, &defines(&[("max_depth", depth)]))
                .unwrap_or_else(|e| panic!("{scene} max_depth {depth}: {e}"));
        }
    }
}

/// The `<bsdf>` elements of a scene: every one is either `$bsdf` with exactly one child,
/// `<rgb name="reflectance">`, or one of the non-diffuse types; and the `<default>`s are the
/// study's.
#[test]
fn diffuse_surfaces_use_the_bsdf_parameter() {
    for scene in SCENES {
        let path = study_dir().join(format!("{scene}.xml"));
        let text = std::fs::read_to_string(&path).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let mut diffuse = 0;
        for node in doc.descendants().filter(|n| n.has_tag_name("bsdf")) {
            let ty = node.attribute("type").unwrap();
            let kids: Vec<_> = node.children().filter(|c| c.is_element()).collect();
            match ty {
                "$bsdf" => {
                    diffuse += 1;
                    assert_eq!(
                        kids.len(),
                        1,
                        "{scene}: $bsdf at byte {} must hold only a reflectance",
                        node.range().start
                    );
                    assert!(kids[0].has_tag_name("rgb") && kids[0].attribute("name") == Some("reflectance"));
                }
                "dielectric" | "conductor" | "roughconductor" => {}
                other => panic!("{scene}: bsdf type {other} is neither $bsdf nor a non-diffuse type"),
            }
        }
        assert!(diffuse >= 2, "{scene}: only {diffuse} diffuse bsdfs");
        let default = |name: &str| {
            doc.descendants()
                .find(|n| n.has_tag_name("default") && n.attribute("name") == Some(name))
                .and_then(|n| n.attribute("value"))
        };
        assert_eq!(default("bsdf"), Some("lambert"), "{scene}");
        assert_eq!(default("spp"), Some("64"), "{scene}");
        assert_eq!(default("res"), Some("256"), "{scene}");
        assert_eq!(default("max_depth"), Some(if *scene == "bunny" { "2" } else { "-1" }), "{scene}");
    }
    // The room's glass ball is a dielectric of IOR 1.5.
    let room = std::fs::read_to_string(study_dir().join("room.xml")).unwrap();
    assert!(room.contains("<bsdf type=\"dielectric\">\n            <float name=\"int_ior\" value=\"1.5\"/>"));
}

/// `docs/renderer-semantics.md` §7: `direct` (one light and one BSDF sample) has the same expectation as
/// `path` with max_depth 2. Renders the bunny both ways, for two models (Lambert and the
/// view-dependent Wolff), and compares the image means.
#[test]
fn bunny_default_is_direct_lighting() {
    let path = study_dir().join("bunny.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let path_integrator =
        "<integrator type=\"path\">\n        <integer name=\"max_depth\" value=\"$max_depth\"/>\n    </integrator>";
    assert!(text.contains(path_integrator));
    // `direct` has no max_depth, so its default goes too.
    let direct_text = text
        .replace(path_integrator, "<integrator type=\"direct\"/>")
        .replace("<default name=\"max_depth\" value=\"2\"/>", "");
    for t in ["lambert", "wolff"] {
        let d = defines(&[("bsdf", t), ("res", "32")]);
        let a = load_file(&path, &d).unwrap();
        let b = load_str(&direct_text, &path, &d).unwrap_or_else(|e| panic!("{e}"));
        let (ia, _) = render(
            &a.scene,
            &a.integrator,
            &a.camera,
            a.film.clone(),
            a.sampling.with_spp(256).with_seed(1),
            &|_, _| {},
        );
        let (ib, _) = render(
            &b.scene,
            &b.integrator,
            &b.camera,
            b.film.clone(),
            b.sampling.with_spp(256).with_seed(2),
            &|_, _| {},
        );
        let (ma, mb) = (mean(&ia), mean(&ib));
        for c in 0..3 {
            assert!((ma[c] - mb[c]).abs() <= 0.01 * mb[c], "{t}: path(max_depth 2) {ma} vs direct {mb}");
        }
        // Full path tracing adds the bunny-ground interreflections: brighter.
        let c = load_file(&path, &defines(&[("bsdf", t), ("res", "32"), ("max_depth", "-1")])).unwrap();
        let (ic, _) = render(
            &c.scene,
            &c.integrator,
            &c.camera,
            c.film.clone(),
            c.sampling.with_spp(256).with_seed(3),
            &|_, _| {},
        );
        let mc = mean(&ic);
        for c in 0..3 {
            assert!(mc[c] > 1.02 * mb[c], "{t}: max_depth -1 gives {mc}, direct {mb}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// generated meshes

/// Signed volume by the divergence theorem (positive iff the closed surface's
/// counter-clockwise faces point outward), after checking that the mesh is closed with a
/// consistent winding: every directed edge once, and its reverse once.
fn closed_outward_volume(name: &str, m: &TriangleMesh) -> f64 {
    let mut edges = HashSet::new();
    for t in &m.triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            assert!(edges.insert((a, b)), "{name}: directed edge ({a}, {b}) twice: inconsistent winding");
        }
    }
    for &(a, b) in &edges {
        assert!(edges.contains(&(b, a)), "{name}: boundary edge ({a}, {b})");
    }
    let vol: f64 = (0..m.triangles.len())
        .map(|i| {
            let [p0, p1, p2] = m.corners(i).map(|p| p.as_dvec3());
            p0.dot(p1.cross(p2)) / 6.0
        })
        .sum();
    assert!(vol > 0.0, "{name}: faces point inward (volume {vol})");
    vol
}

/// File normals (where given) agree with the winding: every corner's normal is on the front.
fn normals_agree_with_winding(name: &str, m: &TriangleMesh) {
    assert_eq!(m.normals.len(), m.positions.len(), "{name}: vertex normals");
    for (i, t) in m.triangles.iter().enumerate() {
        let [p0, p1, p2] = m.corners(i);
        let n = (p1 - p0).cross(p2 - p0);
        for &v in t {
            assert!(n.dot(m.normals[v as usize]) > 0.0, "{name}: triangle {i} vertex {v}");
        }
    }
}

/// Steiner's formula: the box of full inner sizes (a, b, c) grown by a ball of radius r has
/// volume abc + r·S + (π/4)·r²·L + (4/3)·π·r³, S the inner surface and L the inner total edge
/// length.
fn rounded_box_volume(size: [f64; 3], r: f64) -> f64 {
    let [a, b, c] = size.map(|s| s - 2.0 * r);
    a * b * c + r * 2.0 * (a * b + b * c + c * a) + PI / 4.0 * r * r * 4.0 * (a + b + c) + 4.0 / 3.0 * PI * r.powi(3)
}

#[test]
fn generated_meshes_are_closed_outward_and_sized() {
    let assets = study_dir().join("assets");
    let opts = MeshOptions::default();
    // (file, closed-form volume): the rounded boxes of make_meshes.py and the torus 2π²Rr².
    // Inscribed polygons lose a little volume: at most 1 % with 6 segments per quarter edge
    // and 64 x 32 torus segments.
    let meshes = [
        ("rounded_tall.obj", rounded_box_volume([0.6, 1.2, 0.6], 0.07)),
        ("rounded_short.obj", rounded_box_volume([0.6, 0.6, 0.6], 0.07)),
        ("chair_seat.obj", rounded_box_volume([0.5, 0.08, 0.48], 0.035)),
        ("chair_back.obj", rounded_box_volume([0.5, 0.3, 0.06], 0.025)),
        ("torus.obj", 2.0 * PI * PI * 0.4 * 0.15 * 0.15),
    ];
    for (file, want) in meshes {
        let m = load_obj(&assets.join(file), &opts).unwrap_or_else(|e| panic!("{e}"));
        let vol = closed_outward_volume(file, &m);
        assert!(vol <= want * 1.0001 && vol >= want * 0.99, "{file}: volume {vol}, closed form {want}");
        normals_agree_with_winding(file, &m);
    }
    // The bunny: closed, outward, height 1 standing on y = 0, footprint centred on x = z = 0.
    let bytes = std::fs::read(assets.join("bunny.ply")).unwrap();
    let header =
        String::from_utf8_lossy(&bytes[..bytes.windows(10).position(|w| w == b"end_header").unwrap()]).into_owned();
    assert!(!header.contains("property float nx"), "bunny.ply carries no normals: renderers compute smooth ones");
    let m = load_ply(&assets.join("bunny.ply"), &opts).unwrap_or_else(|e| panic!("{e}"));
    closed_outward_volume("bunny.ply", &m);
    let lo = m.positions.iter().copied().fold(Vec3::INFINITY, Vec3::min);
    let hi = m.positions.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
    assert!(lo.y.abs() < 1e-6 && (hi.y - 1.0).abs() < 1e-6, "bunny height: {lo} .. {hi}");
    assert!((lo.x + hi.x).abs() < 1e-5 && (lo.z + hi.z).abs() < 1e-5, "bunny footprint not centred: {lo} .. {hi}");
}
