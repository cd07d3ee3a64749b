//! Mitsuba's `.serialized` meshes, read the way Mitsuba 3.9.1's `src/shapes/serialized.cpp`
//! reads them (format: `docs/renderer-semantics.md` §8, and the plugin's own documentation).
//!
//! A file is a sequence of meshes, each `u16 0x041C`, `u16 version` (3 or 4), then one zlib
//! stream holding `u32 flags`, (v4 only) a NUL-terminated name, `u64 vertex_count`,
//! `u64 face_count`, positions, optional normals (flag `0x1`), optional uvs (`0x2`), optional
//! colours (`0x8`), then `u32` triangle indices; `0x2000` means the float arrays are `f64`.
//! The file ends with the offset of every mesh (`u64` in v4, `u32` in v3) and `u32 count`.
//! All little endian. Decompression is `flate2` (zlib).
//!
//! As Mitsuba does:
//! * only the header of the first mesh decides the version; mesh `shape_index` is found
//!   through the end-of-file dictionary (mesh 0 starts at offset 0);
//! * positions × `to_world`; file normals × the inverse transpose, normalised; no file normals
//!   → smooth angle-weighted normals; `face_normals` drops them ([`super::loaded::finish`]);
//! * uvs are used as stored (no flip); vertex colours are skipped (Mitsuba's loader reads and
//!   discards them); the file's own `0x10` "face normals" flag is ignored (only the
//!   `face_normals` property counts).
//!
//! Stricter than Mitsuba, on files it would load into garbage or crash on: a `shape_index`
//! equal to the mesh count, a triangle index out of range, a NaN position, a zero normal and
//! a stream that ends early are errors naming the file and the problem.

use super::error::MeshError;
use super::loaded::{LoadedMesh, finish, world_normal};
use super::options::MeshOptions;
use super::triangle_mesh::TriangleMesh;
use flate2::bufread::ZlibDecoder;
use glam::{Vec2, Vec3};
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::Path;

/// The format identifier every mesh starts with.
const FORMAT_HEADER: u16 = 0x041C;
const HAS_NORMALS: u32 = 0x0001;
const HAS_TEXCOORDS: u32 = 0x0002;
const HAS_COLORS: u32 = 0x0008;
const DOUBLE_PRECISION: u32 = 0x2000;
/// zlib's largest expansion is about 1032:1; a header claiming more data than the file could
/// hold after decompression is corrupt (checked before anything is allocated).
const MAX_INFLATE_RATIO: u64 = 1040;

/// Loads mesh `shape_index` of a `.serialized` file into a world-space mesh (see the module
/// and [`super`] docs).
pub fn load_serialized(path: &Path, shape_index: i64, opts: &MeshOptions) -> Result<TriangleMesh, MeshError> {
    let fail = |message: String| MeshError::new(path, message);
    let io = |what: &str, e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::UnexpectedEof {
            fail(format!("truncated serialized file: ends inside the {what}"))
        } else {
            fail(format!("cannot read serialized file ({what}): {e}"))
        }
    };
    let file = std::fs::File::open(path).map_err(|e| fail(format!("cannot read serialized file: {e}")))?;
    let file_size = file.metadata().map_err(|e| io("file", e))?.len();
    let mut file = BufReader::new(file);
    let version = header(&mut file).map_err(|e| io("header", e))?;
    if version.0 != FORMAT_HEADER {
        return Err(fail(format!(
            "not a serialized mesh file (format identifier {:#06x}, expected 0x041c)",
            version.0
        )));
    }
    let version = version.1;
    if version != 3 && version != 4 {
        return Err(fail(format!("unsupported serialized file version {version} (Mitsuba reads versions 3 and 4)")));
    }
    if shape_index < 0 {
        return Err(fail(format!("shape_index must be nonnegative, got {shape_index}")));
    }
    if shape_index != 0 {
        let offset = mesh_offset(path, &mut file, file_size, version, shape_index as u64)?;
        file.seek(SeekFrom::Start(offset)).map_err(|e| io("dictionary", e))?;
        let h = header(&mut file).map_err(|e| io(&format!("header of mesh {shape_index}"), e))?;
        if h.0 != FORMAT_HEADER {
            return Err(fail(format!(
                "mesh {shape_index}: the dictionary's offset {offset} does not point at a mesh header"
            )));
        }
    }
    let compressed_left = file_size.saturating_sub(file.stream_position().map_err(|e| io("header", e))?);
    let mut z = ZlibDecoder::new(file);
    let mut read = |what: &str, buf: &mut [u8]| {
        z.read_exact(buf).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                fail(format!("truncated serialized file: the compressed stream ends inside the {what}"))
            } else {
                fail(format!("corrupt serialized file: cannot decompress the {what} ({e})"))
            }
        })
    };
    let flags = u32::from_le_bytes(take::<4>(&mut read, "flags")?);
    if version == 4 {
        // The mesh's name: read and dropped (Mitsuba names the shape after the file).
        let mut name_len = 0usize;
        loop {
            let [c] = take::<1>(&mut read, "mesh name")?;
            if c == 0 {
                break;
            }
            name_len += 1;
            if name_len > 1 << 16 {
                return Err(fail("corrupt serialized file: mesh name longer than 65536 bytes".into()));
            }
        }
    }
    let vertex_count = u64::from_le_bytes(take::<8>(&mut read, "vertex count")?);
    let face_count = u64::from_le_bytes(take::<8>(&mut read, "face count")?);
    let float_size: u64 = if flags & DOUBLE_PRECISION != 0 { 8 } else { 4 };
    let per_vertex =
        [(true, 3), (flags & HAS_NORMALS != 0, 3), (flags & HAS_TEXCOORDS != 0, 2), (flags & HAS_COLORS != 0, 3)]
            .iter()
            .filter(|(present, _)| *present)
            .map(|(_, dim)| dim * float_size)
            .sum::<u64>();
    let claimed =
        vertex_count.checked_mul(per_vertex).zip(face_count.checked_mul(12)).and_then(|(a, b)| a.checked_add(b));
    if claimed.is_none_or(|c| c > compressed_left.saturating_mul(MAX_INFLATE_RATIO) + 4096) {
        return Err(fail(format!(
            "corrupt serialized file: mesh {shape_index} claims {vertex_count} vertices and {face_count} triangles, \
             more than its {compressed_left} compressed bytes can hold"
        )));
    }
    if vertex_count > u32::MAX as u64 || face_count > u32::MAX as u64 {
        return Err(fail(format!("mesh {shape_index}: more than 2^32 vertices or triangles")));
    }
    let (nv, nf) = (vertex_count as usize, face_count as usize);
    let mut floats = |what: &str, dim: usize| -> Result<Vec<f32>, MeshError> {
        let mut bytes = vec![0u8; nv * dim * float_size as usize];
        read(what, &mut bytes)?;
        Ok(if float_size == 8 {
            bytes.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().unwrap()) as f32).collect()
        } else {
            bytes.chunks_exact(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect()
        })
    };
    let raw_positions = floats("vertex positions", 3)?;
    let raw_normals = if flags & HAS_NORMALS != 0 { floats("vertex normals", 3)? } else { Vec::new() };
    let raw_uvs = if flags & HAS_TEXCOORDS != 0 { floats("texture coordinates", 2)? } else { Vec::new() };
    if flags & HAS_COLORS != 0 {
        floats("vertex colours", 3)?;
    }
    let mut index_bytes = vec![0u8; nf * 12];
    read("triangle indices", &mut index_bytes)?;

    let normal_matrix = opts.normal_matrix();
    let mut positions = Vec::with_capacity(nv);
    for (i, p) in raw_positions.chunks_exact(3).enumerate() {
        let p = opts.point(Vec3::new(p[0], p[1], p[2]));
        if !p.is_finite() {
            return Err(fail(format!("mesh {shape_index}, vertex {i}: invalid position data (NaN or Inf)")));
        }
        positions.push(p);
    }
    let mut normals = Vec::new();
    if !opts.face_normals {
        for (i, n) in raw_normals.chunks_exact(3).enumerate() {
            let n = world_normal(&normal_matrix, Vec3::new(n[0], n[1], n[2])).ok_or_else(|| {
                fail(format!("mesh {shape_index}, vertex {i}: invalid normal data (zero length, NaN or Inf)"))
            })?;
            normals.push(Some(n));
        }
    }
    let uvs = raw_uvs.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])).collect();
    let mut triangles = Vec::with_capacity(nf);
    for (i, t) in index_bytes.chunks_exact(12).enumerate() {
        let mut ids = [0u32; 3];
        for (k, id) in ids.iter_mut().enumerate() {
            *id = u32::from_le_bytes(t[4 * k..4 * k + 4].try_into().unwrap());
            if *id as usize >= nv {
                return Err(fail(format!(
                    "mesh {shape_index}, triangle {i}: vertex index {id} out of range (mesh has {nv} vertices)"
                )));
            }
        }
        triangles.push(ids);
    }
    finish(path, LoadedMesh { positions, normals, uvs, triangles, attributes: Vec::new() }, opts)
}

/// `(format identifier, version)` of the mesh header at the current position.
fn header(r: &mut impl Read) -> std::io::Result<(u16, u16)> {
    let mut b = [0u8; 4];
    r.read_exact(&mut b)?;
    Ok((u16::from_le_bytes([b[0], b[1]]), u16::from_le_bytes([b[2], b[3]])))
}

/// `N` bytes from the decompressed stream.
fn take<const N: usize>(
    read: &mut impl FnMut(&str, &mut [u8]) -> Result<(), MeshError>,
    what: &str,
) -> Result<[u8; N], MeshError> {
    let mut b = [0u8; N];
    read(what, &mut b)?;
    Ok(b)
}

/// Where mesh `index` (> 0) starts, from the dictionary at the end of the file.
fn mesh_offset(
    path: &Path,
    file: &mut (impl Read + Seek),
    file_size: u64,
    version: u16,
    index: u64,
) -> Result<u64, MeshError> {
    let truncated = || MeshError::new(path, "truncated serialized file: no end-of-file dictionary");
    let mut read_at = |at: u64, buf: &mut [u8]| -> Result<(), MeshError> {
        file.seek(SeekFrom::Start(at)).map_err(|_| truncated())?;
        file.read_exact(buf).map_err(|_| truncated())
    };
    let mut count = [0u8; 4];
    read_at(file_size.checked_sub(4).ok_or_else(truncated)?, &mut count)?;
    let count = u32::from_le_bytes(count) as u64;
    if index >= count {
        return Err(MeshError::new(
            path,
            format!(
                "shape_index {index} is out of range: the file holds {count} mesh{} (0..{})",
                if count == 1 { "" } else { "es" },
                count.saturating_sub(1)
            ),
        ));
    }
    let entry = if version == 4 { 8 } else { 4 };
    let at = file_size.checked_sub(4 + entry * (count - index)).ok_or_else(truncated)?;
    let mut buf = [0u8; 8];
    read_at(at, &mut buf[..entry as usize])?;
    let offset = u64::from_le_bytes(buf);
    if offset.saturating_add(4) > file_size {
        return Err(MeshError::new(
            path,
            format!("corrupt serialized file: mesh {index} starts at {offset}, past the end of the file"),
        ));
    }
    Ok(offset)
}
