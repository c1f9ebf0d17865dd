//! `stiction bem`: the FFT boundary-element solver on a surface: a generated self-affine one, a
//! measured height map (`--map`, read and levelled as `stiction topography` does) or a scenario's
//! height-map face(s) under the shoe (`--scenario`); at one load, over a load sweep or (with
//! adhesion) over a mean-gap path; fields, curves and figures.

use std::path::PathBuf;

use serde::Serialize;
use stiction_bem::{BemSolver, ContactSolution, Dugdale, Grid, SolverOptions, synth};
use stiction_plot::{Chart, ImageMap, Series};
use stiction_topography::{HeightMap, MapInfo, Patch, PreparationReport, prepare, read_file};
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

use super::map_args::MapArgs;
use crate::output::{CliResult, OutputSet, TextTable, print_json, print_table, q, quantity};
use stiction_engine::ScenarioSource;

/// Largest grid side of the command (the solver's own limit is 4096 x 4096 points).
const MAX_SIDE: usize = 4096;

/// Boundary-element contact of a rigid flat on a rough surface: a generated Gaussian self-affine
/// one (default), a measured height map (--map) or a scenario's height-map face(s) under the shoe
/// (--scenario). The cell is periodic: a map is taken as one period of the interface.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A measured height map (.npy, .gsf, .xyz, text/CSV), read, levelled and filtered as
    /// `stiction topography` does; the whole map is the periodic cell (nx x ny, need not be square).
    #[arg(long, value_name = "FILE", conflicts_with = "scenario")]
    pub map: Option<PathBuf>,
    /// With --map: the file's metadata and preparation.
    #[command(flatten)]
    pub map_args: MapArgs,
    /// A scenario with `surface.source` = "height_map": the composite patch of its face(s) under the
    /// shoe (the grid `stiction contact --model bem` and the meter use); E* from its material.
    #[arg(long, value_name = "SCENARIO.json")]
    pub scenario: Option<PathBuf>,
    /// With --scenario: override a scenario field (repeatable).
    #[arg(long = "set", value_name = "PATH=VALUE", requires = "scenario")]
    pub sets: Vec<String>,
    /// Generated surface: side of the square periodic cell ("100 um").
    #[arg(long, default_value = "100 um", value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
    pub size: f64,
    /// Generated surface: grid points per side (2..=4096; powers of two are fastest).
    #[arg(long, default_value_t = 256, conflicts_with_all = ["map", "scenario"])]
    pub grid: usize,
    /// Generated surface: Hurst exponent of the self-affine spectrum (0 < H <= 1).
    #[arg(long, default_value_t = 0.8, conflicts_with_all = ["map", "scenario"])]
    pub hurst: f64,
    /// Generated surface: roll-off wavelength ("25 um"; default: a quarter of the cell).
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
    pub roll_off: Option<f64>,
    /// Generated surface: short-wavelength cut-off ("1.6 um"; default: 4 pixels).
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
    pub short: Option<f64>,
    /// Generated surface: rms height of the composite surface ("0.5 um").
    #[arg(long, default_value = "0.5 um", value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
    pub rms_height: f64,
    /// Generated surface: seed (ChaCha8).
    #[arg(long, default_value_t = 1, conflicts_with_all = ["map", "scenario"])]
    pub seed: u64,
    /// Composite modulus E* = 1/sum((1 - nu^2)/E) ("85 GPa"; default 85 GPa, or 3/(4D) from the
    /// --scenario's material).
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::Positive))]
    pub e_star: Option<f64>,
    /// Mean (nominal) pressure, compressive ("20 MPa"); without adhesion.
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::Positive), conflicts_with_all = ["sweep", "gap_sweep"])]
    pub pressure: Option<f64>,
    /// Sweep of mean pressures FROM:TO:STEPS ("1MPa:50MPa:10"), each from the previous state; without adhesion.
    #[arg(long, value_name = "FROM:TO:STEPS", conflicts_with = "gap_sweep")]
    pub sweep: Option<String>,
    /// Path of mean gaps FROM:TO:STEPS ("1um:0.2um:20"), in order, each from the previous state (approach when
    /// decreasing, retraction when increasing; give two runs or a V-shaped path with --gap-back).
    #[arg(long, value_name = "FROM:TO:STEPS")]
    pub gap_sweep: Option<String>,
    /// With --gap-sweep: go back to FROM after reaching TO (a loading-unloading cycle; pull-off on the way back).
    #[arg(long)]
    pub gap_back: bool,
    /// Work of adhesion of the Dugdale law ("0.1 J/m^2"); needs --range and --gap-sweep.
    #[arg(long, value_parser = quantity(Dimension::SurfaceEnergy, Constraint::Positive), requires = "range")]
    pub work_of_adhesion: Option<f64>,
    /// Range h0 of the Dugdale law ("1 nm"); the Dugdale stress is w/h0.
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive), requires = "work_of_adhesion")]
    pub range: Option<f64>,
    /// Adhesion energy against relative humidity (--rh and its settings).
    #[command(flatten)]
    pub humidity: HumidityArgs,
    /// Interfacial shear strength s for the friction s A_r ("100 MPa").
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::NonNegative))]
    pub shear_strength: Option<f64>,
    /// Relative tolerance of the constrained conjugate gradient.
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance: f64,
    /// Also solve the summit (asperity) model on the same grid at the same loads: independent Hertz summits,
    /// no elastic interaction; adds its contact fraction and the ratio A_BEM/A_asperity to the curve.
    #[arg(long)]
    pub compare_asperity: bool,
    /// Folder for the fields (CSV, PNG heat maps of the last state), the curves (CSV, PNG) and
    /// results.json, with a manifest.json, swapped in whole.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are
    /// left alone; the earlier run's files are replaced or removed).
    #[arg(long)]
    pub force: bool,
    /// Figure size and font (--width, --height, --font-size).
    #[command(flatten)]
    pub fig: crate::figargs::FigureArgs,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// The `--rh` flags of `stiction bem`.
#[derive(clap::Args, Debug)]
pub struct HumidityArgs {
    /// Adhesion energy against relative humidity (the microcantilever experiment's quantity): for
    /// each RH, a capillary cohesive zone of water (Laplace pressure gamma/r_K wherever the gap is
    /// below the meniscus height h_m = 2 r_K cos theta), with the Dugdale law of --work-of-adhesion and
    /// --range for van der Waals if given, and the work of separation of a retraction from the
    /// compressed state at --pressure (default 1 MPa) to separation. A list ("0.1,0.35,0.9" or
    /// "35 %,60 %") or FROM:TO:STEPS ("0.1:0.9:9"); fractions in [0, 1).
    #[arg(long, value_name = "LIST|FROM:TO:STEPS", allow_hyphen_values = true, conflicts_with_all = ["sweep", "gap_sweep", "compare_asperity"])]
    pub rh: Option<String>,
    /// With --rh: temperature ("25 C", "298.15 K"; a bare number is kelvin).
    #[arg(long, default_value = "25 C", allow_hyphen_values = true, requires = "rh")]
    pub temperature: String,
    /// With --rh: contact angle of water on both faces ("0 deg": hydrophilic oxide; >= 90 deg: no
    /// capillary condensation).
    #[arg(long, default_value = "0 deg", allow_hyphen_values = true, value_parser = quantity(Dimension::Angle, Constraint::NonNegative), requires = "rh")]
    pub contact_angle: f64,
    /// With --rh: mean-gap step of the retraction ("0.02 nm"; default a twentieth of the shortest
    /// range of the cohesive laws).
    #[arg(long, allow_hyphen_values = true, value_parser = quantity(Dimension::Length, Constraint::Positive), requires = "rh")]
    pub rh_step: Option<f64>,
    /// With --rh: smallest Kelvin radius at which water condenses ("0.28 nm", a water molecule's
    /// diameter; default none: the continuum meniscus at every humidity). Below it only the van der
    /// Waals law acts (the dry regime at low humidity); the scenario's
    /// `environment.min_kelvin_radius`.
    #[arg(long, allow_hyphen_values = true, value_parser = quantity(Dimension::Length, Constraint::Positive), requires = "rh")]
    pub min_kelvin_radius: Option<f64>,
}

/// One point of a load or gap path.
#[derive(Serialize, Clone, Debug)]
struct Point {
    mean_pressure_pa: f64,
    load_n: f64,
    mean_gap_m: f64,
    contact_fraction: f64,
    contact_area_m2: f64,
    patches: usize,
    cohesive_fraction: f64,
    friction_n: Option<f64>,
    elastic_energy_j_per_m2: f64,
    iterations: usize,
    residual: f64,
    asperity_contact_fraction: Option<f64>,
    area_ratio_bem_over_asperity: Option<f64>,
    /// Why a value of the point is null: no --shear-strength (no friction), no
    /// --compare-asperity (no asperity model beside it), or no asperity contact to divide by.
    #[serde(skip_serializing_if = "Option::is_none")]
    note: Option<&'static str>,
}

/// Where the heights came from.
#[derive(Serialize)]
#[serde(tag = "source", rename_all = "snake_case")]
enum SurfaceSource {
    /// The built-in generator.
    Generated { hurst: f64, roll_off_wavelength_m: f64, short_wavelength_m: f64, seed: u64 },
    /// A height-map file, whole.
    HeightMap { file: String, read: MapInfo, preparation: PreparationReport },
    /// A scenario's face(s) under the shoe.
    Scenario {
        file: String,
        /// The pixel window of each face's map (wall first, then shoe) that makes the patch.
        faces: Vec<Patch>,
    },
}

/// The surface to solve on.
struct Surface {
    grid: Grid,
    heights: Vec<f64>,
    source: SurfaceSource,
    e_star_pa: f64,
}

#[derive(Serialize)]
struct Output {
    surface: SurfaceSource,
    grid: Grid,
    e_star_pa: f64,
    rms_height_m: f64,
    rms_slope: f64,
    /// The generator's seed (null for a map or a scenario).
    seed: Option<u64>,
    dugdale: Option<Dugdale>,
    tolerance: f64,
    points: Vec<Point>,
    /// Most tensile load on the path, N (the pull-off under load control), when adhesive.
    pull_off_n: Option<f64>,
    /// Why the seed, the Dugdale law or the pull-off is null.
    #[serde(skip_serializing_if = "Option::is_none")]
    note: Option<&'static str>,
}

fn parse_path(text: &str, dim: Dimension, flag: &str) -> Result<Vec<f64>, String> {
    let parts: Vec<&str> = text.split(':').collect();
    if parts.len() != 3 {
        return Err(format!("{flag} {text:?}: expected FROM:TO:STEPS"));
    }
    let f = |s: &str| parse_quantity_checked(s, dim, Constraint::Positive).map_err(|e| format!("{flag}: {e}"));
    let (a, b) = (f(parts[0])?, f(parts[1])?);
    let steps: usize = parts[2]
        .trim()
        .parse()
        .ok()
        .filter(|&s| (1..=10_000).contains(&s))
        .ok_or_else(|| format!("{flag} {text:?}: STEPS {:?} must be an integer in 1..=10000", parts[2]))?;
    if steps == 1 {
        return Ok(vec![a]);
    }
    Ok((0..steps).map(|k| a + (b - a) * k as f64 / (steps - 1) as f64).collect())
}

/// The surface of a height map read as `file` (`raw`, `info` from the reader), prepared with the
/// `--level`/`--cutoff` flags: the whole map is the periodic cell.
fn map_surface(args: &Args, file: &str, raw: HeightMap, info: MapInfo) -> Result<Surface, Box<dyn std::error::Error>> {
    let (map, report) = prepare(&raw, &args.map_args.preparation())?;
    drop(raw);
    let grid = Grid::new(map.nx(), map.ny(), map.dx_m(), map.dy_m())
        .map_err(|e| format!("{file}: {e} (the BEM grid limit)"))?;
    let heights = map.into_heights_m();
    stiction_bem::spec::check_complete(&heights).map_err(|e| format!("{file}: {e}"))?;
    Ok(Surface {
        grid,
        heights,
        source: SurfaceSource::HeightMap { file: file.to_string(), read: info, preparation: report },
        e_star_pa: args.e_star.unwrap_or(85e9),
    })
}

/// The composite patch of the height-map face(s) under the shoe of the scenario `source` (with
/// `args.sets` after its own overrides); E* from `--e-star`, else 3/(4D) of its material.
fn scenario_surface(args: &Args, source: &ScenarioSource) -> Result<Surface, Box<dyn std::error::Error>> {
    let scenario = source.parse(&args.sets)?;
    let file = source.name();
    let spec = scenario.require_surface().map_err(|e| format!("{file}: {e}"))?;
    let (patch, faces) =
        stiction_surface::height_map_patch(spec, &source.base).map_err(|e| format!("{file}: surface: {e}"))?;
    let grid = Grid::new(patch.nx(), patch.ny(), patch.dx_m(), patch.dy_m())
        .map_err(|e| format!("{file}: {e} (the BEM grid limit)"))?;
    let heights = patch.into_heights_m();
    stiction_bem::spec::check_complete(&heights).map_err(|e| format!("{file}: {e}"))?;
    let e_star_pa = match args.e_star {
        Some(e) => e,
        None => {
            let m = scenario.require_material().map_err(|e| format!("{file}: {e}"))?;
            0.75 / m.compliance_per_pa()
        }
    };
    Ok(Surface { grid, heights, source: SurfaceSource::Scenario { file, faces }, e_star_pa })
}

/// The surface of the command line: generated, a map file, or a scenario's patch.
fn build_surface(args: &Args) -> Result<Surface, Box<dyn std::error::Error>> {
    if let Some(file) = &args.map {
        let (raw, info) = read_file(file, args.map_args.format, &args.map_args.metadata())?;
        return map_surface(args, &file.display().to_string(), raw, info);
    }
    if let Some(file) = &args.scenario {
        return scenario_surface(args, &ScenarioSource::file(file, &[])?);
    }
    generated_surface(args)
}

/// The generated surface of `--size`, `--grid`, `--hurst`, `--roll-off`, `--short`,
/// `--rms-height` and `--seed`: a Gaussian self-affine surface ([`synth::self_affine`]).
fn generated_surface(args: &Args) -> Result<Surface, Box<dyn std::error::Error>> {
    if !(2..=MAX_SIDE).contains(&args.grid) {
        return Err(format!("--grid {}: expected 2..={MAX_SIDE} points per side", args.grid).into());
    }
    let n = args.grid;
    let dx = args.size / n as f64;
    let grid = Grid::new(n, n, dx, dx)?;
    let roll_off = args.roll_off.unwrap_or(args.size / 4.0);
    let short = args.short.unwrap_or(4.0 * dx);
    let heights = synth::self_affine(grid, args.hurst, roll_off, short, args.rms_height, args.seed)?;
    Ok(Surface {
        grid,
        heights,
        source: SurfaceSource::Generated {
            hurst: args.hurst,
            roll_off_wavelength_m: roll_off,
            short_wavelength_m: short,
            seed: args.seed,
        },
        e_star_pa: args.e_star.unwrap_or(85e9),
    })
}

/// The surface a front end other than the command line solves on: the command line's three
/// sources, with the map already read and the scenario already held in memory.
pub enum BemSurface<'a> {
    /// The generated surface of the generator flags (`--size`, `--grid`, ...; the command line's
    /// default).
    Generated,
    /// A height map read as `file` (`raw`, `info` from the reader), prepared with the map flags
    /// (`stiction bem --map FILE`).
    Map {
        /// Its name in the output (`surface.file`) and in errors.
        file: &'a str,
        /// The heights as read.
        raw: HeightMap,
        /// What the reader found.
        info: MapInfo,
    },
    /// The patch under the shoe of a scenario's height-map face(s) (`stiction bem --scenario S`;
    /// `args.sets` apply after the source's own).
    Scenario(&'a ScenarioSource),
}

impl BemSurface<'_> {
    fn build(self, args: &Args) -> Result<Surface, Box<dyn std::error::Error>> {
        match self {
            BemSurface::Generated => generated_surface(args),
            BemSurface::Map { file, raw, info } => map_surface(args, file, raw, info),
            BemSurface::Scenario(source) => scenario_surface(args, source),
        }
    }
}

/// The checks of the solver's flags (before any work): the tolerance and a load or gap path.
fn check_path_args(args: &Args) -> Result<(), Box<dyn std::error::Error>> {
    if !(args.tolerance.is_finite() && args.tolerance > 0.0 && args.tolerance < 1.0) {
        return Err(format!("--tolerance {}: expected a relative tolerance in (0, 1)", args.tolerance).into());
    }
    if args.humidity.rh.is_some() {
        return Ok(());
    }
    if args.gap_sweep.is_none() && args.sweep.is_none() && args.pressure.is_none() {
        return Err("give --pressure, --sweep, --gap-sweep or --rh".into());
    }
    Ok(())
}

/// Solves on `surface` along the path of `args` (`pressures`, when given, instead of --sweep or
/// --pressure): the output, the states and the heights.
#[allow(clippy::type_complexity)]
fn solve(
    args: &Args,
    surface: Surface,
    pressures: Option<&[f64]>,
) -> Result<(Output, Vec<ContactSolution>, Vec<f64>), Box<dyn std::error::Error>> {
    let Surface { grid, heights, source, e_star_pa } = surface;
    let seed = match source {
        SurfaceSource::Generated { seed, .. } => Some(seed),
        _ => None,
    };
    let mut solver = BemSolver::new(grid.nx, grid.ny, grid.dx_m, grid.dy_m, &heights, e_star_pa)?;
    let rms_slope = solver.slope_rms();
    let opts = SolverOptions { tolerance: args.tolerance, ..Default::default() };
    let law = match (args.work_of_adhesion, args.range) {
        (Some(w), Some(h0)) => Some(Dugdale::from_work_and_range(w, h0)?),
        _ => None,
    };
    let mut states: Vec<ContactSolution> = Vec::new();
    if let Some(text) = &args.gap_sweep {
        let mut gaps = parse_path(text, Dimension::Length, "--gap-sweep")?;
        if args.gap_back {
            let back: Vec<f64> = gaps.iter().rev().skip(1).copied().collect();
            gaps.extend(back);
        }
        for g in gaps {
            let warm = states.last();
            let s = match &law {
                Some(l) => solver.solve_adhesive_mean_gap(g, l, &opts, warm)?,
                None => solver.solve_mean_gap(g, &opts, warm)?,
            };
            states.push(s);
        }
    } else {
        if law.is_some() {
            return Err("adhesion (--work-of-adhesion, --range) needs a mean-gap path (--gap-sweep): \
                        load control cannot pass the load minimum to pull-off"
                .into());
        }
        let loads = match (pressures, &args.sweep, args.pressure) {
            (Some(p), _, _) => p.to_vec(),
            (None, Some(text), _) => parse_path(text, Dimension::Pressure, "--sweep")?,
            (None, None, Some(p)) => vec![p],
            (None, None, None) => return Err("give --pressure, --sweep or --gap-sweep".into()),
        };
        for p in loads {
            let s = solver.solve_load(p, &opts, states.last())?;
            states.push(s);
        }
    }
    let summits = if args.compare_asperity { stiction_bem::asperity::summits(&heights, grid) } else { Vec::new() };
    let mut points: Vec<Point> = states
        .iter()
        .map(|s| Point {
            mean_pressure_pa: s.mean_pressure_pa,
            load_n: s.load_n(&grid),
            mean_gap_m: s.mean_gap_m,
            contact_fraction: s.contact_fraction,
            contact_area_m2: s.contact_area_m2,
            patches: s.patches,
            cohesive_fraction: s.cohesive_fraction,
            friction_n: args.shear_strength.map(|t| s.friction_n(t)),
            elastic_energy_j_per_m2: s.elastic_energy_j_per_m2,
            iterations: s.iterations,
            residual: s.residual,
            asperity_contact_fraction: None,
            area_ratio_bem_over_asperity: None,
            note: None,
        })
        .collect();
    if args.compare_asperity {
        for p in points.iter_mut().filter(|p| p.load_n > 0.0) {
            let st = stiction_bem::asperity::at_load(&summits, e_star_pa, p.load_n)?;
            let frac = st.contact_area_m2 / grid.area_m2();
            p.asperity_contact_fraction = Some(frac);
            p.area_ratio_bem_over_asperity = Some(p.contact_fraction / frac);
        }
    }
    for p in points.iter_mut() {
        let nulls =
            p.friction_n.is_none() || p.asperity_contact_fraction.is_none() || p.area_ratio_bem_over_asperity.is_none();
        p.note = nulls.then_some(
            "null without --shear-strength (friction), without --compare-asperity or at a load <= 0 (the asperity \
             model beside it)",
        );
    }
    let pull_off_n = law.map(|_| points.iter().map(|p| p.load_n).fold(0.0, f64::min));
    let out = Output {
        note: (seed.is_none() || law.is_none()).then_some(
            "seed is null for a map or a scenario's patch (not generated); dugdale and pull_off_n are null without \
             adhesion (no --work-of-adhesion and --range)",
        ),
        surface: source,
        grid,
        e_star_pa,
        rms_height_m: solver.height_rms_m(),
        rms_slope,
        seed,
        dugdale: law,
        tolerance: args.tolerance,
        points,
        pull_off_n,
    };
    Ok((out, states, heights))
}

/// What `stiction bem ... --json` prints for the surface `surface` (generated, a height map already
/// read, or a scenario held in memory; `args.map`, `args.scenario` are not read): with `--rh`, the
/// adhesion energy against relative humidity (`stiction bem --rh`); else the load path, solved at
/// `pressures` (mean pressures, Pa, in order, each from the previous state) when given, else along
/// `args`' path. Every number checked finite. For front ends other than the command line (the
/// Python module).
pub fn bem_json(
    args: &Args,
    surface: BemSurface<'_>,
    pressures: Option<&[f64]>,
) -> Result<serde_json::Value, Box<dyn std::error::Error>> {
    if args.humidity.rh.is_some() {
        if pressures.is_some() {
            return Err("pressure: with rh, one mean pressure (the compressed state each retraction starts from), \
                        not a vector"
                .into());
        }
        check_path_args(args)?;
        let out = humidity::output(args, || surface.build(args))?;
        return Ok(stiction_engine::json::finite_value(&out)?);
    }
    check_front_end_path(args, pressures)?;
    let (out, _, _) = solve(args, surface.build(args)?, pressures)?;
    Ok(stiction_engine::json::finite_value(&out)?)
}

/// The checks of [`bem_json`]'s load path before any work: a tolerance in (0, 1), and a load
/// path (`pressures`, each finite and > 0, or the flags').
fn check_front_end_path(args: &Args, pressures: Option<&[f64]>) -> Result<(), Box<dyn std::error::Error>> {
    if pressures.is_none() {
        check_path_args(args)?;
    } else if !(args.tolerance.is_finite() && args.tolerance > 0.0 && args.tolerance < 1.0) {
        return Err(format!("--tolerance {}: expected a relative tolerance in (0, 1)", args.tolerance).into());
    }
    if let Some(p) = pressures.and_then(|p| p.iter().find(|p| !(p.is_finite() && **p > 0.0))) {
        return Err(format!("pressure {p}: expected a mean pressure > 0 (compressive), Pa").into());
    }
    Ok(())
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    // clap drops `requires = "scenario"` when a flag that conflicts with --scenario (--grid, --seed,
    // --map) is given, so the rule is checked here too: an override without a scenario is an error.
    if let (Some(set), None) = (args.sets.first(), &args.scenario) {
        return Err(format!("--set {set:?} needs --scenario (it overrides a field of the scenario)").into());
    }
    check_path_args(&args)?;
    if args.humidity.rh.is_some() {
        return humidity::run(&args);
    }
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "bem", args.force)?),
        None => None,
    };
    let (out, states, heights) = solve(&args, build_surface(&args)?, None)?;
    let (grid, rms_slope, e_star_pa, law) = (out.grid, out.rms_slope, out.e_star_pa, out.dugdale);
    if let (Some(set), Some(last)) = (outputs, states.last()) {
        write_outputs(set, &out, last, &heights, &args.fig, &args.map_args)?;
    }
    if args.json {
        return print_json(&out);
    }
    print_table(
        "BEM rough contact (periodic half-space, rigid flat)",
        &[
            (
                "grid",
                if grid.dx_m == grid.dy_m {
                    format!("{} x {}, pixel {}", grid.nx, grid.ny, q(grid.dx_m, Dimension::Length))
                } else {
                    format!(
                        "{} x {}, pixel {} x {}",
                        grid.nx,
                        grid.ny,
                        q(grid.dx_m, Dimension::Length),
                        q(grid.dy_m, Dimension::Length)
                    )
                },
            ),
            (
                "surface",
                format!(
                    "{}, rms height {}, rms slope {:.4}",
                    match &out.surface {
                        SurfaceSource::Generated { hurst, seed, .. } =>
                            format!("generated self-affine H {hurst}, seed {seed}"),
                        SurfaceSource::HeightMap { file, .. } => format!("height map {file}"),
                        SurfaceSource::Scenario { file, .. } => format!("shoe patch of {file}"),
                    },
                    q(out.rms_height_m, Dimension::Length),
                    rms_slope
                ),
            ),
            ("E*", q(e_star_pa, Dimension::Pressure)),
            (
                "adhesion",
                law.map_or("none".into(), |l| {
                    format!(
                        "Dugdale, sigma0 {}, range {}",
                        q(l.stress_pa, Dimension::Pressure),
                        q(l.range_m, Dimension::Length)
                    )
                }),
            ),
        ],
    );
    let compared = out.points.iter().any(|p| p.area_ratio_bem_over_asperity.is_some());
    let mut header = vec!["p_mean", "load", "mean gap", "A/A0", "patches", "friction", "iterations"];
    if compared {
        header.push("A(BEM)/A(asperity)");
    }
    let mut t = TextTable::new(&header);
    for p in &out.points {
        let mut row = vec![
            q(p.mean_pressure_pa, Dimension::Pressure),
            q(p.load_n, Dimension::Force),
            q(p.mean_gap_m, Dimension::Length),
            format!("{:.5}", p.contact_fraction),
            p.patches.to_string(),
            p.friction_n.map_or("-".into(), |f| q(f, Dimension::Force)),
            p.iterations.to_string(),
        ];
        if compared {
            row.push(p.area_ratio_bem_over_asperity.map_or("-".into(), |r| format!("{r:.3}")));
        }
        t.row(row);
    }
    t.print("  ");
    if let Some(f) = out.pull_off_n {
        crate::outln!("  pull-off (most tensile load on the path): {}", q(f, Dimension::Force));
    }
    Ok(())
}

fn csv_bytes<T: Serialize>(rows: &[T]) -> Result<Vec<u8>, Box<dyn std::error::Error>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r)?;
    }
    Ok(w.into_inner().map_err(|e| e.to_string())?)
}

#[derive(Serialize)]
struct FieldRow {
    x_m: f64,
    y_m: f64,
    height_m: f64,
    pressure_pa: f64,
    gap_m: f64,
    contact: u8,
}

fn write_outputs(
    mut set: OutputSet,
    out: &Output,
    last: &ContactSolution,
    heights: &[f64],
    fig: &crate::figargs::FigureArgs,
    args_map: &MapArgs,
) -> CliResult {
    let g = out.grid;
    set.add_bytes("results.json", crate::output::json_text(out)?.as_bytes())?;
    let rows: Vec<FieldRow> = (0..g.len())
        .map(|i| FieldRow {
            x_m: (i % g.nx) as f64 * g.dx_m,
            y_m: (i / g.nx) as f64 * g.dy_m,
            height_m: heights[i],
            pressure_pa: last.pressure_pa[i],
            gap_m: last.gap_m[i],
            contact: u8::from(last.contact[i]),
        })
        .collect();
    set.add_bytes("fields.csv", &csv_bytes(&rows)?)?;
    drop(rows);
    set.add_bytes("curve.csv", &csv_bytes(&out.points)?)?;
    let draw = |field: &[f64], title: &str, label: &str, unit: &str| {
        fig.apply_map(heat_map(args_map, field, g, title, label, unit))
    };
    let height = draw(heights, "Height of the composite surface", "height", "m");
    // The load of the drawn state: the last point of the path.
    let state = out.points.last().map_or(String::new(), |p| {
        format!(
            " at mean pressure {} (load {})",
            q(p.mean_pressure_pa, Dimension::Pressure),
            q(p.load_n, Dimension::Force)
        )
    });
    // Elastic contact pressure peaks at several times E* at the summits: the colour bar picks
    // the SI prefix of the largest value (GPa, not 28000 MPa).
    let pressure = draw(&last.pressure_pa, &format!("Pressure{state}"), "pressure", "Pa");
    let gap = draw(&last.gap_m, &format!("Gap{state}"), "gap", "m");
    for (stem, map) in [("height", &height), ("pressure", &pressure), ("gap", &gap)] {
        set.add_map_figure(stem, map)?;
    }
    let pts = &out.points;
    // The solved loads as markers (not joined: a path may leave decades between them), on a log
    // axis where the values span two decades or more.
    let decades = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
        lo > 0.0 && hi / lo >= 100.0
    };
    let p_log = decades(&mut pts.iter().map(|p| p.mean_pressure_pa));
    if pts.len() > 1 {
        let area: Vec<(f64, f64)> = pts.iter().map(|p| (p.mean_pressure_pa * 1e-6, p.contact_fraction)).collect();
        let mut chart = Chart::new("Load-area (BEM)", "mean pressure p (MPa)", "contact fraction A_r/A_0")
            .keys("mean_pressure_mpa", "contact_fraction")
            .with(Series::markers("BEM, solved loads", area).with_color(0));
        chart.x_log = p_log;
        chart.y_log = decades(&mut pts.iter().map(|p| p.contact_fraction));
        set.add_figure("load_area", &fig.apply(chart)?)?;
        let gap: Vec<(f64, f64)> = pts.iter().map(|p| (p.mean_gap_m * 1e9, p.mean_pressure_pa * 1e-6)).collect();
        let mut chart = Chart::new("Load-mean gap (BEM)", "mean gap (nm)", "mean pressure p (MPa)")
            .keys("mean_gap_nm", "mean_pressure_mpa")
            .with(Series::markers("BEM, solved loads", gap).with_color(0));
        chart.y_log = p_log;
        set.add_figure("load_gap", &fig.apply(chart)?)?;
        let ratio: Vec<(f64, f64)> =
            pts.iter().filter_map(|p| p.area_ratio_bem_over_asperity.map(|r| (p.mean_pressure_pa * 1e-6, r))).collect();
        if ratio.len() > 1 {
            let mut chart = Chart::new(
                "Real contact area: BEM / asperity model",
                "mean pressure p (MPa)",
                "A_r(BEM) / A_r(asperity)",
            )
            .keys("mean_pressure_mpa", "area_ratio")
            .with(Series::markers("BEM / independent Hertz summits, solved loads", ratio).with_color(0));
            chart.x_log = p_log;
            set.add_figure("area_ratio", &fig.apply(chart)?)?;
        }
    }
    set.commit()
}

/// A row-major field in SI units as a heat map, every grid cell unless --map-cells asks for
/// blocks; the colour bar in `unit` with the SI prefix that suits the values.
fn heat_map(maps: &MapArgs, field: &[f64], g: Grid, title: &str, value_label: &str, unit: &str) -> ImageMap {
    let (block, cx, cy, cells) = maps.drawn_cells(field, g.nx, g.ny);
    ImageMap {
        title: if block > 1 { format!("{title}, drawn in {block} x {block} blocks") } else { title.to_string() },
        x_label: "x (µm)".into(),
        y_label: "y (µm)".into(),
        value_label: value_label.into(),
        value_unit: Some(unit.into()),
        nx: cx,
        ny: cy,
        values: cells,
        x_max: g.nx as f64 * g.dx_m * 1e6,
        y_max: g.ny as f64 * g.dy_m * 1e6,
        markers: Vec::new(),
        ..ImageMap::default()
    }
}

/// `stiction bem --rh`: adhesion energy against relative humidity.
mod humidity {
    use serde::Serialize;
    use stiction_bem::{BemSolver, Dugdale, Grid, SolverOptions};
    use stiction_contact::capillary::{Capillarity, Liquid};
    use stiction_units::Dimension;

    use super::{Args, SurfaceSource, build_surface, csv_bytes};
    use crate::output::{CliResult, OutputSet, TextTable, print_json, print_table, q};
    use stiction_engine::rh::parse_rh;

    /// `--temperature`: "25 C", "298.15 K" or a bare number in kelvin, in the domain of the water
    /// correlations: the one rule of the scenario's `environment.temperature`
    /// (`stiction_scenario::parse_temperature_k`).
    pub(super) fn parse_temperature(text: &str) -> Result<f64, String> {
        stiction_scenario::parse_temperature_k(&serde_json::Value::String(text.to_string()))
            .map_err(|e| format!("--temperature: {e}"))
    }

    /// One humidity.
    #[derive(Serialize)]
    struct Point {
        relative_humidity: f64,
        /// Kelvin radius r_K, m (null when dry: RH = 0 or a non-wetting angle).
        kelvin_radius_m: Option<f64>,
        /// Meniscus height h_m = r_K (cos th1 + cos th2), m (null when dry, also when r_K lies
        /// below --min-kelvin-radius).
        meniscus_height_m: Option<f64>,
        /// Work of separation per nominal area, J/m^2.
        adhesion_energy_j_per_m2: f64,
        /// The same in mJ/m^2 (the unit of the microcantilever literature).
        adhesion_energy_mj_per_m2: f64,
        /// Most tensile mean traction on the retraction, Pa.
        pull_off_pressure_pa: f64,
        /// Mean-gap steps of the retraction.
        steps: usize,
        /// Why the Kelvin radius or the meniscus height is null (always written: one CSV shape).
        meniscus_note: Option<&'static str>,
    }

    #[derive(Serialize)]
    pub(super) struct Output {
        surface: SurfaceSource,
        grid: Grid,
        e_star_pa: f64,
        rms_height_m: f64,
        temperature_k: f64,
        surface_tension_n_per_m: f64,
        contact_angle_rad: f64,
        /// The flat wetted limit 2 gamma cos theta, J/m^2.
        capillary_limit_j_per_m2: f64,
        /// The van der Waals Dugdale law (null without --work-of-adhesion/--range).
        van_der_waals: Option<Dugdale>,
        /// Why `van_der_waals` is null.
        #[serde(skip_serializing_if = "Option::is_none")]
        van_der_waals_note: Option<&'static str>,
        /// Mean pressure of the compressed state the retractions start from, Pa.
        start_pressure_pa: f64,
        tolerance: f64,
        /// --min-kelvin-radius, m (absent: none).
        #[serde(skip_serializing_if = "Option::is_none")]
        min_kelvin_radius_m: Option<f64>,
        points: Vec<Point>,
    }

    /// The adhesion energy against humidity of `args` on the surface `surface` makes (called
    /// after the cheap checks of the flags).
    pub(super) fn output(
        args: &Args,
        surface: impl FnOnce() -> Result<super::Surface, Box<dyn std::error::Error>>,
    ) -> Result<Output, Box<dyn std::error::Error>> {
        let h = &args.humidity;
        let rhs = parse_rh(h.rh.as_deref().unwrap_or_default())?;
        let temperature_k = parse_temperature(&h.temperature)?;
        let angle = h.contact_angle;
        if !(0.0..=std::f64::consts::PI).contains(&angle) {
            return Err(format!("--contact-angle {angle} rad: expected 0 to 180 deg").into());
        }
        let vdw = match (args.work_of_adhesion, args.range) {
            (Some(w), Some(h0)) => Some(Dugdale::from_work_and_range(w, h0)?),
            _ => None,
        };
        let liquid = Liquid::water(temperature_k);
        let caps: Vec<Option<Capillarity>> = rhs
            .iter()
            .map(|&rh| Capillarity::new(liquid, temperature_k, rh, angle, angle))
            .collect::<Result<_, _>>()
            .map_err(|e| format!("--rh: {e}"))?;
        let super::Surface { grid, heights, source, e_star_pa } = surface()?;
        let mut solver = BemSolver::new(grid.nx, grid.ny, grid.dx_m, grid.dy_m, &heights, e_star_pa)?;
        let opts = SolverOptions { tolerance: args.tolerance, ..Default::default() };
        let start_pressure_pa = args.pressure.unwrap_or(1e6);
        let start = solver.solve_load(start_pressure_pa, &opts, None)?;
        let mut points = Vec::with_capacity(rhs.len());
        for (&rh, air) in rhs.iter().zip(&caps) {
            // No meniscus below the smallest Kelvin radius (the dry regime).
            let cap = air.and_then(|c| c.above_min_kelvin_radius(h.min_kelvin_radius));
            let mut laws: Vec<Dugdale> = vdw.into_iter().collect();
            if let Some(c) = cap {
                laws.push(Dugdale::capillary(c.surface_tension_n_per_m, c.kelvin_radius_m, c.cos_angle_sum)?);
            }
            let (energy, pull_off, steps) = if laws.is_empty() {
                // Dry and without van der Waals: nothing holds the surfaces together.
                (0.0, 0.0, 0)
            } else {
                let shortest = laws.iter().fold(f64::INFINITY, |m, l| m.min(l.range_m));
                let step = h.rh_step.unwrap_or(shortest / 20.0);
                let sep = solver.work_of_separation(&laws, start.mean_gap_m, step, &opts).map_err(|e| {
                    format!("--rh {rh}: the retraction from --pressure to separation failed ({e}); check --rh-step")
                })?;
                (sep.adhesion_energy_j_per_m2, sep.pull_off_pressure_pa, sep.steps)
            };
            points.push(Point {
                relative_humidity: rh,
                kelvin_radius_m: air.map(|c| c.kelvin_radius_m),
                meniscus_height_m: cap.map(|c| c.meniscus_height_m()),
                adhesion_energy_j_per_m2: energy,
                adhesion_energy_mj_per_m2: energy * 1e3,
                pull_off_pressure_pa: pull_off,
                steps,
                meniscus_note: cap.is_none().then_some(stiction_meter::NO_MENISCUS_NOTE),
            });
        }
        let out = Output {
            surface: source,
            grid,
            e_star_pa,
            rms_height_m: solver.height_rms_m(),
            temperature_k,
            surface_tension_n_per_m: liquid.surface_tension_n_per_m,
            contact_angle_rad: angle,
            // 2 gamma cos theta, 0 where the faces do not condense (cos theta_1 + cos theta_2 at
            // or below the neutral-wetting threshold, as `Capillarity::new` decides).
            capillary_limit_j_per_m2: if 2.0 * angle.cos() > stiction_contact::capillary::NEUTRAL_WETTING_COS_SUM {
                2.0 * liquid.surface_tension_n_per_m * angle.cos()
            } else {
                0.0
            },
            van_der_waals: vdw,
            van_der_waals_note: vdw.is_none().then_some("no --work-of-adhesion and --range: no van der Waals law"),
            start_pressure_pa,
            tolerance: args.tolerance,
            min_kelvin_radius_m: h.min_kelvin_radius,
            points,
        };
        Ok(out)
    }

    pub(super) fn run(args: &Args) -> CliResult {
        // The output folder is checked after the flags and before the work, so a refusal comes at once.
        let mut outputs = None;
        let out = output(args, || {
            if let Some(dir) = &args.out {
                outputs = Some(OutputSet::begin(dir, "bem", args.force)?);
            }
            build_surface(args)
        })?;
        let (grid, e_star_pa, temperature_k, angle) =
            (out.grid, out.e_star_pa, out.temperature_k, out.contact_angle_rad);
        if let Some(mut set) = outputs {
            set.add_bytes("results.json", crate::output::json_text(&out)?.as_bytes())?;
            set.add_bytes("humidity.csv", &csv_bytes(&out.points)?)?;
            set.commit()?;
        }
        if args.json {
            return print_json(&out);
        }
        let mut rows = vec![
            ("grid", format!("{} x {}, pixel {}", grid.nx, grid.ny, q(grid.dx_m, Dimension::Length))),
            ("rms height", q(out.rms_height_m, Dimension::Length)),
            ("E*", q(e_star_pa, Dimension::Pressure)),
            ("temperature", format!("{temperature_k:.2} K")),
            ("contact angle", format!("{:.1} deg", angle.to_degrees())),
            ("2 gamma cos theta", format!("{:.1} mJ/m^2", out.capillary_limit_j_per_m2 * 1e3)),
        ];
        if let Some(m) = out.min_kelvin_radius_m {
            rows.push((
                "min Kelvin radius",
                format!("{}: below it no meniscus condenses (h_m shown as -)", q(m, Dimension::Length)),
            ));
        }
        print_table("BEM adhesion energy against relative humidity (capillary cohesive zone)", &rows);
        let mut t = TextTable::new(&["RH", "r_K", "h_m", "Gamma (mJ/m^2)", "pull-off pressure"]);
        for p in &out.points {
            t.row(vec![
                format!("{:.3}", p.relative_humidity),
                p.kelvin_radius_m.map_or("-".into(), |v| q(v, Dimension::Length)),
                p.meniscus_height_m.map_or("-".into(), |v| q(v, Dimension::Length)),
                format!("{:.4}", p.adhesion_energy_mj_per_m2),
                q(p.pull_off_pressure_pa, Dimension::Pressure),
            ]);
        }
        t.print("");
        Ok(())
    }
}
