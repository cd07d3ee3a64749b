//! Wavefront OBJ, read the way Mitsuba's `src/shapes/obj.cpp` reads it (§8).
//!
//! Hand-written rather than `tobj`: `tobj` cannot reproduce Mitsuba's vertex sharing (one
//! output vertex per distinct `(v, vt, vn)` index triple, numbered in order of first use, with
//! no merging of equal positions), keeps no line numbers for errors, and triangulates and
//! flips texture coordinates on its own terms. The format subset Mitsuba reads is small:
//!
//! * `v x y z` (a 4th `w` is ignored), `vt u v` (a 3rd `w` is ignored), `vn x y z`; other
//!   statements (`o`, `g`, `s`, `usemtl`, `mtllib`, `#`, ...) are ignored.
//! * `f` with `v`, `v/vt`, `v//vn` or `v/vt/vn` corners; polygons are fan-triangulated
//!   (0,1,2), (0,2,3), ...; faces with fewer than 3 corners are skipped, as in Mitsuba.
//! * Negative (relative) indices count back from the last element defined so far. Mitsuba
//!   3.9.1 does NOT accept them ("reference to invalid vertex 4294967295"); supporting them
//!   only renders files Mitsuba rejects.
//! * `vt` v is flipped (v ← 1 − v) unless `flip_tex_coords = false` (default true).
//! * A `v` index must refer to a vertex defined above the face (Mitsuba checks it there);
//!   `vt`/`vn` indices may refer forward and are checked at the end.

use super::error::MeshError;
use super::loaded::{LoadedMesh, finish, world_normal};
use super::options::MeshOptions;
use super::triangle_mesh::TriangleMesh;
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// Loads an OBJ file into a world-space mesh (see the module and [`super`] docs).
pub fn load_obj(path: &Path, opts: &MeshOptions) -> Result<TriangleMesh, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::new(path, format!("cannot read OBJ file: {e}")))?;
    let flip_v = opts.flip_tex_coords.unwrap_or(true);
    let mut r = ObjReader::new(opts, flip_v);
    for raw in bytes.split(|&b| b == b'\n') {
        r.line(raw).map_err(|msg| MeshError::at(path, r.line_no, msg))?;
    }
    r.into_mesh(path, opts)
}

/// One face corner: 1-based absolute indices, 0 = absent (Mitsuba's key convention).
type Key = [u32; 3];

struct ObjReader {
    normal_matrix: glam::Mat3,
    opts: MeshOptions,
    flip_v: bool,
    positions: Vec<Vec3>,
    texcoords: Vec<Vec2>,
    normals: Vec<Vec3>,
    /// Distinct corners in order of first use, with the line that first used them.
    keys: Vec<(Key, usize)>,
    key_ids: HashMap<Key, u32>,
    triangles: Vec<[u32; 3]>,
    line_no: usize,
    face_ids: Vec<u32>,
}

impl ObjReader {
    fn new(opts: &MeshOptions, flip_v: bool) -> Self {
        ObjReader {
            normal_matrix: opts.normal_matrix(),
            opts: *opts,
            flip_v,
            positions: Vec::new(),
            texcoords: Vec::new(),
            normals: Vec::new(),
            keys: Vec::new(),
            key_ids: HashMap::new(),
            triangles: Vec::new(),
            line_no: 0,
            face_ids: Vec::new(),
        }
    }

    /// Parses one line (without its '\n'); `Err` is the message for this line.
    fn line(&mut self, raw: &[u8]) -> Result<(), String> {
        self.line_no += 1;
        let start = raw.iter().position(|b| !matches!(b, b' ' | b'\t' | b'\r')).unwrap_or(raw.len());
        let raw = &raw[start..];
        let (tag, rest) = match raw.iter().position(|b| matches!(b, b' ' | b'\t')) {
            Some(p) => (&raw[..p], &raw[p + 1..]),
            None => return Ok(()), // a lone keyword or blank line: Mitsuba ignores it too
        };
        if !matches!(tag, b"v" | b"vt" | b"vn" | b"f") {
            return Ok(());
        }
        // A trailing `# comment` is dropped (Mitsuba stops reading a face at the first
        // non-number; other junk is an error here rather than silently ignored).
        let rest = rest.iter().position(|&b| b == b'#').map_or(rest, |p| &rest[..p]);
        let text = std::str::from_utf8(rest).map_err(|_| "line is not valid UTF-8 text".to_string())?;
        let bad = || format!("could not parse line \"{}\"", String::from_utf8_lossy(raw).trim_end());
        match tag {
            b"v" => {
                let p = self.opts.point(Vec3::from(floats::<3>(text).ok_or_else(bad)?));
                if !p.is_finite() {
                    return Err("mesh contains invalid vertex position data (NaN or Inf)".into());
                }
                self.positions.push(p);
            }
            // With face_normals Mitsuba does not even parse `vn`; a placeholder keeps the
            // relative indices of later faces right.
            b"vn" if self.opts.face_normals => self.normals.push(Vec3::Z),
            b"vn" => {
                let n = Vec3::from(floats::<3>(text).ok_or_else(bad)?);
                let w = world_normal(&self.normal_matrix, n)
                    .ok_or("mesh contains invalid vertex normal data (zero length, NaN or Inf)")?;
                self.normals.push(w);
            }
            b"vt" => {
                let [u, v] = floats::<2>(text).ok_or_else(bad)?;
                if !(u.is_finite() && v.is_finite()) {
                    return Err("mesh contains invalid texture coordinate data (NaN or Inf)".into());
                }
                self.texcoords.push(Vec2::new(u, if self.flip_v { 1.0 - v } else { v }));
            }
            _ => self.face(text).map_err(|m| if m.is_empty() { bad() } else { m })?,
        }
        Ok(())
    }

    /// `f` statement: corners → shared vertex ids → fan triangles.
    fn face(&mut self, text: &str) -> Result<(), String> {
        self.face_ids.clear();
        for corner in text.split_ascii_whitespace() {
            let key = self.corner_key(corner)?;
            let id = match self.key_ids.get(&key) {
                Some(&id) => id,
                None => {
                    let id = u32::try_from(self.keys.len()).map_err(|_| "too many vertices".to_string())?;
                    self.key_ids.insert(key, id);
                    self.keys.push((key, self.line_no));
                    id
                }
            };
            self.face_ids.push(id);
        }
        for k in 2..self.face_ids.len() {
            self.triangles.push([self.face_ids[0], self.face_ids[k - 1], self.face_ids[k]]);
        }
        Ok(())
    }

    /// `v`, `v/vt`, `v//vn`, `v/vt/vn` → absolute 1-based indices (0 = absent).
    fn corner_key(&self, corner: &str) -> Result<Key, String> {
        let mut key = [0u32; 3];
        let counts = [self.positions.len(), self.texcoords.len(), self.normals.len()];
        for (slot, part) in corner.split('/').enumerate() {
            if slot >= 3 {
                return Err(String::new());
            }
            if part.is_empty() {
                if slot == 0 {
                    return Err(String::new());
                }
                continue;
            }
            let value: i64 = part.parse().map_err(|_| String::new())?;
            key[slot] = absolute_index(value, counts[slot])
                .ok_or_else(|| format!("invalid {} index {value} in face corner \"{corner}\"", KIND[slot]))?;
        }
        if key[0] as usize > self.positions.len() {
            return Err(format!(
                "reference to invalid vertex {} (only {} defined above)",
                key[0],
                self.positions.len()
            ));
        }
        Ok(key)
    }

    fn into_mesh(self, path: &Path, opts: &MeshOptions) -> Result<TriangleMesh, MeshError> {
        let has_uv = self.keys.iter().any(|(k, _)| k[1] != 0);
        let has_n = !opts.face_normals && self.keys.iter().any(|(k, _)| k[2] != 0);
        let mut positions = Vec::with_capacity(self.keys.len());
        let mut uvs = Vec::with_capacity(if has_uv { self.keys.len() } else { 0 });
        let mut normals = Vec::with_capacity(if has_n { self.keys.len() } else { 0 });
        for &(k, line) in &self.keys {
            positions.push(self.positions[k[0] as usize - 1]);
            if has_uv {
                uvs.push(match k[1] {
                    0 => Vec2::ZERO,
                    t => *self.texcoords.get(t as usize - 1).ok_or_else(|| {
                        MeshError::at(
                            path,
                            line,
                            format!("reference to invalid texture coordinate {t} (file has {})", self.texcoords.len()),
                        )
                    })?,
                });
            }
            if has_n {
                normals.push(match k[2] {
                    0 => None,
                    n => Some(*self.normals.get(n as usize - 1).ok_or_else(|| {
                        MeshError::at(
                            path,
                            line,
                            format!("reference to invalid normal {n} (file has {})", self.normals.len()),
                        )
                    })?),
                });
            }
        }
        finish(path, LoadedMesh { positions, normals, uvs, triangles: self.triangles, attributes: Vec::new() }, opts)
    }
}

const KIND: [&str; 3] = ["vertex", "texture coordinate", "normal"];

/// OBJ index → 1-based absolute index: positive as is, negative relative to `count` (the
/// number defined so far: −1 = the last one). 0 and indices before the first are invalid.
fn absolute_index(value: i64, count: usize) -> Option<u32> {
    let abs = if value < 0 { count as i64 + 1 + value } else { value };
    if abs < 1 { None } else { u32::try_from(abs).ok() }
}

/// The first `N` whitespace-separated numbers of `text` (more are ignored, as in Mitsuba).
fn floats<const N: usize>(text: &str) -> Option<[f32; N]> {
    let mut out = [0.0; N];
    let mut it = text.split_ascii_whitespace();
    for v in &mut out {
        *v = it.next()?.parse().ok()?;
    }
    Some(out)
}
