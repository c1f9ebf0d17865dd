//! Summits from measured height maps (`source` = "height_map").
//!
//! Each face's map is read and prepared, the shoe's apparent area is cut from it (a stated corner,
//! or a random one drawn from the surface seed: stream 10 for the wall's map, 11 for the shoe's),
//! and the 8-neighbour summits of the patch (of the sum of both patches when both faces have a map)
//! become the summit list, each with its own radius 1/kappa. Heights are measured from the
//! prepared map's reference plane (the levelled mean plane).

use std::path::Path;

use crate::{Radii, Surface, SurfaceError, SurfaceSpec};

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
    for (map_spec, stream) in [(&spec.height_map, WALL_STREAM), (&spec.counter_height_map, SHOE_STREAM)] {
        if let Some(m) = map_spec {
            let (map, _) = m.build_map(base_dir, spec.seed)?;
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
    for (map_spec, stream) in [(&spec.height_map, WALL_STREAM), (&spec.counter_height_map, SHOE_STREAM)] {
        if let Some(m) = map_spec {
            let (map, _) = m.build_map(base_dir, spec.seed)?;
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
