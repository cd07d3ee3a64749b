//! The scalar the kernels are written against, so that each model is written once:
//! - `f32`: the Rust renderer, the CLI and Mitsuba's scalar variants;
//! - `f64`: parameter-only precomputation on the CPU (coefficients, Fresnel averages), rounded
//!   to f32 afterwards, as the kernels always did;
//! - `Traced` (`matte_plugin::traced`): every operation becomes one Dr.Jit operation on the
//!   Mitsuba variant's own `Float`, so the same Rust source is recorded into Dr.Jit's IR
//!   (symbolic loops and calls, automatic differentiation, the LLVM and CUDA backends).
//!
//! Kernels must be branch-free over values: a traced comparison is not a `bool`, so an `if`
//! on a value does not compile for it. Value-dependent choices are [`Real::select`]; early
//! returns are kept for the CPU through [`Real::none`], which never changes a result.
//! Branch-free code must also stay finite on lanes a `select` discards: automatic
//! differentiation propagates a NaN from a discarded lane (multiplied by a zero adjoint).
//! So square roots take `max(x, 0)` and divisors are clamped away from zero.

use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

pub trait Real:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    type Mask: Copy + BitAnd<Output = Self::Mask> + BitOr<Output = Self::Mask> + Not<Output = Self::Mask>;
    /// A read-only table of f32 values indexed by [`Real::gather`] (a slice on the CPU, a
    /// Dr.Jit buffer uploaded once when traced).
    type Table<'t>: Copy;

    /// A constant, rounded to the type's precision (needs no trace context).
    fn c(v: f64) -> Self;
    fn sqrt(self) -> Self;
    fn abs(self) -> Self;
    fn floor(self) -> Self;
    /// `self · b + c` with one rounding.
    fn fma(self, b: Self, c: Self) -> Self;
    /// `min`/`max` as one instruction: a NaN operand gives the other one (the clamps rely on
    /// this to map NaN into range), as `minss`/`maxss` and Dr.Jit's `fmin`/`fmax` (not its
    /// `minimum`/`maximum`, which propagate NaN).
    fn min(self, o: Self) -> Self;
    fn max(self, o: Self) -> Self;
    fn lt(self, o: Self) -> Self::Mask;
    fn le(self, o: Self) -> Self::Mask;
    fn gt(self, o: Self) -> Self::Mask;
    fn eq(self, o: Self) -> Self::Mask;
    fn select(m: Self::Mask, t: Self, f: Self) -> Self;
    /// `true` only when the mask is known to be all false: the CPU's early return. Traced
    /// types cannot read values while recording and answer `false` (unless the mask is a
    /// literal). Results never depend on it.
    fn none(m: Self::Mask) -> bool;
    /// `(sin x, cos x)`: Cephes' single-precision scheme on the CPU (what Dr.Jit evaluates,
    /// `sampling::sincos_cephes`), Dr.Jit's own `sincos` when traced.
    fn sincos(self) -> (Self, Self);
    /// `e^x`: the standard library's on the CPU, Dr.Jit's `exp` when traced (they differ by
    /// an ulp or so).
    fn exp(self) -> Self;
    /// `table[idx + offset]` for a non-negative integer-valued `idx` (below 2²³); out of
    /// range gives the last node on the CPU (callers clamp, so this never happens). The constant `offset`
    /// is separate so that the CPU converts `idx` to an integer once for all of a cell's corners.
    fn gather(table: Self::Table<'_>, idx: Self, offset: u32) -> Self;
    /// The packet `table[8·idx .. 8·idx + 8]` for a non-negative integer-valued `idx`: values
    /// a lookup always needs together (a cell's eight corners), stored side by side so that
    /// one index and one contiguous load fetch them (Dr.Jit's packet gather when traced,
    /// instead of eight random gathers). Out of range gives the last packet on the CPU.
    fn gather8(table: Self::Table<'_>, idx: Self) -> [Self; 8];
    /// The mask as a literal (for masks that do not depend on any value).
    fn mask(v: bool) -> Self::Mask;

    /// `x² + y²` as Mitsuba's `dr::squared_norm` of a 2-D point computes it where this type
    /// runs: the wheel's scalar build contracts `x·x + y·y` to `fma(x, x, y·y)` (checked bit
    /// for bit against `diffuse.sample`), while Dr.Jit's JIT arrays evaluate
    /// `fmadd(y, y, x·x)` (`drjit/array_router.h`). The traced type overrides this default.
    #[inline(always)]
    fn squared_norm_2d(x: Self, y: Self) -> Self {
        x.fma(x, y * y)
    }

    #[inline(always)]
    fn ge(self, o: Self) -> Self::Mask {
        o.le(self)
    }
    /// `self · k` for a constant `k`.
    #[inline(always)]
    fn scale(self, k: f64) -> Self {
        self * Self::c(k)
    }
    /// `max(0, x)` then the square root: finite on every lane.
    #[inline(always)]
    fn safe_sqrt(self) -> Self {
        self.max(Self::c(0.0)).sqrt()
    }
    /// Clamp into `[lo, hi]` (NaN gives `lo`).
    #[inline(always)]
    fn clamp_to(self, lo: f64, hi: f64) -> Self {
        self.max(Self::c(lo)).min(Self::c(hi))
    }
}

/// The CPU implementations: `bool` masks, branchy selects (the compiler turns them into
/// blends where that pays), one `minss`/`maxss` per clamp.
macro_rules! cpu_real {
    ($t:ty, $table:ty, $bits:ty, $mantissa:expr) => {
        impl Real for $t {
            type Mask = bool;
            type Table<'t> = $table;

            #[inline(always)]
            fn c(v: f64) -> Self {
                v as $t
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn floor(self) -> Self {
                <$t>::floor(self)
            }
            #[inline(always)]
            fn fma(self, b: Self, c: Self) -> Self {
                self.mul_add(b, c)
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                if self < o { self } else { o }
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                if self > o { self } else { o }
            }
            #[inline(always)]
            fn lt(self, o: Self) -> bool {
                self < o
            }
            #[inline(always)]
            fn le(self, o: Self) -> bool {
                self <= o
            }
            #[inline(always)]
            fn gt(self, o: Self) -> bool {
                self > o
            }
            #[inline(always)]
            fn eq(self, o: Self) -> bool {
                self == o
            }
            #[inline(always)]
            fn select(m: bool, t: Self, f: Self) -> Self {
                if m { t } else { f }
            }
            #[inline(always)]
            fn none(m: bool) -> bool {
                !m
            }
            #[inline(always)]
            fn mask(v: bool) -> bool {
                v
            }
            #[inline(always)]
            fn sincos(self) -> (Self, Self) {
                let (s, c) = crate::sampling::sincos_cephes(self as f32);
                (s as $t, c as $t)
            }
            #[inline(always)]
            fn exp(self) -> Self {
                <$t>::exp(self)
            }
            #[inline(always)]
            fn gather(table: Nodes<'_>, idx: Self, offset: u32) -> Self {
                table.at(index_bits!($t, $bits, $mantissa, idx) + offset as usize) as $t
            }
            #[inline(always)]
            fn gather8(table: Nodes<'_>, idx: Self) -> [Self; 8] {
                table.packet8(index_bits!($t, $bits, $mantissa, idx)).map(|v| v as $t)
            }
        }
    };
}

/// A non-negative integer-valued float below 2^mantissa as an integer, by adding
/// 2^mantissa (which puts the integer into the mantissa's bits) and masking: an add and an
/// `and`, where `as usize` is a saturating conversion of a dozen instructions with branches.
/// Anything else (NaN, negative, too large) gives some index that [`Nodes`] clamps into the
/// table, so memory safety never depends on the caller.
macro_rules! index_bits {
    ($t:ty, $bits:ty, $mantissa:expr, $x:expr) => {
        (($x + (1u64 << $mantissa) as $t).to_bits() & (((1 as $bits) << $mantissa) - 1)) as usize
    };
}

cpu_real!(f32, Nodes<'t>, u32, 23);
cpu_real!(f64, Nodes<'t>, u64, 52);

/// A non-empty table of f32 node values for the CPU's [`Real::gather`]: a lookup clamps its
/// index to the last node (one `cmov`) instead of a bounds check and a panic path, which in van
/// Ginneken's twelve lookups per eval cost a quarter of its instructions.
#[derive(Clone, Copy, Debug)]
pub struct Nodes<'t> {
    data: &'t [f32],
    last: usize,
}

impl<'t> Nodes<'t> {
    /// A table of `N ≥ 1` nodes (checked at compile time: no run-time cost per eval).
    #[inline(always)]
    pub fn new<const N: usize>(data: &'t [f32; N]) -> Self {
        const { assert!(N > 0, "a gather table needs at least one node") };
        Self { data, last: N - 1 }
    }

    /// A table of the nodes in `data`; `None` if it is empty.
    pub fn from_slice(data: &'t [f32]) -> Option<Self> {
        Some(Self { data, last: data.len().checked_sub(1)? })
    }

    /// The node at `i`, or the last node for an index past the end (callers clamp, so this
    /// only guards memory safety).
    #[inline(always)]
    pub fn at(self, i: usize) -> f32 {
        // SAFETY: `min(i, last)` ≤ `last` = `data.len() − 1`, and `data` is not empty.
        unsafe { *self.data.get_unchecked(i.min(self.last)) }
    }

    /// The nodes `8i .. 8i + 8`, or the last eight for a packet past the end (callers clamp,
    /// so this only guards memory safety); a table of fewer than eight nodes repeats its last.
    #[inline(always)]
    pub fn packet8(self, i: usize) -> [f32; 8] {
        if self.last < 7 {
            return std::array::from_fn(|k| self.at(i.saturating_mul(8) + k));
        }
        let start = i.saturating_mul(8).min(self.last - 7);
        // SAFETY: `start + 7 ≤ last` = `data.len() − 1`; `[f32; 8]` has f32's alignment.
        unsafe { *(self.data.as_ptr().add(start) as *const [f32; 8]) }
    }
}

/// A direction (or any 3-vector) in the local frame, in any [`Real`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3<T> {
    pub x: T,
    pub y: T,
    pub z: T,
}

impl<T: Real> V3<T> {
    #[inline(always)]
    pub fn new(x: T, y: T, z: T) -> Self {
        Self { x, y, z }
    }
}

impl From<glam::Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: glam::Vec3) -> Self {
        V3 { x: v.x, y: v.y, z: v.z }
    }
}

impl From<V3<f32>> for glam::Vec3 {
    #[inline(always)]
    fn from(v: V3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CPU gathers read integer-valued indices exactly and map every other float (NaN,
    /// negative, past the end, infinite) to a node of the table, never past it.
    #[test]
    fn cpu_gathers_read_integer_indices_and_stay_inside_the_table() {
        let data: [f32; 64] = std::array::from_fn(|k| k as f32);
        let t = Nodes::new(&data);
        for k in 0..64 {
            assert_eq!(<f32 as Real>::gather(t, k as f32, 0), k as f32);
            assert_eq!(<f64 as Real>::gather(t, k as f64, 0), k as f64);
        }
        for k in 0..8 {
            assert_eq!(<f32 as Real>::gather8(t, k as f32), std::array::from_fn(|j| (8 * k + j) as f32));
            assert_eq!(<f64 as Real>::gather8(t, k as f64), std::array::from_fn(|j| (8 * k + j) as f64));
        }
        assert_eq!(<f32 as Real>::gather(t, 8_388_607.0, 0), 63.0);
        for x in [f32::NAN, -1.0, -0.5, -1e30, 64.0, 1e7, 8_388_608.0, 1e30, f32::INFINITY, f32::NEG_INFINITY] {
            assert!(data.contains(&<f32 as Real>::gather(t, x, 3)), "{x}");
            assert!(<f32 as Real>::gather8(t, x).iter().all(|v| data.contains(v)), "{x}");
            assert!(data.contains(&(<f64 as Real>::gather(t, x as f64, 3) as f32)), "{x}");
        }
    }
}
