//! `stiction contact`: the explicit asperity-by-asperity solver (or, with `--model bem`, the
//! boundary-element model) on a scenario's surface.

use std::path::PathBuf;

use stiction_contact::explicit::{Detail, Equilibrium, SweepEvent};
use stiction_contact::single::Branch;
use stiction_meter::{ContactModel, build_contact_model};
use stiction_scenario::{ContactModel as ModelKind, MaterialSpec};
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

use crate::output::{CliResult, TextTable, domain_quantity, print_json, print_table, q};
use crate::scenario_source::ScenarioSource;

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

/// Default of `--max-sweep-steps`: a million equilibria take minutes and their rows about 100 MB.
pub const DEFAULT_MAX_SWEEP_STEPS: usize = 1_000_000;

/// Parses FROM:TO:STEPS into the loads, N; at most `max_steps` steps (checked before allocating).
pub fn parse_sweep(text: &str, max_steps: usize) -> Result<Vec<f64>, String> {
    let parts: Vec<&str> = text.split(':').collect();
    if parts.len() != 3 {
        return Err(format!("--sweep {text:?}: expected FROM:TO:STEPS, like \"0uN:10uN:21\""));
    }
    let f = |s: &str, what: &str| {
        let v = parse_quantity_checked(s, Dimension::Force, Constraint::Finite)
            .map_err(|e| format!("--sweep {what}: {e}"))?;
        stiction_scenario::domain::check_value("load", "load", v)
            .map_err(|e| format!("--sweep {what}: {}", e.message))?;
        Ok::<f64, String>(v)
    };
    let (from, to) = (f(parts[0], "FROM")?, f(parts[1], "TO")?);
    let steps: usize = parts[2]
        .trim()
        .parse()
        .ok()
        .filter(|n| *n >= 2)
        .ok_or_else(|| format!("--sweep STEPS {:?}: expected a whole number >= 2", parts[2]))?;
    if steps > max_steps {
        return Err(format!(
            "--sweep STEPS {steps}: more than the limit of {max_steps} steps (one equilibrium solve and about 100 \
             bytes of output each: {:.1e} bytes); raise it with --max-sweep-steps if you mean it",
            steps as f64 * 100.0
        ));
    }
    Ok((0..steps).map(|i| from + (to - from) * i as f64 / (steps - 1) as f64).collect())
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    if args.model == Model::Bem {
        return run_bem(&args);
    }
    let (mut solver, c, material) = explicit_solver(&args, &ScenarioSource::file(&args.scenario, &[])?)?;
    // Per-contact detail only where an output shows it: the summit table (--summits) or the JSON
    // (contact indices); the plain table needs the totals only, which the solver's last pass holds.
    solver.set_detail(if args.summits {
        Detail::Full
    } else if args.json {
        Detail::Indices
    } else {
        Detail::Summary
    });
    if let Some(sweep) = &args.sweep {
        let loads = parse_sweep(sweep, args.max_sweep_steps)?;
        let increasing = loads.last() >= loads.first();
        let result = solver.sweep(&loads, if increasing { Branch::Loading } else { Branch::Unloading })?;
        if args.json {
            return print_json(&result);
        }
        crate::outln!("Load sweep on {} summits, mode {}, law {}", solver.len(), c.mode, c.law);
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
        return Ok(());
    }
    let load = args.load.ok_or("give --load or --sweep")?;
    let eq = solver.solve(load)?;
    if args.json {
        return print_json(&eq);
    }
    print_table(
        &format!("Explicit contact on {} summits (mode {}, law {})", solver.len(), c.mode, c.law),
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
    Ok(())
}

/// The explicit solver of the scenario of `args`, with `--mode` and `--contacts` applied: the
/// solver, the scenario's contact settings and its material.
fn explicit_solver(
    args: &Args,
    source: &ScenarioSource,
) -> Result<
    (Box<stiction_contact::explicit::ExplicitSolver>, stiction_scenario::ContactSpec, MaterialSpec),
    Box<dyn std::error::Error>,
> {
    let mut sets = args.sets.clone();
    sets.push("contact.model=\"explicit\"".into());
    match args.mode {
        Some(Mode::Tilt) => sets.push("contact.mode=\"tilt\"".into()),
        Some(Mode::Flat) => sets.push("contact.mode=\"flat\"".into()),
        Some(Mode::Fixed) => sets.push("contact.mode=\"fixed\"".into()),
        None => {}
    }
    if let Some(n) = args.contacts {
        sets.push(format!("contact.contacts={n}"));
    }
    let scenario = source.parse(&sets)?;
    let name = source.name();
    let material = scenario.require_material().map_err(|e| format!("{name}: {e}"))?.clone();
    let c = scenario.contact_or_default();
    debug_assert_eq!(c.model, ModelKind::Explicit);
    let model = build_contact_model(&scenario, &material, &source.base).map_err(|e| format!("{name}: {e}"))?;
    let ContactModel::Explicit(solver) = model else {
        return Err("the explicit solver could not be built".into());
    };
    Ok((solver, c, material))
}

/// What `stiction contact SCENARIO --json` prints for the scenario `source` (a file or a tree
/// built in memory; `args.scenario` is not read, `args.sets` apply after the source's own). With
/// the explicit solver: the equilibrium at `--load`, or for a sweep (the loads given, else
/// `--sweep`) {"points", "events"}; with `--model bem`: the boundary-element model at those loads
/// (`model`, `grid`, ..., `points`). Every number checked finite. For front ends other than the
/// command line (the Python module).
pub fn contact_json(
    args: &Args,
    source: &ScenarioSource,
    sweep_loads: Option<&[f64]>,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    if args.model == Model::Bem {
        return Ok(crate::json_value::finite_value(&bem_run(args, source, sweep_loads)?)?);
    }
    let (mut solver, _, _) = explicit_solver(args, source)?;
    solver.set_detail(if args.summits { Detail::Full } else { Detail::Indices });
    let parsed;
    let loads = match (sweep_loads, &args.sweep) {
        (Some(l), _) => Some(l),
        (None, Some(text)) => {
            parsed = parse_sweep(text, args.max_sweep_steps)?;
            Some(&parsed[..])
        }
        (None, None) => None,
    };
    if let Some(loads) = loads {
        let increasing = loads.last() >= loads.first();
        let result = solver.sweep(loads, if increasing { Branch::Loading } else { Branch::Unloading })?;
        return Ok(crate::json_value::finite_value(&result)?);
    }
    let load = args.load.ok_or("give --load or --sweep")?;
    Ok(crate::json_value::finite_value(&solver.solve(load)?)?)
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

/// One load of `stiction contact --model bem`.
#[derive(serde::Serialize)]
struct BemPoint {
    load_n: f64,
    real_area_m2: f64,
    contact_fraction: f64,
    patches: usize,
    mean_gap_m: f64,
    /// The Dugdale tension over the cohesive zone, N (the contact pressure carries L plus it).
    adhesive_load_n: f64,
    cohesive_fraction: f64,
    /// s A_r with the material's shear strength, N.
    friction_capacity_n: f64,
    max_pressure_pa: f64,
    iterations: usize,
}

#[derive(serde::Serialize)]
struct BemRun {
    model: &'static str,
    grid: stiction_bem::Grid,
    /// Block factors (x, y) from the map's pixels to the grid.
    coarsening: (usize, usize),
    e_star_pa: f64,
    dugdale: Option<stiction_bem::Dugdale>,
    /// Why `dugdale` is null: no adhesion (law "hertz" or no work of adhesion).
    #[serde(skip_serializing_if = "Option::is_none")]
    dugdale_note: Option<&'static str>,
    shear_strength_pa: f64,
    points: Vec<BemPoint>,
}

/// The boundary-element model of the scenario `source` (`args.sets` after its own overrides) at
/// each load of `sweep_loads` when given, else of `--sweep` or `--load` (N, compressive, in order;
/// the loading branch).
fn bem_run(
    args: &Args,
    source: &ScenarioSource,
    sweep_loads: Option<&[f64]>,
) -> Result<BemRun, Box<dyn std::error::Error>> {
    if args.mode.is_some() || args.contacts.is_some() || args.summits {
        return Err("--mode, --contacts and --summits belong to the explicit solver; --model bem has a flat shoe \
                    unless the scenario's contact.bem.tilt is true (--set contact.bem.tilt=true) and reports contact \
                    patches"
            .into());
    }
    let mut sets = args.sets.clone();
    sets.push("contact.model=\"bem\"".into());
    let scenario = source.parse(&sets)?;
    let name = source.name();
    let material = scenario.require_material().map_err(|e| format!("{name}: {e}"))?.clone();
    let mut bem = stiction_meter::build_bem(&scenario, &material, &source.base).map_err(|e| format!("{name}: {e}"))?;
    let loads = match (sweep_loads, &args.sweep, args.load) {
        (Some(l), _, _) => l.to_vec(),
        (None, Some(sweep), _) => parse_sweep(sweep, args.max_sweep_steps)?,
        (None, None, Some(l)) => vec![l],
        (None, None, None) => return Err("give --load or --sweep".into()),
    };
    if let Some(l) = loads.iter().find(|l| l.is_nan() || **l <= 0.0) {
        return Err(format!(
            "load {}: --model bem follows the loading branch and needs compressive loads > 0",
            q(*l, Dimension::Force)
        )
        .into());
    }
    let grid = bem.grid();
    let stress = bem.law().map_or(0.0, |l| l.stress_pa);
    let mut points = Vec::with_capacity(loads.len());
    for &load in &loads {
        let s = bem.solve(load)?;
        let max_pressure_pa =
            s.pressure_pa.iter().zip(&s.contact).filter(|(_, c)| **c).map(|(p, _)| p + stress).fold(0.0, f64::max);
        points.push(BemPoint {
            load_n: s.load_n(&grid),
            real_area_m2: s.contact_area_m2,
            contact_fraction: s.contact_fraction,
            patches: s.patches,
            mean_gap_m: s.mean_gap_m,
            adhesive_load_n: stress * s.cohesive_fraction * grid.area_m2(),
            cohesive_fraction: s.cohesive_fraction,
            friction_capacity_n: s.friction_n(material.shear_strength),
            max_pressure_pa,
            iterations: s.iterations,
        });
    }
    Ok(BemRun {
        model: "bem",
        grid,
        coarsening: bem.coarsening,
        e_star_pa: 0.75 / material.compliance_per_pa(),
        dugdale: bem.law(),
        dugdale_note: bem.law().is_none().then_some("no adhesion: law \"hertz\" or no work of adhesion"),
        shear_strength_pa: material.shear_strength,
        points,
    })
}

/// `--model bem`: the boundary-element model of the meter at each load (loading branch).
fn run_bem(args: &Args) -> CliResult {
    let out = bem_run(args, &ScenarioSource::file(&args.scenario, &[])?, None)?;
    let grid = out.grid;
    if args.json {
        return print_json(&out);
    }
    crate::outln!(
        "Boundary-element contact on the shoe patch: {} x {} points of {:.4} nm x {:.4} nm (periodic cell = the patch), {}",
        grid.nx,
        grid.ny,
        grid.dx_m * 1e9,
        grid.dy_m * 1e9,
        out.dugdale.map_or("no adhesion".into(), |l| format!(
            "Dugdale adhesion {} over {} (loading branch)",
            q(l.stress_pa, Dimension::Pressure),
            q(l.range_m, Dimension::Length)
        ))
    );
    crate::outln!(
        "  {:>10} {:>12} {:>10} {:>8} {:>12} {:>11} {:>11} {:>9}",
        "L (uN)",
        "A_r (um^2)",
        "A_r/A_0",
        "patches",
        "gap (nm)",
        "F_adh (uN)",
        "F_cap (uN)",
        "q0 (GPa)"
    );
    for p in &out.points {
        crate::outln!(
            "  {:>10.4} {:>12.5e} {:>10.3e} {:>8} {:>12.4} {:>11.4} {:>11.4} {:>9.3}",
            p.load_n * 1e6,
            p.real_area_m2 * 1e12,
            p.contact_fraction,
            p.patches,
            p.mean_gap_m * 1e9,
            p.adhesive_load_n * 1e6,
            p.friction_capacity_n * 1e6,
            p.max_pressure_pa * 1e-9
        );
    }
    Ok(())
}
