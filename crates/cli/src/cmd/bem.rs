//! `stiction bem`: the FFT boundary-element solver on a surface: a generated self-affine one, a
//! measured height map (`--map`, read and levelled as `stiction topography` does) or a scenario's
//! height-map face(s) under the shoe (`--scenario`); at one load, over a load sweep or (with
//! adhesion) over a mean-gap path; fields, curves and figures.

use std::path::PathBuf;

use serde::Serialize;
use stiction_engine::bem::{
    BemHumidity, BemOutput, BemRequest, BemSurface, ContactSolution, Grid, Surface, SurfaceSource, check_path_args,
    humidity, solve,
};
use stiction_engine::range::{GapRange, PressureRange};
use stiction_engine::rh::parse_rh;
use stiction_plot::{Chart, ImageMap, Series};
use stiction_units::{Constraint, Dimension};

use super::map_args::MapArgs;
use crate::output::{CliResult, OutputSet, TextTable, print_json, print_table, q, quantity};
use stiction_engine::ScenarioSource;

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
    #[arg(long, default_value = stiction_engine::bem::DEFAULT_SIZE, value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
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
    #[arg(long, default_value = stiction_engine::bem::DEFAULT_RMS_HEIGHT, value_parser = quantity(Dimension::Length, Constraint::Positive), conflicts_with_all = ["map", "scenario"])]
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
    /// Work of adhesion of the Dugdale law ("0.1 J/m^2"); needs --range, and --gap-sweep (periodic), or
    /// --pressure or --sweep (the loading branch under load control) with --boundary non-periodic or
    /// --hardness.
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
    /// The Green's function: "periodic" (the grid is one cell of a periodic interface) or
    /// "non-periodic" (a finite patch, a rigid face of the grid's size, on a half-space that goes on:
    /// zero-padded, no images; load control: --pressure or --sweep, with or without adhesion).
    #[arg(long, value_enum, default_value_t = BoundaryArg::Periodic)]
    pub boundary: BoundaryArg,
    /// A rigid face that tilts until its moments about the grid's centre balance (approach and two
    /// tilts from the force and moment balance); needs --boundary non-periodic and a load path.
    #[arg(long)]
    pub tilt: bool,
    /// Cap the contact pressure at this hardness ("9 GPa"): perfectly plastic points flow at it,
    /// and the plastic area is reported; load control (--pressure, --sweep), flat face; with
    /// adhesion the net traction is capped, on either boundary (the loading branch).
    #[arg(long, value_parser = quantity(Dimension::Pressure, Constraint::Positive))]
    pub hardness: Option<f64>,
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

/// `--boundary`: the Green's function of the grid.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoundaryArg {
    /// One cell of a periodic interface.
    Periodic,
    /// A finite patch on a half-space that goes on (zero-padded).
    #[value(alias = "non_periodic")]
    NonPeriodic,
}

impl From<BoundaryArg> for stiction_engine::bem::Boundary {
    fn from(b: BoundaryArg) -> Self {
        match b {
            BoundaryArg::Periodic => stiction_engine::bem::Boundary::Periodic,
            BoundaryArg::NonPeriodic => stiction_engine::bem::Boundary::NonPeriodic,
        }
    }
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

impl Args {
    /// The engine's request of these flags: the paths and humidities parsed here, named by their
    /// flags in errors.
    pub fn request(&self) -> Result<BemRequest, String> {
        let h = &self.humidity;
        Ok(BemRequest {
            preparation: self.map_args.preparation(),
            size_m: self.size,
            grid: self.grid,
            hurst: self.hurst,
            roll_off_m: self.roll_off,
            short_m: self.short,
            rms_height_m: self.rms_height,
            seed: self.seed,
            e_star_pa: self.e_star,
            pressure_pa: self.pressure,
            sweep: self.sweep.as_deref().map(|t| PressureRange::parse(t, "--sweep")).transpose()?,
            gap_sweep: self.gap_sweep.as_deref().map(|t| GapRange::parse(t, "--gap-sweep")).transpose()?,
            gap_back: self.gap_back,
            work_of_adhesion_j_per_m2: self.work_of_adhesion,
            range_m: self.range,
            humidity: BemHumidity {
                rh: h.rh.as_deref().map(parse_rh).transpose()?,
                temperature_k: humidity::parse_temperature(&h.temperature, "--temperature")?,
                contact_angle_rad: h.contact_angle,
                rh_step_m: h.rh_step,
                min_kelvin_radius_m: h.min_kelvin_radius,
            },
            shear_strength_pa: self.shear_strength,
            tolerance: self.tolerance,
            compare_asperity: self.compare_asperity,
            boundary: self.boundary.into(),
            tilt: self.tilt,
            hardness_pa: self.hardness,
        })
    }
}

/// The surface of the command line: generated, a map file, or a scenario's patch.
fn build_surface(args: &Args, req: &BemRequest) -> Result<Surface, Box<dyn std::error::Error>> {
    if let Some(file) = &args.map {
        let metadata = args.map_args.metadata();
        return BemSurface::File { path: file, format: args.map_args.format, metadata: &metadata }.build(req);
    }
    if let Some(file) = &args.scenario {
        return BemSurface::Scenario(&ScenarioSource::file(file, &args.sets)?).build(req);
    }
    BemSurface::Generated.build(req)
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    // clap drops `requires = "scenario"` when a flag that conflicts with --scenario (--grid, --seed,
    // --map) is given, so the rule is checked here too: an override without a scenario is an error.
    if let (Some(set), None) = (args.sets.first(), &args.scenario) {
        return Err(format!("--set {set:?} needs --scenario (it overrides a field of the scenario)").into());
    }
    let req = args.request()?;
    check_path_args(&req)?;
    if args.humidity.rh.is_some() {
        return humidity_run(&args, &req);
    }
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "bem", args.force)?),
        None => None,
    };
    let (out, states, heights) = solve(&req, build_surface(&args, &req)?, None)?;
    let (grid, rms_slope, e_star_pa, law) = (out.grid, out.rms_slope, out.e_star_pa, out.dugdale);
    if let (Some(set), Some(last)) = (outputs, states.last()) {
        write_outputs(set, &out, last, &heights, &args.fig, &args.map_args)?;
    }
    if args.json {
        return print_json(&out);
    }
    let title = match (out.boundary, out.tilt) {
        (stiction_engine::bem::Boundary::Periodic, _) => "BEM rough contact (periodic half-space, rigid flat)",
        (_, false) => "BEM rough contact (finite patch on a half-space, rigid flat)",
        (_, true) => "BEM rough contact (finite patch on a half-space, tilting rigid face)",
    };
    let mut rows = vec![
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
    ];
    if let Some(h) = out.hardness_pa {
        rows.push(("hardness cap", q(h, Dimension::Pressure)));
    }
    print_table(title, &rows);
    let compared = out.points.iter().any(|p| p.area_ratio_bem_over_asperity.is_some());
    let mut header = vec!["p_mean", "load", "mean gap", "A/A0", "patches", "friction", "iterations"];
    if compared {
        header.push("A(BEM)/A(asperity)");
    }
    if out.tilt {
        header.extend(["tilt x (rad)", "tilt y (rad)"]);
    }
    if out.hardness_pa.is_some() {
        header.push("A_p/A0");
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
        if out.tilt {
            row.push(p.tilt_x_rad.map_or("-".into(), |v| format!("{v:.3e}")));
            row.push(p.tilt_y_rad.map_or("-".into(), |v| format!("{v:.3e}")));
        }
        if out.hardness_pa.is_some() {
            row.push(p.plastic_fraction.map_or("-".into(), |v| format!("{v:.5}")));
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
    out: &BemOutput,
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

/// `stiction bem --rh`: adhesion energy against relative humidity, printed or written.
fn humidity_run(args: &Args, req: &BemRequest) -> CliResult {
    // The output folder is checked after the flags and before the work, so a refusal comes at once.
    let mut outputs = None;
    let out = humidity::output(req, || {
        if let Some(dir) = &args.out {
            outputs = Some(OutputSet::begin(dir, "bem", args.force)?);
        }
        build_surface(args, req)
    })?;
    let (grid, e_star_pa, temperature_k, angle) = (out.grid, out.e_star_pa, out.temperature_k, out.contact_angle_rad);
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
