//! Kernels whose parameters vary per lane: a model's numeric parameters given as values of
//! the scalar type (a texture's value at the hit), not fixed at construction
//! (`docs/models.md#spatially-varying-parameters`). The constants are computed from them on
//! every call by the same generic constructors as the constant path (`OrenNayarKernel::new`,
//! `EonKernel::new`, …): in f32 by the Rust renderer and the scalar plugin variants, traced
//! (so per lane, with the texture's gradient) by the JIT variants.
//!
//! Values come in the order of [`DiffuseModel::parameters`]' numbers (`oren_nayar`: σ; `eon`: r;
//! `wolff`: int_ior, ext_ior; `ginneken`: m; `roughdiffuse`: α) and are clamped into the
//! model's valid range, since a texture is not validated as a number is: σ, α ≥ 0;
//! r ∈ [0, 1]; ext_ior ≥ 1 and n = int_ior/ext_ior ≥ 1; m ∈ [0.02, 4] (the roughness axis).
//! NaN maps to the lower bound (`Real::max`). Wolff's Fresnel average comes from its fit
//! ([`WolffKernel::per_lane`]); van Ginneken interpolates its tables stacked over m
//! (`ginneken::roughness_axis`).

use super::DiffuseModel;
use super::eon::EonKernel;
use super::ginneken::GinnekenKernel;
use super::ginneken::roughness_axis::{GinnekenAxisKernel, M_MAX, M_MIN, RoughnessAxisTables, clamp_roughness};
use super::kernel::Kernel;
use super::lambert::Lambert;
use super::oren_nayar::OrenNayarKernel;
use super::real::{Real, V3};
use super::rough_diffuse::RoughDiffuse;
use super::wolff::WolffKernel;

/// One model's kernel with constants in `T`.
#[derive(Clone, Copy)]
pub enum LaneKernel<'t, T: Real> {
    Lambert(Lambert),
    OrenNayar(OrenNayarKernel<T>),
    Eon(EonKernel<T>),
    Wolff(WolffKernel<T>),
    Ginneken(GinnekenKernel<'t, T>),
    /// van Ginneken with the roughness per lane (its tables stacked over m).
    GinnekenAxis(GinnekenAxisKernel<'t, T>),
}

impl<'t, T: Real> Kernel<T> for LaneKernel<'t, T> {
    #[inline(always)]
    fn reduced_f<const N: usize>(&self, wi: V3<T>, wo: V3<T>, rho: [T; N]) -> [T; N] {
        match self {
            LaneKernel::Lambert(k) => k.reduced_f(wi, wo, rho),
            LaneKernel::OrenNayar(k) => k.reduced_f(wi, wo, rho),
            LaneKernel::Eon(k) => k.reduced_f(wi, wo, rho),
            LaneKernel::Wolff(k) => k.reduced_f(wi, wo, rho),
            LaneKernel::Ginneken(k) => k.reduced_f(wi, wo, rho),
            LaneKernel::GinnekenAxis(k) => k.reduced_f(wi, wo, rho),
        }
    }
}

/// The numeric parameters of the model `kind` (a plugin name), in the order per-lane values
/// are given: the parameters a texture may give. Empty for unknown kinds.
pub fn numeric_parameter_names(kind: &str) -> &'static [&'static str] {
    match kind {
        "oren_nayar" => &["sigma"],
        "eon" | "ginneken" => &["roughness"],
        "wolff" => &["int_ior", "ext_ior"],
        "roughdiffuse" => &["alpha"],
        _ => &[],
    }
}

/// The number a textured parameter stands for when its model is built (and validated as a
/// number): the texture's `mean` clamped into the range its per-lane values are clamped to,
/// so that any texture is accepted, as its values are per lane. `number(name)` gives another
/// parameter's value when it is a number (Wolff's indices bound each other: int ≥ ext).
pub fn textured_placeholder(kind: &str, name: &str, mean: f64, number: impl Fn(&str) -> Option<f64>) -> f64 {
    let at_least = |lo: f64| if mean >= lo { mean } else { lo }; // NaN gives lo
    match (kind, name) {
        ("ginneken", "roughness") => at_least(M_MIN).min(M_MAX),
        ("eon", "roughness") => at_least(0.0).min(1.0),
        ("wolff", "int_ior") => at_least(number("ext_ior").unwrap_or(1.0).max(1.0)),
        ("wolff", "ext_ior") => at_least(1.0).min(number("int_ior").unwrap_or(1.0).max(1.0)),
        _ => at_least(0.0),
    }
}

impl DiffuseModel {
    /// The number of numeric parameters ([`Self::lane_coefficients`]' input length).
    pub fn numeric_parameter_count(&self) -> usize {
        match self {
            DiffuseModel::Lambert(_) => 0,
            DiffuseModel::Wolff(_) => 2,
            _ => 1,
        }
    }

    /// The tables [`Self::kernel_from_coefficients`] needs for per-lane parameters: van
    /// Ginneken's roughness-axis stacks ([`RoughnessAxisTables`], built on first use), none for
    /// the other models.
    pub fn lane_tables(&self) -> Option<&'static RoughnessAxisTables> {
        matches!(self, DiffuseModel::Ginneken(_)).then(RoughnessAxisTables::shared)
    }

    /// The f32 kernel for per-lane parameter `values`; `None` if `values` is too short.
    pub fn lane_kernel_f32(&self, values: &[f32]) -> Option<LaneKernel<'static, f32>> {
        let c = self.lane_coefficients(values)?;
        self.kernel_from_coefficients(&c, || self.lane_tables().map(|t| t.nodes()))
    }

    /// The kernel with constants `c` (a [`Self::lane_coefficients`] or a `coefficients()`
    /// layout); `None` if `c` is too short. van Ginneken's per-lane kernel takes the
    /// roughness-axis stacks from `axis` (`I`, scaled `∂I/∂m`, `μΛ`, scaled `∂(μΛ)/∂m`).
    pub fn kernel_from_coefficients<'t, T: Real>(
        &self,
        c: &[T],
        axis: impl FnOnce() -> Option<[T::Table<'t>; 4]>,
    ) -> Option<LaneKernel<'t, T>> {
        fn first<T: Copy, const N: usize>(c: &[T]) -> Option<[T; N]> {
            c.get(..N)?.try_into().ok()
        }
        Some(match self {
            DiffuseModel::Lambert(k) => LaneKernel::Lambert(*k),
            DiffuseModel::OrenNayar(b) => {
                LaneKernel::OrenNayar(OrenNayarKernel::from_coefficients(first(c)?, b.model()))
            }
            DiffuseModel::RoughDiffuse(b) => {
                LaneKernel::OrenNayar(OrenNayarKernel::from_coefficients(first(c)?, b.oren_nayar().model()))
            }
            DiffuseModel::Eon(_) => LaneKernel::Eon(EonKernel::from_coefficients(first(c)?)),
            DiffuseModel::Wolff(b) => LaneKernel::Wolff(WolffKernel::from_coefficients(first(c)?, b.normalization())),
            DiffuseModel::Ginneken(b) => {
                let [m] = first(c)?;
                LaneKernel::GinnekenAxis(GinnekenAxisKernel::new(axis()?, m, b.shadowing()))
            }
        })
    }

    /// The kernel constants for per-lane parameter `values` (see the module comment), in the
    /// layout of each kernel's `coefficients()`; `None` if `values` is too short. van
    /// Ginneken's single constant is the clamped roughness m itself.
    pub fn lane_coefficients<T: Real>(&self, values: &[T]) -> Option<Vec<T>> {
        let v = |k: usize| values.get(k).copied();
        Some(match self {
            DiffuseModel::Lambert(_) => vec![],
            DiffuseModel::OrenNayar(b) => OrenNayarKernel::new(v(0)?.max(T::c(0.0)), b.model()).coefficients().to_vec(),
            DiffuseModel::Eon(_) => EonKernel::new(v(0)?.clamp_to(0.0, 1.0)).coefficients().to_vec(),
            DiffuseModel::RoughDiffuse(b) => {
                let sigma = RoughDiffuse::sigma_of_alpha(v(0)?.max(T::c(0.0)));
                OrenNayarKernel::new(sigma, b.oren_nayar().model()).coefficients().to_vec()
            }
            DiffuseModel::Wolff(b) => {
                let (int_ior, ext_ior) = (v(0)?, v(1)?.max(T::c(1.0)));
                WolffKernel::per_lane(int_ior / ext_ior, b.normalization()).coefficients().to_vec()
            }
            DiffuseModel::Ginneken(_) => vec![clamp_roughness(v(0)?)],
        })
    }
}
