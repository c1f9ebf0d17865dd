//! The contact model the meter asks for the real area at a load: explicit, GW+DMT or discrete.

use stiction_contact::discrete;
use stiction_contact::explicit::{self, Equilibrium};
use stiction_contact::gw::GwSurface;
use stiction_contact::single::{AdhesionLaw, AsperityParams};

use crate::MeterError;

/// The state of the contact under an external normal load.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ContactState {
    /// External load L (the clamp force), N.
    pub load_n: f64,
    /// Real contact area A_r, m^2.
    pub real_area_m2: f64,
    /// Number of summits in contact (expected number for GW, which may be fractional).
    pub contacts: f64,
    /// Adhesive load (>= 0), N: the elastic load carried by the contacts minus L.
    pub adhesive_load_n: f64,
    /// Tilt of the shoe face along x (explicit solver, tilt free), rad.
    pub tilt_x_rad: f64,
    /// Tilt of the shoe face along y, rad.
    pub tilt_y_rad: f64,
    /// Largest peak Hertz pressure q0 over the contacts (eq. 11), Pa.
    pub max_pressure_pa: f64,
}

impl ContactState {
    /// The compressive load the contacts carry elastically, L + adhesive load, N.
    pub fn elastic_load_n(&self) -> f64 {
        self.load_n + self.adhesive_load_n
    }
}

/// Real area against load, by one of the paper's models or the explicit solver.
pub enum ContactModel {
    /// The explicit asperity-by-asperity solver on a generated or measured surface.
    Explicit(Box<explicit::ExplicitSolver>),
    /// Greenwood-Williamson with DMT adhesion (eq. 5, 8).
    Gw(GwSurface),
    /// The discrete model of eq. 12 with `contacts` equally loaded summits.
    Discrete {
        /// Number of contacts (1, 2, 3).
        contacts: usize,
        /// Single-asperity law.
        law: AdhesionLaw,
        /// Summit parameters.
        params: AsperityParams,
    },
}

impl ContactModel {
    /// A short name for reports.
    pub fn name(&self) -> String {
        match self {
            ContactModel::Explicit(_) => "explicit".into(),
            ContactModel::Gw(_) => "gw-dmt".into(),
            ContactModel::Discrete { contacts, .. } => format!("discrete-n{contacts}"),
        }
    }

    /// The contact state at external load `load_n` (N). Below pull-off there is no equilibrium,
    /// which is an error (the meter treats it as "no contact").
    ///
    /// `fresh_contact`: the shoe comes down anew (no load history) rather than following the
    /// previous equilibrium; it matters only for the explicit solver, whose equilibria depend on
    /// the load path.
    pub fn state_at_load(&mut self, load_n: f64, fresh_contact: bool) -> Result<ContactState, MeterError> {
        match self {
            ContactModel::Explicit(solver) => {
                if fresh_contact {
                    solver.reset();
                }
                let eq: Equilibrium = solver.solve(load_n).map_err(|e| MeterError::Contact(e.to_string()))?;
                Ok(ContactState {
                    load_n,
                    real_area_m2: eq.real_area_m2,
                    contacts: eq.contacts as f64,
                    adhesive_load_n: eq.adhesive_load_n,
                    tilt_x_rad: eq.tilt_x_rad,
                    tilt_y_rad: eq.tilt_y_rad,
                    max_pressure_pa: eq.max_pressure_pa,
                })
            }
            ContactModel::Gw(surface) => {
                let c = surface.solve_load(load_n, true).map_err(|e| MeterError::Contact(e.to_string()))?;
                Ok(ContactState {
                    load_n,
                    real_area_m2: c.real_area_m2,
                    contacts: c.contacts,
                    adhesive_load_n: c.adhesive_load_n,
                    tilt_x_rad: 0.0,
                    tilt_y_rad: 0.0,
                    // GW has no largest pressure (the Gaussian tail is unbounded); report the mean
                    // real elastic pressure p_e of eq. 7, the quantity of the paper's elastic limit.
                    max_pressure_pa: c.mean_elastic_pressure_pa,
                })
            }
            ContactModel::Discrete { contacts, law, params } => {
                let model = discrete::DiscreteModel::new(*contacts as u32, *law, *params, 1.0)
                    .map_err(|e| MeterError::Contact(e.to_string()))?;
                let p = model.at_load(load_n).map_err(|e| MeterError::Contact(e.to_string()))?;
                // Each contact carries the Hertz load of its radius, a^3 / (R D) (eq. 3b); the
                // adhesive load is what the contacts carry beyond L.
                let a = p.contact_radius_m;
                let elastic = *contacts as f64 * a.powi(3) / (params.radius_m * params.compliance_per_pa);
                Ok(ContactState {
                    load_n,
                    real_area_m2: p.real_area_m2,
                    contacts: *contacts as f64,
                    adhesive_load_n: elastic - load_n,
                    tilt_x_rad: 0.0,
                    tilt_y_rad: 0.0,
                    max_pressure_pa: p.max_pressure_pa,
                })
            }
        }
    }
}
