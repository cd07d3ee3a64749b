//! What stays outside matte's renderer, said once: Mitsuba 3.9.1 plugins of the kinds matte
//! does not render (participating media, polarisation-only plugins, curves, hair, SDF
//! grids) are refused with one line naming the element and the reason, wherever they
//! appear (top level, nested, or through a `<ref>`). A `<volume>` is the one exception: it is
//! rendered as the `volume` of a `<texture type="volume">` (a surface texture) and may be
//! declared at the top level for such a texture to `<ref>`; anywhere else it belongs to a
//! participating medium. The README's scope table lists the same.

use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// A refused class of Mitsuba plugins: the element tags and plugin names it covers (`"*"`:
/// every plugin of that tag) and the reason given.
struct Refused {
    tag: &'static str,
    plugins: &'static [&'static str],
    why: &'static str,
}

const REFUSED: &[Refused] = &[
    Refused { tag: "medium", plugins: &["*"], why: "participating media are outside matte's scope (surfaces only)" },
    Refused {
        tag: "phase",
        plugins: &["*"],
        why: "phase functions belong to participating media, outside matte's scope",
    },
    Refused {
        tag: "volume",
        plugins: &["*"],
        why: "a volume outside a volume texture belongs to a participating medium, outside matte's scope \
              (matte renders a <volume> only as the \"volume\" of a <texture type=\"volume\">)",
    },
    Refused {
        tag: "bsdf",
        plugins: &["polarizer", "retarder", "circular", "pplastic", "measured_polarized"],
        why: "polarisation-only BSDFs are outside matte's scope (matte renders RGB radiance)",
    },
    Refused {
        tag: "integrator",
        plugins: &["stokes"],
        why: "polarisation (Stokes vectors) is outside matte's scope (matte renders RGB radiance)",
    },
    Refused { tag: "bsdf", plugins: &["hair"], why: "hair is outside matte's scope" },
    Refused { tag: "shape", plugins: &["bsplinecurve", "linearcurve"], why: "curves are outside matte's scope" },
    Refused { tag: "shape", plugins: &["sdfgrid"], why: "SDF grids are outside matte's scope" },
];

/// The one-line refusal for `obj` if it is of a kind outside matte's scope.
pub(crate) fn refused(obj: &SceneObject) -> Option<SceneError> {
    let r = REFUSED.iter().find(|r| r.tag == obj.tag && r.plugins.iter().any(|p| *p == "*" || *p == obj.plugin))?;
    Some(SceneError::at(&obj.pos, format!("<{} type=\"{}\">: {}", obj.tag, obj.plugin, r.why)))
}

/// The first object reachable from `root` (depth first, document order) that is out of scope.
/// A `<volume>` is in scope as a child of a `<texture type="volume">` (which reads the one named
/// `volume` and reports any other as unused) and at the top level (declared for a `<ref>`); a volume reached both ways (a declared one that a
/// medium refers to) is refused where it is out of place, as its parent is visited too.
pub(crate) fn check_tree(root: &SceneObject) -> Result<(), SceneError> {
    let mut seen = std::collections::HashSet::new();
    let mut stack = vec![(root, false)];
    while let Some((o, volume_allowed)) = stack.pop() {
        if !seen.insert((o as *const SceneObject, volume_allowed)) {
            continue;
        }
        if !(volume_allowed && o.tag == "volume")
            && let Some(e) = refused(o)
        {
            return Err(e);
        }
        let volume_texture = o.tag == "texture" && o.plugin == "volume";
        stack.extend(o.children.iter().rev().map(|c| (&*c.object, o.tag == "scene" || volume_texture)));
    }
    Ok(())
}

/// Every (tag, plugin) pattern refused by scope, for the README table and tests.
pub fn refused_plugins() -> impl Iterator<Item = (&'static str, &'static str, &'static str)> {
    REFUSED.iter().flat_map(|r| r.plugins.iter().map(move |p| (r.tag, *p, r.why)))
}
