//! Summits from measured height maps (`source` = "height_map").
//!
//! Each face's map is read and prepared, the shoe's apparent area is cut from it (a stated corner,
//! or a random one drawn from the surface seed: stream 10 for the wall's map, 11 for the shoe's),
//! and the 8-neighbour summits of the patch (of the sum of both patches when both faces have a map)
//! become the summit list, each with its own radius 1/kappa. Heights are measured from the
//! prepared map's reference plane (the levelled mean plane).

use std::path::Path;

use serde::Serialize;
use stiction_topography::HeightMap;
use stiction_units::{Dimension, format_quantity};

use crate::{Radii, Surface, SurfaceError, SurfaceSpec};

/// Summit statistics of a height-map surface for the statistical models (GW, discrete): counted
/// on the whole prepared map exactly as `stiction topography` counts them (8-neighbour summits,
/// their density over the candidate pixels, the SD of their heights, the mean of their radii
/// 1/kappa). With two maps (wall and shoe) they are combined as the paper's composite surface
/// (section 3.1): eta = eta1 + eta2, sigma^2 = sigma1^2 + sigma2^2, 1/R = 1/R1 + 1/R2.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapSummitStatistics {
    /// Where the numbers come from, in words.
    pub source: String,
    /// Summits counted.
    pub summit_count: usize,
    /// Summit density eta, m^-2.
    pub summit_density_per_m2: f64,
    /// Summit height SD sigma, m.
    pub summit_sd_m: f64,
    /// Mean summit radius R, m.
    pub summit_radius_m: f64,
}

fn describe(spec: &stiction_topography::HeightMapSpec) -> String {
    match &spec.file {
        Some(f) => format!("the height map {}", f.display()),
        None => "the generated height map".to_string(),
    }
}

/// The summit statistics of the surface's height map(s) (see [`MapSummitStatistics`]).
pub fn map_summit_statistics(spec: &SurfaceSpec, base_dir: &Path) -> Result<MapSummitStatistics, SurfaceError> {
    if spec.source != crate::SurfaceSource::HeightMap {
        return Err(SurfaceError::Spec("summit statistics from a map need `source` = \"height_map\"".into()));
    }
    let mut faces = Vec::new();
    for (m, field) in [(&spec.height_map, "height_map"), (&spec.counter_height_map, "counter_height_map")] {
        let Some(m) = m else { continue };
        let (map, _) = m.build_map(base_dir, spec.seed)?;
        let summits = stiction_topography::find_summits(&map);
        let st = stiction_topography::summit_stats(&map, &summits);
        let (Some(sd), Some(r)) = (st.height_sd_m, st.radius_mean_m) else {
            return Err(SurfaceError::Spec(format!(
                "`surface.{field}`: {} summit(s) on the map; the statistical models need at least two",
                st.count
            )));
        };
        faces.push((describe(m), st.count, st.density_per_m2, sd, r));
    }
    if faces.is_empty() {
        return Err(SurfaceError::Spec(
            "`source` = \"height_map\" needs `height_map` (the wall's map) or `counter_height_map` (the shoe's)".into(),
        ));
    }
    let names: Vec<String> = faces.iter().map(|f| f.0.clone()).collect();
    Ok(MapSummitStatistics {
        source: format!(
            "summit statistics counted on {} (the numbers `stiction topography` prints{})",
            names.join(" and "),
            if faces.len() > 1 { "; the two faces combined as a composite surface" } else { "" }
        ),
        summit_count: faces.iter().map(|f| f.1).sum(),
        summit_density_per_m2: faces.iter().map(|f| f.2).sum(),
        // One face: its own numbers, bit for bit; two: the composite rule.
        summit_sd_m: if faces.len() == 1 { faces[0].3 } else { faces.iter().map(|f| f.3 * f.3).sum::<f64>().sqrt() },
        summit_radius_m: if faces.len() == 1 { faces[0].4 } else { 1.0 / faces.iter().map(|f| 1.0 / f.4).sum::<f64>() },
    })
}

/// Pixels of a patch `length` long at pixel size `d` (as the patch cutter counts them).
fn patch_pixels(length: f64, d: f64) -> usize {
    (length / d * (1.0 + 1e-9)).floor() as usize
}

/// The map a patch of `length x width` is cut from: the map itself when it is large enough; when
/// it is smaller and the spec asks for `tile`, the map repeated as a periodic cell (one period
/// more than the patch along each short direction, so a random corner can fall anywhere in the
/// cell); otherwise an error in plain units naming the option. Returns the map and, when tiled,
/// a sentence saying so.
fn cover_shoe(
    map: HeightMap,
    m: &stiction_topography::HeightMapSpec,
    field: &str,
    length: f64,
    width: f64,
) -> Result<(HeightMap, Option<String>), SurfaceError> {
    let (nx_need, ny_need) = (patch_pixels(length, map.dx_m()), patch_pixels(width, map.dy_m()));
    let (nx, ny) = (map.nx(), map.ny());
    if nx_need <= nx && ny_need <= ny {
        return Ok((map, None));
    }
    let len = |x: f64| format_quantity(x, Dimension::Length);
    if !m.tile {
        return Err(SurfaceError::Spec(format!(
            "the shoe's apparent area {} x {} ({nx_need} x {ny_need} pixels) is larger than `surface.{field}` ({}, {} x {}, {nx} x {ny} pixels); set `surface.{field}.tile` = true to use the map as a periodic cell (tiled), or give a larger map",
            len(length),
            len(width),
            describe(m),
            len(map.length_x_m()),
            len(map.length_y_m()),
        )));
    }
    let tx = if nx_need > nx { nx_need + nx } else { nx };
    let ty = if ny_need > ny { ny_need + ny } else { ny };
    stiction_topography::check_grid_size(&format!("`surface.{field}` tiled"), tx as u64, ty as u64)?;
    let h = map.heights_m();
    let mut out = Vec::with_capacity(tx * ty);
    for iy in 0..ty {
        let row = &h[(iy % ny) * nx..(iy % ny + 1) * nx];
        out.extend((0..tx).map(|ix| row[ix % nx]));
    }
    let tiled = HeightMap::new(tx, ty, map.dx_m(), map.dy_m(), out)?;
    let note = format!(
        "`surface.{field}`: {} ({} x {}) is used as a periodic cell, tiled {:.2} x {:.2} times under the shoe's {} x {} (summits at the seams are the map's edges joined)",
        describe(m),
        len(map.length_x_m()),
        len(map.length_y_m()),
        length / map.length_x_m(),
        width / map.length_y_m(),
        len(length),
        len(width)
    );
    Ok((tiled, Some(note)))
}

/// Sentences saying which height maps of the surface are tiled under the shoe (empty: none).
pub fn height_map_tiling(spec: &SurfaceSpec, base_dir: &Path) -> Result<Vec<String>, SurfaceError> {
    let mut notes = Vec::new();
    if spec.source != crate::SurfaceSource::HeightMap {
        return Ok(notes);
    }
    for (m, field) in [(&spec.height_map, "height_map"), (&spec.counter_height_map, "counter_height_map")] {
        if let Some(m) = m {
            let (map, _) = m.build_map(base_dir, spec.seed)?;
            if let (_, Some(note)) = cover_shoe(map, m, field, spec.apparent_length, spec.apparent_width)? {
                notes.push(note);
            }
        }
    }
    Ok(notes)
}

/// ChaCha8 streams of the random patch corners.
const WALL_STREAM: u64 = 10;
const SHOE_STREAM: u64 = 11;

/// The composite height patch under the shoe of a `source` = "height_map" surface: each face's
/// map read (or generated) and prepared, the shoe's apparent area cut from it at the same corner
/// the summit list uses (stated, or drawn from the surface seed), and the two patches added when
/// both faces have a map. This is the grid a boundary-element solver takes for the shoe face;
/// returns the patch and, per face, the pixel window it was cut from.
pub fn height_map_patch(
    spec: &SurfaceSpec,
    base_dir: &Path,
) -> Result<(stiction_topography::HeightMap, Vec<stiction_topography::Patch>), SurfaceError> {
    if spec.source != crate::SurfaceSource::HeightMap {
        return Err(SurfaceError::Spec(
            "a height patch needs `source` = \"height_map\" with `height_map` and/or `counter_height_map`".into(),
        ));
    }
    let (l, w) = (spec.apparent_length, spec.apparent_width);
    crate::surface::check_positive("apparent_length", l, "m")?;
    crate::surface::check_positive("apparent_width", w, "m")?;
    let mut patch: Option<stiction_topography::HeightMap> = None;
    let mut windows = Vec::new();
    for (map_spec, stream, field) in
        [(&spec.height_map, WALL_STREAM, "height_map"), (&spec.counter_height_map, SHOE_STREAM, "counter_height_map")]
    {
        if let Some(m) = map_spec {
            let (map, _) = m.build_map(base_dir, spec.seed)?;
            let (map, _) = cover_shoe(map, m, field, l, w)?;
            let p = m.patch(&map, l, w, spec.seed, stream)?;
            let cut = map.crop(p.ix0, p.iy0, p.nx, p.ny)?;
            drop(map);
            windows.push(p);
            patch = Some(match patch {
                None => cut,
                Some(acc) => acc.add(&cut)?,
            });
        }
    }
    let patch = patch.ok_or_else(|| {
        SurfaceError::Spec(
            "`source` = \"height_map\" needs `height_map` (the wall's map) or `counter_height_map` (the shoe's)".into(),
        )
    })?;
    Ok((patch, windows))
}

pub(crate) fn build(spec: &SurfaceSpec, base_dir: &Path) -> Result<Surface, SurfaceError> {
    for (name, present) in [
        ("summit_density", spec.summit_density.is_some()),
        ("summit_sd", spec.summit_sd.is_some()),
        ("summit_radius", spec.summit_radius.is_some()),
        ("counter_face", spec.counter_face.is_some()),
        ("csv_path", spec.csv_path.is_some()),
        ("pair_reach", spec.pair_reach.is_some()),
    ] {
        if present {
            return Err(SurfaceError::Spec(format!(
                "`{name}` must be absent when `source` is \"height_map\" (the map gives the summits)"
            )));
        }
    }
    let (l, w) = (spec.apparent_length, spec.apparent_width);
    crate::surface::check_positive("apparent_length", l, "m")?;
    crate::surface::check_positive("apparent_width", w, "m")?;
    let mut faces = Vec::new();
    for (map_spec, stream, field) in
        [(&spec.height_map, WALL_STREAM, "height_map"), (&spec.counter_height_map, SHOE_STREAM, "counter_height_map")]
    {
        if let Some(m) = map_spec {
            let (map, _) = m.build_map(base_dir, spec.seed)?;
            let (map, _) = cover_shoe(map, m, field, l, w)?;
            let patch = m.patch(&map, l, w, spec.seed, stream)?;
            faces.push((map, patch));
        }
    }
    if faces.is_empty() {
        return Err(SurfaceError::Spec(
            "`source` = \"height_map\" needs `height_map` (the wall's map) or `counter_height_map` (the shoe's)".into(),
        ));
    }
    let refs: Vec<_> = faces.iter().map(|(m, p)| (m, *p)).collect();
    let s = stiction_topography::patch_summits(&refs)?;
    if s.height_m.len() > crate::MAX_SUMMITS {
        return Err(SurfaceError::Spec(format!("more than {} summits on the patch", crate::MAX_SUMMITS)));
    }
    let inside = |v: f64, lim: f64| {
        let mut f = v as f32;
        while f64::from(f) > lim {
            f = f.next_down();
        }
        f
    };
    let xs = s.x_m.iter().map(|&x| inside(x, l)).collect();
    let ys = s.y_m.iter().map(|&y| inside(y, w)).collect();
    Surface::new(l, w, xs, ys, s.height_m, Radii::PerSummit(s.radius_m))
}
