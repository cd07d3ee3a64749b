//! Every property Mitsuba 3.9.1 reads (the harvested list,
//! `rust/render/src/load/mitsuba_plugins.rs`) of every plugin the loader builds (`MITSUBA_PLUGINS`)
//! is accepted, each alone in a scene that otherwise loads; the README's scope table says what the
//! loader's tables say, and every plugin it names loads.

use std::path::PathBuf;

use super::load;
use crate::common::{SENSOR, scene};

/// An asset of `mitsuba_scenes/assets` by absolute path.
fn asset(name: &str) -> String {
    format!("{}/mitsuba_scenes/assets/{name}", crate::common::repo().display())
}

/// A scene holding one object of Mitsuba plugin (`tag`, `plugin`), with `props` (XML of its
/// properties) inside it, plus whatever else that plugin requires to load (a nested BSDF, a
/// file name, a shape group to instance, ...). `props` never repeats a name given here.
fn scene_with_plugin(tag: &str, plugin: &str, props: &str, given: &[&str]) -> String {
    let has = |n: &str| given.contains(&n);
    let req = |name: &str, xml: String| if has(name) { String::new() } else { xml };
    let string = |name: &str, v: &str| req(name, format!("<string name=\"{name}\" value=\"{v}\"/>"));
    let diffuse = "<bsdf type=\"diffuse\"/>";
    let bitmap = |name: &str, file: &str| {
        req(
            name,
            format!(
                "<texture type=\"bitmap\" name=\"{name}\"><string name=\"filename\" value=\"{}\"/></texture>",
                asset(file)
            ),
        )
    };
    let sensor = |inner: &str| format!("<sensor type=\"perspective\">{inner}</sensor>");
    let film = |inner: &str| {
        format!(
            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"2\"/>{inner}</film>"
        )
    };
    let object = |extra: String| format!("<{tag} type=\"{plugin}\">{props}{extra}</{tag}>");
    let body = match (tag, plugin) {
        ("scene", _) => return format!("<scene version=\"3.0.0\">\n{props}\n{SENSOR}\n</scene>"),
        ("bsdf", "twosided" | "mask") => object(diffuse.into()),
        ("bsdf", "blendbsdf") => {
            object(format!("{}{diffuse}{diffuse}", req("weight", "<float name=\"weight\" value=\"0.5\"/>".into())))
        }
        ("bsdf", "normalmap") => object(format!("{}{diffuse}", bitmap("normalmap", "bumps.png"))),
        ("bsdf", "bumpmap") => object(format!("{}{diffuse}", bitmap("texture", "bumps.png"))),
        ("bsdf", _) => format!("<shape type=\"rectangle\">{}</shape>", object(String::new())),
        ("texture", "mesh_attribute") => format!(
            "<shape type=\"ply\"><string name=\"filename\" value=\"{}\"/><bsdf type=\"diffuse\">{}</bsdf></shape>",
            asset("wavy_grid.ply"),
            object(string("name", "vertex_color")).replace("<texture ", "<texture name=\"reflectance\" ")
        ),
        ("texture", _) => {
            let extra = match plugin {
                "bitmap" => string("filename", &asset("checker.png")),
                "rawconstant" => req("value", "<float name=\"value\" value=\"0.5\"/>".into()),
                "volume" => "<volume type=\"constvolume\" name=\"volume\"/>".into(),
                _ => String::new(),
            };
            format!(
                "<shape type=\"rectangle\"><bsdf type=\"diffuse\">{}</bsdf></shape>",
                object(extra).replace("<texture ", "<texture name=\"reflectance\" ")
            )
        }
        // A volume is rendered as the volume of a surface's volume texture.
        ("volume", _) => format!(
            "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><texture type=\"volume\" name=\"reflectance\">{}</texture></bsdf></shape>",
            object(if plugin == "gridvolume" { string("filename", &asset("rgb_grid.vol")) } else { String::new() })
                .replace("<volume ", "<volume name=\"volume\" ")
        ),
        ("emitter", "area") => format!("<shape type=\"rectangle\">{}</shape>", object(String::new())),
        ("emitter", "envmap") => object(string("filename", &asset("sky.png"))),
        ("emitter", "projector") => object(bitmap("irradiance", "sky.png")),
        ("emitter", _) => object(String::new()),
        ("shape", "obj") => object(string("filename", &asset("icosahedron.obj"))),
        ("shape", "ply") => object(string("filename", &asset("prism.ply"))),
        ("shape", "serialized") => object(string("filename", &asset("shapes.serialized"))),
        ("shape", "shapegroup") => object("<shape type=\"sphere\"/>".into()),
        ("shape", "instance") => format!(
            "<shape type=\"shapegroup\" id=\"group\"><shape type=\"sphere\"/></shape>\n{}",
            object("<ref id=\"group\"/>".into())
        ),
        ("shape", _) => object(String::new()),
        ("integrator", "moment") => object("<integrator type=\"path\"/>".into()),
        // matte's ptracer needs the box filter.
        ("integrator", "ptracer") => {
            return format!(
                "<scene version=\"3.0.0\">\n{}\n{}\n</scene>",
                sensor(&film("<rfilter type=\"box\"/>")),
                object(String::new())
            );
        }
        ("integrator", _) => object(String::new()),
        ("sensor", _) => {
            let aperture = match plugin {
                "thinlens" => req("aperture_radius", "<float name=\"aperture_radius\" value=\"0.1\"/>".into()),
                _ => String::new(),
            };
            return format!("<scene version=\"3.0.0\">\n{}\n</scene>", object(format!("{aperture}{}", film(""))));
        }
        ("film", _) => return format!("<scene version=\"3.0.0\">\n{}\n</scene>", sensor(&object(String::new()))),
        ("rfilter", _) => {
            return format!("<scene version=\"3.0.0\">\n{}\n</scene>", sensor(&film(&object(String::new()))));
        }
        ("sampler", _) => return format!("<scene version=\"3.0.0\">\n{}\n</scene>", sensor(&object(String::new()))),
        _ => panic!("no template for <{tag} type=\"{plugin}\">"),
    };
    format!("<scene version=\"3.0.0\">\n{SENSOR}\n{body}\n</scene>")
}

/// A valid value, as XML, for property `p` of `plugin`: the plugin's own default where Mitsuba
/// has a literal one, else a value of the property's kind that the plugin accepts.
fn valid_property_xml(tag: &str, plugin: &str, p: &matte_render::load::mitsuba_plugins::PluginProperty) -> String {
    use matte_render::load::mitsuba_plugins::Kind;
    let n = p.name;
    // Properties whose valid values the kind alone does not give.
    let special: Option<String> = match (tag, plugin, n) {
        (_, _, "filename") => Some(match (tag, plugin) {
            ("shape", "ply") => asset("prism.ply"),
            ("shape", "obj") => asset("icosahedron.obj"),
            ("shape", "serialized") => asset("shapes.serialized"),
            ("emitter", "envmap") | ("texture", "bitmap") => asset("sky.png"),
            ("volume", "gridvolume") => asset("rgb_grid.vol"),
            _ => asset("checker.png"),
        }),
        (_, _, "fov") => Some("45".into()),
        (_, _, "distribution") => Some("beckmann".into()),
        ("texture", "mesh_attribute", "name") => Some("vertex_color".into()),
        ("emitter", "spot", "texture") => {
            return format!(
                "<texture type=\"bitmap\" name=\"texture\"><string name=\"filename\" value=\"{}\"/></texture>",
                asset("checker.png")
            );
        }
        (_, _, "focal_length") => Some("35mm".into()),
        ("shape", "cylinder", "p1") => None,
        _ => None,
    };
    if let Some(v) = special {
        let xml_tag = if n == "fov" { "float" } else { "string" };
        return format!("<{xml_tag} name=\"{n}\" value=\"{v}\"/>");
    }
    let literal = p.literal;
    match p.kind {
        Kind::Float => format!("<float name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("0.5")),
        Kind::Integer => format!("<integer name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("1")),
        Kind::Boolean => format!("<boolean name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("false")),
        Kind::String => format!("<string name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("")),
        Kind::Transform => format!("<transform name=\"{n}\"><translate x=\"0.25\"/></transform>"),
        Kind::Point | Kind::Vector => {
            if plugin == "cylinder" && n == "p1" {
                format!("<point name=\"{n}\" x=\"0\" y=\"0\" z=\"2\"/>")
            } else {
                format!("<point name=\"{n}\" x=\"0\" y=\"0\" z=\"{}\"/>", if n == "direction" { -1 } else { 0 })
            }
        }
        Kind::Color => format!("<rgb name=\"{n}\" value=\"0.5\"/>"),
        Kind::Texture | Kind::EmissiveTexture | Kind::UnboundedTexture | Kind::Volume => {
            format!("<float name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("0.5"))
        }
        Kind::Any => match literal {
            Some(v) if v.parse::<f64>().is_err() && v != "true" && v != "false" => {
                format!("<string name=\"{n}\" value=\"{v}\"/>")
            }
            Some("true" | "false") => format!("<boolean name=\"{n}\" value=\"{}\"/>", literal.unwrap()),
            _ => format!("<float name=\"{n}\" value=\"{}\"/>", literal.unwrap_or("0.5")),
        },
        Kind::Object => unreachable!("objects are skipped"),
    }
}

/// Issue "real scenes": every property that Mitsuba 3.9.1's implementation of a plugin matte
/// renders reads (harvested from its sources by `validation/generators/harvest_mitsuba_properties.py`)
/// is accepted by matte, each alone in a scene that otherwise loads: implemented by the
/// plugin's builder, or accepted without effect where it cannot change the image
/// (`load/no_effect.rs`). A property Mitsuba does not read stays an error.
#[test]
fn every_harvested_property_of_every_supported_plugin_is_accepted() {
    use matte_render::load::no_effect::MITSUBA_REFUSES;
    use matte_render::load::{MITSUBA_PLUGINS, mitsuba_plugins};
    // MATTE_DUMP_WALK=dir writes every scene of the walk there, for
    // validation/check_harvest.py to load in Mitsuba (the same scenes, Mitsuba's verdict).
    let dump = std::env::var_os("MATTE_DUMP_WALK").map(PathBuf::from);
    if let Some(dir) = &dump {
        std::fs::create_dir_all(dir).unwrap();
    }
    let mut checked = 0;
    let mut failures = Vec::new();
    for &(tag, plugins) in MITSUBA_PLUGINS {
        for &plugin in plugins {
            let h = mitsuba_plugins::plugin(tag, plugin)
                .unwrap_or_else(|| panic!("<{tag} type=\"{plugin}\"> is not in the harvested list"));
            // The bare plugin loads, and a property Mitsuba does not read is refused.
            let bare = scene_with_plugin(tag, plugin, "", &[]);
            if let Err(e) = load(&bare) {
                failures.push(format!("<{tag} type=\"{plugin}\"> alone: {e}"));
                continue;
            }
            let made_up = scene_with_plugin(tag, plugin, "<float name=\"not_a_mitsuba_property\" value=\"1\"/>", &[]);
            match load(&made_up) {
                Err(e) if e.to_string().contains("unreferenced property \"not_a_mitsuba_property\"") => {}
                other => failures.push(format!("<{tag} type=\"{plugin}\">: a made-up property gave {:?}", other.err())),
            }
            for p in h.properties {
                // Python-only objects (a `Bitmap`, a tensor): no XML element can give them.
                if p.kind == mitsuba_plugins::Kind::Object {
                    continue;
                }
                // Properties Mitsuba reads only together with another (its checks or its
                // branches): both are given.
                let partner = match p.name {
                    "alpha_u" => Some("alpha_v"),
                    "alpha_v" => Some("alpha_u"),
                    "fov_axis" => Some("fov"),
                    _ => None,
                };
                let mut xml_props = valid_property_xml(tag, plugin, p);
                let mut given = vec![p.name];
                if let Some(q) = partner.and_then(|q| h.properties.iter().find(|x| x.name == q)) {
                    xml_props += &valid_property_xml(tag, plugin, q);
                    given.push(q.name);
                }
                let xml = scene_with_plugin(tag, plugin, &xml_props, &given);
                checked += 1;
                if let Some(dir) = &dump {
                    let file = dir.join(format!("{tag}-{plugin}-{}.xml", p.name));
                    std::fs::write(&file, &xml).unwrap();
                }
                // Mitsuba reads some only to refuse them (e.g. `srf` in RGB variants): matte
                // must refuse them with Mitsuba's reason.
                let refused = MITSUBA_REFUSES.iter().find(|r| {
                    r.tag == tag && r.plugins.iter().any(|x| *x == "*" || *x == plugin) && r.names.contains(&p.name)
                });
                match (load(&xml), refused) {
                    (Ok(_), None) => {}
                    (Err(e), Some(r)) if e.to_string().contains(r.why) => {}
                    (Ok(_), Some(r)) => failures.push(format!(
                        "<{tag} type=\"{plugin}\"> {}: loads, but Mitsuba refuses it: {}",
                        p.name, r.why
                    )),
                    (Err(e), _) => {
                        failures.push(format!("<{tag} type=\"{plugin}\"> {} ({:?}, {}): {e}", p.name, p.kind, p.source))
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{} of {checked} properties refused:\n{}", failures.len(), failures.join("\n"));
    assert!(checked > 150, "only {checked} properties checked");
}

/// The README's scope table ("Scope: what `matte render` reads") says what the loader does:
/// each supported plugin (`MITSUBA_PLUGINS`) is in its row's "supported" cell and every name
/// there loads; each no-effect property (`NO_EFFECT`) is in the "accepted" cell; each plugin
/// refused for scope (`scope::refused_plugins`) and each property Mitsuba refuses
/// (`MITSUBA_REFUSES`) is in the "refused" cell, and every plugin named there fails to load.
#[test]
fn readme_scope_table_matches_the_loader() {
    use matte_render::load::no_effect::{MITSUBA_REFUSES, NO_EFFECT};
    use matte_render::load::{MITSUBA_PLUGINS, mitsuba_plugins, scope};
    let readme = std::fs::read_to_string(crate::common::repo().join("README.md")).unwrap();
    let start = readme.find("### Scope: what `matte render` reads").expect("scope section");
    let rows: Vec<Vec<String>> = readme[start..]
        .lines()
        .skip_while(|l| !l.starts_with("| element"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| l.trim().trim_matches('|').split('|').map(|c| c.trim().to_string()).collect())
        .collect();
    assert!(rows.len() >= 10, "scope table not found");
    let row_of = |tag: &str| -> &Vec<String> {
        let label = match tag {
            "film" | "rfilter" => "film, rfilter",
            "medium" | "phase" => "medium, phase",
            t => t,
        };
        rows.iter().find(|r| r[0] == label).unwrap_or_else(|| panic!("no row for {tag}"))
    };
    let names = |cell: &str| -> Vec<String> { cell.split('`').skip(1).step_by(2).map(str::to_string).collect() };
    let in_cell = |cell: &str, name: &str| {
        names(cell).iter().any(|n| n == name || (n.ends_with('*') && name.starts_with(n.trim_end_matches('*'))))
    };
    for &(tag, plugins) in MITSUBA_PLUGINS {
        for &p in plugins.iter().filter(|_| tag != "scene") {
            assert!(in_cell(&row_of(tag)[1], p), "README scope: {tag} {p} not listed as supported");
        }
    }
    for e in NO_EFFECT {
        for n in e.names {
            assert!(in_cell(&row_of(e.tag)[2], n), "README scope: {} property {n} not listed as accepted", e.tag);
        }
    }
    for (tag, p, _) in scope::refused_plugins() {
        assert!(in_cell(&row_of(tag)[3], p) || row_of(tag)[3].contains("every plugin"), "README scope: {tag} {p}");
    }
    for e in MITSUBA_REFUSES {
        for n in e.names {
            assert!(in_cell(&row_of(e.tag)[3], n), "README scope: {} property {n} not listed as refused", e.tag);
        }
    }
    // What the table says, the loader does.
    for row in rows.iter().filter(|r| r[0] != "document" && r[0] != "scene" && !r[0].contains("medium")) {
        let tags: Vec<&str> = if row[0] == "film, rfilter" { vec!["film", "rfilter"] } else { vec![row[0].as_str()] };
        for name in names(&row[1]) {
            if name == "tabulated_brdf" {
                continue; // needs a table file: loaded in tests/render/matte_bsdf.rs
            }
            let tag = tags.iter().copied().find(|t| mitsuba_plugins::plugin(t, &name).is_some()).unwrap_or(tags[0]);
            if let Err(e) = load(&scene_with_plugin(tag, &name, "", &[])) {
                panic!("README scope says <{tag} type=\"{name}\"> is supported, but: {e}");
            }
        }
        for name in names(&row[3]) {
            let Some(tag) = tags.iter().copied().find(|t| mitsuba_plugins::plugin(t, &name).is_some()) else {
                continue; // a property (checked against MITSUBA_REFUSES above)
            };
            let xml = scene(&format!("{SENSOR}\n<{tag} type=\"{name}\"/>"));
            assert!(load(&xml).is_err(), "README scope says <{tag} type=\"{name}\"> is refused, but it loads");
        }
    }
}
