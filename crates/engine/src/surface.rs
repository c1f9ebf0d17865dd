//! `surface`: a scenario's rough sidewall built (generated or read) and its summit statistics.

use std::path::Path;

use serde::Serialize;
use stiction_scenario::Scenario;
use stiction_surface::{Surface, SurfaceStats};

use crate::Error;

/// What `surface --json` prints: the statistics of the built summits beside the requested ones.
#[derive(Serialize)]
pub struct SurfaceOutput {
    /// The built summits' statistics (SI).
    pub stats: SurfaceStats,
    /// The summit density the scenario asks for, 1/m^2.
    pub requested_summit_density_per_m2: Option<f64>,
    /// The summit height sd the scenario asks for, m.
    pub requested_summit_sd_m: Option<f64>,
    /// The summit radius the scenario asks for, m.
    pub requested_summit_radius_m: Option<f64>,
    /// Why a requested value is null: the surface is read (summit list, height map), not generated
    /// from these fields.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub requested_note: Option<&'static str>,
    /// A hash of the summits (x, y, height, radius), hexadecimal.
    pub content_hash: String,
}

/// Builds the surface of `scenario` (named `name` in errors, relative paths from `base`): the
/// summits and their statistics. A surface without summits is refused (it has no statistics).
pub fn surface(scenario: &Scenario, name: &str, base: &Path) -> Result<(Surface, SurfaceOutput), Error> {
    let spec = scenario.require_surface().map_err(|e| format!("{name}: {e}"))?;
    let surface = spec.build(base).map_err(|e| format!("{name}: surface: {e}"))?;
    if surface.is_empty() {
        return Err(format!(
            "{name}: the surface has no summits (density x apparent area is too small), so it has no height or radius \
             statistics; raise `surface.summit_density` or the apparent area"
        )
        .into());
    }
    let out = SurfaceOutput {
        stats: surface.stats(),
        requested_summit_density_per_m2: spec.summit_density,
        requested_summit_sd_m: spec.summit_sd,
        requested_summit_radius_m: spec.summit_radius,
        requested_note: (spec.summit_density.is_none() || spec.summit_sd.is_none() || spec.summit_radius.is_none())
            .then_some("not given: the surface is read (a summit list or a height map), not generated from it"),
        content_hash: format!("{:016x}", surface.content_hash()),
    };
    Ok((surface, out))
}
