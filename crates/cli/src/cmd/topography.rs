//! `stiction topography`: a measured height map in, its summits and statistics out.

use std::path::PathBuf;

use stiction_engine::ScenarioSource;
use stiction_engine::topography::{
    self, ChannelSelector, HeightMap, MapInfo, MetaSource, Nayak, PreparationReport, Summits, TopographyOutput,
    summit_file_bytes,
};
use stiction_plot::{Chart, ImageMap, Series};
use stiction_units::io::write_atomic;

use super::map_args::MapArgs;
use crate::output::{CliResult, OutputSet, print_json, print_table};

/// Read a measured height map (AFM, optical profiler): level it, filter it, find its summits
/// (8-neighbour maxima, curvature -(z_xx + z_yy)/2) and print the statistics beside Nayak's
/// random-process predictions; with --scenario, the GW parameters and the adhesion parameter theta
/// for the scenario's material.
///
/// Formats, recognised by their content (the extension only where the content has no magic):
/// .npy (float32/64), .gsf (Gwyddion simple field), Bruker NanoScope (.spm, .di, .001), Igor
/// binary wave (.ibw), ISO 25178-71 SDF (.sdf), ISO 25178-72 X3P (.x3p), Digital Surf (.sur), Wyko (.opd); .xyz (x y z points on a grid); any other text a
/// grid (Gwyddion's ASCII export header gives the pixel size and unit). An instrument file's first
/// height channel is read unless --channel names another; --channels lists them.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The height-map file.
    pub file: PathBuf,
    /// List the file's channels (index, name, grid, size, unit; `*` marks the default) and exit.
    #[arg(long)]
    pub channels: bool,
    /// The channel to read from an instrument file: its name or index (default: the first
    /// height channel).
    #[arg(long, value_name = "NAME|INDEX", value_parser = |s: &str| s.parse::<ChannelSelector>())]
    pub channel: Option<ChannelSelector>,
    /// Metadata and preparation of the map.
    #[command(flatten)]
    pub map: MapArgs,
    /// Write the summits as CSV (x_m,y_m,height_m,radius_m: readable by a scenario with "source": "csv"),
    /// or, for a name ending in .npy, as an N x 4 float64 NumPy array (x, y, height, radius in m;
    /// readable with "source": "npy").
    #[arg(long, value_name = "OUT.csv|OUT.npy")]
    pub summits: Option<PathBuf>,
    /// Write figures (PNG) with their data (CSV), summits.csv and statistics.json to this folder,
    /// with a manifest.json; the folder is replaced as a whole.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Write into an --out folder that holds files not from an earlier stiction run (they are
    /// left alone; the earlier run's files are replaced or removed).
    #[arg(long)]
    pub force: bool,
    /// A scenario whose material gives the GW parameters' adhesion parameter theta.
    #[arg(long, value_name = "SCENARIO.json")]
    pub scenario: Option<PathBuf>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
    /// Figure size and font (with --out).
    #[command(flatten)]
    pub fig: crate::figargs::FigureArgs,
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    // Check the output folder before the work, so a refusal comes at once.
    let outputs = match &args.out {
        Some(dir) => Some(OutputSet::begin(dir, "topography", args.force)?),
        None => None,
    };
    if args.channels {
        return print_channels(&args);
    }
    let (raw, info) = topography::read(&args.file, args.map.format, args.channel.as_ref(), &args.map.metadata())?;
    if let Some(path) = &args.summits {
        crate::output::check_output_flag("--summits", path)?;
    }
    let scenario = args.scenario.as_deref().map(|p| ScenarioSource::file(p, &[])).transpose()?;
    let (out, map, summits) =
        topography::compose(args.file.display().to_string(), raw, info, &args.map.preparation(), scenario.as_ref())?;
    let report = out.preparation;
    if let (Some(mut set), Some(dir)) = (outputs, &args.out) {
        set.add_bytes("statistics.json", crate::output::json_text(&out)?.as_bytes())?;
        set.add_bytes("summits.csv", &summit_file_bytes(&map, &summits, false)?)?;
        figures(&map, &summits, &report, out.nayak.as_ref(), &mut set, &args.fig, &args.map)?;
        set.commit()?;
        crate::errln!("wrote figures, their data, summits.csv, statistics.json and manifest.json to {}", dir.display());
    }
    // After the --out folder is in place, so a --summits file inside it is not swept away with the
    // folder's earlier contents.
    if let Some(path) = &args.summits {
        // A name ending in .npy gets the N x 4 float64 array (x, y, height, radius) of `stiction surface --npy`.
        let npy = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy"));
        write_atomic(path, &summit_file_bytes(&map, &summits, npy)?)?;
        crate::errln!("wrote {} summits to {}", summits.len(), path.display());
    }
    if args.json {
        return print_json(&out);
    }
    print_table_of(&out);
    Ok(())
}

/// `--channels`: the file's channels, as a table or JSON.
fn print_channels(args: &Args) -> CliResult {
    let (format, list) = topography::channels(&args.file, args.map.format, &args.map.metadata())?;
    let default = list.iter().find(|c| c.is_height).map(|c| c.index);
    if args.json {
        return print_json(&topography::ChannelList {
            file: args.file.display().to_string(),
            format,
            default_channel: default,
            channels: &list,
        });
    }
    let rows: Vec<(String, String)> = list
        .iter()
        .map(|c| {
            let size = c
                .size_m
                .map_or("size not in the file".into(), |(a, b)| format!("{:.6} um x {:.6} um", a * 1e6, b * 1e6));
            let unit = if c.unit.is_empty() { "no unit".to_string() } else { c.unit.clone() };
            let mark = if Some(c.index) == default { " (default)" } else { "" };
            (
                format!("{} {}{mark}", c.index, c.name),
                format!("{} x {} pixels, {size}, {unit}{}", c.nx, c.ny, if c.is_height { ", height" } else { "" }),
            )
        })
        .collect();
    let rows: Vec<(&str, String)> = rows.iter().map(|(a, b)| (a.as_str(), b.clone())).collect();
    print_table(&format!("Channels of {} ({})", args.file.display(), format.name()), &rows);
    Ok(())
}

fn channel_text(info: &MapInfo) -> String {
    match &info.channel {
        None => "the file's only map".into(),
        Some(c) if c.chosen == "default" => {
            format!("{} `{}` of {} (the first height channel; --channel picks another)", c.index, c.name, c.of)
        }
        Some(c) => format!("{} `{}` of {} (--channel)", c.index, c.name, c.of),
    }
}

fn source_text(s: MetaSource) -> &'static str {
    match s {
        MetaSource::File => "the file",
        MetaSource::Given => "the flags",
        MetaSource::FileAndGiven => "the file (the flag agrees)",
    }
}

fn opt(v: Option<f64>, scale: f64, unit: &str) -> String {
    v.map_or("n/a".into(), |v| format!("{:.4} {unit}", v * scale))
}

fn print_table_of(o: &TopographyOutput) {
    let st = &o.statistics;
    let n = o.nayak.as_ref();
    let nay = |f: &dyn Fn(&Nayak) -> Option<f64>, scale: f64, unit: &str| {
        n.and_then(f).map_or(String::new(), |v| format!("   (Nayak {:.4} {unit})", v * scale))
    };
    let cut = |v: Option<f64>| v.map_or("none".into(), |v| format!("{:.4} um", v * 1e6));
    print_table(
        &format!("Height map {} ({})", o.file, o.format.name()),
        &[
            (
                "grid",
                format!(
                    "{} x {} pixels of {:.4} nm x {:.4} nm, {} missing",
                    st.nx,
                    st.ny,
                    st.dx_m * 1e9,
                    st.dy_m * 1e9,
                    st.missing_pixels
                ),
            ),
            ("channel", channel_text(&o.read)),
            (
                "pixel size, height unit",
                format!("from {}, from {}", source_text(o.read.pixel_size_from), source_text(o.read.height_unit_from)),
            ),
            ("levelling", o.preparation.levelling.to_string()),
            (
                "short, long cut-off",
                format!("{}, {}", cut(o.preparation.short_cutoff_m), cut(o.preparation.long_cutoff_m)),
            ),
            ("RMS height", format!("{:.4} nm", o.rms_height_m * 1e9)),
            ("RMS slope", format!("{:.4}", o.rms_slope)),
            ("RMS curvature", format!("{:.4} 1/um", o.rms_curvature_per_m * 1e-6)),
            (
                "autocorrelation length",
                match (o.autocorrelation_length_m, o.autocorrelation_length_note) {
                    (Some(l), _) => format!("{:.4} um", l * 1e6),
                    (None, note) => format!("n/a ({})", note.unwrap_or("not computed")),
                },
            ),
            (
                "bandwidth alpha",
                n.map_or(format!("n/a ({})", o.nayak_note.unwrap_or("not computed")), |n| {
                    format!("{:.3}", n.bandwidth_alpha)
                }),
            ),
            ("summits", format!("{}", o.summit_count)),
            (
                "summit density",
                format!(
                    "{:.4e} m^-2{}",
                    o.summit_density_per_m2,
                    n.map_or(String::new(), |n| format!("   (Nayak {:.4e} m^-2)", n.summit_density_per_m2))
                ),
            ),
            (
                "summit height SD",
                format!("{}{}", opt(o.summit_height_sd_m, 1e9, "nm"), nay(&|n| n.summit_height_sd_m, 1e9, "nm")),
            ),
            (
                "summit height mean",
                format!(
                    "{}{}",
                    opt(o.summit_height_mean_m, 1e9, "nm"),
                    nay(&|n| Some(n.summit_height_mean_m), 1e9, "nm")
                ),
            ),
            (
                "summit curvature mean",
                format!(
                    "{}{}",
                    opt(o.summit_curvature_mean_per_m, 1e-6, "1/um"),
                    nay(&|n| Some(n.summit_curvature_mean_per_m), 1e-6, "1/um")
                ),
            ),
            ("summit radius mean", opt(o.summit_radius_mean_m, 1e6, "um")),
            ("summit radius median", opt(o.summit_radius_median_m, 1e6, "um")),
            (
                "GW theta (eq. 9)",
                o.gw.adhesion_parameter_theta
                    .map_or(format!("n/a ({})", o.gw.theta_note), |t| format!("{t:.4} ({})", o.gw.theta_note)),
            ),
        ],
    );
}

/// Histogram (lower edge, upper edge, count) of `v` in `bins` equal bins over [lo, hi].
fn histogram(v: &[f64], lo: f64, hi: f64, bins: usize) -> Vec<(f64, f64, usize)> {
    let w = (hi - lo) / bins as f64;
    let mut c = vec![0usize; bins];
    for &x in v {
        if x >= lo && x <= hi && w > 0.0 {
            c[(((x - lo) / w) as usize).min(bins - 1)] += 1;
        }
    }
    (0..bins).map(|k| (lo + k as f64 * w, lo + (k + 1) as f64 * w, c[k])).collect()
}

/// A histogram as the corners of its staircase ([`Series::step`]), x scaled by `scale`: from 0 up
/// at the first edge, each bin's count from its lower edge, down to 0 at the last edge.
fn histogram_steps(h: &[(f64, f64, usize)], scale: f64) -> Vec<(f64, f64)> {
    let (Some(first), Some(last)) = (h.first(), h.last()) else { return Vec::new() };
    let mut pts = vec![(first.0 * scale, 0.0)];
    pts.extend(h.iter().map(|&(a, _, c)| (a * scale, c as f64)));
    pts.push((last.1 * scale, last.2 as f64));
    pts.push((last.1 * scale, 0.0));
    pts
}

/// The figures (height map, PSD, summit heights and radii), each with its data CSV in the units its
/// axes show, through the output set.
fn figures(
    map: &HeightMap,
    s: &Summits,
    report: &PreparationReport,
    nayak: Option<&Nayak>,
    set: &mut OutputSet,
    fig: &crate::figargs::FigureArgs,
    map_args: &MapArgs,
) -> CliResult {
    // Height map, every grid cell unless --map-cells asks for blocks, with the summits.
    let (block, cx, cy, cells) = map_args.drawn_cells(map.heights_m(), map.nx(), map.ny());
    let (xmax, ymax) = (map.length_x_m() * 1e6, map.length_y_m() * 1e6);
    let markers: Vec<(f64, f64)> = (0..s.len())
        .map(|i| ((f64::from(s.ix[i]) + 0.5) * map.dx_m() * 1e6, (f64::from(s.iy[i]) + 0.5) * map.dy_m() * 1e6))
        .collect();
    let height_map = fig.apply_map(ImageMap {
        title: format!(
            "Height map ({} summits{})",
            s.len(),
            if block > 1 { format!(", drawn in {block} x {block} blocks") } else { String::new() }
        ),
        x_label: "x (µm)".into(),
        y_label: "y (µm)".into(),
        value_label: "height".into(),
        value_unit: Some("m".into()),
        nx: cx,
        ny: cy,
        values: cells,
        x_max: xmax,
        y_max: ymax,
        markers: if s.len() <= 5000 { markers } else { Vec::new() },
        ..Default::default()
    });
    set.add_map_figure("height_map", &height_map)?;

    // PSD with the cut-offs.
    let psd = topography::psd(map);
    let pts: Vec<(f64, f64)> = psd.f_per_m.iter().zip(&psd.psd_m4).map(|(f, p)| (f * 1e-6, *p)).collect();
    let mut chart = Chart::new(
        "Radially averaged PSD of the height map (Hann window)",
        "spatial frequency 1/λ (1/µm)",
        "PSD C (m⁴)",
    )
    .keys("spatial_frequency_per_um", "psd_m4")
    .with(Series::line("map", pts.clone()));
    chart.x_log = true;
    chart.y_log = true;
    let (ylo, yhi) =
        pts.iter().filter(|p| p.1 > 0.0).fold((f64::INFINITY, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
    for (name, cut) in
        [("short-wavelength cut-off", report.short_cutoff_m), ("long-wavelength cut-off", report.long_cutoff_m)]
    {
        if let Some(l) = cut {
            chart = chart.with(Series::dashed(name, vec![(1e-6 / l, ylo), (1e-6 / l, yhi)]));
        }
    }
    add_chart(set, "psd", chart, fig)?;

    // Summit height and radius histograms, with Nayak's predictions from the spectral moments.
    if s.len() >= 2 {
        let (lo, hi) = s.height_m.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| (a.min(h), b.max(h)));
        let bins = (s.len() as f64).sqrt().clamp(5.0, 60.0) as usize;
        let hh = histogram(&s.height_m, lo, hi, bins);
        let mut heights = Chart::new(
            format!("Summit heights ({} summits)", s.len()),
            "summit height above the mean plane (nm)",
            "summits per bin",
        )
        .keys("summit_height_nm", "summits_per_bin")
        .with(Series::step(format!("map: {} summits", s.len()), histogram_steps(&hh, 1e9)).with_color(0));
        if let Some(n) = nayak
            && let Some(sd) = n.summit_height_sd_m.filter(|sd| *sd > 0.0)
        {
            // Expected summits per bin: N w p(z), p the normal density with Nayak's large-alpha mean and SD.
            let w = (hi - lo) / bins as f64;
            let mean = n.summit_height_mean_m;
            let curve: Vec<(f64, f64)> = (0..=120)
                .map(|k| {
                    let z = lo + (hi - lo) * f64::from(k) / 120.0;
                    let p = (-0.5 * ((z - mean) / sd).powi(2)).exp() / (sd * (2.0 * std::f64::consts::PI).sqrt());
                    (z * 1e9, s.len() as f64 * w * p)
                })
                .collect();
            heights.series.insert(
                0,
                Series::line(
                    format!(
                        "Nayak (α = {}, large-α normal): mean {} nm, SD {} nm",
                        crate::format::sig3(n.bandwidth_alpha),
                        crate::format::sig3(mean * 1e9),
                        crate::format::sig3(sd * 1e9)
                    ),
                    curve,
                )
                .with_color(1),
            );
        }
        add_chart(set, "summit_heights", heights, fig)?;
        let mut radii: Vec<f64> = (0..s.len()).map(|i| s.radius_m(i)).collect();
        radii.sort_by(f64::total_cmp);
        let p99 = radii[((radii.len() - 1) as f64 * 0.99) as usize];
        let rh = histogram(&radii, 0.0, p99, bins);
        let top = rh.iter().map(|b| b.2).max().unwrap_or(0) as f64;
        let mut radii_chart = Chart::new(
            format!(
                "Summit radii 1/κ ({} summits; {} above the 99th percentile not shown)",
                s.len(),
                radii.len() - rh.iter().map(|b| b.2).sum::<usize>()
            ),
            "summit radius (µm)",
            "summits per bin",
        )
        .keys("summit_radius_um", "summits_per_bin")
        .with(Series::step(format!("map: {} summits", s.len()), histogram_steps(&rh, 1e6)).with_color(0));
        // Nayak's radius of the mean curvature (solid) under the map's own (dashed), both visible
        // where they coincide.
        if let Some(n) = nayak.filter(|n| n.summit_radius_m.is_finite() && n.summit_radius_m > 0.0) {
            let r_um = n.summit_radius_m * 1e6;
            radii_chart.series.push(
                Series::line(
                    format!("Nayak: 1/(mean curvature) = {} µm", crate::format::sig3(r_um)),
                    vec![(r_um, 0.0), (r_um, top)],
                )
                .with_color(1),
            );
        }
        let curvatures: Vec<f64> = radii.iter().filter(|r| r.is_finite() && **r > 0.0).map(|r| 1.0 / r).collect();
        if !curvatures.is_empty() {
            let mean_k = curvatures.iter().sum::<f64>() / curvatures.len() as f64;
            radii_chart.series.push(
                Series::dashed(
                    format!("map: 1/(mean curvature) = {} µm", crate::format::sig3(1e6 / mean_k)),
                    vec![(1e6 / mean_k, 0.0), (1e6 / mean_k, top)],
                )
                .with_color(0),
            );
        }
        add_chart(set, "summit_radii", radii_chart, fig)?;
    }
    Ok(())
}

/// Adds a chart as `{stem}.svg` and `{stem}.png` with its data CSV.
fn add_chart(set: &mut OutputSet, stem: &str, chart: Chart, fig: &crate::figargs::FigureArgs) -> CliResult {
    set.add_figure(stem, &fig.apply(chart)?)
}
