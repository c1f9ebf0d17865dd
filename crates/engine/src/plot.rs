//! `plot`: the numbers of the paper's figures 2 and 3 (GW + DMT curves, a scenario's theta); the
//! charts themselves are drawn by the front end from these curves.

use std::path::Path;

use stiction_contact::gw;
use stiction_scenario::Scenario;

/// The GW pull-off (L* = -P_c*, A* there), which Fig. 3 marks.
pub use stiction_contact::gw::GwPullOff;

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

/// N* at L* = 0 of a theta (eq. 5a, 8), as a value and as its log10 (N* underflows f64 for theta
/// above about 10^3).
#[derive(Clone, Copy, Debug)]
pub struct ZeroLoadContacts {
    /// N*, the fraction of summits in contact at zero load.
    pub n_star: f64,
    /// log10 N*.
    pub log10_n_star: f64,
}

/// The numbers of Fig. 2: N*(L* = 0) against theta from 0.5 up (to 40, or to 1.5 times a
/// scenario's theta where its N* can be drawn), and the scenario's own N*.
pub struct Fig2Curves {
    /// (theta, N*) along the axis.
    pub curve: Vec<(f64, f64)>,
    /// The scenario's theta and N* at L* = 0, when a theta was given.
    pub scenario: Option<(f64, ZeroLoadContacts)>,
    /// Whether the scenario's N* is above 1e-250 (drawn on the axis; else named in a note).
    pub drawable: bool,
}

/// Fig. 2's curve (GW + DMT, eq. 5a, 8) and, with `theta` (a scenario's, eq. 9), its N*.
pub fn fig2_curves(theta: Option<f64>) -> Result<Fig2Curves, Error> {
    let state = theta.map(|t| gw::GwModel::new(Some(t)).and_then(|m| m.solve(0.0))).transpose()?;
    let drawable = state.as_ref().is_some_and(|st| st.log10_n_star > -250.0);
    let top = match (theta, drawable) {
        (Some(t), true) => (t * 1.5).max(40.0),
        _ => 40.0,
    };
    let curve = gw::fig2_series(0.5, top, if top > 40.0 { 160 } else { 80 })?;
    let scenario =
        theta.zip(state).map(|(t, st)| (t, ZeroLoadContacts { n_star: st.n_star, log10_n_star: st.log10_n_star }));
    Ok(Fig2Curves { curve, scenario, drawable })
}

/// One curve of Fig. 3: A* against L* (GW + DMT, eq. 5b, 8) for one theta.
pub struct Fig3Curve {
    /// (L*, A*) from the pull-off load (or L* = 1e-6 without adhesion) to L* = 1, the loads
    /// spaced evenly in sign(L*) log10(1 + |L*|/1e-6), so both branches get points.
    pub points: Vec<(f64, f64)>,
    /// The pull-off (L* = -P_c*), where the model has one.
    pub pull_off: Option<GwPullOff>,
}

/// The Fig. 3 curve of `theta` (None: no adhesion, theta = infinity), 240 points.
pub fn fig3_curve(theta: Option<f64>) -> Result<Fig3Curve, Error> {
    let model = gw::GwModel::new(theta)?;
    let pull_off = model.pull_off();
    let start = match (theta, &pull_off) {
        (Some(_), Some(po)) => po.l_star,
        _ => 1e-6,
    };
    let points = symlog_series(&model, start, 1.0, 240)?;
    Ok(Fig3Curve { points, pull_off })
}

/// `n` points of A*(L*) from `from` to `to`, evenly spaced in sign(L*) log10(1 + |L*|/1e-6).
fn symlog_series(model: &gw::GwModel, from: f64, to: f64, n: usize) -> Result<Vec<(f64, f64)>, Error> {
    let c = 1e-6;
    let f = |v: f64| v.signum() * (v.abs() / c).ln_1p();
    let g = |t: f64| t.signum() * c * t.abs().exp_m1();
    let (a, b) = (f(from), f(to));
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let l = if i == 0 {
            from
        } else if i + 1 == n {
            to
        } else {
            g(a + (b - a) * i as f64 / (n - 1) as f64)
        };
        out.push((l, model.solve(l)?.a_star));
    }
    Ok(out)
}
