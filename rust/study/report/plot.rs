//! The convergence section's plot: a region's ratio to Lambert against spp, one series per
//! renderer with its 99 % intervals, as inline SVG.

use crate::markup::escape;
use crate::study::configuration::Configuration;
use crate::study::convergence::{Point, Series};
use std::fmt::Write as _;

const COLOURS: [&str; 2] = ["#1f77b4", "#d95f02"];

/// Region ratio against spp (log axis), one series per renderer with 99 % error bars, and
/// Lambert's level (1) dashed when it is within the data's range (else an arrow says where).
pub fn ratio_over_spp(s: &Series, model: Configuration, title: &str) -> String {
    let (w, h, left, right, top, bottom) = (470.0, 250.0, 58.0, 12.0, 40.0, 36.0);
    let pts: Vec<&Point> = s.points.iter().filter(|p| p.model == model).collect();
    if pts.is_empty() || s.levels.is_empty() {
        return String::new();
    }
    let mut lo = pts.iter().map(|p| p.ratio.low()).fold(f64::INFINITY, f64::min);
    let mut hi = pts.iter().map(|p| p.ratio.high()).fold(f64::NEG_INFINITY, f64::max);
    let pad = ((hi - lo) * 0.15).max(0.002);
    lo -= pad;
    hi += pad;
    let n = s.levels.len();
    let x_of = |i: usize, r: usize| left + (w - left - right) * (i as f64 + 0.5) / n as f64 + (r as f64 - 0.5) * 10.0;
    let y_of = |v: f64| top + (h - top - bottom) * (hi - v) / (hi - lo);
    let mut g = String::new();
    let _ = write!(
        g,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" style="font:12px system-ui,sans-serif;margin:4px 12px 4px 0">"#
    );
    let _ = write!(g, r#"<text x="{left}" y="16" font-weight="bold">{}</text>"#, escape(title));
    let _ = write!(
        g,
        r##"<rect x="{left}" y="{top}" width="{}" height="{}" fill="none" stroke="#999"/>"##,
        w - left - right,
        h - top - bottom
    );
    for k in 0..=4 {
        let v = lo + (hi - lo) * k as f64 / 4.0;
        let y = y_of(v);
        let _ = write!(
            g,
            r##"<line x1="{}" x2="{left}" y1="{y:.1}" y2="{y:.1}" stroke="#999"/><text x="{}" y="{:.1}" text-anchor="end">{v:.3}</text>"##,
            left - 4.0,
            left - 6.0,
            y + 4.0
        );
    }
    if (lo..=hi).contains(&1.0) {
        let y1 = y_of(1.0);
        let _ = write!(
            g,
            r##"<line x1="{left}" x2="{}" y1="{y1:.1}" y2="{y1:.1}" stroke="#444" stroke-dasharray="4 3"/><text x="{}" y="{:.1}" text-anchor="end" fill="#444">Lambert</text>"##,
            w - right,
            w - right - 4.0,
            y1 - 4.0
        );
    } else {
        let (y, arrow) = if hi < 1.0 { (top + 14.0, "↑ above") } else { (h - bottom - 6.0, "↓ below") };
        let _ = write!(
            g,
            r##"<text x="{}" y="{y:.1}" text-anchor="end" fill="#444">Lambert (1) {arrow} the plot</text>"##,
            w - right - 6.0
        );
    }
    for (i, spp) in s.levels.iter().enumerate() {
        let _ = write!(
            g,
            r#"<text x="{:.1}" y="{}" text-anchor="middle">{spp}</text>"#,
            x_of(i, 0) + 5.0,
            h - bottom + 16.0
        );
    }
    let _ = write!(
        g,
        r#"<text x="{:.1}" y="{}" text-anchor="middle">total spp</text>"#,
        left + (w - left - right) / 2.0,
        h - 4.0
    );
    for (r, name) in s.renderers.iter().enumerate() {
        let c = COLOURS[r % 2];
        let mut line = Vec::new();
        for (i, spp) in s.levels.iter().enumerate() {
            let Some(p) = s.point(model, name, *spp) else { continue };
            let x = x_of(i, r);
            let (ya, yb, ym) = (y_of(p.ratio.low()), y_of(p.ratio.high()), y_of(p.ratio.value));
            let _ = write!(
                g,
                r#"<line x1="{x:.1}" x2="{x:.1}" y1="{ya:.1}" y2="{yb:.1}" stroke="{c}"/><line x1="{:.1}" x2="{:.1}" y1="{ya:.1}" y2="{ya:.1}" stroke="{c}"/><line x1="{:.1}" x2="{:.1}" y1="{yb:.1}" y2="{yb:.1}" stroke="{c}"/><circle cx="{x:.1}" cy="{ym:.1}" r="3" fill="{c}"/>"#,
                x - 3.0,
                x + 3.0,
                x - 3.0,
                x + 3.0
            );
            line.push(format!("{x:.1},{ym:.1}"));
        }
        let _ = write!(g, r#"<polyline points="{}" fill="none" stroke="{c}" stroke-opacity="0.5"/>"#, line.join(" "));
        let _ = write!(g, r#"<text x="{}" y="32" fill="{c}">● {}</text>"#, left + 150.0 * r as f64, escape(name));
    }
    g.push_str("</svg>");
    g
}
