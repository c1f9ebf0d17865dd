//! `stiction discrete`: the discrete N-contact model (eq. 12).

use stiction_engine::discrete::{AdhesionLaw, DiscreteModel, DiscreteRequest, Fig7Curve, discrete, fig7_curve};
use stiction_engine::scenario::{ReferenceSpec, Scenario};
use stiction_plot::{Chart, Series};
use stiction_units::{Constraint, Dimension};

use crate::output::{CliResult, domain_quantity, print_json, print_table, q, quantity};

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

pub use stiction_engine::discrete::MAX_CONTACTS;

/// Friction of N equally loaded summits: F_f = s N pi a^2 with a from the single-asperity law at L/N (eq. 12).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of contacts N (the paper: 1, 2 or 3 by the shoe's degrees of freedom; 3 in section 5).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=MAX_CONTACTS as i64))]
    pub contacts: u32,
    /// Summit radius R ("0.5 um").
    #[arg(long, value_parser = domain_quantity(Dimension::Length, Constraint::Positive, "surface.summit_radius", "--radius"))]
    pub radius: f64,
    /// Work of adhesion dgamma ("0.1 J/m^2").
    #[arg(long, value_parser = domain_quantity(Dimension::SurfaceEnergy, Constraint::NonNegative, "material.work_of_adhesion", "--work-of-adhesion"))]
    pub work_of_adhesion: f64,
    /// Composite compliance D = 3/4 ((1-nu1^2)/E1 + (1-nu2^2)/E2) ("9.1e-12 1/Pa").
    #[arg(long, value_parser = domain_quantity(Dimension::Compliance, Constraint::Positive, "material.compliance", "--compliance"))]
    pub compliance: f64,
    /// Interfacial shear strength s ("1.4 GPa").
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::NonNegative))]
    pub shear_strength: f64,
    /// Applied load L ("3 uN"; negative down to the pull-off load).
    #[arg(long, allow_hyphen_values = true, value_parser = domain_quantity(Dimension::Force, Constraint::Finite, "load", "--load"))]
    pub load: f64,
    /// Single-asperity law.
    #[arg(long, value_enum, default_value = "dmt")]
    pub adhesion: Law,
    /// Equilibrium spacing z0 of the surface forces, for the Tabor and Maugis parameters ("0.3 nm").
    #[arg(long, default_value = "0.3 nm", value_parser = domain_quantity(Dimension::Length, Constraint::Positive, "material.equilibrium_spacing", "--equilibrium-spacing"))]
    pub equilibrium_spacing: f64,
    /// Also give the shear strength for which the slope at --load equals this value (the paper: 0.7).
    #[arg(long)]
    pub target_slope: Option<f64>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

impl Args {
    /// The engine's request of these flags.
    pub fn request(&self) -> DiscreteRequest {
        DiscreteRequest {
            contacts: self.contacts,
            radius_m: self.radius,
            work_of_adhesion_j_per_m2: self.work_of_adhesion,
            compliance_per_pa: self.compliance,
            shear_strength_pa: self.shear_strength,
            load_n: self.load,
            law: self.adhesion.into(),
            equilibrium_spacing_m: self.equilibrium_spacing,
            target_slope: self.target_slope,
        }
    }
}

/// The command line's name of a request field.
fn flag(field: &str) -> String {
    match field {
        "radius_m" => "--radius",
        "work_of_adhesion_j_per_m2" => "--work-of-adhesion",
        "compliance_per_pa" => "--compliance",
        "shear_strength_pa" => "--shear-strength",
        "load_n" => "--load",
        "equilibrium_spacing_m" => "--equilibrium-spacing",
        "contacts" => "--contacts",
        other => other,
    }
    .to_string()
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let req = args.request();
    // The flags were checked against their domains as they were parsed (warnings printed there).
    req.validate(&flag)?;
    let out = discrete(&req)?;
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

/// What `plot fig7` draws: a discrete model, where its parameters come from, and the reference
/// values to show.
pub struct Fig7Setup {
    /// The model (N, law, summit, s).
    pub model: DiscreteModel,
    /// Measured values to draw (the F_a0 band), if any.
    pub reference: Option<ReferenceSpec>,
    /// Where the parameters come from, for the note.
    pub origin: String,
}

impl Fig7Setup {
    /// The paper's Fig. 7: N = 3, DMT, Table 1, s = 1.4 GPa, with the paper's measured F_a0.
    pub fn paper() -> Fig7Setup {
        Fig7Setup {
            model: DiscreteModel::fig7(),
            reference: Some(crate::figargs::reference::paper()),
            origin: "Table 1 and s of the paper".into(),
        }
    }

    /// A scenario's material, model summit radius, contact law and number of contacts (the
    /// scenario's `contact.contacts` for the discrete model or a fixed shoe, else the paper's 3),
    /// with its `reference` section if it has one.
    pub fn of_scenario(s: &Scenario, base: &std::path::Path) -> Result<Fig7Setup, Box<dyn std::error::Error>> {
        let model = stiction_engine::discrete::fig7_model(s, base)?;
        Ok(Fig7Setup { model, reference: s.reference.clone(), origin: "the scenario".into() })
    }
}

/// The user-facing name of a single-asperity law.
pub fn law_name(law: AdhesionLaw) -> &'static str {
    match law {
        AdhesionLaw::Hertz => "Hertz",
        AdhesionLaw::Dmt => "DMT",
        AdhesionLaw::Jkr => "JKR",
        AdhesionLaw::MaugisDugdale => "Maugis-Dugdale",
    }
}

/// Fig. 7 of the paper: F_f against L for the discrete model (default N = 3, R = 0.5 µm,
/// s = 1.4 GPa, DMT: Table 1), with the eq. 10 line of slope mu = dF_f/dL at 3 µN through F_f(0)
/// and the measured F_a0 as a band at L = -F_a0 (where eq. 10's line meets F_f = 0).
pub fn fig7_chart(setup: &Fig7Setup) -> Result<Chart, Box<dyn std::error::Error>> {
    use crate::figargs::reference;
    use crate::format::sig3;
    let model = &setup.model;
    let Fig7Curve { curve_un: curve, slope_at_3un: mu, zero_load_friction_n: f0, pull_off_n: pull_off } =
        fig7_curve(model)?;
    let fa0 = f0 / mu;
    let line = vec![(-fa0 * 1e6, 0.0), (15.0, (f0 + mu * 15e-6) * 1e6)];
    let p = &model.params;
    let mut chart = Chart::new(
        format!(
            "Fig. 7: friction against load, discrete model N = {}, {} (eq. 12)",
            model.contacts,
            law_name(model.law)
        ),
        "applied load L (µN)",
        "friction force F_f (µN)",
    )
    .keys("load_un", "friction_un")
    .with_note(format!(
        "R = {} µm, s = {} GPa, Δγ = {} J/m², D = {} 1/Pa ({})",
        sig3(p.radius_m * 1e6),
        sig3(model.shear_strength_pa / 1e9),
        sig3(p.work_of_adhesion_j_per_m2),
        sig3(p.compliance_per_pa),
        setup.origin
    ))
    .with(Series::line(
        format!(
            "F_f = s A_r, N = {}, R = {} µm, s = {} GPa",
            model.contacts,
            sig3(p.radius_m * 1e6),
            sig3(model.shear_strength_pa / 1e9)
        ),
        curve,
    ))
    .with(Series::dashed(format!("eq. 10: μ_e,a = {mu:.2} (slope at 3 µN), F_a0 = {:.2} µN", fa0 * 1e6), line));
    let mut low = -fa0 * 1e6;
    if let Some(r) = &setup.reference
        && let (Some((a, b)), Some(label)) = (reference::adhesion_range_un(r), reference::adhesion_label(r))
    {
        // At L = -F_a0, where eq. 10's line meets F_f = 0: the measured range of -F_a0.
        chart.series.push(Series::x_range(format!("{label}, at L = −F_a0"), -b, -a).with_color(2));
        low = low.min(-b);
        if let Some(n) = reference::meaning_note(r) {
            chart.note = Some(format!("{}\n{n}", chart.note.take().unwrap_or_default()));
        }
    }
    chart.legend = stiction_plot::LegendPosition::LowerRight;
    chart.y_range = Some((0.0, (f0 + mu * 15e-6) * 1e6 * 1.05));
    chart.x_range = Some((low.min(pull_off * 1e6) - 0.3, 15.5));
    Ok(chart)
}
