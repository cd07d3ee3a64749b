//! `<bsdf>`: which type builds each plugin name. Every type reads its own properties
//! (`from_props` in its file under `rust/render/src/bsdf/`, through [`PluginProps`]): Mitsuba's
//! `diffuse`, `twosided`, `dielectric`, `thindielectric`, `roughdielectric`, `conductor`,
//! `roughconductor`, `plastic`, `roughplastic`, `normalmap`, `null`, `bumpmap`, `mask`,
//! `blendbsdf`, `principled`, `principledthin`, and matte's registered types
//! (`matte_brdf::BSDF_TYPES`: the diffuse models and `tabulated_brdf`, built as [`Matte`] by the
//! kernels' own construction, the one the Mitsuba plugin uses). A wrapper's nested BSDF is built
//! through [`NestedBsdf`], implemented for [`Bsdf`] here beside the dispatch.

use super::builder::{Builder, err};
use super::props::{FromProps, NestedBsdf, PluginProps};
use crate::bsdf::{
    Blend, Bsdf, BumpMap, Conductor, Dielectric, Diffuse, Mask, Matte, NormalMap, Null, Plastic, Principled,
    PrincipledThin, RoughConductor, RoughDielectric, RoughPlastic, ThinDielectric, TwoSided,
};
use crate::texture::Texture;
use glam::Vec3;
use matte_brdf::BSDF_TYPES;
use matte_scene_file::SceneError;
use matte_scene_file::xml::SceneObject;

/// The BSDF index for this XML object, building it the first time it is seen.
/// A BSDF that depends on its shape (a `mesh_attribute` texture, a `bumpmap`) is built again
/// for every shape.
pub fn get_or_build(b: &mut Builder, obj: &SceneObject) -> Result<u32, SceneError> {
    let key = obj as *const SceneObject;
    if let Some(&i) = b.bsdf_index.get(&key) {
        return Ok(i);
    }
    let outer = b.shape_dependent.replace(false);
    let bsdf = build(b, obj);
    let dependent = b.shape_dependent.replace(outer);
    let bsdf = bsdf?;
    b.bsdfs.push(bsdf);
    let i = (b.bsdfs.len() - 1) as u32;
    if dependent {
        b.shape_dependent_bsdfs.insert(key);
    } else {
        b.bsdf_index.insert(key, i);
    }
    Ok(i)
}

/// A constant-colour diffuse BSDF (Mitsuba's default for shapes without one).
pub fn default_diffuse(b: &mut Builder, reflectance: f32) -> u32 {
    b.bsdfs.push(Bsdf::Diffuse(Diffuse { reflectance: Texture::Constant(Vec3::splat(reflectance)) }));
    (b.bsdfs.len() - 1) as u32
}

type Constructor = fn(&mut PluginProps) -> Result<Bsdf, SceneError>;

/// `T::from_props` as a [`Bsdf`].
fn make<T: FromProps + Into<Bsdf>>(p: &mut PluginProps) -> Result<Bsdf, SceneError> {
    T::from_props(p).map(Into::into)
}

plugins! {
    /// Mitsuba 3.9.1's BSDF plugins matte builds, each with its type.
    pub(super) MITSUBA_NAMES, MITSUBA: Constructor = [
        "diffuse" => make::<Diffuse>,
        "twosided" => make::<TwoSided<Bsdf>>,
        "dielectric" => make::<Dielectric>,
        "thindielectric" => make::<ThinDielectric>,
        "roughdielectric" => make::<RoughDielectric>,
        "conductor" => make::<Conductor>,
        "roughconductor" => make::<RoughConductor>,
        "plastic" => make::<Plastic>,
        "roughplastic" => make::<RoughPlastic>,
        "normalmap" => make::<NormalMap<Bsdf>>,
        "null" => make::<Null>,
        "bumpmap" => make::<BumpMap<Bsdf>>,
        "mask" => make::<Mask<Bsdf>>,
        "blendbsdf" => make::<Blend<Bsdf>>,
        "principled" => make::<Principled>,
        "principledthin" => make::<PrincipledThin>,
    ];
}

/// Builds the BSDF of `obj` (nested BSDFs are built by their wrapper's `from_props`).
pub(crate) fn build(b: &Builder, obj: &SceneObject) -> Result<Bsdf, SceneError> {
    let name = obj.plugin.as_str();
    let constructor = match MITSUBA.iter().find(|(n, _)| *n == name) {
        Some(&(_, c)) => c,
        None if BSDF_TYPES.contains(&name) => make::<Matte>,
        None => {
            let names: Vec<&str> = MITSUBA_NAMES.iter().chain(BSDF_TYPES.iter()).copied().collect();
            return Err(err(obj, format!("unsupported bsdf type \"{name}\" (matte renders: {})", names.join(", "))));
        }
    };
    let bsdf = constructor(&mut PluginProps::new(b, obj))?;
    obj.check_all_used()?;
    Ok(bsdf)
}

impl NestedBsdf for Bsdf {
    /// Builds a nested BSDF object of any plugin (each nested BSDF reads its own properties).
    fn from_nested(p: &PluginProps, obj: &SceneObject) -> Result<Self, SceneError> {
        build(p.builder(), obj)
    }
}
