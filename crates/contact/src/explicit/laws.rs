//! Per-summit force laws as the explicit solver evaluates them (hot path).

use std::f64::consts::PI;

use crate::single::{
    AdhesionLaw, AsperityParams, Branch, MaugisTable, SummitModel, jkr_interference_minimum, summit_response,
};
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
    /// Capillary part of the pull of member i at z (N, >= 0; 0 for dry laws).
    fn capillary_n(&self, _i: usize, _z: f64) -> f64 {
        0.0
    }
    /// With [`LawEval::uniform_hertz_dmt`] (whose pull then includes the meniscus f R): the
    /// meniscus of the fast pass (f R, h_m, 1 / h_m); None when dry.
    fn fast_meniscus(&self) -> Option<(f64, f64, f64)> {
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

/// Spacing of the Maugis-Dugdale tables in `ln R` (so `ln lambda` steps by a third of it,
/// `lambda ~ R^(1/3)`); see [`MdPerSummit`] for the measured interpolation error.
pub(crate) const MD_NODE_STEP_LN_R: f64 = 0.05;

/// One Maugis-Dugdale table of [`MdPerSummit`]: the curve of one Maugis parameter in normalised
/// variables and its branch ends.
struct MdNode {
    table: MaugisTable,
    /// Jump-in interference `Delta_in = Delta(A = 0)` (normalised).
    delta_in: f64,
    /// End of the displacement-controlled branch `Delta_c = min Delta(A)` (normalised).
    delta_c: f64,
    /// Load there, `P_bar(Delta_c)`.
    p_c: f64,
}

/// Maugis-Dugdale with a radius per summit.
///
/// The normalised response `P_bar(Delta), A(Delta)` depends on the radius only through the Maugis
/// parameter `lambda = 2 sigma0 (R D^2 / (pi dgamma))^(1/3) ~ R^(1/3)`; the scales are closed forms
/// in R: load `pi dgamma R`, contact radius `(pi dgamma R^2 D)^(1/3)`, interference
/// `(pi^2 dgamma^2 R D^2)^(1/3)`. So the normalised curve is tabulated once per node of a grid
/// log-spaced in R between the smallest and largest radius of the surface ([`MaugisTable`], one
/// exact displacement-controlled solve per query) and summit i with `ln R_i = (1 - t) ln R_k +
/// t ln R_(k+1)` gets the linear interpolation between nodes k and k + 1 *at the same distance
/// `s = Delta - Delta_c` from the end of the branch*:
/// ```text
/// Delta_c,i = (1-t) Delta_c,k + t Delta_c,k+1   (Delta_in,i likewise)
/// P_bar_i(Delta) = (1-t) P_bar_k(Delta_c,k + s) + t P_bar_k+1(Delta_c,k+1 + s)
/// A_i(Delta) likewise,  dP_bar_i/dDelta = the same combination of the node stiffnesses
/// ```
/// This is a smooth law per summit whose stiffness is its exact derivative (so the solver's
/// equilibrium residuals are unaffected); its branch ends are defined for every node
/// (s >= 0) and `Delta_in,i >= Delta_c,i` holds as at the nodes. A summit whose radius is a node
/// (one radius for all: a single node) gets the exact Maugis-Dugdale law. The error against the
/// exact law at the summit's own lambda is second order in the node step
/// ([`MD_NODE_STEP_LN_R`]); measured in `tests/explicit_md_radii.rs`.
pub(crate) struct MdTables {
    ln_r0: f64,
    /// 1 / (node step in ln R); 0 with one node.
    inv_step: f64,
    nodes: Vec<MdNode>,
    /// Lowest jump-in or release interference over all summits (m, <= 0): a bound.
    z_min: f64,
}

impl MdTables {
    /// Builds the node tables for the radii range of `radii` (about 0.7 ms per node).
    pub fn new(params: AsperityParams, radii: &[f64]) -> Result<Self, crate::error::ContactError> {
        let r_min = radii.iter().copied().fold(f64::INFINITY, f64::min);
        let r_max = radii.iter().copied().fold(0.0, f64::max);
        let span = (r_max / r_min).ln();
        let steps = if span > 0.0 { (span / MD_NODE_STEP_LN_R).ceil().max(1.0) as usize } else { 0 };
        let step = if steps > 0 { span / steps as f64 } else { 0.0 };
        let ln_r0 = r_min.ln();
        let mut nodes = Vec::with_capacity(steps + 1);
        let mut z_min_bar: f64 = 0.0;
        for k in 0..=steps {
            let r = match k {
                0 => r_min,
                k if k == steps => r_max,
                k => (ln_r0 + k as f64 * step).exp(),
            };
            let table = MaugisTable::new(AsperityParams { radius_m: r, ..params }.maugis_parameter())?;
            let c = table.curve;
            let node = MdNode {
                delta_in: c.zero_radius.delta_bar,
                delta_c: c.interference_minimum.delta_bar,
                p_c: c.interference_minimum.p_bar,
                table,
            };
            z_min_bar = z_min_bar.min(node.delta_in).min(node.delta_c);
            nodes.push(node);
        }
        // The interference scale grows with R, the normalised branch ends are <= 0.
        let z_min = z_min_bar * AsperityParams { radius_m: r_max, ..params }.interference_scale_m();
        let inv_step = if steps > 0 { 1.0 / step } else { 0.0 };
        Ok(Self { ln_r0, inv_step, nodes, z_min })
    }
}

/// [`MdTables`] applied to the summits' radii (a view built per solve, no allocation).
pub(crate) struct MdPerSummit<'a> {
    pub params: AsperityParams,
    pub radii: &'a [f64],
    pub tables: &'a MdTables,
}

impl MdPerSummit<'_> {
    fn p(&self, i: usize) -> AsperityParams {
        AsperityParams { radius_m: self.radii[i], ..self.params }
    }

    /// Node k and weight t of node k + 1 for summit i (t = 0: node k alone).
    #[inline]
    fn weights(&self, i: usize) -> (usize, f64) {
        let tb = self.tables;
        if tb.nodes.len() == 1 {
            return (0, 0.0);
        }
        let u = (self.radii[i].ln() - tb.ln_r0) * tb.inv_step;
        let last = tb.nodes.len() - 2;
        let k = (u.floor().max(0.0) as usize).min(last);
        (k, (u - k as f64).clamp(0.0, 1.0))
    }

    #[inline]
    fn mix(&self, k: usize, t: f64, f: impl Fn(&MdNode) -> f64) -> f64 {
        let n = &self.tables.nodes;
        if t == 0.0 { f(&n[k]) } else { (1.0 - t) * f(&n[k]) + t * f(&n[k + 1]) }
    }

    /// Normalised state of node `n` at distance `s >= 0` from the end of its branch:
    /// (P_bar, A, dP_bar/dDelta).
    fn node_state(n: &MdNode, s: f64) -> (f64, f64, f64) {
        let st = if s > 0.0 { n.table.state_at_interference(n.delta_c + s) } else { None }
            .unwrap_or(n.table.curve.interference_minimum);
        (st.p_bar, st.a_hat, (st.dp_bar_da / st.ddelta_bar_da).max(0.0))
    }
}

impl LawEval for MdPerSummit<'_> {
    fn contact(&self, i: usize, z: f64) -> Resp {
        let p = self.p(i);
        let (ls, rs, ds) = (p.load_scale_n(), p.radius_scale_m(), p.interference_scale_m());
        let (k, t) = self.weights(i);
        let delta_c = self.mix(k, t, |n| n.delta_c);
        let s = z / ds - delta_c;
        if s.is_nan() || s < 0.0 {
            return Resp { load_n: self.p_rel(i), stiffness: 0.0, radius: 0.0, elastic_n: 0.0, q0: 0.0 };
        }
        let (p0, a0, k0) = Self::node_state(&self.tables.nodes[k], s);
        let (p_bar, a_hat, k_bar) = if t == 0.0 {
            (p0, a0, k0)
        } else {
            let (p1, a1, k1) = Self::node_state(&self.tables.nodes[k + 1], s);
            ((1.0 - t) * p0 + t * p1, (1.0 - t) * a0 + t * a1, (1.0 - t) * k0 + t * k1)
        };
        let a = a_hat * rs;
        Resp {
            load_n: p_bar * ls,
            stiffness: k_bar * ls / ds,
            radius: a,
            elastic_n: a * a * a / (p.radius_m * p.compliance_per_pa),
            q0: p.hertz_peak_pressure_pa(a),
        }
    }
    fn z_in(&self, i: usize) -> f64 {
        let (k, t) = self.weights(i);
        self.mix(k, t, |n| n.delta_in) * self.p(i).interference_scale_m()
    }
    fn z_rel(&self, i: usize) -> f64 {
        let (k, t) = self.weights(i);
        self.mix(k, t, |n| n.delta_c) * self.p(i).interference_scale_m()
    }
    fn p_rel(&self, i: usize) -> f64 {
        let (k, t) = self.weights(i);
        self.mix(k, t, |n| n.p_c) * self.p(i).load_scale_n()
    }
    fn z_min(&self) -> f64 {
        self.tables.z_min
    }
}

/// A water meniscus at a summit (circular-meniscus approximation, constant Kelvin radius, see
/// [`crate::explicit::Meniscus`]): the capillary pull of summit i at interference z,
/// `F = f R_i` in contact (z >= 0), `F = f R_i (1 + z / h_m)` for `-h_m <= z < 0` (the
/// sphere-flat force `2 pi R gamma (cos th1 + cos th2 - D / r_K)` at separation D = -z, with
/// `f = 2 pi gamma (cos th1 + cos th2)` and `h_m = r_K (cos th1 + cos th2)`), 0 below (ruptured), N.
#[inline(always)]
pub(crate) fn meniscus_force_n(force_per_radius_n_per_m: f64, height_m: f64, radius_m: f64, z: f64) -> f64 {
    if z >= 0.0 {
        force_per_radius_n_per_m * radius_m
    } else if z >= -height_m {
        force_per_radius_n_per_m * radius_m * (1.0 + z / height_m)
    } else {
        0.0
    }
}

/// A dry law `L` with a meniscus in equilibrium with the vapour at every summit within the
/// meniscus height of the shoe (capillary condensation, Kelvin condition).
///
/// A summit carries a meniscus whenever its interference is at least `-h_m` (gap below `h_m`),
/// on approach as on retraction: it joins the contact set there (`z_in = min(z_in_dry, -h_m)`)
/// and leaves it below `min(z_rel_dry, -h_m)` (rupture at `h_m`, or the dry law's release if that
/// reaches further). Load of a member: the dry law's while in solid contact, minus
/// [`meniscus_force_n`] (a function of z alone, no hysteresis). Solid contact: `z >= z_in_dry`, or
/// `z >= z_rel_dry` for a summit that was in solid contact at the last equilibrium (the bit set
/// `solid`, kept by the solver between load points; Hertz/DMT have `z_in = z_rel = 0` and need no
/// bits). The meniscus pull falls with the separation (negative stiffness `-f R / h_m`); the
/// stiffness given to the Newton iteration is the dry law's alone (clipped at >= 0 like every
/// law's, so the Hessian stays positive semi-definite), the force and the energy are exact.
pub(crate) struct Wet<'a, L: ?Sized> {
    pub dry: &'a L,
    pub radii: &'a Radii,
    pub solid: &'a [u64],
    pub force_per_radius_n_per_m: f64,
    pub height_m: f64,
}

impl<L: LawEval + ?Sized> Wet<'_, L> {
    #[inline(always)]
    fn r(&self, i: usize) -> f64 {
        match self.radii {
            Radii::Uniform(r) => *r,
            Radii::PerSummit(v) => v[i],
        }
    }
    #[inline(always)]
    fn was_solid(&self, i: usize) -> bool {
        self.solid.get(i >> 6).is_some_and(|w| (w >> (i & 63)) & 1 == 1)
    }
    /// Whether a member at interference z is in solid contact (on the dry law's contact branch).
    #[inline(always)]
    pub fn solid(&self, i: usize, z: f64) -> bool {
        z >= self.dry.z_in(i) || (z >= self.dry.z_rel(i) && self.was_solid(i))
    }
}

impl<L: LawEval + ?Sized> LawEval for Wet<'_, L> {
    #[inline]
    fn contact(&self, i: usize, z: f64) -> Resp {
        let cap = meniscus_force_n(self.force_per_radius_n_per_m, self.height_m, self.r(i), z);
        let mut r = if self.solid(i, z) {
            self.dry.contact(i, z)
        } else {
            Resp { load_n: 0.0, stiffness: 0.0, radius: 0.0, elastic_n: 0.0, q0: 0.0 }
        };
        r.load_n -= cap;
        r
    }
    fn z_in(&self, i: usize) -> f64 {
        self.dry.z_in(i).min(-self.height_m)
    }
    fn z_rel(&self, i: usize) -> f64 {
        if self.was_solid(i) { self.dry.z_rel(i).min(-self.height_m) } else { self.dry.z_in(i).min(-self.height_m) }
    }
    fn p_rel(&self, i: usize) -> f64 {
        // Continuous with the contact branch at z_rel: the meniscus is gone there (z_rel <= -h_m);
        // the dry law's end load if its release lies beyond the meniscus height.
        if self.was_solid(i) && self.dry.z_rel(i) < -self.height_m { self.dry.p_rel(i) } else { 0.0 }
    }
    fn z_min(&self) -> f64 {
        self.dry.z_min().min(-self.height_m)
    }
    fn uniform_hertz_dmt(&self) -> Option<(f64, f64, f64)> {
        // Hertz/DMT of one radius: in solid contact the meniscus adds the constant pull f R.
        self.dry.uniform_hertz_dmt().map(|(r, inv_d, c0)| (r, inv_d, c0 + self.force_per_radius_n_per_m * r))
    }
    fn fast_meniscus(&self) -> Option<(f64, f64, f64)> {
        self.dry
            .uniform_hertz_dmt()
            .map(|(r, _, _)| (self.force_per_radius_n_per_m * r, self.height_m, 1.0 / self.height_m))
    }
    fn capillary_n(&self, i: usize, z: f64) -> f64 {
        meniscus_force_n(self.force_per_radius_n_per_m, self.height_m, self.r(i), z)
    }
}
