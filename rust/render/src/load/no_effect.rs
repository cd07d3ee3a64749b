//! Properties Mitsuba 3.9.1 reads that cannot change matte's expected image, e.g. a pinhole
//! camera's `focus_distance`: accepted with the type Mitsuba reads them as (from the
//! harvested [`super::mitsuba_plugins`]), then ignored. Every other property Mitsuba reads
//! is implemented by the plugin's builder (or refused there with a one-line reason when a
//! value needs something matte does not do); anything else is an unreferenced property, as
//! in Mitsuba. `tests/render/load/walk.rs` walks the harvested list to show that every property
//! of every supported plugin is one of the two.

use super::mitsuba_plugins::{self, Kind};
use matte_scene_file::SceneError;
use matte_scene_file::xml::{SceneObject, Value};

/// A group of properties of one element tag accepted without effect.
pub struct NoEffect {
    /// Element tag (`"scene"` for the root).
    pub tag: &'static str,
    /// Plugin names, or `["*"]` for every plugin of `tag`.
    pub plugins: &'static [&'static str],
    pub names: &'static [&'static str],
    /// Why the expected image cannot change.
    pub why: &'static str,
}

/// What is accepted without effect, with the reason.
pub const NO_EFFECT: &[NoEffect] = &[
    NoEffect {
        tag: "scene",
        plugins: &["*"],
        names: &[
            "allow_thread_reordering",
            "compact_acceleration_structures",
            "embree_use_robust_intersections",
            "kd_intersection_cost",
            "kd_traversal_cost",
            "kd_empty_space_bonus",
            "kd_stop_prims",
            "kd_max_depth",
            "kd_min_max_bins",
            "kd_clip",
            "kd_retract_bad_splits",
            "kd_exact_primitive_threshold",
        ],
        why: "scheduling and acceleration-structure settings: the same intersections, the same image",
    },
    NoEffect {
        tag: "sensor",
        plugins: &["*"],
        names: &["shutter_open", "shutter_close"],
        why: "the shutter interval only matters for moving objects, and Mitsuba 3 scenes have none",
    },
    NoEffect {
        tag: "sensor",
        plugins: &["perspective", "orthographic"],
        names: &["focus_distance"],
        why: "a pinhole or orthographic camera has no depth of field, so the focus distance changes nothing",
    },
    NoEffect {
        tag: "shape",
        plugins: &["*"],
        names: &["silhouette_sampling_weight"],
        why: "weighs silhouette sampling in Mitsuba's projective (differentiable) integrators only",
    },
    NoEffect {
        tag: "integrator",
        plugins: &["*"],
        names: &["samples_per_pass", "block_size"],
        why: "how the samples are split into passes and tiles: the same samples, the same expected image",
    },
    NoEffect {
        tag: "integrator",
        plugins: &["*"],
        names: &["timeout"],
        why: "a wall-clock limit on rendering; matte always renders every sample",
    },
    NoEffect {
        tag: "integrator",
        plugins: &["moment"],
        names: &["hide_emitters"],
        why: "the moment integrator's own flag is unused; its nested integrators read theirs",
    },
    NoEffect {
        tag: "film",
        plugins: &["hdrfilm"],
        names: &["banner", "compensate"],
        why: "Mitsuba 3 marks both as read and ignores them (no banner; compensated accumulation was removed)",
    },
    NoEffect {
        tag: "texture",
        plugins: &["bitmap"],
        names: &["accel"],
        why: "hardware texture filtering on GPUs: the same interpolation, the same image",
    },
    NoEffect {
        tag: "volume",
        plugins: &["gridvolume"],
        names: &["accel"],
        why: "hardware texture interpolation on GPUs: the same interpolation, the same image",
    },
    NoEffect {
        tag: "volume",
        plugins: &["gridvolume"],
        names: &["raw"],
        why: "it only turns off the spectral upsampling of RGB grids, which RGB variants do not do",
    },
    NoEffect {
        tag: "volume",
        plugins: &["gridvolume"],
        names: &["max_value"],
        why: "it fixes the value the volume reports as its maximum (a medium's majorant), not its values",
    },
    NoEffect {
        tag: "shape",
        plugins: &["shapegroup"],
        names: &["to_world"],
        why: "a shape group is placed by its instances; Mitsuba's ShapeGroup does not apply its own to_world",
    },
];

/// Properties Mitsuba 3.9.1 reads only to refuse them (in its RGB variants, which matte's
/// images are compared with, or always): matte refuses them with Mitsuba's reason.
pub const MITSUBA_REFUSES: &[NoEffect] = &[
    NoEffect {
        tag: "sensor",
        plugins: &["*"],
        names: &["srf"],
        why: "a spectral response function needs a spectral variant; Mitsuba's RGB variants refuse it too \
              (Sensor(), src/render/sensor.cpp)",
    },
    NoEffect {
        tag: "emitter",
        plugins: &["area"],
        names: &["to_world"],
        why: "an area emitter inherits its shape's transformation; Mitsuba refuses a to_world on it too \
              (src/emitters/area.cpp)",
    },
];

/// The entry of `table` covering property `name` of `obj`, if any.
fn find(table: &'static [NoEffect], obj: &SceneObject, name: &str) -> Option<&'static NoEffect> {
    table.iter().find(|e| {
        e.tag == obj.tag && e.plugins.iter().any(|p| *p == "*" || *p == obj.plugin) && e.names.contains(&name)
    })
}

/// The [`NO_EFFECT`] entry covering property `name` of `obj`, if any.
pub fn entry(obj: &SceneObject, name: &str) -> Option<&'static NoEffect> {
    find(NO_EFFECT, obj, name)
}

/// Whether `value` is of a type Mitsuba accepts for a property it reads as `kind`
/// (`Properties::get<T>` conversions: an integer is a float, a point is a vector and back;
/// a colour or texture may be given as a number, an RGB triple or a spectrum).
pub fn type_fits(kind: Kind, value: &Value) -> bool {
    use Value as V;
    match kind {
        Kind::Float => matches!(value, V::Float(_) | V::Integer(_)),
        Kind::Integer => matches!(value, V::Integer(_)),
        Kind::Boolean => matches!(value, V::Boolean(_)),
        Kind::String => matches!(value, V::String(_)),
        Kind::Transform => matches!(value, V::Transform(_)),
        Kind::Point | Kind::Vector => matches!(value, V::Point(_) | V::Vector(_)),
        Kind::Color => matches!(value, V::Rgb(_) | V::Float(_) | V::Integer(_)),
        Kind::Texture | Kind::EmissiveTexture | Kind::UnboundedTexture | Kind::Volume => {
            matches!(value, V::Rgb(_) | V::Float(_) | V::Integer(_) | V::Spectrum(_))
        }
        Kind::Object => false,
        Kind::Any => true,
    }
}

/// Accepts the no-effect properties of every object reachable from `root`: each is checked
/// against the type Mitsuba reads it as and marked used. Returns the notes to show (one per
/// ignored property whose value a user may have meant to take effect, e.g. a `timeout`).
pub fn accept_tree(root: &SceneObject) -> Result<Vec<String>, SceneError> {
    let mut notes = Vec::new();
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![root];
    while let Some(o) = stack.pop() {
        if !seen.insert(o as *const SceneObject) {
            continue;
        }
        let plugin_name = if o.tag == "scene" { "scene" } else { o.plugin.as_str() };
        let harvested = mitsuba_plugins::plugin(&o.tag, plugin_name);
        for p in o.properties.iter() {
            if let Some(r) = find(MITSUBA_REFUSES, o, &p.name) {
                return Err(SceneError::at(
                    &p.pos,
                    format!("property \"{}\" of {} \"{}\": {}", p.name, o.tag, o.plugin, r.why),
                ));
            }
            let Some(e) = entry(o, &p.name) else { continue };
            let kind = harvested.and_then(|h| h.properties.iter().find(|q| q.name == p.name)).map(|q| q.kind);
            if let Some(kind) = kind
                && !type_fits(kind, &p.value)
            {
                return Err(SceneError::at(
                    &p.pos,
                    format!(
                        "property \"{}\" has the wrong type (expected {}, found {})",
                        p.name,
                        kind_name(kind),
                        p.value.type_name()
                    ),
                ));
            }
            o.properties.get(&p.name);
            let positive = match p.value {
                Value::Float(t) => t > 0.0,
                Value::Integer(t) => t > 0,
                _ => false,
            };
            if p.name == "timeout" && positive {
                notes.push(format!("{}: integrator timeout ignored: {}", p.pos, e.why));
            }
        }
        stack.extend(o.children.iter().rev().map(|c| &*c.object));
    }
    Ok(notes)
}

/// The XML tag a property of `kind` is written with, for messages.
pub fn kind_name(kind: Kind) -> &'static str {
    match kind {
        Kind::Float => "float",
        Kind::Integer => "integer",
        Kind::Boolean => "boolean",
        Kind::String => "string",
        Kind::Transform => "transform",
        Kind::Point => "point",
        Kind::Vector => "vector",
        Kind::Color => "rgb",
        Kind::Texture | Kind::EmissiveTexture | Kind::UnboundedTexture => "rgb, spectrum, float or a texture",
        Kind::Volume => "float or a volume",
        Kind::Object => "a nested object",
        Kind::Any => "any",
    }
}
