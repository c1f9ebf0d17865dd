//! `topography`: a measured height map in, its summits and statistics (beside Nayak's
//! random-process predictions and the GW parameters) out.

use std::path::Path;

use serde::Serialize;
use stiction_topography::{ChannelInfo, Statistics, find_summits, prepare, statistics};

use crate::Error;
use crate::scenario_source::ScenarioSource;

// The height map's types that a front end names, parses from its flags or prints: the map and
// how it was read (format, channel, metadata and where each came from), its preparation, its
// summits, Nayak's predictions and its spectrum.
pub use stiction_topography::{
    ArrayLayout, BorrowedHeights, ChannelSelector, HeightMap, Levelling, MapFormat, MapInfo, MapMetadata,
    MapMetadataRead, MetaSource, Nayak, Preparation, PreparationReport, Psd, Summits, parse_length_unit,
};

/// GW parameters of the map and the adhesion parameter.
#[derive(Serialize)]
pub struct Gw {
    /// eta: the counted summit density, m^-2.
    pub summit_density_per_m2: f64,
    /// sigma: the counted summit height SD, m.
    pub summit_sd_m: Option<f64>,
    /// R: the counted mean summit radius, m.
    pub summit_radius_m: Option<f64>,
    /// theta (eq. 9) with the scenario's material; null with the reason in `theta_note`.
    pub adhesion_parameter_theta: Option<f64>,
    /// Where theta comes from, or why it is null.
    pub theta_note: String,
}

/// What `topography --json` prints (its keys: docs/topography.md).
#[allow(missing_docs)]
#[derive(Serialize)]
pub struct TopographyOutput {
    pub file: String,
    pub format: MapFormat,
    pub read: MapInfo,
    pub preparation: PreparationReport,
    pub summit_count: usize,
    pub summit_density_per_m2: f64,
    pub summit_height_sd_m: Option<f64>,
    pub summit_height_mean_m: Option<f64>,
    pub summit_radius_mean_m: Option<f64>,
    pub summit_radius_median_m: Option<f64>,
    pub summit_curvature_mean_per_m: Option<f64>,
    pub rms_height_m: f64,
    pub rms_slope: f64,
    pub rms_curvature_per_m: f64,
    pub autocorrelation_length_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub autocorrelation_length_note: Option<&'static str>,
    pub nayak: Option<Nayak>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nayak_note: Option<&'static str>,
    pub gw: Gw,
    pub statistics: Statistics,
}

/// What `topography --channels --json` prints.
#[allow(missing_docs)]
#[derive(Serialize)]
pub struct ChannelList<'a> {
    pub file: String,
    pub format: MapFormat,
    /// Index of the channel read by default (the first height channel), if any.
    pub default_channel: Option<usize>,
    pub channels: &'a [ChannelInfo],
}

/// Prepares `raw` (levelling, cut-offs), finds its summits and composes the statistics of the
/// map named `file`; the prepared map and its summits come back beside them.
pub fn compose(
    file: String,
    raw: HeightMap,
    info: MapInfo,
    prep: &Preparation,
    scenario: Option<&ScenarioSource>,
) -> Result<(TopographyOutput, HeightMap, Summits), Error> {
    let (map, report) = prepare(&raw, prep)?;
    drop(raw);
    let summits = find_summits(&map);
    let st = statistics(&map, &summits);
    let gw = gw_of(&st, scenario)?;
    let out = TopographyOutput {
        file,
        format: info.format,
        read: info,
        preparation: report,
        summit_count: st.summits.count,
        summit_density_per_m2: st.summits.density_per_m2,
        summit_height_sd_m: st.summits.height_sd_m,
        summit_height_mean_m: st.summits.height_mean_m,
        summit_radius_mean_m: st.summits.radius_mean_m,
        summit_radius_median_m: st.summits.radius_median_m,
        summit_curvature_mean_per_m: st.summits.curvature_mean_per_m,
        rms_height_m: st.rms_height_m,
        rms_slope: st.rms_slope,
        rms_curvature_per_m: st.rms_curvature_per_m,
        autocorrelation_length_m: st.autocorrelation_length_m,
        autocorrelation_length_note: st.autocorrelation_length_note,
        nayak: st.nayak,
        nayak_note: st.nayak_note,
        gw,
        statistics: st,
    };
    Ok((out, map, summits))
}

/// The JSON object `stiction topography FILE --json` prints for the map `raw` as read (with
/// `info`) from `file`, prepared with `prep`, with the material of `scenario` (a file or a tree
/// built in memory) for theta; the
/// prepared map and its summits beside it.
pub fn topography_json(
    file: &str,
    raw: HeightMap,
    info: MapInfo,
    prep: &Preparation,
    scenario: Option<&ScenarioSource>,
) -> Result<(serde_json::Value, HeightMap, Summits), Error> {
    let (out, map, summits) = compose(file.to_string(), raw, info, prep, scenario)?;
    Ok((crate::json::finite_value(&out)?, map, summits))
}

/// The GW parameters of the map's statistics, with theta from the material of `scenario`.
pub fn gw_of(st: &Statistics, scenario: Option<&ScenarioSource>) -> Result<Gw, Error> {
    let s = &st.summits;
    let (sd, r) = (s.height_sd_m, s.radius_mean_m);
    let (theta, note) = match scenario {
        None => (None, "no --scenario: theta needs a material (compliance, work of adhesion)".to_string()),
        Some(source) => {
            let sc = source.parse(&[])?;
            let m = sc.require_material().map_err(|e| format!("{}: {e}", source.name()))?;
            match (sd, r) {
                (Some(sd), Some(r)) if sd > 0.0 => {
                    match stiction_contact::gw::adhesion_parameter(sd, r, m.compliance_per_pa(), m.work_of_adhesion)? {
                        Some(t) => (Some(t), format!("material of {}", source.name())),
                        None => (None, "work of adhesion 0: theta is infinite (no adhesion)".into()),
                    }
                }
                _ => (None, "fewer than 2 summits: no summit height SD".into()),
            }
        }
    };
    Ok(Gw {
        summit_density_per_m2: s.density_per_m2,
        summit_sd_m: sd,
        summit_radius_m: r,
        adhesion_parameter_theta: theta,
        theta_note: note,
    })
}

/// Reads the height map `path` (in `format`, None: from its extension; channel `channel`, None:
/// the first height channel) with `meta` for what the file does not say: the heights as read and
/// what the reader found.
pub fn read(
    path: &Path,
    format: Option<MapFormat>,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), Error> {
    Ok(stiction_topography::read_file_channel(path, format, channel, meta)?)
}

/// A height map held in memory (a front end's array, `heights` with its `layout`: strides in
/// elements, negative ones included) read as [`read`] reads a file, named `origin` in errors, with
/// `meta` for the pixel size and height unit.
pub fn read_array(
    heights: BorrowedHeights<'_>,
    layout: ArrayLayout,
    origin: &str,
    meta: &MapMetadata,
) -> Result<(HeightMap, MapInfo), Error> {
    Ok(stiction_topography::read_array(heights, layout, origin, meta)?)
}

/// The height map `path` as [`read`] reads it, as its heights in metres (row-major, NaN where
/// missing) and what was read: format, size, pixel size, channel and the file's other channels
/// (Python's `read_map`).
pub fn read_with_metadata(
    path: &Path,
    format: Option<MapFormat>,
    channel: Option<&ChannelSelector>,
    meta: &MapMetadata,
) -> Result<(Vec<f64>, MapMetadataRead), Error> {
    Ok(stiction_topography::read_map_with_metadata(path, format, channel, meta)?)
}

/// The channels of the height-map file `path` (`stiction topography --channels`): the format
/// read and each channel's name, size, unit and whether it holds heights.
pub fn channels(
    path: &Path,
    format: Option<MapFormat>,
    meta: &MapMetadata,
) -> Result<(MapFormat, Vec<ChannelInfo>), Error> {
    Ok(stiction_topography::list_channels(path, format, meta)?)
}

/// The radially averaged PSD of a prepared map, with a 2-D Hann window (measured maps are not
/// periodic): spatial frequency 1/m against C in m^4.
pub fn psd(map: &HeightMap) -> Psd {
    stiction_topography::radial_psd(map, stiction_topography::PsdWindow::Hann)
}

/// A map's summits as the summit files scenarios read: the CSV (x_m, y_m, height_m, radius_m
/// over the map's area), or with `npy` the N x 4 float64 array of `stiction surface --npy`.
/// Each summit sits at its pixel's centre.
pub fn summit_file_bytes(map: &HeightMap, s: &Summits, npy: bool) -> Result<Vec<u8>, Error> {
    use stiction_surface::{Radii, Surface};
    let (lx, ly) = (map.length_x_m(), map.length_y_m());
    let xs = s.ix.iter().map(|&i| ((f64::from(i) + 0.5) * map.dx_m()) as f32).collect();
    let ys = s.iy.iter().map(|&i| ((f64::from(i) + 0.5) * map.dy_m()) as f32).collect();
    let radii = (0..s.len()).map(|i| s.radius_m(i)).collect();
    let surface = Surface::new(lx, ly, xs, ys, s.height_m.clone(), Radii::PerSummit(radii))?;
    if npy {
        return Ok(surface.to_npy_bytes());
    }
    let mut bytes = Vec::new();
    surface.write_csv(&mut bytes)?;
    Ok(bytes)
}
