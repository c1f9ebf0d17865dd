//! `stiction surface`: build a scenario's rough sidewall, print its statistics, export it.

use std::path::PathBuf;

use stiction_engine::scenario::Scenario;

use crate::output::{CliResult, print_json, print_table};

/// Generate (or read) the scenario's rough sidewall: summit statistics against the requested
/// parameters, and an export as CSV (x_m, y_m, height_m, radius_m in SI) or NumPy .npy for
/// inspection or reuse.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The scenario JSON file (its `surface` section).
    pub scenario: PathBuf,
    /// Write the summits to this CSV file (readable back with `"source": "csv"`).
    #[arg(long, value_name = "FILE.csv")]
    pub csv: Option<PathBuf>,
    /// Write the summits to this NumPy file: an N x 4 float64 array, columns x, y, height, radius
    /// in m (`np.load`; readable back with `"source": "npy"`).
    #[arg(long, value_name = "FILE.npy")]
    pub npy: Option<PathBuf>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Override a scenario field (repeatable): --set surface.seed=7.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let scenario = Scenario::load(&args.scenario, &args.sets)?;
    if let Some(path) = &args.csv {
        crate::output::check_output_flag("--csv", path)?;
    }
    let base = args.scenario.parent().map(PathBuf::from).unwrap_or_default();
    let (surface, out) = stiction_engine::surface::surface(&scenario, &args.scenario.display().to_string(), &base)?;
    if let Some(path) = &args.csv {
        // Again after the build, which read the scenario's own summit CSV, if any.
        crate::output::check_output_flag("--csv", path)?;
        surface.write_csv_file(path)?;
        crate::errln!("wrote {} summits to {}", surface.len(), path.display());
    }
    if let Some(path) = &args.npy {
        surface.write_npy_file(path)?;
        crate::errln!("wrote {} summits to {}", surface.len(), path.display());
    }
    if args.json {
        return print_json(&out);
    }
    let s = &out.stats;
    let req = |x: Option<f64>, scale: f64, unit: &str| {
        x.map_or(String::new(), |v| format!("  (requested {:.4} {unit})", v * scale))
    };
    let req_density =
        out.requested_summit_density_per_m2.map_or(String::new(), |v| format!("  (requested {v:.4e} m^-2)"));
    print_table(
        &format!("Rough sidewall of {} (content hash {})", args.scenario.display(), out.content_hash),
        &[
            ("summits", format!("{}", s.count)),
            ("summit density", format!("{:.4e} m^-2{req_density}", s.summit_density_per_m2)),
            ("height mean", format!("{:.4} nm", s.height_mean_m * 1e9)),
            ("height SD", format!("{:.4} nm{}", s.height_sd_m * 1e9, req(out.requested_summit_sd_m, 1e9, "nm"))),
            ("height min, max", format!("{:.4} nm, {:.4} nm", s.height_min_m * 1e9, s.height_max_m * 1e9)),
            (
                "radius mean",
                format!("{:.4} um{}", s.radius_mean_m * 1e6, req(out.requested_summit_radius_m, 1e6, "um")),
            ),
            ("radius SD", format!("{:.4} um", s.radius_sd_m * 1e6)),
            ("radius min, max", format!("{:.4} um, {:.4} um", s.radius_min_m * 1e6, s.radius_max_m * 1e6)),
        ],
    );
    Ok(())
}
