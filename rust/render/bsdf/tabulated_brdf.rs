//! `<bsdf type="tabulated_brdf">`: a BRDF read from a table file
//! (`matte_brdf::tabulated`, `docs/microgeometry.md#the-tabulated-ground-truth-brdf`), such as
//! the simulated microsurface `matte microgeometry --table` writes. Reflectance per RGB channel
//! (the table is non-linear in ρ), one-sided like the matte models, cosine-weighted sampling.
//! The interpolation is the generic kernel the Mitsuba plugin runs ([`TableModel`]).
//! Properties: `filename` (required) and `reflectance` (a texture, default 0.5).

use super::{BsdfFlags, BsdfModel, BsdfSample};
use crate::load::props::{FromProps, PluginProps};
use crate::shape::SurfaceInteraction;
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use matte_brdf::DiffuseBrdf;
use matte_brdf::tabulated::TableModel;
use matte_scene_file::SceneError;
use std::sync::Arc;

/// `tabulated_brdf`: the table and the reflectance ρ.
#[derive(Clone, Debug)]
pub struct TabulatedBrdf {
    pub table: Arc<TableModel>,
    pub reflectance: Texture,
}

impl FromProps for TabulatedBrdf {
    fn from_props(p: &mut PluginProps) -> Result<Self, SceneError> {
        let reflectance = p.texture("reflectance")?;
        let filename = p.string_opt("filename")?.ok_or_else(|| p.err("missing property \"filename\""))?;
        let path = p.resolve(&filename);
        let table = TableModel::read(&path).map_err(|e| p.prop_err("filename", crate::load::values::one_line(&e)))?;
        Ok(TabulatedBrdf { table: Arc::new(table), reflectance })
    }
}

/// `(f·cos θo, pdf)`.
#[inline]
pub fn eval_pdf(table: &TableModel, rho: Vec3, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    (Vec3::from_array(table.eval::<3>(wi, wo, rho.to_array())) * wo.z, table.pdf(wi, wo))
}

#[inline]
pub fn sample(table: &TableModel, rho: Vec3, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wi.z <= 0.0 {
        return None;
    }
    let s = table.sample::<3>(wi, u, rho.to_array())?;
    if !(s.pdf > 0.0) {
        return None;
    }
    Some(BsdfSample { wo: s.wo, weight: Vec3::from_array(s.weight), pdf: s.pdf, delta: false, eta: 1.0 })
}

impl BsdfModel for TabulatedBrdf {
    #[inline]
    fn eval_pdf(&self, si: &SurfaceInteraction, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
        eval_pdf(&self.table, self.reflectance.eval(si), wi, wo)
    }

    #[inline]
    fn sample(&self, si: &SurfaceInteraction, wi: Vec3, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        sample(&self.table, self.reflectance.eval(si), wi, u)
    }

    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::DIFFUSE_REFLECTION | BsdfFlags::FRONT_SIDE
    }
}
