//! Bitmap files → linear RGB texels, the way Mitsuba's `bitmap` texture stores them
//! (`src/textures/bitmap.cpp`, `src/core/bitmap.cpp`; §11):
//!
//! * 8-bit PNG/JPEG are sRGB-encoded (PNG gAMA is ignored). Mitsuba keeps the bytes and
//!   decodes each texel on lookup, before interpolating; decoding every texel once at load
//!   gives the same numbers. `raw = true`: value/255, no decoding.
//! * 16-bit PNG: value/65535, sRGB-decoded unless `raw`, stored as half floats (Mitsuba's
//!   `auto` format for 2-byte sources); the f16 rounding is reproduced.
//! * EXR, Radiance RGBE (`.hdr`) and PFM: linear, as stored (R, G, B or Y channels).
//! * TGA, PPM/PGM, BMP: 8-bit, sRGB-decoded like PNG (Mitsuba's other 8-bit formats).
//! * Alpha is dropped (not premultiplied); gray images become R = G = B.
//! * Images smaller than 2×2 are padded to 2 by repeating the last column/row
//!   (`Bitmap::pad_to`), which changes the texel grid the lookup uses.

use crate::image_io::read_exr;
use exr::prelude::f16;
use glam::Vec3;
use image::DynamicImage;
use std::path::Path;

/// Decoded texels, row-major, top row first (v = 0 is the first row of the file).
pub(super) struct Texels {
    pub width: u32,
    pub height: u32,
    pub data: Vec<Vec3>,
}

/// The exact sRGB EOTF (electro-optical transfer function): encoded value in 0..=1 → linear. Mitsuba
/// uses a rational fit of it that agrees to ~1e-6 (128/255 → 0.215861, §11).
#[inline]
pub fn srgb_to_linear(c: f32) -> f32 {
    let c = c as f64;
    (if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }) as f32
}

pub(super) fn load(path: &Path, raw: bool) -> Result<Texels, String> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let t = if ext.as_deref() == Some("exr") {
        let img = read_exr(path)?;
        Texels { width: img.width, height: img.height, data: img.pixels }
    } else if ext.as_deref() == Some("hdr") {
        // Radiance RGBE. Mitsuba writes the signature `#?RGBE`, which the decoder does not
        // know; it is the same format as `#?RADIANCE`.
        let mut bytes = std::fs::read(path).map_err(|e| format!("{}: cannot open bitmap: {e}", path.display()))?;
        if let Some(rest) = bytes.strip_prefix(b"#?RGBE") {
            bytes = [b"#?RADIANCE".as_slice(), rest].concat();
        }
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Hdr)
            .map_err(|e| format!("{}: cannot decode bitmap: {e}", path.display()))?;
        decode(img, raw)
    } else if ext.as_deref() == Some("pfm") {
        let bytes = std::fs::read(path).map_err(|e| format!("{}: cannot open bitmap: {e}", path.display()))?;
        read_pfm(&bytes).map_err(|e| format!("{}: invalid PFM file: {e}", path.display()))?
    } else {
        let img = image::ImageReader::open(path)
            .map_err(|e| format!("{}: cannot open bitmap: {e}", path.display()))?
            .with_guessed_format()
            .map_err(|e| format!("{}: cannot read bitmap: {e}", path.display()))?
            .decode()
            .map_err(|e| format!("{}: cannot decode bitmap: {e}", path.display()))?;
        decode(img, raw)
    };
    if t.width == 0 || t.height == 0 {
        return Err(format!("{}: bitmap is empty", path.display()));
    }
    Ok(pad_to_2x2(t))
}

fn decode(img: DynamicImage, raw: bool) -> Texels {
    let (width, height) = (img.width(), img.height());
    let data = match img {
        DynamicImage::ImageLuma8(_) | DynamicImage::ImageLumaA8(_) => {
            let lut = lut8(raw);
            img.into_luma8().pixels().map(|p| Vec3::splat(lut[p.0[0] as usize])).collect()
        }
        DynamicImage::ImageRgb8(_) | DynamicImage::ImageRgba8(_) => {
            let lut = lut8(raw);
            img.into_rgb8().pixels().map(|p| Vec3::from(p.0.map(|c| lut[c as usize]))).collect()
        }
        DynamicImage::ImageLuma16(_) | DynamicImage::ImageLumaA16(_) => {
            img.into_luma16().pixels().map(|p| Vec3::splat(decode16(p.0[0], raw))).collect()
        }
        DynamicImage::ImageRgb16(_) | DynamicImage::ImageRgba16(_) => {
            img.into_rgb16().pixels().map(|p| Vec3::from(p.0.map(|c| decode16(c, raw)))).collect()
        }
        // Float images (not produced by the PNG/JPEG decoders): linear as stored.
        other => other.into_rgb32f().pixels().map(|p| Vec3::from(p.0)).collect(),
    };
    Texels { width, height, data }
}

/// Portable float map as Mitsuba reads it (`Bitmap::read_pfm`): `PF` (RGB) or `Pf` (gray),
/// width and height, a scale whose sign gives the byte order (≤ 0: little endian) and whose
/// magnitude multiplies every value, then f32 rows from the bottom row up.
fn read_pfm(bytes: &[u8]) -> Result<Texels, String> {
    // The four header fields (type, width, height, scale), separated by whitespace; one
    // whitespace character ends the header.
    let mut fields = Vec::new();
    let mut at = 0;
    while fields.len() < 4 {
        while at < bytes.len() && bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while at < bytes.len() && !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        if start == at {
            return Err("truncated header".into());
        }
        fields.push(std::str::from_utf8(&bytes[start..at]).map_err(|_| "header is not text")?);
    }
    at += 1;
    let channels = match fields[0] {
        "PF" => 3,
        "Pf" => 1,
        other => return Err(format!("unknown type \"{other}\" (expected PF or Pf)")),
    };
    let dim = |s: &str| s.parse::<u32>().ok().filter(|&d| d > 0 && d <= 1 << 16).ok_or(format!("bad size \"{s}\""));
    let (width, height) = (dim(fields[1])?, dim(fields[2])?);
    let scale: f32 = fields[3].parse().map_err(|_| format!("bad scale \"{}\"", fields[3]))?;
    let n = width as usize * height as usize * channels;
    let body = bytes.get(at..at + 4 * n).ok_or("truncated pixel data")?;
    let value = |i: usize| {
        let b: [u8; 4] = body[4 * i..4 * i + 4].try_into().unwrap();
        scale.abs() * if scale <= 0.0 { f32::from_le_bytes(b) } else { f32::from_be_bytes(b) }
    };
    let mut data = Vec::with_capacity(n / channels);
    for y in (0..height as usize).rev() {
        for x in 0..width as usize {
            let i = (y * width as usize + x) * channels;
            data.push(if channels == 3 {
                Vec3::new(value(i), value(i + 1), value(i + 2))
            } else {
                Vec3::splat(value(i))
            });
        }
    }
    Ok(Texels { width, height, data })
}

/// Linear value of every 8-bit code.
fn lut8(raw: bool) -> [f32; 256] {
    std::array::from_fn(|i| {
        let c = i as f32 / 255.0;
        if raw { c } else { srgb_to_linear(c) }
    })
}

/// 16-bit code → linear, rounded to half precision like Mitsuba's storage.
fn decode16(c: u16, raw: bool) -> f32 {
    let v = c as f32 / 65535.0;
    f16::from_f32(if raw { v } else { srgb_to_linear(v) }).to_f32()
}

/// `Bitmap::pad_to(2, 2)`: widen by repeating the last column, then the last row.
fn pad_to_2x2(t: Texels) -> Texels {
    if t.width >= 2 && t.height >= 2 {
        return t;
    }
    let (w, h) = (t.width.max(2), t.height.max(2));
    let mut data = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        let sy = y.min(t.height - 1);
        for x in 0..w {
            data.push(t.data[(sy * t.width + x.min(t.width - 1)) as usize]);
        }
    }
    Texels { width: w, height: h, data }
}
