//! Image files in and out (§12): OpenEXR the way Mitsuba writes it (linear RGB, channels
//! "R", "G", "B"; float32 from `mi.Bitmap(...).write`, float16 from `film.write` and the
//! `mitsuba` CLI), and an 8-bit sRGB PNG preview.

use crate::film::Image;
use exr::prelude::{AnyChannels, FlatSamples, Layer, ReadChannels, ReadLayers, read};
use glam::Vec3;
use std::path::Path;

/// Writes `img` as an RGB float32 OpenEXR with channels "R", "G", "B" (linear, no alpha),
/// the format `mi.Bitmap(img).write("x.exr")` produces.
pub fn write_exr(path: &Path, img: &Image) -> Result<(), String> {
    check_size(img)?;
    let w = img.width as usize;
    exr::prelude::write_rgb_file(path, w, img.height as usize, |x, y| {
        let p = img.pixels[y * w + x];
        (p.x, p.y, p.z)
    })
    .map_err(|e| format!("{}: cannot write EXR: {e}", path.display()))
}

/// Reads an OpenEXR image by channel name: "R", "G", "B" (or a single "Y" as gray) in
/// f16, f32 or u32 samples, from the first layer that has them. Other channels (alpha,
/// AOVs) are ignored. Linear values are returned as stored.
pub fn read_exr(path: &Path) -> Result<Image, String> {
    let fail = |m: String| format!("{}: {m}", path.display());
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_file(path)
        .map_err(|e| fail(format!("cannot read EXR: {e}")))?;
    for layer in &image.layer_data {
        if let Some(img) = layer_rgb(layer) {
            return Ok(img);
        }
    }
    Err(fail("EXR file has no R, G, B (or Y) channels".into()))
}

/// The RGB (or gray) image of one layer, if it has those channels.
fn layer_rgb(layer: &Layer<AnyChannels<FlatSamples>>) -> Option<Image> {
    let find = |name: &str| layer.channel_data.list.iter().find(|c| c.name == *name);
    let (w, h) = (layer.size.0, layer.size.1);
    let planes: Vec<Vec<f32>> = match (find("R"), find("G"), find("B"), find("Y")) {
        (Some(r), Some(g), Some(b), _) => [r, g, b].iter().map(|c| c.sample_data.values_as_f32().collect()).collect(),
        (_, _, _, Some(y)) => vec![y.sample_data.values_as_f32().collect(); 3],
        _ => return None,
    };
    if planes.iter().any(|p| p.len() != w * h) {
        return None; // subsampled channels: not something Mitsuba writes
    }
    let pixels = (0..w * h).map(|i| Vec3::new(planes[0][i], planes[1][i], planes[2][i])).collect();
    Some(Image { width: w as u32, height: h as u32, pixels })
}

/// Writes an 8-bit sRGB PNG: each channel clamped to [0, 1], encoded with the sRGB OETF and
/// rounded (NaN → 0). A preview only; the EXR is the result.
pub fn write_png(path: &Path, img: &Image) -> Result<(), String> {
    check_size(img)?;
    let bytes: Vec<u8> = img.pixels.iter().flat_map(|p| p.to_array().map(encode_srgb8)).collect();
    image::save_buffer_with_format(
        path,
        &bytes,
        img.width,
        img.height,
        image::ExtendedColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .map_err(|e| format!("{}: cannot write PNG: {e}", path.display()))
}

/// Linear → 8-bit sRGB code value.
#[inline]
pub fn encode_srgb8(v: f32) -> u8 {
    let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

fn check_size(img: &Image) -> Result<(), String> {
    if img.width == 0 || img.height == 0 || img.pixels.len() != img.width as usize * img.height as usize {
        return Err(format!("invalid image: {}x{} with {} pixels", img.width, img.height, img.pixels.len()));
    }
    Ok(())
}
