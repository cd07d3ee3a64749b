//! Forward-mode dual numbers over f64 (`v + d ε`, ε² = 0) as a [`Real`]: running a kernel with
//! them gives its value and its derivative along one input in one pass, with the same code
//! the CPU and Dr.Jit run. matte uses them to measure the traced kernels' roughness gradient
//! against finite differences of the reference integral ([`crate::ginneken::accuracy`]).

use super::real::{Nodes, Real};
use std::ops::{Add, Div, Mul, Neg, Sub};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual {
    pub v: f64,
    pub d: f64,
}

impl Dual {
    /// The variable of differentiation at `v`.
    pub fn variable(v: f64) -> Self {
        Dual { v, d: 1.0 }
    }
}

impl Add for Dual {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Dual { v: self.v + o.v, d: self.d + o.d }
    }
}
impl Sub for Dual {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Dual { v: self.v - o.v, d: self.d - o.d }
    }
}
impl Mul for Dual {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Dual { v: self.v * o.v, d: self.d * o.v + self.v * o.d }
    }
}
impl Div for Dual {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        Dual { v: self.v / o.v, d: (self.d * o.v - self.v * o.d) / (o.v * o.v) }
    }
}
impl Neg for Dual {
    type Output = Self;
    fn neg(self) -> Self {
        Dual { v: -self.v, d: -self.d }
    }
}

impl Real for Dual {
    type Mask = bool;
    type Table<'t> = Nodes<'t>;

    fn c(v: f64) -> Self {
        Dual { v, d: 0.0 }
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        Dual { v: s, d: if s > 0.0 { 0.5 * self.d / s } else { 0.0 } }
    }
    fn abs(self) -> Self {
        if self.v < 0.0 { -self } else { self }
    }
    fn floor(self) -> Self {
        Dual { v: self.v.floor(), d: 0.0 }
    }
    fn fma(self, b: Self, c: Self) -> Self {
        self * b + c
    }
    fn min(self, o: Self) -> Self {
        if self.v < o.v { self } else { o }
    }
    fn max(self, o: Self) -> Self {
        if self.v > o.v { self } else { o }
    }
    fn lt(self, o: Self) -> bool {
        self.v < o.v
    }
    fn le(self, o: Self) -> bool {
        self.v <= o.v
    }
    fn gt(self, o: Self) -> bool {
        self.v > o.v
    }
    fn eq(self, o: Self) -> bool {
        self.v == o.v
    }
    fn select(m: bool, t: Self, f: Self) -> Self {
        if m { t } else { f }
    }
    fn none(m: bool) -> bool {
        !m
    }
    fn mask(v: bool) -> bool {
        v
    }
    fn sincos(self) -> (Self, Self) {
        let (s, c) = self.v.sin_cos();
        (Dual { v: s, d: c * self.d }, Dual { v: c, d: -s * self.d })
    }
    fn exp(self) -> Self {
        let e = self.v.exp();
        Dual { v: e, d: e * self.d }
    }
    fn gather(table: Nodes<'_>, idx: Self, offset: u32) -> Self {
        <Dual as Real>::c(table.at(idx.v as usize + offset as usize) as f64)
    }
    fn gather8(table: Nodes<'_>, idx: Self) -> [Self; 8] {
        table.packet8(idx.v as usize).map(|v| <Dual as Real>::c(v as f64))
    }
}
