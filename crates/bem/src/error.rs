//! Errors of the boundary-element solver.

use thiserror::Error;

/// Errors of the boundary-element solver (bad input or no convergence).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum BemError {
    /// A grid dimension out of range.
    #[error("grid {nx} x {ny}: expected 2 <= nx, ny and nx * ny <= {limit} points")]
    GridSize {
        /// Columns.
        nx: usize,
        /// Rows.
        ny: usize,
        /// The limit on the number of points.
        limit: usize,
    },
    /// The height field's length does not match the grid.
    #[error("height field has {len} values, expected nx * ny = {expected}")]
    HeightLength {
        /// Values given.
        len: usize,
        /// Values expected.
        expected: usize,
    },
    /// A height is not finite.
    #[error("height at index {index} is {value}, expected a finite number (m)")]
    HeightValue {
        /// Row-major index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The height field has missing (NaN) or infinite values.
    #[error(
        "the height map has {count} missing or non-finite pixel(s) (the first at row-major index {first_index}); \
         the boundary-element solver needs a complete periodic grid: fill or crop the map first"
    )]
    MissingHeights {
        /// How many.
        count: usize,
        /// The first, row-major.
        first_index: usize,
    },
    /// A scalar input out of range.
    #[error("{name} = {value}: expected {expected}")]
    Value {
        /// The input's name.
        name: &'static str,
        /// The value.
        value: f64,
        /// What was expected.
        expected: &'static str,
    },
    /// A tilting shoe spent its work budget ([`PATH_WORK_FACTOR`] times the per-solve iteration
    /// cap, over every pose of every start) without balancing its moments.
    #[error(
        "tilting shoe at the mean pressure {target_pa:e} Pa: no balance within {iterations} conjugate-gradient \
         iterations over all its poses (the work budget); a coarser grid (contact.bem.pixel_size) or a flat shoe \
         resolves it"
    )]
    TiltWorkBudget {
        /// Iterations spent.
        iterations: usize,
        /// The target mean pressure, Pa.
        target_pa: f64,
    },
    /// An adhesive loading path spent its work budget ([`PATH_WORK_FACTOR`] times the per-solve
    /// iteration cap) without reaching the load.
    #[error(
        "{what} did not reach the mean pressure {target_pa:e} Pa within {iterations} conjugate-gradient iterations \
         (Dugdale stress {stress_pa:e} Pa over the range {range_m:e} m): the cohesive zone keeps switching; a \
         longer range or a coarser grid resolves it"
    )]
    WorkBudget {
        /// Which path.
        what: &'static str,
        /// Iterations spent.
        iterations: usize,
        /// The target mean pressure, Pa.
        target_pa: f64,
        /// The Dugdale stress, Pa.
        stress_pa: f64,
        /// The Dugdale range, m.
        range_m: f64,
    },
    /// A capped pose of the tilting shoe was not solved on a set of candidate points (those poses
    /// are solved on sets, [`crate::restricted`], and on the whole grid only when the contact
    /// outgrows the largest set).
    #[error(
        "tilting shoe with the hardness cap at the mean pressure {target_pa:e} Pa: a pose was not solved on a set of \
         candidate points (the set solve gave up; the capped tilting shoe is not solved on the whole grid for a \
         contact that fits a set, where the capped iteration can stall for minutes); a higher hardness, a coarser \
         grid (contact.bem.pixel_size) or a flat shoe resolves it"
    )]
    CappedPoseOffSet {
        /// The target mean pressure, Pa.
        target_pa: f64,
    },
    /// The iteration did not reach the tolerance.
    #[error("{what} did not converge in {iterations} iterations (residual {residual:e}, tolerance {tolerance:e})")]
    NoConvergence {
        /// Which iteration.
        what: &'static str,
        /// Iterations done.
        iterations: usize,
        /// Last residual.
        residual: f64,
        /// Tolerance asked for.
        tolerance: f64,
    },
}

/// The work a loading path may take before it is given up, in conjugate-gradient iterations:
/// this many times the per-solve cap (`SolverOptions::max_iterations`).
pub const PATH_WORK_FACTOR: usize = 20;

pub(crate) fn check_positive(name: &'static str, value: f64, expected: &'static str) -> Result<f64, BemError> {
    if value.is_finite() && value > 0.0 { Ok(value) } else { Err(BemError::Value { name, value, expected }) }
}

pub(crate) fn check_nonnegative(name: &'static str, value: f64, expected: &'static str) -> Result<f64, BemError> {
    if value.is_finite() && value >= 0.0 { Ok(value) } else { Err(BemError::Value { name, value, expected }) }
}
