//! The `bitmap` texture (`rust/render/texture`). Oracles: the §11 verified values of
//! `docs/renderer-semantics.md` (§N below is its section N) (128/255 → 0.215861, mid-point 0.303965), values read
//! back from Mitsuba 3.9.1 for RGBA / gray-alpha PNGs, the exact sRGB EOTF, and hand-derived
//! texel indices for orientation and wrapping.

use crate::common;

use glam::{Affine2, Vec2, Vec3};
use image::{ImageBuffer, Luma, LumaA, Rgb, Rgba};
use matte::render::film::Image;
use matte::render::image_io::write_exr;
use matte::render::texture::{BitmapFilter, BitmapOptions, BitmapTexture, WrapMode};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

fn temp_path(name: &str) -> PathBuf {
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!("matte-bitmap-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(format!("{}-{name}", COUNTER.fetch_add(1, Ordering::Relaxed)))
}

fn rgb8(w: u32, h: u32, texels: &[[u8; 3]]) -> PathBuf {
    let path = temp_path("t.png");
    ImageBuffer::<Rgb<u8>, _>::from_raw(w, h, texels.concat()).unwrap().save(&path).unwrap();
    path
}

fn load(path: &Path, opts: BitmapOptions) -> BitmapTexture {
    BitmapTexture::load(path, &opts).unwrap()
}

fn nearest(wrap: WrapMode) -> BitmapOptions {
    BitmapOptions { filter: BitmapFilter::Nearest, wrap, ..Default::default() }
}

/// The exact sRGB EOTF in f64 (an independent closed form).
fn eotf(c: f64) -> f64 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

fn assert_close(a: Vec3, b: Vec3, tol: f32) {
    assert!((a - b).abs().max_element() <= tol, "{a} vs {b}");
}

const RED: [u8; 3] = [255, 0, 0];
const GREEN: [u8; 3] = [0, 255, 0];
const BLUE: [u8; 3] = [0, 0, 255];
const GRAY: [u8; 3] = [128, 128, 128];

#[test]
fn eight_bit_texels_are_srgb_decoded() {
    // §11 [verified]: 128/255 → 0.215861.
    let p = rgb8(2, 2, &[GRAY; 4]);
    for filter in [BitmapFilter::Bilinear, BitmapFilter::Nearest] {
        let t = load(&p, BitmapOptions { filter, ..Default::default() });
        for uv in [Vec2::new(0.3, 0.7), Vec2::new(-5.2, 3.9), Vec2::ZERO] {
            assert_close(t.eval(uv), Vec3::splat(0.215861), 2e-6);
        }
    }
    // raw = true: value/255, no decoding [verified].
    let t = load(&p, BitmapOptions { raw: true, ..Default::default() });
    assert_close(t.eval(Vec2::splat(0.5)), Vec3::splat(128.0 / 255.0), 1e-7);
}

#[test]
fn bilinear_mixes_linear_values() {
    // §11 [verified]: the mid-point of red, green / blue, gray(128) is 0.303965 in every
    // channel = the mean of the linear texels.
    let t = load(&rgb8(2, 2, &[RED, GREEN, BLUE, GRAY]), BitmapOptions::default());
    assert_close(t.eval(Vec2::splat(0.5)), Vec3::splat(0.303965), 2e-6);
    assert_close(t.mean(), Vec3::splat(0.303965), 2e-6);
    // Black | white columns: halfway is 0.5 in linear, not the sRGB mid-grey.
    let t = load(&rgb8(2, 2, &[[0; 3], [255; 3], [0; 3], [255; 3]]), BitmapOptions::default());
    assert_close(t.eval(Vec2::new(0.5, 0.3)), Vec3::splat(0.5), 1e-6);
    assert_close(t.eval(Vec2::new(0.375, 0.3)), Vec3::splat(0.25), 1e-6);
}

#[test]
fn v_zero_is_the_top_row() {
    // Top row red, bottom row blue; texel centres at ((i+½)/W, (j+½)/H) [verified].
    let p = rgb8(2, 2, &[RED, RED, BLUE, BLUE]);
    for filter in [BitmapFilter::Bilinear, BitmapFilter::Nearest] {
        let t = load(&p, BitmapOptions { filter, ..Default::default() });
        assert_close(t.eval(Vec2::new(0.25, 0.25)), Vec3::X, 1e-6);
        assert_close(t.eval(Vec2::new(0.75, 0.75)), Vec3::Z, 1e-6);
    }
    let t = load(&p, nearest(WrapMode::Repeat));
    assert_close(t.eval(Vec2::new(0.9, 0.49)), Vec3::X, 0.0);
    assert_close(t.eval(Vec2::new(0.1, 0.5)), Vec3::Z, 0.0);
}

/// 4×2 texels: x channel = column value, y channel = row.
fn columns() -> Vec<Vec3> {
    (0..2).flat_map(|r| (0..4).map(move |c| Vec3::new(0.1 * (c + 1) as f32, r as f32, 0.0))).collect()
}

#[test]
fn wrap_modes_pick_the_expected_texels() {
    // u → p = 4u → texel floor(p); expected columns by the definitions: repeat = p mod 4,
    // mirror = reflected every other period (…3 2 1 0 | 0 1 2 3 | 3 2 1 0…), clamp = [0, 3].
    let cases: [(f32, [usize; 3]); 6] =
        [(-0.1, [3, 0, 0]), (1.1, [0, 3, 3]), (-1.1, [3, 3, 0]), (2.3, [1, 1, 3]), (1.9, [3, 0, 3]), (0.6, [2, 2, 2])];
    for (k, wrap) in [WrapMode::Repeat, WrapMode::Mirror, WrapMode::Clamp].into_iter().enumerate() {
        let t = BitmapTexture::from_linear(4, 2, columns(), &nearest(wrap)).unwrap();
        for (u, want) in cases {
            let got = t.eval(Vec2::new(u, 0.25));
            assert_eq!(got, Vec3::new(0.1 * (want[k] + 1) as f32, 0.0, 0.0), "{wrap:?} u={u}");
        }
        // v wraps the same way: v = -0.25 → row p = -0.5 → -1.
        let row = t.eval(Vec2::new(0.1, -0.25)).y;
        assert_eq!(row, [1.0, 0.0, 0.0][k], "{wrap:?}");
    }
    // Bilinear left of the first texel centre: repeat mixes in the last column.
    for (wrap, want) in [(WrapMode::Repeat, 0.75 * 0.1 + 0.25 * 0.4), (WrapMode::Clamp, 0.1), (WrapMode::Mirror, 0.1)] {
        let t = BitmapTexture::from_linear(4, 2, columns(), &BitmapOptions { wrap, ..Default::default() }).unwrap();
        assert!((t.eval(Vec2::new(1.0 / 16.0, 0.25)).x - want).abs() < 1e-6, "{wrap:?}");
    }
}

#[test]
fn to_uv_is_applied_first() {
    let opts = BitmapOptions { to_uv: Affine2::from_scale(Vec2::splat(2.0)), ..nearest(WrapMode::Repeat) };
    let t = BitmapTexture::from_linear(4, 2, columns(), &opts).unwrap();
    assert_eq!(t.eval(Vec2::new(0.6, 0.1)).x, 0.1); // u' = 1.2 → p = 4.8 → column 0
    let opts = BitmapOptions { to_uv: Affine2::from_translation(Vec2::new(0.25, 0.0)), ..nearest(WrapMode::Clamp) };
    let t = BitmapTexture::from_linear(4, 2, columns(), &opts).unwrap();
    assert_eq!(t.eval(Vec2::new(0.1, 0.1)).x, 0.2);
}

#[test]
fn alpha_is_dropped_and_gray_is_replicated() {
    // Mitsuba 3.9.1 read back (scalar_rgb): RGBA (200,100,50,128) → (0.577581, 0.127438,
    // 0.031896), mean() 0.216275; gray+alpha (200,128) → 0.577581 in all channels.
    let p = temp_path("rgba.png");
    ImageBuffer::<Rgba<u8>, _>::from_raw(2, 2, [200u8, 100, 50, 128].repeat(4)).unwrap().save(&p).unwrap();
    let t = load(&p, BitmapOptions::default());
    assert_close(t.eval(Vec2::new(0.3, 0.6)), Vec3::new(0.577581, 0.127438, 0.031896), 2e-6);
    assert!((t.mean_luminance() - 0.216275).abs() < 2e-6);
    let p = temp_path("ya.png");
    ImageBuffer::<LumaA<u8>, _>::from_raw(2, 2, [200u8, 128].repeat(4)).unwrap().save(&p).unwrap();
    assert_close(load(&p, BitmapOptions::default()).eval(Vec2::new(0.3, 0.6)), Vec3::splat(0.577581), 2e-6);
    let p = temp_path("y.png");
    ImageBuffer::<Luma<u8>, _>::from_raw(2, 2, vec![0, 255, 255, 0]).unwrap().save(&p).unwrap();
    let t = load(&p, nearest(WrapMode::Repeat));
    assert_eq!(t.eval(Vec2::new(0.75, 0.25)), Vec3::ONE);
}

#[test]
fn sixteen_bit_png_is_decoded_to_half_precision() {
    let p = temp_path("16.png");
    ImageBuffer::<Rgb<u16>, _>::from_raw(2, 2, [32768u16, 65535, 0].repeat(4)).unwrap().save(&p).unwrap();
    let t = load(&p, BitmapOptions::default());
    let want = Vec3::new(eotf(32768.0 / 65535.0) as f32, 1.0, 0.0);
    assert_close(t.eval(Vec2::splat(0.5)), want, 1e-3 * want.x);
    let t = load(&p, BitmapOptions { raw: true, ..Default::default() });
    assert_close(t.eval(Vec2::splat(0.5)), Vec3::new(0.5, 1.0, 0.0), 1e-3);
}

#[test]
fn exr_textures_stay_linear() {
    let img = Image {
        width: 2,
        height: 2,
        pixels: vec![Vec3::new(2.5, 0.0, 0.1), Vec3::ONE, Vec3::splat(-0.5), Vec3::splat(0.25)],
    };
    let p = temp_path("t.exr");
    write_exr(&p, &img).unwrap();
    let t = load(&p, nearest(WrapMode::Repeat));
    assert_eq!(t.eval(Vec2::new(0.2, 0.2)), Vec3::new(2.5, 0.0, 0.1));
    assert_eq!(t.eval(Vec2::new(0.2, 0.7)), Vec3::splat(-0.5));
    assert_close(t.mean(), (img.pixels.iter().sum::<Vec3>()) / 4.0, 1e-6);
}

#[test]
fn tiny_images_are_padded_and_jpeg_is_srgb() {
    let t = load(&rgb8(1, 1, &[GRAY]), BitmapOptions::default());
    assert_eq!(t.resolution(), [2, 2]);
    assert_close(t.eval(Vec2::new(0.9, 0.1)), Vec3::splat(0.215861), 2e-6);
    let t = load(&rgb8(1, 2, &[RED, BLUE]), nearest(WrapMode::Repeat));
    assert_eq!(t.resolution(), [2, 2]);
    assert_eq!(t.eval(Vec2::new(0.9, 0.9)), Vec3::Z);

    let p = temp_path("t.jpg");
    ImageBuffer::<Rgb<u8>, _>::from_raw(8, 8, [128u8; 3].repeat(64)).unwrap().save(&p).unwrap();
    let v = load(&p, BitmapOptions::default()).eval(Vec2::splat(0.5));
    let (lo, hi) = (eotf(126.0 / 255.0) as f32, eotf(130.0 / 255.0) as f32);
    assert!(v.cmpge(Vec3::splat(lo)).all() && v.cmple(Vec3::splat(hi)).all(), "{v}");
}

#[test]
fn lookups_never_return_nan() {
    let t = load(&rgb8(2, 2, &[RED, GREEN, BLUE, GRAY]), BitmapOptions::default());
    for uv in [Vec2::NAN, Vec2::new(f32::INFINITY, 0.0), Vec2::new(1e30, -1e30), Vec2::new(-3e9, 7e8)] {
        assert!(t.eval(uv).is_finite(), "{uv}");
    }
}

#[test]
fn bad_files_are_errors_naming_the_file() {
    let missing = temp_path("missing.png");
    assert!(BitmapTexture::load(&missing, &BitmapOptions::default()).unwrap_err().contains("missing.png"));
    let junk = temp_path("junk.png");
    std::fs::write(&junk, b"\x89PNG\r\n\x1a\n garbage").unwrap();
    assert!(BitmapTexture::load(&junk, &BitmapOptions::default()).unwrap_err().contains("junk.png"));
    let p = rgb8(2, 2, &[GRAY; 4]);
    let opts = BitmapOptions { to_uv: Affine2::from_scale(Vec2::new(f32::NAN, 1.0)), ..Default::default() };
    assert!(BitmapTexture::load(&p, &opts).is_err());
    assert!(BitmapTexture::from_linear(1, 2, vec![Vec3::ONE; 2], &BitmapOptions::default()).is_err());
    assert!(BitmapTexture::from_linear(2, 2, vec![Vec3::ONE; 3], &BitmapOptions::default()).is_err());
}

#[test]
fn lookups_match_mitsuba_bitmap_texture() {
    // Mitsuba 3.9.1 writes a random 5×3 8-bit PNG and evaluates its `bitmap` texture at 200
    // random uv in [-2, 3]² for every filter / wrap / raw combination, with a to_uv of
    // translate(0.1, -0.2)·scale(1.5, 0.7). Skipped when the venv is absent.
    let Some(python) = common::mitsuba_python() else { return };
    let script = r#"
import sys, json, numpy as np, mitsuba as mi
mi.set_variant('scalar_rgb')
rng = np.random.default_rng(3)
mi.Bitmap(rng.integers(0, 256, size=(3, 5, 3), dtype=np.uint8)).write(sys.argv[1])
uvs = [[float(np.float32(u)) for u in rng.uniform(-2, 3, 2)] for _ in range(200)]
out = {'uvs': uvs}
to_uv = mi.ScalarAffineTransform4f().translate([0.1, -0.2, 0]) @ mi.ScalarAffineTransform4f().scale([1.5, 0.7, 1])
for filt in ['bilinear', 'nearest']:
    for wrap in ['repeat', 'mirror', 'clamp']:
        for raw in [False, True]:
            t = mi.load_dict({'type': 'bitmap', 'filename': sys.argv[1], 'filter_type': filt, 'wrap_mode': wrap,
                              'raw': raw, 'to_uv': to_uv})
            si = mi.SurfaceInteraction3f()
            vals = []
            for uv in uvs:
                si.uv = uv
                vals.append(list(t.eval(si)))
            out[f'{filt}-{wrap}-{raw}'] = vals
json.dump(out, open(sys.argv[2], 'w'))
"#;
    let (png, json) = (temp_path("mitsuba.png"), temp_path("mitsuba.json"));
    let out = std::process::Command::new(python).arg("-c").arg(script).arg(&png).arg(&json).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let uvs: Vec<[f32; 2]> = serde_json::from_value(j["uvs"].clone()).unwrap();
    let to_uv = Affine2::from_translation(Vec2::new(0.1, -0.2)) * Affine2::from_scale(Vec2::new(1.5, 0.7));
    for (fname, filter) in [("bilinear", BitmapFilter::Bilinear), ("nearest", BitmapFilter::Nearest)] {
        for (wname, wrap) in [("repeat", WrapMode::Repeat), ("mirror", WrapMode::Mirror), ("clamp", WrapMode::Clamp)] {
            for (rname, raw) in [("False", false), ("True", true)] {
                let t = load(&png, BitmapOptions { filter, wrap, raw, to_uv });
                let want: Vec<[f32; 3]> =
                    serde_json::from_value(j[format!("{fname}-{wname}-{rname}")].clone()).unwrap();
                for (uv, w) in uvs.iter().zip(&want) {
                    let got = t.eval(Vec2::from(*uv));
                    assert!(
                        (got - Vec3::from(*w)).abs().max_element() < 1e-5,
                        "{fname} {wname} raw={raw} uv {uv:?}: {got} vs {w:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn other_file_formats_read_as_mitsuba_reads_them() {
    // A random 5×3 image as Radiance RGBE (.hdr) and PFM (float RGB, linear) and as TGA and
    // PPM (8-bit, sRGB), written by Mitsuba 3.9.1 (TGA by hand: Mitsuba only reads it), and
    // Mitsuba's `bitmap` texture (nearest) at every texel centre. Skipped without the venv.
    let Some(python) = common::mitsuba_python() else { return };
    let script = r#"
import sys, json, os, numpy as np, mitsuba as mi
mi.set_variant('scalar_rgb')
rng = np.random.default_rng(5)
out = {}
for ext, data in [('hdr', rng.uniform(0.01, 4.0, (3, 5, 3)).astype(np.float32)),
                  ('pfm', rng.uniform(0.0, 4.0, (3, 5, 3)).astype(np.float32)),
                  ('tga', rng.integers(0, 256, (3, 5, 3), dtype=np.uint8)),
                  ('ppm', rng.integers(0, 256, (3, 5, 3), dtype=np.uint8))]:
    path = os.path.join(sys.argv[1], 'image.' + ext)
    if ext == 'tga':
        # Mitsuba reads TGA (version 2, with its footer) but does not write it: uncompressed
        # 24-bit BGR, top row first.
        header = bytes([0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 5, 0, 3, 0, 24, 0x20])
        footer = bytes(8) + b'TRUEVISION-XFILE.\0'
        open(path, 'wb').write(header + data[..., ::-1].tobytes() + footer)
    else:
        mi.Bitmap(data, mi.Bitmap.PixelFormat.RGB).write(path)
    t = mi.load_dict({'type': 'bitmap', 'filename': path, 'filter_type': 'nearest'})
    si = mi.SurfaceInteraction3f()
    vals = []
    for y in range(3):
        for x in range(5):
            si.uv = [(x + 0.5) / 5, (y + 0.5) / 3]
            vals.append(list(t.eval(si)))
    out[ext] = vals
json.dump(out, open(os.path.join(sys.argv[1], 'values.json'), 'w'))
"#;
    let dir = temp_path("formats");
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(python).arg("-c").arg(script).arg(&dir).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("values.json")).unwrap()).unwrap();
    for ext in ["hdr", "pfm", "tga", "ppm"] {
        let t = load(&dir.join(format!("image.{ext}")), nearest(WrapMode::Clamp));
        let want: Vec<[f32; 3]> = serde_json::from_value(j[ext].clone()).unwrap();
        assert_eq!(want.len(), 15);
        for (i, w) in want.iter().enumerate() {
            let uv = Vec2::new(((i % 5) as f32 + 0.5) / 5.0, ((i / 5) as f32 + 0.5) / 3.0);
            let got = t.eval(uv);
            let tol = 1e-5 * Vec3::from(*w).max_element().max(1.0);
            assert!((got - Vec3::from(*w)).abs().max_element() <= tol, "{ext} texel {i}: {got} vs {w:?}");
        }
    }
    // A PFM cut short is an error naming the file.
    let bytes = std::fs::read(dir.join("image.pfm")).unwrap();
    std::fs::write(dir.join("short.pfm"), &bytes[..bytes.len() - 7]).unwrap();
    let e = BitmapTexture::load(&dir.join("short.pfm"), &BitmapOptions::default()).unwrap_err();
    assert!(e.contains("short.pfm") && e.contains("truncated"), "{e}");
}
