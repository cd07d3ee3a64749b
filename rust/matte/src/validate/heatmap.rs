//! Difference pictures a person can read: the signed relative difference on a diverging
//! colormap (ColorBrewer RdBu via `colorous`: red = matte brighter, blue = Mitsuba brighter)
//! and the per-pixel test (viridis of −log₁₀ p up to the Šidák threshold; rejected pixels
//! magenta), each with a colour bar whose numbers the HTML report prints.

use std::path::Path;

const REJECTED: [u8; 3] = [255, 0, 255];

fn save(path: &Path, w: u32, h: u32, rgb: Vec<u8>) -> Result<(), String> {
    image::RgbImage::from_raw(w, h, rgb)
        .ok_or("image buffer size")?
        .save(path)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// Signed relative difference in [−range, range] → RdBu.
pub fn write_difference(path: &Path, w: u32, h: u32, rel: &[f32], range: f32) -> Result<(), String> {
    let rgb = rel
        .iter()
        .flat_map(|&x| {
            let t = if x.is_finite() { (0.5 - 0.5 * x / range).clamp(0.0, 1.0) } else { 0.5 };
            colorous::RED_BLUE.eval_continuous(t as f64).as_array()
        })
        .collect();
    save(path, w, h, rgb)
}

/// Per-pixel evidence: −log₁₀(min over channels of p), scaled so the Šidák threshold is the
/// top of the colormap; pixels rejected at that threshold are magenta.
pub fn write_pvalues(path: &Path, w: u32, h: u32, p_min: &[f32], alpha_pixel: f64) -> Result<(), String> {
    let top = -alpha_pixel.log10();
    let rgb = p_min
        .iter()
        .flat_map(|&p| {
            if (p as f64) < alpha_pixel {
                REJECTED
            } else {
                let s = (-(p.max(1e-300) as f64).log10() / top).clamp(0.0, 1.0);
                colorous::VIRIDIS.eval_continuous(s).as_array()
            }
        })
        .collect();
    save(path, w, h, rgb)
}

/// Horizontal colour bars (256×12) for the two maps.
pub fn write_colorbars(diff_path: &Path, p_path: &Path) -> Result<(), String> {
    let (w, h) = (256u32, 12u32);
    let bar = |f: &dyn Fn(f64) -> [u8; 3]| -> Vec<u8> {
        (0..h).flat_map(|_| (0..w).flat_map(|x| f(x as f64 / (w - 1) as f64))).collect()
    };
    save(diff_path, w, h, bar(&|s| colorous::RED_BLUE.eval_continuous(1.0 - s).as_array()))?;
    save(p_path, w, h, bar(&|s| colorous::VIRIDIS.eval_continuous(s).as_array()))
}
