//! Two-dimensional electrostatics of the comb cross-section (the plane normal to the finger
//! length): a finite-difference Laplace solver that gives the capacitance per unit finger length
//! of one finger between its front and back electrodes, including the fringing through the top
//! and bottom of both gaps, the finger's own width (a thick plate), the shielding by the
//! neighbouring electrode and, optionally, a conducting substrate (handle wafer) below.
//!
//! **Cell.** One period of the comb, periodic in `x` (the travel direction):
//!
//! `electrode (w_e) | front gap g_f | finger (w_f) | back gap g_b |` (then the next electrode)
//!
//! all of height `t` (device layer), centred on `z = 0`. The electrodes are at potential `V`,
//! the finger at 0. Without a back electrode the cell is an isolated pair, `pad | electrode |
//! g_f | finger | pad`, with zero-flux walls `pad` away. Above and below the device layer the
//! cell is open to a zero-flux lid at `open_height` (the field of a periodic comb decays as
//! `exp(-2 pi |z| / P)`); a substrate replaces the lower lid by a conducting plane
//! `substrate_gap` below the device layer, at the finger's or at the electrodes' potential.
//!
//! **Discretisation.** Node-centred finite volumes on a tensor grid graded towards every edge
//! and corner (cosine clustering); the discrete energy `W' = eps/2 sum_edges G_e (phi_i -
//! phi_j)^2` with `G_e` = dual face length / edge length. Solved by Jacobi-preconditioned
//! conjugate gradients. With unit voltage the capacitance per unit length is `C' = 2 W'/V^2 =
//! eps sum G_e dphi^2` (F/m). The finger is moved by re-gridding the same topology (same number
//! of cells per region), so `C'(x)` is smooth in the travel `x` and its derivative is the force.
//!
//! **Table.** [`CrossSectionTable`] stores the fringing excess per unit length over the two
//! parallel plates, `dC'(x) = C'_2D(x) - eps t [1/(g_f - x) + 1/(g_b + x)]`, at nodes uniform in
//! `ln(g_f - x)`, and interpolates with a natural cubic spline; values and derivatives are
//! analytic in the spline. Tables are computed once per geometry and cached for the process.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock, RwLock};

use serde::{Deserialize, Serialize};

use crate::error::{ActuatorError, nonnegative, positive};

/// Vacuum permittivity eps0 (F/m), CODATA 2018.
pub const VACUUM_PERMITTIVITY: f64 = 8.854_187_812_8e-12;

/// Potential of the substrate (handle wafer) under the device layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SubstratePotential {
    /// At the moving plates' (spine's) potential, usually ground.
    Plates,
    /// At the fixed electrodes' potential.
    Electrodes,
}

/// A conducting substrate below the device layer.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Substrate {
    /// Distance from the bottom of the device layer to the substrate surface (m), e.g. the
    /// buried-oxide thickness of an SOI wafer.
    pub gap_m: f64,
    /// Its potential.
    pub potential: SubstratePotential,
}

/// Cross-section geometry beyond the plate array's gaps and thickness.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct CombGeometry {
    /// In-plane width of a movable finger `w_f` (m), the plate's extent along the travel.
    pub finger_width_m: f64,
    /// In-plane width of a fixed electrode finger `w_e` (m).
    pub electrode_width_m: f64,
    /// Optional substrate; `None`: open below (zero-flux lid far away).
    pub substrate: Option<Substrate>,
}

impl CombGeometry {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        positive("comb.finger_width", self.finger_width_m)?;
        positive("comb.electrode_width", self.electrode_width_m)?;
        if let Some(s) = self.substrate {
            positive("comb.substrate.gap", s.gap_m)?;
        }
        Ok(())
    }
}

/// One cross-section problem: the cell at a given pair of gaps (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellProblem {
    /// Device-layer thickness `t` (m).
    pub thickness_m: f64,
    /// Front gap (m).
    pub front_gap_m: f64,
    /// Back gap (m); `None`: isolated pair (no back electrode).
    pub back_gap_m: Option<f64>,
    /// Widths and substrate.
    pub geometry: CombGeometry,
    /// Grid refinement: cells across the smallest feature; 1.0 is the default resolution
    /// (about 2e-3 relative accuracy of the force, see the tests), 2.0 doubles every count.
    pub refinement: f64,
    /// Gaps `(front, back)` (m) from which the cell counts are chosen; `None`: the problem's
    /// own gaps. Problems that differ only by the finger's position and share a reference get
    /// the same grid topology, so that `C'` is smooth in the travel.
    pub grid_reference_gaps_m: Option<(f64, Option<f64>)>,
}

/// Node positions of one interval `[a, b]` with `n` cells: `Both` clusters at both ends,
/// `Start`/`End` at one end (cosine mapping).
#[derive(Clone, Copy)]
enum Cluster {
    Both,
    Start,
    End,
}

fn interval(a: f64, b: f64, n: usize, c: Cluster, out: &mut Vec<f64>) {
    for k in 1..=n {
        let s = k as f64 / n as f64;
        let u = match c {
            Cluster::Both => 0.5 * (1.0 - (std::f64::consts::PI * s).cos()),
            Cluster::Start => 1.0 - (0.5 * std::f64::consts::PI * s).cos(),
            Cluster::End => (0.5 * std::f64::consts::PI * s).sin(),
        };
        out.push(a + (b - a) * u);
    }
}

fn cells(len: f64, h: f64, min: usize, max: usize) -> usize {
    ((len / h).ceil() as usize).clamp(min, max)
}

/// Capacitance per unit length (F/m, vacuum) between the electrodes (at `V`) and the finger
/// (with the substrate when it is at the finger's potential) of one cell: `C' = 2 W'/V^2`.
// Grid code indexes several arrays by the same node index; explicit indices read clearer.
#[allow(clippy::needless_range_loop)]
pub fn capacitance_per_length(p: &CellProblem) -> Result<f64, ActuatorError> {
    let t = positive("thickness", p.thickness_m)?;
    let gf = positive("front_gap", p.front_gap_m)?;
    if let Some(gb) = p.back_gap_m {
        positive("back_gap", gb)?;
    }
    p.geometry.validate()?;
    let r = positive("refinement", p.refinement)?;
    let (wf, we) = (p.geometry.finger_width_m, p.geometry.electrode_width_m);
    let (rf, rb) = p.grid_reference_gaps_m.unwrap_or((gf, p.back_gap_m));
    let feature = rf.min(wf).min(we).min(rb.unwrap_or(f64::INFINITY));
    // Cell size scale: the cosine clustering puts cells ~ (pi/2n)^2 len at the edges.
    let h = feature / (6.0 * r);
    let nmin = (6.0 * r).round() as usize;
    let nmax = (64.0 * r).round() as usize;
    // x grid.
    let periodic = p.back_gap_m.is_some();
    let mut xs = vec![0.0];
    let mut conductors_x: Vec<(f64, f64, f64)> = Vec::new(); // (x0, x1, potential)
    if let Some(gb) = p.back_gap_m {
        let mut x = 0.0;
        let rb = rb.unwrap_or(gb);
        for (len, rlen, pot) in [(we, we, Some(1.0)), (gf, rf, None), (wf, wf, Some(0.0)), (gb, rb, None)] {
            interval(x, x + len, cells(rlen, h, nmin, nmax), Cluster::Both, &mut xs);
            if let Some(v) = pot {
                conductors_x.push((x, x + len, v));
            }
            x += len;
        }
        xs.pop(); // periodic: the last node is the first
    } else {
        let pad = 2.0 * t.max(rf);
        let mut x = 0.0;
        interval(x, x + pad, cells(pad, 4.0 * h, nmin, nmax), Cluster::End, &mut xs);
        x += pad;
        for (len, rlen, pot) in [(we, we, Some(1.0)), (gf, rf, None), (wf, wf, Some(0.0))] {
            interval(x, x + len, cells(rlen, h, nmin, nmax), Cluster::Both, &mut xs);
            if let Some(v) = pot {
                conductors_x.push((x, x + len, v));
            }
            x += len;
        }
        interval(x, x + pad, cells(pad, 4.0 * h, nmin, nmax), Cluster::Start, &mut xs);
    }
    let period = if periodic { we + gf + wf + p.back_gap_m.unwrap_or(0.0) } else { 0.0 };
    // z grid: lower region, device layer, upper region.
    let reference_period = we + rf + wf + rb.unwrap_or(0.0);
    let open = if periodic { 2.0 * reference_period } else { 2.0 * t.max(rf) };
    let (z_bot, bottom_dirichlet) = match p.geometry.substrate {
        Some(s) => (-0.5 * t - s.gap_m, Some(if s.potential == SubstratePotential::Plates { 0.0 } else { 1.0 })),
        None => (-0.5 * t - open, None),
    };
    let mut zs = vec![z_bot];
    let lower = -0.5 * t - z_bot;
    let lower_cluster = if bottom_dirichlet.is_some() { Cluster::Both } else { Cluster::End };
    interval(z_bot, -0.5 * t, cells(lower, 2.0 * h, nmin, nmax), lower_cluster, &mut zs);
    interval(-0.5 * t, 0.5 * t, cells(t, 2.0 * h, nmin, 2 * nmax), Cluster::Both, &mut zs);
    interval(0.5 * t, 0.5 * t + open, cells(open, 4.0 * h, nmin, nmax), Cluster::Start, &mut zs);
    let (nx, nz) = (xs.len(), zs.len());
    let idx = |i: usize, k: usize| k * nx + i;
    // Edge lengths along x (with wrap for periodic) and dual widths.
    let dx: Vec<f64> = (0..nx)
        .map(|i| {
            if i + 1 < nx {
                xs[i + 1] - xs[i]
            } else if periodic {
                period - xs[i]
            } else {
                f64::NAN
            }
        })
        .collect();
    let nxe = if periodic { nx } else { nx - 1 };
    let dz: Vec<f64> = (0..nz - 1).map(|k| zs[k + 1] - zs[k]).collect();
    let hx: Vec<f64> = (0..nx)
        .map(|i| {
            let left = if i > 0 {
                dx[i - 1]
            } else if periodic {
                dx[nx - 1]
            } else {
                0.0
            };
            let right = if i < nxe { dx[i] } else { 0.0 };
            0.5 * (left + right)
        })
        .collect();
    let hz: Vec<f64> = (0..nz)
        .map(|k| {
            let lo = if k > 0 { dz[k - 1] } else { 0.0 };
            let hi = if k + 1 < nz { dz[k] } else { 0.0 };
            0.5 * (lo + hi)
        })
        .collect();
    // Fixed nodes.
    let tol = 1e-9 * t;
    let mut fixed: Vec<Option<f64>> = vec![None; nx * nz];
    for k in 0..nz {
        let z = zs[k];
        for i in 0..nx {
            let x = xs[i];
            if z >= -0.5 * t - tol && z <= 0.5 * t + tol {
                for &(a, b, v) in &conductors_x {
                    if x >= a - tol && x <= b + tol {
                        fixed[idx(i, k)] = Some(v);
                    }
                }
            }
            if k == 0
                && let Some(v) = bottom_dirichlet
            {
                fixed[idx(i, k)] = Some(v);
            }
        }
    }
    // Edges: (a, b, conductance).
    let mut edges: Vec<(usize, usize, f64)> = Vec::with_capacity(2 * nx * nz);
    for k in 0..nz {
        for i in 0..nxe {
            let j = (i + 1) % nx;
            edges.push((idx(i, k), idx(j, k), hz[k] / dx[i]));
        }
    }
    for k in 0..nz - 1 {
        for i in 0..nx {
            edges.push((idx(i, k), idx(i, k + 1), hx[i] / dz[k]));
        }
    }
    // Linear system on free nodes: A phi = b.
    let n = nx * nz;
    let mut phi: Vec<f64> = fixed.iter().map(|f| f.unwrap_or(0.5)).collect();
    let mut diag = vec![0.0; n];
    for &(a, b, g) in &edges {
        diag[a] += g;
        diag[b] += g;
    }
    let free: Vec<bool> = fixed.iter().map(|f| f.is_none()).collect();
    let apply = |v: &[f64], out: &mut [f64]| {
        out.iter_mut().for_each(|o| *o = 0.0);
        for &(a, b, g) in &edges {
            let d = g * (v[a] - v[b]);
            out[a] += d;
            out[b] -= d;
        }
    };
    // residual r = -A phi on free nodes (b = 0 with fixed values inside phi).
    let mut tmp = vec![0.0; n];
    apply(&phi, &mut tmp);
    let mut res: Vec<f64> = (0..n).map(|i| if free[i] { -tmp[i] } else { 0.0 }).collect();
    let mut z: Vec<f64> = (0..n).map(|i| if free[i] { res[i] / diag[i] } else { 0.0 }).collect();
    let mut dir = z.clone();
    let mut rz: f64 = res.iter().zip(&z).map(|(a, b)| a * b).sum();
    let norm0 = res.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
    let mut converged = false;
    for _ in 0..20 * n {
        apply(&dir, &mut tmp);
        for i in 0..n {
            if !free[i] {
                tmp[i] = 0.0;
            }
        }
        let dad: f64 = dir.iter().zip(&tmp).map(|(a, b)| a * b).sum();
        if dad <= 0.0 {
            converged = true;
            break;
        }
        let alpha = rz / dad;
        for i in 0..n {
            phi[i] += alpha * dir[i];
            res[i] -= alpha * tmp[i];
        }
        if res.iter().map(|x| x * x).sum::<f64>().sqrt() <= 1e-12 * norm0 {
            converged = true;
            break;
        }
        for i in 0..n {
            z[i] = if free[i] { res[i] / diag[i] } else { 0.0 };
        }
        let rz_new: f64 = res.iter().zip(&z).map(|(a, b)| a * b).sum();
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            dir[i] = z[i] + beta * dir[i];
        }
    }
    if !converged {
        return Err(ActuatorError::Solver("cross-section Laplace solve did not converge".into()));
    }
    let energy2: f64 = edges.iter().map(|&(a, b, g)| g * (phi[a] - phi[b]).powi(2)).sum();
    Ok(VACUUM_PERMITTIVITY * energy2)
}

/// Fringing excess of one cell over its parallel plates, tabulated against the travel.
#[derive(Clone, Debug, PartialEq)]
pub struct CrossSectionTable {
    front_gap_m: f64,
    /// Spline nodes in `s = ln(g_f - x)` (ascending).
    s: Vec<f64>,
    /// `dC'` (F/m, vacuum) at the nodes.
    y: Vec<f64>,
    /// Second derivatives `d2 dC'/ds2` of the natural spline.
    m: Vec<f64>,
}

/// Number of travel nodes of a table.
const TABLE_NODES: usize = 20;
/// Smallest tabulated front gap, as a fraction of the gap at rest.
const MIN_GAP_FRACTION: f64 = 0.12;
/// Largest tabulated front gap (negative travel), as a fraction of the gap at rest.
const MAX_GAP_FRACTION: f64 = 1.15;

impl CrossSectionTable {
    /// Tabulates `dC'(x)` for a plate array's cell: front gap at rest `g_f`, back gap at rest
    /// `g_b` (or none), thickness `t`, widths and substrate.
    pub fn compute(
        thickness_m: f64,
        front_gap_m: f64,
        back_gap_m: Option<f64>,
        geometry: CombGeometry,
    ) -> Result<Self, ActuatorError> {
        positive("front_gap", front_gap_m)?;
        let (s_lo, s_hi) = ((MIN_GAP_FRACTION * front_gap_m).ln(), (MAX_GAP_FRACTION * front_gap_m).ln());
        let s: Vec<f64> =
            (0..TABLE_NODES).map(|k| s_lo + (s_hi - s_lo) * k as f64 / (TABLE_NODES - 1) as f64).collect();
        let mut y = Vec::with_capacity(TABLE_NODES);
        for &sk in &s {
            let g = sk.exp();
            let x = front_gap_m - g;
            let back = back_gap_m.map(|b| b + x);
            let c = capacitance_per_length(&CellProblem {
                thickness_m,
                front_gap_m: g,
                back_gap_m: back,
                geometry,
                refinement: 1.0,
                grid_reference_gaps_m: Some((front_gap_m, back_gap_m)),
            })?;
            let pp = VACUUM_PERMITTIVITY * thickness_m * (1.0 / g + back.map_or(0.0, |b| 1.0 / b));
            y.push(c - pp);
        }
        let m = natural_spline(&s, &y);
        Ok(Self { front_gap_m, s, y, m })
    }

    /// `(dC', d dC'/dx, d2 dC'/dx2)` at travel `x` (F/m, F/m^2, F/m^3, vacuum). Outside the
    /// tabulated front gaps (`0.12 g_f` to `1.15 g_f`) the end segment is continued linearly in
    /// `s = ln(g_f - x)`.
    pub fn excess(&self, travel_m: f64) -> (f64, f64, f64) {
        let g = (self.front_gap_m - travel_m).max(1e-3 * self.front_gap_m);
        let sv = g.ln();
        let n = self.s.len();
        let (v, ds, dss) = if sv <= self.s[0] || sv >= self.s[n - 1] {
            let (i, e) = if sv <= self.s[0] { (0, 0) } else { (n - 2, n - 1) };
            let (_, d, _) = spline_eval(&self.s, &self.y, &self.m, i, self.s[e]);
            (self.y[e] + d * (sv - self.s[e]), d, 0.0)
        } else {
            let i = self.s.partition_point(|&a| a <= sv).saturating_sub(1).min(n - 2);
            spline_eval(&self.s, &self.y, &self.m, i, sv)
        };
        // s = ln(g), g = g_f - x: d/dx = -(1/g) d/ds, d2/dx2 = (d2/ds2 - d/ds)/g^2.
        (v, -ds / g, (dss - ds) / (g * g))
    }
}

fn natural_spline(x: &[f64], y: &[f64]) -> Vec<f64> {
    let n = x.len();
    let mut m = vec![0.0; n];
    if n < 3 {
        return m;
    }
    let mut c = vec![0.0; n];
    let mut d = vec![0.0; n];
    for i in 1..n - 1 {
        let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
        let a = h0 / 6.0;
        let b = (h0 + h1) / 3.0;
        let cc = h1 / 6.0;
        let r = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
        let den = b - a * c[i - 1];
        c[i] = cc / den;
        d[i] = (r - a * d[i - 1]) / den;
    }
    for i in (1..n - 1).rev() {
        m[i] = d[i] - c[i] * m[i + 1];
    }
    m
}

fn spline_eval(x: &[f64], y: &[f64], m: &[f64], i: usize, v: f64) -> (f64, f64, f64) {
    let h = x[i + 1] - x[i];
    let a = (x[i + 1] - v) / h;
    let b = (v - x[i]) / h;
    let val = a * y[i] + b * y[i + 1] + ((a * a * a - a) * m[i] + (b * b * b - b) * m[i + 1]) * h * h / 6.0;
    let d1 = (y[i + 1] - y[i]) / h + (-(3.0 * a * a - 1.0) * m[i] + (3.0 * b * b - 1.0) * m[i + 1]) * h / 6.0;
    let d2 = a * m[i] + b * m[i + 1];
    (val, d1, d2)
}

type Key = [u64; 8];

fn cache() -> &'static RwLock<HashMap<Key, Arc<CrossSectionTable>>> {
    static CACHE: OnceLock<RwLock<HashMap<Key, Arc<CrossSectionTable>>>> = OnceLock::new();
    CACHE.get_or_init(|| RwLock::new(HashMap::new()))
}

/// The table for a geometry, computed on first use and cached for the process (same inputs,
/// same bits, same table).
pub fn table(
    thickness_m: f64,
    front_gap_m: f64,
    back_gap_m: Option<f64>,
    geometry: CombGeometry,
) -> Result<Arc<CrossSectionTable>, ActuatorError> {
    let sub = geometry.substrate;
    let key: Key = [
        thickness_m.to_bits(),
        front_gap_m.to_bits(),
        back_gap_m.map_or(u64::MAX, f64::to_bits),
        geometry.finger_width_m.to_bits(),
        geometry.electrode_width_m.to_bits(),
        sub.map_or(u64::MAX, |s| s.gap_m.to_bits()),
        sub.map_or(0, |s| 1 + s.potential as u64),
        0,
    ];
    if let Some(t) = cache().read().ok().and_then(|c| c.get(&key).cloned()) {
        return Ok(t);
    }
    nonnegative("thickness", thickness_m)?;
    let t = Arc::new(CrossSectionTable::compute(thickness_m, front_gap_m, back_gap_m, geometry)?);
    if let Ok(mut c) = cache().write() {
        c.insert(key, t.clone());
    }
    Ok(t)
}
