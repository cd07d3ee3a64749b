//! The scene loader `matte_render::load` (XML object tree → renderable `LoadedScene`), one
//! file per plugin family under `tests/render/load/` (`integrator`, `sensor`, `shape`,
//! `emitter`, `bsdf`, `texture`), plus the parser's errors seen through the loader (`errors`),
//! odd values (`odd_values`), the walk over every property Mitsuba reads (`walk`) and the
//! bundled scenes (`scenes`); the helpers they share are here. Expected values come from
//! `docs/renderer-semantics.md` (the section is named at each use as §N; [verified] numbers
//! there were measured with Mitsuba 3.9.1 `scalar_rgb`), from `docs/models.md` for matte's own
//! plugins, or from closed forms (ray–sphere/cylinder/plane hits, normal-incidence Fresnel, the
//! pinhole projection). Mitsuba's own numbers are in `load/references.rs`, which
//! `load/generate_reference.py` writes from Mitsuba 3.9.1 (`scalar_rgb`).
//! Every error test checks that the message names `file:line` and says what is wrong.
//! Where matte is deliberately stricter than Mitsuba (limits that keep NaN and panics out of
//! the renderer), the test says "matte's limit".

mod bsdf;
mod emitter;
mod errors;
mod integrator;
mod odd_values;
#[rustfmt::skip] // generated data, one reference per line
mod references;
mod scenes;
mod sensor;
mod shape;
mod texture;
mod walk;

use std::path::{Path, PathBuf};

use glam::Vec3;
use matte_render::bsdf::{Bsdf, Diffuse, Matte};
use matte_render::geometry::Ray;
use matte_render::load::{LoadedScene, load_str};
use matte_render::shape::SurfaceInteraction;
use matte_render::texture::Texture;
use matte_scene_file::SceneError;

use crate::common::{SENSOR, assert_error_at, scene};

const FILE: &str = "/virtual/scenes/scene.xml";

fn load(xml: &str) -> Result<LoadedScene, SceneError> {
    load_str(xml, Path::new(FILE), &[])
}

fn ok(xml: &str) -> LoadedScene {
    match load(xml) {
        Ok(s) => s,
        Err(e) => panic!("unexpected error: {e}\n--- scene ---\n{xml}"),
    }
}

/// [`SENSOR`] on line 2, `body` from line 3 on.
fn with_sensor(body: &str) -> String {
    scene(&format!("{SENSOR}\n{body}"))
}

fn assert_err(r: Result<LoadedScene, SceneError>, line: u32, needle: &str) {
    match r {
        Ok(_) => panic!("expected an error containing {needle:?}"),
        Err(e) => assert_error_at(&e, Path::new(FILE), line, needle),
    }
}

/// `assert_err` for a scene made by [`with_sensor`]: `line` counts from `body`'s first line (= 1).
fn assert_body_err(body: &str, line: u32, needle: &str) {
    assert_err(load(&with_sensor(body)), line + 2, needle);
}

fn close3(got: Vec3, want: Vec3, tol: f32) -> bool {
    (got - want).abs().max_element() <= tol
}

#[track_caller]
fn assert_vec(got: Vec3, want: Vec3, tol: f32) {
    assert!(close3(got, want, tol), "got {got}, want {want}");
}

fn hit(s: &LoadedScene, o: Vec3, d: Vec3) -> Option<SurfaceInteraction> {
    s.scene.intersect(&Ray::new(o, d.normalize(), f32::INFINITY))
}

/// The BSDF of shape `i`.
fn shape_bsdf(s: &LoadedScene, i: usize) -> &Bsdf {
    &s.scene.bsdfs[s.scene.shapes[i].bsdf as usize]
}

fn constant_reflectance(b: &Bsdf) -> Vec3 {
    match b {
        Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(c) })
        | Bsdf::Matte(Matte { reflectance: Texture::Constant(c), .. }) => *c,
        other => panic!("expected a constant diffuse reflectance, got {other:?}"),
    }
}

/// A fresh folder for tests that write files.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_render_load_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}
