//! The convergence section's plot: a region's ratio to Lambert against spp, one series per
//! renderer with its 99 % intervals, drawn by plotters as inline SVG in the study's font.

use crate::markup::escape;
use crate::study::configuration::Configuration;
use crate::study::convergence::{Point, Series};
use crate::study::font::DEJAVU_SANS;
use plotters::prelude::*;
use plotters::style::register_font;
use std::sync::Once;

const COLOURS: [RGBColor; 2] = [RGBColor(0x1f, 0x77, 0xb4), RGBColor(0xd9, 0x5f, 0x02)];
/// The SVG's font-family: DejaVu Sans where the browser has it, laid out with its metrics.
const FAMILY: &str = "DejaVu Sans, sans-serif";

/// Region ratio against spp (log axis), one series per renderer with 99 % error bars, and
/// Lambert's level (1) dashed when it is within the plot's range (else the legend says where).
/// Empty when the series has no point of `model`.
pub fn ratio_over_spp(s: &Series, model: Configuration, title: &str) -> String {
    static FONT: Once = Once::new();
    FONT.call_once(|| {
        assert!(register_font(FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok(), "the embedded font parses")
    });
    let pts: Vec<&Point> = s.points.iter().filter(|p| p.model == model).collect();
    if pts.is_empty() || s.levels.is_empty() {
        return String::new();
    }
    let lo = pts.iter().map(|p| p.ratio.low()).fold(f64::INFINITY, f64::min);
    let hi = pts.iter().map(|p| p.ratio.high()).fold(f64::NEG_INFINITY, f64::max);
    let pad = ((hi - lo) * 0.15).max(0.002);
    let (lo, hi) = (lo - pad, hi + pad);
    // Room above the data for the legend.
    let top = hi + 0.45 * (hi - lo);
    let levels: Vec<f64> = s.levels.iter().map(|&l| l as f64).collect();
    let (first, last) = (levels[0], levels[levels.len() - 1]);
    // The renderers side by side at each level, a sixteenth of an octave apart.
    let shift = |r: usize| (2f64).powf((r as f64 - 0.5) / 8.0);
    let mut svg = String::new();
    let drawn = (|| -> Result<(), Box<dyn std::error::Error + '_>> {
        let root = SVGBackend::with_string(&mut svg, (480, 280)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FAMILY, 18))
            .margin(8)
            .x_label_area_size(34)
            .y_label_area_size(66)
            .build_cartesian_2d((first / 1.5..last * 1.5).log_scale().with_key_points(levels.clone()), lo..top)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .light_line_style(WHITE.mix(0.0))
            .x_desc("total spp")
            .y_desc("region ratio to Lambert")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_label_formatter(&|y| format!("{y:.3}"))
            .label_style((FAMILY, 15))
            .axis_desc_style((FAMILY, 15))
            .draw()?;
        // Lambert's level: dashed where the plot shows it, else a legend entry says where it is.
        let grey = RGBColor(0x44, 0x44, 0x44);
        let ends = [(first / 1.5, 1.0), (last * 1.5, 1.0)];
        let shown = (lo..=top).contains(&1.0);
        let label = match (shown, top < 1.0) {
            (true, _) => "Lambert (1)",
            (false, true) => "Lambert (1): ↑ above",
            (false, false) => "Lambert (1): ↓ below",
        };
        let level = if shown { &ends[..] } else { &ends[..0] };
        chart
            .draw_series(DashedLineSeries::new(level.iter().copied(), 4, 3, grey.into()))?
            .label(label)
            .legend(move |(x, y)| PathElement::new(if shown { vec![(x, y), (x + 16, y)] } else { vec![] }, grey));
        for (r, name) in s.renderers.iter().enumerate() {
            let c = COLOURS[r % 2];
            let mine: Vec<(f64, &Point)> =
                s.levels.iter().filter_map(|&l| Some((l as f64 * shift(r), s.point(model, name, l)?))).collect();
            chart.draw_series(LineSeries::new(mine.iter().map(|(x, p)| (*x, p.ratio.value)), c.mix(0.5)))?;
            chart
                .draw_series(mine.iter().map(|(x, p)| {
                    ErrorBar::new_vertical(*x, p.ratio.low(), p.ratio.value, p.ratio.high(), c.filled(), 6)
                }))?
                .label(name.as_str())
                .legend(move |(x, y)| Circle::new((x + 8, y), 3, c.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(RGBColor(0xcc, 0xcc, 0xcc))
            .label_font((FAMILY, 15))
            .draw()?;
        root.present()?;
        Ok(())
    })();
    drawn.map_or_else(
        |e| format!(r#"<p class="note">{}: no plot ({}).</p>"#, escape(title), escape(&e.to_string())),
        |()| svg,
    )
}
