//! The Mitsuba XML parser layer (`matte_scene_file::xml`) against `docs/renderer-semantics.md`
//! §1–3 ("doc §N" below) and, where the doc is silent, against values printed by
//! Mitsuba 3.9.1 `scalar_rgb` itself (its `mi.parser.parse_string` and `mi.traverse` outputs,
//! quoted where used). Every error test checks that the message names the file and the line.
//! The transform and colour numbers are checked by tests/scene_file/xml/generate_reference.py.

use std::path::{Path, PathBuf};
use std::rc::Rc;

use glam::{DMat4, DVec3, DVec4};
use matte_scene_file::xml::{ColorUse, SceneObject, Spectrum, Value, parse_file, parse_str};
use matte_scene_file::{SceneError, SourcePos};

const FILE: &str = "/virtual/dir/scene.xml";

fn parse(xml: &str) -> Result<Rc<SceneObject>, SceneError> {
    parse_str(xml, Path::new(FILE), &[])
}

fn parse_kw(xml: &str, kw: &[(&str, &str)]) -> Result<Rc<SceneObject>, SceneError> {
    let kw: Vec<(String, String)> = kw.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
    parse_str(xml, Path::new(FILE), &kw)
}

fn ok(xml: &str) -> Rc<SceneObject> {
    parse(xml).unwrap_or_else(|e| panic!("unexpected error: {e}"))
}

/// `<scene version="3.0.0">` on line 1, then `body` from line 2 on.
fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

/// The error names `file` and `line` (in its position and in its Display) and says `needle`.
fn assert_err_in(e: &SceneError, file: &Path, line: u32, needle: &str) {
    let pos = e.pos.as_ref().unwrap_or_else(|| panic!("error without position: {e}"));
    assert_eq!(pos.file.as_path(), file, "{e}");
    assert_eq!(pos.line, line, "{e}");
    assert!(e.to_string().starts_with(&format!("{}:{line}:", file.display())), "{e}");
    assert!(e.message.contains(needle), "expected {needle:?} in: {e}");
}

fn assert_err(r: Result<Rc<SceneObject>, SceneError>, line: u32, needle: &str) {
    match r {
        Ok(_) => panic!("expected an error containing {needle:?}"),
        Err(e) => assert_err_in(&e, Path::new(FILE), line, needle),
    }
}

fn first(s: &SceneObject) -> Rc<SceneObject> {
    s.children[0].object.clone()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

fn assert_rgb(got: [f64; 3], want: [f64; 3], tol: f64) {
    assert!((0..3).all(|i| close(got[i], want[i], tol)), "got {got:?}, want {want:?}");
}

fn assert_mat(got: DMat4, rows: [[f64; 4]; 4], tol: f64) {
    let want = DMat4::from_cols_array_2d(&rows).transpose();
    assert!(got.abs_diff_eq(want, tol), "got rows {:?}\nwant rows {rows:?}", got.transpose().to_cols_array_2d());
}

/// A fresh folder for tests that need files.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("matte_scene_xml_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

// ------------------------------------------------------------------------------------------
// Objects and properties

#[test]
fn object_tree_has_tags_plugins_ids_names_and_positions() {
    let s = ok(&scene(
        "  <shape type=\"sphere\" id=\"ball\">\n    <bsdf type=\"diffuse\" name=\"surface\"/>\n  </shape>\n  <integrator type=\"path\"/>",
    ));
    assert_eq!((s.tag.as_str(), s.plugin.as_str(), s.id.as_deref()), ("scene", "", None));
    assert_eq!((s.pos.line, s.pos.col), (1, 1));
    assert_eq!(s.children.len(), 2);
    let shape = first(&s);
    assert_eq!((shape.tag.as_str(), shape.plugin.as_str(), shape.id.as_deref()), ("shape", "sphere", Some("ball")));
    assert_eq!((shape.pos.line, shape.pos.col), (2, 3));
    assert_eq!(s.children[0].name, None);
    let b = &shape.children[0];
    assert_eq!(b.name.as_deref(), Some("surface"));
    assert_eq!((b.object.tag.as_str(), b.object.plugin.as_str()), ("bsdf", "diffuse"));
    assert_eq!((b.pos.line, b.pos.col), (3, 5));
    assert_eq!(s.children[1].object.tag, "integrator");
    for tag in ["sensor", "film", "rfilter", "sampler", "emitter", "texture", "medium", "phase", "volume"] {
        let s = ok(&scene(&format!("<{tag} type=\"x\"/>")));
        assert_eq!(first(&s).tag, tag);
    }
    // <spectrum type=...> is a texture object, not a property (Mitsuba's parse_xml_node).
    let s = ok(&scene("<bsdf type=\"diffuse\"><spectrum type=\"d65\" name=\"reflectance\"/></bsdf>"));
    let t = &first(&s).children[0];
    assert_eq!(
        (t.object.tag.as_str(), t.object.plugin.as_str(), t.name.as_deref()),
        ("texture", "d65", Some("reflectance"))
    );
}

#[test]
fn every_property_type_parses() {
    let s = ok(&scene(
        r#"<bsdf type="test">
  <integer name="i" value=" -42 "/>
  <float name="f" value="+1.5e-1"/>
  <float name="g" value=" .5 "/>
  <boolean name="b1" value="True"/>
  <boolean name="b2" value="FALSE"/>
  <string name="s" value=" keep  as is "/>
  <rgb name="c1" value="0.5"/>
  <rgb name="c3" value="0.1,0.2 , 0.3"/>
  <spectrum name="sc" value="2"/>
  <spectrum name="ss" value="400:0.2, 500:0.8 600:0.4"/>
  <point name="p1" value="1"/>
  <point name="p3" x="1" y="2" z="3"/>
  <vector name="v" value="4, 5, 6"/>
  <transform name="t"><translate x="1" y="2" z="3"/></transform>
</bsdf>"#,
    ));
    let b = first(&s);
    let p = &b.properties;
    assert_eq!(p.len(), 14);
    assert_eq!(p.integer("i").unwrap(), Some(-42));
    assert_eq!(p.float("f").unwrap(), Some(0.15));
    assert_eq!(p.float("g").unwrap(), Some(0.5));
    assert_eq!(p.boolean("b1").unwrap(), Some(true));
    assert_eq!(p.boolean("b2").unwrap(), Some(false));
    assert_eq!(p.string("s").unwrap().as_deref(), Some(" keep  as is "));
    assert_eq!(p.get("c1").unwrap().value, Value::Rgb([0.5; 3]));
    assert_eq!(p.get("c3").unwrap().value, Value::Rgb([0.1, 0.2, 0.3]));
    assert_eq!(p.get("sc").unwrap().value, Value::Spectrum(Spectrum::Constant(2.0)));
    assert_eq!(
        p.get("ss").unwrap().value,
        Value::Spectrum(Spectrum::Sampled(vec![(400.0, 0.2), (500.0, 0.8), (600.0, 0.4)]))
    );
    assert_eq!(p.get("p1").unwrap().value, Value::Point(DVec3::ONE));
    assert_eq!(p.point("p3").unwrap(), Some(DVec3::new(1.0, 2.0, 3.0)));
    assert_eq!(p.get("v").unwrap().value, Value::Vector(DVec3::new(4.0, 5.0, 6.0)));
    assert_eq!(p.transform("t").unwrap(), Some(DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0))));
    assert_eq!(p.get("i").unwrap().pos.line, 3);
    let names: Vec<&str> = p.iter().map(|q| q.name.as_str()).collect();
    assert_eq!(names, ["i", "f", "g", "b1", "b2", "s", "c1", "c3", "sc", "ss", "p1", "p3", "v", "t"]);
    b.check_all_used().unwrap();
}

#[test]
fn getters_convert_like_mitsuba() {
    let s = ok(&scene(
        "<bsdf type=\"t\">\n<integer name=\"n\" value=\"3\"/>\n<float name=\"x\" value=\"0.5\"/>\n<point name=\"p\" value=\"1 2 3\"/>\n<vector name=\"v\" value=\"4 5 6\"/>\n</bsdf>",
    ));
    let p = &first(&s).properties;
    // integer → float is fine, float → integer is not (doc §1 "integer" [verified]).
    assert_eq!(p.float("n").unwrap(), Some(3.0));
    let e = p.integer("x").unwrap_err();
    assert_err_in(&e, Path::new(FILE), 4, "\"x\" has the wrong type (expected integer, found float)");
    // Mitsuba 3 has a single 3-vector type for <point> and <vector>.
    assert_eq!(p.vector("p").unwrap(), Some(DVec3::new(1.0, 2.0, 3.0)));
    assert_eq!(p.point("v").unwrap(), Some(DVec3::new(4.0, 5.0, 6.0)));
    // Missing → None.
    assert_eq!(p.float("missing").unwrap(), None);
    assert_eq!(p.color("missing", ColorUse::Bounded).unwrap(), None);
    // Other wrong types, each naming the line of the property.
    assert_err_in(&p.boolean("n").unwrap_err(), Path::new(FILE), 3, "expected boolean, found integer");
    assert_err_in(&p.string("x").unwrap_err(), Path::new(FILE), 4, "expected string, found float");
    assert_err_in(&p.transform("p").unwrap_err(), Path::new(FILE), 5, "expected transform, found point");
    assert_err_in(&p.point("x").unwrap_err(), Path::new(FILE), 4, "expected point, found float");
    assert_err_in(&p.float("v").unwrap_err(), Path::new(FILE), 6, "expected float, found vector");
    assert_err_in(&p.color("p", ColorUse::Emissive).unwrap_err(), Path::new(FILE), 5, "found point");
}

#[test]
fn unqueried_property_is_reported_like_mitsuba() {
    let s = ok(&scene(
        "<bsdf type=\"diffuse\">\n  <rgb name=\"reflectance\" value=\"0.5\"/>\n  <float name=\"roughness\" value=\"0.3\"/>\n</bsdf>",
    ));
    let b = first(&s);
    // contains() does not count as a query.
    assert!(b.properties.contains("roughness"));
    assert!(!b.properties.contains("alpha"));
    b.properties.color("reflectance", ColorUse::Bounded).unwrap();
    let e = b.check_all_used().unwrap_err();
    assert_eq!(
        e.to_string(),
        format!("{FILE}:4:3: unreferenced property \"roughness\" (float) in bsdf plugin of type \"diffuse\"")
    );
    let e = b.properties.check_all_used("bsdf", "diffuse").unwrap_err();
    assert_err_in(&e, Path::new(FILE), 4, "unreferenced property \"roughness\"");
    assert!(b.properties.get("roughness").is_some());
    b.check_all_used().unwrap();
}

#[test]
fn children_lookup_and_unused_child_error() {
    let s = ok(&scene(
        "<emitter type=\"point\">\n  <bsdf type=\"diffuse\"/>\n</emitter>\n<shape type=\"sphere\">\n  <bsdf type=\"diffuse\" name=\"b\"/>\n  <emitter type=\"area\"/>\n</shape>",
    ));
    let em = &s.children[0].object;
    let e = em.check_all_used().unwrap_err();
    assert_err_in(
        &e,
        Path::new(FILE),
        3,
        "unexpected nested bsdf of type \"diffuse\" in emitter plugin of type \"point\"",
    );

    let shape = &s.children[1].object;
    assert!(shape.child("nope").is_none());
    assert_eq!(shape.child("b").unwrap().object.plugin, "diffuse");
    let e = shape.check_all_used().unwrap_err();
    assert_err_in(
        &e,
        Path::new(FILE),
        7,
        "unexpected nested emitter of type \"area\" in shape plugin of type \"sphere\"",
    );
    let ems: Vec<&str> = shape.children_with_tag("emitter").map(|c| c.object.plugin.as_str()).collect();
    assert_eq!(ems, ["area"]);
    shape.check_all_used().unwrap();

    // The whole-tree check finds the unused child of the first emitter.
    for c in &s.children {
        c.mark_used();
    }
    assert_err_in(&s.check_tree_used().unwrap_err(), Path::new(FILE), 3, "unexpected nested bsdf");
    em.children[0].mark_used();
    // ... and then the unqueried properties of nothing: all clean.
    s.check_tree_used().unwrap();
}

#[test]
fn tree_check_reports_unqueried_property_deep_down() {
    let s = ok(&scene(
        "<shape type=\"sphere\">\n<bsdf type=\"diffuse\">\n<float name=\"alpha\" value=\"1\"/>\n</bsdf>\n</shape>",
    ));
    s.children[0].mark_used();
    s.children[0].object.children[0].mark_used();
    assert_err_in(
        &s.check_tree_used().unwrap_err(),
        Path::new(FILE),
        4,
        "unreferenced property \"alpha\" (float) in bsdf",
    );
}

// ------------------------------------------------------------------------------------------
// Parameters: $name, <default>, overrides

#[test]
fn substitution_is_plain_text_longest_key_first() {
    // Doc §1 [verified]: with only r=0.2, "$r5" becomes "0.25"; $rr is replaced before $r.
    let xml = scene("<bsdf type=\"t\"><float name=\"a\" value=\"$r5\"/><float name=\"b\" value=\"$rr\"/></bsdf>");
    let s = parse_kw(&xml, &[("r", "0.2"), ("rr", "0.75")]).unwrap();
    let p = &first(&s).properties;
    assert_eq!(p.float("a").unwrap(), Some(0.25));
    assert_eq!(p.float("b").unwrap(), Some(0.75));
}

#[test]
fn substitution_applies_to_every_attribute_and_escapes() {
    let xml = scene(
        "<bsdf type=\"$plugin\" id=\"o_$n\"><string name=\"$n\" value=\"cost \\$5 for $n\"/><float name=\"x\" value=\"$v$v\"/></bsdf>",
    );
    let s = parse_kw(&xml, &[("plugin", "diffuse"), ("n", "k"), ("v", "1")]).unwrap();
    let b = first(&s);
    assert_eq!(b.plugin, "diffuse");
    assert_eq!(b.id.as_deref(), Some("o_k"));
    assert_eq!(b.properties.string("k").unwrap().as_deref(), Some("cost $5 for k"));
    assert_eq!(b.properties.float("x").unwrap(), Some(11.0));
}

#[test]
fn defaults_first_wins_and_overrides_beat_them() {
    let xml = scene(
        "<default name=\"a\" value=\"1\"/>\n<default name=\"a\" value=\"2\"/>\n<default name=\"b\" value=\"3\"/>\n<default name=\"c\" value=\"$a$b\"/>\n<bsdf type=\"t\"><float name=\"a\" value=\"$a\"/><float name=\"b\" value=\"$b\"/><float name=\"c\" value=\"$c\"/></bsdf>",
    );
    let s = parse(&xml).unwrap();
    let p = &first(&s).properties;
    assert_eq!(
        (p.float("a").unwrap(), p.float("b").unwrap(), p.float("c").unwrap()),
        (Some(1.0), Some(3.0), Some(13.0))
    );
    // An override beats every default; unused defaults are never an error.
    let s = parse_kw(&xml, &[("b", "7")]).unwrap();
    let p = &first(&s).properties;
    assert_eq!(
        (p.float("a").unwrap(), p.float("b").unwrap(), p.float("c").unwrap()),
        (Some(1.0), Some(7.0), Some(17.0))
    );
    parse(&scene("<default name=\"unused\" value=\"1\"/>")).unwrap();
}

#[test]
fn parameter_errors() {
    // Used before its <default> (doc §1 [verified]).
    assert_err(
        parse(&scene(
            "<bsdf type=\"t\">\n<float name=\"a\" value=\"$x\"/>\n</bsdf>\n<default name=\"x\" value=\"1\"/>",
        )),
        3,
        "undefined parameter $x",
    );
    // Never defined, in any attribute.
    assert_err(parse(&scene("\n<bsdf type=\"$kind\"/>")), 3, "undefined parameter $kind");
    // The escape protects only the escaped dollar.
    assert_err(parse(&scene("<string name=\"s\" value=\"\\$a $b\"/>")), 2, "undefined parameter $b");
    // An override nothing uses (doc §1: "Found unused parameters: $foo=3").
    match parse_kw(&scene(""), &[("foo", "3")]) {
        Err(e) => {
            assert_eq!(e.pos.as_ref().unwrap().file.as_path(), Path::new(FILE));
            assert!(e.to_string().starts_with(FILE), "{e}");
            assert_eq!(e.message, "unused parameter $foo=3");
        }
        Ok(_) => panic!("unused override accepted"),
    }
    // An empty <default> name.
    assert_err(parse(&scene("\n<default name=\"\" value=\"1\"/>")), 3, "name must be non-empty");
    assert_err(parse(&scene("<default name=\"a\"/>")), 2, "missing required attribute \"value\" in <default>");
}

// ------------------------------------------------------------------------------------------
// <include>

#[test]
fn include_splices_children_resolves_relative_paths_and_shares_parameters() {
    let dir = temp_dir("include");
    std::fs::create_dir_all(dir.join("sub/deeper")).unwrap();
    // The include's own include is relative to sub/, not to the main file.
    std::fs::write(
        dir.join("sub/a.xml"),
        "<scene version=\"3.0.0\">\n  <default name=\"d\" value=\"0.7\"/>\n  <bsdf type=\"diffuse\" id=\"inner\"><float name=\"reflectance\" value=\"$r\"/></bsdf>\n  <include filename=\"deeper/b.xml\"/>\n</scene>",
    )
    .unwrap();
    std::fs::write(dir.join("sub/deeper/b.xml"), "<scene version=\"3.0.0\"><integrator type=\"path\"/></scene>")
        .unwrap();
    std::fs::write(
        dir.join("sub/c.xml"),
        "<bsdf version=\"3.0.0\" type=\"diffuse\" id=\"cc\"><float name=\"reflectance\" value=\"$d\"/></bsdf>",
    )
    .unwrap();
    let main = dir.join("main.xml");
    std::fs::write(
        &main,
        "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"/>\n  <include filename=\"sub/a.xml\"/>\n  <shape type=\"sphere\"><include filename=\"sub/c.xml\" name=\"thebsdf\"/></shape>\n  <shape type=\"sphere\"><ref id=\"inner\"/></shape>\n</scene>",
    )
    .unwrap();
    // r is used only inside the include: it counts as used. d is a default made inside the
    // include and visible afterwards in the main file's next include.
    let kw = [("r".to_string(), "0.3".to_string())];
    let s = parse_file(&main, &kw).unwrap();
    let tags: Vec<(&str, &str)> =
        s.children.iter().map(|c| (c.object.tag.as_str(), c.object.plugin.as_str())).collect();
    assert_eq!(
        tags,
        [
            ("sensor", "perspective"),
            ("bsdf", "diffuse"),
            ("integrator", "path"),
            ("shape", "sphere"),
            ("shape", "sphere")
        ]
    );
    let inner = &s.children[1].object;
    assert_eq!(inner.properties.float("reflectance").unwrap(), Some(0.3));
    assert_eq!(inner.pos.file.as_path(), dir.join("sub/a.xml"));
    assert_eq!(inner.pos.line, 3);
    assert_eq!(s.children[2].object.pos.file.as_path(), dir.join("sub/deeper/b.xml"));
    let c = s.children[3].object.child("thebsdf").unwrap();
    assert_eq!(c.object.id.as_deref(), Some("cc"));
    assert_eq!(c.object.properties.float("reflectance").unwrap(), Some(0.7));
    assert!(Rc::ptr_eq(&s.children[4].object.children[0].object, inner));
}

#[test]
fn include_errors_name_the_right_file_and_line() {
    let dir = temp_dir("include_errors");
    let main = dir.join("main.xml");
    // Missing file.
    std::fs::write(&main, "<scene version=\"3.0.0\">\n\n  <include filename=\"nope.xml\"/>\n</scene>").unwrap();
    assert_err_in(&parse_file(&main, &[]).unwrap_err(), &main, 3, "cannot read included file");
    // An error inside the included file names that file and line (and where it was included).
    let bad = dir.join("bad.xml");
    std::fs::write(
        &bad,
        "<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n<float name=\"x\" value=\"abc\"/>\n</bsdf>\n</scene>",
    )
    .unwrap();
    std::fs::write(&main, "<scene version=\"3.0.0\">\n  <include filename=\"bad.xml\"/>\n</scene>").unwrap();
    let e = parse_file(&main, &[]).unwrap_err();
    assert_err_in(&e, &bad, 3, "could not parse float value \"abc\"");
    assert!(e.message.contains(&format!("included at {}:2:3", main.display())), "{e}");
    // Self-inclusion stops at the maximum depth of 15.
    let me = dir.join("self.xml");
    std::fs::write(&me, "<scene version=\"3.0.0\">\n<include filename=\"self.xml\"/>\n</scene>").unwrap();
    assert_err_in(&parse_file(&me, &[]).unwrap_err(), &me, 2, "maximum include depth of 15");
    // Depth 14 is fine: a chain main → f1 → ... → f14.
    for k in 1..=14 {
        let next = if k < 14 {
            format!("<include filename=\"f{}.xml\"/>", k + 1)
        } else {
            "<integrator type=\"path\"/>".into()
        };
        std::fs::write(dir.join(format!("f{k}.xml")), format!("<scene version=\"3.0.0\">{next}</scene>")).unwrap();
    }
    std::fs::write(&main, "<scene version=\"3.0.0\"><include filename=\"f1.xml\"/></scene>").unwrap();
    assert_eq!(first(&parse_file(&main, &[]).unwrap()).plugin, "path");
    // A property directly inside an included <scene> is dropped by Mitsuba: refused here.
    std::fs::write(&bad, "<scene version=\"3.0.0\">\n<float name=\"x\" value=\"1\"/>\n</scene>").unwrap();
    std::fs::write(&main, "<scene version=\"3.0.0\"><bsdf type=\"t\"><include filename=\"bad.xml\"/></bsdf></scene>")
        .unwrap();
    assert_err_in(&parse_file(&main, &[]).unwrap_err(), &bad, 2, "directly inside an included <scene>");
    // The included root needs a version, and must be a scene or an object.
    std::fs::write(&bad, "<bsdf type=\"diffuse\"/>").unwrap();
    assert_err_in(&parse_file(&main, &[]).unwrap_err(), &bad, 1, "missing version attribute");
    std::fs::write(&bad, "<float version=\"3.0.0\" name=\"a\" value=\"1\"/>").unwrap();
    assert_err_in(&parse_file(&main, &[]).unwrap_err(), &bad, 1, "must be <scene> or an object");
    // Missing main file.
    let e = parse_file(&dir.join("absent.xml"), &[]).unwrap_err();
    assert_eq!(e.pos.as_ref().unwrap().file.as_path(), dir.join("absent.xml"));
    assert!(e.message.contains("cannot read scene file"), "{e}");
}

#[test]
fn parse_str_resolves_includes_against_the_given_path() {
    let dir = temp_dir("parse_str_include");
    std::fs::write(dir.join("inc.xml"), "<scene version=\"3.0.0\"><sampler type=\"independent\"/></scene>").unwrap();
    let s = parse_str(&scene("<include filename=\"inc.xml\"/>"), &dir.join("virtual.xml"), &[]).unwrap();
    assert_eq!(first(&s).plugin, "independent");
}

// ------------------------------------------------------------------------------------------
// <ref>, ids, <alias>

/// `<spectrum filename>` (`Properties::Spectrum(const fs::path &)`, `src/core/properties.cpp`):
/// `λ value` per line, `#` lines and empty lines skipped, resolved through the file resolver
/// (here: the scene's folder); the same samples as given inline.
#[test]
fn spectrum_files_are_read_like_mitsuba() {
    let dir = temp_dir("spectrum_file");
    std::fs::write(dir.join("s.spd"), "# a comment\n400 0.25\n\n500\t0.5 trailing words\r\n600 0.75\n").unwrap();
    std::fs::write(dir.join("one.spd"), "500 0.5\n").unwrap();
    std::fs::write(dir.join("bad.spd"), "400 0.2\n500 x\n").unwrap();
    let file = dir.join("scene.xml");
    let body = |f: &str| {
        scene(&format!("<bsdf type=\"diffuse\">\n<spectrum name=\"reflectance\" filename=\"{f}\"/>\n</bsdf>"))
    };
    std::fs::write(&file, body("s.spd")).unwrap();
    let root = parse_file(&file, &[]).expect("the spectrum file is read");
    let got = first(&root).properties.get("reflectance").map(|p| p.value.clone());
    assert_eq!(got, Some(Value::Spectrum(Spectrum::Sampled(vec![(400.0, 0.25), (500.0, 0.5), (600.0, 0.75)]))));
    for (f, needle) in [("one.spd", "at least two entries"), ("bad.spd", "could not extract value in line 2")] {
        std::fs::write(&file, body(f)).unwrap();
        assert_err_in(&parse_file(&file, &[]).expect_err("an error"), &file, 3, needle);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn forward_references_share_one_object() {
    let s = ok(&scene(
        "<shape type=\"sphere\"><ref id=\"m\" name=\"bsdf\"/></shape>\n<shape type=\"cube\"><ref id=\"m\"/></shape>\n<bsdf type=\"diffuse\" id=\"m\"/>\n<alias id=\"m\" as=\"m2\"/>\n<shape type=\"disk\"><ref id=\"m2\"/></shape>",
    ));
    let a = &s.children[0].object.children[0];
    assert_eq!(a.name.as_deref(), Some("bsdf"));
    assert_eq!(a.pos.line, 2);
    let b = &s.children[1].object.children[0];
    assert_eq!(b.name, None);
    assert!(Rc::ptr_eq(&a.object, &b.object));
    assert!(Rc::ptr_eq(&a.object, &s.children[2].object));
    assert!(Rc::ptr_eq(&a.object, &s.children[3].object.children[0].object));
    assert_eq!(a.object.id.as_deref(), Some("m"));
}

#[test]
fn reference_errors() {
    assert_err(
        parse(&scene("<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>")),
        3,
        &format!("duplicate id \"a\" (first at {FILE}:2:1)"),
    );
    assert_err(
        parse(&scene("<shape type=\"sphere\">\n<ref id=\"nope\"/></shape>")),
        3,
        "unresolved reference to \"nope\"",
    );
    assert_err(parse(&scene("\n<alias id=\"a\" as=\"b\"/>")), 3, "alias source id \"a\" not found");
    assert_err(
        parse(&scene("<bsdf type=\"d\" id=\"a\"/>\n<bsdf type=\"d\" id=\"b\"/>\n<alias id=\"a\" as=\"b\"/>")),
        4,
        "alias destination id \"b\" already exists",
    );
    assert_err(
        parse(&scene(
            "<bsdf type=\"twosided\" id=\"a\"><ref id=\"b\"/></bsdf>\n<bsdf type=\"twosided\" id=\"b\">\n<ref id=\"a\"/></bsdf>",
        )),
        4,
        "circular reference: a -> b -> a",
    );
    assert_err(parse(&scene("<bsdf type=\"t\" id=\"a\"><ref id=\"a\"/></bsdf>")), 2, "circular reference: a -> a");
    assert_err(
        parse(&scene("<shape type=\"sphere\"><ref name=\"x\"/></shape>")),
        2,
        "missing required attribute \"id\" in <ref>",
    );
}

#[test]
fn duplicate_names_in_one_object() {
    let s = scene("<bsdf type=\"diffuse\">\n<float name=\"a\" value=\"1\"/>\n<float name=\"a\" value=\"2\"/>\n</bsdf>");
    assert_err(parse(&s), 4, &format!("\"a\" is specified more than once in <bsdf> (first at {FILE}:3:1)"));
    let s = scene(
        "<bsdf type=\"diffuse\">\n<texture type=\"bitmap\" name=\"reflectance\"/>\n<rgb name=\"reflectance\" value=\"1\"/>\n</bsdf>",
    );
    assert_err(parse(&s), 4, "\"reflectance\" is specified more than once");
    let s = scene("<bsdf type=\"twosided\">\n<bsdf type=\"diffuse\" name=\"a\"/>\n<ref id=\"x\" name=\"a\"/>\n</bsdf>");
    assert_err(parse(&s), 4, "\"a\" is specified more than once");
    // Unnamed children never clash.
    ok(&scene("<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>"));
}

// ------------------------------------------------------------------------------------------
// Transforms (doc §3)

fn to_world(ops: &str) -> DMat4 {
    let s = ok(&scene(&format!("<shape type=\"rectangle\"><transform name=\"to_world\">{ops}</transform></shape>")));
    first(&s).properties.transform("to_world").unwrap().unwrap()
}

#[test]
fn first_listed_operation_is_applied_first() {
    // Doc §3 [verified]: <translate x="1"/><rotate y="1" angle="90"/> sends the origin to (0,0,-1).
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = to_world("<translate x=\"1\"/><rotate y=\"1\" angle=\"90\"/>");
    assert!(m.transform_point3(DVec3::ZERO).abs_diff_eq(DVec3::new(0.0, 0.0, -1.0), 1e-15));
    // The reverse order leaves the rotated origin at the origin, then moves it by +x.
    let m = to_world("<rotate y=\"1\" angle=\"90\"/><translate x=\"1\"/>");
    assert!(m.transform_point3(DVec3::ZERO).abs_diff_eq(DVec3::X, 1e-15));
    // scale then translate: (2·p) + t.
    let m = to_world("<scale value=\"2\"/><translate value=\"1 2 3\"/>");
    assert_mat(m, [[2., 0., 0., 1.], [0., 2., 0., 2.], [0., 0., 2., 3.], [0., 0., 0., 1.]], 0.0);
}

#[test]
fn rotate_is_right_handed_in_degrees_with_an_unnormalized_axis() {
    // x-axis +90° takes +y to +z (doc §3 [verified]).
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = to_world("<rotate x=\"1\" angle=\"90\"/>");
    assert!(m.transform_vector3(DVec3::Y).abs_diff_eq(DVec3::Z, 1e-15));
    // Doc §3 pitfall [verified]: x="2", 90° → diag(4, cos, cos) with off-diagonals ±2.
    let m = to_world("<rotate x=\"2\" angle=\"90\"/>");
    assert_mat(m, [[4., 0., 0., 0.], [0., 0., -2., 0.], [0., 2., 0., 0.], [0., 0., 0., 1.]], 1e-15);
    // Axis (1,1,0), 30°: cosθ·I + (1−cosθ)·a·aᵀ + sinθ·[a]× in closed form.
    let (s, c) = (0.5, 3f64.sqrt() / 2.0);
    let k = 1.0 - c;
    let m = to_world("<rotate value=\"1, 1, 0\" angle=\"30\"/>");
    assert_mat(m, [[c + k, k, s, 0.], [k, c + k, -s, 0.], [-s, s, c, 0.], [0., 0., 0., 1.]], 1e-15);
    // Missing components are 0.
    let m = to_world("<rotate z=\"1\" angle=\"180\"/>");
    assert!(m.transform_vector3(DVec3::X).abs_diff_eq(-DVec3::X, 1e-15));
}

#[test]
fn matrix_is_row_major_and_defaults_fill_in() {
    // Doc §3 [verified]: translation in elements 3, 7, 11.
    let m = to_world("<matrix value=\"1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1\"/>");
    assert_eq!(m.transform_point3(DVec3::ZERO), DVec3::new(5.0, 6.0, 7.0));
    // 9 values fill the upper-left 3×3 (Mitsuba printed [[1,2,3,0],[4,5,6,0],[7,8,9,0],[0,0,0,1]]).
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = to_world("<matrix value=\"1,2,3,4,5,6,7,8,9\"/>");
    assert_mat(m, [[1., 2., 3., 0.], [4., 5., 6., 0.], [7., 8., 9., 0.], [0., 0., 0., 1.]], 0.0);
    // translate defaults to 0, scale to 1, per component.
    assert_eq!(to_world("<translate y=\"2\"/>"), DMat4::from_translation(DVec3::new(0.0, 2.0, 0.0)));
    assert_eq!(to_world("<scale z=\"3\"/>"), DMat4::from_scale(DVec3::new(1.0, 1.0, 3.0)));
    assert_eq!(to_world("<scale value=\"2 3 4\"/>"), DMat4::from_scale(DVec3::new(2.0, 3.0, 4.0)));
    assert_eq!(to_world(""), DMat4::IDENTITY);
}

#[test]
fn lookat_columns_are_left_up_dir_origin() {
    // Camera at (0,0,5) looking at the origin, up +y: dir = −z, left = up × dir = −x, up' = +y.
    let m = to_world("<lookat origin=\"0,0,5\" target=\"0,0,0\" up=\"0,1,0\"/>");
    assert_eq!(m.col(0), DVec4::new(-1.0, 0.0, 0.0, 0.0));
    assert_eq!(m.col(1), DVec4::new(0.0, 1.0, 0.0, 0.0));
    assert_eq!(m.col(2), DVec4::new(0.0, 0.0, -1.0, 0.0));
    assert_eq!(m.col(3), DVec4::new(0.0, 0.0, 5.0, 1.0));
    // A non-orthogonal up is re-orthogonalized: origin (1,2,3) → 0, up +z.
    let m = to_world("<lookat origin=\"1 2 3\" target=\"0 0 0\" up=\"0 0 1\"/>");
    let dir = -DVec3::new(1.0, 2.0, 3.0) / 14f64.sqrt();
    let left = DVec3::Z.cross(dir).normalize();
    assert!(m.col(2).truncate().abs_diff_eq(dir, 1e-15));
    assert!(m.col(0).truncate().abs_diff_eq(left, 1e-15));
    assert!(m.col(1).truncate().abs_diff_eq(dir.cross(left), 1e-15));
    // No up: Mitsuba takes coordinate_system(dir).0. Its parser printed, for these inputs:
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let m = to_world("<lookat origin=\"0,0,0\" target=\"0 0 -1\"/>");
    assert_mat(m, [[0., 1., 0., 0.], [1., 0., 0., 0.], [0., 0., -1., 0.], [0., 0., 0., 1.]], 1e-15);
    let m = to_world("<lookat origin=\"0,0,0\" target=\"0 0 1\" up=\"0 0 0\"/>");
    assert_mat(m, [[0., 1., 0., 0.], [-1., 0., 0., 0.], [0., 0., 1., 0.], [0., 0., 0., 1.]], 1e-15);
    let m = to_world("<lookat origin=\"1,2,3\" target=\"0 0 0\"/>");
    assert_mat(
        m,
        [
            [-0.079286509705, 0.960356745147, -0.267261241912, 1.],
            [0.84142698059, -0.079286509705, -0.534522483825, 2.],
            [-0.534522483825, -0.267261241912, -0.801783725737, 3.],
            [0., 0., 0., 1.],
        ],
        1e-11,
    );
}

#[test]
fn transform_errors() {
    let t = |ops: &str| {
        scene(&format!("<shape type=\"sphere\">\n<transform name=\"to_world\">\n{ops}\n</transform>\n</shape>"))
    };
    assert_err(parse(&t("<rotate angle=\"30\"/>")), 4, "rotation axis cannot be zero");
    assert_err(parse(&t("<rotate x=\"1\"/>")), 4, "missing required attribute \"angle\" in <rotate>");
    assert_err(parse(&t("<rotate x=\"1\" angle=\"ninety\"/>")), 4, "could not parse angle \"ninety\"");
    assert_err(
        parse(&t("<matrix value=\"1 2 3 4 5 6 7 8 9 10 11 12 13 14 15\"/>")),
        4,
        "must have 9 or 16 values, got 15",
    );
    assert_err(parse(&t("<matrix value=\"nan 0 0 0 1 0 0 0 1\"/>")), 4, "NaN or infinity");
    assert_err(parse(&t("<matrix value=\"1 0 0 0 1 0 0 0 x\"/>")), 4, "could not parse matrix value \"x\"");
    assert_err(parse(&t("<translate x=\"inf\"/>")), 4, "NaN or infinity");
    assert_err(parse(&t("<scale x=\"1e200\"/>\n<scale x=\"1e200\"/>")), 5, "transform contains NaN or infinity");
    assert_err(
        parse(&t("<lookat origin=\"0 0 0\" target=\"0 1 0\" up=\"0 1 0\"/>")),
        4,
        "invalid lookat transformation",
    );
    assert_err(parse(&t("<lookat origin=\"1 1 1\" target=\"1 1 1\"/>")), 4, "invalid lookat transformation");
    assert_err(
        parse(&t("<lookat origin=\"0 0\" target=\"0 1 0\"/>")),
        4,
        "\"origin\" of <lookat> must have 3 numbers, got 2",
    );
    assert_err(parse(&t("<lookat target=\"0 1 0\"/>")), 4, "missing required attribute \"origin\"");
    assert_err(parse(&t("<float name=\"a\" value=\"1\"/>")), 4, "unexpected <float> element inside <transform>");
    assert_err(parse(&t("<translate x=\"1\" w=\"2\"/>")), 4, "unexpected attribute \"w\" in <translate>");
    assert_err(parse(&t("<translate value=\"1\" x=\"2\"/>")), 4, "cannot mix \"value\"");
    assert_err(parse(&t("<scale value=\"1 2\"/>")), 4, "must have 1 or 3 numbers, got 2");
    assert_err(
        parse(&t("<translate x=\"1\"><scale x=\"2\"/></translate>")),
        4,
        "<scale> cannot occur inside <translate>",
    );
    assert_err(
        parse(&scene("<shape type=\"sphere\">\n<translate x=\"1\"/></shape>")),
        3,
        "can only appear inside a <transform>",
    );
    assert_err(
        parse(&scene("<shape type=\"sphere\">\n<transform><translate x=\"1\"/></transform></shape>")),
        3,
        "missing required attribute \"name\" in <transform>",
    );
}

// ------------------------------------------------------------------------------------------
// Colours (doc §2)

fn colors(body: &str) -> Rc<SceneObject> {
    first(&ok(&scene(&format!("<bsdf type=\"t\">\n{body}\n</bsdf>"))))
}

#[test]
fn rgb_float_and_constant_spectrum_per_use() {
    let b = colors(
        "<rgb name=\"c\" value=\"0.2 0.4 0.6\"/>\n<float name=\"f\" value=\"0.3\"/>\n<integer name=\"i\" value=\"2\"/>\n<spectrum name=\"s\" value=\"2.5\"/>\n<rgb name=\"hot\" value=\"-1 2 0.5\"/>",
    );
    let p = &b.properties;
    for u in [ColorUse::Bounded, ColorUse::Unbounded, ColorUse::Emissive] {
        // <rgb> is linear and used as is; <float>/<integer> are gray.
        assert_eq!(p.color("c", u).unwrap(), Some([0.2, 0.4, 0.6]));
        assert_eq!(p.color("f", u).unwrap(), Some([0.3; 3]));
        assert_eq!(p.color("i", u).unwrap(), Some([2.0; 3]));
    }
    // A constant spectrum is uniform, except as emission: v·xyz_to_srgb(1,1,1).
    assert_eq!(p.color("s", ColorUse::Bounded).unwrap(), Some([2.5; 3]));
    assert_eq!(p.color("s", ColorUse::Unbounded).unwrap(), Some([2.5; 3]));
    // The doc's (1.204794, 0.948291, 0.908916) × 2.5; Mitsuba printed [3.01198, 2.37073, 2.27229].
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    assert_rgb(p.color("s", ColorUse::Emissive).unwrap().unwrap(), [3.011985, 2.3707275, 2.27229], 2e-6);
    // Out-of-range rgb: fine for unbounded and emissive uses, an error for reflectances.
    assert_eq!(p.color("hot", ColorUse::Emissive).unwrap(), Some([-1.0, 2.0, 0.5]));
    assert_eq!(p.color("hot", ColorUse::Unbounded).unwrap(), Some([-1.0, 2.0, 0.5]));
    assert_err_in(&p.color("hot", ColorUse::Bounded).unwrap_err(), Path::new(FILE), 7, "invalid RGB reflectance value");
    // A gray float above 1 is not range-checked (Mitsuba's uniform spectrum).
    assert_eq!(p.color("i", ColorUse::Bounded).unwrap(), Some([2.0; 3]));
}

#[test]
fn unit_constant_emission_is_the_equal_energy_colour() {
    // Mitsuba: <spectrum name="radiance" value="1"/> → [1.204793930053711, 0.948291003704071,
    // 0.9089160561561584] (float32), i.e. the XYZ→sRGB row sums 1.204794, 0.948291, 0.908916.
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let b = colors("<spectrum name=\"radiance\" value=\"1\"/>");
    let c = b.properties.color("radiance", ColorUse::Emissive).unwrap().unwrap();
    assert_rgb(c, [1.204793930053711, 0.948291003704071, 0.9089160561561584], 1e-12);
    assert_rgb(c, [1.204794, 0.948291, 0.908916], 1e-6);
}

#[test]
fn sampled_spectra_match_mitsuba() {
    let b = colors(
        "<spectrum name=\"flat\" value=\"360:0.5 830:0.5\"/>\n<spectrum name=\"ramp\" value=\"400:0.2, 500:0.8 600:0.4\"/>\n<spectrum name=\"red\" value=\"550:0.1 600:0.9 700:0.9\"/>\n<spectrum name=\"k\" value=\"400:3 700:2\"/>\n<spectrum name=\"dip\" value=\"400:1 450:0 700:0\"/>",
    );
    let p = &b.properties;
    // Doc §2 [verified]: flat 0.5 → (0.4995, 0.4994, 0.4994) as reflectance, (0.6024, 0.4741,
    // 0.4546) as radiance. Full float32 digits printed by Mitsuba's mi.traverse:
    // Generated by tests/scene_file/xml/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    assert_rgb(
        p.color("flat", ColorUse::Bounded).unwrap().unwrap(),
        [0.4994926452636719, 0.4994368553161621, 0.499400794506073],
        2e-7,
    );
    assert_rgb(
        p.color("flat", ColorUse::Emissive).unwrap().unwrap(),
        [0.6024418473243713, 0.4741140902042389, 0.4546334147453308],
        2e-7,
    );
    // Out of gamut: clamped to [0,1] as reflectance (Mitsuba warns), negatives → 0 otherwise.
    assert_rgb(
        p.color("ramp", ColorUse::Bounded).unwrap().unwrap(),
        [0.0, 0.6751750707626343, 0.5193376541137695],
        2e-7,
    );
    assert_rgb(
        p.color("ramp", ColorUse::Unbounded).unwrap().unwrap(),
        [0.0, 0.6751750707626343, 0.5193376541137695],
        2e-7,
    );
    assert_rgb(
        p.color("ramp", ColorUse::Emissive).unwrap().unwrap(),
        [0.0, 0.6430652737617493, 0.4639976918697357],
        2e-7,
    );
    assert_rgb(p.color("red", ColorUse::Bounded).unwrap().unwrap(), [1.0, 0.12008368223905563, 0.0], 2e-7);
    assert_rgb(
        p.color("k", ColorUse::Unbounded).unwrap().unwrap(),
        [2.181877851486206, 2.5228137969970703, 2.8486852645874023],
        1e-6,
    );
    assert_rgb(
        p.color("dip", ColorUse::Emissive).unwrap().unwrap(),
        [0.02165452018380165, 0.0, 0.15275929868221283],
        2e-7,
    );
}

#[test]
fn color_of_a_wrong_type_is_an_error() {
    let b = colors("\n<string name=\"reflectance\" value=\"red\"/>");
    let e = b.properties.color("reflectance", ColorUse::Bounded).unwrap_err();
    assert_err_in(&e, Path::new(FILE), 4, "expected rgb, spectrum, float or a texture, found string");
}

// ------------------------------------------------------------------------------------------
// Syntax errors, each with file and line

#[test]
fn document_level_errors() {
    assert_err(parse("<scene version=\"3.0.0\">\n<bsdf type=\"diffuse\">\n</scene>"), 3, "malformed XML");
    assert_err(parse("\n<bsdf version=\"3.0.0\" type=\"diffuse\"/>"), 2, "the root element must be <scene");
    assert_err(parse("<scene>\n</scene>"), 1, "missing version attribute in root element <scene>");
    assert_err(parse("<scene version=\"3.0\"/>"), 1, "invalid version number \"3.0\"");
    assert_err(parse("<scene version=\"3.0.0\" type=\"x\"/>"), 1, "unexpected attribute \"type\" in <scene>");
    assert_err(parse(&scene("\n\n<foo/>")), 4, "unknown element <foo>");
    assert_err(parse(&scene("<scene version=\"3.0.0\"/>")), 2, "<scene> can only be the root element");
    assert_err(parse(&scene("<path value=\"no_such_folder_x\"/>")), 2, "<path>: folder");
    // Text and comments are ignored, as in Mitsuba.
    ok(&scene("hello <!-- comment --> <integrator type=\"path\"/>"));
}

#[test]
fn element_level_errors() {
    let e = |body: &str| parse(&scene(&format!("<bsdf type=\"t\">\n{body}\n</bsdf>")));
    assert_err(parse(&scene("\n<bsdf type=\"diffuse\" foo=\"1\"/>")), 3, "unexpected attribute \"foo\" in <bsdf>");
    assert_err(parse(&scene("<bsdf id=\"x\"/>")), 2, "missing required attribute \"type\" in <bsdf>");
    assert_err(e("<float value=\"1\"/>"), 3, "missing required attribute \"name\" in <float>");
    assert_err(e("<float name=\"a\"/>"), 3, "missing required attribute \"value\" in <float>");
    assert_err(e("<float name=\"a\" value=\"1\" unit=\"m\"/>"), 3, "unexpected attribute \"unit\" in <float>");
    assert_err(
        e("<float name=\"a\" value=\"1\"><float name=\"b\" value=\"2\"/></float>"),
        3,
        "<float> cannot occur inside <float>",
    );
    assert_err(e("<float name=\"a\" value=\"1,5\"/>"), 3, "could not parse float value \"1,5\"");
    assert_err(e("<float name=\"a\" value=\"\"/>"), 3, "could not parse float value");
    assert_err(e("<integer name=\"a\" value=\"1.0\"/>"), 3, "could not parse integer value \"1.0\"");
    assert_err(e("<integer name=\"a\" value=\"+1\"/>"), 3, "could not parse integer value \"+1\"");
    assert_err(e("<integer name=\"a\" value=\"99999999999999999999\"/>"), 3, "could not parse integer value");
    assert_err(e("<boolean name=\"a\" value=\"yes\"/>"), 3, "could not parse boolean value \"yes\"");
    assert_err(e("<rgb name=\"a\" value=\"0.1 0.2\"/>"), 3, "<rgb> requires one or three values, got 2");
    assert_err(e("<rgb name=\"a\" value=\"0.1 red 0.2\"/>"), 3, "could not parse RGB value");
    assert_err(e("<point name=\"a\" x=\"1\"/>"), 3, "missing required attribute \"y\" in <point>");
    assert_err(e("<point name=\"a\" value=\"1\" x=\"1\"/>"), 3, "cannot mix \"value\"");
    assert_err(e("<vector name=\"a\" value=\"1 2\"/>"), 3, "must have 1 or 3 numbers, got 2");
    assert_err(e("<vector name=\"a\" x=\"1\" y=\"b\" z=\"3\"/>"), 3, "could not parse y \"b\"");
    assert_err(e("<spectrum name=\"a\" filename=\"no_such_file_x.spd\"/>"), 3, "cannot read spectrum file");
    assert_err(e("<spectrum name=\"a\" value=\"1\" filename=\"x.spd\"/>"), 3, "but not both");
    assert_err(e("<spectrum name=\"a\"/>"), 3, "either a \"value\" or a \"filename\"");
    assert_err(e("<spectrum name=\"a\" value=\"500:0.5\"/>"), 3, "at least two wavelength:value pairs");
    assert_err(e("<spectrum name=\"a\" value=\"500:0.5 400:0.3\"/>"), 3, "strictly increasing");
    assert_err(e("<spectrum name=\"a\" value=\"500:0.5 600\"/>"), 3, "could not parse spectrum sample \"600\"");
    assert_err(e("<spectrum name=\"a\" value=\"x\"/>"), 3, "could not parse spectrum value \"x\"");
    assert_err(e("<ref id=\"a\"><float name=\"b\" value=\"2\"/></ref>"), 3, "<float> cannot occur inside <ref>");
    assert_err(e("<include/>"), 3, "missing required attribute \"filename\" in <include>");
    assert_err(e("<alias id=\"a\"/>"), 3, "missing required attribute \"as\" in <alias>");
}

// ------------------------------------------------------------------------------------------
// Version 1 scenes

#[test]
fn version_1_scenes_are_upgraded() {
    let s = ok(
        "<scene version=\"0.6.0\">\n<bsdf type=\"diffuse\"><rgb name=\"diffuseReflectance\" value=\"0.2\"/></bsdf>\n<bsdf type=\"dielectric\"><float name=\"intIOR\" value=\"1.5\"/><bsdf type=\"x\" name=\"nestedThing\"/></bsdf>\n<texture type=\"bitmap\"><float name=\"uoffset\" value=\"0.5\"/><integer name=\"vscale\" value=\"2\"/></texture>\n</scene>",
    );
    let p = &s.children[0].object.properties;
    assert_eq!(p.color("reflectance", ColorUse::Bounded).unwrap(), Some([0.2; 3]));
    let d = &s.children[1].object;
    assert_eq!(d.properties.float("int_ior").unwrap(), Some(1.5));
    assert!(d.child("nested_thing").is_some());
    // to_uv = scale(1, 2, 1) · translate(0.5, 0, 0): (0,0) → (0.5, 0).
    let t = s.children[2].object.properties.transform("to_uv").unwrap().unwrap();
    assert!(t.transform_point3(DVec3::new(0.0, 1.0, 0.0)).abs_diff_eq(DVec3::new(0.5, 2.0, 0.0), 1e-15));
    assert!(!s.children[2].object.properties.contains("uoffset"));
    // A 3.x scene keeps camelCase names as written.
    let s = ok(&scene("<bsdf type=\"t\"><float name=\"intIOR\" value=\"1\"/></bsdf>"));
    assert!(first(&s).properties.contains("intIOR"));
}

#[test]
fn error_positions_are_the_element_start() {
    // Column of '<' in the line, 1-based.
    let e = parse(&scene("<bsdf type=\"t\">\n     <float name=\"a\" value=\"z\"/>\n</bsdf>")).unwrap_err();
    assert_eq!(e.pos, Some(SourcePos::new(std::sync::Arc::new(PathBuf::from(FILE)), 3, 6)));
}
