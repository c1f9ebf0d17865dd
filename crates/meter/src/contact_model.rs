//! The contact model the meter asks for the real area at a load: explicit, GW+DMT, discrete or
//! the boundary-element solver on the height-map patch under the shoe.

use stiction_contact::capillary::Capillarity;
use stiction_contact::discrete;
use stiction_contact::explicit::{self, Equilibrium};
use stiction_contact::gw::GwSurface;
use stiction_contact::single::{AdhesionLaw, AsperityParams};

use crate::error::MeterError;

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
    /// Capillary part of the adhesive load (the pull of the water menisci), N; 0 (and not written)
    /// when dry.
    #[serde(skip_serializing_if = "is_zero")]
    pub capillary_load_n: f64,
    /// Tilt of the shoe face along x (explicit solver, tilt free), rad.
    pub tilt_x_rad: f64,
    /// Tilt of the shoe face along y, rad.
    pub tilt_y_rad: f64,
    /// Largest peak Hertz pressure q0 over the contacts (eq. 11), Pa.
    pub max_pressure_pa: f64,
    /// The part of the real area flowing at the hardness (the `bem` model with
    /// `contact.bem.plastic`), m^2; None (and not written) for an elastic model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub plastic_area_m2: Option<f64>,
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
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
    /// Greenwood-Williamson with DMT adhesion (eq. 5, 8), with a meniscus at every summit in
    /// contact when humid.
    Gw(GwSurface, Option<Capillarity>),
    /// The FFT boundary-element solver on the composite height patch under the shoe.
    Bem(Box<BemContact>),
    /// The discrete model of eq. 12 with `contacts` equally loaded summits.
    Discrete {
        /// Number of contacts (1, 2, 3).
        contacts: usize,
        /// Single-asperity law.
        law: AdhesionLaw,
        /// Summit parameters.
        params: AsperityParams,
        /// The meniscus at each contact, when humid.
        capillarity: Option<Capillarity>,
    },
}

impl ContactModel {
    /// A short name for reports.
    pub fn name(&self) -> String {
        match self {
            ContactModel::Explicit(_) => "explicit".into(),
            ContactModel::Gw(..) => "gw-dmt".into(),
            ContactModel::Bem(_) => "bem".into(),
            ContactModel::Discrete { contacts, .. } => format!("discrete-n{contacts}"),
        }
    }

    /// The number of summits the model holds (the expected number `eta A_a` for GW, the contacts
    /// of the discrete model, the grid points of the boundary-element patch): no more can touch.
    pub fn summit_count(&self) -> f64 {
        match self {
            ContactModel::Explicit(solver) => solver.len() as f64,
            ContactModel::Gw(surface, _) => surface.summit_density_per_m2 * surface.apparent_area_m2,
            ContactModel::Bem(bem) => (bem.grid.nx * bem.grid.ny) as f64,
            ContactModel::Discrete { contacts, .. } => *contacts as f64,
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
                    capillary_load_n: eq.capillary_load_n,
                    tilt_x_rad: eq.tilt_x_rad,
                    tilt_y_rad: eq.tilt_y_rad,
                    max_pressure_pa: eq.max_pressure_pa,
                    plastic_area_m2: None,
                })
            }
            ContactModel::Gw(surface, capillarity) => {
                let c = surface
                    .solve_load_wet(load_n, true, capillarity.as_ref())
                    .map_err(|e| MeterError::Contact(e.to_string()))?;
                Ok(ContactState {
                    load_n,
                    real_area_m2: c.real_area_m2,
                    contacts: c.contacts,
                    adhesive_load_n: c.adhesive_load_n,
                    capillary_load_n: c.capillary_load_n,
                    tilt_x_rad: 0.0,
                    tilt_y_rad: 0.0,
                    // GW has no largest pressure (the Gaussian tail is unbounded); report the mean
                    // real elastic pressure p_e of eq. 7, the quantity of the paper's elastic limit.
                    max_pressure_pa: c.mean_elastic_pressure_pa,
                    plastic_area_m2: None,
                })
            }
            ContactModel::Bem(bem) => bem.state_at_load(load_n),
            ContactModel::Discrete { contacts, law, params, capillarity } => {
                let model = discrete::DiscreteModel::new(*contacts as u32, *law, *params, 1.0)
                    .map_err(|e| MeterError::Contact(e.to_string()))?;
                let p =
                    model.at_load_wet(load_n, capillarity.as_ref()).map_err(|e| MeterError::Contact(e.to_string()))?;
                // Each contact carries the Hertz load of its radius, a^3 / (R D) (eq. 3b); the
                // adhesive load is what the contacts carry beyond L.
                let a = p.contact_radius_m;
                let elastic = *contacts as f64 * a.powi(3) / (params.radius_m * params.compliance_per_pa);
                Ok(ContactState {
                    load_n,
                    real_area_m2: p.real_area_m2,
                    contacts: *contacts as f64,
                    adhesive_load_n: elastic - load_n,
                    capillary_load_n: model.capillary_load_n(capillarity.as_ref()),
                    tilt_x_rad: 0.0,
                    tilt_y_rad: 0.0,
                    max_pressure_pa: p.max_pressure_pa,
                    plastic_area_m2: None,
                })
            }
        }
    }
}

/// The boundary-element model of the shoe face: the composite height patch under the shoe's
/// apparent area, by default a finite patch on a wall that goes on (the non-periodic Green's
/// function, `contact.bem.boundary`), or one periodic cell; a rigid shoe that approaches flat (the
/// default) or tilts until its moments balance (`contact.bem.tilt`, non-periodic only); the
/// elastic interaction of every point with every other through the half-space.
/// Without adhesion (law "hertz" or no work of adhesion) the state at a load is the Polonsky-Keer
/// solution; with adhesion the Dugdale cohesive law (`w` of the material, range
/// `contact.bem.range`) on the loading branch (`stiction_bem::shoe` under load control for the
/// finite patch, `stiction_bem::loading` for the periodic cell).
#[derive(Debug)]
pub struct BemContact {
    solver: stiction_bem::BemSolver,
    grid: stiction_bem::Grid,
    law: Option<stiction_bem::Dugdale>,
    options: stiction_bem::SolverOptions,
    path: stiction_bem::LoadingPath,
    last: Option<stiction_bem::ContactSolution>,
    tilting: bool,
    last_tilt: Option<stiction_bem::TiltedShoe>,
    hardness_pa: Option<f64>,
    /// Block factors (x, y) that coarsened the map's pixels into the grid.
    pub coarsening: (usize, usize),
}

/// A solved state, the shoe's tilts (rad) and, with the hardness cap, the plastic area (m^2).
pub type Pose = (stiction_bem::ContactSolution, (f64, f64), Option<f64>);

/// The shoe of a [`BemContact`]: its Green's function and whether it tilts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BemShoe {
    /// Periodic cell or finite patch on the wall.
    pub boundary: stiction_bem::Boundary,
    /// Whether the shoe tilts (force and moment balance) or approaches flat.
    pub tilting: bool,
    /// The hardness the contact pressure is capped at (perfectly plastic pixels), Pa; None: elastic.
    pub hardness_pa: Option<f64>,
}

impl BemContact {
    /// The model on the row-major `heights_m` of an `nx x ny` grid of `dx_m x dy_m` pixels (already
    /// coarsened and size-checked), composite modulus `e_star_pa`, optional Dugdale law, the shoe.
    pub fn new(
        grid: stiction_bem::Grid,
        heights_m: &[f64],
        e_star_pa: f64,
        law: Option<stiction_bem::Dugdale>,
        tolerance: f64,
        coarsening: (usize, usize),
        shoe: BemShoe,
    ) -> Result<Self, MeterError> {
        if shoe.tilting && shoe.boundary == stiction_bem::Boundary::Periodic {
            return Err(MeterError::Scenario(
                "contact.bem.tilt: a tilting shoe needs the finite patch (contact.bem.boundary = \"non_periodic\"); a \
                 periodic cell has no edge to tilt about"
                    .into(),
            ));
        }
        if let Some(h) = shoe.hardness_pa.filter(|h| !(h.is_finite() && *h > 0.0)) {
            return Err(MeterError::Scenario(format!("material.hardness {h:e} Pa: expected a finite hardness > 0")));
        }
        let solver = stiction_bem::BemSolver::with_boundary(
            grid.nx,
            grid.ny,
            grid.dx_m,
            grid.dy_m,
            heights_m,
            e_star_pa,
            shoe.boundary,
        )
        .map_err(|e| MeterError::Contact(format!("bem: {e}")))?;
        // At most 50 cohesive-zone updates per solve (1-7 in the validation cases): with the path's
        // work budget (stiction_bem::error::PATH_WORK_FACTOR) every load is bounded.
        let options = stiction_bem::SolverOptions { tolerance, max_zone_updates: 50, ..Default::default() };
        Ok(BemContact {
            solver,
            grid,
            law,
            options,
            path: Default::default(),
            last: None,
            tilting: shoe.tilting,
            last_tilt: None,
            hardness_pa: shoe.hardness_pa,
            coarsening,
        })
    }

    /// The grid.
    pub fn grid(&self) -> stiction_bem::Grid {
        self.grid
    }

    /// The Dugdale law, if adhesive.
    pub fn law(&self) -> Option<stiction_bem::Dugdale> {
        self.law
    }

    /// The full solution at external load `load_n` (N, > 0) on the patch (in the shoe's pose when
    /// it tilts: heights seen from the tilted face).
    pub fn solve(&mut self, load_n: f64) -> Result<stiction_bem::ContactSolution, MeterError> {
        self.solve_pose(load_n).map(|(s, _)| s)
    }

    /// The solution and the tilts `(dw/dx, dw/dy)` (rad; zero for a flat shoe).
    pub fn solve_pose(&mut self, load_n: f64) -> Result<(stiction_bem::ContactSolution, (f64, f64)), MeterError> {
        self.solve_full(load_n).map(|(s, t, _)| (s, t))
    }

    /// The hardness the pressure is capped at, Pa (None: elastic).
    pub fn hardness_pa(&self) -> Option<f64> {
        self.hardness_pa
    }

    /// The shoe: boundary, whether it tilts, the hardness cap.
    pub fn shoe(&self) -> BemShoe {
        BemShoe { boundary: self.solver.boundary(), tilting: self.tilting, hardness_pa: self.hardness_pa }
    }

    /// The solution, the tilts `(dw/dx, dw/dy)` (rad; zero for a flat shoe) and, with the hardness
    /// cap, the plastic area `A_p` (m^2; None for an elastic model).
    pub fn solve_full(&mut self, load_n: f64) -> Result<Pose, MeterError> {
        if !(load_n.is_finite() && load_n > 0.0) {
            return Err(MeterError::Contact(format!(
                "bem: load {load_n:e} N: the loading branch needs a compressive load > 0 (below, the shoe is not in \
                 contact on approach)"
            )));
        }
        let p = load_n / self.grid.area_m2();
        let err = |e: stiction_bem::BemError| MeterError::Contact(format!("bem: {e}"));
        if self.tilting {
            // Continue the path from the last pose while the load rises; start afresh below it.
            // With the hardness cap every pose is the capped solve.
            let opts = stiction_bem::SolverOptions { hardness_pa: self.hardness_pa, ..self.options };
            let warm = self.last_tilt.as_ref().filter(|t| t.solution.mean_pressure_pa <= p);
            let t = self.solver.tilting_at_load(p, self.law.as_ref(), &opts, warm).map_err(err)?;
            let out = (t.solution.clone(), (t.tilt_x_rad, t.tilt_y_rad), t.plastic.map(|pl| pl.1));
            self.last_tilt = Some(t);
            return Ok(out);
        }
        if let Some(h) = self.hardness_pa {
            // The hardness cap (a flat shoe; a tilting one caps each pose, above); at a mean pressure at or above the
            // hardness the whole face flows and no state exists (the solver's error). With
            // adhesion the net traction is capped and the zone is grown on the loading branch,
            // continued from the lower load's state; without, each load is solved cold (a warm
            // start from the previous plastic state could stall the iteration where the cold
            // solve converges: stiction_engine::bem, the sweep).
            let opts = stiction_bem::SolverOptions { hardness_pa: Some(h), ..self.options };
            let warm = self.last.as_ref().filter(|s| self.law.is_some() && s.mean_pressure_pa <= p);
            let st = self
                .solver
                .plastic_at_load(p, self.law.as_ref(), &opts, warm)
                .map_err(|e| MeterError::Contact(format!("bem (hardness cap, material.hardness = {h:e} Pa): {e}")))?;
            self.last = Some(st.solution.clone());
            return Ok((st.solution, (0.0, 0.0), Some(st.plastic_area_m2)));
        }
        let s = match (&self.law, self.solver.boundary()) {
            (None, _) => self.solver.solve_load(p, &self.options, self.last.as_ref()),
            (Some(law), stiction_bem::Boundary::Periodic) => {
                self.solver.adhesive_loading_at_pressure(p, law, &self.options, &mut self.path)
            }
            (Some(law), stiction_bem::Boundary::NonPeriodic) => {
                let warm = self.last.as_ref().filter(|s| s.mean_pressure_pa <= p);
                self.solver.adhesive_at_load(p, law, &self.options, warm)
            }
        }
        .map_err(err)?;
        if self.law.is_none() || self.solver.boundary() == stiction_bem::Boundary::NonPeriodic {
            self.last = Some(s.clone());
        }
        Ok((s, (0.0, 0.0), None))
    }

    /// The contact state at external load `load_n` (N): real area (contact points times the pixel
    /// area), contact patches as "contacts", adhesive load = the Dugdale tension over the cohesive
    /// zone (the contact pressure carries `L` plus it), largest contact pressure.
    pub fn state_at_load(&mut self, load_n: f64) -> Result<ContactState, MeterError> {
        let pose = self.solve_full(load_n)?;
        Ok(self.state_of(load_n, &pose))
    }

    /// The contact state of a solved `pose` at external load `load_n` (N), as
    /// [`Self::state_at_load`].
    pub fn state_of(&self, load_n: f64, pose: &Pose) -> ContactState {
        let (s, (tilt_x_rad, tilt_y_rad), plastic_area_m2) = pose;
        let stress = self.law.map_or(0.0, |l| l.stress_pa);
        // Net traction p = p_c - sigma0 in the zone: the contact pressure is p + sigma0 there.
        let max_pressure_pa =
            s.pressure_pa.iter().zip(&s.contact).filter(|(_, c)| **c).map(|(p, _)| p + stress).fold(0.0, f64::max);
        let adhesive_load_n = stress * s.cohesive_fraction * self.grid.area_m2();
        ContactState {
            load_n,
            real_area_m2: s.contact_area_m2,
            contacts: s.patches as f64,
            adhesive_load_n,
            capillary_load_n: 0.0,
            tilt_x_rad: *tilt_x_rad,
            tilt_y_rad: *tilt_y_rad,
            max_pressure_pa,
            plastic_area_m2: *plastic_area_m2,
        }
    }
}
