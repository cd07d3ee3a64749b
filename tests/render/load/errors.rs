//! Parser-level errors seen through the loader: malformed XML, unknown tags and parameters, each
//! one line naming `file:line`.

use std::path::Path;

use glam::Vec3;
use matte_render::load::{load_file, load_str};

use super::{FILE, assert_body_err, assert_err, hit, load, ok, with_sensor};

#[test]
fn malformed_xml_unknown_tags_and_parameters() {
    assert_err(load("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n</scene>"), 3, "malformed XML");
    assert_err(
        load(&with_sensor("<shape type=\"sphere\"><float name=\"radius\" value=\"1\"></shape>")),
        3,
        "malformed XML",
    );
    // Any object may stand at the top level (Mitsuba's `Scene` constructor): it is built, so
    // its properties are checked, and otherwise unused.
    ok(&with_sensor("<rfilter type=\"box\"/>\n<sampler type=\"independent\"/>\n<film type=\"hdrfilm\"/>"));
    // An area light declared at the top level belongs to the shape that refers to it; one
    // that no shape uses emits nothing, and is still checked.
    let lit = ok(&with_sensor(
        "<emitter type=\"area\" id=\"l\"><rgb name=\"radiance\" value=\"3\"/></emitter>\n<shape type=\"sphere\"><ref id=\"l\"/></shape>",
    ));
    assert_eq!((lit.scene.emitters.len(), lit.scene.shapes[0].emitter), (1, Some(0)));
    assert_eq!(ok(&with_sensor("<emitter type=\"area\"/>\n<shape type=\"sphere\"/>")).scene.emitters.len(), 0);
    assert_body_err(
        "<emitter type=\"area\">\n<float name=\"bogus\" value=\"1\"/>\n</emitter>",
        2,
        "unreferenced property \"bogus\"",
    );
    assert_body_err(
        "<rfilter type=\"box\">\n<float name=\"radius\" value=\"2\"/>\n</rfilter>",
        2,
        "unreferenced property \"radius\"",
    );
    assert_body_err(
        "<sampler type=\"independent\">\n<integer name=\"sample_count\" value=\"0\"/>\n</sampler>",
        2,
        "sample_count",
    );
    // Out of scope, wherever it appears: one line naming the element.
    assert_body_err(
        "<medium type=\"homogeneous\"/>",
        1,
        "<medium type=\"homogeneous\">: participating media are outside matte's scope",
    );
    assert_body_err(
        "<shape type=\"sphere\">\n<medium type=\"homogeneous\" name=\"interior\"/>\n</shape>",
        2,
        "participating media are outside matte's scope",
    );
    assert_body_err("<shape type=\"sphere\">\n<bsdf type=\"polarizer\"/>\n</shape>", 2, "polarisation-only BSDFs");
    assert_body_err("<shape type=\"linearcurve\"/>", 1, "curves are outside matte's scope");
    assert_body_err("<shape type=\"sdfgrid\"/>", 1, "SDF grids are outside matte's scope");
    assert_body_err("<shape type=\"sphere\"><bsdf type=\"hair\"/></shape>", 1, "hair is outside matte's scope");
    assert_body_err("<shape type=\"$kind\"/>", 1, "undefined parameter $kind");
    // -D parameters: used ones substitute, an unused one is an error naming the file.
    let xml = with_sensor("<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>");
    let s = load_str(&xml, Path::new(FILE), &[("r".into(), "2".into())]).unwrap_or_else(|e| panic!("{e}"));
    assert!(hit(&s, Vec3::new(1.9, 0.0, 5.0), Vec3::NEG_Z).is_some());
    let Err(e) = load_str(&xml, Path::new(FILE), &[("r".into(), "2".into()), ("foo".into(), "3".into())]) else {
        panic!("expected an error")
    };
    assert!(e.to_string().starts_with(FILE) && e.to_string().contains("unused parameter $foo=3"), "{e}");
    // Missing scene file.
    let Err(e) = load_file(Path::new("/nonexistent/dir/scene.xml"), &[]) else { panic!("expected an error") };
    assert!(e.to_string().contains("/nonexistent/dir/scene.xml") && e.to_string().contains("cannot read"), "{e}");
}
