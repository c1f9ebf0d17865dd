//! Geometry of the shoe and the summits: the summits sorted by descending height with the shoe's
//! rigid-body basis ([`Geom`]), the contact set and pose ([`State`]), and a summit's interference
//! at a pose.

use std::sync::atomic::AtomicU64;

use stiction_surface::Radii;

use super::eval::Eval;
use crate::explicit::laws::LawEval;

/// Summits sorted by descending height plus the rigid-body basis of the shoe.
pub(super) struct Geom {
    pub(super) xs: Vec<f32>,
    pub(super) ys: Vec<f32>,
    pub(super) hs: Vec<f64>,
    pub(super) radii: Radii,
    /// Surface index of each sorted summit (None: the surface was already sorted).
    pub(super) original: Option<Vec<u32>>,
    pub(super) length: f64,
    pub(super) width: f64,
    /// Basis functions phi_j(x, y) = b\[j\]\[0\] + b\[j\]\[1\] x + b\[j\]\[2\] y of the plane
    /// w = sum_j q_j phi_j; unused rows are zero.
    pub(super) basis: [[f64; 3]; 3],
    pub(super) ndof: usize,
    pub(super) load_point: (f64, f64),
    /// Hardness for the elastic-limit count (infinite without one), Pa.
    pub(super) hardness: f64,
    /// FixedContacts: number of supports (the first `n` sorted summits).
    pub(super) support: Option<usize>,
    /// Tilt-free and flat modes: (x0, y0, 1/l), the basis is phi = (1, (x - x0)/l, (y - y0)/l)
    /// (flat: its first function only); enables the fast pass.
    pub(super) uv: Option<(f64, f64, f64)>,
    /// Allow the final Newton step without a pass ([`super::shortcuts::linear_step`]) and the
    /// extrapolated first step ([`super::shortcuts::predictor`]); off only for comparisons
    /// ([`super::ExplicitSolver::set_shortcuts`]).
    pub(super) shortcuts: bool,
    /// Evaluation passes and summits scanned by them since construction (diagnostics).
    pub(super) passes: AtomicU64,
    pub(super) scanned: AtomicU64,
}

impl Geom {
    #[inline(always)]
    pub(super) fn plane(&self, q: &[f64; 3]) -> (f64, f64, f64) {
        let mut p = (0.0, 0.0, 0.0);
        for (qj, b) in q.iter().zip(&self.basis) {
            p.0 += qj * b[0];
            p.1 += qj * b[1];
            p.2 += qj * b[2];
        }
        p
    }
    pub(super) fn phi_at(&self, x: f64, y: f64) -> [f64; 3] {
        let b = &self.basis;
        [b[0][0] + b[0][1] * x + b[0][2] * y, b[1][0] + b[1][1] * x + b[1][2] * y, b[2][0] + b[2][1] * x + b[2][2] * y]
    }
    /// Largest |change of the plane height| over the apparent area for a step `dq`.
    pub(super) fn movement(&self, dq: &[f64; 3]) -> f64 {
        let (a, b, c) = self.plane(dq);
        let mut m: f64 = 0.0;
        for (x, y) in [(0.0, 0.0), (self.length, 0.0), (0.0, self.width), (self.length, self.width)] {
            m = m.max((a + b * x + c * y).abs());
        }
        m
    }
    pub(super) fn original_index(&self, i: usize) -> u32 {
        match &self.original {
            Some(o) => o[i],
            None => i as u32,
        }
    }
    pub(super) fn radius(&self, i: usize) -> f64 {
        match &self.radii {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(v) => v[i],
        }
    }
}

/// Contact set and pose; cloned to back up during pull-off searches.
#[derive(Clone, Debug)]
pub(super) struct State {
    pub(super) q: [f64; 3],
    /// Bit set of the sorted summits in contact.
    pub(super) member: Vec<u64>,
    /// All members have sorted index < bound.
    pub(super) bound: usize,
    pub(super) members: usize,
    /// Trust radius: largest plane movement per step, m.
    pub(super) tau: f64,
    /// Incremented whenever the contact set changes.
    pub(super) generation: u64,
    /// Last evaluation at `q` with the load term removed, valid for `generation`.
    pub(super) cache: Option<(u64, [f64; 3], Eval)>,
    /// The last (up to) three equilibria (load, pose) of successive solves, oldest first.
    pub(super) history: [(f64, [f64; 3]); 3],
    pub(super) history_len: usize,
    /// Sums of (x - x0) and (y - y0) over the members \[m\] (kept by [`State::join`] and
    /// [`State::leave`]; the area's linearisation in [`super::shortcuts::linear_step`]).
    pub(super) member_dx: f64,
    pub(super) member_dy: f64,
}

impl State {
    #[inline(always)]
    pub(super) fn is_member(&self, i: usize) -> bool {
        (self.member[i >> 6] >> (i & 63)) & 1 == 1
    }
    pub(super) fn set(&mut self, i: usize) {
        if !self.is_member(i) {
            self.member[i >> 6] |= 1 << (i & 63);
            self.members += 1;
            self.generation += 1;
            self.bound = self.bound.max(i + 1);
        }
    }
    pub(super) fn clear(&mut self, i: usize) {
        if self.is_member(i) {
            self.member[i >> 6] &= !(1 << (i & 63));
            self.members -= 1;
            self.generation += 1;
        }
    }
    /// [`State::set`], keeping the members' coordinate sums.
    pub(super) fn join(&mut self, g: &Geom, i: usize) {
        if !self.is_member(i) {
            self.set(i);
            self.member_dx += f64::from(g.xs[i]) - g.load_point.0;
            self.member_dy += f64::from(g.ys[i]) - g.load_point.1;
        }
    }
    /// [`State::clear`], keeping the members' coordinate sums.
    pub(super) fn leave(&mut self, g: &Geom, i: usize) {
        if self.is_member(i) {
            self.clear(i);
            self.member_dx -= f64::from(g.xs[i]) - g.load_point.0;
            self.member_dy -= f64::from(g.ys[i]) - g.load_point.1;
        }
    }
}

pub(super) fn tilt_basis(lp: (f64, f64), ell: f64) -> [[f64; 3]; 3] {
    [[1.0, 0.0, 0.0], [-lp.0 / ell, 1.0 / ell, 0.0], [-lp.1 / ell, 0.0, 1.0 / ell]]
}

/// Interference of sorted summit `i` at pose `q`, computed exactly as the evaluation pass does.
#[inline(always)]
pub(super) fn interference<L: LawEval + ?Sized>(g: &Geom, law: &L, q: &[f64; 3], i: usize) -> f64 {
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
