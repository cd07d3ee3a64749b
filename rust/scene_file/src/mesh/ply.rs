//! Stanford PLY (ascii, binary little and big endian) through `ply-rs-bw`, with the property
//! conventions of Mitsuba's `src/shapes/ply.cpp` (§8):
//!
//! * vertex `x y z` (required), `nx ny nz` (used only if all three exist and
//!   `face_normals = false`), texture coordinates from the first complete pair of `u v`,
//!   `texture_u texture_v`, `s t`; `flip_tex_coords` default **false**.
//! * face list `vertex_index` (preferred when both exist) or `vertex_indices`.
//! * other scalar vertex and face properties become mesh attributes by Mitsuba's naming
//!   rules ([`super::ply_attributes`]), e.g. `color_0 color_1 color_2` → `vertex_color`;
//!   integer-typed ones are normalised to [0, 1] by their type's maximum (Mitsuba warns
//!   that colours should be in [0, 1]). A face attribute is repeated for every triangle of
//!   a fan-triangulated polygon.
//! * other elements are skipped.
//!
//! Deviations, all on files Mitsuba 3.9.1 cannot load correctly: polygons are
//! fan-triangulated (Mitsuba accepts only triangles); face indices are range-checked (Mitsuba
//! does not check); integer-typed coordinates are rejected (Mitsuba silently normalises them
//! to [0, 1] like colours, which is never what a mesh means); zero-length normals are
//! rejected (Mitsuba would produce NaN).

use super::attribute::MeshAttribute;
use super::error::MeshError;
use super::loaded::{LoadedMesh, finish, world_normal};
use super::options::MeshOptions;
use super::ply_attributes::{AttributeFields, find_attributes};
use super::triangle_mesh::TriangleMesh;
use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Encoding, Header, Property, PropertyAccess, PropertyAccessResult};
use std::cell::RefCell;
use std::io::{BufReader, Read};
use std::path::Path;

/// Loads a PLY file into a world-space mesh (see the module and [`super`] docs).
pub fn load_ply(path: &Path, opts: &MeshOptions) -> Result<TriangleMesh, MeshError> {
    let file = std::fs::File::open(path).map_err(|e| MeshError::new(path, format!("cannot read PLY file: {e}")))?;
    let mut reader = Reader::new(BufReader::new(file));
    let parser = Parser::<Record>::new();
    let fail = |e: ply_rs_bw::parser::ParseError| {
        // The line goes into MeshError::line, not twice into the message.
        let text = e.to_string();
        let text = e.line().and_then(|l| text.strip_prefix(&format!("Line {l}: ")).map(str::to_string)).unwrap_or(text);
        MeshError { path: path.to_path_buf(), line: e.line(), message: format!("invalid PLY file: {text}") }
    };
    let header = parser.read_header(&mut reader).map_err(fail)?;
    let layout = Layout::of(path, &header, opts)?;
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for (name, def) in header.elements.iter() {
        let extra = match name.as_str() {
            "vertex" => &layout.vertex_attributes,
            "face" => &layout.face_attributes,
            _ => &Vec::new(),
        };
        EXTRA_FIELDS.with(|f| *f.borrow_mut() = extra.iter().flat_map(|a| a.fields.iter().cloned()).collect());
        let records = parser.read_payload_for_element(&mut reader, def, &header).map_err(fail);
        EXTRA_FIELDS.with(|f| f.borrow_mut().clear());
        match name.as_str() {
            "vertex" => vertices = records?,
            "face" => faces = records?,
            _ => drop(records?),
        }
    }
    if header.encoding != Encoding::Ascii {
        let mut rest = [0u8; 1];
        if reader.get_mut().read(&mut rest).map_err(|e| MeshError::new(path, e.to_string()))? != 0 {
            return Err(MeshError::new(path, "invalid PLY file: trailing content after the last element"));
        }
    }
    build(path, &layout, &vertices, &faces, opts)
}

thread_local! {
    /// The attribute properties of the element being read, in [`Record::extra`] order
    /// (`PropertyAccess::new` has no way to receive them).
    static EXTRA_FIELDS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Which properties of the header are used (decided once, from the header).
struct Layout {
    normals: bool,
    /// Slots in [`Record::values`] of the u and v coordinates.
    uv: Option<(usize, usize)>,
    /// Use `vertex_index` (true) or `vertex_indices` (false).
    vertex_index: bool,
    vertex_attributes: Vec<AttributeFields>,
    face_attributes: Vec<AttributeFields>,
}

/// Scalar property names of an element, in file order.
fn scalar_properties(e: &ElementDef) -> Vec<String> {
    use ply_rs_bw::ply::PropertyType;
    e.properties.values().filter(|p| matches!(p.data_type, PropertyType::Scalar(_))).map(|p| p.name.clone()).collect()
}

/// Names of the scalar vertex properties read, in [`Record::values`] order.
const NAMES: [&str; 12] = ["x", "y", "z", "nx", "ny", "nz", "u", "v", "texture_u", "texture_v", "s", "t"];

impl Layout {
    fn of(path: &Path, header: &Header, opts: &MeshOptions) -> Result<Layout, MeshError> {
        let vertex =
            header.elements.get("vertex").ok_or_else(|| MeshError::new(path, "PLY file has no \"vertex\" element"))?;
        let has = |e: &ElementDef, n: &str| e.properties.contains_key(n);
        for n in ["x", "y", "z"] {
            if !has(vertex, n) {
                return Err(MeshError::new(path, format!("PLY vertex element has no \"{n}\" property")));
            }
        }
        let normals = !opts.face_normals && ["nx", "ny", "nz"].iter().all(|n| has(vertex, n));
        let uv = [(6, 7), (8, 9), (10, 11)].into_iter().find(|&(a, b)| has(vertex, NAMES[a]) && has(vertex, NAMES[b]));
        let face = header
            .elements
            .get("face")
            .ok_or_else(|| MeshError::new(path, "mesh has no triangles (PLY file has no \"face\" element)"))?;
        let vertex_index = if has(face, "vertex_index") {
            true
        } else if has(face, "vertex_indices") {
            false
        } else {
            return Err(MeshError::new(path, "PLY face element has no \"vertex_index\"/\"vertex_indices\" property"));
        };
        let vertex_attributes =
            find_attributes("vertex", &scalar_properties(vertex), &["x", "y", "z", "nx", "ny", "nz", "u", "v"]);
        let face_attributes = find_attributes("face", &scalar_properties(face), &["vertex_index", "vertex_indices"]);
        Ok(Layout { normals, uv, vertex_index, vertex_attributes, face_attributes })
    }
}

fn build(
    path: &Path,
    layout: &Layout,
    vertices: &[Record],
    faces: &[Record],
    opts: &MeshOptions,
) -> Result<TriangleMesh, MeshError> {
    let flip_v = opts.flip_tex_coords.unwrap_or(false);
    let normal_matrix = opts.normal_matrix();
    let mut positions = Vec::with_capacity(vertices.len());
    let mut normals = Vec::with_capacity(if layout.normals { vertices.len() } else { 0 });
    let mut uvs = Vec::with_capacity(if layout.uv.is_some() { vertices.len() } else { 0 });
    for (i, r) in vertices.iter().enumerate() {
        let f = |k: usize| r.values[k] as f32;
        let p = opts.point(Vec3::new(f(0), f(1), f(2)));
        if !p.is_finite() {
            return Err(MeshError::new(path, format!("vertex {i}: invalid position data (NaN or Inf)")));
        }
        positions.push(p);
        if layout.normals {
            let n = world_normal(&normal_matrix, Vec3::new(f(3), f(4), f(5))).ok_or_else(|| {
                MeshError::new(path, format!("vertex {i}: invalid normal data (zero length, NaN or Inf)"))
            })?;
            normals.push(Some(n));
        }
        if let Some((a, b)) = layout.uv {
            let (u, v) = (f(a), f(b));
            if !(u.is_finite() && v.is_finite()) {
                return Err(MeshError::new(path, format!("vertex {i}: invalid texture coordinate data (NaN or Inf)")));
            }
            uvs.push(Vec2::new(u, if flip_v { 1.0 - v } else { v }));
        }
    }
    let mut triangles = Vec::with_capacity(faces.len());
    // The face each triangle comes from (for face attributes).
    let mut source_face = Vec::with_capacity(faces.len());
    for (i, r) in faces.iter().enumerate() {
        let idx = if layout.vertex_index { &r.vertex_index } else { &r.vertex_indices };
        let mut ids = [0u32; 3];
        for (k, &v) in idx.iter().enumerate() {
            let id = u32::try_from(v).ok().filter(|&id| (id as usize) < positions.len()).ok_or_else(|| {
                MeshError::new(
                    path,
                    format!("face {i}: vertex index {v} out of range (file has {} vertices)", positions.len()),
                )
            })?;
            match k {
                0..=2 => ids[k] = id,
                _ => (ids[1], ids[2]) = (ids[2], id),
            }
            if k >= 2 {
                triangles.push(ids);
                source_face.push(i);
            }
        }
    }
    let mut attributes = Vec::new();
    for (list, records, per_face) in
        [(&layout.vertex_attributes, vertices, false), (&layout.face_attributes, faces, true)]
    {
        let mut offset = 0;
        for a in list {
            let dim = a.fields.len();
            let entry = |r: &Record, out: &mut Vec<f32>| out.extend((0..dim).map(|k| r.extra[offset + k] as f32));
            let mut values = Vec::new();
            if per_face {
                values.reserve(triangles.len() * dim);
                for &f in &source_face {
                    entry(&faces[f], &mut values);
                }
            } else {
                values.reserve(records.len() * dim);
                for r in records {
                    entry(r, &mut values);
                }
            }
            attributes.push(MeshAttribute { name: a.name.clone(), dim, per_face, values });
            offset += dim;
        }
    }
    finish(path, LoadedMesh { positions, normals, uvs, triangles, attributes }, opts)
}

/// One PLY element as read: the known scalar vertex properties (as f64) and the face lists.
/// A single type serves every element, so unknown elements are read and dropped.
#[derive(Default)]
struct Record {
    values: [f64; 12],
    vertex_index: Vec<i64>,
    vertex_indices: Vec<i64>,
    /// Attribute properties, in the order of [`EXTRA_FIELDS`].
    extra: Vec<f64>,
}

impl Record {
    fn slot(name: &str) -> Option<usize> {
        NAMES.iter().position(|&n| n == name)
    }

    fn set_real(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        match Self::slot(name) {
            Some(k) => {
                self.values[k] = value;
                PropertyAccessResult::Set
            }
            None => self.set_extra(name, value),
        }
    }

    fn set_extra(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        match EXTRA_FIELDS.with(|f| f.borrow().iter().position(|n| n == name)) {
            Some(k) => {
                self.extra[k] = value;
                PropertyAccessResult::Set
            }
            None => PropertyAccessResult::Ignored,
        }
    }

    fn set_list(&mut self, name: &str, values: impl Iterator<Item = i64>) -> PropertyAccessResult {
        let target = match name {
            "vertex_index" => &mut self.vertex_index,
            "vertex_indices" => &mut self.vertex_indices,
            _ => return PropertyAccessResult::Ignored,
        };
        target.clear();
        target.extend(values);
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for Record {
    fn new() -> Self {
        let n = EXTRA_FIELDS.with(|f| f.borrow().len());
        Record { extra: vec![0.0; n], ..Record::default() }
    }

    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.set_real(name, value as f64)
    }

    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.set_real(name, value)
    }

    /// Integer scalars and float lists end here: an error for the geometry properties we
    /// read, normalised by the type's maximum for attributes.
    fn set_property(&mut self, name: &str, value: Property) -> PropertyAccessResult {
        if Self::slot(name).is_some() || matches!(name, "vertex_index" | "vertex_indices") {
            return PropertyAccessResult::UnsupportedType;
        }
        let normalised = match value {
            Property::Char(v) => v as f64 / i8::MAX as f64,
            Property::UChar(v) => v as f64 / u8::MAX as f64,
            Property::Short(v) => v as f64 / i16::MAX as f64,
            Property::UShort(v) => v as f64 / u16::MAX as f64,
            Property::Int(v) => v as f64 / i32::MAX as f64,
            Property::UInt(v) => v as f64 / u32::MAX as f64,
            _ => return PropertyAccessResult::Ignored,
        };
        self.set_extra(name, normalised)
    }

    fn set_list_char(&mut self, name: &str, value: Vec<i8>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }

    fn set_list_uchar(&mut self, name: &str, value: Vec<u8>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }

    fn set_list_short(&mut self, name: &str, value: Vec<i16>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }

    fn set_list_ushort(&mut self, name: &str, value: Vec<u16>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }

    fn set_list_int(&mut self, name: &str, value: Vec<i32>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }

    fn set_list_uint(&mut self, name: &str, value: Vec<u32>) -> PropertyAccessResult {
        self.set_list(name, value.into_iter().map(i64::from))
    }
}
