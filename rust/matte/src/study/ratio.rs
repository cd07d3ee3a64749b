//! A measured ratio with its 99 % confidence interval, and how two such intervals relate.
//! Every verdict of the study ("brighter than Lambert", "stable over spp", "the renderers
//! agree") is decided here from the intervals, never from display text.

use serde::Serialize;

/// An estimate and the half-width of its 99 % confidence interval.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Ratio {
    pub value: f64,
    pub half_width: f64,
}

/// Where one interval lies relative to another (or to an exact value).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// Entirely above.
    Above,
    /// Entirely below.
    Below,
    /// The intervals overlap.
    Indistinguishable,
}

impl Relation {
    /// The relation as a comparison of brightness, for sentences: "brighter than", …
    pub fn brightness(self) -> &'static str {
        match self {
            Relation::Above => "brighter than",
            Relation::Below => "darker than",
            Relation::Indistinguishable => "not distinguishable from",
        }
    }
}

impl Ratio {
    /// An estimate and its 99 % half-width.
    pub fn new(value: f64, half_width: f64) -> Self {
        Ratio { value, half_width }
    }

    /// An exact value (no uncertainty), e.g. Lambert's own ratio 1.
    pub fn exact(value: f64) -> Self {
        Ratio { value, half_width: 0.0 }
    }

    /// The interval's lower end.
    pub fn low(self) -> f64 {
        self.value - self.half_width
    }

    /// The interval's upper end.
    pub fn high(self) -> f64 {
        self.value + self.half_width
    }

    /// Where this interval lies relative to `other`'s.
    pub fn relation_to(self, other: Ratio) -> Relation {
        if self.low() > other.high() {
            Relation::Above
        } else if self.high() < other.low() {
            Relation::Below
        } else {
            Relation::Indistinguishable
        }
    }

    /// Relative to Lambert's ratio, 1.
    pub fn relation_to_one(self) -> Relation {
        self.relation_to(Ratio::exact(1.0))
    }

    /// Two estimates agree when their intervals overlap.
    pub fn overlaps(self, other: Ratio) -> bool {
        (self.value - other.value).abs() <= self.half_width + other.half_width
    }

    /// `self − other` for independent estimates: half-widths add in quadrature.
    pub fn minus(self, other: Ratio) -> Ratio {
        Ratio::new(self.value - other.value, self.half_width.hypot(other.half_width))
    }
}

/// Whether a difference (to Lambert, or a model's from its own surface) grows under global
/// illumination: the verdict on Δ = |r_global − 1| − |r_direct − 1| ([`super::metrics::growth`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Δ's interval lies above 0.
    Grows,
    /// Δ's interval lies below 0.
    Shrinks,
    /// Δ's interval contains 0.
    Undecided,
    /// The scene is lit directly only (its own max_depth is 2): both settings are one image.
    DirectOnly,
}

impl Verdict {
    /// The verdict as the report and study.json write it: `grows`, `shrinks`, …
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Grows => "grows",
            Verdict::Shrinks => "shrinks",
            Verdict::Undecided => "undecided",
            Verdict::DirectOnly => "direct only",
        }
    }

    /// The verdict on Δ's interval.
    pub fn of(delta: Ratio, direct_only: bool) -> Verdict {
        if direct_only {
            Verdict::DirectOnly
        } else if delta.low() > 0.0 {
            Verdict::Grows
        } else if delta.high() < 0.0 {
            Verdict::Shrinks
        } else {
            Verdict::Undecided
        }
    }
}

/// A named image region's ratio to Lambert.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionRatio {
    pub name: String,
    pub ratio: Ratio,
}
