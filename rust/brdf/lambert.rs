//! Lambert: `f = ρ/π` (research page §1). Must agree with Mitsuba's built-in `diffuse` to
//! float precision, including its sampling routine.

use super::frame::both_above;
use super::model::{Albedo, AlbedoMethod, DiffuseBrdf};
use glam::Vec3;
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Lambert;

impl DiffuseBrdf for Lambert {
    #[inline]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        if !both_above(wi, wo) {
            return [0.0; N];
        }
        reflectance.map(|rho| rho * FRAC_1_PI)
    }

    fn albedo(&self, cos_theta_i: f64, reflectance: f32) -> Albedo {
        let value = if cos_theta_i > 0.0 { reflectance as f64 } else { 0.0 };
        Albedo { value, method: AlbedoMethod::ClosedForm }
    }
}
