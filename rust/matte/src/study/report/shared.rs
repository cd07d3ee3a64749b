//! What the sections' JSON and tables share: a ratio in both lightings, a region's ratios,
//! a strip with its heatmap, and the tables' `value ± half-width` cell.

use crate::study::options::Lighting;
use crate::study::ratio::{Ratio, RegionRatio};
use serde::Serialize;
use std::path::PathBuf;

/// A ratio (to Lambert, or to a true surface) under global and direct lighting, each with
/// its 99 % half-width.
#[derive(Serialize)]
pub struct LightingRatios {
    pub ratio_global: f64,
    pub ratio_global_ci99: f64,
    pub ratio_direct: f64,
    pub ratio_direct_ci99: f64,
}

impl LightingRatios {
    /// The two ratios as study.json writes them.
    pub fn new(global: Ratio, direct: Ratio) -> LightingRatios {
        LightingRatios {
            ratio_global: global.value,
            ratio_global_ci99: global.half_width,
            ratio_direct: direct.value,
            ratio_direct_ci99: direct.half_width,
        }
    }

    /// The ratio in `lighting`.
    pub fn get(&self, lighting: Lighting) -> Ratio {
        match lighting {
            Lighting::Global => Ratio::new(self.ratio_global, self.ratio_global_ci99),
            Lighting::Direct => Ratio::new(self.ratio_direct, self.ratio_direct_ci99),
        }
    }
}

/// A region's ratio to Lambert in both lightings.
#[derive(Serialize)]
pub struct RegionJson {
    pub name: String,
    #[serde(flatten)]
    pub ratios: LightingRatios,
}

impl RegionJson {
    /// Pairs the regions of one image under global and direct lighting.
    pub fn pair(global: &[RegionRatio], direct: &[RegionRatio]) -> Vec<RegionJson> {
        global
            .iter()
            .zip(direct)
            .map(|(g, d)| RegionJson { name: g.name.clone(), ratios: LightingRatios::new(g.ratio, d.ratio) })
            .collect()
    }
}

/// A strip image and its heatmap strip for one lighting.
#[derive(Serialize)]
pub struct StripJson {
    pub lighting: &'static str,
    pub strip: PathBuf,
    pub difference: PathBuf,
    /// Colour-scale half-range of the heatmap (relative difference).
    pub difference_range: f32,
}

/// `value ± half-width` with four decimals, the tables' cell.
pub fn ci(r: &Ratio) -> String {
    format!("{:.4} ± {:.4}", r.value, r.half_width)
}
