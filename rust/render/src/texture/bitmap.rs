//! The `bitmap` texture lookup (`src/textures/bitmap.cpp`, Dr.Jit's `drjit/texture.h`; §11).
//!
//! * `to_uv` is applied first; then p = uv·(W, H) − ½, so texel (i, j) has its centre at
//!   ((i+½)/W, (j+½)/H), and **v = 0 is the first (top) row of the file**, v growing
//!   downward. Bilinear interpolation mixes the 4 neighbours of p, each wrapped separately.
//! * Nearest takes the texel containing uv·(W, H).
//! * Interpolation happens on LINEAR values (8-bit texels are decoded before mixing).

use super::bitmap_load::{Texels, load};
use crate::load::props::{FromProps, PluginProps};
use glam::{Affine2, Vec2, Vec3};
use matte_scene_file::SceneError;
use std::path::Path;

/// `filter_type`: "bilinear" (default) or "nearest".
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BitmapFilter {
    #[default]
    Bilinear,
    Nearest,
}

/// `wrap_mode`: "repeat" (default), "mirror", "clamp" (Dr.Jit's `tex_wrap`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WrapMode {
    #[default]
    Repeat,
    Mirror,
    Clamp,
}

impl WrapMode {
    /// The `wrap_mode` word (Mitsuba's `repeat`, `mirror`, `clamp`), or `None`.
    pub fn parse(word: &str) -> Option<Self> {
        match word {
            "repeat" => Some(WrapMode::Repeat),
            "mirror" => Some(WrapMode::Mirror),
            "clamp" => Some(WrapMode::Clamp),
            _ => None,
        }
    }
}

/// The texture's XML properties.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BitmapOptions {
    pub filter: BitmapFilter,
    pub wrap: WrapMode,
    /// `raw = true`: 8/16-bit values are used as value/max, without sRGB decoding.
    pub raw: bool,
    /// `to_uv`: the upper-left 2×2 and the translation of Mitsuba's transform.
    pub to_uv: Affine2,
}

impl Default for BitmapOptions {
    fn default() -> Self {
        BitmapOptions { filter: BitmapFilter::Bilinear, wrap: WrapMode::Repeat, raw: false, to_uv: Affine2::IDENTITY }
    }
}

/// An image texture in linear RGB.
#[derive(Clone, Debug)]
pub struct BitmapTexture {
    width: u32,
    height: u32,
    texels: Vec<Vec3>,
    filter: BitmapFilter,
    wrap: WrapMode,
    to_uv: Affine2,
    mean: Vec3,
}

/// |p| beyond this has no fraction in f32 anyway; clamping keeps the i64 texel math safe.
const MAX_COORD: f32 = (1u32 << 30) as f32;

impl BitmapTexture {
    /// Loads a PNG/JPEG (8/16-bit) or EXR file. Errors name the file.
    pub fn load(path: &Path, opts: &BitmapOptions) -> Result<Self, String> {
        let t = load(path, opts.raw)?;
        if !opts.to_uv.is_finite() {
            return Err(format!("{}: bitmap to_uv transform is not finite", path.display()));
        }
        Ok(Self::from_texels(t, opts))
    }

    /// A texture from linear texels already in memory (row-major, top row first), e.g. a
    /// generated texture. No sRGB decoding and no padding: `width`, `height` must be ≥ 2.
    pub fn from_linear(width: u32, height: u32, texels: Vec<Vec3>, opts: &BitmapOptions) -> Result<Self, String> {
        if width < 2 || height < 2 || texels.len() != width as usize * height as usize {
            return Err(format!(
                "invalid texel buffer: {width}x{height} with {} texels (at least 2x2 needed)",
                texels.len()
            ));
        }
        Ok(Self::from_texels(Texels { width, height, data: texels }, opts))
    }

    fn from_texels(t: Texels, opts: &BitmapOptions) -> Self {
        let sum = t.data.iter().fold(glam::DVec3::ZERO, |s, v| s + v.as_dvec3());
        let mean = (sum / t.data.len() as f64).as_vec3();
        BitmapTexture {
            width: t.width,
            height: t.height,
            texels: t.data,
            filter: opts.filter,
            wrap: opts.wrap,
            to_uv: opts.to_uv,
            mean,
        }
    }

    /// Linear RGB at `uv`. Never NaN for finite texels: a non-finite uv is looked up at (0, 0).
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Vec3 {
        let uv = self.to_uv.transform_point2(uv);
        let uv = if uv.is_finite() { uv } else { Vec2::ZERO };
        let res = Vec2::new(self.width as f32, self.height as f32);
        match self.filter {
            BitmapFilter::Nearest => {
                let p = (uv * res).clamp(Vec2::splat(-MAX_COORD), Vec2::splat(MAX_COORD)).floor();
                self.texel(p.x as i64, p.y as i64)
            }
            BitmapFilter::Bilinear => {
                let p = (uv * res - 0.5).clamp(Vec2::splat(-MAX_COORD), Vec2::splat(MAX_COORD));
                let i = p.floor();
                let w1 = p - i;
                let w0 = 1.0 - w1;
                let (x, y) = (i.x as i64, i.y as i64);
                self.texel(x, y) * (w0.x * w0.y)
                    + self.texel(x + 1, y) * (w1.x * w0.y)
                    + self.texel(x, y + 1) * (w0.x * w1.y)
                    + self.texel(x + 1, y + 1) * (w1.x * w1.y)
            }
        }
    }

    /// Mitsuba's `BitmapTexture::eval_1_grad` (used by `bumpmap`): the uv gradient of the
    /// bilinearly interpolated luminance, through the `to_uv` transform (transpose multiply),
    /// in units of the texture's resolution. Zero for nearest filtering.
    #[inline]
    pub fn eval_1_grad(&self, uv: Vec2) -> Vec2 {
        if self.filter == BitmapFilter::Nearest {
            return Vec2::ZERO;
        }
        let t = self.to_uv.transform_point2(uv);
        let t = if t.is_finite() { t } else { Vec2::ZERO };
        let res = Vec2::new(self.width as f32, self.height as f32);
        let p = (t * res - 0.5).clamp(Vec2::splat(-MAX_COORD), Vec2::splat(MAX_COORD));
        let i = p.floor();
        let w1 = p - i;
        let w0 = 1.0 - w1;
        let (x, y) = (i.x as i64, i.y as i64);
        let lum = |v: Vec3| v.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169));
        let (f00, f10) = (lum(self.texel(x, y)), lum(self.texel(x + 1, y)));
        let (f01, f11) = (lum(self.texel(x, y + 1)), lum(self.texel(x + 1, y + 1)));
        let dx = w0.y.mul_add(f10 - f00, w1.y * (f11 - f01));
        let dy = w0.x.mul_add(f01 - f00, w1.x * (f11 - f10));
        let m = self.to_uv.matrix2;
        let du = m.x_axis.x * dx + m.x_axis.y * dy;
        let dv = m.y_axis.x * dx + m.y_axis.y * dy;
        res * Vec2::new(du, dv)
    }

    /// Per-channel mean of the linear texels.
    pub fn mean(&self) -> Vec3 {
        self.mean
    }

    /// Mitsuba's `Texture::mean()`: the mean luminance (Rec. 709 Y) of the texels.
    pub fn mean_luminance(&self) -> f32 {
        self.mean.dot(Vec3::new(0.212_671, 0.715_160, 0.072_169))
    }

    /// The linear texels, row-major, top row first.
    pub fn texels(&self) -> &[Vec3] {
        &self.texels
    }

    /// Texel grid size after Mitsuba's padding of sub-2×2 images.
    pub fn resolution(&self) -> [u32; 2] {
        [self.width, self.height]
    }

    #[inline]
    fn texel(&self, x: i64, y: i64) -> Vec3 {
        let x = wrap(x, self.width as i64, self.wrap);
        let y = wrap(y, self.height as i64, self.wrap);
        self.texels[(y * self.width as i64 + x) as usize]
    }
}

/// Dr.Jit's `tex_wrap` for one integer coordinate: clamp to the edge, repeat (Euclidean
/// modulo), or mirror (every other period reflected, edge texels repeated at the seams).
#[inline]
pub(crate) fn wrap(pos: i64, res: i64, mode: WrapMode) -> i64 {
    match mode {
        WrapMode::Clamp => pos.clamp(0, res - 1),
        WrapMode::Repeat => pos.rem_euclid(res),
        WrapMode::Mirror => {
            let period = pos.div_euclid(res);
            let m = pos.rem_euclid(res);
            if period % 2 == 0 { m } else { res - 1 - m }
        }
    }
}

impl FromProps for BitmapTexture {
    /// `filename`, `filter_type` (bilinear,
    /// nearest), `wrap_mode`, `raw`, `to_uv`; `format` is read and has no effect (matte keeps
    /// RGB).
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let path = p.file("filename")?;
        let filter = match p.string("filter_type")?.as_str() {
            "bilinear" => BitmapFilter::Bilinear,
            "nearest" => BitmapFilter::Nearest,
            other => {
                return Err(p.prop_err("filter_type", format!("must be bilinear or nearest, got \"{other}\"")));
            }
        };
        let word = p.string("wrap_mode")?;
        let wrap = WrapMode::parse(&word)
            .ok_or_else(|| p.prop_err("wrap_mode", format!("must be repeat, mirror or clamp, got \"{word}\"")))?;
        let raw = p.boolean("raw")?;
        let to_uv = p.uv_transform("to_uv")?;
        let _ = p.string("format")?;
        p.object().check_all_used()?;
        BitmapTexture::load(&path, &BitmapOptions { filter, wrap, raw, to_uv })
            .map_err(|e| p.file_err("filename", &path, &e))
    }
}
