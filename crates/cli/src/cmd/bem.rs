//! `stiction bem`: the FFT boundary-element solver on a generated self-affine surface, at one
//! load, over a load sweep or (with adhesion) over a mean-gap path; fields, curves and figures.

use std::path::{Path, PathBuf};

use plotters::prelude::*;
use plotters::style::colors::colormaps::{ColorMap, ViridisRGB};
use serde::Serialize;
use stiction_bem::{BemSolver, ContactSolution, Dugdale, Grid, SolverOptions, synth};
use stiction_plot::{Chart, Series};
use stiction_units::io::write_atomic;
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

use crate::output::{CliResult, ensure_dir, print_json, print_table, q, quantity};

/// Largest grid side of the command (the solver's own limit is 4096 x 4096 points).
const MAX_SIDE: usize = 4096;

/// Boundary-element contact of a rigid flat on a generated Gaussian self-affine rough surface.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Side of the square periodic cell ("100 um").
    #[arg(long, default_value = "100 um", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub size: f64,
    /// Grid points per side (2..=4096; powers of two are fastest).
    #[arg(long, default_value_t = 256)]
    pub grid: usize,
    /// Hurst exponent of the self-affine spectrum (0 < H <= 1).
    #[arg(long, default_value_t = 0.8)]
    pub hurst: f64,
    /// Roll-off wavelength ("25 um"; default: a quarter of the cell).
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub roll_off: Option<f64>,
    /// Short-wavelength cut-off ("1.6 um"; default: 4 pixels).
    #[arg(long, value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub short: Option<f64>,
    /// Rms height of the composite surface ("0.5 um").
    #[arg(long, default_value = "0.5 um", value_parser = quantity(Dimension::Length, Constraint::Positive))]
    pub rms_height: f64,
    /// Seed of the surface (ChaCha8).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Composite modulus E* = 1/sum((1 - nu^2)/E) ("85 GPa").
    #[arg(long, default_value = "85 GPa", value_parser = quantity(Dimension::Pressure, Constraint::Positive))]
    pub e_star: f64,
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
    /// Folder for the fields (CSV, PNG heat maps of the last state) and the curves (CSV, PNG).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
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
}

#[derive(Serialize)]
struct Output {
    grid: Grid,
    e_star_pa: f64,
    rms_height_m: f64,
    rms_slope: f64,
    seed: u64,
    dugdale: Option<Dugdale>,
    tolerance: f64,
    points: Vec<Point>,
    /// Most tensile load on the path, N (the pull-off under load control), when adhesive.
    pull_off_n: Option<f64>,
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

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    if !(2..=MAX_SIDE).contains(&args.grid) {
        return Err(format!("--grid {}: expected 2..={MAX_SIDE} points per side", args.grid).into());
    }
    if !(args.tolerance.is_finite() && args.tolerance > 0.0 && args.tolerance < 1.0) {
        return Err(format!("--tolerance {}: expected a relative tolerance in (0, 1)", args.tolerance).into());
    }
    let n = args.grid;
    let dx = args.size / n as f64;
    let grid = Grid::new(n, n, dx, dx)?;
    let roll_off = args.roll_off.unwrap_or(args.size / 4.0);
    let short = args.short.unwrap_or(4.0 * dx);
    let heights = synth::self_affine(grid, args.hurst, roll_off, short, args.rms_height, args.seed)?;
    let mut solver = BemSolver::new(n, n, dx, dx, &heights, args.e_star)?;
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
        let loads = match (&args.sweep, args.pressure) {
            (Some(text), _) => parse_path(text, Dimension::Pressure, "--sweep")?,
            (None, Some(p)) => vec![p],
            (None, None) => return Err("give --pressure, --sweep or --gap-sweep".into()),
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
        })
        .collect();
    if args.compare_asperity {
        for p in points.iter_mut().filter(|p| p.load_n > 0.0) {
            let st = stiction_bem::asperity::at_load(&summits, args.e_star, p.load_n)?;
            let frac = st.contact_area_m2 / grid.area_m2();
            p.asperity_contact_fraction = Some(frac);
            p.area_ratio_bem_over_asperity = Some(p.contact_fraction / frac);
        }
    }
    let pull_off_n = law.map(|_| points.iter().map(|p| p.load_n).fold(0.0, f64::min));
    let out = Output {
        grid,
        e_star_pa: args.e_star,
        rms_height_m: solver.height_rms_m(),
        rms_slope,
        seed: args.seed,
        dugdale: law,
        tolerance: args.tolerance,
        points,
        pull_off_n,
    };
    if let (Some(dir), Some(last)) = (&args.out, states.last()) {
        write_outputs(dir, &out, last, &heights)?;
    }
    if args.json {
        return print_json(&out);
    }
    print_table(
        "BEM rough contact (periodic half-space, rigid flat)",
        &[
            ("grid", format!("{n} x {n}, pixel {}", q(dx, Dimension::Length))),
            (
                "surface",
                format!(
                    "H {}, rms height {}, rms slope {:.4}",
                    args.hurst,
                    q(out.rms_height_m, Dimension::Length),
                    rms_slope
                ),
            ),
            ("E*", q(args.e_star, Dimension::Pressure)),
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
    crate::outln!(
        "  {:>12} {:>12} {:>12} {:>10} {:>8} {:>12} {:>6}",
        "p_mean",
        "load",
        "mean gap",
        "A/A0",
        "patches",
        "friction",
        "iter"
    );
    for p in &out.points {
        crate::outln!(
            "  {:>12} {:>12} {:>12} {:>10.5} {:>8} {:>12} {:>6} {:>10}",
            q(p.mean_pressure_pa, Dimension::Pressure),
            q(p.load_n, Dimension::Force),
            q(p.mean_gap_m, Dimension::Length),
            p.contact_fraction,
            p.patches,
            p.friction_n.map_or("-".into(), |f| q(f, Dimension::Force)),
            p.iterations,
            p.area_ratio_bem_over_asperity.map_or("-".into(), |r| format!("{r:.3}"))
        );
    }
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

fn write_outputs(dir: &Path, out: &Output, last: &ContactSolution, heights: &[f64]) -> CliResult {
    ensure_dir(dir)?;
    let g = out.grid;
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
    write_atomic(&dir.join("fields.csv"), &csv_bytes(&rows)?)?;
    write_atomic(&dir.join("curve.csv"), &csv_bytes(&out.points)?)?;
    let side_um = g.nx as f64 * g.dx_m * 1e6;
    heat_map(&dir.join("pressure.png"), &last.pressure_pa, g, "Pressure (MPa)", 1e-6, side_um)?;
    let gap_nm: Vec<f64> = last.gap_m.clone();
    heat_map(&dir.join("gap.png"), &gap_nm, g, "Gap (nm)", 1e9, side_um)?;
    let pts = &out.points;
    if pts.len() > 1 {
        let area: Vec<(f64, f64)> = pts.iter().map(|p| (p.mean_pressure_pa * 1e-6, p.contact_fraction)).collect();
        Chart::new("Load - area (BEM)", "Mean pressure (MPa)", "Contact fraction A_r/A_0")
            .with(Series::line("BEM", area.clone()))
            .with(Series::markers("solved", area))
            .write_png(&dir.join("load_area.png"))?;
        let gap: Vec<(f64, f64)> = pts.iter().map(|p| (p.mean_gap_m * 1e9, p.mean_pressure_pa * 1e-6)).collect();
        Chart::new("Load - mean gap (BEM)", "Mean gap (nm)", "Mean pressure (MPa)")
            .with(Series::line("BEM", gap.clone()))
            .with(Series::markers("solved", gap))
            .write_png(&dir.join("load_gap.png"))?;
        let ratio: Vec<(f64, f64)> =
            pts.iter().filter_map(|p| p.area_ratio_bem_over_asperity.map(|r| (p.mean_pressure_pa * 1e-6, r))).collect();
        if ratio.len() > 1 {
            Chart::new("Real contact area: BEM / asperity model", "Mean pressure (MPa)", "A_r(BEM) / A_r(asperity)")
                .with(Series::line("BEM / independent Hertz summits", ratio.clone()))
                .with(Series::markers("solved", ratio))
                .write_png(&dir.join("area_ratio.png"))?;
        }
    }
    Ok(())
}

/// A heat map of a row-major field (values times `scale`), with a colour bar; at most 512 x 512
/// cells are drawn (larger grids are sampled every k-th point).
fn heat_map(path: &Path, field: &[f64], g: Grid, label: &str, scale: f64, side_um: f64) -> CliResult {
    let step = g.nx.max(g.ny).div_ceil(512).max(1);
    let (lo, hi) =
        field.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, &v| (a.0.min(v * scale), a.1.max(v * scale)));
    let span = if hi > lo { hi - lo } else { 1.0 };
    let root = BitMapBackend::new(path, (1000, 860)).into_drawing_area();
    root.fill(&WHITE)?;
    let (main, bar) = root.split_horizontally(860);
    let mut chart = ChartBuilder::on(&main)
        .caption(label, ("sans-serif", 28))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..side_um, 0.0..side_um * g.ny as f64 * g.dy_m / (g.nx as f64 * g.dx_m))?;
    chart.configure_mesh().disable_mesh().x_desc("x (um)").y_desc("y (um)").label_style(("sans-serif", 18)).draw()?;
    let (px, py) = (g.dx_m * 1e6 * step as f64, g.dy_m * 1e6 * step as f64);
    chart.draw_series((0..g.ny).step_by(step).flat_map(|j| {
        (0..g.nx).step_by(step).map(move |i| {
            let v = (field[j * g.nx + i] * scale - lo) / span;
            let c: RGBColor = ViridisRGB.get_color(v.clamp(0.0, 1.0));
            let (x, y) = (i as f64 * g.dx_m * 1e6, j as f64 * g.dy_m * 1e6);
            Rectangle::new([(x, y), (x + px, y + py)], c.filled())
        })
    }))?;
    let mut cb = ChartBuilder::on(&bar)
        .margin_top(60)
        .margin_bottom(66)
        .margin_right(10)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..1.0, lo..lo + span)?;
    cb.configure_mesh().disable_mesh().disable_x_axis().label_style(("sans-serif", 16)).draw()?;
    cb.draw_series((0..200).map(|k| {
        let (a, b) = (lo + span * k as f64 / 200.0, lo + span * (k + 1) as f64 / 200.0);
        Rectangle::new([(0.0, a), (1.0, b)], ViridisRGB.get_color(k as f64 / 199.0).filled())
    }))?;
    root.present()?;
    Ok(())
}
