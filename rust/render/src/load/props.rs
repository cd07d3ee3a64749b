//! [`PluginProps`]: one XML object as its plugin's constructor reads it (Mitsuba's
//! `Properties` seen from `Plugin(const Properties &props)`), the one way every plugin of the
//! loader (BSDFs, emitters, shapes, sensors, films, filters, samplers, integrators, textures,
//! volumes) reads its properties. A type reads `float("alpha")`, `integer("lobes", 1..=1024)`,
//! `transform("to_world")`, `texture("reflectance")`, `emission("intensity")`,
//! `string("distribution")`, …; every error about a value names the file, line and property.
//! The default and the value kinds a name accepts come from the harvested entry for (tag,
//! plugin, name) in [`super::mitsuba_plugins`] (matte's own plugins, `tabulated_brdf` included:
//! [`MATTE_MODEL`]). Where Mitsuba's default is an expression rather than a literal (another
//! property, a constructor argument), the plugin's file supplies it, as its `.cpp` does. Each
//! type reads in its own file (`from_props`, most through [`FromProps`]). The reads that build
//! a nested object are written beside the dispatch that builds it, which this file does not
//! import: methods of [`PluginProps`] (`texture` and `emission_texture`, `build_texture` and
//! `build_volume` in `load/texture.rs`, `nested_rfilter` in `load/sensor.rs`), and for a
//! wrapper's nested BSDF [`NestedBsdf`], which `load/bsdf.rs` implements for the scene's BSDF.
//!
//! Reading a name the entry does not list, or reading it as a kind of value the plugin does not
//! accept, is a bug in the plugin's file and panics; `tests/render/load/walk.rs` loads every
//! supported plugin with each harvested property, which runs every read.

use super::builder::{Builder, err};
use super::mitsuba_plugins::{self, Kind, Plugin, PluginProperty};
use glam::{Affine2, Affine3A, DMat4, DVec4, Mat2, Mat3, Vec3};
use matte_brdf::params::{MAX_MAGNITUDE, too_large};
use matte_scene_file::SceneError;
use matte_scene_file::xml::{self, ColorUse, SceneObject, Value};
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::rc::Rc;

/// matte's registered types (`matte_brdf::BSDF_TYPES`: the diffuse models and `tabulated_brdf`):
/// `reflectance`, then every other property goes to the kernels' own construction, as in the
/// Mitsuba plugin (`cpp/matte_bsdf.h`).
pub static MATTE_MODEL: Plugin = Plugin {
    tag: "bsdf",
    name: "<matte model>",
    source: "cpp/matte_bsdf.h",
    properties: &[PluginProperty {
        name: "reflectance",
        kind: Kind::Texture,
        default: Some(".5f"),
        literal: Some("0.5"),
        source: "cpp/matte_bsdf.h:60",
    }],
    reads_any_property: true,
};

/// The entry describing what plugin (`tag`, `name`) reads: the harvested one, or matte's own.
#[must_use]
pub fn plugin_entry(tag: &str, name: &str) -> Option<&'static Plugin> {
    mitsuba_plugins::plugin(tag, name).or(match (tag, name) {
        ("bsdf", n) if matte_brdf::BSDF_TYPES.contains(&n) => Some(&MATTE_MODEL),
        _ => None,
    })
}

/// How a plugin's file reads a name: each accepts a subset of the values of some kinds.
#[derive(Clone, Copy, Debug)]
pub(super) enum Read {
    /// Whether it is given (Mitsuba's `has_property`, `type`).
    Query,
    Float,
    Integer,
    Boolean,
    String,
    Transform,
    /// A `<point>` or a `<vector>` (Mitsuba stores both as one 3-vector type).
    Point,
    /// A number or one of Mitsuba's IOR names (`lookup_ior`).
    Ior,
    /// A colour property only.
    Color,
    Texture,
    /// A colour or a texture read as emission (`get_emissive_texture`).
    Emission,
    /// A nested object of that name.
    Object,
}

impl Read {
    /// Whether a plugin reading a name as `kind` accepts every value this read takes.
    fn fits(self, kind: Kind) -> bool {
        use Kind as K;
        match self {
            Read::Query => true,
            Read::Float => matches!(kind, K::Float | K::Texture | K::UnboundedTexture | K::Any),
            Read::Integer => matches!(kind, K::Integer | K::Any),
            Read::Boolean => matches!(kind, K::Boolean | K::Any),
            Read::String => matches!(kind, K::String | K::Any),
            Read::Transform => matches!(kind, K::Transform | K::Any),
            Read::Point => matches!(kind, K::Point | K::Vector | K::Any),
            Read::Ior => matches!(kind, K::Any),
            Read::Color => matches!(kind, K::Color | K::Texture | K::UnboundedTexture),
            Read::Texture => matches!(kind, K::Texture | K::UnboundedTexture),
            Read::Emission => matches!(kind, K::EmissiveTexture),
            Read::Object => {
                matches!(kind, K::Object | K::Texture | K::UnboundedTexture | K::EmissiveTexture | K::Volume)
            }
        }
    }
}

/// A type built from its XML object, reading its own properties (Mitsuba's
/// `Plugin(const Properties &props)` constructors); errors name the file and line.
pub(crate) trait FromProps: Sized {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError>;
}

/// A BSDF that a wrapper (`twosided`, `mask`, `blendbsdf`, `normalmap`, `bumpmap`) builds from
/// one of its nested `<bsdf>` objects, whatever that object's plugin. The wrappers are generic
/// over the BSDF they nest; the scene's BSDF ([`crate::bsdf::Bsdf`], the enum that holds the
/// wrappers) implements this in `load/bsdf.rs`, beside its dispatch, so that no wrapper's file
/// names the enum.
pub(crate) trait NestedBsdf: Sized {
    /// Builds `obj`, a BSDF nested in the object `p` reads (it reads its own properties).
    fn from_nested(p: &PluginProps, obj: &SceneObject) -> Result<Self, SceneError>;
}

/// One XML object as its plugin reads it; see the module documentation.
pub(crate) struct PluginProps<'a> {
    b: &'a Builder,
    obj: &'a SceneObject,
    plugin: &'static Plugin,
    /// Names read so far (properties and named children).
    read: Vec<String>,
}

impl<'a> PluginProps<'a> {
    /// The reader for `obj`.
    ///
    /// # Panics
    /// If `obj`'s plugin has no entry ([`plugin_entry`]): the loader refuses unknown plugins
    /// before building them.
    pub fn new(b: &'a Builder, obj: &'a SceneObject) -> Self {
        let plugin = plugin_entry(&obj.tag, &obj.plugin)
            .unwrap_or_else(|| panic!("bug: no property list for {} \"{}\"", obj.tag, obj.plugin));
        PluginProps { b, obj, plugin, read: Vec::new() }
    }

    /// The XML object.
    #[must_use]
    pub fn object(&self) -> &'a SceneObject {
        self.obj
    }

    /// The scene being built (the shape a BSDF is built for, asset paths).
    #[must_use]
    pub fn builder(&self) -> &'a Builder {
        self.b
    }

    /// An error at the object's line: `bsdf "name": what`.
    #[must_use]
    pub fn err(&self, what: impl Into<String>) -> SceneError {
        err(self.obj, what)
    }

    /// An error about property `name`, at its own line when it is given.
    #[must_use]
    pub fn prop_err(&self, name: &str, what: impl Into<String>) -> SceneError {
        let obj = self.obj;
        let pos = obj.properties.iter().find(|p| p.name == name).map_or(&obj.pos, |p| &p.pos);
        SceneError::at(pos, format!("{} \"{}\": property \"{name}\" {}", obj.tag, obj.plugin, what.into()))
    }

    /// The harvested entry of `name` read as `read`; `None` for a name a plugin that reads
    /// any property (the matte models) does not list.
    ///
    /// # Panics
    /// If the plugin does not read `name`, or not as `read` (a bug in the plugin's file).
    pub(super) fn entry(&mut self, name: &str, read: Read) -> Option<&'static PluginProperty> {
        if !matches!(read, Read::Query) && !self.read.iter().any(|n| n == name) {
            self.read.push(name.to_string());
        }
        let p = self.plugin;
        let Some(e) = p.properties.iter().find(|e| e.name == name) else {
            assert!(
                p.reads_any_property,
                "bug: {} \"{}\" reads \"{name}\", which its plugin does not read ({})",
                p.tag, p.name, p.source
            );
            return None;
        };
        assert!(
            read.fits(e.kind),
            "bug: {} \"{}\" reads \"{name}\" as {read:?}, which Mitsuba reads as {:?} ({})",
            p.tag,
            p.name,
            e.kind,
            e.source
        );
        Some(e)
    }

    /// The harvested literal default of `name`.
    ///
    /// # Panics
    /// If the harvest has none (Mitsuba's default is an expression or there is none: read with
    /// an `_or` or `_opt` method and give the default in the plugin's file).
    fn literal(e: Option<&'static PluginProperty>, name: &str) -> &'static str {
        e.and_then(|e| e.literal).unwrap_or_else(|| panic!("bug: \"{name}\" has no literal default in the harvest"))
    }

    /// Checks that the plugin's file may supply the default of `name`: the harvest has no
    /// literal one (each default lives once).
    ///
    /// # Panics
    /// If the harvest has a literal default (read without `_or`).
    fn own_default(e: Option<&'static PluginProperty>, name: &str) {
        if let Some(lit) = e.and_then(|e| e.literal) {
            panic!("bug: \"{name}\" has the literal default {lit} in the harvest; read it without a default");
        }
    }

    /// Whether `name` is given, as a property or a named nested object (Mitsuba's
    /// `has_property`); marks nothing read.
    pub fn has(&mut self, name: &str) -> bool {
        self.entry(name, Read::Query);
        self.obj.properties.contains(name) || self.has_nested(name)
    }

    /// Whether `name` is given as a property (not a nested object); marks nothing read.
    pub fn has_property(&mut self, name: &str) -> bool {
        self.entry(name, Read::Query);
        self.obj.properties.contains(name)
    }

    /// Whether a nested object is named `name`; marks nothing read.
    pub(super) fn has_nested(&self, name: &str) -> bool {
        self.obj.children.iter().any(|c| c.name.as_deref() == Some(name))
    }

    /// Whether `name` is given as a nested object (a texture); marks nothing read.
    pub fn is_nested(&mut self, name: &str) -> bool {
        self.entry(name, Read::Query);
        self.has_nested(name)
    }

    /// The nested object named `name`, marked used.
    pub fn child(&mut self, name: &str) -> Option<&'a SceneObject> {
        self.entry(name, Read::Object);
        self.obj.child(name).map(|c| &*c.object)
    }

    /// The property's value as written, without marking it read (Mitsuba's `props.type`).
    pub fn raw(&mut self, name: &str) -> Option<&'a Value> {
        self.entry(name, Read::Query);
        self.obj.properties.iter().find(|p| p.name == name).map(|p| &p.value)
    }

    /// A float (or an integer), or the harvested default.
    pub fn float(&mut self, name: &str) -> Result<f64, SceneError> {
        let e = self.entry(name, Read::Float);
        match self.obj.properties.float(name)? {
            Some(v) => Ok(v),
            None => Ok(Self::literal(e, name).parse().expect("a numeric literal")),
        }
    }

    /// A float (or an integer), or `default`, the plugin's own (Mitsuba's is an expression).
    pub fn float_or(&mut self, name: &str, default: f64) -> Result<f64, SceneError> {
        Self::own_default(self.entry(name, Read::Float), name);
        Ok(self.obj.properties.float(name)?.unwrap_or(default))
    }

    /// A float (or an integer) if given.
    pub fn float_opt(&mut self, name: &str) -> Result<Option<f64>, SceneError> {
        self.entry(name, Read::Float);
        self.obj.properties.float(name)
    }

    /// A finite, strictly positive float, or the harvested default.
    pub fn positive(&mut self, name: &str) -> Result<f64, SceneError> {
        let v = self.float(name)?;
        if !(v.is_finite() && v > 0.0) {
            return Err(self.prop_err(name, format!("must be a positive number, got {v}")));
        }
        Ok(v)
    }

    /// A finite float (NaN or ∞ would give NaN pixels), or `default` (as [`Self::float_or`]).
    pub fn finite_or(&mut self, name: &str, default: f64) -> Result<f64, SceneError> {
        let v = self.float_or(name, default)?;
        if !v.is_finite() {
            return Err(self.prop_err(name, format!("must be a finite number, got {v}")));
        }
        Ok(v)
    }

    /// An integer in `range`, or the harvested default.
    pub fn integer(&mut self, name: &str, range: RangeInclusive<i64>) -> Result<i64, SceneError> {
        let e = self.entry(name, Read::Integer);
        let default = || Self::literal(e, name).parse().expect("an integer literal");
        let v = self.obj.properties.integer(name)?.unwrap_or_else(default);
        self.in_range(name, v, range)
    }

    /// An integer in `range`, or `default`, the plugin's own (Mitsuba's is an expression).
    pub fn integer_or(&mut self, name: &str, default: i64, range: RangeInclusive<i64>) -> Result<i64, SceneError> {
        Self::own_default(self.entry(name, Read::Integer), name);
        let v = self.obj.properties.integer(name)?.unwrap_or(default);
        self.in_range(name, v, range)
    }

    /// An integer if given (no range check).
    pub fn integer_opt(&mut self, name: &str) -> Result<Option<i64>, SceneError> {
        self.entry(name, Read::Integer);
        self.obj.properties.integer(name)
    }

    /// `v` if it lies in `range`, else an error naming `name`.
    fn in_range(&self, name: &str, v: i64, range: RangeInclusive<i64>) -> Result<i64, SceneError> {
        if !range.contains(&v) {
            return Err(self.prop_err(name, format!("must be in [{}, {}], got {v}", range.start(), range.end())));
        }
        Ok(v)
    }

    /// A boolean, or the harvested default.
    pub fn boolean(&mut self, name: &str) -> Result<bool, SceneError> {
        let e = self.entry(name, Read::Boolean);
        match self.obj.properties.boolean(name)? {
            Some(v) => Ok(v),
            None => Ok(Self::literal(e, name).parse().expect("a boolean literal")),
        }
    }

    /// A boolean if given.
    pub fn boolean_opt(&mut self, name: &str) -> Result<Option<bool>, SceneError> {
        self.entry(name, Read::Boolean);
        self.obj.properties.boolean(name)
    }

    /// A string, or the harvested default.
    pub fn string(&mut self, name: &str) -> Result<String, SceneError> {
        let e = self.entry(name, Read::String);
        match self.obj.properties.string(name)? {
            Some(v) => Ok(v),
            None => Ok(Self::literal(e, name).to_string()),
        }
    }

    /// A string if given.
    pub fn string_opt(&mut self, name: &str) -> Result<Option<String>, SceneError> {
        self.entry(name, Read::String);
        self.obj.properties.string(name)
    }

    /// A string Mitsuba requires (no default): "missing property" when absent.
    pub fn required_string(&mut self, name: &str) -> Result<String, SceneError> {
        self.string_opt(name)?.ok_or_else(|| self.err(format!("missing property \"{name}\"")))
    }

    /// A 4×4 transform (`to_world`) as an f32 affine map; absent, the identity (Mitsuba's
    /// default, `ScalarAffineTransform4f()`). Projective rows and non-finite entries are
    /// errors (Mitsuba's shapes, emitters and sensors use affine transforms).
    pub fn transform(&mut self, name: &str) -> Result<Affine3A, SceneError> {
        self.entry(name, Read::Transform);
        match self.obj.properties.transform(name)? {
            None => Ok(Affine3A::IDENTITY),
            Some(m) => to_affine(&m).ok_or_else(|| self.prop_err(name, "must be affine (last row 0 0 0 1) and finite")),
        }
    }

    /// A texture's `to_uv` as a 2-D affine map: the upper-left 2×2 block and the translation
    /// column of the 4×4 transform (Mitsuba's `Properties::get<AffineTransform3f>`); absent,
    /// the identity.
    pub fn uv_transform(&mut self, name: &str) -> Result<Affine2, SceneError> {
        self.entry(name, Read::Transform);
        let Some(m) = self.obj.properties.transform(name)? else { return Ok(Affine2::IDENTITY) };
        let a = Mat2::from_cols(m.x_axis.truncate().truncate().as_vec2(), m.y_axis.truncate().truncate().as_vec2());
        Ok(Affine2::from_mat2_translation(a, m.w_axis.truncate().truncate().as_vec2()))
    }

    /// A point (or a vector), or the harvested default (a number: all three coordinates).
    pub fn point(&mut self, name: &str) -> Result<Vec3, SceneError> {
        let e = self.entry(name, Read::Point);
        match self.obj.properties.point(name)? {
            Some(p) => Ok(p.as_vec3()),
            None => Ok(Vec3::splat(Self::literal(e, name).parse().expect("a numeric literal"))),
        }
    }

    /// A point (or a vector), or `default`, the plugin's own (Mitsuba's is an expression).
    pub fn point_or(&mut self, name: &str, default: Vec3) -> Result<Vec3, SceneError> {
        Self::own_default(self.entry(name, Read::Point), name);
        Ok(self.obj.properties.point(name)?.map_or(default, |p| p.as_vec3()))
    }

    /// A point or a vector if given.
    pub fn point_opt(&mut self, name: &str) -> Result<Option<Vec3>, SceneError> {
        self.entry(name, Read::Point);
        Ok(self.obj.properties.point(name)?.map(|p| p.as_vec3()))
    }

    /// An index of refraction: a number or a name from Mitsuba's table (`lookup_ior`, shared
    /// with the kernels), default the harvested one (`"bk7"`, `"air"`, …); ≥ 1 and finite.
    pub fn ior(&mut self, name: &str) -> Result<f32, SceneError> {
        let e = self.entry(name, Read::Ior);
        let unknown = |s: &str| self.prop_err(name, format!("unknown IOR name \"{s}\""));
        let v = match self.obj.properties.get(name).map(|p| &p.value) {
            None => {
                let lit = Self::literal(e, name);
                lit.parse().ok().or_else(|| matte_brdf::params::lookup_ior(lit)).ok_or_else(|| unknown(lit))?
            }
            Some(Value::String(s)) => matte_brdf::params::lookup_ior(s).ok_or_else(|| unknown(s))?,
            Some(_) => self.obj.properties.float(name)?.unwrap_or_default(),
        };
        if !(v.is_finite() && v >= 1.0) {
            return Err(self.prop_err(name, format!("must be ≥ 1, got {v}")));
        }
        if v > MAX_MAGNITUDE {
            return Err(self.prop_err(name, too_large(v)));
        }
        Ok(v as f32)
    }

    /// `int_ior / ext_ior` (in f32, as Mitsuba); the two must differ (Mitsuba's
    /// `roughdielectric` and `roughplastic`: "must be positive and differ").
    pub fn relative_ior(&mut self) -> Result<f32, SceneError> {
        let (int_ior, ext_ior) = (self.ior("int_ior")?, self.ior("ext_ior")?);
        if int_ior == ext_ior {
            return Err(self.prop_err("int_ior", format!("must differ from ext_ior (both are {int_ior})")));
        }
        Ok(int_ior / ext_ior)
    }

    /// How a texture or colour read as `kind` is checked (docs/renderer-semantics.md §2).
    pub(super) fn usage(e: Option<&'static PluginProperty>) -> ColorUse {
        match e.map(|e| e.kind) {
            Some(Kind::Texture | Kind::Color) => ColorUse::Bounded,
            Some(Kind::EmissiveTexture) => ColorUse::Emissive,
            _ => ColorUse::Unbounded,
        }
    }

    /// The harvested default of a colour or texture, as a grey.
    pub(super) fn grey_default(e: Option<&'static PluginProperty>) -> Option<Vec3> {
        e.and_then(|e| e.literal).map(|l| Vec3::splat(l.parse().expect("a numeric literal")))
    }

    /// A constant colour property read as `usage` demands (docs/renderer-semantics.md §2), or
    /// `default`. NaN or ∞ is an error for every usage, and so is a negative reflectance-like
    /// value (`<float>`/`<spectrum>`; the parser already rejects an `<rgb>` outside [0, 1]).
    /// Mitsuba takes such floats silently; they would only produce NaN or negative pixels. A
    /// `<float>` reflectance above 1 stays allowed, as in Mitsuba.
    pub(super) fn colour_value(&self, name: &str, usage: ColorUse, default: Vec3) -> Result<Vec3, SceneError> {
        let Some(c) = self.obj.properties.color(name, usage)? else { return Ok(default) };
        let v = Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32);
        if !v.is_finite() {
            return Err(self.prop_err(name, format!("must be finite, got {v}")));
        }
        if usage == ColorUse::Bounded && v.min_element() < 0.0 {
            return Err(self.prop_err(name, format!("must not be negative, got {v}")));
        }
        Ok(v)
    }

    /// A constant colour property (a nested object of that name is not looked at), or the
    /// harvested default.
    pub fn color(&mut self, name: &str) -> Result<Vec3, SceneError> {
        let e = self.entry(name, Read::Color);
        self.colour_value(name, Self::usage(e), Self::grey_default(e).unwrap_or(Vec3::ZERO))
    }

    /// A constant colour that Mitsuba reads as a texture but matte only as a constant (the
    /// specular BSDFs' `specular_*` weights), or the harvested default.
    pub fn constant_color(&mut self, name: &str) -> Result<Vec3, SceneError> {
        let e = self.entry(name, Read::Color);
        Ok(self.optional_constant_color(name)?.unwrap_or_else(|| Self::grey_default(e).unwrap_or(Vec3::ONE)))
    }

    /// As [`Self::constant_color`], `None` when not given (Mitsuba only multiplies with it
    /// when it is given).
    pub fn optional_constant_color(&mut self, name: &str) -> Result<Option<Vec3>, SceneError> {
        let e = self.entry(name, Read::Color);
        if self.obj.child(name).is_some() {
            return Err(self.err(format!("a texture for \"{name}\" is not supported by matte render")));
        }
        if !self.obj.properties.contains(name) {
            return Ok(None);
        }
        self.colour_value(name, Self::usage(e), Vec3::ONE).map(Some)
    }

    /// A constant emitted colour (`radiance`, `intensity`, `irradiance`: no range check, a
    /// `<spectrum value=v>` is not white, docs/renderer-semantics.md §2), or the harvested
    /// default; a texture there is refused.
    pub fn emission(&mut self, name: &str) -> Result<Vec3, SceneError> {
        let e = self.entry(name, Read::Emission);
        if self.obj.child(name).is_some() {
            return Err(self.err(format!("a texture for \"{name}\" is not supported by matte render")));
        }
        self.colour_value(name, ColorUse::Emissive, Self::grey_default(e).unwrap_or(Vec3::ONE))
    }

    /// The nested objects with element name `tag` (`"bsdf"`, `"texture"`), in document order,
    /// whatever their names (Mitsuba's `props.objects()`); marked used.
    pub fn nested(&mut self, tag: &str) -> Vec<Rc<SceneObject>> {
        self.obj.children_with_tag(tag).map(|c| c.object.clone()).collect()
    }

    /// An asset file name resolved as Mitsuba's file resolver does.
    #[must_use]
    pub fn resolve(&self, file: &str) -> PathBuf {
        self.b.resolve(file)
    }

    /// The asset file named by property `name` (required), resolved ([`Self::resolve`]).
    pub fn file(&mut self, name: &str) -> Result<PathBuf, SceneError> {
        let file = self.required_string(name)?;
        Ok(self.resolve(&file))
    }

    /// An error about the asset file `path` named by property `name`: `"path": message`, the
    /// message's first line (scene errors are one line).
    #[must_use]
    pub fn file_err(&self, name: &str, path: &Path, message: &str) -> SceneError {
        self.prop_err(name, format!("\"{}\": {}", path.display(), one_line(message)))
    }

    /// The properties not read so far, in document order, marked used (for a plugin that
    /// reads any property).
    ///
    /// # Panics
    /// If the plugin does not read any property.
    pub fn remaining_properties(&mut self) -> Vec<&'a xml::Property> {
        assert!(self.plugin.reads_any_property, "bug: {} does not read any property", self.plugin.name);
        let rest: Vec<&'a xml::Property> =
            self.obj.properties.iter().filter(|p| !self.read.contains(&p.name)).collect();
        for p in &rest {
            p.used.set(true);
            self.read.push(p.name.clone());
        }
        rest
    }

    /// The names of the named nested objects not read so far, in document order (for a plugin
    /// that reads any property).
    ///
    /// # Panics
    /// If the plugin does not read any property.
    pub fn remaining_nested_names(&self) -> Vec<String> {
        assert!(self.plugin.reads_any_property, "bug: {} does not read any property", self.plugin.name);
        self.obj.children.iter().filter_map(|c| c.name.clone()).filter(|n| !self.read.iter().any(|r| r == n)).collect()
    }
}

/// `m` as an f32 affine map, or `None` when its last row is not (0 0 0 1) or it is not finite.
fn to_affine(m: &DMat4) -> Option<Affine3A> {
    if m.row(3) != DVec4::new(0.0, 0.0, 0.0, 1.0) || !m.is_finite() {
        return None;
    }
    let m3 =
        Mat3::from_cols(m.x_axis.truncate().as_vec3(), m.y_axis.truncate().as_vec3(), m.z_axis.truncate().as_vec3());
    Some(Affine3A::from_mat3_translation(m3, m.w_axis.truncate().as_vec3()))
}

/// The first non-empty line of a message from a file-format library (ply-rs-bw, for one,
/// appends its parser state over several lines): scene errors are one line.
#[must_use]
pub fn one_line(msg: &str) -> &str {
    msg.lines().map(str::trim).find(|l| !l.is_empty()).unwrap_or("")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn builder() -> Builder {
        Builder {
            base_dir: PathBuf::new(),
            search_paths: Vec::new(),
            bsdfs: Vec::new(),
            bsdf_index: std::collections::HashMap::new(),
            shapes: Vec::new(),
            emitters: Vec::new(),
            sampling_weights: Vec::new(),
            shape: None,
            shape_dependent: std::cell::Cell::new(false),
            shape_dependent_bsdfs: std::collections::HashSet::new(),
            area_emitters: std::collections::HashSet::new(),
        }
    }

    /// The first `<bsdf>` of a scene holding `xml`.
    fn bsdf_object(xml: &str) -> Rc<SceneObject> {
        let text = format!("<scene version=\"3.0.0\">{xml}</scene>");
        let root = xml::parse_str(&text, std::path::Path::new("/virtual/props.xml"), &[]).unwrap();
        root.children.iter().find(|c| c.object.tag == "bsdf").unwrap().object.clone()
    }

    #[test]
    fn defaults_come_from_the_harvest() {
        let b = builder();
        let obj = bsdf_object(r#"<bsdf type="roughconductor"/>"#);
        let mut p = PluginProps::new(&b, &obj);
        assert_eq!(p.float("alpha").unwrap(), 0.1);
        assert!(p.boolean("sample_visible").unwrap());
        assert_eq!(p.string("material").unwrap(), "none");
        assert_eq!(p.color("k").unwrap(), Vec3::ONE);
        let obj = bsdf_object(r#"<bsdf type="dielectric"/>"#);
        let mut p = PluginProps::new(&b, &obj);
        assert_eq!(p.ior("int_ior").unwrap(), 1.5046);
        assert_eq!(p.ior("ext_ior").unwrap(), 1.000277);
    }

    #[test]
    #[should_panic(expected = "which its plugin does not read")]
    fn reading_a_name_the_plugin_does_not_read_is_a_bug() {
        let b = builder();
        let obj = bsdf_object(r#"<bsdf type="diffuse"/>"#);
        let _ = PluginProps::new(&b, &obj).float("alpha");
    }

    #[test]
    #[should_panic(expected = "which Mitsuba reads as Boolean")]
    fn reading_a_name_as_another_kind_is_a_bug() {
        let b = builder();
        let obj = bsdf_object(r#"<bsdf type="twosided"/>"#);
        let _ = PluginProps::new(&b, &obj).float("allow_transmission");
    }
}
