//! Named values that are flat only where the data must be ([`Flat`]): a model's numeric
//! parameters and kernel constants as slices for the traced plugin's arena and a texture's
//! per-lane values; [`flat_values!`] declares them.

/// Named values in any `T` (a model's numeric parameters, its kernel constants) that are flat
/// data only at the boundary that needs it: the traced plugin's arena indices, a texture's
/// per-lane values. The slice order is the declaration order. [`flat_values!`] declares one.
pub trait Flat<T: Copy>: Copy {
    /// The names, in the slice order.
    const NAMES: &'static [&'static str];

    /// The values from the first entries of `c`; `None` if it is short.
    fn from_flat(c: &[T]) -> Option<Self>;

    /// The values in the slice order.
    fn to_flat(&self) -> Vec<T>;

    /// Each value replaced by `f(k, value)`, `k` its position in the slice order.
    #[must_use]
    fn map(self, f: impl FnMut(usize, T) -> T) -> Self;
}

/// No values: the numeric parameters and constants of a model that has none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoValues;

impl<T: Copy> Flat<T> for NoValues {
    const NAMES: &'static [&'static str] = &[];
    fn from_flat(_: &[T]) -> Option<Self> {
        Some(NoValues)
    }
    fn to_flat(&self) -> Vec<T> {
        Vec::new()
    }
    fn map(self, _: impl FnMut(usize, T) -> T) -> Self {
        self
    }
}

/// `flat_values! { /// doc\n pub struct Name { /// doc\n a, b } }`: a struct of named values
/// `pub a: T, pub b: T` with [`Flat`] (slice order: the fields') and `map_values`, the same
/// values converted to another type.
macro_rules! flat_values {
    ($(#[$m:meta])* $vis:vis struct $name:ident { $($(#[$fm:meta])* $field:ident),+ $(,)? }) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug, PartialEq)]
        $vis struct $name<T> {
            $($(#[$fm])* pub $field: T,)+
        }

        impl<T: Copy> $crate::registry::Flat<T> for $name<T> {
            const NAMES: &'static [&'static str] = &[$(stringify!($field)),+];

            #[inline(always)]
            fn from_flat(c: &[T]) -> Option<Self> {
                let mut c = c.iter().copied();
                Some(Self { $($field: c.next()?,)+ })
            }

            fn to_flat(&self) -> Vec<T> {
                vec![$(self.$field),+]
            }

            #[inline(always)]
            fn map(self, mut f: impl FnMut(usize, T) -> T) -> Self {
                let mut k = 0;
                $(let $field = f(k, self.$field);
                k += 1;)+
                let _ = k;
                Self { $($field),+ }
            }
        }

        impl<T: Copy> $name<T> {
            /// The same values converted by `f` (f64 constants rounded to f32).
            #[inline(always)]
            pub fn map_values<U>(self, f: impl Fn(T) -> U) -> $name<U> {
                $name { $($field: f(self.$field)),+ }
            }
        }
    };
}
pub(crate) use flat_values;
