//! The boundary-element contact solver ([`BemSolver`]): the elastic half-space on the grid
//! ([`HalfSpace`]), the Dugdale cohesive zones ([`Dugdale`]), the constrained conjugate-gradient
//! solve at a mean gap or a load ([`SolverOptions`], [`ContactSolution`]) and the separation
//! path to pull-off ([`Separation`]); the method is in the [crate docs](crate).

use rayon::prelude::*;
use realfft::num_complex::Complex;
use serde::Serialize;

use crate::error::{BemError, check_nonnegative, check_positive};
use crate::fft::Fft2;
use crate::green::{Boundary, MAX_POINTS_NON_PERIODIC, Padded};
use crate::grid::{Grid, SUM_BLOCK, block_sum, block_sum2, in_pool};
use crate::{patches, synth};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Operator {
    /// `u(q) = 2 p(q)/(E* |q|)` (m/Pa).
    Compliance,
    /// `p(q) = E* |q| u(q)/2` (Pa/m).
    Stiffness,
}

/// The elastic half-space on the grid: FFT plans, the multipliers and work buffers; periodic, or
/// a finite patch on an unbounded half-space ([`Boundary`], [`crate::green`]).
#[derive(Debug)]
pub struct HalfSpace {
    grid: Grid,
    e_star_pa: f64,
    /// The zero-padded (non-periodic) compliance, when the boundary is non-periodic.
    padded: Option<Box<Padded>>,
    fft: Fft2,
    compliance: Vec<f64>,
    stiffness: Vec<f64>,
    rows: Vec<Complex<f64>>,
    spec: Vec<Complex<f64>>,
}

impl HalfSpace {
    /// The half-space of composite modulus `e_star_pa` (Pa, finite > 0) on `grid`.
    pub fn new(grid: Grid, e_star_pa: f64) -> Result<Self, BemError> {
        check_positive("e_star_pa", e_star_pa, "a finite composite modulus E* > 0 (Pa)")?;
        let fft = Fft2::new(grid.nx, grid.ny);
        let (nxc, ny) = (fft.nxc(), grid.ny);
        let norm = 1.0 / grid.len() as f64;
        let mut compliance = vec![0.0; nxc * ny];
        let mut stiffness = vec![0.0; nxc * ny];
        for kx in 0..nxc {
            for ky in 0..ny {
                let q = grid.wavenumber(kx, ky);
                if q > 0.0 {
                    compliance[kx * ny + ky] = 2.0 / (e_star_pa * q) * norm;
                    stiffness[kx * ny + ky] = 0.5 * e_star_pa * q * norm;
                }
            }
        }
        let n = fft.spectrum_len();
        Ok(HalfSpace {
            grid,
            e_star_pa,
            padded: None,
            fft,
            compliance,
            stiffness,
            rows: vec![Complex::default(); n],
            spec: vec![Complex::default(); n],
        })
    }

    /// The half-space of composite modulus `e_star_pa` (Pa) under a finite `grid` patch that goes
    /// on beyond it (no periodic images; [`crate::green`]); `nx ny` at most
    /// [`MAX_POINTS_NON_PERIODIC`]. Its traction-from-displacement operator is not available.
    pub fn non_periodic(grid: Grid, e_star_pa: f64) -> Result<Self, BemError> {
        if grid.len() > MAX_POINTS_NON_PERIODIC {
            return Err(BemError::GridSize { nx: grid.nx, ny: grid.ny, limit: MAX_POINTS_NON_PERIODIC });
        }
        let mut h = HalfSpace::new(grid, e_star_pa)?;
        h.padded = Some(Box::new(Padded::new(grid, e_star_pa)));
        Ok(h)
    }

    /// Which Green's function this half-space uses.
    pub fn boundary(&self) -> Boundary {
        if self.padded.is_some() { Boundary::NonPeriodic } else { Boundary::Periodic }
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.grid
    }

    /// The composite modulus `E*`, Pa.
    pub fn e_star_pa(&self) -> f64 {
        self.e_star_pa
    }

    /// The non-periodic influence coefficients at the patch's offsets ([`Padded::table`]); `None`
    /// on the periodic cell.
    pub(crate) fn influence_table(&self) -> Option<&[f64]> {
        self.padded.as_ref().map(|p| p.table())
    }

    pub(crate) fn apply(&mut self, op: Operator, input: &[f64], out: &mut [f64]) {
        if let (Some(p), Operator::Compliance) = (self.padded.as_mut(), op) {
            p.compliance(input, out);
            return;
        }
        let m = match op {
            Operator::Compliance => &self.compliance,
            Operator::Stiffness => &self.stiffness,
        };
        self.fft.convolve(input, m, &mut self.rows, &mut self.spec, out);
    }

    /// `out = A[field]` after `prepare(offset, block)` has rewritten `field` block by block, in
    /// the pass that transforms it ([`Fft2::convolve_prepared`]).
    fn apply_prepared<P: Fn(usize, &mut [f64]) + Sync>(
        &mut self,
        op: Operator,
        field: &mut [f64],
        prepare: P,
        out: &mut [f64],
    ) {
        if let (Some(p), Operator::Compliance) = (self.padded.as_mut(), op) {
            // `prepare` rewrites the field element by element (by offset): row by row here.
            let nx = self.grid.nx;
            field.par_chunks_mut(nx).enumerate().for_each(|(j, row)| prepare(j * nx, row));
            p.compliance(field, out);
            return;
        }
        let m = match op {
            Operator::Compliance => &self.compliance,
            Operator::Stiffness => &self.stiffness,
        };
        self.fft.convolve_prepared(field, prepare, m, &mut self.rows, &mut self.spec, out);
    }

    /// Surface displacement `u = K[p]` (m, zero mean) under the traction `pressure_pa` (Pa).
    pub fn displacement(&mut self, pressure_pa: &[f64]) -> Vec<f64> {
        let mut u = vec![0.0; self.grid.len()];
        self.apply(Operator::Compliance, pressure_pa, &mut u);
        u
    }

    /// Traction `p = K^-1[u] - mean` (Pa, zero mean) for the displacement `u` (m), with the
    /// periodic stiffness (also on a non-periodic half-space, whose own inverse is not diagonal).
    pub fn traction(&mut self, displacement_m: &[f64]) -> Vec<f64> {
        let mut p = vec![0.0; self.grid.len()];
        self.apply(Operator::Stiffness, displacement_m, &mut p);
        p
    }

    /// Elastic energy per nominal area, J/m^2: `U/A0 = mean(p u)/2` with `u = K[p]` (periodic: the
    /// mean pressure does no work on the zero-mean displacement; non-periodic: the whole work).
    pub fn elastic_energy_j_per_m2(&mut self, pressure_pa: &[f64]) -> f64 {
        let u = self.displacement(pressure_pa);
        0.5 * block_sum(u.len(), |r| r.map(|i| pressure_pa[i] * u[i]).sum()) / u.len() as f64
    }
}

/// Solver settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SolverOptions {
    /// Relative tolerance on the complementarity residual (see the crate docs); default 1e-8.
    pub tolerance: f64,
    /// Cap on conjugate-gradient iterations per solve; default 10 000.
    pub max_iterations: usize,
    /// Cap on the cohesive-zone updates of an adhesive solve; default 500.
    pub max_zone_updates: usize,
    /// Hardness `H` (Pa) at which the compressive traction is capped (perfectly plastic pixels),
    /// read by [`BemSolver::plastic_at_load`]; `None` (the default): elastic.
    pub hardness_pa: Option<f64>,
    /// Whether the load-controlled solves on the finite patch ([`BemSolver::solve_load`],
    /// [`BemSolver::adhesive_at_load`] on [`Boundary::NonPeriodic`]) first solve on a set of
    /// candidate points with the influence matrix and verify the result on the whole grid
    /// ([`crate::restricted`]); default true. False: every solve iterates on the whole grid.
    pub restricted: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            tolerance: 1e-8,
            max_iterations: 10_000,
            max_zone_updates: 500,
            hardness_pa: None,
            restricted: true,
        }
    }
}

impl SolverOptions {
    pub(crate) fn validate(&self) -> Result<(), BemError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(BemError::Value {
                name: "tolerance",
                value: self.tolerance,
                expected: "a relative tolerance in (0, 1)",
            });
        }
        if self.max_iterations == 0 || self.max_zone_updates == 0 {
            return Err(BemError::Value { name: "max_iterations", value: 0.0, expected: "iteration caps >= 1" });
        }
        if let Some(h) = self.hardness_pa {
            check_positive("hardness_pa", h, "a finite hardness > 0 (Pa)")?;
        }
        Ok(())
    }
}

/// The Maugis-Dugdale cohesive law: tension `stress_pa` for gaps below `range_m`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Dugdale {
    /// Dugdale stress `sigma0`, Pa.
    pub stress_pa: f64,
    /// Range `h0`, m.
    pub range_m: f64,
}

impl Dugdale {
    /// The law with work of adhesion `w` (J/m^2) and range `h0` (m): `sigma0 = w/h0`.
    pub fn from_work_and_range(work_of_adhesion_j_per_m2: f64, range_m: f64) -> Result<Self, BemError> {
        check_positive(
            "work_of_adhesion_j_per_m2",
            work_of_adhesion_j_per_m2,
            "a finite work of adhesion > 0 (J/m^2)",
        )?;
        check_positive("range_m", range_m, "a finite interaction range > 0 (m)")?;
        Ok(Dugdale { stress_pa: work_of_adhesion_j_per_m2 / range_m, range_m })
    }

    /// The capillary cohesive zone of condensed liquid in equilibrium with its vapour: the
    /// Laplace pressure `gamma / r_K` (Pa) wherever the gap is below the meniscus height
    /// `h_m = r_K (cos th1 + cos th2)` (Kelvin radius `r_K`, m; surface tension `gamma`, N/m; the
    /// contact angles' cosines summed, > 0). Its work of adhesion is
    /// `sigma0 h_m = gamma (cos th1 + cos th2)` (2 gamma cos theta for equal faces): the flat-flat
    /// limit of a wetted interface.
    pub fn capillary(surface_tension_n_per_m: f64, kelvin_radius_m: f64, cos_angle_sum: f64) -> Result<Self, BemError> {
        check_positive("surface_tension_n_per_m", surface_tension_n_per_m, "a finite surface tension > 0 (N/m)")?;
        check_positive("kelvin_radius_m", kelvin_radius_m, "a finite Kelvin radius > 0 (m)")?;
        check_positive("cos_angle_sum", cos_angle_sum, "cos th1 + cos th2 > 0 (a wetting liquid)")?;
        Ok(Dugdale { stress_pa: surface_tension_n_per_m / kelvin_radius_m, range_m: kelvin_radius_m * cos_angle_sum })
    }

    /// Work of adhesion `w = sigma0 h0`, J/m^2.
    pub fn work_of_adhesion_j_per_m2(&self) -> f64 {
        self.stress_pa * self.range_m
    }

    /// Maugis parameter of a sphere of radius `R` (m) on this law:
    /// `lambda = 2 sigma0 (R D^2/(pi w))^(1/3)`, `D = 3/(4 E*)`.
    pub fn maugis_parameter(&self, radius_m: f64, e_star_pa: f64) -> f64 {
        let d = 0.75 / e_star_pa;
        2.0 * self.stress_pa * (radius_m * d * d / (std::f64::consts::PI * self.work_of_adhesion_j_per_m2())).cbrt()
    }
}

/// A converged contact state.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ContactSolution {
    /// Total normal traction on the surface, Pa, compressive positive (row-major): the contact
    /// pressure, minus the Dugdale stress in the cohesive zone.
    pub pressure_pa: Vec<f64>,
    /// Gap between the deformed surface and the flat, m (row-major; 0 in contact).
    pub gap_m: Vec<f64>,
    /// Whether each point is in contact (row-major).
    #[serde(skip)]
    pub contact: Vec<bool>,
    /// Mean traction (load per nominal area), Pa.
    pub mean_pressure_pa: f64,
    /// Mean gap, m.
    pub mean_gap_m: f64,
    /// Fraction of points in contact, `A_r/A0`.
    pub contact_fraction: f64,
    /// Real contact area `A_r`, m^2.
    pub contact_area_m2: f64,
    /// Points in the cohesive zone (gap below the range, contact included), as a fraction (0
    /// without adhesion).
    pub cohesive_fraction: f64,
    /// Number of contact patches (periodic 4-connected components).
    pub patches: usize,
    /// Elastic energy per nominal area, J/m^2.
    pub elastic_energy_j_per_m2: f64,
    /// Conjugate-gradient iterations (summed over cohesive-zone updates).
    pub iterations: usize,
    /// Cohesive-zone updates (1 without adhesion).
    pub zone_updates: usize,
    /// Final complementarity residual.
    pub residual: f64,
    /// The candidate set of a solve on a set of points, verified on the whole grid
    /// ([`crate::restricted`]); `None` when the solve iterated on the whole grid.
    #[serde(skip)]
    pub restriction: Option<Restriction>,
}

/// How a solve on a set of candidate points went ([`crate::restricted`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Restriction {
    /// Points in the first candidate set.
    pub initial_points: usize,
    /// Points in the final set (the one the returned state was solved and verified on).
    pub points: usize,
    /// Whole-grid checks of the complementarity conditions off the set (one per verified
    /// solve, one more per check that found a point to add).
    pub checks: usize,
}

/// Load `mean_pressure_pa * A0` and friction helpers.
impl ContactSolution {
    /// Normal load on the cell, N (`mean pressure * A0`).
    pub fn load_n(&self, grid: &Grid) -> f64 {
        self.mean_pressure_pa * grid.area_m2()
    }

    /// Static friction `F = s A_r` (N) for an interfacial shear strength `s` (Pa).
    pub fn friction_n(&self, shear_strength_pa: f64) -> f64 {
        shear_strength_pa * self.contact_area_m2
    }
}

/// The rough-contact problem: a height field on a half-space.
#[derive(Debug)]
pub struct BemSolver {
    pub(crate) half: HalfSpace,
    pub(crate) heights: Vec<f64>,
    height_mean: f64,
    height_max: f64,
    pub(crate) height_rms: f64,
    stiff_rms: f64,
}

/// The rms of `E*|q| h/2` (Pa), the scale of the dual (mean-gap) residual, on the periodic cell;
/// 0 on the finite patch, where the dual solves are refused ([`BemSolver::require_periodic`]).
fn stiffness_rms(half: &mut HalfSpace, heights_m: &[f64]) -> f64 {
    if half.boundary() == Boundary::NonPeriodic {
        return 0.0;
    }
    let k = half.traction(heights_m);
    (block_sum(k.len(), |r| k[r].iter().map(|v| v * v).sum()) / k.len() as f64).sqrt()
}

/// Output of the constrained conjugate gradient.
pub(crate) struct CgOut {
    /// The complementary field `r - mean_{x>0} r`.
    pub(crate) complementary: Vec<f64>,
    /// `mean_{x>0} r`: the Lagrange multiplier of the mean (minus the rigid approach under load
    /// control).
    pub(crate) multiplier: f64,
    pub(crate) iterations: usize,
    pub(crate) residual: f64,
}

impl BemSolver {
    /// The problem of the row-major height field `heights_m` (m, toward the flat; `nx` columns by
    /// `ny` rows of `dx_m x dy_m` pixels, periodic) on a half-space of composite modulus `e_star_pa`.
    pub fn new(
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
        heights_m: &[f64],
        e_star_pa: f64,
    ) -> Result<Self, BemError> {
        Self::with_boundary(nx, ny, dx_m, dy_m, heights_m, e_star_pa, Boundary::Periodic)
    }

    /// As [`Self::new`], with the Green's function of `boundary`: [`Boundary::NonPeriodic`] makes
    /// the grid a finite patch (a shoe face) on a half-space that goes on ([`crate::green`]);
    /// only load-controlled solves are then available.
    pub fn with_boundary(
        nx: usize,
        ny: usize,
        dx_m: f64,
        dy_m: f64,
        heights_m: &[f64],
        e_star_pa: f64,
        boundary: Boundary,
    ) -> Result<Self, BemError> {
        let grid = Grid::new(nx, ny, dx_m, dy_m)?;
        if heights_m.len() != grid.len() {
            return Err(BemError::HeightLength { len: heights_m.len(), expected: grid.len() });
        }
        if let Some((index, &value)) = heights_m.iter().enumerate().find(|(_, h)| !h.is_finite()) {
            return Err(BemError::HeightValue { index, value });
        }
        let mut half = match boundary {
            Boundary::Periodic => HalfSpace::new(grid, e_star_pa)?,
            Boundary::NonPeriodic => HalfSpace::non_periodic(grid, e_star_pa)?,
        };
        let n = grid.len() as f64;
        let height_mean = block_sum(heights_m.len(), |r| heights_m[r].iter().sum()) / n;
        let height_max = heights_m.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let height_rms =
            (block_sum(heights_m.len(), |r| heights_m[r].iter().map(|h| (h - height_mean).powi(2)).sum()) / n).sqrt();
        let stiff_rms = stiffness_rms(&mut half, heights_m);
        Ok(BemSolver { half, heights: heights_m.to_vec(), height_mean, height_max, height_rms, stiff_rms })
    }

    /// The grid.
    pub fn grid(&self) -> Grid {
        self.half.grid
    }

    /// Replaces the height field (same grid; finite values checked) and its statistics, keeping
    /// the half-space (FFT plans and multipliers): for a rigid shoe whose pose changes.
    pub fn set_heights(&mut self, heights_m: &[f64]) -> Result<(), BemError> {
        let n = self.heights.len();
        if heights_m.len() != n {
            return Err(BemError::HeightLength { len: heights_m.len(), expected: n });
        }
        if let Some((index, &value)) = heights_m.iter().enumerate().find(|(_, h)| !h.is_finite()) {
            return Err(BemError::HeightValue { index, value });
        }
        self.heights.copy_from_slice(heights_m);
        let nf = n as f64;
        self.height_mean = block_sum(n, |r| heights_m[r].iter().sum()) / nf;
        self.height_max = heights_m.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let m = self.height_mean;
        self.height_rms = (block_sum(n, |r| heights_m[r].iter().map(|h| (h - m).powi(2)).sum()) / nf).sqrt();
        self.stiff_rms = stiffness_rms(&mut self.half, heights_m);
        Ok(())
    }

    /// The height field, m (row-major).
    pub fn heights_m(&self) -> &[f64] {
        &self.heights
    }

    /// The Green's function in use.
    pub fn boundary(&self) -> Boundary {
        self.half.boundary()
    }

    /// Refuses a mean-gap (dual) solve on a non-periodic half-space, whose stiffness operator is
    /// not diagonal in Fourier space.
    fn require_periodic(&self) -> Result<(), BemError> {
        if self.half.boundary() == Boundary::NonPeriodic {
            return Err(BemError::Value {
                name: "mean_gap_m",
                value: f64::NAN,
                expected: "load control on a non-periodic half-space (mean-gap control needs the periodic \
                           Green's function)",
            });
        }
        Ok(())
    }

    /// The half-space (for displacements and energies of a solution).
    pub fn half_space(&mut self) -> &mut HalfSpace {
        &mut self.half
    }

    /// Rms height of the field, m.
    pub fn height_rms_m(&self) -> f64 {
        self.height_rms
    }

    /// Rms slope `h'_rms` (spectral: `sqrt(sum q^2 |h(q)|^2)`), the quantity of the light-load law
    /// `A/A0 = kappa p/(E* h'_rms)`.
    pub fn slope_rms(&self) -> f64 {
        synth::rms_slope(&self.heights, self.half.grid)
    }

    /// The constrained conjugate gradient on `x >= 0` with `mean(x) = target` for the operator
    /// `op` and data `b` (residual `r = A x - b`, complementary field `r - mean_{x>0} r`).
    fn constrained_cg(
        &mut self,
        op: Operator,
        b: &[f64],
        x: &mut [f64],
        target: f64,
        scale: f64,
        opts: &SolverOptions,
    ) -> Result<CgOut, BemError> {
        let n = x.len();
        let mut a = GridOperator { half: &mut self.half, op };
        in_pool(|| constrained_cg(&mut a, b, x, target, n, scale, opts))
    }

    #[allow(clippy::too_many_arguments)]
    pub(crate) fn finish(
        &mut self,
        pressure_pa: Vec<f64>,
        gap_m: Vec<f64>,
        contact: Vec<bool>,
        cohesive_points: usize,
        iterations: usize,
        zone_updates: usize,
        residual: f64,
    ) -> ContactSolution {
        self.finish_with(pressure_pa, gap_m, contact, cohesive_points, iterations, zone_updates, residual, None, None)
    }

    /// [`Self::finish`] with the displacement `u = K[pressure_pa]` already computed (for the
    /// elastic energy) and the candidate set of a restricted solve.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn finish_with(
        &mut self,
        pressure_pa: Vec<f64>,
        gap_m: Vec<f64>,
        contact: Vec<bool>,
        cohesive_points: usize,
        iterations: usize,
        zone_updates: usize,
        residual: f64,
        displacement_m: Option<&[f64]>,
        restriction: Option<Restriction>,
    ) -> ContactSolution {
        let grid = self.half.grid;
        let n = grid.len() as f64;
        let mean_pressure_pa = block_sum(pressure_pa.len(), |r| pressure_pa[r].iter().sum()) / n;
        let mean_gap_m = block_sum(gap_m.len(), |r| gap_m[r].iter().sum()) / n;
        let n_contact = contact.iter().filter(|&&c| c).count();
        let contact_fraction = n_contact as f64 / n;
        let patches = match self.half.boundary() {
            Boundary::Periodic => patches::count_patches(&contact, grid.nx, grid.ny),
            Boundary::NonPeriodic => patches::count_patches_bounded(&contact, grid.nx, grid.ny),
        };
        let elastic_energy_j_per_m2 = match displacement_m {
            Some(u) => 0.5 * block_sum(u.len(), |r| r.map(|i| pressure_pa[i] * u[i]).sum()) / u.len() as f64,
            None => self.half.elastic_energy_j_per_m2(&pressure_pa),
        };
        ContactSolution {
            pressure_pa,
            gap_m,
            contact,
            mean_pressure_pa,
            mean_gap_m,
            contact_fraction,
            contact_area_m2: contact_fraction * grid.area_m2(),
            cohesive_fraction: cohesive_points as f64 / n,
            patches,
            elastic_energy_j_per_m2,
            iterations,
            zone_updates,
            residual,
            restriction,
        }
    }

    /// Non-adhesive contact under load control: mean pressure `mean_pressure_pa` (Pa, > 0)
    /// (Polonsky-Keer). `warm`: a previous solution to start from.
    pub fn solve_load(
        &mut self,
        mean_pressure_pa: f64,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        opts.validate()?;
        check_positive("mean_pressure_pa", mean_pressure_pa, "a finite mean pressure > 0 (Pa)")?;
        // On the finite patch: first on a set of candidate points, verified on the whole grid.
        if let Ok(s) = self.restricted_at_load(mean_pressure_pa, None, opts, warm, None) {
            return Ok(s.solution);
        }
        let n = self.heights.len();
        let mut p = match warm {
            Some(s) if s.pressure_pa.len() == n && s.mean_pressure_pa > 0.0 => {
                let f = mean_pressure_pa / s.mean_pressure_pa;
                s.pressure_pa.iter().map(|p| (p * f).max(0.0)).collect()
            }
            _ => vec![mean_pressure_pa; n],
        };
        if !p.iter().any(|&v| v > 0.0) {
            p.fill(mean_pressure_pa);
        }
        let b = self.heights.clone();
        let out = match self.constrained_cg(Operator::Compliance, &b, &mut p, mean_pressure_pa, self.height_rms, opts) {
            // A warm start whose residual vanishes on its contact set (a single contact point)
            // gives the first step no direction; start again from the uniform pressure.
            Err(BemError::NoConvergence { .. }) if warm.is_some() => {
                p.fill(mean_pressure_pa);
                self.constrained_cg(Operator::Compliance, &b, &mut p, mean_pressure_pa, self.height_rms, opts)?
            }
            other => other?,
        };
        let contact: Vec<bool> = p.iter().map(|&v| v > 0.0).collect();
        let gap: Vec<f64> =
            out.complementary.iter().zip(&contact).map(|(g, &c)| if c { 0.0 } else { g.max(0.0) }).collect();
        Ok(self.finish(p, gap, contact, 0, out.iterations, 1, out.residual))
    }

    /// Non-adhesive contact under mean-gap control: `mean(g) = mean_gap_m` (m, > 0) (the dual
    /// iteration of Rey et al. 2017). Above `max(h) - mean(h)` there is no contact.
    pub fn solve_mean_gap(
        &mut self,
        mean_gap_m: f64,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        opts.validate()?;
        self.require_periodic()?;
        check_positive("mean_gap_m", mean_gap_m, "a finite mean gap > 0 (m)")?;
        let b = self.data_for_gap(None);
        self.gap_solve(&b, mean_gap_m, opts, warm.map(|s| s.gap_m.as_slice())).map(|(g, p, it, res)| {
            let contact: Vec<bool> = g.iter().map(|&v| v == 0.0).collect();
            let nc = contact.iter().filter(|&&c| c).count();
            self.finish(p, g, contact, nc, it, 1, res)
        })
    }

    /// `b = -K^-1[h']` for the dual iteration, with `h' = h + K[sum_k sigma_k 1_Z_k]` when zones
    /// are given (one per cohesive law, each of `n` points, concatenated).
    fn data_for_gap(&mut self, zone: Option<(&[bool], &[Dugdale])>) -> Vec<f64> {
        let mut hp = self.heights.clone();
        let n = hp.len();
        if let Some((z, laws)) = zone {
            let f: Vec<f64> = (0..n)
                .map(|i| laws.iter().enumerate().fold(0.0, |t, (k, l)| if z[k * n + i] { t + l.stress_pa } else { t }))
                .collect();
            let u = self.half.displacement(&f);
            hp.iter_mut().zip(&u).for_each(|(h, u)| *h += u);
        }
        let mut b = self.half.traction(&hp);
        b.iter_mut().for_each(|v| *v = -*v);
        b
    }

    /// Dual solve for data `b`; returns (gap, contact pressure, iterations, residual).
    fn gap_solve(
        &mut self,
        b: &[f64],
        mean_gap_m: f64,
        opts: &SolverOptions,
        warm: Option<&[f64]>,
    ) -> Result<(Vec<f64>, Vec<f64>, usize, f64), BemError> {
        let n = self.heights.len();
        let mut g: Vec<f64> = match warm {
            Some(w) if w.len() == n && w.iter().any(|&v| v > 0.0) => w.to_vec(),
            _ => {
                let top = mean_gap_m + self.height_mean;
                self.heights.iter().map(|h| (top - h).max(0.0)).collect()
            }
        };
        let mean = g.iter().sum::<f64>() / n as f64;
        if mean > 0.0 {
            g.iter_mut().for_each(|v| *v *= mean_gap_m / mean);
        } else {
            g.fill(mean_gap_m);
        }
        let out = self.constrained_cg(Operator::Stiffness, b, &mut g, mean_gap_m, self.stiff_rms, opts)?;
        let p: Vec<f64> =
            out.complementary.iter().zip(&g).map(|(p, &g)| if g > 0.0 { 0.0 } else { p.max(0.0) }).collect();
        Ok((g, p, out.iterations, out.residual))
    }

    /// Whether a mean gap `mean_gap_m` leaves the undeformed surface out of contact.
    pub fn out_of_contact(&self, mean_gap_m: f64) -> bool {
        mean_gap_m >= self.height_max - self.height_mean
    }

    /// Adhesive contact with the Dugdale law `law` under mean-gap control (m, > 0). `warm`: the
    /// previous state of a loading or unloading path (its gap and cohesive zone are the start).
    pub fn solve_adhesive_mean_gap(
        &mut self,
        mean_gap_m: f64,
        law: &Dugdale,
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        self.solve_cohesive_mean_gap(mean_gap_m, std::slice::from_ref(law), opts, warm)
    }

    /// Adhesive contact with several Dugdale laws acting together (a tension `sum_k sigma_k` over
    /// the points whose gap is below each law's range; e.g. van der Waals and a capillary zone,
    /// [`Dugdale::capillary`]) under mean-gap control (m, > 0). The zones are updated together
    /// until none changes. One law is [`Self::solve_adhesive_mean_gap`], to the bit.
    pub fn solve_cohesive_mean_gap(
        &mut self,
        mean_gap_m: f64,
        laws: &[Dugdale],
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        in_pool(|| self.solve_cohesive_on_worker(mean_gap_m, laws, opts, warm))
    }

    /// [`Self::solve_cohesive_mean_gap`] on a pool worker.
    fn solve_cohesive_on_worker(
        &mut self,
        mean_gap_m: f64,
        laws: &[Dugdale],
        opts: &SolverOptions,
        warm: Option<&ContactSolution>,
    ) -> Result<ContactSolution, BemError> {
        opts.validate()?;
        self.require_periodic()?;
        check_positive("mean_gap_m", mean_gap_m, "a finite mean gap > 0 (m)")?;
        if laws.is_empty() {
            return Err(BemError::Value { name: "laws", value: 0.0, expected: "at least one cohesive law" });
        }
        for law in laws {
            check_positive("stress_pa", law.stress_pa, "a finite Dugdale stress > 0 (Pa)")?;
            check_nonnegative("range_m", law.range_m, "a finite range >= 0 (m)")?;
        }
        let n = self.heights.len();
        let top = mean_gap_m + self.height_mean;
        let mut gap: Vec<f64> = match warm {
            Some(w) if w.gap_m.len() == n => w.gap_m.clone(),
            _ => self.heights.iter().map(|h| (top - h).max(0.0)).collect(),
        };
        let zones_of =
            |gap: &[f64]| -> Vec<bool> { laws.iter().flat_map(|l| gap.iter().map(move |&g| g < l.range_m)).collect() };
        let mut zone = zones_of(&gap);
        let mut iterations = 0;
        // The zones are updated from inexact solves ([`zone_tolerance`]) while they change, then
        // confirmed by a solve to the tolerance: a state is returned only when the zones of the
        // converged gap are the zones it was solved with.
        let loose = SolverOptions { tolerance: zone_tolerance(opts.tolerance), ..*opts };
        let mut tight = loose.tolerance <= opts.tolerance;
        for update in 1..=opts.max_zone_updates {
            let b = self.data_for_gap(Some((&zone, laws)));
            let (g, pc, it, res) = self.gap_solve(&b, mean_gap_m, if tight { opts } else { &loose }, Some(&gap))?;
            iterations += it;
            gap = g;
            let new_zone = zones_of(&gap);
            if new_zone == zone && !tight {
                tight = true;
                continue;
            }
            if new_zone == zone {
                let p: Vec<f64> = (0..n)
                    .map(|i| {
                        let t = laws
                            .iter()
                            .enumerate()
                            .fold(0.0, |t, (k, l)| if zone[k * n + i] { t + l.stress_pa } else { t });
                        if (0..laws.len()).any(|k| zone[k * n + i]) { pc[i] - t } else { pc[i] }
                    })
                    .collect();
                let contact: Vec<bool> = gap.iter().map(|&v| v == 0.0).collect();
                let nz = (0..n).filter(|&i| (0..laws.len()).any(|k| zone[k * n + i])).count();
                return Ok(self.finish(p, gap, contact, nz, iterations, update, res));
            }
            zone = new_zone;
        }
        Err(BemError::NoConvergence {
            what: "Dugdale cohesive-zone update",
            iterations: opts.max_zone_updates,
            residual: f64::NAN,
            tolerance: 0.0,
        })
    }
}

/// A linear operator of the constrained conjugate gradient ([`constrained_cg`]): the half-space's
/// on the whole grid ([`GridOperator`]), or its influence matrix on a set of points
/// ([`crate::restricted`]).
pub(crate) trait CgOperator {
    /// `out = A[input]`.
    fn apply(&mut self, input: &[f64], out: &mut [f64]);
    /// `out = A[field]` after `prepare(offset, block)` has rewritten `field` block by block.
    fn apply_prepared<P: Fn(usize, &mut [f64]) + Sync>(&mut self, field: &mut [f64], prepare: P, out: &mut [f64]);
}

/// The half-space's operator `op` on the whole grid.
pub(crate) struct GridOperator<'a> {
    pub(crate) half: &'a mut HalfSpace,
    pub(crate) op: Operator,
}

impl CgOperator for GridOperator<'_> {
    fn apply(&mut self, input: &[f64], out: &mut [f64]) {
        self.half.apply(self.op, input, out);
    }
    fn apply_prepared<P: Fn(usize, &mut [f64]) + Sync>(&mut self, field: &mut [f64], prepare: P, out: &mut [f64]) {
        self.half.apply_prepared(self.op, field, prepare, out);
    }
}

/// The constrained conjugate gradient on `x >= 0` with `sum(x)/n_mean = target` for the operator
/// `a` and data `b` (residual `r = A x - b`, complementary field `r - mean_{x>0} r`); on the whole
/// grid `n_mean` is the number of points, on a set of them ([`crate::restricted`]) the grid's, so
/// that the mean and the residual are the whole grid's with `x = 0` off the set. Each iteration is
/// seven parallel passes over `x` besides its convolution's five (the direction is built in the
/// convolution's first pass); the block sums are those of [`block_sum`], so the bytes do not
/// depend on the thread count. Call it on a pool worker ([`in_pool`]).
pub(crate) fn constrained_cg<A: CgOperator>(
    a: &mut A,
    b: &[f64],
    x: &mut [f64],
    target: f64,
    n_mean: usize,
    scale: f64,
    opts: &SolverOptions,
) -> Result<CgOut, BemError> {
    let n = x.len();
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let mut r = vec![0.0; n];
    let mut ax = vec![0.0; n];
    let mut t = vec![0.0; n];
    let mut w = vec![0.0; n];
    let mut g_old = 1.0;
    let mut delta = 0.0;
    let mut residual = f64::INFINITY;
    // `ax = A x` is updated from `A t` when a step moves no point on or off the bound (one
    // convolution per iteration), and recomputed after a projection or release, every
    // REFRESH iterations and before accepting convergence (two convolutions).
    const REFRESH: usize = 50;
    a.apply(x, &mut ax);
    let mut exact = true;
    let mut it = 0;
    while it < opts.max_iterations {
        if !exact && it % REFRESH == 0 {
            a.apply(x, &mut ax);
            exact = true;
        }
        // r = A x - b, and the count and sum of r on the active set S = {x > 0}.
        let parts: Vec<(f64, f64)> = {
            let (xs, ax) = (&*x, &ax);
            r.par_chunks_mut(SUM_BLOCK)
                .enumerate()
                .map(|(k, rc)| {
                    let o = k * SUM_BLOCK;
                    for (j, r) in rc.iter_mut().enumerate() {
                        *r = ax[o + j] - b[o + j];
                    }
                    (0..rc.len()).filter(|&j| xs[o + j] > 0.0).fold((0.0, 0.0), |a, j| (a.0 + 1.0, a.1 + rc[j]))
                })
                .collect()
        };
        let (ns, sum_rs) = parts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        if ns == 0.0 {
            return Err(BemError::NoConvergence {
                what: "constrained CG (empty active set)",
                iterations: it,
                residual,
                tolerance: opts.tolerance,
            });
        }
        let rbar = sum_rs / ns;
        // r -= mean_S r; the residual's two sums and the squared norm of r on S.
        let parts: Vec<(f64, f64, f64)> = {
            let xs = &*x;
            r.par_chunks_mut(SUM_BLOCK)
                .enumerate()
                .map(|(k, rc)| {
                    let o = k * SUM_BLOCK;
                    rc.iter_mut().for_each(|r| *r -= rbar);
                    let (sx, sv) = (0..rc.len()).fold((0.0, 0.0), |a, j| {
                        let xi = xs[o + j];
                        if xi > 0.0 {
                            (a.0 + xi, a.1 + xi * rc[j].abs())
                        } else {
                            (a.0, a.1 + (-rc[j]).max(0.0) * target)
                        }
                    });
                    let g: f64 = (0..rc.len()).filter(|&j| xs[o + j] > 0.0).map(|j| rc[j] * rc[j]).sum();
                    (sx, sv, g)
                })
                .collect()
        };
        let (sum_x, sum_viol) = parts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        residual = sum_viol / (sum_x * scale);
        if residual < opts.tolerance {
            if exact {
                return Ok(CgOut { complementary: r, multiplier: rbar, iterations: it, residual });
            }
            a.apply(x, &mut ax);
            exact = true;
            continue;
        }
        let g: f64 = parts.iter().map(|p| p.2).sum();
        let beta = delta * g / g_old;
        // t = r + beta t on S, 0 elsewhere, built in the convolution's first pass; w = A t.
        {
            let (xs, rs) = (&*x, &r);
            a.apply_prepared(
                &mut t,
                |o, tc| {
                    for (j, t) in tc.iter_mut().enumerate() {
                        let i = o + j;
                        *t = if xs[i] > 0.0 { rs[i] + beta * *t } else { 0.0 };
                    }
                },
                &mut w,
            );
        }
        g_old = g;
        let sum_w = block_sum(n, |rg| rg.filter(|&i| x[i] > 0.0).map(|i| w[i]).sum());
        let wbar = sum_w / ns;
        let (num, den) = block_sum2(n, |rg| {
            rg.filter(|&i| x[i] > 0.0).fold((0.0, 0.0), |a, i| (a.0 + r[i] * t[i], a.1 + (w[i] - wbar) * t[i]))
        });
        if den <= 0.0 || !den.is_finite() {
            return Err(BemError::NoConvergence {
                what: "constrained CG (no descent)",
                iterations: it,
                residual,
                tolerance: opts.tolerance,
            });
        }
        let tau = num / den;
        // Step on the active set, project on x >= 0, and release the points that overlap
        // (x = 0 with a negative complementary field); in the same pass, count the points
        // the step put on the bound and sum x.
        let parts: Vec<(usize, f64, f64)> = x
            .par_chunks_mut(SUM_BLOCK)
            .zip(t.par_chunks(SUM_BLOCK))
            .zip(r.par_chunks(SUM_BLOCK))
            .map(|((x, t), r)| {
                let mut k = 0;
                for ((x, t), r) in x.iter_mut().zip(t).zip(r) {
                    if *x > 0.0 {
                        *x = (*x - tau * t).max(0.0);
                    } else if *r < 0.0 {
                        *x = -tau * r;
                        k += 1;
                    }
                }
                let bound = x.iter().zip(t).filter(|&(x, t)| *t != 0.0 && *x == 0.0).count() as f64;
                let sum: f64 = x.iter().sum();
                (k, bound, sum)
            })
            .collect();
        let n_overlap: usize = parts.iter().map(|p| p.0).sum();
        delta = if n_overlap == 0 { 1.0 } else { 0.0 };
        let n_bound: f64 = parts.iter().map(|p| p.1).sum();
        let mean = parts.iter().map(|p| p.2).sum::<f64>() / n_mean as f64;
        if mean.is_nan() || mean <= 0.0 {
            return Err(BemError::NoConvergence {
                what: "constrained CG (all points released)",
                iterations: it,
                residual,
                tolerance: opts.tolerance,
            });
        }
        let f = target / mean;
        it += 1;
        if n_overlap == 0 && n_bound == 0.0 {
            x.par_chunks_mut(SUM_BLOCK).zip(ax.par_chunks_mut(SUM_BLOCK)).zip(w.par_chunks(SUM_BLOCK)).for_each(
                |((x, a), w)| {
                    for ((x, a), w) in x.iter_mut().zip(a).zip(w) {
                        *x *= f;
                        *a = f * (*a - tau * w);
                    }
                },
            );
            exact = false;
        } else {
            x.par_chunks_mut(SUM_BLOCK).for_each(|x| x.iter_mut().for_each(|x| *x *= f));
            a.apply(x, &mut ax);
            exact = true;
        }
    }
    Err(BemError::NoConvergence {
        what: "constrained conjugate gradient",
        iterations: opts.max_iterations,
        residual,
        tolerance: opts.tolerance,
    })
}

/// Tolerance of the inexact solves between cohesive-zone updates for the caller's `tolerance`:
/// 100 times it, at most 1e-4 (the last solve, whose zones do not change, is to the tolerance).
/// At 1e-3 the zones of the inexact gaps send some states of a rough path into other equilibria
/// (up to 93 pixels of contact on the 128^2 comparison path); at 1e-4 they are the same
/// equilibria to 2 pixels, with 40 % fewer iterations.
fn zone_tolerance(tolerance: f64) -> f64 {
    (100.0 * tolerance).min(1e-4).max(tolerance)
}

/// A retraction under mean-gap control with cohesive laws, and its work ([`BemSolver::work_of_separation`]).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Separation {
    /// Work of separation per nominal area `Gamma = int max(-p_bar, 0) d g_bar` over the
    /// retraction (trapezoid rule), J/m^2: the adhesion energy of a microcantilever experiment.
    pub adhesion_energy_j_per_m2: f64,
    /// Most tensile mean traction on the way (the pull-off pressure, <= 0), Pa.
    pub pull_off_pressure_pa: f64,
    /// Mean gap of the first and last state, m.
    pub start_mean_gap_m: f64,
    /// Mean gap of the last state (no contact, no cohesive zone), m.
    pub end_mean_gap_m: f64,
    /// Mean-gap steps.
    pub steps: usize,
    /// Conjugate-gradient iterations, summed.
    pub iterations: usize,
}

/// Most mean-gap steps [`BemSolver::work_of_separation`] takes.
pub const MAX_SEPARATION_STEPS: usize = 20_000;

impl BemSolver {
    /// Retracts the flat from the mean gap `start_mean_gap_m` (m, > 0; a compressed state) in
    /// steps of `step_m` (m, > 0), each state warm-started from the one before (the cohesive
    /// zones follow the path), until no point is in contact or in a zone and the mean gap exceeds
    /// `max(h) - mean(h) + max range`; returns the work of separation
    /// `Gamma = int max(-p_bar, 0) d g_bar` (the tensile part of the retraction: from where the
    /// mean traction crosses zero, the adhered state at zero load, to separation). For a flat
    /// interface with one law this is `sigma0 h0` (to `sigma0 step / 2`, the trapezoid's error at
    /// the jump); with [`Dugdale::capillary`] it is `gamma (cos th1 + cos th2)`.
    ///
    /// Errors: bad values, a path longer than [`MAX_SEPARATION_STEPS`] steps, a solve that fails.
    pub fn work_of_separation(
        &mut self,
        laws: &[Dugdale],
        start_mean_gap_m: f64,
        step_m: f64,
        opts: &SolverOptions,
    ) -> Result<Separation, BemError> {
        check_positive("start_mean_gap_m", start_mean_gap_m, "a finite mean gap > 0 (m)")?;
        check_positive("step_m", step_m, "a finite mean-gap step > 0 (m)")?;
        let reach = laws.iter().fold(0.0f64, |m, l| m.max(l.range_m));
        let end = (self.height_max - self.height_mean) + reach;
        let planned = ((end - start_mean_gap_m).max(0.0) / step_m).ceil() + 1.0;
        if planned > MAX_SEPARATION_STEPS as f64 {
            return Err(BemError::Value {
                name: "step_m",
                value: step_m,
                expected: "a step giving at most 20000 steps from the start to separation (a larger step)",
            });
        }
        let mut g = start_mean_gap_m;
        let mut state = self.solve_cohesive_mean_gap(g, laws, opts, None)?;
        let mut iterations = state.iterations;
        let tension = |s: &ContactSolution| (-s.mean_pressure_pa).max(0.0);
        let mut work = 0.0;
        let mut pull_off = state.mean_pressure_pa.min(0.0);
        let mut steps = 0;
        while !(g > end && state.cohesive_fraction == 0.0 && state.contact_fraction == 0.0) {
            if steps >= MAX_SEPARATION_STEPS {
                return Err(BemError::NoConvergence {
                    what: "retraction to separation",
                    iterations: steps,
                    residual: g,
                    tolerance: end,
                });
            }
            let next = self.solve_cohesive_mean_gap(g + step_m, laws, opts, Some(&state))?;
            iterations += next.iterations;
            work += 0.5 * (tension(&state) + tension(&next)) * step_m;
            pull_off = pull_off.min(next.mean_pressure_pa);
            g += step_m;
            state = next;
            steps += 1;
        }
        Ok(Separation {
            adhesion_energy_j_per_m2: work,
            pull_off_pressure_pa: pull_off,
            start_mean_gap_m,
            end_mean_gap_m: g,
            steps,
            iterations,
        })
    }
}
