//! The explicit solver: active-set Newton on the shoe's potential energy.

use std::sync::atomic::{AtomicU64, Ordering};

use nalgebra::Matrix3;
use stiction_surface::{Radii, Surface};

mod fast;

use super::laws::{HertzDmt, JkrPerSummit, LawEval, MdPerSummit, MdTables, Resp, Uniform, Wet};
use super::types::*;
use crate::single::{AdhesionLaw, AsperityParams, Branch, SummitModel};

/// Summits sorted by descending height plus the rigid-body basis of the shoe.
struct Geom {
    xs: Vec<f32>,
    ys: Vec<f32>,
    hs: Vec<f64>,
    radii: Radii,
    /// Surface index of each sorted summit (None: the surface was already sorted).
    original: Option<Vec<u32>>,
    length: f64,
    width: f64,
    /// Basis functions phi_j(x, y) = b\[j\]\[0\] + b\[j\]\[1\] x + b\[j\]\[2\] y of the plane
    /// w = sum_j q_j phi_j; unused rows are zero.
    basis: [[f64; 3]; 3],
    ndof: usize,
    load_point: (f64, f64),
    /// Hardness for the elastic-limit count (infinite without one), Pa.
    hardness: f64,
    /// FixedContacts: number of supports (the first `n` sorted summits).
    support: Option<usize>,
    /// Tilt-free and flat modes: (x0, y0, 1/l), the basis is phi = (1, (x - x0)/l, (y - y0)/l)
    /// (flat: its first function only); enables the fast pass.
    uv: Option<(f64, f64, f64)>,
    /// Allow the final Newton step without a pass ([`linear_step`]) and the extrapolated first
    /// step ([`predictor`]); off only for comparisons ([`ExplicitSolver::set_shortcuts`]).
    shortcuts: bool,
    /// Evaluation passes and summits scanned by them since construction (diagnostics).
    passes: AtomicU64,
    scanned: AtomicU64,
}

impl Geom {
    #[inline(always)]
    fn plane(&self, q: &[f64; 3]) -> (f64, f64, f64) {
        let mut p = (0.0, 0.0, 0.0);
        for (qj, b) in q.iter().zip(&self.basis) {
            p.0 += qj * b[0];
            p.1 += qj * b[1];
            p.2 += qj * b[2];
        }
        p
    }
    fn phi_at(&self, x: f64, y: f64) -> [f64; 3] {
        let b = &self.basis;
        [b[0][0] + b[0][1] * x + b[0][2] * y, b[1][0] + b[1][1] * x + b[1][2] * y, b[2][0] + b[2][1] * x + b[2][2] * y]
    }
    /// Largest |change of the plane height| over the apparent area for a step `dq`.
    fn movement(&self, dq: &[f64; 3]) -> f64 {
        let (a, b, c) = self.plane(dq);
        let mut m: f64 = 0.0;
        for (x, y) in [(0.0, 0.0), (self.length, 0.0), (0.0, self.width), (self.length, self.width)] {
            m = m.max((a + b * x + c * y).abs());
        }
        m
    }
    fn original_index(&self, i: usize) -> u32 {
        match &self.original {
            Some(o) => o[i],
            None => i as u32,
        }
    }
    fn radius(&self, i: usize) -> f64 {
        match &self.radii {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(v) => v[i],
        }
    }
}

/// Contact set and pose; cloned to back up during pull-off searches.
#[derive(Clone, Debug)]
struct State {
    q: [f64; 3],
    /// Bit set of the sorted summits in contact.
    member: Vec<u64>,
    /// All members have sorted index < bound.
    bound: usize,
    members: usize,
    /// Trust radius: largest plane movement per step, m.
    tau: f64,
    /// Incremented whenever the contact set changes.
    generation: u64,
    /// Last evaluation at `q` with the load term removed, valid for `generation`.
    cache: Option<(u64, [f64; 3], Eval)>,
    /// The last (up to) three equilibria (load, pose) of successive solves, oldest first.
    history: [(f64, [f64; 3]); 3],
    history_len: usize,
    /// Sums of (x - x0) and (y - y0) over the members \[m\] (kept by [`State::join`] and
    /// [`State::leave`]; the area's linearisation in [`linear_step`]).
    member_dx: f64,
    member_dy: f64,
}

impl State {
    #[inline(always)]
    fn is_member(&self, i: usize) -> bool {
        (self.member[i >> 6] >> (i & 63)) & 1 == 1
    }
    fn set(&mut self, i: usize) {
        if !self.is_member(i) {
            self.member[i >> 6] |= 1 << (i & 63);
            self.members += 1;
            self.generation += 1;
            self.bound = self.bound.max(i + 1);
        }
    }
    fn clear(&mut self, i: usize) {
        if self.is_member(i) {
            self.member[i >> 6] &= !(1 << (i & 63));
            self.members -= 1;
            self.generation += 1;
        }
    }
    /// [`State::set`], keeping the members' coordinate sums.
    fn join(&mut self, g: &Geom, i: usize) {
        if !self.is_member(i) {
            self.set(i);
            self.member_dx += f64::from(g.xs[i]) - g.load_point.0;
            self.member_dy += f64::from(g.ys[i]) - g.load_point.1;
        }
    }
    /// [`State::clear`], keeping the members' coordinate sums.
    fn leave(&mut self, g: &Geom, i: usize) {
        if self.is_member(i) {
            self.clear(i);
            self.member_dx -= f64::from(g.xs[i]) - g.load_point.0;
            self.member_dy -= f64::from(g.ys[i]) - g.load_point.1;
        }
    }
}

#[derive(Clone, Copy, Debug, Default)]
struct Eval {
    g: [f64; 3],
    h: [[f64; 3]; 3],
    force: f64,
    force_abs: f64,
    releases: usize,
    contacts: usize,
    /// Totals over members and touchers on the contact branch (for the result without a second pass).
    area: f64,
    elastic: f64,
    q0_max: f64,
    over_limit: usize,
    moment_x: f64,
    moment_y: f64,
    /// Words of the contact bit set that can hold a member past release (first, last), when the
    /// pass knows them (the fast pass); `None`: any word.
    release_words: Option<(usize, usize)>,
    /// What a Newton step without a pass needs (the fast pass only; see [`linear_step`]).
    lin: Option<Linear>,
    /// Menisci only: their total pull and the number of summits in solid contact (contact
    /// radius > 0), at an equilibrium (no member past release).
    capillary: f64,
    solid: usize,
    /// Members were released from this evaluation without a new pass: `capillary` and `solid`
    /// are stale.
    released: bool,
}

/// Quantities of a fast pass beyond the gradient and Hessian, for a final Newton step applied by
/// linearisation instead of a new pass ([`linear_step`]).
#[derive(Clone, Copy, Debug, Default)]
struct Linear {
    /// Smallest z of the summits in contact with z >= 0 \[m\]: a summit's z may fall by less
    /// without any of them releasing.
    gap_in: f64,
    /// Lower bound of |z| over all other summits (scanned ones exactly, the others by the height
    /// threshold of the prefix) \[m\]: a summit's z may rise by less without any of them touching.
    gap_out: f64,
    /// Lower bound of |z - z_hard| over the summits in contact (infinite without a hardness) \[m\].
    hard_gap: f64,
    /// sum k u, sum k v (the flat shoe's Hessian holds only sum k).
    k_uv: [f64; 2],
    /// Menisci: the magnitude of a tail's (negative) stiffness f R / h_m (0 when dry) \[N/m\].
    tail_k: f64,
    /// Menisci: the bridged summits' number and sums of u, v, u^2, u v, v^2 (zero when dry).
    tail: [f64; 6],
}

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

    /// Solves a sequence of loads in order, each from the previous equilibrium.
    ///
    /// `direction` states the intent (`Loading`: loads must not decrease; `Unloading`: must not
    /// increase); each summit follows its own hysteresis (JKR/MD) whatever the direction. Contact
    /// changes are reported as [`SweepEvent::JumpIn`] / [`SweepEvent::Release`]; when the shoe comes
    /// off, a [`SweepEvent::PullOff`] ends the sweep (the remaining loads are not solved).
    pub fn sweep(&mut self, loads_n: &[f64], direction: Branch) -> Result<Sweep, SolveError> {
        for w in loads_n.windows(2) {
            let ok = match direction {
                Branch::Loading => w[1] >= w[0],
                Branch::Unloading => w[1] <= w[0],
            };
            if !ok {
                return Err(invalid(
                    "loads_n",
                    format!("{} then {}", w[0], w[1]),
                    format!(
                        "{} loads for a {direction} sweep",
                        if direction == Branch::Loading { "non-decreasing" } else { "non-increasing" }
                    ),
                ));
            }
        }
        let mut points: Vec<Equilibrium> = Vec::with_capacity(loads_n.len());
        let mut events = Vec::new();
        let mut before = self.state.members;
        for &l in loads_n {
            match self.solve(l) {
                Ok(eq) => {
                    let after = eq.contacts;
                    let point = points.len();
                    if after > before {
                        events.push(SweepEvent::JumpIn {
                            point,
                            load_n: l,
                            contacts_before: before,
                            contacts_after: after,
                        });
                    } else if after < before {
                        events.push(SweepEvent::Release {
                            point,
                            load_n: l,
                            contacts_before: before,
                            contacts_after: after,
                        });
                    }
                    before = after;
                    points.push(eq);
                }
                Err(SolveError::NoEquilibrium { .. }) if direction == Branch::Unloading => {
                    let last = points.last().map(|p| p.load_n);
                    let note = last.is_none().then(|| {
                        "the first load of the sweep has no equilibrium: the shoe is off at every load of it"
                            .to_string()
                    });
                    events.push(SweepEvent::PullOff { load_n: l, last_stable_load_n: last, note });
                    break;
                }
                Err(e) => return Err(e),
            }
        }
        Ok(Sweep { points, events })
    }

    /// Unloads from the current equilibrium until the shoe comes off and returns the last
    /// equilibrium: its load is the pull-off load of this contact history, found by bisection to
    /// `relative_tolerance_load` of the adhesion scale (the state is left at that equilibrium).
    /// The current state must be an equilibrium at `from_load_n` (call [`Self::solve`] first).
    pub fn pull_off(&mut self, from_load_n: f64, relative_tolerance_load: f64) -> Result<Equilibrium, SolveError> {
        let mut hi_eq = self.solve(from_load_n)?;
        let scale = self.adhesion_ref.max(1e-3 * from_load_n.abs()).max(1e-15);
        let mut step = scale;
        // Bracket: walk down until no equilibrium.
        let mut lo;
        loop {
            let trial = hi_eq.load_n - step;
            match self.solve(trial) {
                Ok(eq) => {
                    hi_eq = eq;
                    step *= 2.0;
                }
                Err(SolveError::NoEquilibrium { .. }) => {
                    lo = trial;
                    break;
                }
                Err(e) => return Err(e),
            }
            if step > 1e6 * scale * (self.len() as f64) {
                return Err(SolveError::NoEquilibrium {
                    load_n: trial,
                    reason: "no pull-off found: contact never breaks".into(),
                });
            }
        }
        while hi_eq.load_n - lo > relative_tolerance_load * scale {
            let mid = 0.5 * (lo + hi_eq.load_n);
            match self.solve(mid) {
                Ok(eq) => hi_eq = eq,
                Err(SolveError::NoEquilibrium { .. }) => lo = mid,
                Err(e) => return Err(e),
            }
        }
        Ok(hi_eq)
    }

    /// The loading curve the paper's experiments follow: from the initial state the shoe is
    /// brought into contact at zero load, unloaded to its pull-off ([`Self::pull_off`]), then loaded
    /// in `points` equal steps from the pull-off load to `max_load_n`.
    pub fn loading_curve(&mut self, max_load_n: f64, points: usize) -> Result<Sweep, SolveError> {
        if points < 2 {
            return Err(invalid("points", points, "at least 2"));
        }
        self.reset();
        let po = self.pull_off(0.0, 1e-6)?;
        let l0 = po.load_n;
        if max_load_n <= l0 {
            return Err(invalid("max_load_n", max_load_n, format!("a load above the pull-off load {l0:e} N")));
        }
        let loads: Vec<f64> = (0..points).map(|k| l0 + (max_load_n - l0) * k as f64 / (points - 1) as f64).collect();
        self.sweep(&loads, Branch::Loading)
    }

    /// Contact state for a prescribed pose, without equilibrium: every summit with interference
    /// `z >= z_in` (the approach rule; Hertz/DMT: z > 0 counts, z = 0 carries no area) is in
    /// contact. `load_n` of the result is the total contact force sum P_i (the load this pose
    /// needs), the force residual is 0. Used to compare with GW's integrals at fixed separation.
    pub fn evaluate_pose(&mut self, separation_m: f64, tilt_x_rad: f64, tilt_y_rad: f64) -> Equilibrium {
        let saved = self.state.clone();
        let saved_solid = std::mem::take(&mut self.solid);
        self.solid = vec![0; saved_solid.len()];
        self.state.member.iter_mut().for_each(|w| *w = 0);
        self.state.members = 0;
        self.state.bound = 0;
        // Pose -> q: solve the basis for the plane (A, B, C) with w(x0, y0) = separation.
        let (x0, y0) = self.geom.load_point;
        let a = separation_m - tilt_x_rad * x0 - tilt_y_rad * y0;
        self.state.q = self.q_from_plane(a, tilt_x_rad, tilt_y_rad);
        let mut touch = std::mem::take(&mut self.scratch);
        self.with_law(|g, law| {
            let _ = evaluate(g, law, &State { ..self.state.clone() }, &self.state.q, 0.0, true, false, &mut touch);
        });
        for &i in &touch {
            self.state.set(i as usize);
        }
        self.scratch = touch;
        let mut eq = self.report(0.0, 0);
        eq.load_n -= eq.force_residual_n;
        eq.force_residual_n = 0.0;
        self.state = saved;
        self.solid = saved_solid;
        eq
    }

    fn q_from_plane(&self, a: f64, b: f64, c: f64) -> [f64; 3] {
        // Least squares is not needed: the bases are invertible on their span.
        let g = &self.geom;
        match g.ndof {
            1 => [a + b * g.load_point.0 + c * g.load_point.1, 0.0, 0.0],
            _ => {
                // Solve M q = (a, b, c) for the used columns (tilt basis: exact).
                let m = Matrix3::new(
                    g.basis[0][0],
                    g.basis[1][0],
                    g.basis[2][0],
                    g.basis[0][1],
                    g.basis[1][1],
                    g.basis[2][1],
                    g.basis[0][2],
                    g.basis[1][2],
                    g.basis[2][2],
                );
                let sol = m.pseudo_inverse(1e-30).map(|p| p * nalgebra::Vector3::new(a, b, c));
                match sol {
                    Ok(v) => [v[0], v[1], v[2]],
                    Err(_) => [a, 0.0, 0.0],
                }
            }
        }
    }

    /// Builds the result for the current state (members are the contacts).
    fn report(&self, load_n: f64, iterations: usize) -> Equilibrium {
        let q = self.state.q;
        let g = &self.geom;
        let (a, b, c) = g.plane(&q);
        let (x0, y0) = g.load_point;
        let detail = self.config.detail;
        let hardness = self.config.hardness_pa;
        let mut e = Equilibrium {
            load_n,
            separation_m: a + b * x0 + c * y0,
            tilt_x_rad: b,
            tilt_y_rad: c,
            load_point_x_m: x0,
            load_point_y_m: y0,
            contacts: self.state.members,
            contact_indices: Vec::new(),
            real_area_m2: 0.0,
            elastic_load_n: 0.0,
            adhesive_load_n: 0.0,
            capillary_load_n: 0.0,
            wetted_summits: 0,
            friction_capacity_n: 0.0,
            max_pressure_pa: 0.0,
            summits_over_elastic_limit: 0,
            force_residual_n: load_n,
            moment_residual_x_n_m: 0.0,
            moment_residual_y_n_m: 0.0,
            iterations,
            summits: Vec::new(),
        };
        if detail == Detail::Summary
            && let Some((generation, cq, ev)) = &self.state.cache
            && (self.wet.is_none() || !ev.released)
            && *generation == self.state.generation
            && *cq == q
        {
            // The last evaluation of the solve holds every total: no second pass.
            e.real_area_m2 = ev.area;
            e.elastic_load_n = ev.elastic;
            e.max_pressure_pa = ev.q0_max;
            e.summits_over_elastic_limit = ev.over_limit;
            e.moment_residual_x_n_m = ev.moment_x;
            e.moment_residual_y_n_m = ev.moment_y;
            e.force_residual_n = load_n - ev.force;
            e.adhesive_load_n = e.elastic_load_n - ev.force;
            e.friction_capacity_n = self.config.shear_strength_pa * e.real_area_m2;
            if self.wet.is_some() {
                e.capillary_load_n = ev.capillary;
                e.wetted_summits = e.contacts;
                e.contacts = ev.solid;
            }
            return e;
        }
        let mut total = 0.0;
        let (mut capillary, mut solid) = (0.0, 0usize);
        self.with_law(|g, law| {
            for i in 0..self.state.bound {
                if !self.state.is_member(i) {
                    continue;
                }
                let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
                let z = g.hs[i] - (a + b * x + c * y);
                let r: Resp = law.contact(i, z);
                if self.wet.is_some() {
                    capillary += law.capillary_n(i, z);
                    solid += usize::from(r.radius > 0.0);
                }
                total += r.load_n;
                e.real_area_m2 += std::f64::consts::PI * r.radius * r.radius;
                e.elastic_load_n += r.elastic_n;
                e.moment_residual_x_n_m += r.load_n * (x - x0);
                e.moment_residual_y_n_m += r.load_n * (y - y0);
                e.max_pressure_pa = e.max_pressure_pa.max(r.q0);
                let over = hardness.is_some_and(|h| r.q0 > h);
                e.summits_over_elastic_limit += usize::from(over);
                if detail != Detail::Summary {
                    e.contact_indices.push(g.original_index(i));
                }
                if detail == Detail::Full {
                    e.summits.push(SummitContact {
                        index: g.original_index(i),
                        x_m: x,
                        y_m: y,
                        height_m: g.hs[i],
                        radius_m: g.radius(i),
                        interference_m: z,
                        load_n: r.load_n,
                        contact_radius_m: r.radius,
                        max_pressure_pa: r.q0,
                        over_elastic_limit: over,
                    });
                }
            }
        });
        e.contact_indices.sort_unstable();
        e.summits.sort_unstable_by_key(|s| s.index);
        e.force_residual_n = load_n - total;
        e.adhesive_load_n = e.elastic_load_n - total;
        if self.wet.is_some() {
            e.capillary_load_n = capillary;
            e.wetted_summits = e.contacts;
            e.contacts = solid;
        }
        e.friction_capacity_n = self.config.shear_strength_pa * e.real_area_m2;
        e
    }

    /// The single-asperity law in use.
    pub fn law(&self) -> AdhesionLaw {
        self.law
    }
}

/// Largest tilt of a tilt-free shoe \[rad\]: beyond it the small-angle plane `w = d + t x` is no
/// longer the shoe face (error 1e-3 of the movement) and the solve reports that the shoe tips over.
/// Equilibria of the Table 1 surfaces stay below 3e-3 rad.
pub(crate) const MAX_TILT_RAD: f64 = 0.05;

/// Relative residual below which members past their release interference leave the contact set.
const RELEASE_RESIDUAL: f64 = 1e-4;

fn tilt_basis(lp: (f64, f64), ell: f64) -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [-lp.0 / ell, 1.0 / ell, 0.0], [-lp.1 / ell, 0.0, 1.0 / ell]]
}

/// One pass over the summits that can touch the shoe at pose `q`: gradient and Hessian of the
/// potential energy restricted to the members plus the summits touching at `q` (collected in
/// `touch`), and the members below their release interference.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
fn evaluate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &State,
    q: &[f64; 3],
    load: f64,
    allow_touch: bool,
    lin: bool,
    touch: &mut Vec<u32>,
) -> Eval {
    touch.clear();
    let (a, b, c) = g.plane(q);
    let phi0 = g.phi_at(g.load_point.0, g.load_point.1);
    let mut ev = Eval { g: [load * phi0[0], load * phi0[1], load * phi0[2]], ..Default::default() };
    let end = match g.support {
        Some(k) => k,
        None => {
            // Lowest point of the plane over the apparent area, minus the longest reach of the law.
            let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
            let thr = wmin + law.z_min();
            g.hs.partition_point(|&h| h >= thr).max(st.bound)
        }
    };
    g.passes.fetch_add(1, Ordering::Relaxed);
    if let (Some((x0, y0, inv_ell)), Some((radius, inv_d, c0))) = (g.uv, law.uniform_hertz_dmt()) {
        let a_hard = g.hardness * std::f64::consts::PI * radius / (1.5 * inv_d);
        let z_hard = a_hard * a_hard / radius;
        let lin = lin && g.shortcuts;
        let (cap_f, hm, inv_hm) = law.fast_meniscus().unwrap_or((0.0, 0.0, 0.0));
        let k = fast::Kernel {
            q: *q,
            x0,
            y0,
            inv_ell,
            radius,
            inv_d,
            c0,
            allow_touch,
            a_hard,
            z_hard,
            lin,
            cap_f,
            hm,
            inv_hm,
        };
        let mut ev = fast::evaluate(g, st, &k, end, load, touch);
        // The pass scans whole blocks of 64; a summit beyond them lies below the threshold
        // (h < w_min: DMT/Hertz reach nothing below the plane), so its |z| >= w_min - h.
        let scanned = (end.div_ceil(64) * 64).min(g.hs.len());
        g.scanned.fetch_add(scanned as u64, Ordering::Relaxed);
        if let (Some(lin), Some(&h_next)) = (ev.lin.as_mut(), g.hs.get(scanned)) {
            let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
            // (With menisci the summits beyond lie below -h_m: their distance to it.)
            let tail = if k.cap_f != 0.0 { wmin - k.hm - h_next } else { wmin - h_next };
            lin.gap_out = if tail > 0.0 { lin.gap_out.min(tail) } else { 0.0 };
        }
        return ev;
    }
    g.scanned.fetch_add(end as u64, Ordering::Relaxed);
    let bs = &g.basis;
    let (mut h00, mut h01, mut h02, mut h11, mut h12, mut h22) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut g0, mut g1, mut g2) = (0.0, 0.0, 0.0);
    let (mut area, mut elastic, mut q0_max, mut over, mut mx, mut my) = (0.0, 0.0, 0.0f64, 0usize, 0.0, 0.0);
    for i in 0..end {
        let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
        let z = g.hs[i] - (a + b * x + c * y);
        let member = st.is_member(i);
        let on_branch = if member {
            if z < law.z_rel(i) {
                ev.releases += 1;
                false
            } else {
                true
            }
        } else if allow_touch && z >= law.z_in(i) && (z > 0.0 || law.z_in(i) < 0.0 || law.p_rel(i) != 0.0) {
            touch.push(i as u32);
            true
        } else {
            continue;
        };
        let (p, k) = if on_branch {
            let r = law.contact(i, z);
            ev.capillary += law.capillary_n(i, z);
            ev.solid += usize::from(r.radius > 0.0);
            area += r.radius * r.radius;
            elastic += r.elastic_n;
            q0_max = q0_max.max(r.q0);
            over += usize::from(r.q0 > g.hardness);
            (r.load_n, r.stiffness)
        } else {
            (law.p_rel(i), 0.0)
        };
        mx += p * (x - g.load_point.0);
        my += p * (y - g.load_point.1);
        ev.contacts += 1;
        ev.force += p;
        ev.force_abs += p.abs();
        let f0 = bs[0][0] + bs[0][1] * x + bs[0][2] * y;
        let f1 = bs[1][0] + bs[1][1] * x + bs[1][2] * y;
        let f2 = bs[2][0] + bs[2][1] * x + bs[2][2] * y;
        g0 += p * f0;
        g1 += p * f1;
        g2 += p * f2;
        h00 += k * f0 * f0;
        h01 += k * f0 * f1;
        h02 += k * f0 * f2;
        h11 += k * f1 * f1;
        h12 += k * f1 * f2;
        h22 += k * f2 * f2;
    }
    ev.g[0] -= g0;
    ev.g[1] -= g1;
    ev.g[2] -= g2;
    ev.h = [[h00, h01, h02], [h01, h11, h12], [h02, h12, h22]];
    ev.area = std::f64::consts::PI * area;
    ev.elastic = elastic;
    ev.q0_max = q0_max;
    ev.over_limit = over;
    ev.moment_x = mx;
    ev.moment_y = my;
    ev
}

/// Interference of sorted summit `i` at pose `q`, computed exactly as the evaluation pass does.
#[inline(always)]
fn interference<L: LawEval + ?Sized>(g: &Geom, law: &L, q: &[f64; 3], i: usize) -> f64 {
    match (g.uv, law.uniform_hertz_dmt()) {
        (Some((x0, y0, inv_ell)), Some(_)) => {
            let u = (f64::from(g.xs[i]) - x0) * inv_ell;
            let v = (f64::from(g.ys[i]) - y0) * inv_ell;
            g.hs[i] - (q[0] + q[1] * u + q[2] * v)
        }
        _ => {
            let (a, b, c) = g.plane(q);
            g.hs[i] - (a + b * f64::from(g.xs[i]) + c * f64::from(g.ys[i]))
        }
    }
}

/// Active-set update at the current pose: members below their release interference leave the
/// contact set. They were off the contact branch (constant force p_rel, zero stiffness) in the
/// evaluation `ev` at this pose, so their terms are removed from it without a new pass (no other
/// summit can touch at the same pose: touching summits joined when `ev` was computed).
fn release<L: LawEval + ?Sized>(g: &Geom, law: &L, st: &mut State, ev: &mut Eval) {
    let q = st.q;
    let (x0, y0) = g.load_point;
    let words = st.bound.div_ceil(64);
    // The fast pass names the words holding members past release (members only leave the set
    // here, and summits that joined at this pose have z >= 0, so no other word can hold one).
    let (lo, hi) = match ev.release_words {
        Some((lo, hi)) => (lo, (hi + 1).min(words)),
        None => (0, words),
    };
    for w in lo..hi {
        let mut bits = st.member[w];
        while bits != 0 {
            let i = w * 64 + bits.trailing_zeros() as usize;
            bits &= bits - 1;
            if interference(g, law, &q, i) < law.z_rel(i) {
                st.leave(g, i);
                let p = law.p_rel(i);
                let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
                let phi = g.phi_at(x, y);
                for (gj, fj) in ev.g.iter_mut().zip(&phi) {
                    *gj += p * fj;
                }
                ev.force -= p;
                ev.force_abs = (ev.force_abs - p.abs()).max(0.0);
                ev.moment_x -= p * (x - x0);
                ev.moment_y -= p * (y - y0);
                ev.contacts -= 1;
                ev.releases = ev.releases.saturating_sub(1);
                ev.released = true;
            }
        }
    }
}

/// Applies the Newton step `dq` (plane movement `mv` over the apparent area) without a pass over
/// the summits when that is exact to within half the tolerance `tol`, and returns whether it did.
///
/// The last evaluation `ev` (a fast pass at the current pose with its statistics, the contact set
/// consistent: no member past release) knows the smallest z of the contacts (`gap_in`), the
/// smallest |z| of all other summits (`gap_out`) and of |z - z_hard| of the contacts. If z falls
/// nowhere by more than `gap_in / 2`, rises nowhere by `gap_out` and moves by less than the
/// hardness gap (the plane's change is linear: its extremes are at the corners), no summit
/// touches, releases or crosses the hardness limit, so the contact set and every count stay; each
/// contact's force changes by `k dz + 1/2 P''(xi) dz^2` with |dz| <= m and, for Hertz/DMT,
/// `P'' = 3/4 R^1/2 / (D xi^1/2)`, `xi >= gap_in - fall`. The gradient after the step is therefore
/// `g + H dq` (exact linearisation, the sums of `ev`) up to at most
/// `1/2 m^2 n P''(gap_in - fall) max|phi_j|` per row (n contacts). When that bound plus
/// `|g + H dq|` is below `tol / 2` the step is applied: force, elastic load and moments by
/// `-H dq`, the real area exactly (`pi R sum z+` is linear in the pose for a fixed contact set; the
/// set keeps its members' coordinate sums), the largest pressure from the largest interference
/// rescanned at the new pose. The residuals of such a result are the linearised ones; the true
/// ones differ by at most the bound. It saves the pass that only confirmed the last Newton step
/// (one of three per load point on large surfaces).
fn linear_step<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    ev: &mut Eval,
    dq: &[f64; 3],
    mv: f64,
    tol: f64,
) -> bool {
    let (Some(lin), Some((radius, inv_d, _)), Some((x0, y0, inv_ell))) = (ev.lin, law.uniform_hertz_dmt(), g.uv) else {
        return false;
    };
    if ev.releases != 0 {
        return false;
    }
    // Largest fall and rise of z (the plane's movement at the corners: it is linear), with room
    // for the rounding of z (a few ulp of the heights and the plane).
    let n_summits = g.hs.len();
    let magnitude = g.hs[0].abs() + g.hs[n_summits - 1].abs() + st.q.iter().map(|v| v.abs()).sum::<f64>();
    let slack = 1e-13 * magnitude;
    let (a, b, c) = g.plane(dq);
    let (mut fall, mut rise) = (0.0f64, 0.0f64);
    for (x, y) in [(0.0, 0.0), (g.length, 0.0), (0.0, g.width), (g.length, g.width)] {
        let dz = -(a + b * x + c * y);
        fall = fall.max(-dz);
        rise = rise.max(dz);
    }
    let (fall, rise) = (fall * (1.0 + 1e-9) + slack, rise * (1.0 + 1e-9) + slack);
    let m = mv.max(fall).max(rise) * (1.0 + 1e-9) + slack;
    // No contact releases (and the remainder below has xi >= gap_in / 2), none touches, none
    // crosses the hardness limit. With menisci the others' gaps (to 0 and -h_m) hold either way.
    let wet = lin.tail_k != 0.0;
    let out_move = if wet { fall.max(rise) } else { rise };
    if !(lin.gap_in > 2.0 * fall && lin.gap_out > out_move && lin.hard_gap > m) {
        return false;
    }
    let nd = g.ndof;
    let mut gl = ev.g;
    for (gj, hj) in gl.iter_mut().zip(&ev.h).take(nd) {
        *gj += hj.iter().zip(dq).take(nd).map(|(h, d)| h * d).sum::<f64>();
    }
    // Menisci: the bridged summits' tails, exactly linear in z (stiffness -f R / h_m each), which
    // the Hessian leaves out: their change of the gradient, force and moments.
    let [tn, tu, tv, tuu, tuv, tvv] = lin.tail;
    let tk = lin.tail_k;
    let th = [[-tk * tn, -tk * tu, -tk * tv], [-tk * tu, -tk * tuu, -tk * tuv], [-tk * tv, -tk * tuv, -tk * tvv]];
    if wet {
        for (gj, hj) in gl.iter_mut().zip(&th).take(nd) {
            *gj += hj.iter().zip(dq).take(nd).map(|(h, d)| h * d).sum::<f64>();
        }
    }
    // Every contact has z > 0 here (|z| >= gap > 0 and no member is past release); with menisci
    // n also counts the bridged summits, whose tails are linear (an upper bound).
    let n = ev.contacts as f64;
    let rem = 0.5 * m * m * n * 0.75 * radius.sqrt() * inv_d / (lin.gap_in - fall).sqrt();
    let phi_max = [1.0, x0.abs().max((g.length - x0).abs()) * inv_ell, y0.abs().max((g.width - y0).abs()) * inv_ell];
    let worst =
        (0..nd).map(|j| gl[j].abs() + rem * phi_max[j]).fold(0.0f64, |m, v| if v > m || v.is_nan() { v } else { m });
    if worst.is_nan() || worst > 0.5 * tol {
        return false;
    }
    let [d0, d1, d2] = *dq;
    let (k, [ku, kv]) = (ev.h[0][0], lin.k_uv);
    let (kuu, kuv, kvv) = (ev.h[1][1], ev.h[1][2], ev.h[2][2]);
    let dp = -(k * d0 + ku * d1 + kv * d2);
    let dpu = -(ku * d0 + kuu * d1 + kuv * d2);
    let dpv = -(kv * d0 + kuv * d1 + kvv * d2);
    let ell = 1.0 / inv_ell;
    ev.g = gl;
    if wet {
        // The tails' change (only d0 on a flat shoe: d1 = d2 = 0 there).
        let dpt = -(th[0][0] * d0 + th[0][1] * d1 + th[0][2] * d2);
        let dptu = -(th[1][0] * d0 + th[1][1] * d1 + th[1][2] * d2);
        let dptv = -(th[2][0] * d0 + th[2][1] * d1 + th[2][2] * d2);
        ev.force += dp + dpt;
        ev.elastic += dp;
        ev.capillary -= dpt;
        ev.moment_x += (dpu + dptu) * ell;
        ev.moment_y += (dpv + dptv) * ell;
        // Area over the summits in solid contact: the members but the bridged ones.
        let (su, sv) = (st.member_dx * inv_ell - tu, st.member_dy * inv_ell - tv);
        ev.area -= std::f64::consts::PI * radius * ((n - tn) * d0 + su * d1 + sv * d2);
    } else {
        ev.force += dp;
        ev.elastic += dp;
        // (sum |P_i| is only the tolerance's scale: it moves by at most sum k m, relative ~1e-7 here.)
        ev.moment_x += dpu * ell;
        ev.moment_y += dpv * ell;
        // Area pi R sum z+ over the contacts (all members, all with z > 0): linear in the pose, with
        // the members' coordinate sums kept by the contact set.
        let (su, sv) = (st.member_dx * inv_ell, st.member_dy * inv_ell);
        ev.area -= std::f64::consts::PI * radius * (n * d0 + su * d1 + sv * d2);
    }
    ev.lin =
        Some(Linear { gap_in: lin.gap_in - fall, gap_out: lin.gap_out - out_move, hard_gap: lin.hard_gap - m, ..lin });
    st.q = [st.q[0] + d0, st.q[1] + d1, st.q[2] + d2];
    // Largest interference at the new pose, exactly as a pass computes it: z_i <= h_i - w_min and
    // the heights descend, so only the first few summits can hold it.
    let (a, b, c) = g.plane(&st.q);
    let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
    let mut zmax = 0.0f64;
    for i in 0..n_summits {
        if g.hs[i] - wmin <= zmax {
            break;
        }
        if st.is_member(i) {
            zmax = zmax.max(interference(g, law, &st.q, i));
        }
    }
    ev.q0_max = 1.5 * (radius * zmax).sqrt() * inv_d / (std::f64::consts::PI * radius);
    true
}

/// Newton direction on the used degrees of freedom; directions of zero stiffness in which the
/// energy still decreases get a long descent component (capped later by the trust radius).
fn direction(ev: &Eval, ndof: usize, tol: f64, tau_scale: f64) -> [f64; 3] {
    if let Some(d) = newton_ldlt(&ev.h, &ev.g, ndof) {
        return d;
    }
    let mut m = Matrix3::zeros();
    let mut diag_max: f64 = 0.0;
    for j in 0..ndof {
        for k in 0..ndof {
            m[(j, k)] = ev.h[j][k];
        }
        diag_max = diag_max.max(ev.h[j][j]);
    }
    let pad = if diag_max > 0.0 { diag_max } else { 1.0 };
    for j in ndof..3 {
        m[(j, j)] = pad;
    }
    let eig = m.symmetric_eigen();
    let lam_max = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b));
    let thr = 1e-12 * lam_max;
    let gv = nalgebra::Vector3::new(ev.g[0], ev.g[1], ev.g[2]);
    let mut d = nalgebra::Vector3::zeros();
    for k in 0..3 {
        let v = eig.eigenvectors.column(k);
        let gk = v.dot(&gv);
        let lam = eig.eigenvalues[k];
        if lam > thr && lam_max > 0.0 {
            d -= v * (gk / lam);
        } else if gk.abs() > 0.1 * tol {
            d -= v * (gk.signum() * 1e6 * tau_scale);
        }
    }
    for j in ndof..3 {
        d[j] = 0.0;
    }
    [d[0], d[1], d[2]]
}

/// Newton direction `d = -H^-1 g` on the used degrees of freedom by an LDL^T factorisation of
/// the (at most 3x3, symmetric) Hessian, when every pivot is at least `1e-8` of the largest
/// diagonal entry (then H is positive definite and far from the zero-stiffness directions that
/// need the eigen-decomposition of [`direction`]); `None` otherwise. It replaces the
/// eigen-decomposition in the common case (about 30x cheaper; the two agree to rounding).
#[allow(clippy::needless_range_loop)]
fn newton_ldlt(h: &[[f64; 3]; 3], g: &[f64; 3], ndof: usize) -> Option<[f64; 3]> {
    let dmax = (0..ndof).fold(0.0f64, |m, j| m.max(h[j][j]));
    if !(dmax > 0.0 && dmax.is_finite()) {
        return None;
    }
    let thr = 1e-8 * dmax;
    let mut l = [[0.0f64; 3]; 3];
    let mut d = [0.0f64; 3];
    for j in 0..ndof {
        let mut dj = h[j][j];
        for k in 0..j {
            dj -= l[j][k] * l[j][k] * d[k];
        }
        if dj.is_nan() || dj <= thr {
            return None;
        }
        d[j] = dj;
        for i in j + 1..ndof {
            let mut v = h[i][j];
            for k in 0..j {
                v -= l[i][k] * l[j][k] * d[k];
            }
            l[i][j] = v / dj;
        }
    }
    // Solve L y = -g, D z = y, L^T x = z.
    let mut x = [0.0f64; 3];
    for i in 0..ndof {
        let mut v = -g[i];
        for k in 0..i {
            v -= l[i][k] * x[k];
        }
        x[i] = v;
    }
    for i in 0..ndof {
        x[i] /= d[i];
    }
    for i in (0..ndof).rev() {
        let mut v = x[i];
        for k in i + 1..ndof {
            v -= l[k][i] * x[k];
        }
        x[i] = v;
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[allow(clippy::too_many_arguments)]
fn equilibrate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
) -> Result<usize, SolveError> {
    let fixed = g.support.is_some();
    let tau_min = 1e-15 * height_range.max(1e-9);
    st.tau = st.tau.max(tau_min).max(1e-3 * height_range);
    let phi0 = g.phi_at(g.load_point.0, g.load_point.1);
    let mut predict = None;
    let mut ev = match st.cache {
        // The previous solve ended here: only the load term of the gradient changes.
        Some((generation, q, mut cached)) if generation == st.generation && q == st.q => {
            cached.g.iter_mut().zip(&phi0).for_each(|(gj, pj)| *gj += load * pj);
            touch.clear();
            predict = if g.shortcuts { predictor(st, load) } else { None };
            cached
        }
        _ => evaluate(g, law, st, &st.q, load, !fixed, true, touch),
    };
    for &i in touch.iter() {
        st.join(g, i as usize);
    }
    let result = iterate(g, law, st, touch, load, cfg, adhesion_ref, height_range, &mut ev, predict);
    st.cache = match result {
        Ok(_) => {
            let mut e = ev;
            e.g.iter_mut().zip(&phi0).for_each(|(gj, pj)| *gj -= load * pj);
            if st.history_len == 3 {
                st.history.rotate_left(1);
                st.history_len = 2;
            }
            st.history[st.history_len] = (load, st.q);
            st.history_len += 1;
            Some((st.generation, st.q, e))
        }
        Err(_) => None,
    };
    result
}

/// Pose predicted for `load` by quadratic extrapolation of the last three equilibria along the
/// load path (Lagrange in the load), when the solver stands at the last of them and the loads
/// run monotonically in nearly even steps towards `load`; None otherwise.
fn predictor(st: &State, load: f64) -> Option<[f64; 3]> {
    if st.history_len < 3 {
        return None;
    }
    let [(l1, q1), (l2, q2), (l3, q3)] = st.history;
    if q3 != st.q {
        return None;
    }
    let (s1, s2, s3) = (l2 - l1, l3 - l2, load - l3);
    // Same direction, steps within a factor 2 of each other.
    let even = |a: f64, b: f64| a * b > 0.0 && (0.5..=2.0).contains(&(a / b));
    if !(even(s1, s2) && even(s2, s3)) {
        return None;
    }
    let w1 = (load - l2) * (load - l3) / ((l1 - l2) * (l1 - l3));
    let w2 = (load - l1) * (load - l3) / ((l2 - l1) * (l2 - l3));
    let w3 = (load - l1) * (load - l2) / ((l3 - l1) * (l3 - l2));
    Some([0, 1, 2].map(|j| w1 * q1[j] + w2 * q2[j] + w3 * q3[j]))
}

/// The Newton iteration of one solve: [`iterate_phase`] with the Hessian of the evaluation pass
/// (each summit's stiffness clipped at >= 0, the meniscus tails left out), and, only if that does
/// not converge within `max_iterations`, a second phase of up to `max_iterations` more on the
/// Hessian of the exact forces (central differences of the gradient).
///
/// Why: the clipped Hessian is exact for Hertz/DMT dry, but it overestimates the stiffness of a
/// summit on the falling part of its JKR/Maugis-Dugdale branch (dP/dz < 0 between its
/// load-controlled pull-off and its release) and of a meniscus tail (`-f R / h_m`). Newton's
/// method with a stiffness `K_c` above the true `K` converges linearly with the ratio
/// `1 - K / K_c`; near the pull-off of the contact `K -> 0` (at a load `eps` above it
/// `K ~ sqrt(eps)`), so a pull-off bisection, which probes ever closer to the fold, ran out of
/// iterations (NotConverged a few parts per million above the pull-off, e.g. one JKR summit with
/// a meniscus at -0.665 uN), and just below the pull-off a solve crawled towards separation (steps
/// of 1e-17 m: the clipped stiffness resists a force excess of 1e-15 N). With the exact Hessian the
/// convergence is quadratic again; where it is not positive definite (beyond the fold: the load is
/// below the pull-off of this contact) the step goes down the energy along its negative curvature,
/// capped by the trust radius, and the shoe comes off in a few steps ([`exact_newton_direction`]).
/// Every solve that converged in the first phase is unchanged to the bit.
#[allow(clippy::too_many_arguments)]
fn iterate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
    ev: &mut Eval,
    predict: Option<[f64; 3]>,
) -> Result<usize, SolveError> {
    let phase = |st: &mut State, touch: &mut Vec<u32>, ev: &mut Eval, predict, fd: Option<f64>, it, limit| {
        iterate_phase(g, law, st, touch, load, cfg, adhesion_ref, height_range, ev, predict, fd, it, limit)
    };
    match phase(st, touch, ev, predict, None, 0, cfg.max_iterations) {
        Err(SolveError::NotConverged { iterations, .. }) => {
            // Difference step: 1e-5 of the law's reach (JKR/MD release, meniscus height), or of
            // a thousandth of the height range for Hertz/DMT dry.
            let fd = 1e-5 * (-law.z_min()).max(1e-3 * height_range.max(1e-9));
            phase(st, touch, ev, None, Some(fd), iterations, iterations + cfg.max_iterations)
        }
        other => other,
    }
}

/// Hessian of the exact forces at `st.q` on the used degrees of freedom by central differences
/// of the gradient (step `h` in each pose coordinate; members only, as at the current pose), and
/// its Newton direction if it is positive definite ([`newton_ldlt`]); otherwise Newton along its
/// directions of positive curvature and a long step down the energy (to be capped by the trust
/// radius) along those of negative curvature, and of none where a force acts along them (`tol`:
/// the force tolerance). None if the differences are not finite.
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
fn exact_newton_direction<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &State,
    touch: &mut Vec<u32>,
    load: f64,
    ev: &Eval,
    h: f64,
    tol: f64,
) -> Option<[f64; 3]> {
    let nd = g.ndof;
    let mut hs = [[0.0f64; 3]; 3];
    for j in 0..nd {
        let (mut qp, mut qm) = (st.q, st.q);
        qp[j] += h;
        qm[j] -= h;
        let ep = evaluate(g, law, st, &qp, load, false, false, touch);
        let em = evaluate(g, law, st, &qm, load, false, false, touch);
        let step = qp[j] - qm[j];
        for i in 0..nd {
            hs[i][j] = (ep.g[i] - em.g[i]) / step;
        }
    }
    touch.clear();
    for i in 0..nd {
        for j in 0..i {
            let m = 0.5 * (hs[i][j] + hs[j][i]);
            hs[i][j] = m;
            hs[j][i] = m;
        }
    }
    if let Some(d) = newton_ldlt(&hs, &ev.g, nd) {
        return Some(d);
    }
    // Not positive definite: Newton on the curvature directions (eigenvalue > 1e-8 of the
    // largest magnitude), and down the energy along the others (negative or no curvature: the
    // energy falls without bound there, so a long step, capped by the trust radius).
    // (Unused degrees of freedom padded with the largest used diagonal: their own eigenvectors.)
    let mut m = Matrix3::zeros();
    let mut diag_abs = 0.0f64;
    for i in 0..nd {
        for j in 0..nd {
            m[(i, j)] = hs[i][j];
        }
        diag_abs = diag_abs.max(hs[i][i].abs());
    }
    for j in nd..3 {
        m[(j, j)] = if diag_abs > 0.0 { diag_abs } else { 1.0 };
    }
    let eig = m.symmetric_eigen();
    let lam_abs = eig.eigenvalues.iter().take(3).fold(0.0f64, |a, &b| a.max(b.abs()));
    if !(lam_abs.is_finite() && lam_abs > 0.0) {
        return None;
    }
    let gv = nalgebra::Vector3::new(ev.g[0], ev.g[1], ev.g[2]);
    let mut d = nalgebra::Vector3::zeros();
    for k in 0..3 {
        let v = eig.eigenvectors.column(k);
        let (gk, lam) = (v.dot(&gv), eig.eigenvalues[k]);
        if lam > 1e-8 * lam_abs {
            d -= v * (gk / lam);
        } else if lam < -1e-8 * lam_abs || gk.abs() > 0.1 * tol {
            // (A direction of no curvature without a force along it, e.g. the tilt of a shoe on
            // one summit under its load point, is neutral: no step.)
            let sense = if gk > 0.0 { -1.0 } else { 1.0 };
            d += v * (sense * 1e3 * st.tau.max(1e-300));
        }
    }
    for j in nd..3 {
        d[j] = 0.0;
    }
    let out = [d[0], d[1], d[2]];
    out.iter().all(|x| x.is_finite()).then_some(out)
}

/// One phase of the Newton iteration (see [`iterate`]): from iteration `it` up to `limit`; `fd`:
/// the difference step of the exact Hessian (None: the pass's clipped Hessian).
#[allow(clippy::too_many_arguments)]
fn iterate_phase<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    touch: &mut Vec<u32>,
    load: f64,
    cfg: &SolverConfig,
    adhesion_ref: f64,
    height_range: f64,
    ev: &mut Eval,
    mut predict: Option<[f64; 3]>,
    fd: Option<f64>,
    mut it: usize,
    limit: usize,
) -> Result<usize, SolveError> {
    let fixed = g.support.is_some();
    let tau_min = 1e-15 * height_range.max(1e-9);
    let tau_max = 1e3 * height_range + 1e-6;
    loop {
        let scale = load.abs().max(ev.force_abs).max(adhesion_ref).max(1e-300);
        let tol = cfg.relative_tolerance * scale;
        let resid = ev.g[..g.ndof].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // Active-set update once the Newton iteration has nearly converged on the current set
        // (the last steps are small, so no member is released by an overshoot).
        // DMT/Hertz: a member past its release interference pulls with its largest tension
        // p_rel. When every contributor is past release and together they cannot carry the
        // (tensile) load, no pose with this contact set is an equilibrium: the shoe comes off.
        if !fixed
            && load < 0.0
            && law.release_force_is_extreme()
            && st.members > 0
            && ev.releases == st.members
            && ev.contacts == ev.releases
            && ev.force > load
        {
            return Err(separates(load));
        }
        if resid <= tol.max(RELEASE_RESIDUAL * scale) && ev.releases > 0 && !fixed {
            release(g, law, st, ev);
            if st.members == 0 && load <= 0.0 {
                return Err(separates(load));
            }
            it += 1;
            if it >= limit {
                break;
            }
            continue;
        }
        if resid <= tol {
            if ev.releases == 0 {
                if st.members == 0 {
                    return Err(SolveError::NoEquilibrium { load_n: load, reason: "no summit in contact".into() });
                }
                // A neutral equilibrium (a tilt no contact resists, e.g. one summit at zero load)
                // is not stable: tip the shoe until the nearest summit touches, then go on.
                if !fixed
                    && g.ndof > 1
                    && it < limit
                    && let Some(dq) = tip_to_next_contact(g, law, st, ev)
                {
                    st.q = [st.q[0] + dq[0], st.q[1] + dq[1], st.q[2] + dq[2]];
                    *ev = evaluate(g, law, st, &st.q, load, true, true, touch);
                    for &i in touch.iter() {
                        st.join(g, i as usize);
                    }
                    it += 1;
                    continue;
                }
                return Ok(it);
            }
            if fixed {
                // Report the first support that left contact.
                let (a, b, c) = g.plane(&st.q);
                for i in 0..g.support.unwrap_or(0) {
                    let z = g.hs[i] - (a + b * f64::from(g.xs[i]) + c * f64::from(g.ys[i]));
                    if z < law.z_rel(i) {
                        return Err(SolveError::ContactLost {
                            load_n: load,
                            index: g.original_index(i),
                            interference_m: z,
                        });
                    }
                }
            }
            // Release the members below their release interference (active-set update).
            release(g, law, st, ev);
            if st.members == 0 && load <= 0.0 {
                return Err(separates(load));
            }
            it += 1;
            if it >= limit {
                break;
            }
            continue;
        }
        if st.members == 0 && load < 0.0 {
            return Err(separates(load));
        }
        it += 1;
        if it >= limit {
            break;
        }
        // Direction, capped by the trust radius.
        let mut dq = match fd {
            Some(h) => exact_newton_direction(g, law, st, touch, load, ev, h, tol)
                .unwrap_or_else(|| direction(ev, g.ndof, tol, st.tau)),
            None => direction(ev, g.ndof, tol, st.tau),
        };
        // First step of a solve along a smooth load path: the extrapolated pose, when it agrees
        // with the Newton step (whose stiffness misses the summits that will touch and the
        // change of the stiffness along the step) to 10 % of the step.
        if let Some(qp) = predict.take() {
            let dp = [qp[0] - st.q[0], qp[1] - st.q[1], qp[2] - st.q[2]];
            let diff = [dp[0] - dq[0], dp[1] - dq[1], dp[2] - dq[2]];
            if g.movement(&diff) <= 0.1 * g.movement(&dq) {
                dq = dp;
            }
        }
        let mv = g.movement(&dq);
        let mut capped = false;
        if mv > st.tau {
            let s = st.tau / mv;
            dq.iter_mut().for_each(|v| *v *= s);
            capped = true;
        }
        if !capped && !fixed && g.shortcuts && fd.is_none() && linear_step(g, law, st, ev, &dq, mv, tol) {
            continue;
        }
        let slope0: f64 = (0..3).map(|j| ev.g[j] * dq[j]).sum();
        if slope0 >= 0.0 {
            // No descent possible within rounding: accept the current point as converged only if
            // the residual is small; otherwise report.
            break;
        }
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..60 {
            let qt = [st.q[0] + alpha * dq[0], st.q[1] + alpha * dq[1], st.q[2] + alpha * dq[2]];
            // The first step of a solve carries the load increment: it is never the last one, so
            // its pass skips the statistics of a linear step.
            let evt = evaluate(g, law, st, &qt, load, !fixed, it > 1, touch);
            let slope: f64 = (0..3).map(|j| evt.g[j] * dq[j]).sum();
            if slope <= 0.9 * slope0.abs() {
                accepted = Some((qt, evt));
                break;
            }
            let sec = slope0 / (slope0 - slope);
            alpha *= sec.clamp(0.1, 0.5);
        }
        let Some((qt, evt)) = accepted else { break };
        st.q = qt;
        *ev = evt;
        for &i in touch.iter() {
            st.join(g, i as usize);
        }
        if alpha == 1.0 && capped {
            st.tau = (2.0 * st.tau).min(tau_max);
            if st.tau >= tau_max && st.members < 3 && g.ndof == 3 && ev.contacts == 0 {
                return Err(SolveError::NoEquilibrium {
                    load_n: load,
                    reason: "the shoe tips over: nothing supports the load point".into(),
                });
            }
        } else if alpha < 1.0 {
            st.tau = (alpha * mv.min(st.tau)).max(tau_min);
        }
        if st.tau >= tau_max {
            return Err(SolveError::NoEquilibrium {
                load_n: load,
                reason: "the shoe moves without bound (tips over or separates)".into(),
            });
        }
        if g.ndof == 3 && !fixed {
            let (_, tx, ty) = g.plane(&st.q);
            if tx.hypot(ty) > MAX_TILT_RAD {
                return Err(SolveError::NoEquilibrium {
                    load_n: load,
                    reason: format!(
                        "the shoe tips over (tilt above {MAX_TILT_RAD} rad, outside the small-angle model)"
                    ),
                });
            }
        }
    }
    let scale = load.abs().max(ev.force_abs).max(adhesion_ref);
    let resid = ev.g[..g.ndof].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if resid <= cfg.relative_tolerance * scale && ev.releases == 0 && st.members > 0 {
        return Ok(it);
    }
    Err(SolveError::NotConverged { load_n: load, iterations: it, residual_n: resid, contacts: st.members })
}

/// For a converged pose whose Hessian is singular on the used degrees of freedom, the smallest
/// rotation along a zero-stiffness direction (either sense) that brings a non-member summit to its
/// jump-in interference; None when the Hessian is regular or nothing can be reached.
fn tip_to_next_contact<L: LawEval + ?Sized>(g: &Geom, law: &L, st: &State, ev: &Eval) -> Option<[f64; 3]> {
    let mut m = Matrix3::zeros();
    for j in 0..g.ndof {
        for k in 0..g.ndof {
            m[(j, k)] = ev.h[j][k];
        }
    }
    let eig = m.symmetric_eigen();
    let lam_max = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b));
    let (a, b, c) = g.plane(&st.q);
    let mut best: Option<(f64, [f64; 3])> = None;
    for k in 0..3 {
        if eig.eigenvalues[k] > 1e-12 * lam_max && lam_max > 0.0 {
            continue;
        }
        let v = eig.eigenvectors.column(k);
        let mut vq = [v[0], v[1], v[2]];
        vq.iter_mut().skip(g.ndof).for_each(|v| *v = 0.0);
        if vq.iter().all(|x| x.abs() < 1e-12) {
            continue;
        }
        let (da, db, dc) = g.plane(&vq);
        // Lower bound of the step that brings summit i to touch: its gap is at least
        // z_min + w_min - h_i (w_min the lowest plane point over the apparent area) and the plane
        // moves by at most dw_max per unit step there (a linear function: largest at a corner).
        // It grows down the height-sorted list, so the scan stops once it exceeds the best step
        // (summits lie inside the apparent area: Surface::new checks it).
        let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
        let dw_max = g.movement(&vq) * (1.0 + 1e-9);
        let z_min = law.z_min();
        for i in 0..g.hs.len() {
            if let Some((b0, _)) = best
                && (z_min + wmin - g.hs[i]) > b0 * dw_max + 1e-12 * (wmin.abs() + g.hs[i].abs())
            {
                break;
            }
            if st.is_member(i) {
                continue;
            }
            let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
            let gap = law.z_in(i) - (g.hs[i] - (a + b * x + c * y));
            let dw = da + db * x + dc * y;
            if gap <= 0.0 || dw == 0.0 {
                continue;
            }
            // Moving by alpha * (sign * v) lowers the plane at i by alpha * sign * (-dw).
            let alpha = gap / dw.abs();
            let sign = if dw < 0.0 { 1.0 } else { -1.0 };
            if best.is_none_or(|(b0, _)| alpha < b0) {
                let s = sign * alpha * (1.0 + 1e-9);
                best = Some((alpha, [s * vq[0], s * vq[1], s * vq[2]]));
            }
        }
    }
    best.map(|(_, dq)| dq)
}

/// The shoe comes off: the load is below the pull-off of the current contact.
fn separates(load_n: f64) -> SolveError {
    SolveError::NoEquilibrium { load_n, reason: "the shoe separates from the surface (load below pull-off)".into() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stiction_surface::{FaceParams, Layout, Placement, generate};

    /// The fast pass gives the same bits on the baseline instruction set and on the best one of
    /// this machine (AVX2+FMA on most x86-64): fixed lanes, no contraction, exact sqrt; dry and
    /// with menisci.
    #[test]
    fn fast_pass_has_the_same_bits_on_every_instruction_set() {
        let layout =
            Layout { apparent_length_m: 40e-6, apparent_width_m: 10e-6, placement: Placement::Poisson, seed: 7 };
        for (mode, hardness) in [(ShoeMode::TiltFree, None), (ShoeMode::Flat, None), (ShoeMode::TiltFree, Some(2e9))] {
            let surface = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
            let cfg = SolverConfig { mode, hardness_pa: hardness, ..Default::default() };
            let mut s = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver");
            s.solve(0.1).expect("solve");
            let LawImpl::HertzDmt { inv_d, two_pi_dgamma } = s.imp else { panic!("DMT law expected") };
            let (x0, y0, inv_ell) = s.geom.uv.expect("fast pass");
            let radius = s.geom.radius(0);
            let a_hard = s.geom.hardness * std::f64::consts::PI * radius / (1.5 * inv_d);
            // A pose slightly off the equilibrium (members past release, summits touching).
            let q = [s.state.q[0] - 1e-9, s.state.q[1] + 4e-9, s.state.q[2] - 4e-9];
            // Dry, and with menisci (water at 35 %: f R = 0.45 uN, h_m = 1 nm), each without and
            // with the linear step's data.
            for (lin, cap_f, hm) in [(false, 0.0, 0.0), (true, 0.0, 0.0), (false, 0.45e-6, 1e-9), (true, 0.45e-6, 1e-9)]
            {
                let k = fast::Kernel {
                    q,
                    x0,
                    y0,
                    inv_ell,
                    radius,
                    inv_d,
                    c0: two_pi_dgamma * radius + cap_f,
                    allow_touch: true,
                    a_hard,
                    z_hard: a_hard * a_hard / radius,
                    lin,
                    cap_f,
                    hm,
                    inv_hm: if hm > 0.0 { 1.0 / hm } else { 0.0 },
                };
                let end = s.geom.hs.len();
                let (mut t1, mut t2) = (Vec::new(), Vec::new());
                let e1 = fast::evaluate_with(pulp::Arch::Scalar, &s.geom, &s.state, &k, end, 0.1, &mut t1);
                let e2 = fast::evaluate_with(pulp::Arch::new(), &s.geom, &s.state, &k, end, 0.1, &mut t2);
                assert!(e1.contacts > 100 && e1.releases > 0 && !t1.is_empty(), "{e1:?}");
                assert_eq!(e1.lin.is_some(), lin);
                assert_eq!(format!("{e1:?}"), format!("{e2:?}"), "{mode:?}");
                assert_eq!(t1, t2);
            }
        }
    }

    /// A solver for `summits` summits of the Table 1 statistics (4:1 face).
    fn table1_solver(summits: f64, mode: ShoeMode, hardness_pa: Option<f64>) -> ExplicitSolver {
        let width = (summits / 4e12 / 4.0).sqrt();
        let layout =
            Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed: 3 };
        let surface = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).expect("surface");
        let cfg = SolverConfig { mode, hardness_pa, detail: Detail::Summary, ..Default::default() };
        ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver")
    }

    /// Load at L* = 0.1 (eq. 5c) for `m` summits of the Table 1 statistics \[N\].
    fn load_star_01(m: usize) -> f64 {
        0.1 * m as f64 * 0.5e-6f64.sqrt() * 0.04e-6f64.powf(1.5) / 9.1e-12
    }

    /// After every solve of a loading curve (pull-off, then 40 points to L* = 0.1), a fresh pass at
    /// the final pose confirms what the solve reported, also where its last Newton step was a
    /// linear one (no pass): the same contacts (no summit touching, none past release), force
    /// and moment residuals below the tolerance (the remainder bound of `linear_step` holds),
    /// real area and elastic load equal to rounding, the largest pressure and the count over the
    /// hardness exactly. Tilt free, flat, and tilt free with a hardness.
    #[test]
    fn linear_steps_agree_with_a_pass_at_the_final_pose() {
        for (mode, hardness) in [(ShoeMode::TiltFree, None), (ShoeMode::Flat, None), (ShoeMode::TiltFree, Some(3e9))] {
            let mut s = table1_solver(3e4, mode, hardness);
            let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            let l_max = load_star_01(s.len());
            let mut linear = 0;
            for k in 0..40 {
                let load = po + (l_max - po) * f64::from(k) / 39.0;
                let passes = s.work().passes;
                let eq = s.solve(load).expect("solve");
                linear += usize::from(s.work().passes - passes < eq.iterations as u64);
                let law =
                    HertzDmt { inv_d: 1.0 / 9.1e-12, two_pi_dgamma: 0.2 * std::f64::consts::PI, radii: &s.geom.radii };
                let mut touch = Vec::new();
                let ev = evaluate(&s.geom, &law, &s.state, &s.state.q, load, true, true, &mut touch);
                let scale = load.abs().max(ev.force_abs).max(s.adhesion_ref);
                let tol = s.config.relative_tolerance * scale;
                assert!(touch.is_empty() && ev.releases == 0, "{mode:?} point {k}: contact set changed");
                assert_eq!(ev.contacts, eq.contacts, "{mode:?} point {k}");
                assert!(ev.g[..s.geom.ndof].iter().all(|g| g.abs() <= tol), "{mode:?} point {k}: {:?} > {tol:e}", ev.g);
                let ell = 1.0 / s.geom.uv.expect("fast pass").2;
                for (a, b, what) in [
                    (eq.force_residual_n, load - ev.force, "force residual"),
                    (eq.moment_residual_x_n_m / ell, ev.moment_x / ell, "moment x"),
                    (eq.moment_residual_y_n_m / ell, ev.moment_y / ell, "moment y"),
                    (eq.elastic_load_n, ev.elastic, "elastic load"),
                ] {
                    assert!((a - b).abs() <= tol, "{mode:?} point {k}: {what} {a:e} against {b:e}");
                }
                assert!((eq.real_area_m2 - ev.area).abs() <= 1e-12 * ev.area, "{mode:?} point {k}: area");
                assert_eq!(eq.max_pressure_pa, ev.q0_max, "{mode:?} point {k}");
                assert_eq!(eq.summits_over_elastic_limit, ev.over_limit, "{mode:?} point {k}");
            }
            // The shortcut is taken on most points of the curve.
            assert!(linear >= 20, "{mode:?}: {linear} linear last steps of 40");
        }
    }

    /// The same with menisci (water at 35 %: f R = 0.45 uN, h_m = 1 nm): a fresh pass at every
    /// final pose confirms the contacts (solid and wetted), the residuals, the capillary load and
    /// the elastic load to the tolerance, and the real area to rounding, also where the last step
    /// was a linear one with the tails in it. Tilt free and flat.
    #[test]
    fn linear_steps_with_menisci_agree_with_a_pass_at_the_final_pose() {
        let men = Meniscus { force_per_radius_n_per_m: 0.45e-6 / 0.5e-6, height_m: 1e-9 };
        for mode in [ShoeMode::TiltFree, ShoeMode::Flat] {
            let mut s = table1_solver(3e4, mode, None);
            s.set_meniscus(Some(men)).expect("meniscus");
            let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
            let l_max = load_star_01(s.len());
            let mut linear = 0;
            for k in 0..40 {
                let load = po + (l_max - po) * f64::from(k) / 39.0;
                let passes = s.work().passes;
                let eq = s.solve(load).expect("solve");
                linear += usize::from(s.work().passes - passes < eq.iterations as u64);
                let dry =
                    HertzDmt { inv_d: 1.0 / 9.1e-12, two_pi_dgamma: 0.2 * std::f64::consts::PI, radii: &s.geom.radii };
                let law = Wet {
                    dry: &dry,
                    radii: &s.geom.radii,
                    solid: &s.solid,
                    force_per_radius_n_per_m: men.force_per_radius_n_per_m,
                    height_m: men.height_m,
                };
                let mut touch = Vec::new();
                let ev = evaluate(&s.geom, &law, &s.state, &s.state.q, load, true, true, &mut touch);
                let scale = load.abs().max(ev.force_abs).max(s.adhesion_ref);
                let tol = s.config.relative_tolerance * scale;
                assert!(touch.is_empty() && ev.releases == 0, "{mode:?} point {k}: contact set changed");
                assert_eq!(ev.contacts, eq.wetted_summits, "{mode:?} point {k}");
                assert_eq!(ev.solid, eq.contacts, "{mode:?} point {k}");
                assert!(ev.g[..s.geom.ndof].iter().all(|g| g.abs() <= tol), "{mode:?} point {k}: {:?} > {tol:e}", ev.g);
                let ell = 1.0 / s.geom.uv.expect("fast pass").2;
                for (a, b, what) in [
                    (eq.force_residual_n, load - ev.force, "force residual"),
                    (eq.moment_residual_x_n_m / ell, ev.moment_x / ell, "moment x"),
                    (eq.moment_residual_y_n_m / ell, ev.moment_y / ell, "moment y"),
                    (eq.elastic_load_n, ev.elastic, "elastic load"),
                    (eq.capillary_load_n, ev.capillary, "capillary load"),
                ] {
                    assert!((a - b).abs() <= tol, "{mode:?} point {k}: {what} {a:e} against {b:e}");
                }
                assert!((eq.real_area_m2 - ev.area).abs() <= 1e-12 * ev.area, "{mode:?} point {k}: area");
                assert_eq!(eq.max_pressure_pa, ev.q0_max, "{mode:?} point {k}");
            }
            // The shortcut is taken with menisci too.
            assert!(linear >= 10, "{mode:?}: {linear} linear last steps of 40");
        }
    }

    /// The shortcuts (extrapolated first step, linear last step) change the equilibria of a loading
    /// curve only within the solver tolerance: same contact counts at every point, elastic load
    /// within 1e-9 of the load scale, separation within that load over the contact stiffness; and
    /// off, the iteration takes every step with a pass (more passes).
    #[test]
    fn shortcuts_change_the_curve_only_within_the_tolerance() {
        for mode in [ShoeMode::TiltFree, ShoeMode::Flat] {
            let run = |shortcuts: bool| {
                let mut s = table1_solver(3e4, mode, None);
                s.set_shortcuts(shortcuts);
                let po = s.pull_off(0.0, 1e-6).expect("pull-off").load_n;
                let l_max = load_star_01(s.len());
                let loads: Vec<f64> = (0..40).map(|k| po + (l_max - po) * f64::from(k) / 39.0).collect();
                let sweep = s.sweep(&loads, Branch::Loading).expect("sweep");
                (sweep.points, s.work().passes)
            };
            let (fast, fast_passes) = run(true);
            let (exact, exact_passes) = run(false);
            assert!(fast_passes < exact_passes, "{mode:?}: {fast_passes} passes against {exact_passes}");
            for (k, (a, b)) in fast.iter().zip(&exact).enumerate() {
                let scale = a.load_n.abs().max(b.elastic_load_n).max(2.0 * std::f64::consts::PI * 0.1 * 0.5e-6);
                assert_eq!(a.contacts, b.contacts, "{mode:?} point {k}");
                assert!((a.elastic_load_n - b.elastic_load_n).abs() <= 1e-9 * scale, "{mode:?} point {k}: {a:?} {b:?}");
                // Separation: the load scale's tolerance over the stiffness (> 1e3 N/m here); the
                // area pi R sum z+ moves by at most pi R n times that.
                let sep_tol = 1e-9 * scale / 1e3;
                assert!((a.separation_m - b.separation_m).abs() <= sep_tol, "{mode:?} point {k}");
                let area_tol = 1e-8 * b.real_area_m2 + std::f64::consts::PI * 0.5e-6 * b.contacts as f64 * sep_tol;
                assert!((a.real_area_m2 - b.real_area_m2).abs() <= area_tol, "{mode:?} point {k}: {a:?} {b:?}");
            }
        }
    }

    /// The LDL^T Newton direction agrees with the eigen-decomposition (to rounding) on a positive
    /// definite Hessian, and declines a singular one.
    #[test]
    fn ldlt_direction_matches_the_eigen_direction() {
        let h = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
        let ev = Eval { g: [1.0, -2.0, 0.5], h, ..Default::default() };
        let d = newton_ldlt(&ev.h, &ev.g, 3).expect("positive definite");
        let m = Matrix3::from_fn(|i, j| h[i][j]);
        let x = m.try_inverse().expect("regular") * nalgebra::Vector3::new(-1.0, 2.0, -0.5);
        for j in 0..3 {
            assert!((d[j] - x[j]).abs() <= 1e-14 * x.norm(), "{d:?} {x:?}");
        }
        let singular = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(newton_ldlt(&singular, &ev.g, 3).is_none());
        // Flat mode: one degree of freedom.
        let d1 = newton_ldlt(&h, &[2.0, 9.0, 9.0], 1).expect("k > 0");
        assert_eq!(d1, [-0.5, 0.0, 0.0]);
    }
}
