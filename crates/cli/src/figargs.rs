//! `--width`, `--height`, `--dpi`, `--font-size` and `--preset`: the figure options shared by every
//! command that draws.
//!
//! A size is pixels (`800`, `800 px`; 1 px = 1/96 in) or a length on the page (`85 mm`, `8.5 cm`,
//! `3.5 in`). At a length on the page the SVG declares that size and the PNG has it at `--dpi`
//! (default 300); the font size is in points on the page. At pixel sizes the PNG has exactly
//! that many pixels unless `--dpi` is given (then size x dpi / 96).

use stiction_plot::{Chart, ImageMap};

/// Smallest and largest figure side, pixels.
pub const SIZE_PX: std::ops::RangeInclusive<u32> = 200..=8000;
/// Smallest and largest figure side on the page, millimetres.
pub const SIZE_MM: std::ops::RangeInclusive<f64> = 20.0..=1000.0;
/// Smallest and largest font size, points.
pub const FONT_PT: std::ops::RangeInclusive<f64> = 5.0..=50.0;
/// Smallest and largest PNG resolution, dots per inch.
pub const DPI: std::ops::RangeInclusive<f64> = 50.0..=2400.0;

/// A figure side: pixels, or millimetres on the page.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Length {
    /// Pixels of 1/96 in.
    Px(u32),
    /// Millimetres on the page.
    Mm(f64),
}

impl Length {
    fn mm(self) -> f64 {
        match self {
            Length::Px(p) => p as f64 / 96.0 * 25.4,
            Length::Mm(m) => m,
        }
    }
}

/// Parses `800`, `800 px`, `85 mm`, `8.5 cm` or `3.5 in`.
pub fn parse_length(s: &str) -> Result<Length, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (num, unit) = (t[..split].trim(), t[split..].trim().to_ascii_lowercase());
    let v: f64 =
        num.parse().map_err(|_| format!("{s:?} is not a size: expected pixels (800) or a length (85 mm, 3.5 in)"))?;
    if !v.is_finite() {
        return Err(format!("{s:?} is not a finite size"));
    }
    let mm = match unit.as_str() {
        "" | "px" => {
            if v.fract() != 0.0 || !(*SIZE_PX.start() as f64..=*SIZE_PX.end() as f64).contains(&v) {
                return Err(format!("{s:?}: expected whole pixels from {} to {}", SIZE_PX.start(), SIZE_PX.end()));
            }
            return Ok(Length::Px(v as u32));
        }
        "mm" => v,
        "cm" => v * 10.0,
        "in" => v * 25.4,
        _ => return Err(format!("{s:?}: unknown unit {unit:?}, expected px, mm, cm or in")),
    };
    if !SIZE_MM.contains(&mm) {
        return Err(format!("{s:?} is out of range: expected {} to {} mm", SIZE_MM.start(), SIZE_MM.end()));
    }
    Ok(Length::Mm(mm))
}

/// Figure sizes for journals: a column's width with 8 pt text.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// 85 mm x 60 mm, 8 pt.
    SingleColumn,
    /// 175 mm x 110 mm, 8 pt.
    DoubleColumn,
}

impl Preset {
    /// Width and height in mm, font size in pt.
    pub fn size(self) -> (f64, f64, f64) {
        match self {
            Preset::SingleColumn => (85.0, 60.0, 8.0),
            Preset::DoubleColumn => (175.0, 110.0, 8.0),
        }
    }
}

/// Size, resolution and font of the figures a command writes.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct FigureArgs {
    /// Figure width: pixels, 200 to 8000 (`800`), or a length on the page (`85 mm`, `3.5 in`)
    /// (default: 800 px; with only --width the height is 0.7 times it).
    #[arg(long, value_name = "SIZE", value_parser = parse_length)]
    pub width: Option<Length>,
    /// Figure height: pixels or a length on the page (default: 560 px; with only --height the
    /// width is 1/0.7 times it).
    #[arg(long, value_name = "SIZE", value_parser = parse_length)]
    pub height: Option<Length>,
    /// PNG resolution in dots per inch, 50 to 2400 (default: 300 at a length on the page; at
    /// pixel sizes the PNG has the pixels given).
    #[arg(long, value_name = "DPI", value_parser = dpi)]
    pub dpi: Option<f64>,
    /// Font size of tick labels in points on the page (1 pt = 4/3 px), 5 to 50 (default 8 pt at
    /// a length on the page, else about 11 pt); titles, labels, legend and caption scale with it.
    #[arg(long, value_name = "PT", value_parser = font_points)]
    pub font_size: Option<f64>,
    /// A journal size: single-column (85 mm x 60 mm, 8 pt) or double-column (175 mm x 110 mm,
    /// 8 pt); --width, --height and --font-size override its parts.
    #[arg(long, value_enum)]
    pub preset: Option<Preset>,
}

fn font_points(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().trim_end_matches("pt").trim().parse().map_err(|_| format!("{s:?} is not a number"))?;
    if !FONT_PT.contains(&v) {
        return Err(format!("{v} pt is out of range: expected {} to {} pt", FONT_PT.start(), FONT_PT.end()));
    }
    Ok(v)
}

fn dpi(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().trim_end_matches("dpi").trim().parse().map_err(|_| format!("{s:?} is not a number"))?;
    if !DPI.contains(&v) {
        return Err(format!("{v} dpi is out of range: expected {} to {}", DPI.start(), DPI.end()));
    }
    Ok(v)
}

/// The size the options ask for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FigureSize {
    /// Pixels.
    Px(u32, u32),
    /// Millimetres on the page.
    Mm(f64, f64),
}

impl FigureArgs {
    fn sides(&self) -> (Option<Length>, Option<Length>) {
        let preset = self.preset.map(|p| p.size());
        (self.width.or(preset.map(|p| Length::Mm(p.0))), self.height.or(preset.map(|p| Length::Mm(p.1))))
    }

    /// The figure size, if given (the missing side from the 10:7 aspect ratio); millimetres when
    /// either side is a length on the page.
    pub fn size(&self) -> Option<FigureSize> {
        let (w, h) = self.sides();
        let physical = matches!(w, Some(Length::Mm(_))) || matches!(h, Some(Length::Mm(_)));
        if physical {
            let clamp = |v: f64| v.clamp(*SIZE_MM.start(), *SIZE_MM.end());
            let (w, h) = match (w.map(Length::mm), h.map(Length::mm)) {
                (Some(w), Some(h)) => (w, h),
                (Some(w), None) => (w, clamp(w * 0.7)),
                (None, Some(h)) => (clamp(h / 0.7), h),
                (None, None) => return None,
            };
            return Some(FigureSize::Mm(w, h));
        }
        let px = |l: Option<Length>| match l {
            Some(Length::Px(p)) => Some(p),
            _ => None,
        };
        let clamp = |v: f64| (v.round() as u32).clamp(*SIZE_PX.start(), *SIZE_PX.end());
        match (px(w), px(h)) {
            (None, None) => None,
            (Some(w), None) => Some(FigureSize::Px(w, clamp(w as f64 * 0.7))),
            (None, Some(h)) => Some(FigureSize::Px(clamp(h as f64 / 0.7), h)),
            (Some(w), Some(h)) => Some(FigureSize::Px(w, h)),
        }
    }

    /// The figure size in pixels, if given in pixels.
    pub fn size_px(&self) -> Option<(u32, u32)> {
        match self.size() {
            Some(FigureSize::Px(w, h)) => Some((w, h)),
            _ => None,
        }
    }

    /// The figure size in millimetres, if given as a length on the page (or by a preset).
    pub fn size_mm(&self) -> Option<(f64, f64)> {
        match self.size() {
            Some(FigureSize::Mm(w, h)) => Some((w, h)),
            _ => None,
        }
    }

    /// The font size in pixels of 1/96 in, if given (or set by a preset).
    pub fn font_px(&self) -> Option<f64> {
        self.font_size.or(self.preset.map(|p| p.size().2)).map(|pt| pt * 4.0 / 3.0)
    }

    /// The chart with these options.
    pub fn apply(&self, chart: Chart) -> Result<Chart, Box<dyn std::error::Error>> {
        let mut chart = chart.sized(self.size_px(), self.font_px())?;
        if let Some(mm) = self.size_mm() {
            chart = chart.physical(mm, self.dpi)?;
        } else {
            chart.dpi = self.dpi.or(chart.dpi);
        }
        Ok(chart)
    }

    /// An image map with these options.
    pub fn apply_map(&self, mut map: ImageMap) -> ImageMap {
        map.size_px = self.size_px().or(map.size_px);
        map.size_mm = self.size_mm().or(map.size_mm);
        map.font_px = self.font_px().or(map.font_px);
        map.dpi = self.dpi.or(map.dpi);
        map
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_as_pixels_or_lengths_on_the_page() {
        assert_eq!(parse_length("800").unwrap(), Length::Px(800));
        assert_eq!(parse_length("640 px").unwrap(), Length::Px(640));
        assert_eq!(parse_length("85 mm").unwrap(), Length::Mm(85.0));
        assert_eq!(parse_length("8.5cm").unwrap(), Length::Mm(85.0));
        // 3.5 in = 88.9 mm (1 in = 25.4 mm exactly), to rounding
        assert!(matches!(parse_length("3.5 in").unwrap(), Length::Mm(v) if (v - 88.9).abs() < 1e-12));
        for bad in ["85 furlongs", "12 mm", "100", "1e9 px", "wide", "NaN mm"] {
            assert!(parse_length(bad).is_err(), "{bad}");
        }
        let preset = FigureArgs { preset: Some(Preset::SingleColumn), ..Default::default() };
        assert_eq!(preset.size(), Some(FigureSize::Mm(85.0, 60.0)));
        assert_eq!(preset.font_px(), Some(8.0 * 4.0 / 3.0));
        let mixed = FigureArgs { width: Some(Length::Mm(85.0)), height: Some(Length::Px(384)), ..Default::default() };
        assert_eq!(mixed.size(), Some(FigureSize::Mm(85.0, 101.6)));
        let chart = preset.apply(Chart::new("t", "x", "y")).unwrap();
        assert_eq!(chart.png_size(), (1004, 709));
    }
}

/// The reference values of a scenario as figure labels and text lines (shown only when the
/// scenario has a `reference` section).
pub mod reference {
    use stiction_engine::scenario::ReferenceSpec;

    /// Trims the float noise of a value converted to µN: 2.0000000000000004 -> 2.
    fn r6(v: f64) -> f64 {
        (v * 1e6).round() / 1e6
    }

    /// A reference number as written (to 6 decimals, no float noise): 0.7, 2, 1.3.
    pub fn num(v: f64) -> String {
        format!("{}", r6(v))
    }

    /// `μ_e,a = 0.7 ± 0.3, source` for a legend (± is explained by [`text`]).
    pub fn mu_label(r: &ReferenceSpec) -> Option<String> {
        let m = r.mu_apparent?;
        Some(match r.mu_apparent_uncertainty {
            Some(u) => format!("measured μ_e,a = {} ± {} ({})", r6(m), r6(u), r.source),
            None => format!("measured μ_e,a = {} ({})", r6(m), r.source),
        })
    }

    /// `F_a0 = 2 ± 1.3 µN, source` for a legend.
    pub fn adhesion_label(r: &ReferenceSpec) -> Option<String> {
        let f = r.apparent_adhesion_force? * 1e6;
        Some(match r.apparent_adhesion_force_uncertainty {
            Some(u) => format!("measured F_a0 = {} ± {} µN ({})", r6(f), r6(u * 1e6), r.source),
            None => format!("measured F_a0 = {} µN ({})", r6(f), r.source),
        })
    }

    /// The range of mu_e,a the reference allows (value ± uncertainty; a point without one).
    pub fn mu_range(r: &ReferenceSpec) -> Option<(f64, f64)> {
        let m = r.mu_apparent?;
        let u = r.mu_apparent_uncertainty.unwrap_or(0.0);
        Some((m - u, m + u))
    }

    /// The range of F_a0 in µN (value ± uncertainty).
    pub fn adhesion_range_un(r: &ReferenceSpec) -> Option<(f64, f64)> {
        let f = r.apparent_adhesion_force? * 1e6;
        let u = r.apparent_adhesion_force_uncertainty.unwrap_or(0.0) * 1e6;
        Some((f - u, f + u))
    }

    /// What the ± means, for a figure note: `±: uncertainty stated by ...`.
    pub fn meaning_note(r: &ReferenceSpec) -> Option<String> {
        let any = r.mu_apparent_uncertainty.is_some() || r.apparent_adhesion_force_uncertainty.is_some();
        (any && !r.uncertainty_meaning.is_empty()).then(|| format!("measured ±: {}", r.uncertainty_meaning))
    }

    /// The text line printed by `run` and `study`: values, source and what the +/- is.
    pub fn text(r: &ReferenceSpec) -> String {
        let values: Vec<String> =
            [r.mu_text().map(|t| format!("mu_e,a = {t}")), r.adhesion_text().map(|t| format!("F_a0 = {t}"))]
                .into_iter()
                .flatten()
                .collect();
        let meaning = if r.mu_apparent_uncertainty.is_some() || r.apparent_adhesion_force_uncertainty.is_some() {
            format!("; +/- is the {}", r.uncertainty_meaning)
        } else {
            String::new()
        };
        format!("reference, measured ({}): {}{meaning}", r.source, values.join(", "))
    }

    /// The paper's measurement (section 5), for `plot fig7` without a scenario: the paper's own
    /// figure shows it. The same values as the `reference` section of scenarios/tas2000.json.
    pub fn paper() -> ReferenceSpec {
        ReferenceSpec {
            device: None,
            source: "Tas et al., MEMS 2000, section 5".into(),
            mu_apparent: Some(0.7),
            mu_apparent_uncertainty: Some(0.3),
            apparent_adhesion_force: Some(2.0e-6),
            apparent_adhesion_force_uncertainty: Some(1.3e-6),
            uncertainty_meaning: "uncertainty stated by the paper, from the uncertainty of the conversion factors \
                                  a_clamp and a_pull"
                .into(),
        }
    }
}
