//! Power heuristic (β = 2), as Mitsuba's integrators use (Veach 1997, §9.2).

/// `a² / (a² + b²)`, 0 when both are 0 or non-finite.
#[inline]
pub fn power_heuristic(a: f32, b: f32) -> f32 {
    let a2 = a * a;
    let w = a2 / (a2 + b * b);
    if w.is_finite() { w } else { 0.0 }
}
