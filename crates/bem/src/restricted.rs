//! Load-controlled solves on a set of candidate points, verified on the whole grid.
//!
//! On the finite patch ([`crate::Boundary::NonPeriodic`]) a shoe often touches the wall at a few
//! pixels: every point outside the contact and the cohesive zone carries no traction, yet each
//! iteration on the whole grid pays for FFTs of the zero-padded field. The same discrete problem
//! is solved on a set `S` of candidate points, the only ones allowed a traction:
//!
//! 1. **The problem on `S`.** The Polonsky-Keer iteration (`constrained_cg`,
//!    the same routine as on the whole grid) with the influence matrix `K_SS` (`|S|^2` Love
//!    coefficients, [`crate::green`], looked up in a table over the patch's offsets built with the
//!    padded operator), the unknown zero off `S`, the mean over the whole grid fixed (so the
//!    residual is the whole grid's with `p = 0` off `S`). With Dugdale adhesion the cohesive-zone
//!    iteration of [`BemSolver::adhesive_at_load`] runs on `S` too: the heights are shifted by
//!    `sigma0 K_SS[1_Z]` with the zone `Z` inside `S`.
//! 2. **The check.** The converged traction's displacement on the whole grid, once, by the FFT
//!    operator: every point off `S` must have a gap `g = u - h - c >= 0` (`c` the approach's
//!    multiplier), and with adhesion `g >= h0` (outside the zone). Then the state satisfies the
//!    complementarity conditions of the whole grid (on `S` to the solver's tolerance, off `S`
//!    exactly: zero traction and an open gap) and is a solution of the whole-grid problem; its
//!    gap off `S` and its elastic energy come from that displacement.
//! 3. **Growth.** The points that fail the check, with a ring of [`RING_PX`] pixels, join `S`,
//!    and the solve is repeated from the current state. So do, before any check, the neighbours
//!    of a contact or zone point on the border of `S` (which would likely fail it), twice in a
//!    row at most: then the check is made (its violators say where a contact that keeps reaching
//!    the border is). When the grown set would pass the bound (the set missed the contact: a warm
//!    start from another pose of a tilting shoe stands elsewhere), `S` starts again, at most
//!    [`MAX_RESEEDS`] times, as the current contact and zone and the [`COLD_SEEDS`] most violated
//!    points, each with the ring.
//!
//! `S` starts as the warm state's contact and zone with the ring, or cold as the [`COLD_SEEDS`]
//! highest points with the ring. The work is bounded: at most [`MAX_ROUNDS`] solves on a set, a set
//! of at most [`max_set_points`] points (where the `|S|^2` products stop being cheaper than the
//! padded FFTs), the iteration caps of [`crate::SolverOptions`]; past any of them, or when a
//! solve on the set fails, the caller solves on the whole grid as without the set (so rough
//! contacts with many points cost what they did, plus at most one check).
//!
//! The state differs from the whole-grid iteration's only in its iterates: both are solutions of
//! the same discrete problem to the tolerance (tests/restricted.rs compares them). The residual's
//! scale is the rms of the unshifted heights (the whole-grid adhesive iteration uses the shifted
//! ones, which differ by the zone's far field, a fraction of a nanometre against the heights'
//! rms).

use rayon::prelude::*;

use crate::boxqp;
use crate::boxqp::restore_mean;
use crate::error::{BemError, PATH_WORK_FACTOR};
use crate::grid::{Grid, SUM_BLOCK, in_pool};
use crate::solver::{
    BemSolver, CgOperator, CgOut, ContactSolution, Dugdale, Restriction, SolverOptions, constrained_cg,
};

/// Largest candidate set, points: its influence matrix is 8 MB (the exact capped solve's bound on
/// its free points, [`crate::boxqp`], is the same number).
pub const MAX_SET_POINTS: usize = boxqp::MAX_FREE;

/// Most solves on a set (the first and each after the set grew) before the whole grid is solved.
pub const MAX_ROUNDS: usize = 16;

/// Ring, in pixels (a square neighbourhood), added around the seeds of a set and around the
/// points that join it.
pub const RING_PX: usize = 2;

/// Consecutive growths of a set whose contact reaches its border before the whole-grid check is
/// made instead.
const MAX_TOUCHING_ROUNDS: usize = 2;

/// Most fresh starts of a set that missed the contact (module docs, growth).
pub const MAX_RESEEDS: usize = 4;

/// Highest points that seed a cold set.
pub const COLD_SEEDS: usize = 32;

/// Rows from which the matrix products run in parallel.
const PAR_ROWS: usize = 256;

/// Largest set worth solving on for `grid`: `|S|^2 <= 4 N log2(4 N)`, where a product with the
/// full matrix costs about one FFT convolution of the padded `4 N` points (measured on one core:
/// 1024 points against 128^2, 256^2 and 500 x 125 patches, the product 0.22-0.32 ms, the
/// convolution 0.26, 0.90 and 1.24 ms; the iteration's products only touch the contact's columns),
/// at most [`MAX_SET_POINTS`] and `N`.
pub fn max_set_points(grid: Grid) -> usize {
    let np = 4.0 * grid.len() as f64;
    let by_cost = (np * np.log2()).sqrt() as usize;
    by_cost.min(MAX_SET_POINTS).min(grid.len())
}

/// The influence matrix `K_SS` (m/Pa, symmetric, row-major) of a set of points.
struct SetOperator {
    m: usize,
    matrix: Vec<f64>,
    /// The nonzero entries of the last input (the unknown and the direction vanish off the
    /// contact, so a product costs `|S|` times the contact's points).
    nonzero: Vec<usize>,
}

impl SetOperator {
    /// The matrix of `set` (grid indices, ascending) on an `nx`-column patch from the table of
    /// influence coefficients over offsets ([`crate::green`]).
    fn new(table: &[f64], nx: usize, set: &[usize]) -> Self {
        let m = set.len();
        let mut matrix = vec![0.0; m * m];
        let fill = |(a, row): (usize, &mut [f64])| {
            let (xa, ya) = (set[a] % nx, set[a] / nx);
            for (v, &j) in row.iter_mut().zip(set) {
                *v = table[ya.abs_diff(j / nx) * nx + xa.abs_diff(j % nx)];
            }
        };
        if m >= PAR_ROWS {
            matrix.par_chunks_mut(m).enumerate().for_each(fill);
        } else {
            matrix.chunks_mut(m).enumerate().for_each(fill);
        }
        SetOperator { m, matrix, nonzero: Vec::with_capacity(m) }
    }
}

impl CgOperator for SetOperator {
    /// `out_i = sum_j K_ij in_j` over the nonzero `in_j` in ascending `j` (the matrix is
    /// symmetric: row `j` is column `j`); the same bytes on any number of threads.
    fn apply(&mut self, input: &[f64], out: &mut [f64]) {
        let m = self.m;
        self.nonzero.clear();
        self.nonzero.extend((0..m).filter(|&j| input[j] != 0.0));
        let (mat, nz) = (&self.matrix, &self.nonzero);
        let rows = |(k, o): (usize, &mut [f64])| {
            let off = k * PAR_ROWS;
            o.fill(0.0);
            for &j in nz {
                let (xj, col) = (input[j], &mat[j * m + off..j * m + off + o.len()]);
                for (o, c) in o.iter_mut().zip(col) {
                    *o += xj * c;
                }
            }
        };
        if m >= PAR_ROWS {
            out.par_chunks_mut(PAR_ROWS).enumerate().for_each(rows);
        } else {
            rows((0, out));
        }
    }

    fn apply_prepared<P: Fn(usize, &mut [f64]) + Sync>(&mut self, field: &mut [f64], prepare: P, out: &mut [f64]) {
        prepare(0, field);
        self.apply(field, out);
    }
}

/// The points within `ring` pixels (a square) of `seeds` on an `nx x ny` patch, marked in `mark`.
fn dilate(seeds: impl Iterator<Item = usize>, ring: usize, nx: usize, ny: usize, mark: &mut [bool]) {
    for i in seeds {
        let (x, y) = (i % nx, i / nx);
        for yy in y.saturating_sub(ring)..(y + ring + 1).min(ny) {
            for xx in x.saturating_sub(ring)..(x + ring + 1).min(nx) {
                mark[yy * nx + xx] = true;
            }
        }
    }
}

/// The state on a set: the contact pressure and the zone at each of its points.
struct SetState {
    /// Grid indices, ascending.
    set: Vec<usize>,
    /// Contact pressure `p_c` (Pa) on the set.
    pressure: Vec<f64>,
    /// Cohesive zone on the set.
    zone: Vec<bool>,
}

impl SetState {
    /// The state on the set `mark`: the points of the current set keep their values, new points
    /// carry nothing, points left out are dropped.
    fn regrid(&mut self, mark: &[bool]) {
        let set: Vec<usize> = (0..mark.len()).filter(|&i| mark[i]).collect();
        let mut pressure = vec![0.0; set.len()];
        let mut zone = vec![false; set.len()];
        for (k, &i) in set.iter().enumerate() {
            if let Ok(a) = self.set.binary_search(&i) {
                pressure[k] = self.pressure[a];
                zone[k] = self.zone[a];
            }
        }
        *self = SetState { set, pressure, zone };
    }
}

/// A converged solve on a set: the unknown, its gap on the set, the CG's output, and with a cap
/// the points at it and the largest plastic depth (m).
struct SetSolve {
    pressure: Vec<f64>,
    gap: Vec<f64>,
    out: CgOut,
    plastic: (usize, f64),
}

/// Why a solve on a set returned no state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum SetMiss {
    /// No set path: the periodic cell, or `SolverOptions::restricted` false.
    NotApplicable,
    /// The contact (with its zone and ring) needs more than [`max_set_points`] points.
    TooLarge,
    /// A solve on the set failed, or the rounds, fresh starts or work ran out.
    GaveUp,
}

/// A state solved on a set and verified on the whole grid: with a hardness cap, the points at
/// the cap and the largest plastic depth (m; 0 without plastic points).
pub(crate) struct SetOutcome {
    pub(crate) solution: ContactSolution,
    pub(crate) plastic_points: usize,
    pub(crate) max_plastic_depth_m: f64,
}

/// One Polonsky-Keer solve on a set at the mean pressure `target_pa` over the `n` points of the
/// grid, from `start` (scaled to the target as [`BemSolver::solve_load`] scales its warm start;
/// uniform on the set if it has no positive value), again from the uniform start if a warm start
/// gives the iteration no direction.
fn set_solve(
    op: &mut SetOperator,
    b: &[f64],
    start: &[f64],
    target_pa: f64,
    n: usize,
    scale: f64,
    opts: &SolverOptions,
) -> Result<SetSolve, BemError> {
    let m = b.len();
    let uniform = target_pa * n as f64 / m as f64;
    let mean = start.iter().sum::<f64>() / n as f64;
    let mut p: Vec<f64> = if mean > 0.0 {
        let f = target_pa / mean;
        start.iter().map(|p| (p * f).max(0.0)).collect()
    } else {
        vec![uniform; m]
    };
    let warm = p.iter().any(|&v| v > 0.0) && mean > 0.0;
    if !p.iter().any(|&v| v > 0.0) {
        p.fill(uniform);
    }
    let out = match in_pool(|| constrained_cg(op, b, &mut p, target_pa, n, scale, opts)) {
        Err(BemError::NoConvergence { .. }) if warm => {
            p.fill(uniform);
            in_pool(|| constrained_cg(op, b, &mut p, target_pa, n, scale, opts))?
        }
        other => other?,
    };
    let gap = out.complementary.iter().zip(&p).map(|(g, &x)| if x > 0.0 { 0.0 } else { g.max(0.0) }).collect();
    Ok(SetSolve { pressure: p, gap, out, plastic: (0, 0.0) })
}

/// One capped solve on a set (the contact pressure in `[0, cap]`, `cap` in Pa) at the mean
/// pressure `target_pa` over the `n` points of the grid, solved exactly by the active-set method
/// of [`crate::boxqp`] from `start` clamped to the cap and brought to the target as the
/// whole-grid capped iteration brings its start; without a positive value, the total poured on
/// the highest points at the cap ([`boxqp::fill_highest`]).
/// `None` when the set cannot carry the target below the cap or the method gives up.
#[allow(clippy::too_many_arguments)]
fn capped_set_solve(
    op: &SetOperator,
    b: &[f64],
    start: &[f64],
    target_pa: f64,
    n: usize,
    cap: f64,
    scale: f64,
    opts: &SolverOptions,
) -> Option<SetSolve> {
    let m = b.len();
    let total = target_pa * n as f64;
    let set_mean = total / m as f64;
    if !set_mean.is_finite() || set_mean >= cap {
        return None;
    }
    let mut x: Vec<f64> = start.iter().map(|p| p.clamp(0.0, cap)).collect();
    match restore_mean(&x, cap, set_mean) {
        Some(fix) if x.iter().any(|&v| v > 0.0) => x.iter_mut().for_each(|v| *v = fix.apply(*v, cap)),
        _ => x = boxqp::fill_highest(b, total, cap),
    }
    // A held point is released when its gap has the wrong sign beyond rounding of the heights.
    let size = b.iter().fold(scale, |a, b| a.max(b.abs()));
    let out = boxqp::solve_capped(&op.matrix, b, &mut x, total, cap, 1e-9 * size, opts.max_iterations).ok()?;
    let r = &out.gap;
    // The residual of the whole-grid capped iteration ([`crate::BemSolver::solve_load_plastic`]).
    let (sum_x, viol) = boxqp::capped_violation(&x, r, cap, target_pa);
    let plastic_points = x.iter().filter(|&&v| v >= cap).count();
    let depth = x.iter().zip(r).filter(|&(&v, _)| v >= cap).fold(0.0f64, |d, (_, &g)| d.max(-g));
    let gap = r.iter().zip(&x).map(|(g, &v)| if v > 0.0 { 0.0 } else { g.max(0.0) }).collect();
    let cg = CgOut {
        complementary: out.gap.clone(),
        multiplier: out.multiplier,
        iterations: out.steps,
        residual: viol / (sum_x * scale),
    };
    Some(SetSolve { pressure: x, gap, out: cg, plastic: (plastic_points, depth) })
}

impl BemSolver {
    /// The load-controlled state at the external mean pressure `target_pa` (Pa) solved on a set
    /// of candidate points and verified on the whole grid (module docs): without `law` the
    /// Polonsky-Keer state of [`Self::solve_load`] (`warm` as there), with it the Dugdale loading
    /// branch of [`Self::adhesive_at_load`] (`warm` as there, already filtered by the caller).
    /// With `hardness_pa` (Pa) the capped state of [`Self::plastic_at_load`] (each solve on the
    /// set the exact active-set solve of [`crate::boxqp`]; the contact pressure capped at the
    /// hardness, plus the Dugdale stress with adhesion).
    /// An error ([`SetMiss`]) when the set path does not apply (periodic cell, `opts.restricted`
    /// false), the contact outgrows the largest set, or it gives up (a bound reached, a solve
    /// failed): the caller solves on the whole grid.
    pub(crate) fn restricted_at_load(
        &mut self,
        target_pa: f64,
        law: Option<&Dugdale>,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
        hardness_pa: Option<f64>,
    ) -> Result<SetOutcome, SetMiss> {
        if !opts.restricted {
            return Err(SetMiss::NotApplicable);
        }
        self.half.influence_table().ok_or(SetMiss::NotApplicable)?;
        let grid = self.grid();
        let (n, nx, ny) = (grid.len(), grid.nx, grid.ny);
        let cap = max_set_points(grid);
        let (stress, range) = law.map_or((0.0, 0.0), |l| (l.stress_pa, l.range_m));
        let warm = warm.filter(|w| w.pressure_pa.len() == n && w.gap_m.len() == n);
        // The first set, and the contact pressure and zone on the whole grid to start from.
        let mut mark = vec![false; n];
        let (start, zone_start): (Option<Vec<f64>>, Vec<bool>) = match (warm, law) {
            (Some(w), None) if w.mean_pressure_pa > 0.0 => {
                // As [`BemSolver::solve_load`]'s warm start (`set_solve` scales it to the load).
                dilate((0..n).filter(|&i| w.pressure_pa[i] > 0.0), RING_PX, nx, ny, &mut mark);
                (Some(w.pressure_pa.iter().map(|p| p.max(0.0)).collect()), vec![false; n])
            }
            (Some(w), Some(_)) => {
                let z: Vec<bool> = w.gap_m.iter().map(|&g| g < range).collect();
                let pc: Vec<f64> =
                    w.pressure_pa.iter().zip(&z).map(|(p, &inz)| if inz { p + stress } else { *p }.max(0.0)).collect();
                dilate((0..n).filter(|&i| pc[i] > 0.0 || z[i]), RING_PX, nx, ny, &mut mark);
                (Some(pc), z)
            }
            _ => (None, vec![false; n]),
        };
        if !mark.iter().any(|&m| m) {
            // Cold: the highest points (ties by index, so the set does not depend on the sort).
            let mut order: Vec<usize> = (0..n).collect();
            let k = COLD_SEEDS.min(n - 1);
            let h = &self.heights;
            order.select_nth_unstable_by(k, |&a, &b| h[b].total_cmp(&h[a]).then(a.cmp(&b)));
            dilate(order[..k].iter().copied(), RING_PX, nx, ny, &mut mark);
        }
        let set: Vec<usize> = (0..n).filter(|&i| mark[i]).collect();
        if set.len() > cap {
            return Err(SetMiss::TooLarge);
        }
        let mut state = SetState {
            pressure: set.iter().map(|&i| start.as_ref().map_or(0.0, |s| s[i])).collect(),
            zone: set.iter().map(|&i| zone_start[i]).collect(),
            set,
        };
        // With the cap the set must be able to carry the load below it: at least twice the
        // points that carry it at the hardness (the set grows by rings until it does).
        if let Some(hd) = hardness_pa {
            while (state.set.len() as f64) * hd < 2.0 * target_pa * n as f64 {
                let mut grown = vec![false; n];
                dilate(state.set.iter().copied(), RING_PX, nx, ny, &mut grown);
                if grown.iter().filter(|&&g| g).count() > cap || grown.iter().all(|&g| g) {
                    return Err(SetMiss::TooLarge);
                }
                state.regrid(&grown);
            }
        }
        let initial_points = state.set.len();
        // Cold with adhesion: the non-adhesive state at the load is the start (as on the grid).
        let mut dry_first = law.is_some() && start.is_none();
        let mut iterations = 0usize;
        let mut updates = 0usize;
        let mut checks = 0usize;
        let mut reseeds = 0usize;
        let mut touching_rounds = 0usize;
        let budget = PATH_WORK_FACTOR * opts.max_iterations;
        for _round in 0..MAX_ROUNDS {
            let table = self.half.influence_table().ok_or(SetMiss::NotApplicable)?;
            let mut op = SetOperator::new(table, nx, &state.set);
            let m = state.set.len();
            let h: Vec<f64> = state.set.iter().map(|&i| self.heights[i]).collect();
            let scale = self.height_rms;
            // One solve on the set: the capped one with the hardness, else the Polonsky-Keer one.
            let solve = |op: &mut SetOperator, b: &[f64], start: &[f64], target: f64, pressure_cap: Option<f64>| {
                match pressure_cap {
                    Some(c) => capped_set_solve(op, b, start, target, n, c, scale, opts),
                    None => set_solve(op, b, start, target, n, scale, opts).ok(),
                }
            };
            if dry_first {
                let s = solve(&mut op, &h, &state.pressure, target_pa, hardness_pa).ok_or(SetMiss::GaveUp)?;
                iterations += s.out.iterations;
                state.zone = s.gap.iter().map(|&g| g < range).collect();
                state.pressure = s.pressure;
                dry_first = false;
            }
            // The cohesive-zone iteration on the set (one solve without adhesion).
            let mut converged = None;
            for _ in 0..opts.max_zone_updates {
                let tension: Vec<f64> = state.zone.iter().map(|&z| if z { stress } else { 0.0 }).collect();
                let nz = state.zone.iter().filter(|&&z| z).count();
                let mut b = vec![0.0; m];
                if nz > 0 {
                    op.apply(&tension, &mut b);
                }
                b.iter_mut().zip(&h).for_each(|(b, h)| *b += h);
                let carried = target_pa + stress * nz as f64 / n as f64;
                let s = solve(&mut op, &b, &state.pressure, carried, hardness_pa.map(|h| h + stress))
                    .ok_or(SetMiss::GaveUp)?;
                iterations += s.out.iterations;
                updates += 1;
                if iterations > budget {
                    return Err(SetMiss::GaveUp);
                }
                let new_zone: Vec<bool> = s.gap.iter().map(|&g| g < range).collect();
                let same = new_zone == state.zone;
                state.pressure = s.pressure.clone();
                state.zone = new_zone;
                if same {
                    converged = Some(s);
                    break;
                }
            }
            let s = converged.ok_or(SetMiss::GaveUp)?;
            // A contact or zone point next to a point off the set: grow before checking.
            let mut border = vec![false; n];
            let in_set = {
                let mut a = vec![false; n];
                state.set.iter().for_each(|&i| a[i] = true);
                a
            };
            let active: Vec<usize> =
                (0..m).filter(|&a| state.zone[a] || state.pressure[a] > 0.0).map(|a| state.set[a]).collect();
            let touching: Vec<usize> = active
                .iter()
                .copied()
                .filter(|&i| {
                    let (x, y) = (i % nx, i / nx);
                    (y.saturating_sub(1)..(y + 2).min(ny))
                        .any(|yy| (x.saturating_sub(1)..(x + 2).min(nx)).any(|xx| !in_set[yy * nx + xx]))
                })
                .collect();
            // While the contact keeps reaching the border (a set that has to walk to a contact
            // that moved: a tilting shoe's next pose) the whole-grid check takes over from the
            // third round, and its violators say where the contact is.
            if !touching.is_empty() && touching_rounds < MAX_TOUCHING_ROUNDS {
                touching_rounds += 1;
                dilate(touching.into_iter(), RING_PX, nx, ny, &mut border);
                border.iter_mut().zip(&in_set).for_each(|(b, &s)| *b |= s);
                if border.iter().filter(|&&b| b).count() > cap {
                    return Err(SetMiss::TooLarge);
                }
                state.regrid(&border);
                continue;
            }
            touching_rounds = 0;
            // The check on the whole grid: the net traction's displacement, the gap off the set.
            let mut p_net = vec![0.0; n];
            for (a, &i) in state.set.iter().enumerate() {
                p_net[i] = state.pressure[a] - if state.zone[a] { stress } else { 0.0 };
            }
            let u = self.half.displacement(&p_net);
            checks += 1;
            let c = s.out.multiplier;
            let heights = &self.heights;
            let gap_off: Vec<(f64, bool)> = (0..n)
                .into_par_iter()
                .with_min_len(SUM_BLOCK)
                .map(|i| {
                    if in_set[i] {
                        (0.0, false)
                    } else {
                        let g = u[i] - heights[i] - c;
                        // Without adhesion a point off the set must be open (g >= 0); with it,
                        // outside the zone (g >= h0); a NaN gap fails.
                        (g, g.partial_cmp(&range).is_none_or(|o| o.is_lt()))
                    }
                })
                .collect();
            let violators: Vec<usize> = (0..n).filter(|&i| gap_off[i].1).collect();
            if violators.is_empty() {
                let mut gap: Vec<f64> = gap_off.iter().map(|g| g.0.max(0.0)).collect();
                let mut contact = vec![false; n];
                for (a, &i) in state.set.iter().enumerate() {
                    gap[i] = s.gap[a];
                    contact[i] = state.pressure[a] > 0.0;
                }
                let nz = state.zone.iter().filter(|&&z| z).count();
                let restriction = Restriction { initial_points, points: m, checks };
                let updates = if law.is_some() { updates } else { 1 };
                let solution = self.finish_with(
                    p_net,
                    gap,
                    contact,
                    nz,
                    iterations,
                    updates,
                    s.out.residual,
                    Some(&u),
                    Some(restriction),
                );
                return Ok(SetOutcome { solution, plastic_points: s.plastic.0, max_plastic_depth_m: s.plastic.1 });
            }
            let mut grown = in_set;
            dilate(violators.iter().copied(), RING_PX, nx, ny, &mut grown);
            if grown.iter().filter(|&&g| g).count() > cap {
                // The set missed the contact (a warm start from another pose of a tilting shoe
                // stands elsewhere): start again from its contact and zone and the most violated
                // points, each with the ring.
                reseeds += 1;
                if reseeds > MAX_RESEEDS {
                    return Err(SetMiss::GaveUp);
                }
                let mut worst = violators;
                let k = COLD_SEEDS.min(worst.len());
                if k < worst.len() {
                    worst.select_nth_unstable_by(k, |&a, &b| gap_off[a].0.total_cmp(&gap_off[b].0).then(a.cmp(&b)));
                }
                let mut seeds = vec![false; n];
                dilate(worst[..k].iter().copied(), RING_PX, nx, ny, &mut seeds);
                dilate(active.iter().copied(), RING_PX, nx, ny, &mut seeds);
                if seeds.iter().filter(|&&g| g).count() > cap {
                    return Err(SetMiss::TooLarge);
                }
                grown = seeds;
            }
            state.regrid(&grown);
        }
        Err(SetMiss::GaveUp)
    }
}
