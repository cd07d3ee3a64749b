//! Film, reconstruction filters and image I/O (`rust/render/src/film`, `rust/render/src/image_io.rs`).
//! Oracles: the verified numbers of `docs/renderer-semantics.md` §6 (Gaussian table,
//! half-bright/half-dark edge test), closed forms (tent table, constant images, plain means),
//! and EXR files written by Mitsuba 3.9.1 itself when its venv is present.

use crate::common::{self, Pcg32, PcgExt};
use glam::{Vec2, Vec3};
use matte_render::film::{CropWindow, Film, GAUSSIAN_FIT, Image, ReconstructionFilter, SplatWeights, Tile};
use matte_render::image_io::{read_exr, write_exr, write_png};
use std::path::PathBuf;
use std::process::Command;

/// §6 [verified]: Mitsuba's discretised default Gaussian (σ = 0.5), k = 0..30
/// (`film/gaussian_table.json`, checked against Mitsuba 3.9.1 by `film/generate_reference.py`).
fn mitsuba_gaussian_table() -> Vec<f32> {
    let doc: serde_json::Value = serde_json::from_str(include_str!("film/gaussian_table.json")).unwrap();
    doc["values"].as_array().unwrap().iter().map(|v| v.as_f64().unwrap() as f32).collect()
}

fn temp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("matte-film-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Renders `samples` the way the path tracer will: tile by tile, each sample put into the
/// block of the tile holding its pixel, blocks added to the film.
fn render(film: &mut Film, tile_size: u32, samples: &[(Vec2, Vec3)]) -> Image {
    for tile in film.tiles(tile_size) {
        let mut block = film.new_block(&tile);
        for &(pos, rgb) in samples {
            if in_tile(&tile, pos) {
                block.put(pos, rgb);
            }
        }
        film.put_block(&block);
    }
    film.develop()
}

fn in_tile(t: &Tile, p: Vec2) -> bool {
    let (x, y) = (p.x.floor() as i64, p.y.floor() as i64);
    let (ox, oy) = (t.offset[0] as i64, t.offset[1] as i64);
    x >= ox && x < ox + t.size[0] as i64 && y >= oy && y < oy + t.size[1] as i64
}

/// `spp` uniform samples in every pixel of the crop window, radiance from `f(position)`.
fn sample_crop(film: &Film, spp: u32, seed: u64, mut f: impl FnMut(Vec2) -> Vec3) -> Vec<(Vec2, Vec3)> {
    let c = film.crop();
    let mut rng = Pcg32::new(seed, 7);
    let mut out = Vec::new();
    for y in c.offset[1]..c.offset[1] + c.size[1] {
        for x in c.offset[0]..c.offset[0] + c.size[0] {
            for _ in 0..spp {
                let p = Vec2::new(x as f32, y as f32) + rng.next_vec2();
                out.push((p, f(p)));
            }
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// filters

#[test]
fn gaussian_table_matches_mitsuba() {
    // The §6 numbers have 5 decimals: agreement to their rounding (5e-6, plus f32 slack).
    let t = ReconstructionFilter::default().table();
    assert_eq!(ReconstructionFilter::default(), ReconstructionFilter::Gaussian { stddev: 0.5 });
    assert_eq!(t.radius(), 2.0);
    for (k, (&ours, &mitsuba)) in t.values().iter().zip(&mitsuba_gaussian_table()).enumerate() {
        assert!((ours - mitsuba).abs() <= 6e-6, "bin {k}: {ours} vs Mitsuba {mitsuba}");
    }
    assert_eq!(t.values()[31], 0.0);
}

#[test]
fn gaussian_fit_is_the_minimax_approximation() {
    // p(t) ≈ exp(−t/2) on [0, 16] with equioscillating relative error: its extremes are all
    // ±E, E ≈ 4.04e-4, alternating in sign 11 times (Chebyshev alternation theorem).
    let p = |t: f64| GAUSSIAN_FIT.iter().rev().fold(0.0, |a, &c| a * t + c);
    let rel: Vec<f64> = (0..=16_000).map(|i| i as f64 * 1e-3).map(|t| p(t) / (-t / 2.0).exp() - 1.0).collect();
    let e = rel.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    assert!((4.0e-4..4.1e-4).contains(&e), "max relative error {e}");
    let mut signs = vec![rel[0].signum()];
    for r in &rel {
        if r.abs() > 0.99 * e && r.signum() != *signs.last().unwrap() {
            signs.push(r.signum());
        }
    }
    assert!(rel[0].abs() > 0.99 * e && signs.len() == 11, "alternation points: {}", signs.len());
    // §6: the filter built on it differs from the exact shifted Gaussian by ≤ 4.2e-4.
    let g = ReconstructionFilter::GAUSSIAN;
    for i in 0..=400 {
        let x = i as f32 * 0.005;
        let exact = ((-2.0 * (x as f64).powi(2)).exp() - (-8.0f64).exp()).max(0.0);
        assert!((g.eval(x) as f64 - exact).abs() <= 4.2e-4, "x = {x}");
    }
}

#[test]
fn tent_table_is_the_left_endpoint_discretisation() {
    for radius in [1.0f32, 1.5, 3.0] {
        let t = ReconstructionFilter::Tent { radius }.table();
        for k in 0..31 {
            assert!((t.values()[k] - (1.0 - k as f32 / 31.0)).abs() < 1e-6, "r {radius} bin {k}");
        }
        assert_eq!(t.values()[31], 0.0);
        // Lookup: bin = trunc(|x|·31/r); both signs; |x| ≥ r → 0.
        let bin_width = radius / 31.0;
        assert_eq!(t.eval(0.3 * bin_width), t.values()[0]);
        assert_eq!(t.eval(-(5.7 * bin_width)), t.values()[5]);
        assert_eq!(t.eval(radius), 0.0);
        assert_eq!(t.eval(-2.0 * radius), 0.0);
    }
    assert_eq!(ReconstructionFilter::TENT, ReconstructionFilter::Tent { radius: 1.0 });
}

/// The negative-lobed filters against Mitsuba 3.9.1's own `rfilter.eval` and
/// `eval_discretized` (`mi.load_dict({'type': 'mitchell'})` etc. in `scalar_rgb`, printed to 7
/// digits), and closed forms: every Mitchell–Netravali cubic integrates to 1.
/// Generated by tests/render/film/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
#[test]
fn mitchell_catmullrom_lanczos_match_mitsuba() {
    let xs = [0.0, 0.3, 0.75, 1.0, 1.4, 1.9, 2.5];
    let cases: [(ReconstructionFilter, f32, [f32; 7], [f32; 3]); 5] = [
        (
            ReconstructionFilter::Mitchell { b: 1.0 / 3.0, c: 1.0 / 3.0 },
            2.0,
            [0.888889, 0.740389, 0.2560764, 0.0555556, -0.0359999, -0.0029442, 0.0],
            [0.888889, 0.7757451, -0.0343129],
        ),
        (
            ReconstructionFilter::Mitchell { b: 0.2, c: 0.4 },
            2.0,
            [0.9333333, 0.7704333, 0.2442707, 0.0333332, -0.0504004, -0.003567, 0.0],
            [0.9333333, 0.8091616, -0.0501273],
        ),
        (
            ReconstructionFilter::CatmullRom,
            2.0,
            [1.0, 0.8155, 0.2265625, 0.0, -0.072, -0.0045002, 0.0],
            [1.0, 0.8592864, -0.0738479],
        ),
        (
            ReconstructionFilter::Lanczos { lobes: 3 },
            3.0,
            [1.0, 0.8443431, 0.2701898, 0.0, -0.1466851, -0.0237699, 0.0243171],
            [1.0, 0.8537122, -0.1469572],
        ),
        (
            ReconstructionFilter::Lanczos { lobes: 2 },
            2.0,
            [1.0, 0.8269746, 0.2353467, 0.0, -0.0795496, -0.0027135, 0.0],
            [1.0, 0.8697127, -0.0841129],
        ),
    ];
    for (f, radius, eval, table) in cases {
        assert_eq!(f.radius(), radius, "{f:?}");
        f.validate().unwrap();
        for (&x, &want) in xs.iter().zip(&eval) {
            assert!((f.eval(x) - want).abs() < 2e-6, "{f:?} eval({x}) = {} not {want}", f.eval(x));
            assert_eq!(f.eval(-x), f.eval(x), "{f:?} is even");
        }
        let t = f.table();
        for (&x, &want) in [0.0f32, 0.3, 1.4].iter().zip(&table) {
            assert!((t.eval(x) - want).abs() < 2e-6, "{f:?} table({x}) = {} not {want}", t.eval(x));
        }
    }
    for (b, c) in [(1.0 / 3.0, 1.0 / 3.0), (0.0, 0.5), (1.0, 0.0), (0.2, 0.4)] {
        let f = ReconstructionFilter::Mitchell { b, c };
        let n = 100_000;
        let integral: f64 =
            (0..n).map(|i| f.eval(-2.0 + 4.0 * (i as f32 + 0.5) / n as f32) as f64).sum::<f64>() * 4.0 / n as f64;
        assert!((integral - 1.0).abs() < 1e-4, "B = {b}, C = {c}: ∫ = {integral}");
    }
    assert!(ReconstructionFilter::Mitchell { b: f32::NAN, c: 0.0 }.validate().is_err());
}

#[test]
fn border_sizes_follow_mitsuba() {
    // ceil(r − 0.5 − 2·RayEpsilon); the box filter has none.
    // Generated by tests/render/film/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    let cases = [
        (ReconstructionFilter::Box, 0),
        (ReconstructionFilter::TENT, 1),
        (ReconstructionFilter::Tent { radius: 0.5 }, 0),
        (ReconstructionFilter::Tent { radius: 1.6 }, 2),
        (ReconstructionFilter::GAUSSIAN, 2),
        (ReconstructionFilter::Gaussian { stddev: 1.0 }, 4),
    ];
    for (f, b) in cases {
        assert_eq!(f.border_size(), b, "{f:?}");
    }
}

#[test]
fn splat_weights_come_from_the_table() {
    // Two samples on the same row, colours 1 and 0: a pixel's value is wA/(wA + wB) with
    // w = table[trunc(|i + 0.5 − f|·31/2)] (the y weights cancel). Offsets are chosen away
    // from bin edges; the expected bins use Mitsuba's verified table.
    let t = &mitsuba_gaussian_table();
    let a = Vec2::new(2.3, 2.5);
    let b = Vec2::new(3.9, 2.5);
    let samples = [(a, Vec3::ONE), (b, Vec3::ZERO)];
    let expect_row = [1.0, 1.0, t[3] / (t[3] + t[21]), t[18] / (t[18] + t[6]), 0.0, 0.0];
    for tile_size in [1, 2, 4, 64] {
        let mut film = Film::new(6, 5, None, ReconstructionFilter::GAUSSIAN).unwrap();
        let img = render(&mut film, tile_size, &samples);
        for y in 0..5 {
            for x in 0..6 {
                // Rows 0 and 4 are exactly r = 2 away: bin 31 = 0, no weight → 0.
                let want = if y == 0 || y == 4 { 0.0 } else { expect_row[x as usize] };
                let got = img.get(x, y).x;
                assert!((got - want).abs() < 1e-3, "tile {tile_size} pixel ({x},{y}): {got} vs {want}");
            }
        }
    }
}

#[test]
fn half_bright_half_dark_edge_matches_mitsuba() {
    // §6 item 4 [verified]: 8 px wide, left half radiance 1, right half 0, default Gaussian.
    // Generated by tests/render/film/generate_reference.py (Mitsuba 3.9.1, scalar_rgb).
    // Mitsuba gives 0.8339 / 0.1661 ± 6e-5 for the two pixels next to the edge (32 × 65536
    // spp; left + right = 1 by symmetry). Many moderate renders
    // are averaged: one film with 10⁶ samples per pixel would mostly measure f32 rounding of
    // its sums, not the filter.
    let (renders, spp) = (64, 1 << 12);
    let mut sum = Image::new(8, 2);
    for seed in 0..renders {
        let mut film = Film::new(8, 2, None, ReconstructionFilter::default()).unwrap();
        let samples = sample_crop(&film, spp, seed, |p| if p.x < 4.0 { Vec3::ONE } else { Vec3::ZERO });
        let img = render(&mut film, 3, &samples);
        for (s, p) in sum.pixels.iter_mut().zip(&img.pixels) {
            *s += *p / renders as f32;
        }
    }
    for y in 0..2 {
        let (l, r) = (sum.get(3, y).x, sum.get(4, y).x);
        assert!((l - 0.8339).abs() < 2e-3, "left of edge: {l}");
        assert!((r - 0.1661).abs() < 2e-3, "right of edge: {r}");
        assert!((sum.get(0, y).x - 1.0).abs() < 1e-6 && sum.get(7, y).x == 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// film

#[test]
fn constant_image_stays_constant_at_the_edges() {
    let filters = [
        ReconstructionFilter::Box,
        ReconstructionFilter::TENT,
        ReconstructionFilter::Tent { radius: 1.7 },
        ReconstructionFilter::GAUSSIAN,
        ReconstructionFilter::Gaussian { stddev: 1.0 },
    ];
    let value = Vec3::new(0.25, 0.5, 2.0);
    for filter in filters {
        for crop in [None, Some(CropWindow { offset: [2, 1], size: [5, 4] })] {
            let mut film = Film::new(9, 7, crop, filter).unwrap();
            let samples = sample_crop(&film, 4, 1, |_| value);
            let img = render(&mut film, 2, &samples);
            assert_eq!((img.width, img.height), (film.crop().size[0], film.crop().size[1]));
            for p in &img.pixels {
                assert!(((*p - value) / value).abs().max_element() < 1e-5, "{filter:?} {crop:?}: {p}");
            }
        }
    }
}

#[test]
fn box_filter_is_the_plain_per_pixel_mean() {
    let mut film = Film::new(4, 3, None, ReconstructionFilter::Box).unwrap();
    let mut rng = Pcg32::new(3, 1);
    let samples = sample_crop(&film, 5, 9, |_| Vec3::new(rng.next_f32(), 2.0 * rng.next_f32(), -rng.next_f32()));
    let mut sum = [(Vec3::ZERO, 0u32); 12];
    for (p, v) in &samples {
        let s = &mut sum[p.y.floor() as usize * 4 + p.x.floor() as usize];
        s.0 += *v;
        s.1 += 1;
    }
    let img = render(&mut film, 3, &samples);
    for (i, (s, n)) in sum.iter().enumerate() {
        assert_eq!(*n, 5);
        assert!((img.pixels[i] - *s / *n as f32).abs().max_element() < 1e-6);
    }
    // A sample exactly on a pixel boundary belongs to the pixel starting there.
    let mut film = Film::new(2, 1, None, ReconstructionFilter::Box).unwrap();
    let img = render(&mut film, 8, &[(Vec2::new(1.0, 0.5), Vec3::ONE), (Vec2::new(0.999, 0.5), Vec3::splat(3.0))]);
    assert_eq!(img.pixels, vec![Vec3::splat(3.0), Vec3::ONE]);
}

#[test]
fn tiles_cover_the_crop_exactly_once() {
    for (w, h, crop) in [
        (7, 5, None),
        (16, 9, Some(CropWindow { offset: [3, 2], size: [10, 6] })),
        (5, 5, Some(CropWindow { offset: [4, 4], size: [1, 1] })),
    ] {
        let film = Film::new(w, h, crop, ReconstructionFilter::default()).unwrap();
        for ts in [0, 1, 2, 3, 4, 32] {
            let mut cover = vec![0u32; (w * h) as usize];
            for t in film.tiles(ts) {
                assert!(t.size[0] >= 1 && t.size[1] >= 1 && t.size[0] <= ts.max(1) && t.size[1] <= ts.max(1));
                for y in t.offset[1]..t.offset[1] + t.size[1] {
                    for x in t.offset[0]..t.offset[0] + t.size[0] {
                        cover[(y * w + x) as usize] += 1;
                    }
                }
            }
            let c = film.crop();
            for y in 0..h {
                for x in 0..w {
                    let inside = (c.offset[0]..c.offset[0] + c.size[0]).contains(&x)
                        && (c.offset[1]..c.offset[1] + c.size[1]).contains(&y);
                    assert_eq!(cover[(y * w + x) as usize], inside as u32, "({x},{y}) tile {ts}");
                }
            }
        }
    }
}

#[test]
fn crop_is_a_window_of_the_full_film() {
    let crop = CropWindow { offset: [3, 2], size: [6, 5] };
    let f = |p: Vec2| Vec3::new((p.x * 0.7).sin() + 1.0, p.y * 0.1, 1.0);
    // Box: the crop is exactly the sub-window of the full render (per-pixel means).
    let mut full = Film::new(12, 9, None, ReconstructionFilter::Box).unwrap();
    let samples = sample_crop(&full, 3, 5, f);
    let full_img = render(&mut full, 4, &samples);
    let mut part = Film::new(12, 9, Some(crop), ReconstructionFilter::Box).unwrap();
    let part_img = render(&mut part, 4, &samples);
    assert_eq!((part_img.width, part_img.height), (6, 5));
    for y in 0..5 {
        for x in 0..6 {
            assert_eq!(part_img.get(x, y), full_img.get(x + 3, y + 2));
        }
    }
    // Gaussian: pixels at least r = 2 inside the crop see the same samples as in the full
    // render; only the outer ring differs (it lacks the out-of-crop samples).
    let mut full = Film::new(12, 9, None, ReconstructionFilter::GAUSSIAN).unwrap();
    let full_img = render(&mut full, 4, &samples);
    let mut part = Film::new(12, 9, Some(crop), ReconstructionFilter::GAUSSIAN).unwrap();
    let in_crop: Vec<_> =
        samples.iter().copied().filter(|(p, _)| in_tile(&Tile { offset: crop.offset, size: crop.size }, *p)).collect();
    let part_img = render(&mut part, 4, &in_crop);
    for y in 2..3 {
        for x in 2..4 {
            assert!((part_img.get(x, y) - full_img.get(x + 3, y + 2)).abs().max_element() < 1e-5);
        }
    }
}

#[test]
fn splatting_matches_mitsuba_imageblock() {
    // Mitsuba's own hdrfilm (7×5, crop (1,1)+(5,3)) fed the same samples through
    // ImageBlock.put (box: at the integer pixel, as its integrator does), then developed, in
    // scalar_rgb (weights from the step table) and in llvm_ad_rgb (weights from the kernel).
    let Some(python) = common::mitsuba_python() else { return };
    let script = r#"
import sys, json, numpy as np, mitsuba as mi
variant, out_path = sys.argv[1:3]
mi.set_variant(variant)
rng = np.random.default_rng(5)
samples = []
for y in range(1, 4):
    for x in range(1, 6):
        for k in range(3):
            samples.append(([float(np.float32(x + rng.random())), float(np.float32(y + rng.random()))], [float(np.float32(v)) for v in rng.random(3)]))
out = {'samples': samples}
for name, rf in [('box', {'type': 'box'}), ('tent', {'type': 'tent'}), ('tent17', {'type': 'tent', 'radius': 1.7}),
                 ('gaussian', {'type': 'gaussian'}), ('gaussian1', {'type': 'gaussian', 'stddev': 1.0})]:
    film = mi.load_dict({'type': 'hdrfilm', 'width': 7, 'height': 5, 'crop_offset_x': 1, 'crop_offset_y': 1,
                         'crop_width': 5, 'crop_height': 3, 'rfilter': rf})
    film.prepare([])
    block = film.create_block(mi.ScalarVector2u(5, 3), False, True)
    block.set_offset(mi.ScalarPoint2i(1, 1))
    box = rf['type'] == 'box'
    if variant.startswith('scalar'):
        for p, v in samples:
            block.put(mi.Point2f(np.floor(p[0]), np.floor(p[1])) if box else mi.Point2f(p[0], p[1]), v + [1.0])
    else:
        xy = np.array([p for p, _ in samples], dtype=np.float32)
        xy = np.floor(xy) if box else xy
        rgb = np.array([v for _, v in samples], dtype=np.float32)
        block.put(mi.Point2f(xy[:, 0], xy[:, 1]), [mi.Float(rgb[:, c]) for c in range(3)] + [mi.Float(np.ones(len(samples)))])
    film.put_block(block)
    out[name] = np.array(film.develop()).tolist()
json.dump(out, open(out_path, 'w'))
"#;
    let filters = [
        ("box", ReconstructionFilter::Box),
        ("tent", ReconstructionFilter::TENT),
        ("tent17", ReconstructionFilter::Tent { radius: 1.7 }),
        ("gaussian", ReconstructionFilter::GAUSSIAN),
        ("gaussian1", ReconstructionFilter::Gaussian { stddev: 1.0 }),
    ];
    let largest_difference = |want: &[Vec<[f32; 3]>], img: &Image| {
        let mut d = 0.0f32;
        for (y, row) in want.iter().enumerate() {
            for (x, w) in row.iter().enumerate() {
                d = d.max((img.get(x as u32, y as u32) - Vec3::from(*w)).abs().max_element());
            }
        }
        d
    };
    for (variant, weights, other) in [
        ("scalar_rgb", SplatWeights::Discretized, SplatWeights::Exact),
        ("llvm_ad_rgb", SplatWeights::Exact, SplatWeights::Discretized),
    ] {
        let json_path = temp_path(&format!("splat-{variant}.json"));
        let out = Command::new(&python).arg("-c").arg(script).arg(variant).arg(&json_path).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
        let samples: Vec<(Vec2, Vec3)> = serde_json::from_value::<Vec<([f32; 2], [f32; 3])>>(j["samples"].clone())
            .unwrap()
            .into_iter()
            .map(|(p, v)| (Vec2::from(p), Vec3::from(v)))
            .collect();
        assert_eq!(SplatWeights::of_mitsuba_variant(variant), weights);
        for (name, filter) in filters {
            let want: Vec<Vec<[f32; 3]>> = serde_json::from_value(j[name].clone()).unwrap();
            let film = |w| {
                Film::new(7, 5, Some(CropWindow { offset: [1, 1], size: [5, 3] }), filter)
                    .unwrap()
                    .with_splat_weights(w)
            };
            for tile_size in [1, 2, 16] {
                let d = largest_difference(&want, &render(&mut film(weights), tile_size, &samples));
                assert!(d < 2e-6, "{variant} {name} tile {tile_size}: pixels differ by up to {d}");
            }
            // The other weighting differs from this variant (for every filter but the box), so
            // the comparison above can tell them apart.
            let d = largest_difference(&want, &render(&mut film(other), 16, &samples));
            if name == "box" {
                assert!(d < 2e-6, "{variant} box with {other:?} weights: {d}");
            } else {
                assert!(
                    d > 1e-4,
                    "{variant} {name}: {other:?} weights agree too ({d}); the check cannot see the difference"
                );
            }
        }
    }
}

#[test]
fn film_rejects_bad_configurations() {
    let g = ReconstructionFilter::default();
    assert!(Film::new(0, 4, None, g).is_err());
    assert!(Film::new(4, 0, None, g).is_err());
    assert!(Film::new(4, 4, Some(CropWindow { offset: [2, 0], size: [3, 4] }), g).unwrap_err().contains("crop"));
    assert!(Film::new(4, 4, Some(CropWindow { offset: [0, 0], size: [0, 4] }), g).is_err());
    assert!(Film::new(4, 4, Some(CropWindow { offset: [u32::MAX, 0], size: [2, 4] }), g).is_err());
    for bad in [
        ReconstructionFilter::Tent { radius: 0.0 },
        ReconstructionFilter::Tent { radius: -1.0 },
        ReconstructionFilter::Gaussian { stddev: f32::NAN },
        ReconstructionFilter::Gaussian { stddev: f32::INFINITY },
    ] {
        assert!(Film::new(4, 4, None, bad).unwrap_err().contains("filter"), "{bad:?}");
    }
    assert!(Film::new(4, 4, Some(CropWindow { offset: [1, 1], size: [3, 3] }), g).is_ok());
}

#[test]
fn stray_samples_never_panic_or_leak() {
    for filter in
        [ReconstructionFilter::Box, ReconstructionFilter::GAUSSIAN, ReconstructionFilter::Tent { radius: 3.0 }]
    {
        let mut film = Film::new(4, 4, None, filter).unwrap();
        let tile = film.tiles(2)[3];
        let mut block = film.new_block(&tile);
        for p in [
            Vec2::NAN,
            Vec2::new(f32::INFINITY, 1.0),
            Vec2::new(1e30, -1e30),
            Vec2::new(-1e9, 2.5),
            Vec2::new(3e7, 3e7),
        ] {
            block.put(p, Vec3::ONE);
        }
        film.put_block(&block);
        // Nothing arrived anywhere: all pixels are 0 (no weight), never NaN.
        assert!(film.develop().pixels.iter().all(|p| *p == Vec3::ZERO), "{filter:?}");
        block.put(Vec2::new(3.5, 3.5), Vec3::splat(2.0));
        block.clear();
        block.put(Vec2::new(2.5, 3.5), Vec3::ONE);
        film.put_block(&block);
        assert_eq!(film.develop().get(2, 3), Vec3::ONE);
    }
}

// ---------------------------------------------------------------------------------------------
// image I/O

#[test]
fn exr_round_trip_is_exact() {
    let mut rng = Pcg32::new(11, 2);
    let mut img = Image::new(5, 3);
    for p in img.pixels.iter_mut() {
        *p = Vec3::new(rng.next_f32() * 10.0, -rng.next_f32(), rng.next_f32() * 1e-3);
    }
    let path = temp_path("round.exr");
    write_exr(&path, &img).unwrap();
    assert_eq!(read_exr(&path).unwrap(), img);
    assert!(read_exr(&temp_path("missing.exr")).unwrap_err().contains("missing.exr"));
    let bogus = temp_path("bogus.exr");
    std::fs::write(&bogus, b"not an exr").unwrap();
    assert!(read_exr(&bogus).unwrap_err().contains("bogus.exr"));
    assert!(write_exr(&temp_path("bad.exr"), &Image { width: 2, height: 2, pixels: vec![] }).is_err());
}

#[test]
fn png_is_clamped_srgb_8bit() {
    // sRGB OETF closed form, rounded: 0.5 → 1.055·0.5^(1/2.4) − 0.055 = 0.73536 → 188.
    let values = [0.0f32, 0.5, 1.0, 2.0, -1.0, 0.001, 0.2, f32::NAN];
    let img =
        Image { width: values.len() as u32, height: 1, pixels: values.iter().map(|&v| Vec3::new(v, v, 0.5)).collect() };
    let path = temp_path("preview.png");
    write_png(&path, &img).unwrap();
    let png = image::open(&path).unwrap().into_rgb8();
    let oetf = |v: f64| {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        let s = if v <= 0.0031308 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0).round() as u8
    };
    for (x, &v) in values.iter().enumerate() {
        let p = png.get_pixel(x as u32, 0).0;
        assert_eq!(p, [oetf(v as f64), oetf(v as f64), 188], "value {v}");
    }
}

#[test]
fn reads_exr_files_written_by_mitsuba() {
    let Some(python) = common::mitsuba_python() else { return };
    let (f32_path, f16_path) = (temp_path("mitsuba32.exr"), temp_path("mitsuba16.exr"));
    // float32 via mi.Bitmap(...).write, float16 via hdrfilm.write (the default format).
    let script = r#"
import sys, numpy as np, mitsuba as mi
mi.set_variant('scalar_rgb')
h, w = 3, 4
val = lambda x, y, c: 0.5 + 0.1 * x + 0.01 * y + 0.001 * c
a = np.array([[[val(x, y, c) for c in range(3)] for x in range(w)] for y in range(h)], dtype=np.float32)
mi.Bitmap(a).write(sys.argv[1])
film = mi.load_dict({'type': 'hdrfilm', 'width': w, 'height': h, 'rfilter': {'type': 'box'}})
film.prepare([])
block = film.create_block()
for y in range(h):
    for x in range(w):
        block.put(mi.Point2f(x + 0.5, y + 0.5), [val(x, y, 0), val(x, y, 1), val(x, y, 2), 1.0])
film.put_block(block)
film.write(sys.argv[2])
"#;
    let out = Command::new(python).arg("-c").arg(script).arg(&f32_path).arg(&f16_path).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let val = |x: u32, y: u32, c: u32| 0.5 + 0.1 * x as f32 + 0.01 * y as f32 + 0.001 * c as f32;
    for (path, rel_tol) in [(f32_path, 1e-6), (f16_path, 1e-3)] {
        let img = read_exr(&path).unwrap();
        assert_eq!((img.width, img.height), (4, 3));
        for y in 0..3 {
            for x in 0..4 {
                let want = Vec3::new(val(x, y, 0), val(x, y, 1), val(x, y, 2));
                let got = img.get(x, y);
                assert!(
                    ((got - want) / want).abs().max_element() < rel_tol,
                    "{}: ({x},{y}) {got} vs {want}",
                    path.display()
                );
            }
        }
    }
}
