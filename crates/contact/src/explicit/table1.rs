//! The paper's Table 1 sidewall under a tilt-free shoe, against the discrete N = 3 model (eq. 12).
//!
//! Table 1: eta = 4e12 m^-2, sigma = 0.04 um, R = 0.5 um, D = 9.1e-12 1/Pa, dgamma = 0.1 J/m^2,
//! A_a = 100 um^2 (the 20 um x 5 um shoe face), about 400 summits; shear strength s = 1.4 GPa
//! (section 5). [`friction_vs_load`] generates the surface for a seed, brings the shoe into
//! contact at zero load, unloads it to pull-off and loads it again through the requested loads,
//! and returns per load the explicit friction capacity s A_r with the number of contacts, beside
//! eq. 12 with N = 3. This is the data behind the finding in docs/explicit-solver.md.

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};
use stiction_surface::{FaceParams, Layout, Placement, generate};

use super::{ExplicitSolver, ShoeMode, SolveError, SolverConfig};
use crate::single::{AdhesionLaw, AsperityParams, Branch};

/// Shear strength fitted in the paper's section 5 \[Pa\].
pub const SHEAR_STRENGTH_PA: f64 = 1.4e9;

/// One load of the comparison.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Table1Point {
    /// Applied load L \[N\].
    pub load_n: f64,
    /// Summits carrying the shoe in the explicit model.
    pub contacts: usize,
    /// Explicit friction capacity s A_r \[N\].
    pub friction_explicit_n: f64,
    /// Discrete model, eq. 12 with N = 3 (DMT) \[N\].
    pub friction_discrete_n3_n: f64,
    /// Explicit real contact area \[m^2\].
    pub real_area_m2: f64,
    /// Largest peak Hertz pressure (eq. 11) \[Pa\].
    pub max_pressure_pa: f64,
    /// Tilt magnitude sqrt(t_x^2 + t_y^2) \[rad\].
    pub tilt_rad: f64,
}

/// The comparison for one generated surface.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table1Comparison {
    /// Seed of the surface.
    pub seed: u64,
    /// Number of summits generated.
    pub summits: usize,
    /// Pull-off load of the explicit contact reached at zero load \[N\] (eq. 12 N = 3 DMT:
    /// -3 x 2 pi dgamma R = -0.94 uN).
    pub pull_off_load_n: f64,
    /// One point per requested load at or above the pull-off load, in increasing load.
    pub points: Vec<Table1Point>,
}

/// Eq. 12: F_f = s N pi R [ D / (N R^1/2) (L + N 2 pi dgamma R) ]^(2/3) for the Table 1 summit
/// (DMT), 0 below the N-contact pull-off load \[N\].
pub fn discrete_friction_n(load_n: f64, contacts: usize) -> f64 {
    let p = AsperityParams::table1();
    let n = contacts as f64;
    let inner = load_n + n * p.dmt_adhesion_n();
    if inner <= 0.0 {
        return 0.0;
    }
    SHEAR_STRENGTH_PA * n * PI * p.radius_m * (p.compliance_per_pa / (n * p.radius_m.sqrt()) * inner).powf(2.0 / 3.0)
}

/// Generates the Table 1 surface for `seed` (Poisson placement) and runs the loading path
/// described in the module docs through `loads_n` (sorted; loads below the pull-off load are
/// left out). `law` is the summit law (the paper: DMT).
pub fn friction_vs_load(seed: u64, loads_n: &[f64], law: AdhesionLaw) -> Result<Table1Comparison, SolveError> {
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed };
    let surface = generate(&layout, &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6))
        .map_err(|e| SolveError::InvalidInput { field: "surface", value: seed.to_string(), expected: e.to_string() })?;
    let summits = surface.len();
    let cfg = SolverConfig { mode: ShoeMode::TiltFree, shear_strength_pa: SHEAR_STRENGTH_PA, ..Default::default() };
    let mut solver = ExplicitSolver::new(surface, law, AsperityParams::table1(), cfg)?;
    let po = solver.pull_off(0.0, 1e-6)?;
    let mut loads: Vec<f64> = loads_n.iter().copied().filter(|&l| l >= po.load_n).collect();
    loads.sort_by(f64::total_cmp);
    let sweep = solver.sweep(&loads, Branch::Loading)?;
    let points = sweep
        .points
        .iter()
        .map(|e| Table1Point {
            load_n: e.load_n,
            contacts: e.contacts,
            friction_explicit_n: e.friction_capacity_n,
            friction_discrete_n3_n: discrete_friction_n(e.load_n, 3),
            real_area_m2: e.real_area_m2,
            max_pressure_pa: e.max_pressure_pa,
            tilt_rad: e.tilt_x_rad.hypot(e.tilt_y_rad),
        })
        .collect();
    Ok(Table1Comparison { seed, summits, pull_off_load_n: po.load_n, points })
}
