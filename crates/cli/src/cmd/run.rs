//! `stiction run`: the friction-meter experiment of a scenario (the paper's section 5, Fig. 5).

use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressStyle};
use stiction_engine::run::{
    Experiment, Humidity, LineFit, Meter, MeterResult, RunOutput, discrete_curve_n3, experiment, loading_curve_un,
};
use stiction_engine::scenario::{ReferenceSpec, Scenario};
use stiction_plot::{Chart, Series};

use crate::figargs::{FigureArgs, reference};
use crate::output::{CliResult, OutputSet, print_json};

/// Run the friction meter: clamp at each clamp voltage, ramp the pull voltage until slip, fit eq. 10.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file (e.g. scenarios/tas2000.json).
    pub scenario: PathBuf,
    /// Write results.json, results.csv, fig5.svg/.png and fig7.svg/.png to this folder.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Override a scenario field (repeatable): --set surface.summit_sd="40 nm".
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Print one JSON object on stdout instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are
    /// left alone; the earlier run's files are replaced or removed).
    #[arg(long)]
    pub force: bool,
    /// Figure size and font.
    #[command(flatten)]
    pub fig: FigureArgs,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let scenario = Scenario::load(&args.scenario, &args.sets)?;
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "run", args.force)?),
        None => None,
    };
    let base = args.scenario.parent().map(PathBuf::from).unwrap_or_default();
    let name = args.scenario.display().to_string();
    let bar = ProgressBar::new(0);
    bar.set_style(
        ProgressStyle::with_template("{spinner} clamp voltages {pos}/{len} [{bar:30}] {elapsed_precise}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let Experiment { mut meter, result, measured } = experiment(&scenario, &name, &base, &mut |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })?;
    bar.finish_and_clear();
    let output = RunOutput { scenario: name, description: &scenario.description, result: &result, measured };
    if let Some(set) = outputs {
        write_outputs(set, &output, &scenario, &mut meter, &base, &args.fig)?;
    }
    if args.json {
        return print_json(&output);
    }
    print_summary(&output, scenario.reference.as_ref(), scenario.mu_calibration_relative_sd());
    if let Some(dir) = &args.out {
        let fig5 = if output.result.points.iter().any(|p| p.displacement_m.is_some()) {
            ""
        } else {
            "fig5.svg, fig5.png, fig5.csv, "
        };
        crate::outln!(
            "\nwrote {}/results.json, results.csv, {fig5}fig7.svg, fig7.png, fig7.csv, manifest.json",
            dir.display()
        );
    }
    Ok(())
}

fn print_summary(o: &RunOutput, reference: Option<&ReferenceSpec>, calibration_rel_sd: Option<f64>) {
    let r = o.result;
    crate::outln!("stiction run {}", o.scenario);
    if !o.description.is_empty() {
        crate::outln!("  {}", o.description);
    }
    match &r.structure {
        None => crate::outln!(
            "  contact model: {}, F_spring = {:.3} uN, a_clamp = {:.4e} N/V^2, a_pull = {:.4e} N/V^2 \
             (`stiction scenario FILE --explain` says where each comes from)",
            r.contact_model,
            r.spring_force_n * 1e6,
            r.reduction.a_clamp_n_per_v2,
            r.reduction.a_pull_n_per_v2
        ),
        Some(st) => crate::outln!(
            "  contact model: {}; normal {}: a_n = {:.4e} N/V^2, F_0 = {:.3} uN; tangential {}: {} \
             (`stiction scenario FILE --explain` says where each comes from)",
            r.contact_model,
            st.normal.replace('_', " "),
            st.normal_conversion_factor_n_per_v2,
            st.normal_spring_force_n * 1e6,
            st.tangential.replace('_', " "),
            match (st.tangential_conversion_factor_n_per_v2, st.tangential_stiffness_n_per_m) {
                (Some(a), _) => format!("a_t = {a:.4e} N/V^2"),
                (None, Some(k)) => format!("k = {k:.4} N/m"),
                (None, None) => String::new(),
            }
        ),
    }
    if let Some(h) = &r.environment {
        print_humidity(r, h);
    }
    crate::outln!();
    // A structure's columns say what its parts apply: the normal voltage, and the tangential
    // comb's voltage (or, for a released spring, the displacement that sticks).
    let spring = r.structure.as_ref().is_some_and(|st| st.tangential == "released_spring");
    let (c1, c3, c4) = match (&r.structure, spring) {
        (None, _) => ("V_clamp (V)", "V_pull (V)", "V_pull^2 (V^2)"),
        (Some(_), false) => ("V_n (V)", "V_t (V)", "V_t^2 (V^2)"),
        (Some(_), true) => ("V_n (V)", "x stuck (um)", "-"),
    };
    let mut t = crate::output::TextTable::new(&[
        c1,
        "L (uN)",
        c3,
        c4,
        "F_f (uN)",
        "A_r (um^2)",
        "N",
        "F_adh (uN)",
        "q0 (GPa)",
        "note",
    ]);
    for p in &r.points {
        let opt =
            |x: Option<f64>, scale: f64, prec: usize| x.map_or("-".to_string(), |v| format!("{:.prec$}", v * scale));
        t.row(vec![
            format!("{:.2}", p.v_clamp),
            format!("{:.4}", p.load_n * 1e6),
            if spring { opt(p.displacement_m, 1e6, 4) } else { opt(p.v_pull, 1.0, 2) },
            opt(p.v_pull_sq, 1.0, 1),
            opt(p.friction_n, 1e6, 4),
            format!("{:.5}", p.real_area_m2 * 1e12),
            format!("{:.0}", p.contacts),
            format!("{:.4}", p.adhesive_load_n * 1e6),
            format!("{:.3}", p.max_pressure_pa * 1e-9),
            p.reason.clone().unwrap_or_default(),
        ]);
    }
    t.print("  ");
    crate::outln!();
    match (r.mu_apparent, r.apparent_adhesion_force_n, &r.fit) {
        (Some(mu), Some(fa0), Some(fit)) => {
            crate::outln!(
                "  apparent friction coefficient mu_e,a = {mu:.3} +/- {:.3}  (eq. 10; +/- is the regression's standard error only, without the calibration: `stiction fit` gives both)",
                fit.slope_se
            );
            if let Some(rel) = calibration_rel_sd {
                let total = (rel * mu).hypot(fit.slope_se);
                crate::outln!(
                    "  with the conversion factors' sd (+/- {:.1} % on mu_e,a): mu_e,a = {mu:.3} +/- {total:.3}  \
                     (standard uncertainty: regression and calibration combined)",
                    rel * 100.0
                );
            }
            crate::outln!("  apparent zero-load adhesion F_a0    = {:.3} uN  (eq. 10)", fa0 * 1e6);
            crate::outln!("  fit over {} points with L > 0, R^2 = {:.4}", fit.points, fit.r_squared);
        }
        _ => crate::outln!(
            "  no eq. 10 fit: {}",
            r.fit_note.as_deref().unwrap_or("the fitted slope is not positive, so mu_e,a and F_a0 are undefined")
        ),
    }
    if let Some(lab) = &r.lab_coefficient {
        let c =
            lab.coefficient.map_or_else(|| lab.coefficient_reason.clone().unwrap_or_default(), |c| format!("{c:.3}"));
        let sd = lab.spread.map_or(String::new(), |s| format!(" (spread {s:.3})"));
        crate::outln!("  the lab's reduction ({}): {c}{sd} over {} points", lab.kind, lab.points);
    }
    for w in &r.warnings {
        crate::outln!("  warning [{}]: {}", w.code, w.message);
    }
    if let Some(r) = reference {
        crate::outln!("  {}", reference::text(r));
    }
    if let Some(c) = &o.measured {
        crate::outln!("\n  measured data ({} slips):", c.points.len());
        for rej in c.rows_rejected.iter().take(10) {
            crate::outln!("    left out of the eq. 10 fit: line {}: {}", rej.line, rej.reason);
        }
        if c.rows_rejected.len() > 10 {
            crate::outln!("    ... {} more rows left out (see --json)", c.rows_rejected.len() - 10);
        }
        if let (Some(mu), Some(fa0)) = (c.mu_apparent_measured, c.apparent_adhesion_force_measured_n) {
            crate::outln!(
                "    measured mu_e,a = {mu:.3}, F_a0 = {:.3} uN (eq. 10 on the measured voltages)",
                fa0 * 1e6
            );
        }
        if let Some(note) = &c.measured_fit_note {
            crate::outln!("    no eq. 10 fit of the measured data: {note}");
        }
        if let Some(rms) = c.rms_v_pull_sq_residual_v2 {
            crate::outln!("    model - measured V_pull^2: rms {rms:.1} V^2");
        }
    }
    let slips: Vec<bool> = r.points.iter().filter_map(|p| p.pull_in_at_slip).collect();
    if let (Some(v), false) = (r.pull_array_pull_in_v, slips.is_empty()) {
        let n = slips.iter().filter(|b| **b).count();
        crate::outln!(
            "  pull array pull-in voltage (free shoe) {v:.2} V; it pulled in at {n} of {} slips",
            slips.len()
        );
    }
    let times: Vec<f64> = r.points.iter().filter_map(|p| p.slip_time_to_stop_s).collect();
    let speeds: Vec<f64> = r.points.iter().filter_map(|p| p.slip_impact_velocity_m_per_s).collect();
    if !times.is_empty() {
        let range = |v: &[f64], scale: f64| {
            (v.iter().cloned().fold(f64::INFINITY, f64::min) * scale, v.iter().cloned().fold(0.0, f64::max) * scale)
        };
        let (t0, t1) = range(&times, 1e6);
        let (v0, v1) = range(&speeds, 1.0);
        crate::outln!(
            "  after slip the pull shuttle reaches its stop in {t0:.1}-{t1:.1} us at {v0:.2}-{v1:.2} m/s (rapier dynamics)"
        );
    }
    let stuck = r
        .points
        .iter()
        .filter(|p| p.in_contact && p.error.is_none() && p.v_pull.is_none() && p.displacement_m.is_none())
        .count();
    if stuck > 0 {
        crate::outln!(
            "  {stuck} clamp voltages: no slip up to pull_voltage_max (friction above what the pull array can give)"
        );
    }
}

/// The humidity line of the summary and the capillary share of the adhesive load over the
/// points in contact.
fn print_humidity(r: &MeterResult, h: &Humidity) {
    let (a1, a2) = h.contact_angles_rad;
    let angles = if a1 == a2 {
        format!("{:.0} deg", a1.to_degrees())
    } else {
        format!("{:.0} deg (sidewall) / {:.0} deg (shoe)", a1.to_degrees(), a2.to_degrees())
    };
    let meniscus = match (h.kelvin_radius_m, h.meniscus_height_m) {
        (Some(rk), Some(hm)) => {
            format!("Kelvin radius {:.3} nm, menisci bridge gaps up to {:.3} nm", rk * 1e9, hm * 1e9)
        }
        (Some(rk), None) => format!(
            "Kelvin radius {:.3} nm, below environment.min_kelvin_radius {:.3} nm: no meniscus condenses, the \
             contact is dry",
            rk * 1e9,
            h.min_kelvin_radius_m.unwrap_or(f64::NAN) * 1e9
        ),
        _ => "cos th1 + cos th2 <= 0: hydrophobic faces, no meniscus forms".to_string(),
    };
    match &h.liquid {
        None => crate::outln!(
            "  humid air: relative humidity {:.1} %, {:.2} C, water contact angle {angles}; {meniscus}",
            h.relative_humidity * 100.0,
            h.temperature_k - 273.15
        ),
        Some(name) => crate::outln!(
            "  {name} vapour: {:.1} % of its saturation pressure, {:.2} C, {name} contact angle {angles}; {meniscus}",
            h.relative_humidity * 100.0,
            h.temperature_k - 273.15
        ),
    }
    if let Some(share) = stiction_engine::humidity::capillary_share(r) {
        crate::outln!(
            "  capillary share of the adhesive load: {:.1} % (summed over the points in contact; per point: \
             `capillary_load_n` in --json)",
            100.0 * share
        );
    }
}

fn write_outputs(
    mut set: OutputSet,
    o: &RunOutput,
    scenario: &Scenario,
    meter: &mut Meter,
    base: &Path,
    fig: &FigureArgs,
) -> CliResult {
    // The figures first: results.json holds every plotted curve under `figures`, with the same
    // keys (units included) as the data CSV beside each figure.
    let measured_name = scenario.measured.as_ref().map(|m| {
        m.voltages_csv.file_name().map_or_else(|| m.voltages_csv.display().to_string(), |n| n.to_string_lossy().into())
    });
    // Fig. 5 is in pull voltages: none for a released spring (a `structure` whose tangential load is k x).
    let fig5 = if o.result.points.iter().any(|p| p.displacement_m.is_some()) {
        None
    } else {
        Some(fig.apply(fig5_chart(o, scenario, base, measured_name.as_deref())?)?)
    };
    let (fig7, fig7_notes) = fig7_chart(o, scenario, meter, base, measured_name.as_deref())?;
    let fig7 = fig.apply(fig7)?;
    let mut json = serde_json::to_value(o)?;
    if let Some(obj) = json.as_object_mut() {
        let mut fig7_json = fig7.data_json();
        if let Some(f) = fig7_json.as_object_mut() {
            // What the figure's short caption leaves out.
            f.insert("notes".into(), serde_json::json!(fig7_notes));
        }
        let mut figures = serde_json::Map::new();
        if let Some(f5) = &fig5 {
            figures.insert("fig5".into(), f5.data_json());
        }
        figures.insert("fig7".into(), fig7_json);
        obj.insert("figures".into(), figures.into());
    }
    set.add_bytes("results.json", crate::output::json_text(&json)?.as_bytes())?;
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "v_clamp_v",
        "v_clamp_sq_v2",
        "in_contact",
        "load_n",
        "v_pull_v",
        "v_pull_sq_v2",
        "friction_n",
        "friction_capacity_n",
        "pull_in_at_slip",
        "slip_time_to_stop_s",
        "slip_impact_velocity_m_per_s",
        "real_area_m2",
        "contacts",
        "adhesive_load_n",
        "tilt_x_rad",
        "tilt_y_rad",
        "max_pressure_pa",
        "over_elastic_limit",
        "plastic_area_m2",
        "true_load_n",
        "true_friction_n",
        "error",
    ])?;
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    for p in &o.result.points {
        w.write_record([
            format!("{}", p.v_clamp),
            format!("{}", p.v_clamp_sq),
            format!("{}", p.in_contact),
            format!("{:e}", p.load_n),
            opt(p.v_pull),
            opt(p.v_pull_sq),
            opt(p.friction_n),
            format!("{:e}", p.friction_capacity_n),
            p.pull_in_at_slip.map_or(String::new(), |b| b.to_string()),
            opt(p.slip_time_to_stop_s),
            opt(p.slip_impact_velocity_m_per_s),
            format!("{:e}", p.real_area_m2),
            format!("{}", p.contacts),
            format!("{:e}", p.adhesive_load_n),
            format!("{:e}", p.tilt_x_rad),
            format!("{:e}", p.tilt_y_rad),
            format!("{:e}", p.max_pressure_pa),
            format!("{}", p.over_elastic_limit),
            opt(p.plastic_area_m2),
            format!("{:e}", p.true_load_n),
            opt(p.true_friction_n),
            p.error.clone().unwrap_or_default(),
        ])?;
    }
    let csv_bytes = w.into_inner().map_err(|e| format!("results.csv: {e}"))?;
    set.add_bytes("results.csv", &csv_bytes)?;
    if let Some(f5) = &fig5 {
        set.add_figure("fig5", f5)?;
    }
    set.add_figure("fig7", &fig7)?;
    set.commit()
}

/// The figure titles' account of the data: the virtual meter, and the measured file if any.
fn what(r: &MeterResult, measured: Option<&str>) -> String {
    // The contact model is named in the virtual meter's legend entry.
    match measured {
        Some(name) => format!("measured ({name}) and virtual meter"),
        None => format!("virtual meter, {} contact model", r.contact_model),
    }
}

/// What the figures call the forces and voltages of a run: the paper's clamp and pull arrays, or
/// what a structure's parts apply (a normal comb or plate voltage, a tangential comb voltage or a
/// released displacement).
struct Labels {
    v_normal_sq: &'static str,
    v_tangential: &'static str,
    v_tangential_sq: &'static str,
    reduction: [&'static str; 4],
    load: &'static str,
    friction: &'static str,
    points: &'static str,
    points_note: &'static str,
}

impl Labels {
    fn of(r: &MeterResult) -> Labels {
        let Some(st) = &r.structure else {
            return Labels {
                v_normal_sq: "clamp voltage squared V_clamp² (V²)",
                v_tangential: "pull voltage",
                v_tangential_sq: "pull voltage squared at slip V_pull² (V²)",
                reduction: ["L = a_clamp V_clamp² − F_spring, F_f = a_pull V_pull²", "a_clamp", "a_pull", "F_spring"],
                load: "clamp load L (µN)",
                friction: "friction force F_f (µN)",
                points: "shoe clamped anew at each load",
                points_note: "Meter points: the shoe comes down anew at each clamp voltage (meter.reclamp).",
            };
        };
        let plate = st.normal == "plate_electrode";
        let spring = st.tangential == "released_spring";
        let lowered = st.protocol == "lower_normal";
        Labels {
            v_normal_sq: if plate {
                "plate voltage squared V_n² (V²)"
            } else {
                "normal comb voltage squared V_n² (V²)"
            },
            v_tangential: "tangential comb voltage",
            v_tangential_sq: if lowered {
                "tangential comb voltage squared, held V_t² (V²)"
            } else {
                "tangential comb voltage squared at slip V_t² (V²)"
            },
            reduction: ["L = a_n V_n² − F_0, F_f = a_t V_t²", "a_n", "a_t", "F_0"],
            load: match (plate, lowered) {
                (true, _) => "normal load from the plate voltage, L = a_n V_n² − F_0 (µN)",
                (false, false) => "normal load from the normal comb voltage, L = a_n V_n² − F_0 (µN)",
                (false, true) => "normal load at slip from the normal comb voltage, L = a_n V_n² − F_0 (µN)",
            },
            friction: if spring {
                "friction F_f = k x, the largest released displacement that sticks (µN)"
            } else {
                "friction F_f = a_t V_t², tangential comb force at slip (µN)"
            },
            points: if lowered { "normal load lowered, contact kept" } else { "contact made anew at each load" },
            points_note: if lowered {
                "Points: at each tangential comb voltage the normal voltage is lowered with the contact kept until slip."
            } else {
                "Points: the structure is brought into contact anew at each normal voltage."
            },
        }
    }
}

/// Fig. 5: V_pull^2 at slip against V_clamp^2, with the paper's own analysis (discrete N = 3,
/// eq. 12) turned back into voltages through the same conversion: V_pull^2 = F_f(L) / a_pull,
/// L = a_clamp V_clamp^2 - F_spring; with measured data, the measured slips and their eq. 10 line
/// in the same voltages.
fn fig5_chart(
    o: &RunOutput,
    scenario: &Scenario,
    base: &Path,
    measured: Option<&str>,
) -> Result<Chart, Box<dyn std::error::Error>> {
    let r = o.result;
    let pts: Vec<(f64, f64)> = r.points.iter().filter_map(|p| p.v_pull_sq.map(|v| (p.v_clamp_sq, v))).collect();
    let red = r.reduction;
    let v2_min = red.spring_force_n / red.a_clamp_n_per_v2;
    let v2_max = r.points.iter().map(|p| p.v_clamp_sq).fold(v2_min, f64::max) * 1.02;
    let curve = discrete_curve_n3(scenario, base, red.a_clamp_n_per_v2 * v2_max - red.spring_force_n)?;
    let discrete: Vec<(f64, f64)> = curve
        .into_iter()
        .filter(|(l_un, _)| *l_un >= 0.0)
        .map(|(l_un, f_un)| {
            ((l_un * 1e-6 + red.spring_force_n) / red.a_clamp_n_per_v2, f_un * 1e-6 / red.a_pull_n_per_v2)
        })
        // A released spring (a `structure`) has no pull voltage: no curve in pull voltages.
        .filter(|_| red.a_pull_n_per_v2 > 0.0)
        .collect();
    let labels = Labels::of(r);
    let mut chart = Chart::new(
        format!("Fig. 5: {} at slip, {}", labels.v_tangential, what(r, measured)),
        labels.v_normal_sq,
        labels.v_tangential_sq,
    )
    .keys("v_clamp_squared_v2", "v_pull_squared_v2")
    .with_note(format!(
        "{} (nominal {} = {} N/V², {} = {} N/V², {} = {} µN)",
        labels.reduction[0],
        labels.reduction[1],
        crate::format::sig3(red.a_clamp_n_per_v2),
        labels.reduction[2],
        crate::format::sig3(red.a_pull_n_per_v2),
        labels.reduction[3],
        crate::format::sig3(red.spring_force_n * 1e6)
    ))
    .with(Series::dashed("paper's analysis: discrete N = 3 (eq. 12)", discrete).with_color(1));
    // eq. 10 in voltages: V_pull^2 = (intercept + slope (a_clamp V_clamp^2 - F_spring)) / a_pull,
    // over the virtual meter's slips.
    let eq10 = |fit: &LineFit, x: f64| {
        (fit.intercept + fit.slope * (red.a_clamp_n_per_v2 * x - red.spring_force_n)) / red.a_pull_n_per_v2
    };
    // (A released spring's fit has no pull voltages to draw it in.)
    if let (Some(fit), Some(fa0), false) = (&r.fit, r.apparent_adhesion_force_n, pts.is_empty()) {
        let x0 = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min).max(v2_min);
        let x1 = pts.iter().map(|p| p.0).fold(0.0, f64::max);
        chart.series.push(
            Series::dashed(
                format!("eq. 10 fit of the virtual meter: μ_e,a = {:.2}, F_a0 = {:.2} µN", fit.slope, fa0 * 1e6),
                vec![(x0, eq10(fit, x0)), (x1, eq10(fit, x1))],
            )
            .with_color(3),
        );
    }
    chart.series.push(Series::markers("virtual meter", pts.clone()).with_color(0));
    if let Some(c) = &o.measured {
        if let (Some(fit), Some(mu), Some(fa0)) =
            (&c.measured_fit, c.mu_apparent_measured, c.apparent_adhesion_force_measured_n)
        {
            let x0 = c.points.iter().map(|p| p.v_clamp * p.v_clamp).fold(f64::INFINITY, f64::min).max(v2_min);
            let x1 = c.points.iter().map(|p| p.v_clamp * p.v_clamp).fold(0.0, f64::max);
            // Under the virtual meter's dashed line, so both stay visible where they coincide.
            chart.series.insert(
                0,
                Series::line(
                    format!("eq. 10 fit of the measured slips: μ_e,a = {mu:.2}, F_a0 = {:.2} µN", fa0 * 1e6),
                    vec![(x0, eq10(fit, x0)), (x1, eq10(fit, x1))],
                )
                .with_color(4),
            );
        }
        // Under the virtual meter's points at the same voltages.
        let at = chart.series.len() - 1;
        chart.series.insert(
            at,
            Series::markers(
                "measured",
                c.points.iter().map(|p| (p.v_clamp * p.v_clamp, p.v_pull_measured * p.v_pull_measured)).collect(),
            )
            .with_color(4),
        );
    }
    Ok(chart)
}

/// Fig. 7: friction against load: the meter's points, the contact model's curve from pull-off,
/// the discrete N = 3 model (eq. 12), the eq. 10 lines of the virtual (and measured) points and
/// the reference F_a0 band when the scenario has one. Returns the chart (with a one-line caption)
/// and the notes that explain it, for results.json.
fn fig7_chart(
    o: &RunOutput,
    scenario: &Scenario,
    meter: &mut Meter,
    base: &Path,
    measured: Option<&str>,
) -> Result<(Chart, Vec<String>), Box<dyn std::error::Error>> {
    let r = o.result;
    let mut max_load = r.points.iter().map(|p| p.load_n).fold(0.0, f64::max).max(1e-6) * 1.1;
    if let Some(c) = &o.measured {
        max_load = c.points.iter().map(|p| p.load_measured_n * 1.05).fold(max_load, f64::max);
    }
    let meas: Vec<(f64, f64)> =
        r.points.iter().filter_map(|p| p.friction_n.map(|f| (p.load_n * 1e6, f * 1e6))).collect();
    let labels = Labels::of(r);
    let mut chart = Chart::new(
        format!("Fig. 7: static friction against load, {}", what(r, measured)),
        labels.load,
        labels.friction,
    )
    .keys("load_un", "friction_un")
    .with(Series::markers(format!("virtual meter ({}), {}", r.contact_model, labels.points), meas).with_color(0));
    let mut notes = vec![labels.points_note.to_string()];
    let mut caption = format!("points: {}", labels.points);
    // The contact model's own curve s A_r(L), from its pull-off where it has one.
    if let Some(pts) = loading_curve_un(meter, max_load) {
        chart.series.push(Series::line("explicit solver, one loading path from pull-off", pts).with_color(1));
        notes.push(
            "Solid line: one shoe loaded up from pull-off may rest on another set of summits (below the points) \
             and jumps where it changes set: static friction depends on the load path (docs/experiment.md)."
                .into(),
        );
        caption.push_str("; line: one loading path (friction depends on the path)");
    }
    let discrete = discrete_curve_n3(scenario, base, max_load)?;
    chart.series.push(Series::dashed("discrete model N = 3 (eq. 12)", discrete).with_color(2));
    if let Some(c) = &o.measured {
        // Drawn first, so that the virtual meter's points at the same loads stay visible on top.
        chart.series.insert(
            0,
            Series::markers(
                "measured (nominal a_clamp, a_pull, F_spring)",
                c.points.iter().map(|p| (p.load_measured_n * 1e6, p.friction_measured_n * 1e6)).collect(),
            )
            .with_color(4),
        );
        if let (Some(fit), Some(mu), Some(fa0)) =
            (&c.measured_fit, c.mu_apparent_measured, c.apparent_adhesion_force_measured_n)
        {
            let line = vec![(-fa0 * 1e6, 0.0), (max_load * 1e6, (fit.intercept + fit.slope * max_load) * 1e6)];
            chart.series.push(
                Series::line(
                    format!("eq. 10 fit of the measured slips: μ_e,a = {mu:.2}, F_a0 = {:.2} µN", fa0 * 1e6),
                    line,
                )
                .with_color(4),
            );
        }
    }
    // The virtual meter's eq. 10 line after the measured one: dashed on top of solid, both visible
    // where they coincide.
    if let (Some(fit), Some(fa0)) = (&r.fit, r.apparent_adhesion_force_n) {
        let line = vec![(-fa0 * 1e6, 0.0), (max_load * 1e6, (fit.intercept + fit.slope * max_load) * 1e6)];
        chart.series.push(
            Series::dashed(
                format!("eq. 10 fit of the virtual meter: μ_e,a = {:.2}, F_a0 = {:.2} µN", fit.slope, fa0 * 1e6),
                line,
            )
            .with_color(3),
        );
    }
    if let Some(rf) = &scenario.reference
        && let (Some((a, b)), Some(label)) = (reference::adhesion_range_un(rf), reference::adhesion_label(rf))
    {
        // At L = -F_a0, where an eq. 10 line meets F_f = 0.
        chart.series.push(Series::x_range(format!("{label}, at L = −F_a0"), -b, -a).with_color(7));
        if let Some(n) = reference::meaning_note(rf) {
            notes.push(n);
        }
    }
    chart.note = Some(caption);
    chart.legend = stiction_plot::LegendPosition::UpperLeft;
    let top = chart
        .series
        .iter()
        .filter(|s| s.style != stiction_plot::SeriesStyle::XSpan)
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .fold(0.0, f64::max);
    // Headroom above the data for the legend (upper left).
    chart.y_range = Some((0.0, top * 1.2));
    Ok((chart, notes))
}
