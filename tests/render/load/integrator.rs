//! `<integrator>` (§7): `path` and `direct` with their defaults and values, `moment` rendering its
//! nested integrator, and the integrators' errors.

use std::path::Path;

use matte_render::integrator::Integrator;

use super::{FILE, assert_body_err, load, ok, with_sensor};
use crate::common::{SENSOR, assert_err_at, scene};

#[test]
fn path_integrator_defaults_and_values() {
    let Integrator::Path(p) = ok(&with_sensor("<integrator type=\"path\"/>")).integrator else { panic!("not path") };
    // max_depth −1 is stored as 2³²−1; rr_depth 5; hide_emitters false.
    assert_eq!((p.max_depth, p.rr_depth, p.hide_emitters), (u32::MAX, 5, false));
    let s = ok(&with_sensor(
        "<integrator type=\"path\"><integer name=\"max_depth\" value=\"3\"/><integer name=\"rr_depth\" value=\"2\"/>\
         <boolean name=\"hide_emitters\" value=\"true\"/></integrator>",
    ));
    let Integrator::Path(p) = s.integrator else { panic!("not path") };
    assert_eq!((p.max_depth, p.rr_depth, p.hide_emitters), (3, 2, true));
    let Integrator::Path(p) =
        ok(&with_sensor("<integrator type=\"path\"><integer name=\"max_depth\" value=\"0\"/></integrator>")).integrator
    else {
        panic!("not path")
    };
    assert_eq!(p.max_depth, 0);
    // No <integrator>: matte renders with a default path tracer.
    let Integrator::Path(p) = ok(&with_sensor("")).integrator else { panic!("not path") };
    assert_eq!((p.max_depth, p.rr_depth, p.hide_emitters), (u32::MAX, 5, false));
}

#[test]
fn direct_integrator_defaults_and_values() {
    let Integrator::Direct(d) = ok(&with_sensor("<integrator type=\"direct\"/>")).integrator else {
        panic!("not direct")
    };
    assert_eq!((d.emitter_samples, d.bsdf_samples, d.hide_emitters), (1, 1, false));
    let s = ok(&with_sensor(
        "<integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"4\"/><integer name=\"bsdf_samples\" value=\"0\"/>\
         <boolean name=\"hide_emitters\" value=\"true\"/></integrator>",
    ));
    let Integrator::Direct(d) = s.integrator else { panic!("not direct") };
    assert_eq!((d.emitter_samples, d.bsdf_samples, d.hide_emitters), (4, 0, true));
    // shading_samples sets both.
    let s =
        ok(&with_sensor("<integrator type=\"direct\"><integer name=\"shading_samples\" value=\"3\"/></integrator>"));
    let Integrator::Direct(d) = s.integrator else { panic!("not direct") };
    assert_eq!((d.emitter_samples, d.bsdf_samples), (3, 3));
}

#[test]
fn integrator_errors() {
    assert_body_err("<integrator type=\"aov\"/>", 1, "unsupported integrator type \"aov\"");
    assert_body_err(
        "<integrator type=\"path\">\n<integer name=\"max_depth\" value=\"-2\"/>\n</integrator>",
        2,
        "max_depth",
    );
    assert_body_err(
        "<integrator type=\"path\">\n<integer name=\"rr_depth\" value=\"0\"/>\n</integrator>",
        2,
        "rr_depth",
    );
    assert_body_err(
        "<integrator type=\"path\">\n<float name=\"max_depth\" value=\"3\"/>\n</integrator>",
        2,
        "wrong type",
    );
    assert_body_err(
        "<integrator type=\"path\">\n<string name=\"hide_emitters\" value=\"yes\"/>\n</integrator>",
        2,
        "wrong type",
    );
    assert_body_err(
        "<integrator type=\"path\">\n<integer name=\"samples\" value=\"3\"/>\n</integrator>",
        2,
        "unreferenced property \"samples\"",
    );
    assert_body_err(
        "<integrator type=\"direct\">\n<integer name=\"shading_samples\" value=\"2\"/>\n<integer name=\"bsdf_samples\" value=\"2\"/>\n</integrator>",
        1,
        "shading_samples cannot be combined",
    );
    assert_body_err(
        "<integrator type=\"direct\">\n<integer name=\"emitter_samples\" value=\"0\"/>\n<integer name=\"bsdf_samples\" value=\"0\"/>\n</integrator>",
        1,
        "at least one",
    );
    assert_body_err(
        "<integrator type=\"path\"/>\n<integrator type=\"path\"/>",
        2,
        "only one integrator can be specified per scene",
    );
}

/// `src/integrators/moment.cpp`: the image is the first nested integrator's.
#[test]
fn moment_renders_its_nested_integrator() {
    let s = load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"><integrator type=\"direct\"><integer name=\"emitter_samples\" value=\"3\"/></integrator></integrator>"))).unwrap();
    match s.integrator {
        Integrator::Direct(d) => assert_eq!(d.emitter_samples, 3),
        other => panic!("expected the nested direct integrator, got {other:?}"),
    }
    let s = load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"><integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator><integrator type=\"direct\"/></integrator>"))).unwrap();
    assert!(matches!(s.integrator, Integrator::Path(ref p) if p.max_depth == 2), "{:?}", s.integrator);
    assert_err_at(
        load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\"/>"))),
        Path::new(FILE),
        3,
        "needs at least one nested <integrator>",
    );
    assert_err_at(
        load(&scene(&format!("{SENSOR}\n<integrator type=\"moment\">\n<integrator type=\"bogus\"/></integrator>"))),
        Path::new(FILE),
        4,
        "unsupported integrator type \"bogus\"",
    );
}
