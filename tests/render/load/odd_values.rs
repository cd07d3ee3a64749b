//! Odd values (0, −1, NaN, ±∞, 1e30…) in every numeric property: loading never panics, and whatever
//! loads renders without NaN.

use glam::Vec2;

use super::{FILE, load};
use crate::common::{models_from_defaults, scene};

/// One numeric property (or attribute) set to `{v}` per template; the rest is a small scene.
/// matte's models are in [`templates`], from the registry; here only their combinations.
const ODD_VALUE_TEMPLATES: &[&str] = &[
    r#"<sensor type="perspective"><float name="fov" value="{v}"/></sensor>"#,
    r#"<sensor type="perspective"><string name="focal_length" value="{v}mm"/></sensor>"#,
    r#"<sensor type="perspective"><float name="near_clip" value="{v}"/></sensor>"#,
    r#"<sensor type="perspective"><float name="far_clip" value="{v}"/></sensor>"#,
    r#"<sensor type="perspective"><float name="principal_point_offset_x" value="{v}"/></sensor>"#,
    r#"<sensor type="perspective"><transform name="to_world"><lookat origin="0,0,{v}" target="0,0,0"/></transform></sensor>"#,
    r#"<sensor type="perspective"><transform name="to_world"><rotate x="1" angle="{v}"/></transform></sensor>"#,
    r#"<sensor type="perspective"><film type="hdrfilm"><rfilter type="tent"><float name="radius" value="{v}"/></rfilter></film></sensor>"#,
    r#"<sensor type="perspective"><film type="hdrfilm"><rfilter type="gaussian"><float name="stddev" value="{v}"/></rfilter></film></sensor>"#,
    r#"<sensor type="perspective"><sampler type="independent"><integer name="sample_count" value="{v}"/></sampler></sensor>"#,
    r#"<integrator type="path"><integer name="max_depth" value="{v}"/></integrator>"#,
    r#"<integrator type="direct"><integer name="emitter_samples" value="{v}"/></integrator>"#,
    r#"<shape type="sphere"><float name="radius" value="{v}"/></shape>"#,
    r#"<shape type="sphere"><point name="center" value="{v} 0 0"/></shape>"#,
    r#"<shape type="sphere"><transform name="to_world"><scale value="{v}"/></transform></shape>"#,
    r#"<shape type="cylinder"><float name="radius" value="{v}"/></shape>"#,
    r#"<shape type="cylinder"><point name="p1" value="0 {v} 0"/></shape>"#,
    r#"<shape type="disk"><transform name="to_world"><scale x="{v}"/></transform></shape>"#,
    r#"<shape type="rectangle"><transform name="to_world"><scale y="{v}"/></transform><emitter type="area"/></shape>"#,
    r#"<shape type="cube"><transform name="to_world"><rotate y="1" angle="{v}"/><scale z="{v}"/></transform></shape>"#,
    r#"<shape type="sphere"><emitter type="area"><rgb name="radiance" value="{v} 1 1"/></emitter></shape>"#,
    r#"<shape type="sphere"><emitter type="area"><float name="sampling_weight" value="{v}"/></emitter></shape>"#,
    r#"<emitter type="point"><rgb name="intensity" value="{v} 1 1"/><point name="position" value="0 0 3"/></emitter>"#,
    r#"<emitter type="spot"><float name="cutoff_angle" value="{v}"/><transform name="to_world"><lookat origin="0,0,3" target="0,0,0"/></transform></emitter>"#,
    r#"<emitter type="spot"><float name="beam_width" value="{v}"/><transform name="to_world"><lookat origin="0,0,3" target="0,0,0"/></transform></emitter>"#,
    r#"<emitter type="directional"><vector name="direction" value="{v} 0 -1"/></emitter>"#,
    r#"<emitter type="constant"><float name="radiance" value="{v}"/></emitter>"#,
    r#"<shape type="sphere"><bsdf type="diffuse"><float name="reflectance" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="oren_nayar"><float name="sigma" value="{v}"/><string name="model" value="full"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="dielectric"><float name="int_ior" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="dielectric"><float name="ext_ior" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="conductor"><float name="eta" value="{v}"/><float name="k" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="roughconductor"><float name="alpha" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha_u" value="{v}"/><float name="alpha_v" value="0.2"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="twosided"><bsdf type="roughconductor"><float name="alpha" value="{v}"/><float name="eta" value="{v}"/></bsdf></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="roughconductor"><float name="eta" value="{v}"/><float name="k" value="1"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="roughconductor"><float name="k" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="conductor"><float name="k" value="{v}"/></bsdf></shape>"#,
    r#"<shape type="sphere"><bsdf type="wolff"><float name="ext_ior" value="{v}"/><float name="int_ior" value="1e31"/></bsdf></shape>"#,
];

/// [`ODD_VALUE_TEMPLATES`] and, for every registered model, its reflectance and each of its
/// numeric parameters (the others at their defaults).
fn templates() -> Vec<String> {
    let mut out: Vec<String> = ODD_VALUE_TEMPLATES.iter().map(|t| t.to_string()).collect();
    for spec in models_from_defaults() {
        let kind = spec.name;
        out.push(format!(
            r#"<shape type="sphere"><bsdf type="{kind}"><rgb name="reflectance" value="{{v}} 0.5 0.5"/></bsdf></shape>"#
        ));
        for p in spec.numeric() {
            out.push(format!(
                r#"<shape type="sphere"><bsdf type="{kind}"><float name="{}" value="{{v}}"/></bsdf></shape>"#,
                p.name
            ));
        }
    }
    out
}

const ODD_VALUES: &[&str] = &["0", "-1", "2", "1e-30", "1e30", "nan", "inf", "-inf", "179.99", "1e9", "1e15"];

#[test]
fn odd_values_never_panic_and_accepted_scenes_render_finite() {
    let mut accepted = 0;
    let mut failures = Vec::new();
    let templates = templates();
    for template in &templates {
        for v in ODD_VALUES {
            let element = template.replace("{v}", v);
            // Every scene has a camera on +z looking at the origin, a 4×2 film and an environment,
            // unless the element under test brings its own sensor (or environment).
            let camera = r#"<sensor type="perspective"><float name="fov" value="60"/><transform name="to_world"><lookat origin="0,0,5" target="0,0,0"/></transform><film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#;
            let mut body = if !element.starts_with("<sensor") {
                format!(
                    r#"{camera}{element}<shape type="sphere"><transform name="to_world"><translate z="-3"/></transform></shape>"#
                )
            } else if element.contains("<film") {
                element.replace("<film type=\"hdrfilm\">", "<film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"2\"/>")
                    + r#"<shape type="sphere"/>"#
            } else {
                element.replace("</sensor>", r#"<film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="2"/></film></sensor>"#)
                    + r#"<shape type="sphere"/>"#
            };
            if !element.contains("type=\"constant\"") {
                body.push_str(r#"<emitter type="constant"/>"#);
            }
            let xml = scene(&body);
            let loaded = std::panic::catch_unwind(|| load(&xml)).unwrap_or_else(|_| panic!("panicked on {element}"));
            let s = match loaded {
                Err(e) => {
                    let text = e.to_string();
                    assert!(text.starts_with(&format!("{FILE}:")) && !text.contains('\n'), "{element}: {text}");
                    continue;
                }
                Ok(s) => s,
            };
            accepted += 1;
            for p in [Vec2::ZERO, Vec2::new(4.0, 2.0), Vec2::new(2.0, 1.0)] {
                let r = s.camera.ray(p);
                assert!(r.o.is_finite() && r.d.is_finite() && !r.maxt.is_nan(), "{element}: camera ray {r:?}");
            }
            let rendered = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                matte_render::renderer::render(
                    &s.scene,
                    &s.integrator,
                    &s.camera,
                    s.film.clone(),
                    s.sampling.with_spp(4).with_seed(0),
                    &|_, _| {},
                )
            }));
            match rendered {
                Err(_) => failures.push(format!("{element}: the renderer panicked")),
                Ok((img, stats)) if stats.invalid_samples > 0 || !img.pixels.iter().all(|p| p.is_finite()) => {
                    failures.push(format!("{element}: {} NaN/Inf samples", stats.invalid_samples))
                }
                Ok(_) => {}
            }
        }
    }
    assert!(failures.is_empty(), "accepted, but rendered NaN/Inf:\n{}", failures.join("\n"));
    // Most of the grid is valid input (e.g. fov 0.5, radius 1e30, alpha 0).
    assert!(accepted > templates.len() * 3, "{accepted}");
}
