//! Mitsuba's `volume` texture (`src/textures/volume.cpp`, v3.9.1): a surface texture looked up
//! at the world-space hit point, not at the uv, in a nested volume: `gridvolume`
//! (`src/volumes/grid.cpp`, a voxel grid read from a `.vol` file) or `constvolume`
//! (`src/volumes/const.cpp`). docs/renderer-semantics.md §11 (volume).
//!
//! * Every volume maps the hit point into its local space with the inverse of its `to_world`
//!   (`Volume::Volume`, `src/render/volume.cpp`); a grid spans the unit cube [0, 1]³ there
//!   (with `use_grid_bbox`, the file's bounding box instead).
//! * A grid is Dr.Jit's 3-D texture over the tensor [z, y, x, channel]: trilinear at
//!   `p·res − ½` (voxel centres at (i + ½)/res), or nearest at ⌊p·res⌋, each integer index
//!   wrapped by `wrap_mode` (clamp, repeat, mirror), as the bitmap texture's.
//! * In RGB variants `eval` is the interpolated RGB (one channel: the value in all three) and
//!   `eval_1` its luminance (one channel: the value); `raw` only matters to spectral variants.
//! * `constvolume`'s `eval` is its `value` texture at uv = (0, 0), its `eval_1` the texture's
//!   `mean()`.
//! * `mean()` is not implemented by Mitsuba's volume texture (it throws); matte's loader refuses
//!   a volume texture wherever Mitsuba calls it. Here it is the voxels' mean (luminance for
//!   RGB), and a `constvolume`'s value's mean.
//!
//! The `volume` texture, `gridvolume` and `constvolume` read their properties here.

use super::bitmap::{WrapMode, wrap};
use crate::load::props::PluginProps;
use glam::{Affine3A, Vec3};
use matte_scene_file::SceneError;
use std::path::Path;

/// Rec. 709 luminance, as Mitsuba's `luminance(Color3f)`.
const LUMINANCE: Vec3 = Vec3::new(0.212_671, 0.715_160, 0.072_169);

/// Coordinates beyond this (in voxels) are clamped before the integer conversion, so a far
/// point stays a finite index (the wrap modes then map it into the grid).
const MAX_COORD: f32 = (1u32 << 30) as f32;

/// The contents of a `.vol` file (Mitsuba's `VolumeGrid`, `src/render/volumegrid.cpp`): the
/// resolution, the channel count, the bounding box and the voxel values, x fastest and the
/// channel innermost (`data[((z·yres + y)·xres + x)·channels + c]`).
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeGrid {
    /// (x, y, z) resolution.
    pub res: [u32; 3],
    pub channels: u32,
    pub bbox_min: Vec3,
    pub bbox_max: Vec3,
    pub data: Vec<f32>,
}

/// A little-endian reader that reports a short read as Mitsuba's `FileStream::read` does:
/// "read k out of n bytes" for the field where the file ends.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let left = self.bytes.len() - self.at;
        if left < N {
            return Err(format!("read {left} out of {N} bytes"));
        }
        let mut out = [0u8; N];
        out.copy_from_slice(&self.bytes[self.at..self.at + N]);
        self.at += N;
        Ok(out)
    }

    fn i32(&mut self) -> Result<i32, String> {
        Ok(i32::from_le_bytes(self.take()?))
    }

    fn f32(&mut self) -> Result<f32, String> {
        Ok(f32::from_le_bytes(self.take()?))
    }
}

impl VolumeGrid {
    /// Reads a `.vol` file. Errors are one line, without the file name (the caller adds it).
    pub fn read(path: &Path) -> Result<Self, String> {
        if !path.is_file() {
            return Err("file does not exist!".into());
        }
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read the file: {e}"))?;
        Self::parse(&bytes)
    }

    /// Parses the bytes of a `.vol` file: `VOL`, version 3, encoding 1 (float32), the x, y, z
    /// resolution and the channel count (int32), the bounding box (6 float32: min, max), then
    /// the values. Mitsuba's messages where it has one; a resolution or channel count below 1
    /// and non-finite values are refused too (Mitsuba would fail later or render NaN).
    pub fn parse(bytes: &[u8]) -> Result<Self, String> {
        let mut r = Reader { bytes, at: 0 };
        if r.take::<3>()? != *b"VOL" {
            return Err("Invalid volume file!".into());
        }
        let [version] = r.take::<1>()?;
        if version != 3 {
            return Err(format!("Invalid version, currently only version 3 is supported (found {version})"));
        }
        let encoding = r.i32()?;
        if encoding != 1 {
            return Err(format!(
                "Wrong type, currently only type == 1 (Float32) data is supported (found type = {encoding})"
            ));
        }
        let (x, y, z, channels) = (r.i32()?, r.i32()?, r.i32()?, r.i32()?);
        let mut bbox = [0f32; 6];
        for v in &mut bbox {
            *v = r.f32()?;
        }
        if x < 1 || y < 1 || z < 1 {
            return Err(format!("invalid resolution {x} × {y} × {z} (each must be at least 1)"));
        }
        if channels < 1 {
            return Err(format!("invalid channel count {channels} (must be at least 1)"));
        }
        // Counted in u64 before anything is allocated: a header may claim more than the file has.
        let count = [x, y, z, channels].iter().map(|&v| v as u64).product::<u64>();
        let left = (bytes.len() - r.at) as u64;
        if count > left / 4 {
            return Err(format!("read {} out of 4 bytes", left % 4));
        }
        let data: Vec<f32> = bytes[r.at..r.at + 4 * count as usize]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect();
        if let Some(i) = data.iter().position(|v| !v.is_finite()) {
            return Err(format!("value {} of the grid (index {i}) is not finite", data[i]));
        }
        Ok(VolumeGrid {
            res: [x as u32, y as u32, z as u32],
            channels: channels as u32,
            bbox_min: Vec3::new(bbox[0], bbox[1], bbox[2]),
            bbox_max: Vec3::new(bbox[3], bbox[4], bbox[5]),
            data,
        })
    }
}

/// `gridvolume`'s `filter_type`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GridFilter {
    Trilinear,
    Nearest,
}

/// A `gridvolume` ready to be looked up in its local space.
#[derive(Clone, Debug)]
pub struct GridVolume {
    res: [u32; 3],
    channels: u32,
    /// One RGB per voxel (a one-channel grid in all three).
    voxels: Vec<Vec3>,
    filter: GridFilter,
    wrap: WrapMode,
    mean: Vec3,
}

impl GridVolume {
    /// A grid of 1 or 3 channels (what a texture can evaluate in RGB).
    pub fn new(grid: &VolumeGrid, filter: GridFilter, wrap: WrapMode) -> Result<Self, String> {
        let voxels: Vec<Vec3> = match grid.channels {
            1 => grid.data.iter().map(|&v| Vec3::splat(v)).collect(),
            3 => grid.data.chunks_exact(3).map(|c| Vec3::new(c[0], c[1], c[2])).collect(),
            n => {
                return Err(format!(
                    "the grid has {n} channels; a volume texture is evaluated as a colour, which needs 1 or 3"
                ));
            }
        };
        let mean = voxels.iter().map(|v| v.as_dvec3()).sum::<glam::DVec3>() / voxels.len() as f64;
        Ok(GridVolume { res: grid.res, channels: grid.channels, voxels, filter, wrap, mean: mean.as_vec3() })
    }

    #[inline]
    fn voxel(&self, x: i64, y: i64, z: i64) -> Vec3 {
        let [rx, ry, rz] = self.res.map(i64::from);
        let (x, y, z) = (wrap(x, rx, self.wrap), wrap(y, ry, self.wrap), wrap(z, rz, self.wrap));
        self.voxels[((z * ry + y) * rx + x) as usize]
    }

    /// The grid at local point `p` (the unit cube spans the grid).
    #[inline]
    pub fn eval(&self, p: Vec3) -> Vec3 {
        let p = if p.is_finite() { p } else { Vec3::ZERO };
        let res = Vec3::new(self.res[0] as f32, self.res[1] as f32, self.res[2] as f32);
        match self.filter {
            GridFilter::Nearest => {
                let i = (p * res).clamp(Vec3::splat(-MAX_COORD), Vec3::splat(MAX_COORD)).floor();
                self.voxel(i.x as i64, i.y as i64, i.z as i64)
            }
            GridFilter::Trilinear => {
                let f = (p * res - 0.5).clamp(Vec3::splat(-MAX_COORD), Vec3::splat(MAX_COORD));
                let i = f.floor();
                let w1 = f - i;
                let w0 = 1.0 - w1;
                let (x, y, z) = (i.x as i64, i.y as i64, i.z as i64);
                let lerp_x = |y, z| self.voxel(x, y, z) * w0.x + self.voxel(x + 1, y, z) * w1.x;
                let lerp_y = |z| lerp_x(y, z) * w0.y + lerp_x(y + 1, z) * w1.y;
                lerp_y(z) * w0.z + lerp_y(z + 1) * w1.z
            }
        }
    }

    /// Number of channels of the file (1 or 3).
    pub fn channels(&self) -> u32 {
        self.channels
    }

    /// (x, y, z) resolution.
    pub fn resolution(&self) -> [u32; 3] {
        self.res
    }
}

/// What a volume holds.
#[derive(Clone, Debug)]
pub enum VolumeData {
    Grid(GridVolume),
    /// `constvolume`'s `value`, a colour or a texture looked up at uv = (0, 0): that lookup
    /// (`eval`) and the texture's `mean()` (its `eval_1` and mean), read once.
    Constant {
        value: Vec3,
        mean: f32,
    },
}

/// A volume (`gridvolume` or `constvolume`) with the map from world space to its local space.
#[derive(Clone, Debug)]
pub struct Volume {
    pub to_local: Affine3A,
    pub data: VolumeData,
}

impl Volume {
    /// Mitsuba's `Volume::eval` at world point `p`, in RGB.
    #[inline]
    pub fn eval(&self, p: Vec3) -> Vec3 {
        match &self.data {
            VolumeData::Grid(g) => g.eval(self.to_local.transform_point3(p)),
            VolumeData::Constant { value, .. } => *value,
        }
    }

    /// Mitsuba's `Volume::eval_1`: the value of a one-channel grid, the luminance of an RGB
    /// one; a `constvolume`'s value's `mean()`.
    #[inline]
    pub fn eval_1(&self, p: Vec3) -> f32 {
        match &self.data {
            VolumeData::Grid(g) => {
                let v = g.eval(self.to_local.transform_point3(p));
                if g.channels == 1 { v.x } else { v.dot(LUMINANCE) }
            }
            VolumeData::Constant { mean, .. } => *mean,
        }
    }

    /// Not Mitsuba's (its volume texture has no `mean()`): the voxels' mean (luminance for RGB),
    /// or a `constvolume`'s value's mean.
    pub fn mean(&self) -> f32 {
        match &self.data {
            VolumeData::Grid(g) => {
                if g.channels == 1 {
                    g.mean.x
                } else {
                    g.mean.dot(LUMINANCE)
                }
            }
            VolumeData::Constant { mean, .. } => *mean,
        }
    }
}

/// Mitsuba's `volume` texture (`src/textures/volume.cpp`): one property, `volume`, a nested or
/// referenced `<volume>` (`gridvolume`, `constvolume`), looked up at the world-space hit point.
/// Mitsuba reads it as an object (a number there is "wrong type (expected object, got float)"),
/// and without one it loads and crashes when evaluated: matte requires it.
pub(crate) fn texture_from_props(p: &mut PluginProps) -> Result<Volume, SceneError> {
    if let Some(v) = p.raw("volume") {
        let found = v.type_name();
        return Err(p.prop_err(
            "volume",
            format!(
                "has the wrong type (expected a nested <volume>, found {found}); write <volume name=\"volume\" \
                 type=\"gridvolume\"> or type=\"constvolume\""
            ),
        ));
    }
    let Some(child) = p.child("volume") else {
        // Another nested object is reported as such (unused), before the missing one.
        p.object().check_all_used()?;
        return Err(p.err(
            "missing property \"volume\" (a nested <volume name=\"volume\" type=\"gridvolume\"> or \"constvolume\")",
        ));
    };
    if child.tag != "volume" {
        return Err(crate::load::err(
            child,
            format!("\"volume\" must be a <volume> (gridvolume, constvolume), not a <{}>", child.tag),
        ));
    }
    p.build_volume(child)
}

/// Mitsuba's `gridvolume` (`src/volumes/grid.cpp`): `to_world` (invertible: points are looked
/// up through its inverse), `filename` (a `.vol` file), `filter_type` (trilinear, nearest),
/// `wrap_mode` (clamp, repeat, mirror) and `use_grid_bbox`, with Mitsuba's messages. `raw`,
/// `accel` and `max_value` are accepted without effect (`load/no_effect.rs`).
pub(crate) fn grid_from_props(p: &mut PluginProps) -> Result<Volume, SceneError> {
    let to_world = p.transform("to_world")?;
    let to_local = to_world.inverse();
    if !(to_world.matrix3.determinant() != 0.0 && to_local.is_finite()) {
        return Err(p.prop_err("to_world", "must be invertible (points are looked up through its inverse)"));
    }
    let filter = match p.string("filter_type")?.as_str() {
        "trilinear" => GridFilter::Trilinear,
        "nearest" => GridFilter::Nearest,
        other => {
            let message = format!("Invalid filter type \"{other}\", must be one of: \"nearest\" or \"trilinear\"!");
            return Err(p.prop_err("filter_type", message));
        }
    };
    let word = p.string("wrap_mode")?;
    let wrap = WrapMode::parse(&word).ok_or_else(|| {
        let message = format!("Invalid wrap mode \"{word}\", must be one of: \"repeat\", \"mirror\", or \"clamp\"!");
        p.prop_err("wrap_mode", message)
    })?;
    let use_grid_bbox = p.boolean("use_grid_bbox")?;
    let path = p.file("filename")?;
    p.object().check_all_used()?;
    let grid = VolumeGrid::read(&path).map_err(|e| p.file_err("filename", &path, &e))?;
    let to_local = if use_grid_bbox { grid_bbox(p, &path, &grid)? * to_local } else { to_local };
    let data = GridVolume::new(&grid, filter, wrap).map_err(|e| p.file_err("filename", &path, &e))?;
    Ok(Volume { to_local, data: VolumeData::Grid(data) })
}

/// `VolumeGrid::bbox_transform`: scale(1/extents)·translate(−min), applied after to_local.
fn grid_bbox(p: &PluginProps, path: &Path, grid: &VolumeGrid) -> Result<Affine3A, SceneError> {
    let extents = grid.bbox_max - grid.bbox_min;
    if !(extents.min_element() > 0.0) {
        let message = format!(
            "use_grid_bbox needs a bounding box with positive extents, the file's is {} to {}",
            grid.bbox_min, grid.bbox_max
        );
        return Err(p.file_err("filename", path, &message));
    }
    Ok(Affine3A::from_scale(extents.recip()) * Affine3A::from_translation(-grid.bbox_min))
}

/// Mitsuba's `constvolume` (`src/volumes/const.cpp`): `value`, an unbounded colour or a texture
/// (default 1), looked up at uv = (0, 0) whatever the point. Its value does not depend on the
/// point: `to_world` is read and has no effect.
pub(crate) fn constant_from_props(p: &mut PluginProps) -> Result<Volume, SceneError> {
    p.transform("to_world")?;
    let value = p.texture("value")?;
    if value.needs_surface_point() {
        let c = p.child("value").expect("a nested texture");
        return Err(crate::load::err(
            c,
            "constvolume looks its value up without a surface point: a mesh_attribute or volume texture is not supported",
        ));
    }
    let data = VolumeData::Constant { value: value.eval(glam::Vec2::ZERO), mean: value.mean() };
    Ok(Volume { to_local: Affine3A::IDENTITY, data })
}
