//! What one evaluation pass returns ([`Eval`]): gradient, Hessian and totals of the potential
//! energy at a pose, and what the fast pass adds for a Newton step without a pass ([`Linear`]).

#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Eval {
    pub(super) g: [f64; 3],
    pub(super) h: [[f64; 3]; 3],
    pub(super) force: f64,
    pub(super) force_abs: f64,
    pub(super) releases: usize,
    pub(super) contacts: usize,
    /// Totals over members and touchers on the contact branch (for the result without a second pass).
    pub(super) area: f64,
    pub(super) elastic: f64,
    pub(super) q0_max: f64,
    pub(super) over_limit: usize,
    pub(super) moment_x: f64,
    pub(super) moment_y: f64,
    /// Words of the contact bit set that can hold a member past release (first, last), when the
    /// pass knows them (the fast pass); `None`: any word.
    pub(super) release_words: Option<(usize, usize)>,
    /// What a Newton step without a pass needs (the fast pass only; see
    /// [`super::shortcuts::linear_step`]).
    pub(super) lin: Option<Linear>,
    /// Menisci only: their total pull and the number of summits in solid contact (contact
    /// radius > 0), at an equilibrium (no member past release).
    pub(super) capillary: f64,
    pub(super) solid: usize,
    /// Members were released from this evaluation without a new pass: `capillary` and `solid`
    /// are stale.
    pub(super) released: bool,
}

/// Quantities of a fast pass beyond the gradient and Hessian, for a final Newton step applied by
/// linearisation instead of a new pass ([`super::shortcuts::linear_step`]).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Linear {
    /// Smallest z of the summits in contact with z >= 0 \[m\]: a summit's z may fall by less
    /// without any of them releasing.
    pub(super) gap_in: f64,
    /// Lower bound of |z| over all other summits (scanned ones exactly, the others by the height
    /// threshold of the prefix) \[m\]: a summit's z may rise by less without any of them touching.
    pub(super) gap_out: f64,
    /// Lower bound of |z - z_hard| over the summits in contact (infinite without a hardness) \[m\].
    pub(super) hard_gap: f64,
    /// sum k u, sum k v (the flat shoe's Hessian holds only sum k).
    pub(super) k_uv: [f64; 2],
    /// Menisci: the magnitude of a tail's (negative) stiffness f R / h_m (0 when dry) \[N/m\].
    pub(super) tail_k: f64,
    /// Menisci: the bridged summits' number and sums of u, v, u^2, u v, v^2 (zero when dry).
    pub(super) tail: [f64; 6],
}
