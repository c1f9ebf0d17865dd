//! `bem`: the FFT boundary-element solver on a surface: a generated self-affine one, a measured
//! height map (read and levelled as `topography` does) or a scenario's height-map face(s) under
//! the shoe; at one load, over a load sweep or (with adhesion) over a mean-gap path; and the
//! adhesion energy against relative humidity.

use std::path::Path;

use serde::Serialize;
/// The Green's function of a request (re-exported for the front ends).
pub use stiction_bem::Boundary;
use stiction_bem::{BemSolver, Dugdale, SolverOptions, synth};
use stiction_topography::{HeightMap, MapFormat, MapInfo, MapMetadata, Patch, Preparation, PreparationReport, prepare};

use crate::Error;
use crate::range::{GapRange, PressureRange};
use crate::scenario_source::ScenarioSource;

// The solver's types that a front end names or prints: a solved state and its grid.
pub use stiction_bem::{ContactSolution, Grid};

/// The default side of a generated surface's cell, as the command line writes it (parsed with
/// `stiction_units`, so that every front end gets the same f64).
pub const DEFAULT_SIZE: &str = "100 um";
/// The default rms height of a generated surface, as the command line writes it.
pub const DEFAULT_RMS_HEIGHT: &str = "0.5 um";

/// Largest grid side of a generated surface (the solver's own limit is 4096 x 4096 points).
pub const MAX_SIDE: usize = 4096;

/// Boundary-element contact of a rigid flat on a rough surface. The paths (`sweep`, `gap_sweep`)
/// are typed ranges and the humidities a list of fractions, parsed by the front end from its own
/// inputs (`crate::range`, `crate::rh::parse_rh_as`), naming its flag or argument.
#[derive(Clone, Debug)]
pub struct BemRequest {
    /// The preparation of a height map (levelling and cut-offs).
    pub preparation: Preparation,
    /// Generated surface: side of the square periodic cell, m.
    pub size_m: f64,
    /// Generated surface: grid points per side (2 to [`MAX_SIDE`]).
    pub grid: usize,
    /// Generated surface: Hurst exponent of the self-affine spectrum (0 < H <= 1).
    pub hurst: f64,
    /// Generated surface: roll-off wavelength, m (default: a quarter of the cell).
    pub roll_off_m: Option<f64>,
    /// Generated surface: short-wavelength cut-off, m (default: 4 pixels).
    pub short_m: Option<f64>,
    /// Generated surface: rms height of the composite surface, m.
    pub rms_height_m: f64,
    /// Generated surface: seed (ChaCha8).
    pub seed: u64,
    /// Composite modulus E*, Pa (default 85 GPa, or 3/(4D) of a scenario's material).
    pub e_star_pa: Option<f64>,
    /// One mean (nominal) pressure, compressive, Pa.
    pub pressure_pa: Option<f64>,
    /// A sweep of mean pressures (each from the previous state).
    pub sweep: Option<PressureRange>,
    /// A path of mean gaps (each from the previous state).
    pub gap_sweep: Option<GapRange>,
    /// With `gap_sweep`: back to FROM after TO.
    pub gap_back: bool,
    /// Work of adhesion of the Dugdale law, J/m^2 (with `range_m`).
    pub work_of_adhesion_j_per_m2: Option<f64>,
    /// Range h0 of the Dugdale law, m.
    pub range_m: Option<f64>,
    /// Adhesion energy against relative humidity.
    pub humidity: BemHumidity,
    /// Interfacial shear strength s for the friction s A_r, Pa.
    pub shear_strength_pa: Option<f64>,
    /// Relative tolerance of the constrained conjugate gradient, in (0, 1).
    pub tolerance: f64,
    /// Also solve the summit (asperity) model on the same grid at the same loads.
    pub compare_asperity: bool,
    /// The Green's function: the grid is one periodic cell (the command's default) or a finite
    /// patch on a half-space that goes on (zero-padded; load control only).
    pub boundary: Boundary,
    /// A rigid face that tilts until its moments about the grid's centre balance (non-periodic,
    /// load control; with or without adhesion).
    pub tilt: bool,
    /// The hardness the contact pressure is capped at (perfectly plastic points), Pa; load
    /// control without adhesion.
    pub hardness_pa: Option<f64>,
}

/// The humidity settings of `bem`.
#[derive(Clone, Debug)]
pub struct BemHumidity {
    /// The relative humidities, fractions in [0, 1), 1 to `limits::MAX_RH` of them (None: no
    /// humidity run).
    pub rh: Option<Vec<f64>>,
    /// Temperature, K, in the domain of `environment.temperature` (the water correlations);
    /// a front end parses its text with [`humidity::parse_temperature`].
    pub temperature_k: f64,
    /// Contact angle of water on both faces, rad.
    pub contact_angle_rad: f64,
    /// Mean-gap step of the retraction, m (default a twentieth of the shortest range).
    pub rh_step_m: Option<f64>,
    /// Smallest Kelvin radius at which water condenses, m.
    pub min_kelvin_radius_m: Option<f64>,
}

/// One point of a load or gap path.
#[allow(missing_docs)]
#[derive(Serialize, Clone, Debug)]
pub struct Point {
    pub mean_pressure_pa: f64,
    pub load_n: f64,
    pub mean_gap_m: f64,
    pub contact_fraction: f64,
    pub contact_area_m2: f64,
    pub patches: usize,
    pub cohesive_fraction: f64,
    pub friction_n: Option<f64>,
    pub elastic_energy_j_per_m2: f64,
    pub iterations: usize,
    pub residual: f64,
    pub asperity_contact_fraction: Option<f64>,
    pub area_ratio_bem_over_asperity: Option<f64>,
    /// With --tilt: the face's slope along x, dw/dx, rad (absent for a flat face).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tilt_x_rad: Option<f64>,
    /// With --tilt: the face's slope along y, dw/dy, rad.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tilt_y_rad: Option<f64>,
    /// With --tilt: solves spent on the force and moment balance (the Jacobian's included).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pose_solves: Option<usize>,
    /// With --hardness: the fraction of the grid at the hardness, A_p/A0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_fraction: Option<f64>,
    /// With --hardness: the plastic area A_p, m^2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_area_m2: Option<f64>,
    /// With --hardness: the largest plastic depth (overlap at a point at the hardness), m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_plastic_depth_m: Option<f64>,
    /// Why a value of the point is null: no --shear-strength (no friction), no
    /// --compare-asperity (no asperity model beside it), or no asperity contact to divide by.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

/// Where the heights came from.
#[derive(Serialize)]
#[serde(tag = "source", rename_all = "snake_case")]
pub enum SurfaceSource {
    /// The built-in generator.
    #[allow(missing_docs)]
    Generated { hurst: f64, roll_off_wavelength_m: f64, short_wavelength_m: f64, seed: u64 },
    /// A height-map file, whole.
    #[allow(missing_docs)]
    HeightMap { file: String, read: MapInfo, preparation: PreparationReport },
    /// A scenario's face(s) under the shoe.
    Scenario {
        /// The scenario's name.
        file: String,
        /// The pixel window of each face's map (wall first, then shoe) that makes the patch.
        faces: Vec<Patch>,
    },
}

/// The surface to solve on.
#[allow(missing_docs)]
pub struct Surface {
    pub grid: Grid,
    pub heights: Vec<f64>,
    pub source: SurfaceSource,
    pub e_star_pa: f64,
}

/// What `bem --json` prints for a load or gap path.
#[allow(missing_docs)]
#[derive(Serialize)]
pub struct BemOutput {
    pub surface: SurfaceSource,
    pub grid: Grid,
    pub e_star_pa: f64,
    pub rms_height_m: f64,
    pub rms_slope: f64,
    /// The generator's seed (null for a map or a scenario).
    pub seed: Option<u64>,
    pub dugdale: Option<Dugdale>,
    /// The Green's function (absent: the periodic cell).
    #[serde(skip_serializing_if = "is_periodic")]
    pub boundary: Boundary,
    /// Whether the face tilts (absent: flat).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub tilt: bool,
    /// The hardness the pressure is capped at, Pa (absent: elastic).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hardness_pa: Option<f64>,
    pub tolerance: f64,
    pub points: Vec<Point>,
    /// Most tensile load on the path, N (the pull-off under load control), when adhesive.
    pub pull_off_n: Option<f64>,
    /// Why the seed, the Dugdale law or the pull-off is null.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

fn is_periodic(b: &Boundary) -> bool {
    *b == Boundary::Periodic
}

/// The surface of a height map read as `file` (`raw`, `info` from the reader), prepared with the
/// `--level`/`--cutoff` flags: the whole map is the periodic cell.
pub fn map_surface(args: &BemRequest, file: &str, raw: HeightMap, info: MapInfo) -> Result<Surface, Error> {
    let (map, report) = prepare(&raw, &args.preparation)?;
    drop(raw);
    let grid = Grid::new(map.nx(), map.ny(), map.dx_m(), map.dy_m())
        .map_err(|e| format!("{file}: {e} (the BEM grid limit)"))?;
    let heights = map.into_heights_m();
    stiction_bem::spec::check_complete(&heights).map_err(|e| format!("{file}: {e}"))?;
    Ok(Surface {
        grid,
        heights,
        source: SurfaceSource::HeightMap { file: file.to_string(), read: info, preparation: report },
        e_star_pa: args.e_star_pa.unwrap_or(85e9),
    })
}

/// The composite patch of the height-map face(s) under the shoe of the scenario `source` (with
/// `args.sets` after its own overrides); E* from `--e-star`, else 3/(4D) of its material.
pub fn scenario_surface(args: &BemRequest, source: &ScenarioSource) -> Result<Surface, Error> {
    let scenario = source.parse(&[])?;
    let file = source.name();
    let spec = scenario.require_surface().map_err(|e| format!("{file}: {e}"))?;
    let (patch, faces) =
        stiction_surface::height_map_patch(spec, &source.base).map_err(|e| format!("{file}: surface: {e}"))?;
    let grid = Grid::new(patch.nx(), patch.ny(), patch.dx_m(), patch.dy_m())
        .map_err(|e| format!("{file}: {e} (the BEM grid limit)"))?;
    let heights = patch.into_heights_m();
    stiction_bem::spec::check_complete(&heights).map_err(|e| format!("{file}: {e}"))?;
    let e_star_pa = match args.e_star_pa {
        Some(e) => e,
        None => {
            let m = scenario.require_material().map_err(|e| format!("{file}: {e}"))?;
            0.75 / m.compliance_per_pa()
        }
    };
    Ok(Surface { grid, heights, source: SurfaceSource::Scenario { file, faces }, e_star_pa })
}

/// The generated surface of `--size`, `--grid`, `--hurst`, `--roll-off`, `--short`,
/// `--rms-height` and `--seed`: a Gaussian self-affine surface ([`synth::self_affine`]).
pub fn generated_surface(args: &BemRequest) -> Result<Surface, Error> {
    if !(2..=MAX_SIDE).contains(&args.grid) {
        return Err(format!("--grid {}: expected 2..={MAX_SIDE} points per side", args.grid).into());
    }
    // The generated wall's rms height and Hurst exponent in the scenario's domains (a 1e30 m rms
    // height printed a mean gap of 3e18 Tm); their usual-range notes are the scenario's, not
    // repeated here.
    let flag = |f: &str| if f == "rms_height_m" { "--rms-height".to_string() } else { "--hurst".to_string() };
    let mut unusual = Vec::new();
    crate::check::domain(
        &mut unusual,
        &flag,
        "rms_height_m",
        "surface.height_map.generated.rms_height",
        args.rms_height_m,
    )?;
    crate::check::domain(&mut unusual, &flag, "hurst", "surface.height_map.generated.hurst", args.hurst)?;
    let n = args.grid;
    let dx = args.size_m / n as f64;
    let grid = Grid::new(n, n, dx, dx)?;
    let roll_off = args.roll_off_m.unwrap_or(args.size_m / 4.0);
    let short = args.short_m.unwrap_or(4.0 * dx);
    let heights = synth::self_affine(grid, args.hurst, roll_off, short, args.rms_height_m, args.seed)?;
    Ok(Surface {
        grid,
        heights,
        source: SurfaceSource::Generated {
            hurst: args.hurst,
            roll_off_wavelength_m: roll_off,
            short_wavelength_m: short,
            seed: args.seed,
        },
        e_star_pa: args.e_star_pa.unwrap_or(85e9),
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
    /// A height-map file, read in `format` (None: from its extension) with `metadata` for what
    /// the file does not say (`stiction bem --map FILE`).
    File {
        /// The file.
        path: &'a Path,
        /// Its format.
        format: Option<MapFormat>,
        /// Pixel sizes and height unit the file does not give.
        metadata: &'a MapMetadata,
    },
}

impl BemSurface<'_> {
    /// The surface of this source for the request.
    pub fn build(self, args: &BemRequest) -> Result<Surface, Error> {
        match self {
            BemSurface::Generated => generated_surface(args),
            BemSurface::Map { file, raw, info } => map_surface(args, file, raw, info),
            BemSurface::Scenario(source) => scenario_surface(args, source),
            BemSurface::File { path, format, metadata } => {
                let (raw, info) = stiction_topography::read_file(path, format, metadata)?;
                map_surface(args, &path.display().to_string(), raw, info)
            }
        }
    }
}

/// The checks of the solver's flags (before any work): the tolerance and a load or gap path.
pub fn check_path_args(args: &BemRequest) -> Result<(), Error> {
    if !(args.tolerance.is_finite() && args.tolerance > 0.0 && args.tolerance < 1.0) {
        return Err(format!("--tolerance {}: expected a relative tolerance in (0, 1)", args.tolerance).into());
    }
    check_shoe_args(args)?;
    if let Some(rh) = &args.humidity.rh {
        crate::rh::check_rh_values(rh)?;
        return Ok(());
    }
    if let Some(r) = &args.sweep {
        r.check("sweep")?;
    }
    if let Some(r) = &args.gap_sweep {
        r.check("gap_sweep")?;
    }
    if args.gap_sweep.is_none() && args.sweep.is_none() && args.pressure_pa.is_none() {
        return Err("give --pressure, --sweep, --gap-sweep or --rh".into());
    }
    Ok(())
}

/// The checks of --boundary, --tilt and --hardness against each other and the path (before any
/// work): the finite patch and the tilting face are solved under load control, the hardness cap
/// under load control without adhesion on a flat face; the hardness in its domain.
pub fn check_shoe_args(args: &BemRequest) -> Result<(), Error> {
    let non_periodic = args.boundary == Boundary::NonPeriodic;
    if args.tilt && !non_periodic {
        return Err("--tilt needs --boundary non-periodic: a periodic cell has no edge to tilt about".into());
    }
    if args.humidity.rh.is_some() {
        for (given, flag) in [
            (non_periodic, "--boundary non-periodic"),
            (args.tilt, "--tilt"),
            (args.hardness_pa.is_some(), "--hardness"),
        ] {
            if given {
                return Err(format!(
                    "--rh cannot be used with {flag}: the retraction to separation is a mean-gap path on the periodic \
                     cell"
                )
                .into());
            }
        }
    }
    if non_periodic && args.gap_sweep.is_some() {
        return Err("--gap-sweep needs --boundary periodic: mean-gap control needs the periodic Green's function; on \
                    the finite patch give --pressure or --sweep"
            .into());
    }
    if let Some(h) = args.hardness_pa {
        let mut unusual = Vec::new();
        let flag = |_: &str| "--hardness".to_string();
        crate::check::domain(&mut unusual, &flag, "hardness_pa", "material.hardness", h)?;
        if args.gap_sweep.is_some() {
            return Err(
                "--hardness caps the pressure under load control: give --pressure or --sweep, not --gap-sweep".into()
            );
        }
        if let Some(p) = args.pressure_pa.filter(|&p| p >= h) {
            return Err(format!(
                "--pressure {p:e} Pa: with --hardness {h:e} Pa the mean pressure must lie below the hardness (at \
                 it the whole face flows)"
            )
            .into());
        }
    }
    Ok(())
}

/// Solves on `surface` along the path of `args` (`pressures`, when given, instead of --sweep or
/// --pressure): the output, the states and the heights.
#[allow(clippy::type_complexity)]
pub fn solve(
    args: &BemRequest,
    surface: Surface,
    pressures: Option<&[f64]>,
) -> Result<(BemOutput, Vec<ContactSolution>, Vec<f64>), Error> {
    let Surface { grid, heights, source, e_star_pa } = surface;
    let seed = match source {
        SurfaceSource::Generated { seed, .. } => Some(seed),
        _ => None,
    };
    check_shoe_args(args)?;
    let mut solver =
        BemSolver::with_boundary(grid.nx, grid.ny, grid.dx_m, grid.dy_m, &heights, e_star_pa, args.boundary)?;
    let rms_slope = solver.slope_rms();
    let opts = SolverOptions { tolerance: args.tolerance, ..Default::default() };
    let law = match (args.work_of_adhesion_j_per_m2, args.range_m) {
        (Some(w), Some(h0)) => Some(Dugdale::from_work_and_range(w, h0)?),
        _ => None,
    };
    let mut states: Vec<ContactSolution> = Vec::new();
    // Per state: the tilts and pose solves of a tilting face, the plastic state of a capped one.
    let mut poses: Vec<Option<(f64, f64, usize)>> = Vec::new();
    let mut plastic: Vec<Option<(f64, f64, f64)>> = Vec::new();
    if let Some(range) = &args.gap_sweep {
        let mut gaps = range.values_m();
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
        if law.is_some() && args.boundary == Boundary::Periodic && args.hardness_pa.is_none() {
            return Err("adhesion (--work-of-adhesion, --range) needs a mean-gap path (--gap-sweep): \
                        load control cannot pass the load minimum to pull-off"
                .into());
        }
        let loads = match (pressures, &args.sweep, args.pressure_pa) {
            (Some(p), _, _) => p.to_vec(),
            (None, Some(range), _) => range.values_pa(),
            (None, None, Some(p)) => vec![p],
            (None, None, None) => return Err("give --pressure, --sweep or --gap-sweep".into()),
        };
        if let Some(h) = args.hardness_pa
            && let Some(p) = loads.iter().find(|&&p| p >= h)
        {
            return Err(format!(
                "--sweep: the mean pressure {p:e} Pa is not below --hardness {h:e} Pa (at the hardness the whole face \
                 flows)"
            )
            .into());
        }
        let mut last_tilt: Option<stiction_bem::TiltedShoe> = None;
        for p in loads {
            // Each state continues the path from the one before while the load rises (the
            // loading branch under adhesion), and starts afresh below it.
            let warm = states.last().filter(|s| law.is_none() || s.mean_pressure_pa <= p);
            let (s, pose, pl) = if args.tilt {
                // With --hardness every pose is the capped solve.
                let o = SolverOptions { hardness_pa: args.hardness_pa, ..opts };
                let w = last_tilt.as_ref().filter(|t| t.solution.mean_pressure_pa <= p);
                let t = solver.tilting_at_load(p, law.as_ref(), &o, w)?;
                let pose = (t.tilt_x_rad, t.tilt_y_rad, t.solves);
                let s = t.solution.clone();
                let pl = t.plastic;
                last_tilt = Some(t);
                (s, Some(pose), pl)
            } else if let Some(h) = args.hardness_pa {
                // Without adhesion each load cold: a warm start from the previous plastic state
                // can stall the plastic iteration (seen on a sweep of 1-40 MPa at H = 50 MPa,
                // residual 0.08 after 10,000 iterations, where every cold solve converges in
                // 23-48). With adhesion the net traction is capped and the cohesive zone grows on
                // the loading branch, continued from the lower load's state.
                let capped = SolverOptions { hardness_pa: Some(h), ..opts };
                let w = states.last().filter(|s| law.is_some() && s.mean_pressure_pa <= p);
                let st = solver.plastic_at_load(p, law.as_ref(), &capped, w)?;
                let pl = (st.plastic_fraction, st.plastic_area_m2, st.max_plastic_depth_m);
                (st.solution, None, Some(pl))
            } else if let Some(l) = &law {
                (solver.adhesive_at_load(p, l, &opts, warm)?, None, None)
            } else {
                (solver.solve_load(p, &opts, states.last())?, None, None)
            };
            states.push(s);
            poses.push(pose);
            plastic.push(pl);
        }
    }
    poses.resize(states.len(), None);
    plastic.resize(states.len(), None);
    let summits = if args.compare_asperity { stiction_bem::asperity::summits(&heights, grid) } else { Vec::new() };
    let mut points: Vec<Point> = states
        .iter()
        .zip(poses.iter().zip(&plastic))
        .map(|(s, (pose, pl))| Point {
            mean_pressure_pa: s.mean_pressure_pa,
            load_n: s.load_n(&grid),
            mean_gap_m: s.mean_gap_m,
            contact_fraction: s.contact_fraction,
            contact_area_m2: s.contact_area_m2,
            patches: s.patches,
            cohesive_fraction: s.cohesive_fraction,
            friction_n: args.shear_strength_pa.map(|t| s.friction_n(t)),
            elastic_energy_j_per_m2: s.elastic_energy_j_per_m2,
            iterations: s.iterations,
            residual: s.residual,
            asperity_contact_fraction: None,
            area_ratio_bem_over_asperity: None,
            tilt_x_rad: pose.map(|p| p.0),
            tilt_y_rad: pose.map(|p| p.1),
            pose_solves: pose.map(|p| p.2),
            plastic_fraction: pl.map(|p| p.0),
            plastic_area_m2: pl.map(|p| p.1),
            max_plastic_depth_m: pl.map(|p| p.2),
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
    // The pull-off is the most tensile load of a mean-gap path; a load path (the finite patch or
    // the hardness cap under load control) stays compressive and has none.
    let load_path = args.gap_sweep.is_none();
    let pull_off_n = law.filter(|_| !load_path).map(|_| points.iter().map(|p| p.load_n).fold(0.0, f64::min));
    let note = if law.is_some() && load_path {
        Some(
            "seed is null for a map or a scenario's patch (not generated); pull_off_n is null on a load path \
             (--pressure, --sweep: the loading branch stays compressive; a mean-gap path, --gap-sweep, passes the \
             load minimum)",
        )
    } else {
        (seed.is_none() || law.is_none()).then_some(
            "seed is null for a map or a scenario's patch (not generated); dugdale and pull_off_n are null without \
             adhesion (no --work-of-adhesion and --range)",
        )
    };
    let out = BemOutput {
        note,
        surface: source,
        grid,
        e_star_pa,
        rms_height_m: solver.height_rms_m(),
        rms_slope,
        seed,
        dugdale: law,
        boundary: args.boundary,
        tilt: args.tilt,
        hardness_pa: args.hardness_pa,
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
    args: &BemRequest,
    surface: BemSurface<'_>,
    pressures: Option<&[f64]>,
) -> Result<serde_json::Value, Error> {
    if args.humidity.rh.is_some() {
        if pressures.is_some() {
            return Err("pressure: with rh, one mean pressure (the compressed state each retraction starts from), \
                        not a vector"
                .into());
        }
        check_path_args(args)?;
        let out = humidity::output(args, || surface.build(args))?;
        return Ok(crate::json::finite_value(&out)?);
    }
    check_front_end_path(args, pressures)?;
    let (out, _, _) = solve(args, surface.build(args)?, pressures)?;
    Ok(crate::json::finite_value(&out)?)
}

/// The checks of [`bem_json`]'s load path before any work: a tolerance in (0, 1), and a load
/// path (`pressures`, each finite and > 0, or the flags').
fn check_front_end_path(args: &BemRequest, pressures: Option<&[f64]>) -> Result<(), Error> {
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

/// `stiction bem --rh`: adhesion energy against relative humidity.
pub mod humidity {
    use serde::Serialize;
    use stiction_bem::{BemSolver, Dugdale, Grid, SolverOptions};
    use stiction_contact::capillary::{Capillarity, Liquid};

    use super::{BemRequest, SurfaceSource};
    use crate::Error;

    /// A front end's temperature text ("25 C", "298.15 K" or a bare number in kelvin) in K, in
    /// the domain of the water correlations: the one rule of the scenario's
    /// `environment.temperature` (`stiction_scenario::parse_temperature_k`); `name` (the flag
    /// `--temperature`, the argument `temperature`) names the text in errors.
    pub fn parse_temperature(text: &str, name: &str) -> Result<f64, String> {
        stiction_scenario::parse_temperature_k(&serde_json::Value::String(text.to_string()))
            .map_err(|e| format!("{name}: {e}"))
    }

    /// One humidity.
    #[allow(missing_docs)]
    #[derive(Serialize)]
    pub struct Point {
        pub relative_humidity: f64,
        /// Kelvin radius r_K, m (null when dry: RH = 0 or a non-wetting angle).
        pub kelvin_radius_m: Option<f64>,
        /// Meniscus height h_m = r_K (cos th1 + cos th2), m (null when dry, also when r_K lies
        /// below --min-kelvin-radius).
        pub meniscus_height_m: Option<f64>,
        /// Work of separation per nominal area, J/m^2.
        pub adhesion_energy_j_per_m2: f64,
        /// The same in mJ/m^2 (the unit of the microcantilever literature).
        pub adhesion_energy_mj_per_m2: f64,
        /// Most tensile mean traction on the retraction, Pa.
        pub pull_off_pressure_pa: f64,
        /// Mean-gap steps of the retraction.
        pub steps: usize,
        /// Why the Kelvin radius or the meniscus height is null (always written: one CSV shape).
        pub meniscus_note: Option<&'static str>,
    }

    /// What `bem --rh --json` prints.
    #[allow(missing_docs)]
    #[derive(Serialize)]
    pub struct HumidityOutput {
        pub surface: SurfaceSource,
        pub grid: Grid,
        pub e_star_pa: f64,
        pub rms_height_m: f64,
        pub temperature_k: f64,
        pub surface_tension_n_per_m: f64,
        pub contact_angle_rad: f64,
        /// The flat wetted limit 2 gamma cos theta, J/m^2.
        pub capillary_limit_j_per_m2: f64,
        /// The van der Waals Dugdale law (null without --work-of-adhesion/--range).
        pub van_der_waals: Option<Dugdale>,
        /// Why `van_der_waals` is null.
        #[serde(skip_serializing_if = "Option::is_none")]
        pub van_der_waals_note: Option<&'static str>,
        /// Mean pressure of the compressed state the retractions start from, Pa.
        pub start_pressure_pa: f64,
        pub tolerance: f64,
        /// --min-kelvin-radius, m (absent: none).
        #[serde(skip_serializing_if = "Option::is_none")]
        pub min_kelvin_radius_m: Option<f64>,
        pub points: Vec<Point>,
    }

    /// The adhesion energy against humidity of `args` on the surface `surface` makes (called
    /// after the cheap checks of the flags).
    pub fn output(
        args: &BemRequest,
        surface: impl FnOnce() -> Result<super::Surface, Error>,
    ) -> Result<HumidityOutput, Error> {
        let h = &args.humidity;
        let rhs = h.rh.clone().unwrap_or_default();
        crate::rh::check_rh_values(&rhs)?;
        let temperature_k = h.temperature_k;
        crate::check::domain_value("environment.temperature", "--temperature", temperature_k)
            .map_err(|e| format!("--temperature: {e}"))?;
        let angle = h.contact_angle_rad;
        if !(0.0..=std::f64::consts::PI).contains(&angle) {
            return Err(format!("--contact-angle {angle} rad: expected 0 to 180 deg").into());
        }
        let vdw = match (args.work_of_adhesion_j_per_m2, args.range_m) {
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
        let start_pressure_pa = args.pressure_pa.unwrap_or(1e6);
        let start = solver.solve_load(start_pressure_pa, &opts, None)?;
        let mut points = Vec::with_capacity(rhs.len());
        for (&rh, air) in rhs.iter().zip(&caps) {
            // No meniscus below the smallest Kelvin radius (the dry regime).
            let cap = air.and_then(|c| c.above_min_kelvin_radius(h.min_kelvin_radius_m));
            let mut laws: Vec<Dugdale> = vdw.into_iter().collect();
            if let Some(c) = cap {
                laws.push(Dugdale::capillary(c.surface_tension_n_per_m, c.kelvin_radius_m, c.cos_angle_sum)?);
            }
            let (energy, pull_off, steps) = if laws.is_empty() {
                // Dry and without van der Waals: nothing holds the surfaces together.
                (0.0, 0.0, 0)
            } else {
                let shortest = laws.iter().fold(f64::INFINITY, |m, l| m.min(l.range_m));
                let step = h.rh_step_m.unwrap_or(shortest / 20.0);
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
        let out = HumidityOutput {
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
            min_kelvin_radius_m: h.min_kelvin_radius_m,
            points,
        };
        Ok(out)
    }
}
