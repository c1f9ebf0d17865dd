//! `plot`: the numbers of the paper's figures that come from a scenario (the charts themselves
//! are drawn by the front end from the physics crates' curves).

use std::path::Path;

use stiction_scenario::Scenario;

use crate::Error;

/// The adhesion parameter theta (eq. 9) of a scenario's surface and material, or an error saying
/// what is missing. `None`: no adhesion (theta = infinity).
pub fn scenario_theta(s: &Scenario, base: &Path) -> Result<Option<f64>, Error> {
    let surface = s.require_surface()?;
    let material = s.require_material()?;
    let sd = surface.summit_sd.ok_or("the scenario's surface has no `summit_sd` (needed for theta, eq. 9)")?;
    let radius = stiction_meter::model_summit_radius_m(surface, base)?;
    Ok(stiction_contact::gw::adhesion_parameter(sd, radius, material.compliance_per_pa(), material.work_of_adhesion)?)
}
