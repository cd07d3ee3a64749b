//! Mitsuba 0.6's `roughdiffuse` (`src/bsdfs/roughdiffuse.cpp`): Oren–Nayar with the roughness
//! given as the RMS slope `alpha` of Mitsuba's microfacet models and converted to Oren–Nayar's
//! slope-angle standard deviation by `σ = α/√2` (0.6's conversion, "a perfect fit up to
//! extreme roughness values"). `use_fast_approx` (0.6 XML: `useFastApprox`) selects the
//! qualitative model; the default is the full one. Defaults as 0.6: α = 0.2, ρ = 0.5.
//! So that scenes written for Mitsuba 0.6 render with the rough diffuse model they asked for.

use super::model::{BrdfSample, DiffuseBrdf};
use super::oren_nayar::{OrenNayar, OrenNayarModel};
use super::params::{ParamError, Params};
use super::real::Real;
use glam::{Vec2, Vec3};
use std::f64::consts::FRAC_1_SQRT_2;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoughDiffuse {
    alpha: f32,
    oren_nayar: OrenNayar,
}

impl RoughDiffuse {
    pub const DEFAULT_ALPHA: f64 = 0.2;

    /// Oren–Nayar's σ for the RMS slope α: `α/√2`.
    #[inline]
    pub fn sigma_of_alpha<T: Real>(alpha: T) -> T {
        alpha.scale(FRAC_1_SQRT_2)
    }

    pub fn new(alpha: f64, use_fast_approx: bool) -> Result<Self, ParamError> {
        if !(alpha >= 0.0) || !alpha.is_finite() {
            return Err(ParamError::new("alpha", format!("must be a finite RMS slope >= 0 (got {alpha})")));
        }
        let model = if use_fast_approx { OrenNayarModel::Qualitative } else { OrenNayarModel::Full };
        Ok(Self { alpha: alpha as f32, oren_nayar: OrenNayar::new(Self::sigma_of_alpha(alpha), model)? })
    }

    pub fn from_params(p: &mut Params) -> Result<Self, ParamError> {
        let alpha = p.number("alpha", Self::DEFAULT_ALPHA)?;
        Self::new(alpha, p.flag("use_fast_approx", false)?)
    }

    pub fn alpha(&self) -> f32 {
        self.alpha
    }

    pub fn use_fast_approx(&self) -> bool {
        self.oren_nayar.model() == OrenNayarModel::Qualitative
    }

    /// The Oren–Nayar model it evaluates.
    pub fn oren_nayar(&self) -> &OrenNayar {
        &self.oren_nayar
    }
}

impl DiffuseBrdf for RoughDiffuse {
    #[inline(always)]
    fn eval<const N: usize>(&self, wi: Vec3, wo: Vec3, reflectance: [f32; N]) -> [f32; N] {
        self.oren_nayar.eval(wi, wo, reflectance)
    }

    #[inline]
    fn sample<const N: usize>(&self, wi: Vec3, u: Vec2, reflectance: [f32; N]) -> Option<BrdfSample<N>> {
        self.oren_nayar.sample(wi, u, reflectance)
    }
}
