//! Per-summit force laws as the explicit solver evaluates them (hot path).

use std::f64::consts::PI;

use crate::single::{AdhesionLaw, AsperityParams, Branch, SummitModel, jkr_interference_minimum, summit_response};
use stiction_surface::Radii;

/// Response of one summit in contact, with the split of its load (see [`LawEval`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Resp {
    /// Load P (N), compressive positive.
    pub load_n: f64,
    /// dP/dz (N/m), >= 0.
    pub stiffness: f64,
    /// Contact radius a (m).
    pub radius: f64,
    /// Hertz load a^3/(R D) for that contact radius (N): the elastic part of the load.
    pub elastic_n: f64,
    /// Peak Hertz pressure q0 = 3a/(2 pi D R) (eq. 11), Pa.
    pub q0: f64,
}

/// A law evaluated per summit index (the radius may vary per summit).
///
/// Members of the contact set are on the contact branch: the law's displacement-controlled stable
/// branch (`Branch::Unloading` of [`summit_response`]) down to the release interference `z_rel`;
/// below it the solver uses the constant force `p_rel` with zero stiffness (a convex extension of
/// the summit energy, never part of a reported equilibrium). Summits out of contact carry no
/// force and join when the interference reaches the jump-in value `z_in`.
pub(crate) trait LawEval {
    fn contact(&self, i: usize, z: f64) -> Resp;
    fn z_in(&self, i: usize) -> f64;
    fn z_rel(&self, i: usize) -> f64;
    fn p_rel(&self, i: usize) -> f64;
    /// Lowest z_in / z_rel over all summits (<= 0), for the search threshold.
    fn z_min(&self) -> f64;
    /// p_rel is the largest tension a summit carries on its contact branch (Hertz, DMT).
    fn release_force_is_extreme(&self) -> bool {
        false
    }
    /// Hertz/DMT with one radius: (R, 1/D, 2 pi dgamma R) for the fast pass.
    fn uniform_hertz_dmt(&self) -> Option<(f64, f64, f64)> {
        None
    }
}

/// Hertz (eq. 3) and DMT (eq. 4) in closed form: P = R^1/2 z^3/2 / D - 2 pi dgamma R.
pub(crate) struct HertzDmt<'a> {
    pub inv_d: f64,
    pub two_pi_dgamma: f64,
    pub radii: &'a Radii,
}

impl HertzDmt<'_> {
    #[inline(always)]
    fn r(&self, i: usize) -> f64 {
        match self.radii {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(v) => v[i],
        }
    }
}

impl LawEval for HertzDmt<'_> {
    #[inline(always)]
    fn contact(&self, i: usize, z: f64) -> Resp {
        let r = self.r(i);
        let z = z.max(0.0);
        let a = (r * z).sqrt();
        let elastic = a * z * self.inv_d;
        Resp {
            load_n: elastic - self.two_pi_dgamma * r,
            stiffness: 1.5 * a * self.inv_d,
            radius: a,
            elastic_n: elastic,
            q0: 1.5 * a * self.inv_d / (PI * r),
        }
    }
    #[inline(always)]
    fn z_in(&self, _i: usize) -> f64 {
        0.0
    }
    #[inline(always)]
    fn z_rel(&self, _i: usize) -> f64 {
        0.0
    }
    #[inline(always)]
    fn p_rel(&self, i: usize) -> f64 {
        -self.two_pi_dgamma * self.r(i)
    }
    fn z_min(&self) -> f64 {
        0.0
    }
    fn release_force_is_extreme(&self) -> bool {
        true
    }
    fn uniform_hertz_dmt(&self) -> Option<(f64, f64, f64)> {
        match self.radii {
            Radii::Uniform(r) => Some((*r, self.inv_d, self.two_pi_dgamma * r)),
            Radii::PerSummit(_) => None,
        }
    }
}

fn from_summit_response(p: &AsperityParams, s: crate::single::SummitResponse) -> Resp {
    let a = s.contact_radius_m;
    let elastic = a * a * a / (p.radius_m * p.compliance_per_pa);
    Resp {
        load_n: s.load_n,
        stiffness: s.stiffness_n_per_m.max(0.0),
        radius: a,
        elastic_n: elastic,
        q0: s.max_pressure_pa,
    }
}

/// JKR or Maugis-Dugdale with one radius for all summits, through [`SummitModel`].
pub(crate) struct Uniform {
    pub model: SummitModel,
    pub z_in: f64,
    pub z_rel: f64,
    pub p_rel: f64,
}

impl Uniform {
    pub fn new(model: SummitModel) -> Self {
        let z_in = model.contact_start_interference_m(Branch::Loading);
        let z_rel = model.contact_start_interference_m(Branch::Unloading);
        // Load at the end of the contact branch (just above z_rel).
        let z_probe = z_rel + 1e-9 * z_rel.abs().max(model.params().interference_scale_m());
        let p_rel = model.response(z_probe, Branch::Unloading).load_n;
        Self { model, z_in, z_rel, p_rel }
    }
}

impl LawEval for Uniform {
    #[inline]
    fn contact(&self, _i: usize, z: f64) -> Resp {
        let s = self.model.response(z.max(self.z_rel), Branch::Unloading);
        if s.in_contact {
            from_summit_response(self.model.params(), s)
        } else {
            Resp { load_n: self.p_rel, stiffness: 0.0, radius: 0.0, elastic_n: 0.0, q0: 0.0 }
        }
    }
    fn z_in(&self, _i: usize) -> f64 {
        self.z_in
    }
    fn z_rel(&self, _i: usize) -> f64 {
        self.z_rel
    }
    fn p_rel(&self, _i: usize) -> f64 {
        self.p_rel
    }
    fn z_min(&self) -> f64 {
        self.z_in.min(self.z_rel).min(0.0)
    }
}

/// JKR with a radius per summit: [`summit_response`] per call (about 0.1 us), closed-form branch
/// ends: z_rel = -0.9086 (pi^2 dgamma^2 R D^2)^(1/3), P(z_rel) = -5/6 pi dgamma R.
pub(crate) struct JkrPerSummit<'a> {
    pub params: AsperityParams,
    pub radii: &'a [f64],
    pub delta_c_bar: f64,
    pub p_c_bar: f64,
    pub z_min: f64,
}

impl<'a> JkrPerSummit<'a> {
    pub fn new(params: AsperityParams, radii: &'a [f64]) -> Self {
        let c = jkr_interference_minimum();
        let rmax = radii.iter().copied().fold(0.0, f64::max);
        let pmax = AsperityParams { radius_m: rmax.max(1e-300), ..params };
        Self {
            params,
            radii,
            delta_c_bar: c.delta_bar,
            p_c_bar: c.p_bar,
            z_min: c.delta_bar * pmax.interference_scale_m(),
        }
    }
    fn p(&self, i: usize) -> AsperityParams {
        AsperityParams { radius_m: self.radii[i], ..self.params }
    }
}

impl LawEval for JkrPerSummit<'_> {
    fn contact(&self, i: usize, z: f64) -> Resp {
        let p = self.p(i);
        let s = summit_response(AdhesionLaw::Jkr, &p, z.max(self.z_rel(i)), Branch::Unloading);
        if s.in_contact {
            from_summit_response(&p, s)
        } else {
            Resp { load_n: self.p_rel(i), stiffness: 0.0, radius: 0.0, elastic_n: 0.0, q0: 0.0 }
        }
    }
    fn z_in(&self, _i: usize) -> f64 {
        0.0
    }
    fn z_rel(&self, i: usize) -> f64 {
        self.delta_c_bar * self.p(i).interference_scale_m()
    }
    fn p_rel(&self, i: usize) -> f64 {
        self.p_c_bar * self.p(i).load_scale_n()
    }
    fn z_min(&self) -> f64 {
        self.z_min
    }
}
