//! FFT-based boundary-element method (BEM) for the normal contact of a rough elastic half-space
//! with a rigid flat, periodic in the plane, with or without Maugis-Dugdale adhesion.
//!
//! # Model
//! The two bodies are replaced by the usual composite problem: a rigid flat against an elastic
//! half-space of modulus `E* = (sum (1 - nu_i^2)/E_i)^-1` (Pa; in the paper's notation
//! `E* = 3/(4D)`) whose surface carries the composite roughness `h(x, y)` (m, the height *toward* the
//! flat, row-major on an `ny x nx` grid of pixels `dx x dy`, periodic). With the flat at height `d`,
//! the gap is `g = d - h + u` (m), where `u >= ...` is the elastic displacement of the surface away
//! from the flat under the traction `p` (Pa, compressive positive).
//!
//! # Green's function, zero mode and periodic images
//! The displacement of a periodic half-space is diagonal in Fourier space (Johnson 1985, sec. 13;
//! Stanley & Kato 1997): `u(q) = 2 p(q) / (E* |q|)` for `q != 0`. [`HalfSpace`] evaluates it with a
//! real-to-complex FFT (`realfft` rows, `rustfft` columns) on the grid's discrete wave vectors,
//! with the continuous kernel `2/(E* |q|)` sampled at each `q` (as Tamaas and ContactMechanics do).
//! Because the FFT is periodic, the solution is that of an infinite array of copies of the cell
//! (the periodic images), which is what a statistically homogeneous rough surface needs; an
//! isolated body (the Hertz tests) must be small against the cell (the image correction to the
//! contact radius is of order `(a/L)^3`). The zero mode `q = 0` (a uniform pressure on a periodic
//! half-space) gives an unbounded uniform displacement: its compliance is set to 0, so `u` has zero
//! mean and the rigid-body approach is carried by `d` (mean-gap control fixes `mean(g)`, load
//! control fixes `mean(p)`; the mean gap then comes out as `mean(g) = d - mean(h)`).
//!
//! # Non-adhesive contact: constrained conjugate gradient
//! Load control uses the constrained conjugate gradient of Polonsky & Keer (1999, Wear 231:206),
//! unknown the pressure `p >= 0`, with its mean fixed by rescaling. Mean-gap control uses the dual
//! form of Rey, Anciaux & Molinari (2017, Comput. Mech. 60:69, "Normal adhesive contact on rough
//! surfaces: efficient algorithm for FFT-based BEM resolution"): the same iteration on the gap
//! `g >= 0` with the stiffness operator `p(q) = E* |q| g(q)/2`, mean gap fixed by rescaling. Both are
//! one routine ([`HalfSpace`] is the operator, the pressure or the gap the unknown): they are the
//! methods of the reference code Tamaas (class `PolonskyKeerRey`), converge in a few hundred
//! iterations independently of the grid for rough surfaces, and need two FFT convolutions per
//! iteration. The residual is the complementarity error of Tamaas,
//! `eps = (sum_S x |r| + mean(x) sum_{x=0} max(-r, 0)) / (sum x * scale)`, where `x` is the unknown,
//! `r` its complementary field (the gap for the pressure, the pressure for the gap), `S = {x > 0}` and
//! `scale` the rms of the data (`h` or `E*|q| h/2`); the solve stops at `eps < tolerance`.
//!
//! # Adhesion: Maugis-Dugdale cohesive zone
//! The surfaces attract with the Dugdale law: a tension `sigma0` (Pa) wherever the gap is below the
//! range `h0` (m), none beyond, so the work of adhesion is `w = sigma0 h0` (J/m^2); in contact
//! (`g = 0`) the total traction is `p_c - sigma0` with the contact pressure `p_c >= 0`. This is the
//! law of Maugis (1992) behind the analytic Maugis-Dugdale curve in `stiction-contact`, whose Maugis
//! parameter is `lambda = 2 sigma0 (R D^2/(pi w))^(1/3)` with `D = 3/(4 E*)`. For a given cohesive zone
//! `Z = {g < h0}` the problem is the non-adhesive one with the known tension added
//! (`h -> h + sigma0 K[1_Z]`); the zone is updated from the new gap and the solve repeated until it
//! does not change (an active-set fixed point on the zone, warm-started, under mean-gap control so
//! that a retraction can follow the curve past the load minimum to pull-off). The solves between
//! zone updates are inexact (100 times the tolerance, at most 1e-4); the state returned is that of
//! a solve to the tolerance whose zone is the zone it was solved with.
//!
//! # Load control on a set of candidate points
//! On the finite patch the load-controlled solves ([`BemSolver::solve_load`],
//! [`BemSolver::adhesive_at_load`]) first solve the same problem on a set of candidate points
//! with the influence matrix, then check the complementarity conditions on the whole grid with
//! one padded convolution, growing the set where a point off it is in contact or in the zone
//! ([`restricted`]); a verified state is a solution of the whole-grid problem.
//!
//! # Hardness cap
//! Perfectly plastic pixels: the compressive traction bounded by the hardness `H` (Pa), with or
//! without the Dugdale zone (`BemSolver::solve_load_plastic`, `BemSolver::plastic_at_load` with
//! `SolverOptions::hardness_pa`; with adhesion the net traction `p_c - sigma0 <= H`).
//!
//! # Determinism
//! Sums are taken over fixed blocks of the grid and added in order, and the FFTs transform rows and
//! columns independently, so the same input gives the same bytes whatever the thread count.

pub mod asperity;
mod boxqp;
pub mod error;
mod fft;
pub mod green;
mod grid;
pub mod loading;
pub mod patches;
mod plastic;
pub mod restricted;
pub mod shoe;
mod solver;
pub mod spec;
pub mod synth;

pub use error::BemError;
pub use green::Boundary;
pub use grid::{BYTES_PER_POINT, Grid, MAX_POINTS};
pub use loading::LoadingPath;
pub use plastic::PlasticSolution;
pub use shoe::TiltedShoe;
pub use solver::{
    BemSolver, ContactSolution, Dugdale, HalfSpace, MAX_SEPARATION_STEPS, Restriction, Separation, SolverOptions,
};
pub use spec::BemSpec;
