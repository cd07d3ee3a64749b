//! An 8-wide [`Real`]: eight f32 lanes in one AVX register (`wide::f32x8`; the crate's build
//! targets x86-64-v3, `.cargo/config.toml`), so that every kernel written over [`Real`]
//! evaluates eight direction pairs per call, as Dr.Jit's `llvm` backend does
//! (docs/traced-kernels.md: one kernel source for every scalar type).
//!
//! Each lane computes exactly what the `f32` implementation computes for that lane:
//! `+ − × ÷ √`, `floor` and `fma` are IEEE-exact per lane in both; `min`/`max` are
//! `minps`/`maxps`, which return the second operand on NaN or ties as the scalar
//! `if a < b { a } else { b }` does; comparisons are ordered (false on NaN) as Rust's; `sincos`
//! and `gather` run the scalar code lane by lane. The lane-by-lane tests
//! (`tests/kernels/simd_kernels.rs`) check results bit for bit.

use super::real::{Nodes, Real};
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};
use wide::f32x8;

/// Number of lanes.
pub const LANES: usize = 8;

/// Eight f32 lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct F32x8(pub f32x8);

/// Eight lane masks (all bits set = true), as the comparisons of [`F32x8`] produce them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct M32x8(f32x8);

impl F32x8 {
    #[inline(always)]
    pub fn new(lanes: [f32; LANES]) -> Self {
        F32x8(f32x8::new(lanes))
    }

    #[inline(always)]
    pub fn splat(v: f32) -> Self {
        F32x8(f32x8::splat(v))
    }

    #[inline(always)]
    pub fn to_array(self) -> [f32; LANES] {
        self.0.to_array()
    }

    /// Lane `i`.
    #[inline(always)]
    pub fn lane(self, i: usize) -> f32 {
        self.to_array()[i]
    }
}

impl M32x8 {
    /// Lane `i` of the mask.
    #[inline(always)]
    pub fn lane(self, i: usize) -> bool {
        self.0.to_bitmask() >> i & 1 == 1
    }

    /// One bit per lane, lane 0 in bit 0.
    #[inline(always)]
    pub fn bits(self) -> u32 {
        self.0.to_bitmask()
    }
}

macro_rules! binary {
    ($tr:ident, $f:ident) => {
        impl $tr for F32x8 {
            type Output = F32x8;
            #[inline(always)]
            fn $f(self, o: F32x8) -> F32x8 {
                F32x8($tr::$f(self.0, o.0))
            }
        }
    };
}
binary!(Add, add);
binary!(Sub, sub);
binary!(Mul, mul);
binary!(Div, div);

impl Neg for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn neg(self) -> F32x8 {
        F32x8(-self.0)
    }
}

impl BitAnd for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitand(self, o: M32x8) -> M32x8 {
        M32x8(self.0 & o.0)
    }
}

impl BitOr for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitor(self, o: M32x8) -> M32x8 {
        M32x8(self.0 | o.0)
    }
}

impl Not for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn not(self) -> M32x8 {
        M32x8(!self.0)
    }
}

impl Real for F32x8 {
    type Mask = M32x8;
    type Table<'t> = Nodes<'t>;

    #[inline(always)]
    fn c(v: f64) -> Self {
        F32x8::splat(v as f32)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        F32x8(self.0.sqrt())
    }
    #[inline(always)]
    fn abs(self) -> Self {
        F32x8(self.0.abs())
    }
    #[inline(always)]
    fn floor(self) -> Self {
        F32x8(self.0.floor())
    }
    #[inline(always)]
    fn fma(self, b: Self, c: Self) -> Self {
        // NEON's vfmaq is fused on every aarch64 CPU; x86 needs the FMA extension.
        if cfg!(any(target_feature = "fma", target_arch = "aarch64")) {
            F32x8(self.0.mul_add(b.0, c.0))
        } else {
            // Without FMA, `wide` would round the product first; f32::mul_add does not.
            let (a, b, c) = (self.to_array(), b.to_array(), c.to_array());
            F32x8::new(std::array::from_fn(|i| a[i].mul_add(b[i], c[i])))
        }
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        F32x8(self.0.fast_min(o.0))
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        F32x8(self.0.fast_max(o.0))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> M32x8 {
        M32x8(self.0.simd_lt(o.0))
    }
    #[inline(always)]
    fn le(self, o: Self) -> M32x8 {
        M32x8(self.0.simd_le(o.0))
    }
    #[inline(always)]
    fn gt(self, o: Self) -> M32x8 {
        M32x8(self.0.simd_gt(o.0))
    }
    #[inline(always)]
    fn eq(self, o: Self) -> M32x8 {
        M32x8(self.0.simd_eq(o.0))
    }
    #[inline(always)]
    fn select(m: M32x8, t: Self, f: Self) -> Self {
        F32x8(m.0.bitselect(t.0, f.0))
    }
    #[inline(always)]
    fn none(m: M32x8) -> bool {
        !m.0.any()
    }
    #[inline(always)]
    fn mask(v: bool) -> M32x8 {
        M32x8(f32x8::splat(if v { f32::from_bits(u32::MAX) } else { 0.0 }))
    }
    #[inline(always)]
    fn sincos(self) -> (Self, Self) {
        let x = self.to_array();
        let sc: [(f32, f32); LANES] = std::array::from_fn(|i| x[i].sincos());
        (F32x8::new(sc.map(|p| p.0)), F32x8::new(sc.map(|p| p.1)))
    }
    #[inline(always)]
    fn exp(self) -> Self {
        F32x8::new(self.to_array().map(f32::exp))
    }
    #[inline(always)]
    fn gather(table: Nodes<'_>, idx: Self, offset: u32) -> Self {
        let idx = idx.to_array();
        F32x8::new(idx.map(|i| <f32 as Real>::gather(table, i, offset)))
    }
    /// One contiguous load per lane, then the 8 × 8 transpose.
    #[inline(always)]
    fn gather8(table: Nodes<'_>, idx: Self) -> [Self; 8] {
        let rows = idx.to_array().map(|i| table.packet8(i as usize));
        std::array::from_fn(|k| F32x8::new(std::array::from_fn(|lane| rows[lane][k])))
    }
}
