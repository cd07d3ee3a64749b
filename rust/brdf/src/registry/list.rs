//! `models!`: the list of models (its one call is in `rust/brdf/src/models/mod.rs`) and
//! everything generated from it: [`crate::DiffuseModel`] and its static dispatch,
//! [`crate::LaneKernel`], [`crate::MODELS`], [`crate::BSDF_TYPES`], the parameter parsing.

/// `models! { Variant: module::Type, ... }`: declares the model modules and generates
/// everything that lists the models (see the module comment). The order is the README's.
macro_rules! models {
    ($($variant:ident : $module:ident :: $ty:ident),+ $(,)?) => {
        $crate::registry::models!(@with_dollar ($) $($variant : $module :: $ty),+);
    };
    (@with_dollar ($d:tt) $($variant:ident : $module:ident :: $ty:ident),+) => {
        $(pub mod $module;)+
        $(pub use $module::$ty;)+

        /// Every registered model's declaration, in the README's order.
        pub const MODELS: &[&$crate::registry::ModelSpec] =
            &[$(&<$ty as $crate::registry::Registered>::SPEC),+];

        /// The plugin names, in the README's order.
        pub const BSDF_TYPES: &[&str] = &[$(<$ty as $crate::registry::Registered>::SPEC.name),+];

        const _: () = {
            $(assert!(
                $crate::registry::numeric_count(&<$ty as $crate::registry::Registered>::SPEC)
                    <= $crate::registry::MAX_NUMERIC,
                "a model has more numeric parameters than MAX_NUMERIC"
            );
            assert!(
                $crate::registry::names_numeric_parameters(
                    &<$ty as $crate::registry::Registered>::SPEC,
                    <<$ty as $crate::registry::Registered>::Parameters<f32> as $crate::registry::Flat<f32>>::NAMES,
                ),
                "a model's Parameters are not its SPEC's numeric parameters, in order"
            );
            assert!(
                $crate::registry::fits_are_valid(&<$ty as $crate::registry::Registered>::SPEC),
                "a model's fit bounds lie outside its range or lane clamp (declare them with `with_fit`)"
            );)+
        };

        /// One of matte's diffuse models with its (validated) parameters.
        #[derive(Clone, Debug, PartialEq)]
        pub enum DiffuseModel {
            $($variant($ty),)+
        }

        /// One model's kernel with constants in `T` (per-lane or traced parameters).
        #[derive(Clone, Copy)]
        pub enum LaneKernel<'t, T: $crate::real::Real + 't> {
            $($variant(<$ty as $crate::registry::Registered>::Lane<'t, T>),)+
        }

        impl<'t, T: $crate::real::Real + 't> $crate::kernel::Kernel<T> for LaneKernel<'t, T> {
            #[inline(always)]
            fn reduced_f<const N: usize>(
                &self,
                wi: $crate::real::V3<T>,
                wo: $crate::real::V3<T>,
                rho: [T; N],
            ) -> [T; N] {
                match self {
                    $(LaneKernel::$variant(k) => k.reduced_f(wi, wo, rho),)+
                }
            }

            #[inline(always)]
            fn cosine_sampling(&self) -> bool {
                match self {
                    $(LaneKernel::$variant(k) => $crate::kernel::Kernel::<T>::cosine_sampling(k),)+
                }
            }

            #[inline(always)]
            fn sample_wo(
                &self,
                wi: $crate::real::V3<T>,
                u1: T,
                u2: T,
            ) -> ($crate::real::V3<T>, T) {
                match self {
                    $(LaneKernel::$variant(k) => k.sample_wo(wi, u1, u2),)+
                }
            }

            #[inline(always)]
            fn pdf_wo(&self, wi: $crate::real::V3<T>, wo: $crate::real::V3<T>) -> T {
                match self {
                    $(LaneKernel::$variant(k) => k.pdf_wo(wi, wo),)+
                }
            }
        }

        /// `dispatch!(model, m => expr)`: evaluates `expr` with `m` bound to the concrete
        /// model (static dispatch); `dispatch!(model, m => expr, lane)` also wraps the
        /// expression's `Option<Lane>` into a [`LaneKernel`] of the same variant.
        macro_rules! dispatch {
            ($d self_:expr, $d b:ident => $d e:expr) => {
                match $d self_ {
                    $($crate::DiffuseModel::$variant($d b) => $d e,)+
                }
            };
            ($d self_:expr, $d b:ident => $d e:expr, lane) => {
                match $d self_ {
                    $($crate::DiffuseModel::$variant($d b) => ($d e).map($crate::LaneKernel::$variant),)+
                }
            };
        }
        pub(crate) use dispatch;

        impl DiffuseModel {
            /// Builds the model `kind` (a plugin name) from its parameters. `reflectance` is
            /// not a model parameter here: it is per channel and per call (textures). Unknown
            /// names, unknown parameters and out-of-range values are errors naming the
            /// parameter.
            pub fn from_params(kind: &str, mut params: $crate::Params) -> Result<Self, $crate::ParamError> {
                use $crate::registry::{Registered, Values};
                $(
                    if kind == <$ty as Registered>::SPEC.name {
                        let spec = &<$ty as Registered>::SPEC;
                        let model = <$ty>::build(&Values::read(spec, &mut params)?)?;
                        params.finish(kind, &spec.names())?;
                        return Ok(DiffuseModel::$variant(model));
                    }
                )+
                Err($crate::ParamError::new(
                    "type",
                    format!("unknown bsdf type \"{kind}\" (known: {})", BSDF_TYPES.join(", ")),
                ))
            }

            /// The model's declaration.
            pub fn spec(&self) -> &'static $crate::registry::ModelSpec {
                match self {
                    $(DiffuseModel::$variant(_) => &<$ty as $crate::registry::Registered>::SPEC,)+
                }
            }
        }

        /// The declaration of the model `kind` (a plugin name).
        pub fn spec(kind: &str) -> Option<&'static $crate::registry::ModelSpec> {
            MODELS.iter().copied().find(|s| s.name == kind)
        }

        /// [`$crate::registry::Registered::placeholder`] of the model `kind`; `mean`
        /// itself for unknown kinds.
        pub fn placeholder(kind: &str, name: &str, mean: f64, number: &dyn Fn(&str) -> Option<f64>) -> f64 {
            use $crate::registry::Registered;
            $(
                if kind == <$ty as Registered>::SPEC.name {
                    return <$ty>::placeholder(name, mean, number);
                }
            )+
            mean
        }
    };
}
pub(crate) use models;
