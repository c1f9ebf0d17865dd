//! The figures and the table of `stiction plot humidity` (the sweep itself is the engine's,
//! `stiction_engine::humidity`).

use stiction_engine::humidity::{HumidityPoint, HumiditySweep};
use stiction_plot::{Chart, LegendPosition, Series};

use crate::figargs::reference;

/// The figures of a sweep by file stem: `humidity-mu` (mu_e,a), `humidity-fa0` (F_a0, µN) and
/// `humidity-share` (capillary share of the adhesive load, %), each against RH in %, with the
/// measured reference as a point with its error bars at the experiment's humidity (a band over the
/// grid when the scenario states no humidity). Humidities without an eq. 10 line are named in the
/// figure's note.
pub fn charts(s: &HumiditySweep) -> Vec<(&'static str, Chart)> {
    // Percent, rounded to 12 digits so that 0.9 shows as 90, not 89.99999999999999.
    let pct = |rh: f64| (rh * 1e14).round() / 1e12;
    let x_top = s.points.last().map_or(100.0, |p| pct(p.relative_humidity));
    let x_range = (0.0, if x_top > 0.0 { x_top } else { 100.0 });
    let model_marker = stiction_plot::Marker::Circle;
    let missing: Vec<String> = s
        .points
        .iter()
        .filter(|p| p.mu_apparent.is_none())
        .map(|p| format!("{}", (pct(p.relative_humidity) * 100.0).round() / 100.0))
        .collect();
    let missing_note = (!missing.is_empty())
        .then(|| format!("no eq. 10 line at RH = {} % (reasons: humidity.csv)", missing.join(", ")));
    let model = format!("virtual meter ({})", s.contact_model);
    let x_label = "relative humidity RH (%)";
    let series = |f: &dyn Fn(&HumidityPoint) -> Option<f64>| -> Vec<(f64, f64)> {
        s.points.iter().filter_map(|p| f(p).map(|y| (pct(p.relative_humidity), y))).collect()
    };

    let mut mu = Chart::new("apparent friction coefficient against humidity", x_label, "μ_e,a (eq. 10)")
        .keys("relative_humidity_percent", "mu_apparent")
        .with(Series::markers(model.clone(), series(&|p| p.mu_apparent)).with_color(0).with_marker(model_marker));
    let mut fa0 = Chart::new("apparent adhesion force against humidity", x_label, "F_a0 (µN, eq. 10)")
        .keys("relative_humidity_percent", "apparent_adhesion_force_un")
        .with(
            Series::markers(model.clone(), series(&|p| p.apparent_adhesion_force_n.map(|f| f * 1e6)))
                .with_color(0)
                .with_marker(model_marker),
        );
    let share = Chart::new(
        "capillary share of the adhesive load against humidity",
        x_label,
        "capillary share of the adhesive load (%)",
    )
    .keys("relative_humidity_percent", "capillary_share_percent")
    .with(
        Series::markers(model.clone(), series(&|p| p.capillary_share.map(|c| c * 100.0)))
            .with_color(0)
            .with_marker(model_marker),
    );
    let mut notes: [Vec<String>; 2] = [Vec::new(), Vec::new()];
    if let Some(r) = &s.reference {
        let rf = stiction_engine::scenario::ReferenceSpec {
            device: None,
            source: r.source.clone(),
            mu_apparent: r.mu_apparent,
            mu_apparent_uncertainty: r.mu_apparent_uncertainty,
            apparent_adhesion_force: r.apparent_adhesion_force_n,
            apparent_adhesion_force_uncertainty: r.apparent_adhesion_force_uncertainty_n,
            uncertainty_meaning: r.uncertainty_meaning.clone(),
        };
        let at = |label: String, value: f64, err: Option<f64>| -> Series {
            match r.relative_humidity {
                Some(rh) => {
                    let label = match r.relative_humidity_sd {
                        Some(sd) => format!("{label}, at RH = {} ± {} %", pct(rh), pct(sd)),
                        None => format!("{label}, at RH = {} %", pct(rh)),
                    };
                    let mut m = Series::markers(label, vec![(pct(rh), value)])
                        .with_color(4)
                        .with_marker(stiction_plot::Marker::Square);
                    if let Some(e) = err {
                        m = m.with_y_err(vec![e]);
                    }
                    if let Some(sd) = r.relative_humidity_sd {
                        m = m.with_x_err(vec![pct(sd)]);
                    }
                    m
                }
                None => {
                    let e = err.unwrap_or(0.0);
                    Series::y_range(format!("{label}, humidity not stated"), value - e, value + e).with_color(7)
                }
            }
        };
        if let (Some(m), Some(label)) = (r.mu_apparent, reference::mu_label(&rf)) {
            mu.series.push(at(label, m, r.mu_apparent_uncertainty));
        }
        if let (Some(f), Some(label)) = (r.apparent_adhesion_force_n, reference::adhesion_label(&rf)) {
            fa0.series.push(at(label, f * 1e6, r.apparent_adhesion_force_uncertainty_n.map(|u| u * 1e6)));
        }
        if let Some(n) = reference::meaning_note(&rf) {
            notes[0].push(n.clone());
            notes[1].push(n);
        }
    }
    for n in &mut notes {
        n.extend(missing_note.clone());
    }
    let [mu_notes, fa0_notes] = notes;
    let mut out = Vec::new();
    for (stem, mut chart, notes) in
        [("humidity-mu", mu, mu_notes), ("humidity-fa0", fa0, fa0_notes), ("humidity-share", share, Vec::new())]
    {
        let notes: Vec<String> =
            if stem == "humidity-share" { missing_note.clone().into_iter().collect() } else { notes };
        if !notes.is_empty() {
            chart.note = Some(notes.join("\n"));
        }
        // Margins of 3 % so that the markers at the ends of the grid are drawn whole.
        let w = x_range.1 - x_range.0;
        chart.x_range = Some((x_range.0 - 0.03 * w, x_range.1 + 0.03 * w));
        chart.legend = LegendPosition::UpperLeft;
        let (mut lo, mut hi) = (0.0_f64, if stem == "humidity-share" { 100.0_f64 } else { 0.0 });
        for se in &chart.series {
            for (i, p) in se.points.iter().enumerate() {
                let e = se.y_err.as_ref().and_then(|e| e.get(i)).copied().unwrap_or(0.0);
                let (a, b) = match se.style {
                    stiction_plot::SeriesStyle::YSpan => (p.0, p.1),
                    _ => (p.1 - e, p.1 + e),
                };
                if a.is_finite() && b.is_finite() {
                    lo = lo.min(a);
                    hi = hi.max(b);
                }
            }
        }
        let span = if hi > lo { hi - lo } else { 1.0 };
        // From 0 (or below, for a negative value), 3 % margins, headroom for the legend; the share
        // runs to 100 % (a share cannot exceed it; the legend finds a free corner or goes below).
        let headroom = if stem == "humidity-share" { 0.03 } else { 0.35 };
        chart.y_range = Some((lo - 0.03 * span, hi + headroom * span));
        out.push((stem, chart));
    }
    out
}

/// The table of a sweep as CSV, one row per humidity (`humidity.csv`): every field of
/// `HumidityPoint`, SI units in the column names, an empty cell for a null.
pub fn table_csv(s: &HumiditySweep) -> Result<Vec<u8>, Box<dyn std::error::Error>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for p in &s.points {
        w.serialize(p)?;
    }
    Ok(w.into_inner().map_err(|e| format!("humidity.csv: {e}"))?)
}
