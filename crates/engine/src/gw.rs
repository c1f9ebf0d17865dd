//! `gw`: Greenwood-Williamson with DMT adhesion in normalized form (eq. 5-9), stable branch.

use serde::{Deserialize, Serialize};

// The model [`model`] returns (its pull-off, for a front end that solves many loads).
pub use stiction_contact::gw::GwModel;

use crate::Error;

/// The state at a normalized load L* = D L / (eta A_a R^1/2 sigma^3/2).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GwRequest {
    /// The adhesion parameter theta = sigma^3/2 R^1/2 / (D dgamma R) (eq. 9), finite and > 0;
    /// None for plain GW (no adhesion, theta infinite).
    pub theta: Option<f64>,
    /// The normalized load L* (eq. 8), finite; below the pull-off load there is no equilibrium.
    pub load_star: f64,
}

/// What `gw --json` prints (the fields are its keys: docs/models.md).
#[allow(missing_docs)]
#[derive(Clone, Debug, Serialize)]
pub struct GwOutput {
    pub theta: Option<f64>,
    pub l_star: f64,
    pub h: f64,
    pub n_star: f64,
    pub log10_n_star: f64,
    pub a_star: f64,
    pub log10_a_star: f64,
    pub elastic_l_star: f64,
    pub adhesive_l_star: f64,
    pub elastic_pressure_star: f64,
    pub pull_off_l_star: Option<f64>,
    pub pull_off_h: Option<f64>,
    /// Why theta and the pull-off are null: plain GW, no adhesion (theta infinite).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub theta_note: Option<&'static str>,
}

/// The model of `theta` (None: plain GW), checked: theta finite and > 0.
pub fn model(theta: Option<f64>) -> Result<GwModel, Error> {
    Ok(GwModel::new(theta)?)
}

/// Solves the request: the stable-branch state at `load_star`. `name_load` names the load in a
/// refusal as the front end calls it (`--load-star`, `load_star`).
pub fn gw(req: &GwRequest, name_load: &str) -> Result<GwOutput, Error> {
    if !req.load_star.is_finite() {
        return Err(format!("{name_load} {}: expected a finite normalized load", req.load_star).into());
    }
    let model = model(req.theta)?;
    state(&model, req.load_star)
}

/// The state of `model` at `load_star` as [`GwOutput`].
pub fn state(model: &GwModel, load_star: f64) -> Result<GwOutput, Error> {
    let st = model.solve(load_star)?;
    Ok(GwOutput {
        theta: st.theta,
        l_star: st.l_star,
        h: st.h,
        n_star: st.n_star,
        log10_n_star: st.log10_n_star,
        a_star: st.a_star,
        log10_a_star: st.log10_a_star,
        elastic_l_star: st.elastic_l_star,
        adhesive_l_star: st.adhesive_l_star,
        elastic_pressure_star: st.elastic_pressure_star,
        pull_off_l_star: model.pull_off().map(|p| p.l_star),
        pull_off_h: model.pull_off().map(|p| p.h),
        theta_note: st.theta.is_none().then_some("theta is infinite: plain GW without adhesion, so no pull-off"),
    })
}
