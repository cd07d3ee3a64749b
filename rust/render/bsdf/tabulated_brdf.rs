//! `<bsdf type="tabulated_brdf">`: a BRDF read from a table file
//! (`crate::brdf::tabulated`, `docs/microgeometry.md#the-tabulated-ground-truth-brdf`), such as
//! the simulated microsurface `matte microgeometry --table` writes. Reflectance per RGB channel
//! (the table is non-linear in ρ), one-sided like the matte models, cosine-weighted sampling.

use super::BsdfSample;
use crate::brdf::DiffuseBrdf;
use crate::brdf::tabulated::BrdfTable;
use crate::render::texture::Texture;
use glam::{Vec2, Vec3};
use std::sync::Arc;

#[derive(Clone, Debug)]
pub struct TabulatedBrdf {
    pub table: Arc<BrdfTable>,
    pub reflectance: Texture,
}

/// `(f·cos θo, pdf)`.
#[inline]
pub fn eval_pdf(table: &BrdfTable, rho: Vec3, wi: Vec3, wo: Vec3) -> (Vec3, f32) {
    if wi.z <= 0.0 || wo.z <= 0.0 {
        return (Vec3::ZERO, 0.0);
    }
    (Vec3::from_array(table.eval::<3>(wi, wo, rho.to_array())) * wo.z, table.pdf(wi, wo))
}

#[inline]
pub fn sample(table: &BrdfTable, rho: Vec3, wi: Vec3, u: Vec2) -> Option<BsdfSample> {
    if wi.z <= 0.0 {
        return None;
    }
    let s = table.sample::<3>(wi, u, rho.to_array())?;
    if !(s.pdf > 0.0) {
        return None;
    }
    Some(BsdfSample { wo: s.wo, weight: Vec3::from_array(s.weight), pdf: s.pdf, delta: false, eta: 1.0 })
}
