//! `stiction contact`: the explicit asperity-by-asperity solver (or, with `--model bem`, the
//! boundary-element model) on a scenario's surface.

use std::path::PathBuf;

use stiction_engine::ScenarioSource;
use stiction_engine::contact::{
    BemRun, ContactOutput, ContactRequest, ContactRun, Detail, Equilibrium, Mode as EngineMode, SweepEvent, contact,
};
use stiction_units::{Constraint, Dimension};

use crate::output::{CliResult, TextTable, domain_quantity, print_json, print_table, q};

/// Shoe degrees of freedom.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum Mode {
    /// Approach and two tilts free.
    Tilt,
    /// Approach only (the GW situation).
    Flat,
    /// Only the --contacts highest summits carry the shoe (eq. 12).
    Fixed,
}

/// Which solver `stiction contact` runs.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Model {
    /// The explicit asperity-by-asperity solver (summits, tilting rigid shoe).
    Explicit,
    /// The FFT boundary-element solver on the height-map patch under the shoe (needs
    /// `surface.source` = "height_map"; settings from `contact.bem`).
    Bem,
}

/// Equilibrium of a rigid shoe on the scenario's rough surface under a normal load (or a sweep of loads).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file (surface, material, contact law).
    pub scenario: PathBuf,
    /// The solver: explicit (default) or bem.
    #[arg(long, value_enum, default_value = "explicit")]
    pub model: Model,
    /// Normal load, compressive positive ("3 uN"; negative = adhesive pull, down to pull-off).
    #[arg(long, allow_hyphen_values = true, value_parser = domain_quantity(Dimension::Force, Constraint::Finite, "load", "--load"), required_unless_present = "sweep")]
    pub load: Option<f64>,
    /// Shoe degrees of freedom (default: the scenario's, else tilt).
    #[arg(long, value_enum)]
    pub mode: Option<Mode>,
    /// Number of contacts for --mode fixed.
    #[arg(long)]
    pub contacts: Option<usize>,
    /// A load sweep FROM:TO:STEPS, like "0uN:10uN:21" (loads in order; each from the previous equilibrium).
    #[arg(long, allow_hyphen_values = true, value_name = "FROM:TO:STEPS")]
    pub sweep: Option<String>,
    /// Largest number of --sweep steps (each is one equilibrium solve and one row of output).
    #[arg(long, default_value_t = DEFAULT_MAX_SWEEP_STEPS, value_name = "N")]
    pub max_sweep_steps: usize,
    /// Also list every summit in contact (interference, load, contact radius, peak pressure).
    #[arg(long)]
    pub summits: bool,
    /// Print JSON instead of a table. With --load: one equilibrium object (load_n, separation_m,
    /// tilt_x_rad, tilt_y_rad, contacts, contact_indices, real_area_m2, adhesive_load_n,
    /// friction_capacity_n, max_pressure_pa, residuals, ...). With --sweep: one object
    /// {"points": [one such equilibrium per load, in sweep order], "events": [{"event": "jump_in" |
    /// "release" | "pull_off", "point", "load_n", "contacts_before", "contacts_after" (pull_off:
    /// "load_n", "last_stable_load_n")}]}.
    #[arg(long)]
    pub json: bool,
    /// Override a scenario field (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
}

pub use stiction_engine::contact::DEFAULT_MAX_SWEEP_STEPS;
use stiction_engine::range::LoadRange;

impl Args {
    /// The engine's request of these flags (`--sweep` parsed into its loads).
    pub fn request(&self) -> Result<ContactRequest, String> {
        Ok(ContactRequest {
            model: match self.model {
                Model::Explicit => stiction_engine::contact::Model::Explicit,
                Model::Bem => stiction_engine::contact::Model::Bem,
            },
            load_n: self.load,
            loads_n: match &self.sweep {
                Some(text) => Some(
                    LoadRange::parse(
                        text,
                        "--sweep",
                        self.max_sweep_steps,
                        "raise it with --max-sweep-steps if you mean it",
                    )?
                    .values_n(),
                ),
                None => None,
            },
            mode: self.mode.map(|m| match m {
                Mode::Tilt => EngineMode::Tilt,
                Mode::Flat => EngineMode::Flat,
                Mode::Fixed => EngineMode::Fixed,
            }),
            contacts: self.contacts,
            summits: self.summits,
        })
    }
}

/// The command line's name of a request field.
fn flag(field: &str) -> String {
    match field {
        "load_n" => "--load",
        "loads_n" => "--sweep",
        "mode" => "--mode",
        "contacts" => "--contacts",
        "summits" => "--summits",
        "model" => "--model",
        other => other,
    }
    .to_string()
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    // The model is checked before the sweep is parsed, as before: a bem run's flags first.
    let req = args.request()?;
    let source = ScenarioSource::file(&args.scenario, &args.sets)?;
    // Per-contact detail only where an output shows it: the summit table (--summits) or the JSON
    // (contact indices); the plain table needs the totals only, which the solver's last pass holds.
    let detail = if args.summits {
        Detail::Full
    } else if args.json {
        Detail::Indices
    } else {
        Detail::Summary
    };
    let ContactRun { output, explicit } = contact(&req, &source, detail, &flag)?;
    if args.json {
        return print_json(&output);
    }
    match (output, explicit) {
        (ContactOutput::Bem(out), _) => print_bem(&out),
        (ContactOutput::Sweep(result), Some((summits, c, _))) => {
            crate::outln!("Load sweep on {} summits, mode {}, law {}", summits, c.mode, c.law);
            let mut t = TextTable::new(&[
                "L (uN)",
                "d (nm)",
                "tilt x (rad)",
                "tilt y (rad)",
                "N",
                "A_r (um^2)",
                "F_cap (uN)",
                "q0 (GPa)",
            ]);
            for e in &result.points {
                t.row(vec![
                    format!("{:.4}", e.load_n * 1e6),
                    format!("{:.4}", e.separation_m * 1e9),
                    format!("{:.3e}", e.tilt_x_rad),
                    format!("{:.3e}", e.tilt_y_rad),
                    e.contacts.to_string(),
                    format!("{:.5e}", e.real_area_m2 * 1e12),
                    format!("{:.4}", e.friction_capacity_n * 1e6),
                    format!("{:.3}", e.max_pressure_pa * 1e-9),
                ]);
            }
            t.print("  ");
            if !result.events.is_empty() {
                crate::outln!("\n  Events:");
            }
            for ev in &result.events {
                crate::outln!("    {}", event_line(ev));
            }
        }
        (ContactOutput::Point(eq), Some((summits, c, material))) => {
            print_table(
                &format!("Explicit contact on {} summits (mode {}, law {})", summits, c.mode, c.law),
                &rows(&eq, material.hardness),
            );
            if args.summits {
                crate::outln!();
                let mut t = TextTable::new(&["index", "x (um)", "y (um)", "z (nm)", "P (uN)", "a (nm)", "q0 (GPa)"]);
                for s in &eq.summits {
                    t.row(vec![
                        s.index.to_string(),
                        format!("{:.4}", s.x_m * 1e6),
                        format!("{:.4}", s.y_m * 1e6),
                        format!("{:.5}", s.interference_m * 1e9),
                        format!("{:.5}", s.load_n * 1e6),
                        format!("{:.3}", s.contact_radius_m * 1e9),
                        format!("{:.3}", s.max_pressure_pa * 1e-9),
                    ]);
                }
                t.print("  ");
            }
        }
        _ => return Err("the explicit solver's result came without its solver".into()),
    }
    Ok(())
}

/// A sweep event as a sentence, named as in the JSON (`jump_in`, `release`, `pull_off`), with the
/// same fields.
fn event_line(ev: &SweepEvent) -> String {
    let un = |f: f64| format!("{:.4} uN", f * 1e6);
    match ev {
        SweepEvent::JumpIn { point, load_n, contacts_before, contacts_after } => {
            format!("jump_in at L = {} (point {point}): contacts {contacts_before} -> {contacts_after}", un(*load_n))
        }
        SweepEvent::Release { point, load_n, contacts_before, contacts_after } => {
            format!("release at L = {} (point {point}): contacts {contacts_before} -> {contacts_after}", un(*load_n))
        }
        SweepEvent::PullOff { load_n, last_stable_load_n, note } => format!(
            "pull_off: no equilibrium at L = {} (the shoe comes off); {}; the sweep stops",
            un(*load_n),
            match (last_stable_load_n, note) {
                (Some(l), _) => format!("the last stable load was {}", un(*l)),
                (None, Some(n)) => n.clone(),
                (None, None) => "no load had an equilibrium".into(),
            }
        ),
    }
}

fn rows(eq: &Equilibrium, hardness: f64) -> Vec<(&'static str, String)> {
    vec![
        ("load L", q(eq.load_n, Dimension::Force)),
        ("separation d", q(eq.separation_m, Dimension::Length)),
        ("tilt x, y", format!("{:.3e} rad, {:.3e} rad", eq.tilt_x_rad, eq.tilt_y_rad)),
        ("contacts", format!("{}", eq.contacts)),
        ("real area A_r", format!("{:.5e} m^2", eq.real_area_m2)),
        ("adhesive load", q(eq.adhesive_load_n, Dimension::Force)),
        ("friction capacity s A_r", q(eq.friction_capacity_n, Dimension::Force)),
        (
            "max Hertz pressure q0",
            format!("{}  (hardness {})", q(eq.max_pressure_pa, Dimension::Pressure), q(hardness, Dimension::Pressure)),
        ),
        ("force residual", format!("{:.3e} N", eq.force_residual_n)),
        ("moment residuals", format!("{:.3e} N m, {:.3e} N m", eq.moment_residual_x_n_m, eq.moment_residual_y_n_m)),
    ]
}

/// The table of `--model bem`: the boundary-element model of the meter at each load (loading
/// branch).
fn print_bem(out: &BemRun) {
    let grid = out.grid;
    let face = match out.boundary {
        stiction_engine::bem::Boundary::Periodic => "one periodic cell",
        stiction_engine::bem::Boundary::NonPeriodic => "a finite patch on the wall",
    };
    crate::outln!(
        "Boundary-element contact on the shoe patch: {} x {} points of {:.4} nm x {:.4} nm ({face}{}), {}{}",
        grid.nx,
        grid.ny,
        grid.dx_m * 1e9,
        grid.dy_m * 1e9,
        if out.tilt { ", tilting shoe" } else { ", flat shoe" },
        out.dugdale.map_or("no adhesion".into(), |l| format!(
            "Dugdale adhesion {} over {} (loading branch)",
            q(l.stress_pa, Dimension::Pressure),
            q(l.range_m, Dimension::Length)
        )),
        out.hardness_pa
            .map_or(String::new(), |h| format!(", pressure capped at the hardness {}", q(h, Dimension::Pressure)))
    );
    let mut head = format!(
        "  {:>10} {:>12} {:>10} {:>8} {:>12} {:>11} {:>11} {:>9}",
        "L (uN)", "A_r (um^2)", "A_r/A_0", "patches", "gap (nm)", "F_adh (uN)", "F_cap (uN)", "q0 (GPa)"
    );
    if out.tilt {
        head += &format!(" {:>13} {:>13}", "tilt x (urad)", "tilt y (urad)");
    }
    if out.hardness_pa.is_some() {
        head += &format!(" {:>12}", "A_p (um^2)");
    }
    crate::outln!("{head}");
    for point in &out.points {
        let Some(p) = &point.state else {
            crate::outln!("  {:>10.4} no state: {}", point.load_n * 1e6, point.error.as_deref().unwrap_or("-"));
            continue;
        };
        let mut line = format!(
            "  {:>10.4} {:>12.5e} {:>10.3e} {:>8} {:>12.4} {:>11.4} {:>11.4} {:>9.3}",
            point.load_n * 1e6,
            p.real_area_m2 * 1e12,
            p.contact_fraction,
            p.patches,
            p.mean_gap_m * 1e9,
            p.adhesive_load_n * 1e6,
            p.friction_capacity_n * 1e6,
            p.max_pressure_pa * 1e-9
        );
        if let (Some(x), Some(y)) = (p.tilt_x_rad, p.tilt_y_rad) {
            line += &format!(" {:>13.4} {:>13.4}", x * 1e6, y * 1e6);
        }
        if let Some(a_p) = p.plastic_area_m2 {
            line += &format!(" {:>12.5e}", a_p * 1e12);
        }
        crate::outln!("{line}");
    }
}
