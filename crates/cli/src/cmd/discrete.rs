//! `stiction discrete`: the discrete N-contact model (eq. 12).

use serde::Serialize;
use stiction_contact::discrete::DiscreteModel;
use stiction_contact::single::{AdhesionLaw, AsperityParams};
use stiction_plot::{Chart, Series};
use stiction_scenario::MaterialSpec;
use stiction_units::{Constraint, Dimension};

use crate::output::{CliResult, print_json, print_table, q, quantity};

/// Single-asperity law for each contact.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Law {
    /// DMT (eq. 4), the paper's choice.
    Dmt,
    /// JKR.
    Jkr,
    /// Maugis-Dugdale (uses --equilibrium-spacing for the Maugis parameter).
    MaugisDugdale,
    /// Hertz, no adhesion (eq. 3).
    Hertz,
}

impl From<Law> for AdhesionLaw {
    fn from(l: Law) -> Self {
        match l {
            Law::Dmt => AdhesionLaw::Dmt,
            Law::Jkr => AdhesionLaw::Jkr,
            Law::MaugisDugdale => AdhesionLaw::MaugisDugdale,
            Law::Hertz => AdhesionLaw::Hertz,
        }
    }
}

/// Friction of N equally loaded summits: F_f = s N pi a^2 with a from the single-asperity law at L/N (eq. 12).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of contacts N (the paper: 1, 2 or 3 by the shoe's degrees of freedom; 3 in section 5).
    #[arg(long)]
    pub contacts: u32,
    /// Summit radius R ("0.5 um").
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub radius: f64,
    /// Work of adhesion dgamma ("0.1 J/m^2").
    #[arg(long, value_parser = quantity(Dimension::SurfaceEnergy, Constraint::NonNegative))]
    pub work_of_adhesion: f64,
    /// Composite compliance D = 3/4 ((1-nu1^2)/E1 + (1-nu2^2)/E2) ("9.1e-12 1/Pa").
    #[arg(long, value_parser = quantity(Dimension::Compliance, Constraint::Positive))]
    pub compliance: f64,
    /// Interfacial shear strength s ("1.4 GPa").
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::NonNegative))]
    pub shear_strength: f64,
    /// Applied load L ("3 uN"; negative down to the pull-off load).
    #[arg(long, allow_hyphen_values = true, value_parser = quantity(Dimension::Force, Constraint::Finite))]
    pub load: f64,
    /// Single-asperity law.
    #[arg(long, value_enum, default_value = "dmt")]
    pub adhesion: Law,
    /// Equilibrium spacing z0 of the surface forces, for the Tabor and Maugis parameters ("0.3 nm").
    #[arg(long, default_value = "0.3 nm", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub equilibrium_spacing: f64,
    /// Also give the shear strength for which the slope at --load equals this value (the paper: 0.7).
    #[arg(long)]
    pub target_slope: Option<f64>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Output {
    contacts: u32,
    law: AdhesionLaw,
    load_n: f64,
    friction_n: f64,
    /// null where the contact radius is 0 (then `friction_slope_null_reason` says why).
    friction_slope: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    friction_slope_null_reason: Option<&'static str>,
    zero_load_friction_n: f64,
    apparent_adhesion_force_n: Option<f64>,
    pull_off_load_n: f64,
    real_area_m2: f64,
    contact_radius_m: f64,
    interference_m: f64,
    max_pressure_pa: f64,
    tabor_parameter: f64,
    recommended_law: AdhesionLaw,
    #[serde(skip_serializing_if = "Option::is_none")]
    shear_strength_for_target_slope_pa: Option<f64>,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let params = AsperityParams {
        radius_m: args.radius,
        compliance_per_pa: args.compliance,
        work_of_adhesion_j_per_m2: args.work_of_adhesion,
        equilibrium_spacing_m: args.equilibrium_spacing,
    };
    let model = DiscreteModel::new(args.contacts, args.adhesion.into(), params, args.shear_strength)?;
    let at = model.at_load(args.load)?;
    let zero = model.at_load(0.0)?;
    let rec = params.recommendation();
    let out = Output {
        contacts: args.contacts,
        law: args.adhesion.into(),
        load_n: args.load,
        friction_n: at.friction_n,
        friction_slope: at.friction_slope,
        friction_slope_null_reason: at.friction_slope.is_none().then_some(DiscreteModel::SLOPE_NULL_REASON),
        zero_load_friction_n: zero.friction_n,
        // Eq. 10 as the paper evaluates it in section 5: F_a0 = F_f(0) / (dF_f/dL at the load).
        apparent_adhesion_force_n: at.friction_slope.filter(|s| *s > 0.0).map(|s| zero.friction_n / s),
        pull_off_load_n: model.pull_off_load_n()?,
        real_area_m2: at.real_area_m2,
        contact_radius_m: at.contact_radius_m,
        interference_m: at.interference_m,
        max_pressure_pa: at.max_pressure_pa,
        tabor_parameter: params.tabor_parameter(),
        recommended_law: rec.law,
        shear_strength_for_target_slope_pa: args
            .target_slope
            .map(|t| model.shear_strength_for_slope(t, args.load))
            .transpose()?,
    };
    if args.json {
        return print_json(&out);
    }
    let mut rows = vec![
        ("contacts N, law", format!("{}, {}", out.contacts, out.law)),
        ("load L", q(out.load_n, Dimension::Force)),
        ("friction F_f = s A_r", q(out.friction_n, Dimension::Force)),
        (
            "slope dF_f/dL (mu_e,a)",
            out.friction_slope
                .map_or_else(|| format!("n/a ({})", DiscreteModel::SLOPE_NULL_REASON), |s| format!("{s:.4}")),
        ),
        ("F_f(L = 0)", q(out.zero_load_friction_n, Dimension::Force)),
        (
            "apparent adhesion F_a0 = F_f(0)/slope",
            out.apparent_adhesion_force_n
                .map_or_else(|| "n/a (no finite slope > 0 at this load)".into(), |v| q(v, Dimension::Force)),
        ),
        ("pull-off load", q(out.pull_off_load_n, Dimension::Force)),
        ("real area A_r", format!("{:.5e} m^2", out.real_area_m2)),
        ("contact radius a (each)", q(out.contact_radius_m, Dimension::Length)),
        ("max Hertz pressure q0 (eq. 11)", q(out.max_pressure_pa, Dimension::Pressure)),
        ("Tabor parameter", format!("{:.3} (recommended law: {})", out.tabor_parameter, out.recommended_law)),
    ];
    if let Some(s) = out.shear_strength_for_target_slope_pa {
        rows.push(("s for the target slope", q(s, Dimension::Pressure)));
    }
    print_table("Discrete N-contact model (eq. 12)", &rows);
    Ok(())
}

/// The paper's Fig. 7 curve, N = 3, from the scenario's material and radius, from pull-off to
/// `max_load_n`: (L, F_f) in uN.
pub fn friction_curve_n3(
    material: &MaterialSpec,
    radius_m: f64,
    max_load_n: f64,
) -> Result<Vec<(f64, f64)>, Box<dyn std::error::Error>> {
    let params = stiction_meter::asperity_params(material, radius_m);
    let model = DiscreteModel::new(3, AdhesionLaw::Dmt, params, material.shear_strength)?;
    let pull_off = model.pull_off_load_n()?;
    Ok(model.friction_curve(pull_off, max_load_n, 200)?.into_iter().map(|(l, f)| (l * 1e6, f * 1e6)).collect())
}

/// Fig. 7 of the paper: F_f against L for N = 3, R = 0.5 um, s = 1.4 GPa (Table 1), with the
/// eq. 10 line of slope mu = dF_f/dL at 3 uN through F_f(0).
pub fn fig7_chart() -> Result<Chart, Box<dyn std::error::Error>> {
    let model = DiscreteModel::fig7();
    let pull_off = model.pull_off_load_n()?;
    let curve: Vec<(f64, f64)> =
        model.friction_curve(pull_off, 15e-6, 300)?.into_iter().map(|(l, f)| (l * 1e6, f * 1e6)).collect();
    let mu = model.at_load(3e-6)?.friction_slope.ok_or(DiscreteModel::SLOPE_NULL_REASON)?;
    let f0 = model.at_load(0.0)?.friction_n;
    let fa0 = f0 / mu;
    let line = vec![(-fa0 * 1e6, 0.0), (15.0, (f0 + mu * 15e-6) * 1e6)];
    let mut chart = Chart::new(
        "Fig. 7: friction against load, discrete model N = 3 (eq. 12)",
        "applied load L (uN)",
        "friction force F_f (uN)",
    )
    .with(Series::line("N = 3, R = 0.5 um, s = 1.4 GPa, DMT", curve))
    .with(Series::dashed(format!("eq. 10: mu_e,a = {mu:.2} (slope at 3 uN), F_a0 = {:.2} uN", fa0 * 1e6), line))
    .with(Series::line("paper, measured: F_a0 = 2.0 +/- 1.3 uN (the range on L < 0)", vec![(-3.3, 0.05), (-0.7, 0.05)]))
    .with(Series::markers("", vec![(-2.0, 0.05)]));
    chart.y_range = Some((0.0, (f0 + mu * 15e-6) * 1e6 * 1.05));
    Ok(chart)
}
