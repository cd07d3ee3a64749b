//! `<bsdf>` (§2, §10; docs/models.md): `diffuse` colours, matte's models with their documented
//! and declared defaults, `null`, `twosided`, `mask`, `blendbsdf` and `bumpmap` defaults, dielectrics,
//! conductors and `roughconductor`, and the BSDFs' errors.

use std::path::Path;

use glam::{Vec2, Vec3};
use matte_brdf::ParamValue;
use matte_render::bsdf::{Bsdf, BsdfFlags, Bxdf, Matte, MicrofacetDistribution, RoughConductor, TwoSided};
use matte_render::geometry::Ray;
use matte_render::texture::Texture;

use super::references::{
    CONDUCTOR_AU_F0, CONDUCTOR_DEFAULT_F0, CONDUCTOR_ETA_K_F0, CONDUCTOR_NONE_ETA_K_F0, DIELECTRIC_ETA,
    DIELECTRIC_REFLECTION, DIELECTRIC_REFRACTION, DIFFUSE_REFLECTANCE, MASK_DEFAULT_OPACITY, NULL_SAMPLE,
    ROUGHCONDUCTOR_AU_OVER_MIRROR, ROUGHCONDUCTOR_DEFAULTS, TWOSIDED_AROUND_NULL_REFUSED,
};
use super::{
    FILE, assert_body_err, assert_vec, close3, constant_reflectance, hit, load, ok, shape_bsdf, temp_dir, with_sensor,
};
use crate::common::{SENSOR, assert_err_at, models_from_defaults, scene, write_exr};

/// The only BSDF of a scene with one top-level `<bsdf>` (`xml` is that element).
fn one_bsdf(xml: &str) -> Bsdf {
    let s = ok(&with_sensor(xml));
    assert_eq!(s.scene.bsdfs.len(), 1);
    s.scene.bsdfs[0].clone()
}

#[test]
fn diffuse_reflectance_colours() {
    // §10: diffuse default 0.5; §2 bounded reading: <rgb> as is, <float>/<spectrum value>
    // uniform, a flat sampled 0.5 → (0.4995, 0.4994, 0.4994) [verified]; Mitsuba range-checks
    // only <rgb>: a <float> above 1 is a uniform texture. Mitsuba's: `DIFFUSE_REFLECTANCE`.
    for &(prop, want) in DIFFUSE_REFLECTANCE {
        let b = one_bsdf(&format!("<bsdf type=\"diffuse\">{prop}</bsdf>"));
        assert!(close3(constant_reflectance(&b), want.into(), 1e-4), "{prop}: {b:?}");
    }
}

#[test]
fn matte_models_with_documented_defaults() {
    // docs/models.md: reflectance 0.5; oren_nayar σ 0.3 qualitative; eon r 0.3 cosine; wolff int 1.4,
    // ext 1.0, physical; ginneken m 0.3, vginneken.
    use ParamValue::{Number, Text};
    let num = |x: f64| Number(x as f32 as f64);
    type Case = (&'static str, &'static str, Vec<(&'static str, ParamValue)>);
    let cases: [Case; 9] = [
        ("lambert", "", vec![]),
        (
            "oren_nayar",
            "",
            vec![("sigma", num(0.3)), ("model", Text("qualitative".into())), ("sampling", Text("cosine".into()))],
        ),
        (
            "oren_nayar",
            "<float name=\"sigma\" value=\"0.5\"/><string name=\"model\" value=\"full\"/><string name=\"sampling\" value=\"cltc\"/>",
            vec![("sigma", num(0.5)), ("model", Text("full".into())), ("sampling", Text("cltc".into()))],
        ),
        ("eon", "", vec![("roughness", num(0.3)), ("sampling", Text("cosine".into()))]),
        (
            "eon",
            "<float name=\"roughness\" value=\"0.6\"/><string name=\"sampling\" value=\"cltc\"/>",
            vec![("roughness", num(0.6)), ("sampling", Text("cltc".into()))],
        ),
        ("wolff", "", vec![("int_ior", num(1.4)), ("ext_ior", num(1.0)), ("normalization", Text("physical".into()))]),
        // Named IORs from Mitsuba's table (§10): water 1.3330, an integer is a number too.
        (
            "wolff",
            "<string name=\"int_ior\" value=\"water\"/><integer name=\"ext_ior\" value=\"1\"/><string name=\"normalization\" value=\"raw\"/>",
            vec![("int_ior", num(1.333)), ("ext_ior", num(1.0)), ("normalization", Text("raw".into()))],
        ),
        (
            "ginneken",
            "",
            vec![("roughness", num(0.3)), ("shadowing", Text("vginneken".into())), ("sampling", Text("cosine".into()))],
        ),
        (
            "ginneken",
            "<float name=\"roughness\" value=\"0.1\"/><string name=\"shadowing\" value=\"height_correlated\"/>",
            vec![
                ("roughness", num(0.1)),
                ("shadowing", Text("height_correlated".into())),
                ("sampling", Text("cosine".into())),
            ],
        ),
    ];
    for (kind, props, want) in cases {
        let b = one_bsdf(&format!("<bsdf type=\"{kind}\">{props}</bsdf>"));
        let Bsdf::Matte(Matte { model, reflectance: Texture::Constant(rho), .. }) = &b else { panic!("{kind}: {b:?}") };
        assert_eq!(model.kind(), kind);
        assert_eq!(model.parameters(), want, "{kind} {props}");
        assert_eq!(*rho, Vec3::splat(0.5), "{kind}");
    }
    let b = one_bsdf("<bsdf type=\"lambert\"><rgb name=\"reflectance\" value=\"0.8 0.3 0.2\"/></bsdf>");
    assert_eq!(constant_reflectance(&b), Vec3::new(0.8, 0.3, 0.2));
}

/// Every registered model loads from `<bsdf type="…"/>` with the defaults its declaration gives
/// (the registry's; the documented numbers of the paper's models are pinned above) and
/// reflectance 0.5. (A model with a required file, `tabulated_brdf`, is tested with its table in
/// `tests/render/matte_bsdf.rs`.)
#[test]
fn every_registered_model_loads_with_its_declared_defaults() {
    for spec in models_from_defaults() {
        let b = one_bsdf(&format!("<bsdf type=\"{}\"/>", spec.name));
        let Bsdf::Matte(Matte { model, reflectance: Texture::Constant(rho), .. }) = &b else {
            panic!("{}: {b:?}", spec.name)
        };
        assert_eq!(model.kind(), spec.name);
        let want: Vec<(&str, ParamValue)> = spec
            .params
            .iter()
            .map(|p| match p.default_value().expect("a default") {
                ParamValue::Number(x) => (p.name, ParamValue::Number(x as f32 as f64)),
                v => (p.name, v),
            })
            .collect();
        assert_eq!(model.parameters(), want, "{}", spec.name);
        assert_eq!(*rho, Vec3::splat(0.5), "{}", spec.name);
    }
}

/// `src/bsdfs/null.cpp`, checked against Mitsuba 3.9.1 (`scalar_rgb`): `sample` at
/// wi = (0.3, 0, 0.954) gives wo = −wi, pdf 1, weight 1, sampled type Null; `twosided`
/// refuses it ("Only materials without a transmission component can be nested!"): `NULL_SAMPLE`,
/// `TWOSIDED_AROUND_NULL_REFUSED`.
#[test]
fn null_bsdf_passes_rays_straight_through() {
    let s = ok(&with_sensor("<shape type=\"sphere\"><bsdf type=\"null\"/></shape>"));
    let b = shape_bsdf(&s, 0).clone();
    assert!(matches!(b, Bsdf::Null(_)), "{b:?}");
    let si = hit(&s, Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z).expect("the sphere is hit");
    let wi = Vec3::new(0.3, 0.0, 0.954);
    let bs = b.sample(&si, wi, 0.3, Vec2::new(0.2, 0.7)).expect("a sample");
    let (wo, weight, pdf, passes_on) = NULL_SAMPLE;
    assert_eq!((bs.wo, bs.weight, bs.pdf, bs.delta, bs.eta), (wo.into(), weight.into(), pdf, passes_on, 1.0));
    assert_eq!(b.eval_pdf(&si, wi, -wi), (Vec3::ZERO, 0.0));
    assert!(!b.flags().has(BsdfFlags::SMOOTH));
    let twosided = "<shape type=\"sphere\"><bsdf type=\"twosided\"><bsdf type=\"null\"/></bsdf></shape>";
    assert_eq!(load(&with_sensor(twosided)).is_err(), TWOSIDED_AROUND_NULL_REFUSED);
    assert_body_err(twosided, 1, "cannot wrap a transmissive BSDF");
}

#[test]
fn twosided_wraps_one_or_two_bsdfs() {
    let b = one_bsdf(
        "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"><float name=\"reflectance\" value=\"0.2\"/></bsdf></bsdf>",
    );
    let Bsdf::TwoSided(TwoSided { front, back }) = b else { panic!() };
    assert_eq!((constant_reflectance(&front), constant_reflectance(&back)), (Vec3::splat(0.2), Vec3::splat(0.2)));
    let b = one_bsdf(
        "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/><bsdf type=\"eon\"><float name=\"reflectance\" value=\"0.9\"/></bsdf></bsdf>",
    );
    let Bsdf::TwoSided(TwoSided { front, back }) = b else { panic!() };
    assert_eq!(constant_reflectance(&front), Vec3::splat(0.5));
    assert!(matches!(*back, Bsdf::Matte(Matte { ref model, .. }) if model.kind() == "eon"));
    assert_eq!(constant_reflectance(&back), Vec3::splat(0.9));
    // A referenced inner BSDF works too.
    let s = ok(&with_sensor(
        "<bsdf type=\"conductor\" id=\"m\"/><shape type=\"sphere\"><bsdf type=\"twosided\"><ref id=\"m\"/></bsdf></shape>",
    ));
    assert!(
        matches!(shape_bsdf(&s, 0), Bsdf::TwoSided(TwoSided { front, .. }) if matches!(**front, Bsdf::Conductor(_)))
    );
}

/// `src/bsdfs/mask.cpp`: `opacity` defaults to 0.5 (a float or a texture), exactly one nested
/// BSDF; a `twosided` around a mask is an error (its null component is a transmission,
/// `src/bsdfs/twosided.cpp`); unknown properties are errors.
#[test]
fn mask_defaults_and_errors() {
    let xml = |bsdf: &str| scene(&format!("{SENSOR}\n<shape type=\"rectangle\">\n{bsdf}\n</shape>"));
    let s = load(&xml(r#"<bsdf type="mask"><bsdf type="diffuse"/></bsdf>"#)).unwrap();
    let si = s.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Mask(m) = s.scene.bsdf(&si) else { panic!("expected a mask") };
    assert_eq!(m.opacity(&si), MASK_DEFAULT_OPACITY);
    assert!(matches!(*m.nested, Bsdf::Diffuse { .. }));
    let clipped = load(&xml(r#"<bsdf type="mask"><float name="opacity" value="0.25"/><bsdf type="diffuse"/></bsdf>"#));
    let Bsdf::Mask(m) = clipped.as_ref().unwrap().scene.bsdf(&si) else { panic!() };
    assert_eq!(m.opacity(&si), 0.25);
    assert_err_at(load(&xml("<bsdf type=\"mask\"/>")), Path::new(FILE), 4, "found 0");
    assert_err_at(
        load(&xml("<bsdf type=\"mask\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>")),
        Path::new(FILE),
        4,
        "found 2",
    );
    assert_err_at(
        load(&xml("<bsdf type=\"twosided\"><bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf></bsdf>")),
        Path::new(FILE),
        4,
        "allow_transmission",
    );
    assert_err_at(
        load(&xml("<bsdf type=\"mask\"><float name=\"opacty\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf>")),
        Path::new(FILE),
        4,
        "opacty",
    );
}

/// `src/bsdfs/blendbsdf.cpp`: exactly two nested BSDFs and a `weight` (no default);
/// `src/bsdfs/bumpmap.cpp`: one nested BSDF and one texture child of any name, `scale` 1,
/// `flip_invalid_normals` and `use_shadowing_function` true. matte needs a bitmap height map
/// (Mitsuba's other textures have no gradient) and a mesh (its analytic shapes have no
/// ∂p/∂u, ∂p/∂v).
#[test]
fn blendbsdf_and_bumpmap_defaults_and_errors() {
    let xml = |shape: &str, bsdf: &str| scene(&format!("{SENSOR}\n<shape type=\"{shape}\">\n{bsdf}\n</shape>"));
    let blend = load(&xml(
        "rectangle",
        r#"<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/><bsdf type="conductor"/></bsdf>"#,
    ))
    .unwrap();
    let si = blend.scene.intersect(&Ray::new(Vec3::new(0.0, 0.0, 1.0), Vec3::NEG_Z, f32::INFINITY)).expect("hit");
    let Bsdf::Blend(b) = blend.scene.bsdf(&si) else { panic!("expected a blend") };
    assert!((b.weight(&si) - 0.3).abs() < 1e-7);
    assert!(matches!((&*b.first, &*b.second), (Bsdf::Diffuse { .. }, Bsdf::Conductor(_))));
    let no_weight =
        xml("rectangle", "<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>");
    assert_err_at(load(&no_weight), Path::new(FILE), 4, "weight");
    let one = xml(
        "rectangle",
        "<bsdf type=\"blendbsdf\"><float name=\"weight\" value=\"0.5\"/><bsdf type=\"diffuse\"/></bsdf>",
    );
    assert_err_at(load(&one), Path::new(FILE), 4, "found 1");

    let dir = temp_dir("bumpmap");
    let height = dir.join("h.exr");
    write_exr(&height, 4, 4, |i, j| Vec3::splat((i + 2 * j) as f32 / 10.0));
    let bump =
        |shape: &str, tex: &str| xml(shape, &format!("<bsdf type=\"bumpmap\">{tex}<bsdf type=\"diffuse\"/></bsdf>",));
    let bitmap = format!(
        "<texture type=\"bitmap\" name=\"any_name\"><string name=\"filename\" value=\"{}\"/></texture>",
        height.display()
    );
    let s = load(&bump("rectangle", &bitmap)).unwrap();
    let Bsdf::BumpMap(m) = s.scene.bsdf(&si) else { panic!("expected a bumpmap") };
    assert_eq!((m.scale, m.flip_invalid_normals, m.use_shadowing_function), (1.0, true, true));
    assert_err_at(load(&bump("sphere", &bitmap)), Path::new(FILE), 4, "meshes only");
    assert_err_at(
        load(&bump("rectangle", "<texture type=\"checkerboard\" name=\"h\"/>")),
        Path::new(FILE),
        4,
        "bitmap height texture",
    );
    assert_err_at(load(&bump("rectangle", "")), Path::new(FILE), 4, "found 0");
}

#[test]
fn dielectric_iors_and_weights() {
    // §10: int_ior bk7 1.5046 / ext_ior air 1.000277 → η = 1.504183 [verified]; water / Vacuum
    // 1.333; int < ext is fine (a bubble): only each index must be ≥ 1. Mitsuba's: `DIELECTRIC_ETA`,
    // `DIELECTRIC_REFLECTION`, `DIELECTRIC_REFRACTION`.
    for &(props, eta) in DIELECTRIC_ETA {
        let Bsdf::Dielectric(d) = one_bsdf(&format!("<bsdf type=\"dielectric\">{props}</bsdf>")) else { panic!() };
        assert!((d.eta() - eta).abs() < 1e-6, "{props}: {}", d.eta());
    }
    // Weights: reflection (ξ = 0 ≤ R) carries specular_reflectance, refraction (ξ → 1)
    // specular_transmittance / η² entering the denser side (§10).
    let Bsdf::Dielectric(d) = one_bsdf(
        "<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1\"/>\
         <rgb name=\"specular_reflectance\" value=\"0.5 0.6 0.7\"/><float name=\"specular_transmittance\" value=\"0.9\"/></bsdf>",
    ) else {
        panic!()
    };
    let r = d.sample(Vec3::Z, 0.0, Vec2::ZERO).unwrap();
    assert_vec(r.weight, DIELECTRIC_REFLECTION.1.into(), 1e-6);
    assert_vec(r.wo, DIELECTRIC_REFLECTION.0.into(), 1e-6);
    let t = d.sample(Vec3::Z, 0.999, Vec2::ZERO).unwrap();
    assert_vec(t.weight, DIELECTRIC_REFRACTION.1.into(), 1e-6);
    assert_vec(t.wo, DIELECTRIC_REFRACTION.0.into(), 1e-6);
}

#[test]
fn conductors_fresnel_at_normal_incidence() {
    let f0 = |b: &Bsdf| match b {
        Bsdf::Conductor(c) => c.sample(Vec3::Z, 0.5, Vec2::splat(0.5)).unwrap().weight,
        other => panic!("{other:?}"),
    };
    // §10: default material "none" → η = 0, k = 1 → a perfect mirror. Mitsuba's F(0):
    // `CONDUCTOR_DEFAULT_F0`, `CONDUCTOR_AU_F0`, `CONDUCTOR_ETA_K_F0`, `CONDUCTOR_NONE_ETA_K_F0`.
    assert_vec(f0(&one_bsdf("<bsdf type=\"conductor\"/>")), CONDUCTOR_DEFAULT_F0.into(), 1e-6);
    // §10: normal-incidence Au in a white furnace → (0.96668, 0.80201, 0.32412) [verified].
    assert_vec(
        f0(&one_bsdf("<bsdf type=\"conductor\"><string name=\"material\" value=\"Au\"/></bsdf>")),
        CONDUCTOR_AU_F0.into(),
        2e-5,
    );
    // Explicit η = 1.5, k = 0: ((η−1)/(η+1))² = 0.04, times specular_reflectance.
    let b = one_bsdf(
        "<bsdf type=\"conductor\"><float name=\"eta\" value=\"1.5\"/><float name=\"k\" value=\"0\"/>\
         <rgb name=\"specular_reflectance\" value=\"1 0.5 0.25\"/></bsdf>",
    );
    assert_vec(f0(&b), CONDUCTOR_ETA_K_F0.into(), 1e-6);
    // "none" spelt out next to eta/k is accepted, as by Mitsuba.
    let b = one_bsdf(
        "<bsdf type=\"conductor\"><string name=\"material\" value=\"none\"/><float name=\"eta\" value=\"1.5\"/><float name=\"k\" value=\"0\"/></bsdf>",
    );
    assert_vec(f0(&b), CONDUCTOR_NONE_ETA_K_F0.into(), 1e-6);
}

#[test]
fn roughconductor_defaults_and_roughness() {
    // §10: Beckmann, α 0.1, sample_visible, material none (η 0, k 1), specular_reflectance 1
    // (Mitsuba's: `ROUGHCONDUCTOR_DEFAULTS`, `ROUGHCONDUCTOR_AU_OVER_MIRROR`).
    let want = |d, au, av, vis| RoughConductor::new(d, au, av, vis, Vec3::ZERO, Vec3::ONE, Vec3::ONE).unwrap();
    let rc = |props: &str| match one_bsdf(&format!("<bsdf type=\"roughconductor\">{props}</bsdf>")) {
        Bsdf::RoughConductor(r) => r,
        other => panic!("{other:?}"),
    };
    let (distribution, alpha_u, alpha_v, sample_visible) = ROUGHCONDUCTOR_DEFAULTS;
    assert_eq!(rc(""), want(distribution, alpha_u, alpha_v, sample_visible));
    assert_eq!(
        rc(
            "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.3\"/><boolean name=\"sample_visible\" value=\"false\"/>"
        ),
        want(MicrofacetDistribution::Ggx, 0.3, 0.3, false)
    );
    // Case-insensitive distribution names, as Mitsuba's to_lower.
    assert_eq!(rc("<string name=\"distribution\" value=\"GGX\"/>").distribution().kind, MicrofacetDistribution::Ggx);
    let d = rc("<float name=\"alpha_u\" value=\"0.1\"/><float name=\"alpha_v\" value=\"0.4\"/>").distribution();
    assert_eq!((d.alpha_u, d.alpha_v), (0.1, 0.4));
    // α = 0 is valid and raised to 1e-4 (Mitsuba's microfacet.h: max(α, 1e-4)).
    let d = rc("<float name=\"alpha\" value=\"0\"/>").distribution();
    assert_eq!((d.alpha_u, d.alpha_v), (1e-4, 1e-4));
    // A material: compare with the same conductor's normal-incidence Fresnel through eval:
    // at wi = wo = n the half vector is n and F(1) for Au is §10's (0.96668, 0.80201, 0.32412).
    let au = rc("<string name=\"material\" value=\"Au\"/>");
    let mirror = rc("");
    let ratio = au.eval(Vec3::Z, Vec3::Z) / mirror.eval(Vec3::Z, Vec3::Z);
    assert_vec(ratio, ROUGHCONDUCTOR_AU_OVER_MIRROR.into(), 2e-5);
}

#[test]
fn bsdf_errors() {
    assert_body_err("<bsdf type=\"hair\"/>", 1, "<bsdf type=\"hair\">: hair is outside matte's scope");
    assert_body_err(
        "<bsdf type=\"diffuse\">\n<float name=\"roughness\" value=\"0.1\"/>\n</bsdf>",
        2,
        "unreferenced property \"roughness\"",
    );
    assert_body_err("<bsdf type=\"diffuse\">\n<string name=\"reflectance\" value=\"red\"/>\n</bsdf>", 2, "wrong type");
    assert_body_err("<bsdf type=\"oren_nayar\">\n<rgb name=\"sigma\" value=\"0.1 0.2 0.3\"/>\n</bsdf>", 2, "sigma");
    assert_body_err("<bsdf type=\"eon\">\n<boolean name=\"roughness\" value=\"true\"/>\n</bsdf>", 2, "roughness");
    // Reflectance above 1 or below 0 (§2: "Invalid RGB reflectance value").
    for kind in std::iter::once("diffuse").chain(models_from_defaults().map(|m| m.name)) {
        assert_body_err(
            &format!("<bsdf type=\"{kind}\">\n<rgb name=\"reflectance\" value=\"1.2 0.5 0.5\"/>\n</bsdf>"),
            2,
            "reflectance",
        );
    }
    assert_body_err(
        "<bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"0.5 -0.1 0.5\"/>\n</bsdf>",
        2,
        "reflectance",
    );
    // A <float> reflectance may exceed 1 (Mitsuba's uniform texture), but not be negative or NaN.
    assert_body_err(
        "<bsdf type=\"diffuse\">\n<float name=\"reflectance\" value=\"-0.5\"/>\n</bsdf>",
        2,
        "must not be negative",
    );
    assert_body_err("<bsdf type=\"eon\">\n<float name=\"reflectance\" value=\"nan\"/>\n</bsdf>", 2, "must be finite");
    assert_body_err("<bsdf type=\"conductor\">\n<float name=\"eta\" value=\"inf\"/>\n</bsdf>", 2, "must be finite");
    // Magnitudes beyond 1e6 (matte's limit: the f32 kernels overflow far above it).
    assert_body_err("<bsdf type=\"roughconductor\">\n<float name=\"alpha\" value=\"1e7\"/>\n</bsdf>", 2, "up to 1e6");
    assert_body_err("<bsdf type=\"roughconductor\">\n<float name=\"k\" value=\"1e7\"/>\n</bsdf>", 2, "up to 1e6");
    assert_body_err("<bsdf type=\"dielectric\">\n<float name=\"int_ior\" value=\"1e7\"/>\n</bsdf>", 2, "up to 1e6");
    assert_body_err("<bsdf type=\"wolff\">\n<float name=\"int_ior\" value=\"1e7\"/>\n</bsdf>", 2, "up to 1e6");
    // Negative roughness / sigma.
    assert_body_err("<bsdf type=\"oren_nayar\">\n<float name=\"sigma\" value=\"-0.1\"/>\n</bsdf>", 2, "sigma");
    assert_body_err("<bsdf type=\"eon\">\n<float name=\"roughness\" value=\"-0.1\"/>\n</bsdf>", 2, "roughness");
    assert_body_err("<bsdf type=\"ginneken\">\n<float name=\"roughness\" value=\"-0.1\"/>\n</bsdf>", 2, "roughness");
    assert_body_err("<bsdf type=\"roughconductor\">\n<float name=\"alpha\" value=\"-0.1\"/>\n</bsdf>", 2, "alpha");
    assert_body_err(
        "<bsdf type=\"roughconductor\">\n<float name=\"alpha_u\" value=\"0.1\"/>\n<float name=\"alpha_v\" value=\"-0.1\"/>\n</bsdf>",
        3,
        "alpha_v",
    );
    assert_body_err("<bsdf type=\"oren_nayar\">\n<string name=\"model\" value=\"fancy\"/>\n</bsdf>", 2, "model");
    assert_body_err("<bsdf type=\"lambert\">\n<float name=\"sigma\" value=\"0.2\"/>\n</bsdf>", 2, "sigma");
    // IOR < 1.
    assert_body_err("<bsdf type=\"wolff\">\n<float name=\"int_ior\" value=\"0.8\"/>\n</bsdf>", 2, "int_ior");
    assert_body_err("<bsdf type=\"dielectric\">\n<float name=\"int_ior\" value=\"0.8\"/>\n</bsdf>", 2, "int_ior");
    assert_body_err("<bsdf type=\"dielectric\">\n<float name=\"ext_ior\" value=\"-1\"/>\n</bsdf>", 2, "ext_ior");
    assert_body_err(
        "<bsdf type=\"dielectric\">\n<string name=\"int_ior\" value=\"unobtainium\"/>\n</bsdf>",
        2,
        "unknown IOR name",
    );
    assert_body_err(
        "<bsdf type=\"wolff\">\n<string name=\"int_ior\" value=\"unobtainium\"/>\n</bsdf>",
        2,
        "unobtainium",
    );
    assert_body_err(
        "<bsdf type=\"dielectric\">\n<rgb name=\"specular_transmittance\" value=\"1.5 1 1\"/>\n</bsdf>",
        2,
        "specular_transmittance",
    );
    // Conductors.
    assert_body_err(
        "<bsdf type=\"roughconductor\">\n<float name=\"alpha_u\" value=\"0.1\"/>\n</bsdf>",
        1,
        "alpha_u and alpha_v",
    );
    assert_body_err(
        "<bsdf type=\"roughconductor\">\n<float name=\"alpha\" value=\"0.1\"/>\n<float name=\"alpha_u\" value=\"0.1\"/>\n<float name=\"alpha_v\" value=\"0.1\"/>\n</bsdf>",
        2,
        "unreferenced property \"alpha\"",
    );
    for kind in ["conductor", "roughconductor"] {
        assert_body_err(
            &format!(
                "<bsdf type=\"{kind}\">\n<string name=\"material\" value=\"Au\"/>\n<float name=\"eta\" value=\"1\"/>\n</bsdf>"
            ),
            1,
            "either material or eta/k",
        );
        assert_body_err(
            &format!("<bsdf type=\"{kind}\">\n<string name=\"material\" value=\"Xx\"/>\n</bsdf>"),
            2,
            "material",
        );
    }
    assert_body_err(
        "<bsdf type=\"roughconductor\">\n<string name=\"distribution\" value=\"phong\"/>\n</bsdf>",
        2,
        "beckmann or ggx",
    );
    // twosided.
    assert_body_err("<bsdf type=\"twosided\"/>", 1, "one or two nested BSDFs");
    assert_body_err(
        "<bsdf type=\"twosided\">\n<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/>\n</bsdf>",
        1,
        "found 3",
    );
    assert_body_err("<bsdf type=\"twosided\">\n<bsdf type=\"dielectric\"/>\n</bsdf>", 1, "transmissive");
    assert_body_err(
        "<bsdf type=\"twosided\">\n<bsdf type=\"diffuse\">\n<float name=\"alpha\" value=\"1\"/>\n</bsdf>\n</bsdf>",
        3,
        "unreferenced property \"alpha\"",
    );
}
