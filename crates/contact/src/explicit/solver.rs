//! The explicit solver: active-set Newton on the shoe's potential energy.
//!
//! This file holds [`ExplicitSolver`] itself: construction, settings, the choice of the law's
//! implementation and [`ExplicitSolver::solve`]. The phases live in the submodules:
//! * `geometry`: the height-sorted summits, the shoe's basis, the contact set and pose;
//! * `pass` and `fast`: the evaluation pass (contact search, gradient, Hessian), generic and
//!   vectorised; `eval`: what a pass returns;
//! * `newton`: the Newton iteration of one solve (active-set updates, trust radius, line search);
//!   `direction` and `exact_hessian`: its directions; `shortcuts`: the extrapolated first step
//!   and the linear last step;
//! * `load_path`: sweeps, the pull-off search and the loading curve; `report`: the results.

use std::sync::atomic::{AtomicU64, Ordering};

use stiction_surface::{Radii, Surface};

mod direction;
mod eval;
mod exact_hessian;
mod fast;
mod geometry;
mod load_path;
mod newton;
mod pass;
mod report;
mod shortcuts;
#[cfg(test)]
mod tests;

use super::laws::{HertzDmt, JkrPerSummit, LawEval, MdPerSummit, MdTables, Uniform, Wet};
use super::types::*;
use crate::single::{AdhesionLaw, AsperityParams, SummitModel};
use geometry::{Geom, State, interference, tilt_basis};
use newton::equilibrate;

enum LawImpl {
    HertzDmt {
        inv_d: f64,
        two_pi_dgamma: f64,
    },
    Uniform(Box<Uniform>),
    JkrPerSummit,
    /// Maugis-Dugdale with per-summit radii: normalised tables on a grid of radii.
    MdPerSummit(Box<MdTables>),
}

/// The explicit asperity-by-asperity contact solver: a rigid flat shoe on a rough surface.
///
/// See the [module documentation](super) for the method. Holds the summits sorted by descending
/// height (its search structure) and the current contact state, so successive calls of
/// [`ExplicitSolver::solve`] follow the load path (hysteresis, jump-in, pull-off).
pub struct ExplicitSolver {
    geom: Geom,
    law: AdhesionLaw,
    params: AsperityParams,
    imp: LawImpl,
    config: SolverConfig,
    state: State,
    scratch: Vec<u32>,
    /// One mean summit's adhesive pull-off (scale), N.
    adhesion_ref: f64,
    /// The same without a meniscus, N.
    adhesion_ref_dry: f64,
    height_range: f64,
    /// The meniscus of every summit within the meniscus height (None: dry).
    wet: Option<Meniscus>,
    /// Bit set of the sorted summits in solid contact at the last equilibrium (empty when dry or
    /// with Hertz/DMT, whose solid contact is z >= 0 without history), see [`Wet`].
    solid: Vec<u64>,
}

fn invalid(field: &'static str, value: impl ToString, expected: impl ToString) -> SolveError {
    SolveError::InvalidInput { field, value: value.to_string(), expected: expected.to_string() }
}

impl ExplicitSolver {
    /// Builds a solver for `surface` with the single-asperity `law` and the interface `params`
    /// (compliance D, work of adhesion, equilibrium spacing; `params.radius_m` is not used: every
    /// summit has its own radius from the surface).
    ///
    /// Takes the surface by value and reorders it by descending height in place (no copy; the
    /// result's indices refer to the surface as given). Memory: 16 B per summit (uniform radius)
    /// or 24 B (per-summit radii), plus 4 B for the index map when the surface was not already
    /// sorted (generated surfaces are), plus 1 bit for the contact set.
    ///
    /// Maugis-Dugdale with per-summit radii tabulates the normalised law on a grid of radii
    /// log-spaced over the surface's range (step 0.05 in ln R, about 0.7 ms per table; one table
    /// when all radii are equal) and interpolates between neighbouring tables (docs/explicit-solver.md).
    ///
    /// Errors: invalid parameters or configuration.
    pub fn new(
        mut surface: Surface,
        law: AdhesionLaw,
        params: AsperityParams,
        config: SolverConfig,
    ) -> Result<Self, SolveError> {
        let mean_r = surface.mean_radius_m();
        let check = AsperityParams { radius_m: if mean_r.is_finite() { mean_r } else { 1.0 }, ..params };
        check.validate().map_err(|e| invalid("params", format!("{params:?}"), e.to_string()))?;
        if !(config.shear_strength_pa.is_finite() && config.shear_strength_pa >= 0.0) {
            return Err(invalid("shear_strength_pa", config.shear_strength_pa, "a finite value >= 0 Pa"));
        }
        if let Some(h) = config.hardness_pa
            && !(h.is_finite() && h > 0.0)
        {
            return Err(invalid("hardness_pa", h, "a finite value > 0 Pa"));
        }
        if !(config.relative_tolerance > 0.0 && config.relative_tolerance <= 1e-3) {
            return Err(invalid("relative_tolerance", config.relative_tolerance, "a value in (0, 1e-3]"));
        }
        if surface.is_empty() {
            return Err(invalid("surface", "0 summits", "at least one summit"));
        }
        let original =
            if surface.is_sorted_by_height_descending() { None } else { Some(surface.sort_by_height_descending()) };
        let (length, width, xs, ys, hs, radii) = surface.into_parts();
        let ell = 0.5 * length.hypot(width);
        let n = hs.len();
        let (load_point, basis, ndof, support) = match config.mode {
            ShoeMode::TiltFree | ShoeMode::Flat => {
                let lp = config.load_point_m.unwrap_or((0.5 * length, 0.5 * width));
                if !(lp.0.is_finite() && lp.1.is_finite()) {
                    return Err(invalid("load_point_m", format!("{lp:?}"), "finite coordinates in m"));
                }
                if config.mode == ShoeMode::Flat {
                    (lp, [[1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]], 1, None)
                } else {
                    (lp, tilt_basis(lp, ell), 3, None)
                }
            }
            ShoeMode::FixedContacts { count } => {
                if count == 0 || count > n {
                    return Err(invalid("contacts", count, format!("1 ..= {n} (the number of summits)")));
                }
                let pts: Vec<(f64, f64)> = (0..count).map(|i| (f64::from(xs[i]), f64::from(ys[i]))).collect();
                let c = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0 / count as f64, a.1 + p.1 / count as f64));
                match count {
                    1 => (c, [[1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]], 1, Some(1)),
                    2 => {
                        let (dx, dy) = (pts[1].0 - pts[0].0, pts[1].1 - pts[0].1);
                        let len = dx.hypot(dy);
                        if len == 0.0 {
                            (c, [[1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]], 1, Some(2))
                        } else {
                            let (ex, ey) = (dx / len / ell, dy / len / ell);
                            (c, [[1.0, 0.0, 0.0], [-(ex * c.0 + ey * c.1), ex, ey], [0.0; 3]], 2, Some(2))
                        }
                    }
                    _ => (c, tilt_basis(c, ell), 3, Some(count)),
                }
            }
        };
        let imp = match (law, &radii) {
            (_, _)
                if params.work_of_adhesion_j_per_m2 == 0.0 || matches!(law, AdhesionLaw::Hertz | AdhesionLaw::Dmt) =>
            {
                let dg = if law == AdhesionLaw::Hertz { 0.0 } else { params.work_of_adhesion_j_per_m2 };
                LawImpl::HertzDmt {
                    inv_d: 1.0 / params.compliance_per_pa,
                    two_pi_dgamma: 2.0 * std::f64::consts::PI * dg,
                }
            }
            (_, Radii::Uniform(r)) => {
                let model = SummitModel::new(law, AsperityParams { radius_m: *r, ..params })
                    .map_err(|e| invalid("params", format!("{params:?}"), e.to_string()))?;
                LawImpl::Uniform(Box::new(Uniform::new(model)))
            }
            (AdhesionLaw::Jkr, Radii::PerSummit(_)) => LawImpl::JkrPerSummit,
            // Maugis-Dugdale (Hertz, DMT and JKR are matched above).
            (_, Radii::PerSummit(r)) => {
                let tables =
                    MdTables::new(params, r).map_err(|e| invalid("params", format!("{params:?}"), e.to_string()))?;
                LawImpl::MdPerSummit(Box::new(tables))
            }
        };
        let adhesion_ref = 2.0 * std::f64::consts::PI * params.work_of_adhesion_j_per_m2 * check.radius_m;
        let height_range = (hs[0] - hs[n - 1]).max(1e-12);
        let hardness = config.hardness_pa.unwrap_or(f64::INFINITY);
        let uv = support.is_none().then_some((load_point.0, load_point.1, 1.0 / ell));
        let geom = Geom {
            xs,
            ys,
            hs,
            radii,
            original,
            length,
            width,
            basis,
            ndof,
            load_point,
            hardness,
            support,
            uv,
            shortcuts: true,
            passes: AtomicU64::new(0),
            scanned: AtomicU64::new(0),
        };
        let state = State {
            q: [0.0; 3],
            member: vec![0; n.div_ceil(64)],
            bound: 0,
            members: 0,
            tau: 0.0,
            generation: 0,
            cache: None,
            history: [(0.0, [0.0; 3]); 3],
            history_len: 0,
            member_dx: 0.0,
            member_dy: 0.0,
        };
        let mut s = Self {
            geom,
            law,
            params,
            imp,
            config,
            state,
            scratch: Vec::new(),
            adhesion_ref,
            adhesion_ref_dry: adhesion_ref,
            height_range,
            wet: None,
            solid: Vec::new(),
        };
        s.reset();
        Ok(s)
    }

    /// Returns to the initial state: no load history, the shoe flat and just touching the highest
    /// summit (for `FixedContacts`: its lowest support), so the next solve is an approach.
    pub fn reset(&mut self) {
        let n = self.geom.hs.len();
        self.state.history_len = 0;
        self.state.member_dx = 0.0;
        self.state.member_dy = 0.0;
        self.state.member.iter_mut().for_each(|w| *w = 0);
        self.solid.iter_mut().for_each(|w| *w = 0);
        self.state.members = 0;
        self.state.bound = 0;
        // (The dry law's jump-in also with menisci: the shoe starts touching the highest summit, not
        // at its meniscus height, where a bridged summit's zero pull would balance a zero load on
        // the unstable branch of its meniscus.)
        let z_in0 = self.with_dry_law(|_, law| law.z_in(0));
        let top = match self.geom.support {
            Some(k) => {
                for i in 0..k {
                    self.state.join(&self.geom, i);
                }
                self.geom.hs[k - 1]
            }
            None => {
                // Just touching: the highest summit's interference must reach its jump-in value
                // also after rounding (Maugis-Dugdale: z_in < 0, so h - (h - z_in) may fall short).
                let h0 = self.geom.hs[0];
                let mut top = h0 - z_in0;
                while h0 - top < z_in0 {
                    top = top.next_down();
                }
                top
            }
        };
        // q with the plane flat at `top`: only the constant basis function has a constant term.
        self.state.q = [top, 0.0, 0.0];
        let _ = n;
        self.state.tau = self.initial_tau(0.0);
    }

    fn initial_tau(&self, load: f64) -> f64 {
        // Interference at which one mean summit would carry max(|L|, its adhesion) (Hertz, eq. 3b).
        let r = self.geom.radius(0);
        let f = load.abs().max(self.adhesion_ref).max(1e-15);
        (f * self.params.compliance_per_pa / r.sqrt()).powf(2.0 / 3.0).max(1e-9 * self.height_range)
    }

    /// Number of summits.
    pub fn len(&self) -> usize {
        self.geom.hs.len()
    }

    /// True if the solver holds no summit (never: construction requires one).
    pub fn is_empty(&self) -> bool {
        self.geom.hs.is_empty()
    }

    /// The configuration.
    pub fn config(&self) -> &SolverConfig {
        &self.config
    }

    /// Changes the shear strength used for the friction capacity \[Pa\].
    pub fn set_shear_strength(&mut self, shear_strength_pa: f64) -> Result<(), SolveError> {
        if !(shear_strength_pa.is_finite() && shear_strength_pa >= 0.0) {
            return Err(invalid("shear_strength_pa", shear_strength_pa, "a finite value >= 0 Pa"));
        }
        self.config.shear_strength_pa = shear_strength_pa;
        Ok(())
    }

    /// Changes the per-summit detail of results.
    pub fn set_detail(&mut self, detail: Detail) {
        self.config.detail = detail;
    }

    /// Puts a meniscus ([`Meniscus`]) in equilibrium with the vapour at every summit whose gap to
    /// the shoe is below the meniscus height, in solid contact or not (None: dry, the default), and
    /// returns to the initial state ([`Self::reset`]). The meniscus force is a function of the gap alone (condensation and
    /// rupture at `h_m`); the dry law keeps its own hysteresis. A dry solver (None) is exactly the
    /// solver without this call.
    ///
    /// Errors: a force per radius or a meniscus height that is not finite and > 0.
    pub fn set_meniscus(&mut self, meniscus: Option<Meniscus>) -> Result<(), SolveError> {
        if let Some(m) = meniscus {
            if !(m.force_per_radius_n_per_m.is_finite() && m.force_per_radius_n_per_m > 0.0) {
                return Err(invalid(
                    "meniscus.force_per_radius_n_per_m",
                    m.force_per_radius_n_per_m,
                    "a finite value > 0 N/m",
                ));
            }
            if !(m.height_m.is_finite() && m.height_m > 0.0) {
                return Err(invalid("meniscus.height_m", m.height_m, "a finite value > 0 m"));
            }
        }
        self.wet = meniscus;
        self.solid = if meniscus.is_some() { vec![0; self.geom.hs.len().div_ceil(64)] } else { Vec::new() };
        let mean_r = match &self.geom.radii {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(v) => v.iter().sum::<f64>() / v.len() as f64,
        };
        self.adhesion_ref = match meniscus {
            Some(m) => self.adhesion_ref_dry + m.force_per_radius_n_per_m * mean_r,
            None => self.adhesion_ref_dry,
        };
        self.reset();
        Ok(())
    }

    /// After an equilibrium: the members in solid contact there ([`Wet::solid`]), the history of
    /// the dry law's hysteresis for the next solve. Hertz/DMT (solid contact is z >= 0) keep none.
    fn update_solid(&mut self) {
        let Some(m) = self.wet else { return };
        if matches!(self.imp, LawImpl::HertzDmt { .. }) {
            return;
        }
        let mut bits = std::mem::take(&mut self.solid);
        let q = self.state.q;
        self.with_dry_law(|g, dry| {
            let law = Wet {
                dry,
                radii: &g.radii,
                solid: &bits,
                force_per_radius_n_per_m: m.force_per_radius_n_per_m,
                height_m: m.height_m,
            };
            let mut next = vec![0u64; bits.len()];
            for (w, word) in self.state.member.iter().enumerate() {
                let mut b = *word;
                while b != 0 {
                    let i = w * 64 + b.trailing_zeros() as usize;
                    b &= b - 1;
                    if law.solid(i, interference(g, &law, &q, i)) {
                        next[w] |= 1 << (i & 63);
                    }
                }
            }
            bits = next;
        });
        self.solid = bits;
    }

    /// The meniscus in use (None: dry).
    pub fn meniscus(&self) -> Option<Meniscus> {
        self.wet
    }

    /// Work done since construction: evaluation passes over the summits and the summits they
    /// scanned (the height-sorted prefix that can touch, plus the members). Diagnostics for
    /// performance measurements (cost per scanned summit); not part of any result.
    pub fn work(&self) -> WorkCounters {
        WorkCounters {
            passes: self.geom.passes.load(Ordering::Relaxed),
            summits_scanned: self.geom.scanned.load(Ordering::Relaxed),
        }
    }

    /// Switches the two shortcuts of the Newton iteration on (default) or off: the first step of a
    /// solve extrapolated from the last three equilibria, and the last step applied by
    /// linearisation without a confirming pass when no summit can change its contact state
    /// (docs/explicit-solver.md, "Passes per load point"). Off, every step is confirmed by a pass
    /// and the first step is the Newton step, as before these shortcuts. For comparisons and
    /// tests; the equilibria agree to the solver tolerance.
    pub fn set_shortcuts(&mut self, on: bool) {
        self.geom.shortcuts = on;
    }

    /// Heap bytes per summit held by the solver: summit arrays, index map and contact bit set.
    pub fn bytes_per_summit(&self) -> f64 {
        let g = &self.geom;
        let mut b = g.xs.capacity() * 4 + g.ys.capacity() * 4 + g.hs.capacity() * 8 + self.state.member.capacity() * 8;
        if let Radii::PerSummit(r) = &g.radii {
            b += r.capacity() * 8;
        }
        if let Some(o) = &g.original {
            b += o.capacity() * 4;
        }
        b as f64 / g.hs.len() as f64
    }

    fn with_law<R>(&self, f: impl FnOnce(&Geom, &dyn LawEval) -> R) -> R {
        if let Some(m) = self.wet {
            return self.with_dry_law(|g, dry| {
                let law = Wet {
                    dry,
                    radii: &g.radii,
                    solid: &self.solid,
                    force_per_radius_n_per_m: m.force_per_radius_n_per_m,
                    height_m: m.height_m,
                };
                f(g, &law)
            });
        }
        self.with_dry_law(f)
    }

    fn with_dry_law<R>(&self, f: impl FnOnce(&Geom, &dyn LawEval) -> R) -> R {
        match &self.imp {
            LawImpl::HertzDmt { inv_d, two_pi_dgamma } => {
                f(&self.geom, &HertzDmt { inv_d: *inv_d, two_pi_dgamma: *two_pi_dgamma, radii: &self.geom.radii })
            }
            LawImpl::Uniform(u) => f(&self.geom, u.as_ref()),
            LawImpl::JkrPerSummit => match &self.geom.radii {
                Radii::PerSummit(r) => f(&self.geom, &JkrPerSummit::new(self.params, r)),
                Radii::Uniform(_) => unreachable!("JkrPerSummit is only built for per-summit radii"),
            },
            LawImpl::MdPerSummit(t) => match &self.geom.radii {
                Radii::PerSummit(r) => f(&self.geom, &MdPerSummit { params: self.params, radii: r, tables: t }),
                Radii::Uniform(_) => unreachable!("MdPerSummit is only built for per-summit radii"),
            },
        }
    }

    /// Solves for the equilibrium under the normal load `load_n` \[N\] (compressive positive),
    /// starting from the current state: successive calls follow a quasi-static load path.
    ///
    /// Errors: [`SolveError::NoEquilibrium`] when the shoe comes off (load below the pull-off of
    /// the current contact) or tips over, [`SolveError::ContactLost`] in `FixedContacts` mode,
    /// [`SolveError::NotConverged`]. On error the state is restored to what it was before.
    pub fn solve(&mut self, load_n: f64) -> Result<Equilibrium, SolveError> {
        if !load_n.is_finite() {
            return Err(invalid("load_n", load_n, "a finite load in N"));
        }
        let backup = self.state.clone();
        // The dry law, or the dry law with a meniscus within h_m of the shoe (one monomorphised
        // iteration per law: the dry path is exactly the solver without menisci).
        macro_rules! run {
            ($dry:expr) => {{
                let dry = $dry;
                match self.wet {
                    None => equilibrate(
                        &self.geom,
                        dry,
                        &mut self.state,
                        &mut self.scratch,
                        load_n,
                        &self.config,
                        self.adhesion_ref,
                        self.height_range,
                    ),
                    Some(m) => {
                        let wet = Wet {
                            dry,
                            radii: &self.geom.radii,
                            solid: &self.solid,
                            force_per_radius_n_per_m: m.force_per_radius_n_per_m,
                            height_m: m.height_m,
                        };
                        equilibrate(
                            &self.geom,
                            &wet,
                            &mut self.state,
                            &mut self.scratch,
                            load_n,
                            &self.config,
                            self.adhesion_ref,
                            self.height_range,
                        )
                    }
                }
            }};
        }
        let res = match &self.imp {
            LawImpl::HertzDmt { inv_d, two_pi_dgamma } => {
                run!(&HertzDmt { inv_d: *inv_d, two_pi_dgamma: *two_pi_dgamma, radii: &self.geom.radii })
            }
            LawImpl::Uniform(u) => run!(u.as_ref()),
            LawImpl::JkrPerSummit => {
                let Radii::PerSummit(r) = &self.geom.radii else { unreachable!() };
                run!(&JkrPerSummit::new(self.params, r))
            }
            LawImpl::MdPerSummit(t) => {
                let Radii::PerSummit(r) = &self.geom.radii else { unreachable!() };
                run!(&MdPerSummit { params: self.params, radii: r, tables: t })
            }
        };
        if res.is_ok() && self.wet.is_some() {
            self.update_solid();
        }
        match res {
            Ok(iterations) => Ok(self.report(load_n, iterations)),
            Err(e) => {
                self.state = backup;
                Err(e)
            }
        }
    }

    /// The single-asperity law in use.
    pub fn law(&self) -> AdhesionLaw {
        self.law
    }
}
