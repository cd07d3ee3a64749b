//! The traced scalar: a handle into the C++ arena of one trace (`cpp/arena.h`). Each
//! operation on a [`Traced`] asks the arena to perform one Dr.Jit operation on the Mitsuba
//! variant's own `Float` and returns a handle to the result, so running a kernel generic over
//! [`Real`] with `Traced` records that kernel into Dr.Jit: in symbolic loops and calls, into
//! the automatic-differentiation graph, for the LLVM and the CUDA backend alike. The arena
//! never reads a value.
//!
//! The arena travels inside the handle (`&'a Arena`) rather than in a thread-local: a handle
//! cannot outlive its trace (the borrow the C++ caller lends to the entry point) and cannot
//! cross threads (`Arena` is an opaque C++ type, neither `Send` nor `Sync`), both checked by
//! the compiler. The price is that a constant has no arena to go to: constants stay Rust
//! literals ([`Traced::Lit`]) until they meet a traced operand, and literal-only expressions
//! fold in Rust with IEEE f32 arithmetic, as Dr.Jit folds literals.

use super::bridge::ffi::Arena;
use matte_brdf::real::Real;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

#[derive(Clone, Copy)]
pub enum Traced<'a> {
    Lit(f32),
    Node(&'a Arena, u32),
}

#[derive(Clone, Copy)]
pub enum TracedMask<'a> {
    Lit(bool),
    Node(&'a Arena, u32),
}

/// A table the C++ side registered with the arena (its index in the arena's table list).
#[derive(Clone, Copy)]
pub struct TracedTable<'a> {
    pub arena: &'a Arena,
    pub id: u32,
}

impl<'a> Traced<'a> {
    /// The value the arena holds at `id`.
    pub fn node(arena: &'a Arena, id: u32) -> Self {
        Traced::Node(arena, id)
    }

    /// The arena index of this value (a literal is materialised first).
    pub fn id(self, arena: &Arena) -> u32 {
        match self {
            Traced::Lit(v) => arena.lit(v),
            Traced::Node(_, i) => i,
        }
    }

    fn arena(self) -> Option<&'a Arena> {
        match self {
            Traced::Node(a, _) => Some(a),
            Traced::Lit(_) => None,
        }
    }

    #[inline]
    fn unary(self, fold: fn(f32) -> f32, op: fn(&Arena, u32) -> u32) -> Self {
        match self {
            Traced::Lit(x) => Traced::Lit(fold(x)),
            Traced::Node(a, i) => Traced::Node(a, op(a, i)),
        }
    }

    #[inline]
    fn binary(self, o: Self, fold: fn(f32, f32) -> f32, op: fn(&Arena, u32, u32) -> u32) -> Self {
        match (self, o) {
            (Traced::Lit(x), Traced::Lit(y)) => Traced::Lit(fold(x, y)),
            _ => {
                let a = self.arena().or(o.arena()).expect("one operand is traced");
                Traced::Node(a, op(a, self.id(a), o.id(a)))
            }
        }
    }

    #[inline]
    fn compare(self, o: Self, fold: fn(f32, f32) -> bool, op: fn(&Arena, u32, u32) -> u32) -> TracedMask<'a> {
        match (self, o) {
            (Traced::Lit(x), Traced::Lit(y)) => TracedMask::Lit(fold(x, y)),
            _ => {
                let a = self.arena().or(o.arena()).expect("one operand is traced");
                TracedMask::Node(a, op(a, self.id(a), o.id(a)))
            }
        }
    }
}

impl<'a> TracedMask<'a> {
    pub fn id(self, arena: &Arena) -> u32 {
        match self {
            TracedMask::Lit(v) => arena.mask_lit(v),
            TracedMask::Node(_, i) => i,
        }
    }

    fn arena(self) -> Option<&'a Arena> {
        match self {
            TracedMask::Node(a, _) => Some(a),
            TracedMask::Lit(_) => None,
        }
    }

    fn binary(self, o: Self, fold: fn(bool, bool) -> bool, op: fn(&Arena, u32, u32) -> u32) -> Self {
        match (self, o) {
            (TracedMask::Lit(x), TracedMask::Lit(y)) => TracedMask::Lit(fold(x, y)),
            _ => {
                let a = self.arena().or(o.arena()).expect("one operand is traced");
                TracedMask::Node(a, op(a, self.id(a), o.id(a)))
            }
        }
    }
}

macro_rules! arithmetic {
    ($tr:ident, $m:ident, $fold:expr, $op:expr) => {
        impl<'a> $tr for Traced<'a> {
            type Output = Traced<'a>;
            #[inline]
            fn $m(self, o: Self) -> Self {
                self.binary(o, $fold, $op)
            }
        }
    };
}
arithmetic!(Add, add, |a, b| a + b, Arena::add);
arithmetic!(Sub, sub, |a, b| a - b, Arena::sub);
arithmetic!(Mul, mul, |a, b| a * b, Arena::mul);
arithmetic!(Div, div, |a, b| a / b, Arena::div);

impl<'a> Neg for Traced<'a> {
    type Output = Traced<'a>;
    fn neg(self) -> Self {
        self.unary(|a| -a, Arena::neg)
    }
}

impl BitAnd for TracedMask<'_> {
    type Output = Self;
    fn bitand(self, o: Self) -> Self {
        self.binary(o, |a, b| a & b, Arena::mask_and)
    }
}

impl BitOr for TracedMask<'_> {
    type Output = Self;
    fn bitor(self, o: Self) -> Self {
        self.binary(o, |a, b| a | b, Arena::mask_or)
    }
}

impl Not for TracedMask<'_> {
    type Output = Self;
    fn not(self) -> Self {
        match self {
            TracedMask::Lit(v) => TracedMask::Lit(!v),
            TracedMask::Node(a, i) => TracedMask::Node(a, a.mask_not(i)),
        }
    }
}

impl<'a> Real for Traced<'a> {
    type Mask = TracedMask<'a>;
    type Table<'t> = TracedTable<'a>;

    fn c(v: f64) -> Self {
        Traced::Lit(v as f32)
    }
    fn sqrt(self) -> Self {
        self.unary(f32::sqrt, Arena::sqrt)
    }
    fn abs(self) -> Self {
        self.unary(f32::abs, Arena::abs)
    }
    fn floor(self) -> Self {
        self.unary(f32::floor, Arena::floor)
    }
    fn fma(self, b: Self, c: Self) -> Self {
        match (self, b, c) {
            (Traced::Lit(x), Traced::Lit(y), Traced::Lit(z)) => Traced::Lit(x.mul_add(y, z)),
            _ => {
                let a = self.arena().or(b.arena()).or(c.arena()).expect("one operand is traced");
                Traced::Node(a, a.fma(self.id(a), b.id(a), c.id(a)))
            }
        }
    }
    fn min(self, o: Self) -> Self {
        self.binary(o, <f32 as Real>::min, Arena::minimum)
    }
    fn max(self, o: Self) -> Self {
        self.binary(o, <f32 as Real>::max, Arena::maximum)
    }
    fn lt(self, o: Self) -> TracedMask<'a> {
        self.compare(o, |a, b| a < b, Arena::lt)
    }
    fn le(self, o: Self) -> TracedMask<'a> {
        self.compare(o, |a, b| a <= b, Arena::le)
    }
    fn gt(self, o: Self) -> TracedMask<'a> {
        self.compare(o, |a, b| a > b, Arena::gt)
    }
    fn eq(self, o: Self) -> TracedMask<'a> {
        self.compare(o, |a, b| a == b, Arena::eq)
    }
    fn select(m: TracedMask<'a>, t: Self, f: Self) -> Self {
        match m {
            TracedMask::Lit(true) => t,
            TracedMask::Lit(false) => f,
            TracedMask::Node(a, mi) => Traced::Node(a, a.select(mi, t.id(a), f.id(a))),
        }
    }
    fn none(m: TracedMask<'a>) -> bool {
        matches!(m, TracedMask::Lit(false))
    }
    fn mask(v: bool) -> TracedMask<'a> {
        TracedMask::Lit(v)
    }
    fn sincos(self) -> (Self, Self) {
        match self {
            Traced::Lit(x) => {
                let (s, c) = matte_brdf::sampling::sincos_cephes(x);
                (Traced::Lit(s), Traced::Lit(c))
            }
            Traced::Node(a, i) => {
                let (mut s, mut c) = (0, 0);
                a.sincos(i, &mut s, &mut c);
                (Traced::Node(a, s), Traced::Node(a, c))
            }
        }
    }
    fn exp(self) -> Self {
        self.unary(f32::exp, Arena::exp)
    }
    /// Dr.Jit's `squared_norm` order for JIT arrays: `fmadd(y, y, x·x)`.
    fn squared_norm_2d(x: Self, y: Self) -> Self {
        y.fma(y, x * x)
    }
    fn gather(table: TracedTable<'a>, idx: Self, offset: u32) -> Self {
        Traced::Node(table.arena, table.arena.gather(table.id, idx.id(table.arena), offset))
    }
    /// Dr.Jit's packet gather: the arena pushes the eight values as consecutive entries.
    fn gather8(table: TracedTable<'a>, idx: Self) -> [Self; 8] {
        let first = table.arena.gather8(table.id, idx.id(table.arena));
        std::array::from_fn(|k| Traced::Node(table.arena, first + k as u32))
    }
}
