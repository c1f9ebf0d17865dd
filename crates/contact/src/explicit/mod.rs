//! Explicit asperity-by-asperity contact: a rigid, flat shoe face pressed on a rough surface of
//! individual summits ([`stiction_surface::Surface`]) finds its own equilibrium, so the number of
//! contacts comes out of the geometry instead of being assumed (the paper's section 4 assumes N = 3).
//!
//! # Model
//! The shoe face is the plane `w(x, y) = d + t_x (x - x0) + t_y (y - y0)` above the reference plane
//! (d: separation at the load point (x0, y0), paper Fig. 1; t_x, t_y: small tilts). Summit i
//! (height h_i, radius R_i at (x_i, y_i)) has the interference `z_i = h_i - w(x_i, y_i)` and carries
//! the load `P_i(z_i)` of the chosen single-asperity law ([`crate::single`]): Hertz (eq. 3), DMT
//! (eq. 4, default, closed form inlined), JKR or Maugis-Dugdale. Equilibrium under the normal load L:
//!
//! ```text
//! sum_i P_i = L,   sum_i P_i (x_i - x0) = 0,   sum_i P_i (y_i - y0) = 0
//! ```
//! (only the first in [`ShoeMode::Flat`]). These are the stationarity conditions of the potential
//! energy `Pi(q) = sum_i U_i(z_i) + L d` with `U_i = integral P_i dz`.
//!
//! # Method: active-set Newton on the potential energy
//! The DMT load jumps by -2 pi dgamma R when a summit touches, so Pi has kinks and many local
//! minima (every stable equilibrium is one). The solver keeps a *contact set* S (the members):
//! * With S fixed, the energy of the members, continued below their release interference by a
//!   constant force (a convex extension; for DMT: the adhesive pull -2 pi dgamma R with zero
//!   stiffness), is convex in the pose q = (d, t_x l, t_y l) (l = half-diagonal of the apparent
//!   area, so all unknowns are lengths). Newton steps on it use the 3 x 3 Hessian
//!   `sum k_i phi_i phi_i^T`, phi_i = (1, (x_i - x0)/l, (y_i - y0)/l); directions of zero stiffness
//!   (too few contacts to hold a tilt, summits that just touched) get a descent step instead.
//! * Every step is limited by a trust radius on the plane's movement over the apparent area and
//!   accepted by a curvature (Wolfe) test on the directional derivative of the energy; summits
//!   that the trial pose touches (z >= jump-in interference) join S at once.
//! * When the residual with S fixed is below 1e-4 of the load scale, members below their release
//!   interference leave S (DMT: z < 0; JKR/MD: below the displacement-controlled pull-off
//!   interference) and the iteration continues. It ends when the residuals are below
//!   `relative_tolerance` (default 1e-9) of the load scale max(|L|, sum|P_i|, 2 pi dgamma R)
//!   and S is consistent; otherwise [`SolveError::NotConverged`] is returned, never a silent result.
//!
//! * Along a load path the first step of a solve is the quadratic extrapolation of the last three
//!   equilibria (when it agrees with the Newton step to 10 %), and the last step is applied without
//!   a pass when the previous pass proves that no summit can change its contact state within it
//!   and bounds the linearisation error below half the tolerance (fast pass only; about 2 passes
//!   per load point instead of 3; [`ExplicitSolver::set_shortcuts`] turns both off).
//!
//! Every accepted step lowers the energy, releases lower it further, so the result is a local
//! minimum reached by descent from the previous state: successive solves follow the load path
//! (jump-in on loading, release and pull-off on unloading, JKR/MD hysteresis per summit). Touching
//! summits join in batches at the trial poses; on a sawtooth of many near-simultaneous jump-ins
//! this can land on a neighbouring local minimum of a strictly one-by-one quasi-static path.
//!
//! # Search structure
//! The summits are kept sorted by descending height (generated surfaces already are; others
//! are sorted once, with a 4-byte index map). A summit can only touch the shoe if its height
//! exceeds the lowest point of the plane over the apparent area plus the law's reach, so each pass
//! touches a prefix found by binary search, plus the members. This costs no memory beyond the
//! summit arrays (16-24 B per summit, + 4 B map, + 1 bit contact set). A parry3d-f64 BVH was
//! measured against it (example `explicit_bvh`, docs/explicit-solver.md): 144 B per summit and a
//! query 20-40x slower than a whole pass, because summit heights do not correlate with position.
//! Hertz/DMT with one radius (tilt free or flat) use a vectorised pass over 64-summit blocks.
//!
//! # Entry points
//! [`ExplicitSolver::new`], [`ExplicitSolver::solve`], [`ExplicitSolver::sweep`],
//! [`ExplicitSolver::pull_off`], [`ExplicitSolver::loading_curve`],
//! [`ExplicitSolver::evaluate_pose`]; the Table 1 study in [`table1`].

mod laws;
mod solver;
pub mod table1;
mod types;

pub use solver::ExplicitSolver;
pub use types::{
    Detail, Equilibrium, Meniscus, ShoeMode, SolveError, SolverConfig, SummitContact, Sweep, SweepEvent, WorkCounters,
};
