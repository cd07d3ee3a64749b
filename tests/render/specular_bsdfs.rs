//! Mitsuba's smooth `dielectric`, smooth `conductor` and `roughconductor` as the renderer
//! uses them (`render::bsdf`). Oracles: closed-form Fresnel in f64 (real and complex
//! arithmetic written here), the verified numbers of `docs/renderer-semantics.md` §10, numerical
//! quadrature, Mitsuba's chi-square test, and eval/pdf values of the real Mitsuba 3.9.1.

#[rustfmt::skip] // generated data, one configuration per line
mod mitsuba_reference;

use crate::common::{Pcg32, PcgExt, chi2_render_bsdf, sidak};
use glam::{DVec3, Vec2, Vec3};
use matte_brdf::quadrature::GaussLegendre;
use matte_render::bsdf::fresnel::fresnel_dielectric;
use matte_render::bsdf::vndf::erf_inv;
use matte_render::bsdf::{
    Conductor, Dielectric, MicrofacetDistribution, RoughConductor, conductor_material, fresnel_conductor,
};
use matte_render::shape::SurfaceInteraction;
use mitsuba_reference::MITSUBA_CONFIGS;
use std::f64::consts::PI;

const BECKMANN: MicrofacetDistribution = MicrofacetDistribution::Beckmann;
const GGX: MicrofacetDistribution = MicrofacetDistribution::Ggx;

fn rel(a: f32, b: f32) -> f32 {
    (a - b).abs() / b.abs().max(1e-30)
}

/// Unit direction at polar angle θ and azimuth φ (radians).
fn dir(theta: f64, phi: f64) -> Vec3 {
    Vec3::new((theta.sin() * phi.cos()) as f32, (theta.sin() * phi.sin()) as f32, theta.cos() as f32)
}

/// Uniform direction on the whole sphere.
fn sphere(rng: &mut Pcg32) -> Vec3 {
    let z = 2.0 * rng.next_f32() - 1.0;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * rng.next_f32();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

// ---------------------------------------------------------------------------------------------
// Independent f64 Fresnel formulas.

/// Dielectric R from the s/p amplitude form with explicit indices: light in medium `n_i`
/// hits medium `n_t` at cos θi ∈ [0, 1].
fn fresnel_rs_rp(cos_i: f64, n_i: f64, n_t: f64) -> f64 {
    let sin_t2 = (n_i / n_t).powi(2) * (1.0 - cos_i * cos_i);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (n_i * cos_i - n_t * cos_t) / (n_i * cos_i + n_t * cos_t);
    let rp = (n_t * cos_i - n_i * cos_t) / (n_t * cos_i + n_i * cos_t);
    0.5 * (rs * rs + rp * rp)
}

#[derive(Clone, Copy)]
struct C64(f64, f64);
impl C64 {
    fn add(self, o: C64) -> C64 {
        C64(self.0 + o.0, self.1 + o.1)
    }
    fn sub(self, o: C64) -> C64 {
        C64(self.0 - o.0, self.1 - o.1)
    }
    fn mul(self, o: C64) -> C64 {
        C64(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn div(self, o: C64) -> C64 {
        let d = o.0 * o.0 + o.1 * o.1;
        C64((self.0 * o.0 + self.1 * o.1) / d, (self.1 * o.0 - self.0 * o.1) / d)
    }
    fn abs2(self) -> f64 {
        self.0 * self.0 + self.1 * self.1
    }
    /// Principal square root (via polar form).
    fn sqrt(self) -> C64 {
        let r = self.abs2().sqrt().sqrt();
        let a = 0.5 * self.1.atan2(self.0);
        C64(r * a.cos(), r * a.sin())
    }
}

/// Conductor R with complex index n = η + ik: r_s = (cos θi − w)/(cos θi + w),
/// r_p = (n² cos θi − w)/(n² cos θi + w), w = n cos θt = √(n² − sin²θi) (decaying branch).
fn fresnel_complex(cos_i: f64, eta: f64, k: f64) -> f64 {
    let n2 = C64(eta, k).mul(C64(eta, k));
    let ci = C64(cos_i, 0.0);
    let w = n2.sub(C64(1.0 - cos_i * cos_i, 0.0)).sqrt();
    let rs = ci.sub(w).div(ci.add(w));
    let rp = n2.mul(ci).sub(w).div(n2.mul(ci).add(w));
    0.5 * (rs.abs2() + rp.abs2())
}

// ---------------------------------------------------------------------------------------------
// Fresnel functions.

#[test]
fn dielectric_fresnel_matches_the_amplitude_form_on_both_sides() {
    for &eta in &[1.5046f32 / 1.000277, 1.333, 2.419, 1.1] {
        for i in 0..=200 {
            let c = -1.0 + i as f32 / 100.0;
            let f = fresnel_dielectric(c, eta);
            // Outside (c ≥ 0): from index 1 into η; inside: from η into 1.
            let (n_i, n_t) = if c >= 0.0 { (1.0, eta as f64) } else { (eta as f64, 1.0) };
            let expected = if c == 0.0 { 1.0 } else { fresnel_rs_rp(c.abs() as f64, n_i, n_t) };
            assert!((f.r as f64 - expected).abs() < 2e-6, "eta={eta} cos={c}: {} vs {expected}", f.r);
            assert!((f.eta_it as f64 - n_t / n_i).abs() < 1e-6 && (f.eta_ti as f64 - n_i / n_t).abs() < 1e-6);
            // Snell: n_i sin θi = n_t sin θt; cos θt on the other side, 0 under TIR.
            let sin_t2 = (n_i / n_t).powi(2) * (1.0 - (c as f64).powi(2));
            let cos_t = if sin_t2 >= 1.0 { 0.0 } else { (1.0 - sin_t2).sqrt() };
            assert!((f.cos_t.abs() as f64 - cos_t).abs() < 2e-6, "cos_t {c}");
            assert!(f.cos_t == 0.0 || (f.cos_t < 0.0) == (c >= 0.0));
        }
    }
    // Index matched: no reflection at all (Mitsuba's special case), even at grazing.
    assert_eq!(fresnel_dielectric(0.3, 1.0).r, 0.0);
    assert_eq!(fresnel_dielectric(0.0, 1.0).r, 0.0);
}

#[test]
fn dielectric_fresnel_agrees_with_the_one_sided_brdf_version() {
    for &eta in &[1.5f32, 1.0 / 1.5] {
        for i in 0..=100 {
            let c = i as f32 / 100.0;
            let a = fresnel_dielectric(c, eta).r;
            let b = matte_brdf::fresnel::dielectric_reflectance(c as f64, eta as f64) as f32;
            assert!((a - b).abs() < 2e-6, "eta={eta} c={c}: {a} vs {b}");
        }
    }
}

#[test]
fn conductor_fresnel_matches_complex_arithmetic() {
    let cases =
        [(0.143036, 3.982997), (1.657501, 9.223811), (0.2, 0.0), (1.5, 0.0), (2.5, 1.3), (0.05, 0.4), (0.0, 1.0)];
    for &(eta, k) in &cases {
        for i in 0..=100 {
            let c = i as f32 / 100.0;
            let ours = fresnel_conductor(c, Vec3::splat(eta), Vec3::splat(k));
            let expected = fresnel_complex(c as f64, eta as f64, k as f64);
            for v in ours.to_array() {
                assert!((v as f64 - expected).abs() < 3e-6, "eta={eta} k={k} cos={c}: {v} vs {expected}");
            }
        }
    }
}

#[test]
fn conductor_fresnel_is_finite_at_its_singular_points() {
    // η = 1, k = 0 at grazing and η = k = 0 at normal incidence are 0/0 in the formula.
    for &(c, eta, k) in
        &[(0.0f32, 1.0f32, 0.0f32), (1.0, 0.0, 0.0), (0.0, 0.0, 0.0), (-0.5, 1.2, 0.3), (1.0000001, 0.2, 3.0)]
    {
        let f = fresnel_conductor(c, Vec3::splat(eta), Vec3::splat(k));
        assert!(f.is_finite() && f.min_element() >= 0.0 && f.max_element() <= 1.0 + 1e-6, "{c} {eta} {k}: {f}");
    }
}

// ---------------------------------------------------------------------------------------------
// Smooth dielectric.

fn glass() -> Dielectric {
    Dielectric::new(1.5046, 1.000277, Vec3::ONE, Vec3::ONE).unwrap()
}

#[test]
fn dielectric_reflects_and_refracts_by_snell_on_both_sides() {
    let (n_int, n_ext) = (1.5046f64, 1.000277f64);
    let d = glass();
    let mut rng = Pcg32::new(7, 1);
    for _ in 0..2000 {
        let wi = sphere(&mut rng);
        if wi.z == 0.0 {
            continue;
        }
        let r = d.sample(wi, 0.0, Vec2::ZERO).unwrap();
        assert_eq!(r.wo, Vec3::new(-wi.x, -wi.y, wi.z), "mirror");
        assert!(r.delta && r.eta == 1.0);
        // u_lobe just below 1 refracts unless TIR.
        let (n_i, n_t) = if wi.z > 0.0 { (n_ext, n_int) } else { (n_int, n_ext) };
        let sin_i = ((1.0 - (wi.z as f64).powi(2)).max(0.0)).sqrt();
        let t = d.sample(wi, 0.999_999_9, Vec2::ZERO).unwrap();
        if n_i * sin_i / n_t >= 1.0 + 1e-6 {
            assert_eq!(t.wo, Vec3::new(-wi.x, -wi.y, wi.z), "TIR must reflect: {wi}");
            continue;
        }
        if n_i * sin_i / n_t > 1.0 - 1e-4 {
            continue; // too close to the critical angle for f32
        }
        let wo = t.wo;
        assert!((wo.length() - 1.0).abs() < 1e-5);
        assert!(wo.z * wi.z < 0.0, "refraction crosses the interface");
        let sin_o = ((1.0 - (wo.z as f64).powi(2)).max(0.0)).sqrt();
        assert!((n_i * sin_i - n_t * sin_o).abs() < 1e-5, "Snell: wi={wi} wo={wo}");
        // In the plane of incidence, on the other side of the normal.
        let cross = wi.x * wo.y - wi.y * wo.x;
        assert!(cross.abs() < 1e-5 && wi.x * wo.x + wi.y * wo.y <= 0.0);
    }
}

#[test]
fn dielectric_total_internal_reflection_always_reflects() {
    let d = glass();
    // From inside at 60° > critical angle asin(1.000277/1.5046) = 41.7°.
    let wi = dir(120f64.to_radians(), 0.3);
    for &u in &[0.0f32, 0.5, 0.999_999_9, 1.0] {
        let s = d.sample(wi, u, Vec2::ZERO).unwrap();
        assert_eq!(s.wo, Vec3::new(-wi.x, -wi.y, wi.z));
        assert_eq!((s.pdf, s.eta, s.weight), (1.0, 1.0, Vec3::ONE));
    }
}

#[test]
fn dielectric_chooses_reflection_with_probability_fresnel_r() {
    let (n_int, n_ext) = (1.5046f64, 1.000277f64);
    let d = glass();
    for &theta in &[0.0f64, 20.0, 45.0, 70.0, 89.0, 110.0, 140.0, 160.0, 180.0] {
        let wi = dir(theta.to_radians(), 1.1);
        let (n_i, n_t) = if wi.z > 0.0 { (n_ext, n_int) } else { (n_int, n_ext) };
        let r = fresnel_rs_rp(wi.z.abs() as f64, n_i, n_t) as f32;
        // The lobe switches exactly at u_lobe = R: reflect at or below, refract above.
        let below = d.sample(wi, r * (1.0 - 1e-4), Vec2::ZERO).unwrap();
        let above = d.sample(wi, (r * (1.0 + 1e-4)).min(0.9999), Vec2::ZERO).unwrap();
        assert!(below.wo.z * wi.z > 0.0, "θ={theta}: reflection below R");
        assert!((below.pdf - r).abs() < 2e-6, "θ={theta}: pdf {} vs R {r}", below.pdf);
        if r < 0.9999 {
            assert!(above.wo.z * wi.z < 0.0, "θ={theta}: refraction above R");
            assert!((above.pdf - (1.0 - r)).abs() < 2e-6);
        }
    }
}

#[test]
fn dielectric_weights_and_eta_entering_and_leaving() {
    let (rho_r, rho_t) = (Vec3::new(0.9, 0.5, 0.25), Vec3::new(0.8, 0.6, 0.4));
    let d = Dielectric::new(1.5, 1.0, rho_r, rho_t).unwrap();
    let into = dir(30f64.to_radians(), 0.0);
    let out = dir(160f64.to_radians(), 0.0);
    assert_eq!(d.sample(into, 0.0, Vec2::ZERO).unwrap().weight, rho_r);
    assert_eq!(d.sample(out, 0.0, Vec2::ZERO).unwrap().weight, rho_r);
    // Entering the denser side: ×(1/1.5)², bs.eta = 1.5; leaving: ×1.5², bs.eta = 1/1.5.
    let t_in = d.sample(into, 0.99, Vec2::ZERO).unwrap();
    assert!((t_in.weight - rho_t / 2.25).abs().max_element() < 1e-6, "{}", t_in.weight);
    assert!((t_in.eta - 1.5).abs() < 1e-6 && t_in.delta);
    let t_out = d.sample(out, 0.99, Vec2::ZERO).unwrap();
    assert!((t_out.weight - rho_t * 2.25).abs().max_element() < 1e-5, "{}", t_out.weight);
    assert!((t_out.eta - 1.0 / 1.5).abs() < 1e-6);
    // A round trip through a slab: the η² factors cancel (with RR's η² bookkeeping too).
    assert!((t_in.eta * t_out.eta - 1.0).abs() < 1e-6);
}

#[test]
fn glass_seen_through_one_interface_gives_the_doc_0_424() {
    // §10: an emitter seen inside a glass cube (bk7 in air, normal incidence) renders as
    // (1 − R₀)/η² = 0.424. Expected weight over the lobe choice, by a fine u_lobe grid.
    // Checked against Mitsuba 3.9.1 (scalar_rgb) by validation/verify_semantics.py -k §10.
    let d = glass();
    let n = 100_000;
    let mut sum = 0.0f64;
    for i in 0..n {
        let s = d.sample(Vec3::Z, (i as f32 + 0.5) / n as f32, Vec2::ZERO).unwrap();
        if s.wo.z < 0.0 {
            sum += s.weight.x as f64;
        }
    }
    let e = sum / n as f64;
    assert!((e - 0.424).abs() < 5e-4, "{e}");
    assert!((d.eta() - 1.504183).abs() < 1e-6, "§10 default η");
}

#[test]
fn dielectric_rejects_bad_parameters() {
    assert!(Dielectric::new(-1.5, 1.0, Vec3::ONE, Vec3::ONE).unwrap_err().contains("int_ior"));
    assert!(Dielectric::new(1.5, 0.0, Vec3::ONE, Vec3::ONE).unwrap_err().contains("ext_ior"));
    assert!(Dielectric::new(f32::NAN, 1.0, Vec3::ONE, Vec3::ONE).is_err());
    assert!(
        Dielectric::new(1.5, 1.0, Vec3::new(0.5, -0.1, 0.5), Vec3::ONE).unwrap_err().contains("specular_reflectance")
    );
    assert!(
        Dielectric::new(1.5, 1.0, Vec3::ONE, Vec3::splat(f32::INFINITY))
            .unwrap_err()
            .contains("specular_transmittance")
    );
}

// ---------------------------------------------------------------------------------------------
// Smooth conductor.

#[test]
fn conductor_none_is_a_perfect_mirror_and_one_sided() {
    let (eta, k) = conductor_material("none").unwrap();
    assert_eq!((eta, k), (Vec3::ZERO, Vec3::ONE));
    let c = Conductor::new(eta, k, Vec3::ONE).unwrap();
    let mut rng = Pcg32::new(3, 5);
    for _ in 0..1000 {
        let wi = rng.upper_hemisphere();
        if wi.z <= 0.0 {
            continue;
        }
        let s = c.sample(wi, rng.next_f32(), rng.next_vec2()).unwrap();
        assert_eq!(s.wo, Vec3::new(-wi.x, -wi.y, wi.z));
        assert!((s.weight - Vec3::ONE).abs().max_element() < 1e-6, "{wi}: {}", s.weight);
        assert!(s.delta && s.eta == 1.0 && s.pdf == 1.0);
        assert!(c.sample(-wi, 0.5, Vec2::ZERO).is_none(), "black from the back");
    }
    assert!(c.sample(Vec3::X, 0.5, Vec2::ZERO).is_none(), "grazing: cos θi must be > 0");
}

#[test]
fn conductor_gold_at_normal_incidence_gives_the_doc_furnace_values() {
    // §10 [verified]. Checked against Mitsuba 3.9.1 (scalar_rgb) by validation/verify_semantics.py -k §10.
    let (eta, k) = conductor_material("Au").unwrap();
    let spec = Vec3::new(0.5, 1.0, 0.25);
    let c = Conductor::new(eta, k, spec).unwrap();
    let w = c.sample(Vec3::Z, 0.5, Vec2::splat(0.5)).unwrap().weight;
    let expected = Vec3::new(0.96668, 0.80201, 0.32412) * spec;
    assert!((w - expected).abs().max_element() < 1e-5, "{w} vs {expected}");
}

#[test]
fn conductor_materials_are_named_as_in_mitsuba() {
    for m in ["Au", "Cu", "Ag", "Al"] {
        let (eta, k) = conductor_material(m).unwrap();
        assert!(eta.min_element() > 0.0 && k.min_element() > 1.0, "{m}");
    }
    let err = conductor_material("unobtainium").unwrap_err();
    for m in ["none", "Au", "Cu", "Ag", "Al", "unobtainium"] {
        assert!(err.contains(m), "{err}");
    }
    assert!(Conductor::new(Vec3::ZERO, Vec3::splat(f32::NAN), Vec3::ONE).unwrap_err().contains("k"));
}

// ---------------------------------------------------------------------------------------------
// Rough conductor.

fn gold() -> (Vec3, Vec3) {
    conductor_material("Au").unwrap()
}

fn rough(kind: MicrofacetDistribution, au: f32, av: f32, visible: bool) -> RoughConductor {
    let (eta, k) = gold();
    RoughConductor::new(kind, au, av, visible, eta, k, Vec3::ONE).unwrap()
}

/// Every (distribution, α_u, α_v, sample_visible) the statistical tests run over.
fn rough_configs() -> Vec<(MicrofacetDistribution, f32, f32, bool)> {
    let mut v = Vec::new();
    for kind in [BECKMANN, GGX] {
        for (au, av) in [(0.2, 0.2), (0.6, 0.6), (0.15, 0.45)] {
            for visible in [true, false] {
                v.push((kind, au, av, visible));
            }
        }
    }
    v
}

#[test]
fn rough_conductor_matches_mitsuba_3_9_1() {
    let (eta, k) = gold();
    for &(kind, au, av, spec, rows) in MITSUBA_CONFIGS {
        for visible in [true, false] {
            let b = RoughConductor::new(kind, au, av, visible, eta, k, Vec3::from(spec)).unwrap();
            for &(wi, wo, eval, pdf_vis, pdf_plain) in rows {
                let (wi, wo) = (Vec3::from(wi), Vec3::from(wo));
                let ctx = format!("{kind:?} α=({au},{av}) visible={visible} wi={wi} wo={wo}");
                let e = b.eval(wi, wo);
                for (x, y) in e.to_array().into_iter().zip(eval) {
                    assert!(if y == 0.0 { x == 0.0 } else { rel(x, y) < 1e-4 }, "eval {ctx}: {e} vs {eval:?}");
                }
                let p = b.pdf(wi, wo);
                let expected = if visible { pdf_vis } else { pdf_plain };
                assert!(
                    if expected == 0.0 { p == 0.0 } else { rel(p, expected) < 1e-4 },
                    "pdf {ctx}: {p} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn rough_conductor_samples_follow_pdf_chi_square() {
    // Beyond ~80° the lobe is squeezed against the horizon into a few cells that the helper's
    // 4×4 trapezoid rule cannot integrate (plain D·cos sampling fails there too); grazing
    // incidence is covered by the weight and quadrature tests.
    let incidences = [0.0f64, 35.0, 75.0];
    let configs = rough_configs();
    let level = sidak(configs.len() * incidences.len());
    let mut seed = 11;
    for (kind, au, av, visible) in configs {
        for &theta in &incidences {
            let wi = dir(theta.to_radians(), 0.7);
            seed += 1;
            let si = SurfaceInteraction::at_uv(Vec2::ZERO);
            let out = chi2_render_bsdf(&rough(kind, au, av, visible), &si, wi, seed, 4)
                .unwrap_or_else(|e| panic!("{kind:?} α=({au},{av}) visible={visible} θ={theta}: {e}"));
            assert!(
                out.p_value > level,
                "{kind:?} α=({au},{av}) visible={visible} θ={theta}: p = {} (χ² {} / {} dof)",
                out.p_value,
                out.statistic,
                out.dof
            );
        }
    }
}

#[test]
fn rough_conductor_sample_weight_is_eval_over_pdf() {
    let mut rng = Pcg32::new(99, 3);
    let mut configs = rough_configs();
    configs.extend([(BECKMANN, 0.05, 0.05, true), (GGX, 0.05, 0.05, false), (GGX, 0.02, 0.3, true)]);
    for (kind, au, av, visible) in configs {
        let b = rough(kind, au, av, visible);
        for &theta in &[0.0f64, 30.0, 60.0, 85.0] {
            let wi = dir(theta.to_radians(), 2.0);
            let mut n = 0;
            for _ in 0..4000 {
                let Some(s) = b.sample(wi, rng.next_f32(), rng.next_vec2()) else { continue };
                n += 1;
                let ctx = format!("{kind:?} α=({au},{av}) visible={visible} wi={wi} wo={}", s.wo);
                assert!((s.wo.length() - 1.0).abs() < 1e-5 && s.wo.z > 0.0, "{ctx}");
                assert!(!s.delta && s.eta == 1.0);
                let (e, p) = (b.eval(wi, s.wo), b.pdf(wi, s.wo));
                assert!(rel(s.pdf, p) < 2e-3, "pdf {ctx}: {} vs {p}", s.pdf);
                for (w, x) in s.weight.to_array().into_iter().zip((e / p).to_array()) {
                    assert!((w - x).abs() <= 2e-3 * x.max(1e-3), "weight {ctx}: {} vs {}", s.weight, e / p);
                }
            }
            assert!(n > 1000, "{kind:?} α=({au},{av}) θ={theta}: only {n} valid samples");
        }
    }
}

/// ∫ pdf(wi, wo) dωo by Gauss–Legendre in spherical coordinates around the mirror direction,
/// with the polar range split at multiples of the largest α so that sharp lobes are resolved.
fn integrate_pdf(b: &RoughConductor, wi: Vec3) -> f64 {
    let axis = DVec3::new(-wi.x as f64, -wi.y as f64, wi.z as f64).normalize();
    let t = if axis.z.abs() < 0.9 { DVec3::Z.cross(axis) } else { DVec3::X.cross(axis) }.normalize();
    let s = axis.cross(t);
    let a = b.distribution().alpha_u.max(b.distribution().alpha_v) as f64;
    // Also split at π/2, where the horizon cuts the lobe at normal incidence.
    let mut edges = vec![0.0, PI / 2.0, PI];
    edges.extend([0.5, 1.0, 2.0, 4.0, 8.0].iter().map(|m| m * a).filter(|&x| x < PI));
    edges.sort_by(f64::total_cmp);
    let gl = GaussLegendre::new(64);
    let mut total = 0.0;
    for w in edges.windows(2) {
        for (theta, wt) in gl.mapped(w[0], w[1]) {
            for q in 0..4 {
                let (p0, p1) = (q as f64 * PI / 2.0, (q + 1) as f64 * PI / 2.0);
                for (phi, wp) in gl.mapped(p0, p1) {
                    let d = axis * theta.cos() + (t * phi.cos() + s * phi.sin()) * theta.sin();
                    total += wt * wp * theta.sin() * b.pdf(wi, d.as_vec3()) as f64;
                }
            }
        }
    }
    total
}

#[test]
fn rough_conductor_pdf_integrates_to_at_most_one() {
    let mut configs = rough_configs();
    configs.extend([
        (BECKMANN, 0.05, 0.05, true),
        (GGX, 0.05, 0.05, false),
        (GGX, 0.05, 0.12, true),
        (BECKMANN, 1.0, 1.0, false),
    ]);
    for (kind, au, av, visible) in configs {
        let b = rough(kind, au, av, visible);
        for &theta in &[0.0f64, 40.0, 80.0] {
            let i = integrate_pdf(&b, dir(theta.to_radians(), 0.4));
            let ctx = format!("{kind:?} α=({au},{av}) visible={visible} θ={theta}");
            assert!(i <= 1.0 + 1e-3, "{ctx}: ∫pdf = {i}");
            assert!(i > 0.3, "{ctx}: ∫pdf = {i}");
            // Normal incidence, isotropic: both samplers' pdfs integrate to the probability
            // that the half vector is within 45° of the normal (so that wo is above the
            // surface): 1 − exp(−1/α²) for Beckmann, 1/(1 + α²) for GGX (closed-form CDFs of
            // tan²θh). ≈ 1 for small Beckmann α.
            if theta == 0.0 && au == av {
                let a2 = (au as f64).powi(2);
                let expected = match kind {
                    MicrofacetDistribution::Beckmann => 1.0 - (-1.0 / a2).exp(),
                    MicrofacetDistribution::Ggx => 1.0 / (1.0 + a2),
                };
                assert!((i - expected).abs() < 1e-3, "{ctx}: ∫pdf = {i}, expected {expected}");
            }
        }
    }
}

#[test]
fn rough_conductor_eval_is_reciprocal() {
    let mut rng = Pcg32::new(5, 8);
    for (kind, au, av, _) in rough_configs() {
        let b = rough(kind, au, av, true);
        for _ in 0..2000 {
            let (wi, wo) = (rng.upper_hemisphere(), rng.upper_hemisphere());
            if wi.z < 1e-3 || wo.z < 1e-3 {
                continue;
            }
            let (f1, f2) = (b.eval(wi, wo) / wo.z, b.eval(wo, wi) / wi.z);
            for (x, y) in f1.to_array().into_iter().zip(f2.to_array()) {
                assert!((x - y).abs() <= 1e-4 * x.abs().max(1e-20), "{kind:?} wi={wi} wo={wo}: {f1} vs {f2}");
            }
        }
    }
}

#[test]
fn rough_conductor_eval_is_zero_below_the_surface() {
    let b = rough(GGX, 0.3, 0.3, true);
    let (up, down) = (dir(0.3, 0.0), dir(2.5, 1.0));
    assert_eq!(b.eval(up, down), Vec3::ZERO);
    assert_eq!(b.eval(down, up), Vec3::ZERO);
    assert_eq!((b.pdf(up, down), b.pdf(down, up)), (0.0, 0.0));
    assert!(b.sample(down, 0.5, Vec2::splat(0.5)).is_none());
    assert!(b.sample(Vec3::X, 0.5, Vec2::splat(0.5)).is_none());
}

#[test]
fn nothing_returns_nan_or_inf() {
    let (eta, k) = gold();
    let mut bsdfs = Vec::new();
    for kind in [BECKMANN, GGX] {
        for (au, av) in [(0.0, 0.0), (1e-4, 1e-4), (0.1, 0.1), (0.01, 2.0), (5.0, 5.0), (100.0, 0.3)] {
            for visible in [true, false] {
                bsdfs.push(RoughConductor::new(kind, au, av, visible, eta, k, Vec3::ONE).unwrap());
            }
        }
    }
    let glass = glass();
    let mirror = Conductor::new(eta, k, Vec3::ONE).unwrap();
    let tiny = 1e-30f32;
    let mut dirs = vec![
        Vec3::Z,
        -Vec3::Z,
        Vec3::X,
        Vec3::new(0.0, -1.0, 0.0),
        Vec3::new((1.0 - tiny * tiny).sqrt(), 0.0, tiny),
        Vec3::new(0.0, 1.0, 1e-38),
        Vec3::new(0.6, 0.8, -1e-20),
        Vec3::new(1e-20, 0.0, 1.0),
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(-0.6, 0.0, 0.8),
    ];
    let mut rng = Pcg32::new(1, 2);
    dirs.extend((0..60).map(|_| sphere(&mut rng)));
    let us = [0.0f32, 1e-7, 0.5, 0.999_999_94, 1.0];
    for &wi in &dirs {
        for &wo in &dirs {
            for b in &bsdfs {
                let (e, p) = (b.eval(wi, wo), b.pdf(wi, wo));
                assert!(
                    e.is_finite() && e.min_element() >= 0.0 && p.is_finite() && p >= 0.0,
                    "{b:?} {wi} {wo}: {e} {p}"
                );
            }
        }
        let check = |s: Option<matte_render::bsdf::BsdfSample>, what: &str| {
            if let Some(s) = s {
                assert!(
                    s.wo.is_finite() && s.weight.is_finite() && s.pdf.is_finite() && s.eta.is_finite(),
                    "{what} {wi}: {s:?}"
                );
                assert!(s.weight.min_element() >= 0.0 && s.pdf >= 0.0, "{what} {wi}: {s:?}");
            }
        };
        for &u0 in &us {
            for &u1 in &us {
                let u = Vec2::new(u0, u1);
                for b in &bsdfs {
                    check(b.sample(wi, u0, u), "rough");
                }
                check(glass.sample(wi, u0, u), "glass");
                check(mirror.sample(wi, u0, u), "mirror");
            }
        }
        for _ in 0..200 {
            let (ul, u) = (rng.next_f32(), rng.next_vec2());
            for b in &bsdfs {
                check(b.sample(wi, ul, u), "rough");
            }
        }
    }
}

#[test]
fn rough_conductor_rejects_bad_parameters() {
    let (eta, k) = gold();
    let e = RoughConductor::new(GGX, -0.1, 0.1, true, eta, k, Vec3::ONE).unwrap_err();
    assert!(e.contains("alpha_u"), "{e}");
    assert!(RoughConductor::new(GGX, 0.1, f32::NAN, true, eta, k, Vec3::ONE).unwrap_err().contains("alpha_v"));
    assert!(
        RoughConductor::new(GGX, 0.1, 0.1, true, Vec3::splat(f32::INFINITY), k, Vec3::ONE).unwrap_err().contains("eta")
    );
    assert!(RoughConductor::new(GGX, 0.1, 0.1, true, eta, k, -Vec3::ONE).unwrap_err().contains("specular_reflectance"));
    // α = 0 is accepted and clamped to 1e-4, as Mitsuba does.
    let b = RoughConductor::new(BECKMANN, 0.0, 0.0, true, eta, k, Vec3::ONE).unwrap();
    assert_eq!(b.distribution().alpha_u, 1e-4);
}

#[test]
fn erf_inv_inverts_erf() {
    for i in -999..=999 {
        let x = i as f32 / 1000.0;
        let y = erf_inv(x);
        let back = libm::erf(y as f64);
        // f32 resolution of x near ±1 limits the round trip there.
        let tol = if x.abs() > 0.99 { 3e-5 } else { 1e-6 };
        assert!((back - x as f64).abs() < tol, "{x}: erf({y}) = {back}");
    }
}

#[test]
fn beckmann_visible_slopes_invert_their_cdf() {
    // α = 1 and wi in the xz-plane: no stretch or rotation, so the sampled normal's slopes
    // x̃ = −m.x/m.z, ỹ = −m.y/m.z must satisfy F(x̃) = u.x with the visible-slope CDF
    // F(x) ∝ 1 + erf x + tan θ/√π·exp(−x²) on x < cot θ, and (1 + erf ỹ)/2 = u.y.
    for &theta in &[0.0f64, 30.0, 60.0, 75.0, 85.0, 89.0] {
        let wi = dir(theta.to_radians(), 0.0);
        let tan = (wi.x / wi.z) as f64;
        let cdf = |x: f64| 1.0 + libm::erf(x) + tan / PI.sqrt() * (-x * x).exp();
        let total = cdf(1.0 / tan);
        for i in 1..1000 {
            let u = Vec2::new(i as f32 / 1000.0, 1.0 - i as f32 / 1000.0);
            let m = matte_render::bsdf::vndf::sample_beckmann(wi, 1.0, 1.0, u);
            let (x, y) = ((-m.x / m.z) as f64, (-m.y / m.z) as f64);
            assert!((cdf(x) / total - u.x as f64).abs() < 2e-6, "θ={theta} u={u}: F(x̃={x}) = {}", cdf(x) / total);
            assert!((0.5 * (1.0 + libm::erf(y)) - u.y as f64).abs() < 2e-6, "θ={theta} u={u}: ỹ={y}");
        }
    }
}
