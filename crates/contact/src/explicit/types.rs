//! Public configuration, results and errors of the explicit solver.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Which rigid-body degrees of freedom the shoe has.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", tag = "mode")]
pub enum ShoeMode {
    /// Approach and both tilts free: force and both moments balance about the load point.
    #[default]
    TiltFree,
    /// Approach only, no tilt (the Greenwood-Williamson situation); the moments of the contact
    /// forces about the load point are carried by the guide and reported as moment residuals.
    Flat,
    /// Only the `count` highest summits carry the shoe (the discrete model, eq. 12): all of them
    /// stay in contact, no other summit is considered, and the load acts at their centroid.
    /// Degrees of freedom: approach (count = 1), approach and the tilt along the pair (count = 2),
    /// approach and both tilts (count >= 3). For count <= 3 statics gives every summit L / count,
    /// so the explicit solver reproduces eq. 12 exactly.
    FixedContacts {
        /// Number of supporting summits (>= 1).
        count: usize,
    },
}

/// How much per-summit detail an [`Equilibrium`] carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Detail {
    /// Totals only (`contact_indices` and `summits` empty): the cheapest.
    Summary,
    /// Totals and `contact_indices`.
    Indices,
    /// Totals, `contact_indices` and one [`SummitContact`] per contact (default).
    #[default]
    Full,
}

/// Settings of the explicit solver. Defaults in brackets.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SolverConfig {
    /// Degrees of freedom of the shoe \[tilt free\].
    pub mode: ShoeMode,
    /// Point where the normal load acts (x, y) \[m\] \[centre of the apparent area\]. Ignored by
    /// `FixedContacts`, which loads the centroid of its summits.
    pub load_point_m: Option<(f64, f64)>,
    /// Interface shear strength s for the friction capacity s A_r (eq. 1) \[Pa\] \[1.4 GPa, the
    /// paper's fitted value\].
    pub shear_strength_pa: f64,
    /// Hardness H for the elastic-limit flags: a summit is flagged when its peak Hertz pressure
    /// q0 (eq. 11) exceeds H (the paper's check in section 5) \[None: no flags\].
    pub hardness_pa: Option<f64>,
    /// Convergence: every force residual (and moment residual divided by the half-diagonal of the
    /// apparent area) below this fraction of the load scale max(|L|, sum |P_i|, one summit's
    /// adhesion 2 pi dgamma R) \[1e-9\].
    pub relative_tolerance: f64,
    /// Newton iterations per phase of a solve \[500\]: a solve not converged after them on the
    /// clipped Hessian goes on for as many more on the Hessian of the exact forces before
    /// [`SolveError::NotConverged`] (docs/explicit-solver.md, step 4).
    pub max_iterations: usize,
    /// Per-summit detail in results \[full\].
    pub detail: Detail,
}

impl Default for SolverConfig {
    fn default() -> Self {
        Self {
            mode: ShoeMode::TiltFree,
            load_point_m: None,
            shear_strength_pa: 1.4e9,
            hardness_pa: None,
            relative_tolerance: 1e-9,
            max_iterations: 500,
            detail: Detail::Full,
        }
    }
}

/// One summit in contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SummitContact {
    /// Index of the summit in the surface as given to the solver.
    pub index: u32,
    /// Position x \[m\].
    pub x_m: f64,
    /// Position y \[m\].
    pub y_m: f64,
    /// Summit height above the reference plane \[m\].
    pub height_m: f64,
    /// Summit radius \[m\].
    pub radius_m: f64,
    /// Interference z = height - shoe plane height at the summit \[m\] (negative on the JKR/MD
    /// unloading branch).
    pub interference_m: f64,
    /// Load carried, compressive positive \[N\].
    pub load_n: f64,
    /// Contact radius a \[m\].
    pub contact_radius_m: f64,
    /// Peak Hertz pressure q0 = 3 a / (2 pi D R) (eq. 11) \[Pa\].
    pub max_pressure_pa: f64,
    /// q0 exceeds the configured hardness.
    pub over_elastic_limit: bool,
}

/// An equilibrium of the shoe under a normal load.
///
/// The shoe face is the plane `w(x, y) = separation_m + tilt_x_rad (x - x0) + tilt_y_rad (y - y0)`
/// above the reference plane, (x0, y0) the load point; summit i is in contact with interference
/// `z_i = h_i - w(x_i, y_i)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Equilibrium {
    /// Applied normal load L, compressive positive \[N\].
    pub load_n: f64,
    /// Separation d of the shoe face from the reference plane at the load point \[m\] (paper Fig. 1).
    pub separation_m: f64,
    /// Slope of the shoe face along x, dw/dx (small-angle rotation about y) \[rad\].
    pub tilt_x_rad: f64,
    /// Slope of the shoe face along y, dw/dy (small-angle rotation about x) \[rad\].
    pub tilt_y_rad: f64,
    /// Load point x0 \[m\].
    pub load_point_x_m: f64,
    /// Load point y0 \[m\].
    pub load_point_y_m: f64,
    /// Number of summits in contact N.
    pub contacts: usize,
    /// Surface indices of the summits in contact, ascending (empty with [`Detail::Summary`]).
    pub contact_indices: Vec<u32>,
    /// Real contact area A_r = sum pi a_i^2 \[m^2\].
    pub real_area_m2: f64,
    /// Elastic load sum a_i^3 / (R_i D) (the Hertz load of each contact radius; DMT: eq. 4b
    /// right-hand side) \[N\].
    pub elastic_load_n: f64,
    /// Adhesive load: elastic load minus the carried load, >= 0 for adhesive laws (DMT:
    /// N 2 pi dgamma R) \[N\].
    pub adhesive_load_n: f64,
    /// Capillary part of the adhesive load: the pull of the menisci of the summits within the
    /// meniscus height of the shoe ([`Meniscus`]) \[N\]; 0 (and not written) without a meniscus.
    #[serde(default, skip_serializing_if = "is_zero_f64")]
    pub capillary_load_n: f64,
    /// Summits carrying a meniscus (in contact, or separated from the shoe by less than its
    /// height); 0 (and not written) without a meniscus. With a meniscus `contacts` counts the
    /// summits in solid contact and `contact_indices` / `summits` list every wetted summit.
    #[serde(default, skip_serializing_if = "is_zero_usize")]
    pub wetted_summits: usize,
    /// Friction capacity s A_r (eq. 1) \[N\].
    pub friction_capacity_n: f64,
    /// Largest peak Hertz pressure over the contacts (eq. 11) \[Pa\].
    pub max_pressure_pa: f64,
    /// Number of contacts whose q0 exceeds the hardness (0 without a hardness).
    pub summits_over_elastic_limit: usize,
    /// L - sum P_i \[N\].
    pub force_residual_n: f64,
    /// sum P_i (x_i - x0): first moment of the contact forces along x about the load point,
    /// zero at a tilt-free equilibrium (carried by the guide in flat mode) \[N m\].
    pub moment_residual_x_n_m: f64,
    /// sum P_i (y_i - y0) \[N m\].
    pub moment_residual_y_n_m: f64,
    /// Newton iterations spent on this solve.
    pub iterations: usize,
    /// Per-contact detail ([`Detail::Full`] only), ascending index.
    pub summits: Vec<SummitContact>,
}

/// Something that happened between two points of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case", tag = "event")]
pub enum SweepEvent {
    /// Contacts were gained (on loading: new summits jumped into contact).
    JumpIn {
        /// Index of the sweep point after the event.
        point: usize,
        /// Load at that point \[N\].
        load_n: f64,
        /// Contacts before.
        contacts_before: usize,
        /// Contacts after.
        contacts_after: usize,
    },
    /// Contacts were lost (on unloading: summits released).
    Release {
        /// Index of the sweep point after the event.
        point: usize,
        /// Load at that point \[N\].
        load_n: f64,
        /// Contacts before.
        contacts_before: usize,
        /// Contacts after.
        contacts_after: usize,
    },
    /// The shoe came off: no equilibrium at `load_n`; the sweep stops there.
    PullOff {
        /// The load without equilibrium \[N\].
        load_n: f64,
        /// The last load with an equilibrium \[N\] (None: the first load of the sweep had none).
        last_stable_load_n: Option<f64>,
        /// Why there is no last stable load, when there is none.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        note: Option<String>,
    },
}

/// Work counters of an [`crate::explicit::ExplicitSolver`] (diagnostics for performance
/// measurements, see [`crate::explicit::ExplicitSolver::work`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WorkCounters {
    /// Evaluation passes over the summits.
    pub passes: u64,
    /// Summits scanned by those passes, summed over the passes.
    pub summits_scanned: u64,
}

/// Result of a load sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Sweep {
    /// One equilibrium per load that had one, in sweep order.
    pub points: Vec<Equilibrium>,
    /// Contact changes and pull-off.
    pub events: Vec<SweepEvent>,
}

/// Errors of the explicit solver.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SolveError {
    /// Invalid input (names the field, value and expectation).
    #[error("invalid `{field}` = {value}: expected {expected}")]
    InvalidInput {
        /// Field.
        field: &'static str,
        /// Value as given.
        value: String,
        /// What was expected.
        expected: String,
    },
    /// The law and surface combination is not supported.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// No equilibrium: the shoe separates from the surface (load below pull-off) or tips over.
    #[error("no equilibrium at load {load_n:e} N: {reason}")]
    NoEquilibrium {
        /// The load.
        load_n: f64,
        /// Why.
        reason: String,
    },
    /// A fixed contact was lost (`FixedContacts` mode).
    #[error(
        "fixed-contacts mode at load {load_n:e} N: summit {index} leaves contact (interference {interference_m:e} m)"
    )]
    ContactLost {
        /// The load.
        load_n: f64,
        /// Surface index of the summit.
        index: u32,
        /// Its interference.
        interference_m: f64,
    },
    /// The iteration did not converge; never hidden.
    #[error(
        "no convergence at load {load_n:e} N after {iterations} iterations (force residual {residual_n:e} N, {contacts} contacts)"
    )]
    NotConverged {
        /// The load.
        load_n: f64,
        /// Iterations spent.
        iterations: usize,
        /// Largest remaining residual (force units).
        residual_n: f64,
        /// Contacts at the last iterate.
        contacts: usize,
    },
}

/// A water meniscus at every summit within its height of the shoe (capillary condensation at a
/// relative humidity; the circular-meniscus approximation with a constant Kelvin radius r_K,
/// docs/explicit-solver.md, "Capillarity").
///
/// The meniscus is in equilibrium with the vapour: it condenses in every gap D = -z below
/// `height_m` = h_m = r_K (cos th1 + cos th2), on approach as on retraction, and ruptures beyond
/// it. Its pull is the sphere-flat force `2 pi R gamma (cos th1 + cos th2 - max(D, 0) / r_K)`
/// = `force_per_radius_n_per_m * R * (1 - max(D, 0) / h_m)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Meniscus {
    /// `2 pi gamma (cos th1 + cos th2)`: the pull of a wetted summit in contact per unit radius
    /// \[N/m\] (4 pi gamma cos theta for equal faces).
    pub force_per_radius_n_per_m: f64,
    /// Largest separation the meniscus bridges, h_m = r_K (cos th1 + cos th2) \[m\].
    pub height_m: f64,
}

fn is_zero_f64(v: &f64) -> bool {
    *v == 0.0
}

fn is_zero_usize(v: &usize) -> bool {
    *v == 0
}

impl Meniscus {
    /// The meniscus of a capillary law: `force_per_radius = 2 pi gamma (cos th1 + cos th2)`,
    /// `height = h_m` ([`crate::capillary::Capillarity::meniscus_height_m`]).
    pub fn from_capillarity(c: &crate::capillary::Capillarity) -> Self {
        Self {
            force_per_radius_n_per_m: 2.0 * std::f64::consts::PI * c.surface_tension_n_per_m * c.cos_angle_sum,
            height_m: c.meniscus_height_m(),
        }
    }
}
