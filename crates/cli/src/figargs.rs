//! `--width`, `--height` and `--font-size`: the figure options shared by every command that draws.

use stiction_plot::{Chart, ImageMap};

/// Smallest and largest figure side, pixels.
pub const SIZE_PX: std::ops::RangeInclusive<u32> = 200..=8000;
/// Smallest and largest font size, points.
pub const FONT_PT: std::ops::RangeInclusive<f64> = 5.0..=50.0;

/// Size and font of the figures a command writes.
#[derive(clap::Args, Debug, Clone, Copy, Default)]
pub struct FigureArgs {
    /// Figure width in pixels, 200 to 8000 (default: 800 for SVG, 1200 for PNG; with only
    /// --width the height is 0.7 times it).
    #[arg(long, value_name = "PX", value_parser = clap::value_parser!(u32).range(200..=8000))]
    pub width: Option<u32>,
    /// Figure height in pixels, 200 to 8000 (default: 560 for SVG, 840 for PNG; with only
    /// --height the width is 1/0.7 times it).
    #[arg(long, value_name = "PX", value_parser = clap::value_parser!(u32).range(200..=8000))]
    pub height: Option<u32>,
    /// Font size of tick labels and legends in points (1 pt = 4/3 px), 5 to 50 (default about
    /// 11 pt); titles and axis labels scale with it.
    #[arg(long, value_name = "PT", value_parser = font_points)]
    pub font_size: Option<f64>,
}

fn font_points(s: &str) -> Result<f64, String> {
    let v: f64 = s.trim().trim_end_matches("pt").trim().parse().map_err(|_| format!("{s:?} is not a number"))?;
    if !FONT_PT.contains(&v) {
        return Err(format!("{v} pt is out of range: expected {} to {} pt", FONT_PT.start(), FONT_PT.end()));
    }
    Ok(v)
}

impl FigureArgs {
    /// The figure size in pixels, if given (the missing side from the 10:7 aspect ratio).
    pub fn size_px(&self) -> Option<(u32, u32)> {
        let clamp = |v: f64| (v.round() as u32).clamp(*SIZE_PX.start(), *SIZE_PX.end());
        match (self.width, self.height) {
            (None, None) => None,
            (Some(w), None) => Some((w, clamp(w as f64 * 0.7))),
            (None, Some(h)) => Some((clamp(h as f64 / 0.7), h)),
            (Some(w), Some(h)) => Some((w, h)),
        }
    }

    /// The font size in pixels, if given.
    pub fn font_px(&self) -> Option<f64> {
        self.font_size.map(|pt| pt * 4.0 / 3.0)
    }

    /// The chart with these options.
    pub fn apply(&self, chart: Chart) -> Result<Chart, Box<dyn std::error::Error>> {
        Ok(chart.sized(self.size_px(), self.font_px())?)
    }

    /// An image map with these options.
    pub fn apply_map(&self, mut map: ImageMap) -> ImageMap {
        map.size_px = self.size_px().or(map.size_px);
        map.font_px = self.font_px().or(map.font_px);
        map
    }
}

/// The reference values of a scenario as figure labels and text lines (shown only when the
/// scenario has a `reference` section).
pub mod reference {
    use stiction_scenario::ReferenceSpec;

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
