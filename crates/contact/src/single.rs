//! Single-asperity contact laws: Hertz (eq. 3), DMT as the paper uses it (eq. 4), JKR and
//! Maugis-Dugdale, the Tabor and Maugis parameters, and an interference-controlled response for
//! the explicit solver ([`summit_response`], [`SummitModel`]).
//!
//! # Conventions
//! * A sphere of radius `R` (m) against a flat, composite compliance `D = 3/4 sum (1 - nu^2)/E`
//!   (1/Pa, the paper's eq. 3), so the effective modulus is `E* = 3/(4 D)` and Johnson's
//!   `K = 4 E*/3 = 1/D`. Work of adhesion `dgamma` (J/m^2).
//! * Load `P` (N) is compressive positive; adhesive (tensile) loads are negative.
//! * Interference `delta` (m), the paper's indentation `z`: the overlap of the undeformed sphere
//!   and the flat, positive when they overlap.
//! * Contact radius `a` (m).
//!
//! # Normalised (Maugis) variables, used for JKR and Maugis-Dugdale
//! `A = a / (pi dgamma R^2 D)^(1/3)`, `P_bar = P / (pi dgamma R)`,
//! `Delta = delta / (pi^2 dgamma^2 R D^2)^(1/3)`, and the Maugis parameter
//! `lambda = 2 sigma0 (R D^2 / (pi dgamma))^(1/3)` with the Dugdale stress
//! `sigma0 = 16 dgamma / (9 sqrt(3) z0)` (the peak stress of the Lennard-Jones 9-3 law with
//! equilibrium spacing `z0`), so that `lambda = 1.1570 mu` with Tabor's
//! `mu = (R dgamma^2 / (E*^2 z0^3))^(1/3)`.
//!
//! In these variables (Maugis 1992; Johnson & Greenwood 1997), with `m = c/a` the ratio of the
//! outer radius of the Dugdale zone to the contact radius and `s = sqrt(m^2 - 1)`:
//! ```text
//! (lambda A^2/2) [s + (s^2 - 1) atan s] + (4 lambda^2 A / 3) [s atan s - m + 1] = 1   (MD-1)
//! P_bar = A^3 - lambda A^2 [s + m^2 atan s]                                         (MD-2)
//! Delta = A^2 - (4/3) lambda A s                                                    (MD-3)
//! ```
//! JKR is the limit `lambda -> inf`: `P_bar = A^3 - sqrt(6 A^3)`, `Delta = A^2 - sqrt(8 A / 3)`;
//! DMT the limit `lambda -> 0`: `P_bar = A^3 - 2`, `Delta = A^2` (the paper's eq. 4).
//!
//! # Branches and hysteresis (JKR, Maugis-Dugdale)
//! Under *load control* the stable branch is `dP/da > 0`; it ends at the pull-off load
//! ([`pull_off_force`]). Under *displacement control* (interference prescribed, as in
//! [`summit_response`]) the stable branch is `d delta/da > 0`; it ends at the displacement-controlled
//! pull-off interference `delta_c` (the minimum of `delta(a)`). Out of contact the laws carry no
//! force (the attraction of separated surfaces is neglected, as in the paper's DMT).
//! * [`Branch::Loading`]: the summit is out of contact until the interference reaches the jump-in
//!   value `delta_in`, where the contact radius jumps from 0 to the stable branch: `delta_in = 0`
//!   for Hertz, DMT and JKR; for Maugis-Dugdale `delta_in = Delta(A -> 0) = -(4/3) lambda c0 < 0`
//!   (the interference where the MD solution reaches zero contact radius; `c0` from MD-1 at `A -> 0`).
//! * [`Branch::Unloading`]: the contact persists down to `delta_c <= delta_in` (JKR:
//!   `Delta_c = 6^(-2/3) - sqrt(8/3) 6^(-1/6) = -0.9086`, where `P = -5/6 pi dgamma R`). For Hertz and DMT
//!   `delta_c = delta_in = 0` (no hysteresis).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

use crate::capillary::Capillarity;
use crate::error::{ContactError, check_finite, check_nonnegative, check_positive};

mod normalised;

use normalised::jkr_state_at_interference;
pub use normalised::{MaugisCurve, MaugisState, MaugisTable, jkr_interference_minimum, jkr_state, maugis_state};

/// Default equilibrium spacing `z0` of the Lennard-Jones law used for the Tabor and Maugis
/// parameters: 0.3 nm (m).
pub const DEFAULT_EQUILIBRIUM_SPACING_M: f64 = 0.3e-9;

/// Ratio `lambda / mu` of the Maugis parameter to the Tabor parameter for the Dugdale stress
/// `sigma0 = 16 dgamma / (9 sqrt 3 z0)`: `2 * 16/(9 sqrt 3) * (9/(16 pi))^(1/3) = 1.1570`.
pub fn maugis_over_tabor() -> f64 {
    2.0 * 16.0 / (9.0 * 3f64.sqrt()) * (9.0 / (16.0 * PI)).cbrt()
}

/// Geometry, elasticity and adhesion of one spherical summit against a flat.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Debug, PartialEq)]
pub struct AsperityParams {
    /// Summit (composite) radius of curvature `R`, m.
    pub radius_m: f64,
    /// Composite compliance `D = 3/4 sum (1 - nu_i^2)/E_i` of eq. 3, 1/Pa (`E* = 3/(4D)`).
    pub compliance_per_pa: f64,
    /// Work of adhesion `dgamma`, J/m^2 (0 for no adhesion).
    pub work_of_adhesion_j_per_m2: f64,
    /// Equilibrium spacing `z0` of the Lennard-Jones law for the Tabor/Maugis parameters, m
    /// (default [`DEFAULT_EQUILIBRIUM_SPACING_M`] = 0.3 nm).
    pub equilibrium_spacing_m: f64,
}

/// The single-asperity law.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[serde(rename_all = "kebab-case")]
pub enum AdhesionLaw {
    /// Hertz, no adhesion (eq. 3).
    Hertz,
    /// DMT as the paper uses it (eq. 4): Hertz deformation, adhesion `2 pi dgamma R` added to the
    /// load of every summit in contact. The paper's default.
    #[default]
    Dmt,
    /// Johnson-Kendall-Roberts (the `lambda -> inf` limit of Maugis-Dugdale).
    Jkr,
    /// Maugis-Dugdale (any Maugis parameter `lambda`, from [`AsperityParams::maugis_parameter`]).
    MaugisDugdale,
}

/// Which branch of a hysteretic (JKR, Maugis-Dugdale) law under displacement control.
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[serde(rename_all = "kebab-case")]
pub enum Branch {
    /// Approaching: contact forms at the jump-in interference.
    Loading,
    /// Receding: contact persists down to the displacement-controlled pull-off interference.
    Unloading,
}
stiction_units::display_serde_name!(AdhesionLaw, Branch);

/// Response of one summit at a prescribed interference ([`summit_response`]).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct SummitResponse {
    /// Whether the summit is in contact (contact radius > 0 or on the contact branch).
    pub in_contact: bool,
    /// Normal load on the summit, N: compressive positive, adhesive negative; 0 out of contact.
    pub load_n: f64,
    /// Contact radius `a`, m (0 out of contact).
    pub contact_radius_m: f64,
    /// Contact stiffness `dP/d delta`, N/m (0 out of contact). For JKR/MD it diverges at the end of
    /// the unloading branch (`d delta/da = 0`).
    pub stiffness_n_per_m: f64,
    /// Peak Hertzian pressure for the contact radius, Pa: `q0 = 3 a / (2 pi D R)`, i.e. eq. 11 with
    /// the Hertzian indentation `z = a^2/R` (for Hertz/DMT exactly eq. 11 with the interference).
    /// For JKR/MD the adhesive tension at the contact edge is not included.
    pub max_pressure_pa: f64,
}

impl SummitResponse {
    /// The response of a summit out of contact.
    pub const NO_CONTACT: SummitResponse = SummitResponse {
        in_contact: false,
        load_n: 0.0,
        contact_radius_m: 0.0,
        stiffness_n_per_m: 0.0,
        max_pressure_pa: 0.0,
    };
}

/// Which law the Maugis parameter recommends (adhesion map of Johnson & Greenwood 1997).
#[derive(Serialize, Deserialize, JsonSchema, Clone, Copy, Debug, PartialEq)]
pub struct LawRecommendation {
    /// Tabor parameter `mu = (R dgamma^2 / (E*^2 z0^3))^(1/3)`.
    pub tabor_parameter: f64,
    /// Maugis parameter `lambda = 1.157 mu`.
    pub maugis_parameter: f64,
    /// Recommended law: DMT for `lambda < 0.1`, JKR for `lambda > 5`, Maugis-Dugdale between
    /// (Hertz when `dgamma = 0`).
    pub law: AdhesionLaw,
}

impl AsperityParams {
    /// Parameters with the default equilibrium spacing (0.3 nm), validated.
    pub fn new(radius_m: f64, compliance_per_pa: f64, work_of_adhesion_j_per_m2: f64) -> Result<Self, ContactError> {
        let p = AsperityParams {
            radius_m,
            compliance_per_pa,
            work_of_adhesion_j_per_m2,
            equilibrium_spacing_m: DEFAULT_EQUILIBRIUM_SPACING_M,
        };
        p.validate()?;
        Ok(p)
    }

    /// The paper's Table 1 summit: R = 0.5 um, D = 9.1e-12 1/Pa, dgamma = 0.1 J/m^2, z0 = 0.3 nm.
    pub fn table1() -> Self {
        AsperityParams {
            radius_m: 0.5e-6,
            compliance_per_pa: 9.1e-12,
            work_of_adhesion_j_per_m2: 0.1,
            equilibrium_spacing_m: DEFAULT_EQUILIBRIUM_SPACING_M,
        }
    }

    /// Check every field: radius, compliance and spacing finite and > 0, work of adhesion finite
    /// and >= 0.
    pub fn validate(&self) -> Result<(), ContactError> {
        check_positive("radius_m", self.radius_m, "a finite radius > 0 (m)")?;
        check_positive("compliance_per_pa", self.compliance_per_pa, "a finite compliance D > 0 (1/Pa)")?;
        check_nonnegative(
            "work_of_adhesion_j_per_m2",
            self.work_of_adhesion_j_per_m2,
            "a finite work of adhesion >= 0 (J/m^2)",
        )?;
        check_positive("equilibrium_spacing_m", self.equilibrium_spacing_m, "a finite equilibrium spacing z0 > 0 (m)")?;
        Ok(())
    }

    /// Effective modulus `E* = 3/(4 D)`, Pa.
    pub fn effective_modulus_pa(&self) -> f64 {
        0.75 / self.compliance_per_pa
    }

    /// Tabor parameter `mu = (R dgamma^2 / (E*^2 z0^3))^(1/3)` (dimensionless).
    pub fn tabor_parameter(&self) -> f64 {
        let e = self.effective_modulus_pa();
        (self.radius_m * self.work_of_adhesion_j_per_m2.powi(2) / (e * e * self.equilibrium_spacing_m.powi(3))).cbrt()
    }

    /// Maugis parameter `lambda = 2 sigma0 (R D^2/(pi dgamma))^(1/3)` with
    /// `sigma0 = 16 dgamma/(9 sqrt 3 z0)`; equals [`maugis_over_tabor`]` * mu` = 1.157 mu.
    pub fn maugis_parameter(&self) -> f64 {
        maugis_over_tabor() * self.tabor_parameter()
    }

    /// The recommended law (see [`LawRecommendation`]).
    pub fn recommendation(&self) -> LawRecommendation {
        let mu = self.tabor_parameter();
        let lambda = self.maugis_parameter();
        let law = if self.work_of_adhesion_j_per_m2 == 0.0 {
            AdhesionLaw::Hertz
        } else if lambda < 0.1 {
            AdhesionLaw::Dmt
        } else if lambda > 5.0 {
            AdhesionLaw::Jkr
        } else {
            AdhesionLaw::MaugisDugdale
        };
        LawRecommendation { tabor_parameter: mu, maugis_parameter: lambda, law }
    }

    /// Length scale of the contact radius `(pi dgamma R^2 D)^(1/3)`, m.
    pub fn radius_scale_m(&self) -> f64 {
        (PI * self.work_of_adhesion_j_per_m2 * self.radius_m.powi(2) * self.compliance_per_pa).cbrt()
    }

    /// Load scale `pi dgamma R`, N.
    pub fn load_scale_n(&self) -> f64 {
        PI * self.work_of_adhesion_j_per_m2 * self.radius_m
    }

    /// Interference scale `(pi^2 dgamma^2 R D^2)^(1/3) = a_scale^2 / R`, m.
    pub fn interference_scale_m(&self) -> f64 {
        self.radius_scale_m().powi(2) / self.radius_m
    }

    /// DMT adhesive load of one summit `2 pi dgamma R` (eq. 4), N.
    pub fn dmt_adhesion_n(&self) -> f64 {
        2.0 * PI * self.work_of_adhesion_j_per_m2 * self.radius_m
    }

    /// Hertzian peak pressure for contact radius `a`: `q0 = 3 a/(2 pi D R)` (eq. 11 with `z = a^2/R`), Pa.
    pub fn hertz_peak_pressure_pa(&self, contact_radius_m: f64) -> f64 {
        1.5 * contact_radius_m / (PI * self.compliance_per_pa * self.radius_m)
    }
}

// ---------------------------------------------------------------------------------------------
// Dimensional laws
// ---------------------------------------------------------------------------------------------

/// Characteristic points of a law for given parameters (dimensional).
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct BranchLimits {
    /// Jump-in interference on loading, m (0 for Hertz, DMT, JKR; `< 0` for Maugis-Dugdale).
    pub jump_in_interference_m: f64,
    /// Load right after jump-in, N (DMT: `-2 pi dgamma R`, JKR: `-4/3 pi dgamma R`).
    pub jump_in_load_n: f64,
    /// End of the unloading branch under displacement control, m (JKR: `-0.9086 delta_scale`).
    pub pull_off_interference_m: f64,
    /// Load at the end of the unloading branch (displacement control), N (JKR: `-5/6 pi dgamma R`).
    pub pull_off_interference_load_n: f64,
    /// Minimum load of the load-controlled stable branch (minus the pull-off force), N.
    pub pull_off_load_n: f64,
    /// Contact radius at the load-controlled pull-off, m.
    pub pull_off_contact_radius_m: f64,
}

fn effective_law(law: AdhesionLaw, p: &AsperityParams) -> AdhesionLaw {
    if p.work_of_adhesion_j_per_m2 == 0.0 { AdhesionLaw::Hertz } else { law }
}

/// Characteristic points (jump-in, pull-off under displacement and load control) of `law`.
/// Without adhesion (`dgamma = 0`) every law is Hertz.
pub fn branch_limits(law: AdhesionLaw, p: &AsperityParams) -> Result<BranchLimits, ContactError> {
    p.validate()?;
    let (ls, ds, rs) = (p.load_scale_n(), p.interference_scale_m(), p.radius_scale_m());
    Ok(match effective_law(law, p) {
        AdhesionLaw::Hertz => BranchLimits {
            jump_in_interference_m: 0.0,
            jump_in_load_n: 0.0,
            pull_off_interference_m: 0.0,
            pull_off_interference_load_n: 0.0,
            pull_off_load_n: 0.0,
            pull_off_contact_radius_m: 0.0,
        },
        AdhesionLaw::Dmt => BranchLimits {
            jump_in_interference_m: 0.0,
            jump_in_load_n: -p.dmt_adhesion_n(),
            pull_off_interference_m: 0.0,
            pull_off_interference_load_n: -p.dmt_adhesion_n(),
            pull_off_load_n: -p.dmt_adhesion_n(),
            pull_off_contact_radius_m: 0.0,
        },
        AdhesionLaw::Jkr => {
            let c = jkr_interference_minimum();
            let jump = jkr_state((8.0_f64 / 3.0).cbrt());
            BranchLimits {
                jump_in_interference_m: 0.0,
                jump_in_load_n: jump.p_bar * ls,
                pull_off_interference_m: c.delta_bar * ds,
                pull_off_interference_load_n: c.p_bar * ls,
                pull_off_load_n: -1.5 * ls,
                pull_off_contact_radius_m: 1.5f64.cbrt() * rs,
            }
        }
        AdhesionLaw::MaugisDugdale => {
            let curve = MaugisCurve::new(p.maugis_parameter())?;
            let jump = curve.state_at_interference(curve.zero_radius.delta_bar).unwrap_or(curve.zero_radius);
            BranchLimits {
                jump_in_interference_m: curve.zero_radius.delta_bar * ds,
                jump_in_load_n: jump.p_bar * ls,
                pull_off_interference_m: curve.interference_minimum.delta_bar * ds,
                pull_off_interference_load_n: curve.interference_minimum.p_bar * ls,
                pull_off_load_n: curve.load_minimum.p_bar * ls,
                pull_off_contact_radius_m: curve.load_minimum.a_hat * rs,
            }
        }
    })
}

/// Pull-off force under load control (magnitude, N): 0 (Hertz), `2 pi dgamma R` (DMT, eq. 4),
/// `1.5 pi dgamma R` (JKR), between the two for Maugis-Dugdale.
pub fn pull_off_force(law: AdhesionLaw, p: &AsperityParams) -> Result<f64, ContactError> {
    Ok(-branch_limits(law, p)?.pull_off_load_n)
}

/// Capillary pull of one summit (radius `p.radius_m`) at separation `separation_m` (m; <= 0 in
/// contact), N: the sphere-flat meniscus force `2 pi R gamma (cos th1 + cos th2 - max(D,0)/r_K)` up
/// to the meniscus height `h_m`, 0 beyond ([`Capillarity::sphere_flat_force_n`]). The meniscus is
/// in equilibrium with the vapour: it condenses whenever the gap is below `h_m`, on approach as on
/// retraction, and ruptures beyond `h_m` (docs/models.md, "Capillary adhesion").
pub fn meniscus_force_n(capillarity: &Capillarity, p: &AsperityParams, separation_m: f64) -> f64 {
    capillarity.sphere_flat_force_n(p.radius_m, separation_m)
}

/// Pull-off force under load control with a meniscus (magnitude, N). While the summit touches,
/// its meniscus pulls with the constant `F_m = 2 pi R gamma (cos th1 + cos th2)` (the wetted disc
/// is set by the Kelvin radius, not by the contact radius), so the solid law sees `P + F_m`: every
/// branch shifts by `F_m` and the pull-off is `|P_c| + F_m` (DMT:
/// `2 pi R (dgamma + gamma (cos th1 + cos th2))`, `4 pi R (dgamma/2 + gamma cos theta)` for equal
/// faces; JKR: `1.5 pi dgamma R + F_m`). Once the solid contact breaks the meniscus pulls
/// `F_m(D) < F_m` ([`separated_load_wet_n`]), so no larger tension is held. `None`:
/// [`pull_off_force`].
pub fn pull_off_force_wet(
    law: AdhesionLaw,
    p: &AsperityParams,
    capillarity: Option<&Capillarity>,
) -> Result<f64, ContactError> {
    let solid = pull_off_force(law, p)?;
    Ok(solid + capillarity.map_or(0.0, |c| c.sphere_flat_force_n(p.radius_m, 0.0)))
}

/// The load (N, compressive positive) that holds a summit out of solid contact at separation
/// `separation_m` (m, > 0) from the counter face: the meniscus condensed in the gap pulls it
/// towards the face, so the load is `-F_m(D) = -2 pi R gamma (cos th1 + cos th2 - D/r_K)` for
/// `D <= h_m` and 0 beyond (no meniscus; the DMT and Hertz laws carry nothing out of contact).
/// `None` (dry): 0. The out-of-contact branch of the single-asperity load-separation curve.
pub fn separated_load_wet_n(p: &AsperityParams, separation_m: f64, capillarity: Option<&Capillarity>) -> f64 {
    capillarity.map_or(0.0, |c| -c.sphere_flat_force_n(p.radius_m, separation_m.max(0.0)))
}

/// [`load_state`] of a summit in contact with a meniscus: the solid law carries the applied load
/// plus the meniscus pull at contact, `P + 2 pi R gamma (cos th1 + cos th2)` (see
/// [`pull_off_force_wet`]). `None`: exactly [`load_state`].
pub fn load_state_wet(
    law: AdhesionLaw,
    p: &AsperityParams,
    load_n: f64,
    capillarity: Option<&Capillarity>,
) -> Result<LoadState, ContactError> {
    match capillarity {
        None => load_state(law, p, load_n),
        Some(c) => load_state(law, p, load_n + c.sphere_flat_force_n(p.radius_m, 0.0)),
    }
}

fn check_radius(a: f64) -> Result<f64, ContactError> {
    check_nonnegative("contact_radius_m", a, "a finite contact radius >= 0 (m)")
}

/// Load `P` (N) at contact radius `a` (m): Hertz `a^3/(R D)` (eq. 3b), DMT `a^3/(R D) - 2 pi dgamma R`
/// (eq. 4b), JKR `a^3/(RD) - sqrt(6 pi dgamma a^3 / D)`, Maugis-Dugdale MD-2.
pub fn load_from_contact_radius(
    law: AdhesionLaw,
    p: &AsperityParams,
    contact_radius_m: f64,
) -> Result<f64, ContactError> {
    p.validate()?;
    let a = check_radius(contact_radius_m)?;
    let hertz = a.powi(3) / (p.radius_m * p.compliance_per_pa);
    Ok(match effective_law(law, p) {
        AdhesionLaw::Hertz => hertz,
        AdhesionLaw::Dmt => hertz - p.dmt_adhesion_n(),
        AdhesionLaw::Jkr => jkr_state(a / p.radius_scale_m()).p_bar * p.load_scale_n(),
        AdhesionLaw::MaugisDugdale => {
            maugis_state(p.maugis_parameter(), a / p.radius_scale_m(), 0.0).p_bar * p.load_scale_n()
        }
    })
}

/// Interference `delta` (m) at contact radius `a` (m): Hertz and DMT `a^2/R` (eq. 3a, 4a),
/// JKR `a^2/R - sqrt(8 pi dgamma a D/3)`, Maugis-Dugdale MD-3.
pub fn interference_from_contact_radius(
    law: AdhesionLaw,
    p: &AsperityParams,
    contact_radius_m: f64,
) -> Result<f64, ContactError> {
    p.validate()?;
    let a = check_radius(contact_radius_m)?;
    Ok(match effective_law(law, p) {
        AdhesionLaw::Hertz | AdhesionLaw::Dmt => a * a / p.radius_m,
        AdhesionLaw::Jkr => jkr_state(a / p.radius_scale_m()).delta_bar * p.interference_scale_m(),
        AdhesionLaw::MaugisDugdale => {
            maugis_state(p.maugis_parameter(), a / p.radius_scale_m(), 0.0).delta_bar * p.interference_scale_m()
        }
    })
}

/// Contact state on the load-controlled stable branch.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq)]
pub struct LoadState {
    /// Contact radius `a`, m.
    pub contact_radius_m: f64,
    /// Interference `delta`, m.
    pub interference_m: f64,
    /// `da/dP`, m/N (used for the slope of the discrete model, eq. 12).
    pub dradius_dload_m_per_n: f64,
    /// Hertzian peak pressure `3a/(2 pi D R)`, Pa (eq. 11 with `z = a^2/R`).
    pub max_pressure_pa: f64,
}

/// Contact radius, interference and `da/dP` at load `P` (N) on the load-controlled stable
/// branch (the one with the larger contact). Hertz: `a = (R D P)^(1/3)`; DMT:
/// `a = (R D (P + 2 pi dgamma R))^(1/3)` (eq. 4b); JKR: `A^(3/2) = (sqrt 6 + sqrt(6 + 4 P_bar))/2`;
/// Maugis-Dugdale: MD-1..3 solved numerically. Below the pull-off load: `Err(NoEquilibrium)`.
pub fn load_state(law: AdhesionLaw, p: &AsperityParams, load_n: f64) -> Result<LoadState, ContactError> {
    p.validate()?;
    check_finite("load_n", load_n, "a finite load (N)")?;
    let rd = p.radius_m * p.compliance_per_pa;
    let below =
        |min: f64| ContactError::NoEquilibrium { quantity: "load_n", value: load_n, pull_off: format!("{min:e} N") };
    let (a, delta, da_dp) = match effective_law(law, p) {
        l @ (AdhesionLaw::Hertz | AdhesionLaw::Dmt) => {
            let adh = if l == AdhesionLaw::Dmt { p.dmt_adhesion_n() } else { 0.0 };
            let elastic = load_n + adh;
            if elastic < 0.0 {
                return Err(below(-adh));
            }
            let a = (rd * elastic).cbrt();
            let da = if a > 0.0 { rd / (3.0 * a * a) } else { f64::INFINITY };
            (a, a * a / p.radius_m, da)
        }
        AdhesionLaw::Jkr => {
            let pb = load_n / p.load_scale_n();
            let disc = 6.0 + 4.0 * pb;
            if disc < 0.0 {
                return Err(below(-1.5 * p.load_scale_n()));
            }
            let y = 0.5 * (6f64.sqrt() + disc.sqrt());
            let st = jkr_state(y.powf(2.0 / 3.0));
            (
                st.a_hat * p.radius_scale_m(),
                st.delta_bar * p.interference_scale_m(),
                p.radius_scale_m() / (st.dp_bar_da * p.load_scale_n()),
            )
        }
        AdhesionLaw::MaugisDugdale => {
            let curve = MaugisCurve::new(p.maugis_parameter())?;
            let st = curve
                .state_at_load(load_n / p.load_scale_n())
                .map_err(|_| below(curve.load_minimum.p_bar * p.load_scale_n()))?;
            (
                st.a_hat * p.radius_scale_m(),
                st.delta_bar * p.interference_scale_m(),
                p.radius_scale_m() / (st.dp_bar_da * p.load_scale_n()),
            )
        }
    };
    Ok(LoadState {
        contact_radius_m: a,
        interference_m: delta,
        dradius_dload_m_per_n: da_dp,
        max_pressure_pa: p.hertz_peak_pressure_pa(a),
    })
}

/// Contact radius (m) at load `P` (N) on the load-controlled stable branch; see [`load_state`].
pub fn contact_radius_from_load(law: AdhesionLaw, p: &AsperityParams, load_n: f64) -> Result<f64, ContactError> {
    Ok(load_state(law, p, load_n)?.contact_radius_m)
}

/// Interference-controlled response of one summit, the building block of the explicit solver.
///
/// `interference_m > 0` means overlap. Hertz: contact iff `delta > 0`, `a = sqrt(R delta)`,
/// `P = R^(1/2) delta^(3/2)/D` (eq. 3). DMT: the same with `P -= 2 pi dgamma R` (eq. 4; the load
/// jumps to `-2 pi dgamma R` at touch-down). JKR and Maugis-Dugdale: see the module docs for the
/// branches (Loading: contact iff `delta >= delta_in`; Unloading: iff `delta >= delta_c`), the
/// state is the displacement-controlled stable branch. Out of contact everything is 0.
/// Stiffness `dP/d delta`: `3a/(2D)` for Hertz/DMT.
///
/// Cost: Hertz/DMT a few ns (no validation: `p` must satisfy [`AsperityParams::validate`]);
/// JKR ~0.1 us; Maugis-Dugdale builds its curve on each call (~0.5 ms): for repeated
/// calls use [`SummitModel`], which precomputes a [`MaugisTable`].
pub fn summit_response(law: AdhesionLaw, p: &AsperityParams, interference_m: f64, branch: Branch) -> SummitResponse {
    match effective_law(law, p) {
        AdhesionLaw::Hertz => hertz_dmt_response(p, interference_m, 0.0),
        AdhesionLaw::Dmt => hertz_dmt_response(p, interference_m, p.dmt_adhesion_n()),
        AdhesionLaw::Jkr => jkr_response(p, &Scales::new(p), interference_m, branch),
        AdhesionLaw::MaugisDugdale => match MaugisCurve::new(p.maugis_parameter()) {
            Ok(curve) => {
                md_response(p, &Scales::new(p), &curve, |d| curve.state_at_interference(d), interference_m, branch)
            }
            Err(_) => SummitResponse::NO_CONTACT,
        },
    }
}

#[inline]
fn hertz_dmt_response(p: &AsperityParams, delta: f64, adhesion_n: f64) -> SummitResponse {
    if delta > 0.0 {
        let a = (p.radius_m * delta).sqrt();
        let inv_d = 1.0 / p.compliance_per_pa;
        SummitResponse {
            in_contact: true,
            load_n: a * delta * inv_d - adhesion_n,
            contact_radius_m: a,
            stiffness_n_per_m: 1.5 * a * inv_d,
            max_pressure_pa: 1.5 * a * inv_d / (PI * p.radius_m),
        }
    } else {
        SummitResponse::NO_CONTACT
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
struct Scales {
    load: f64,
    radius: f64,
    interference: f64,
}

impl Scales {
    fn new(p: &AsperityParams) -> Self {
        Scales { load: p.load_scale_n(), radius: p.radius_scale_m(), interference: p.interference_scale_m() }
    }
}

fn normalized_response(p: &AsperityParams, sc: &Scales, st: &MaugisState) -> SummitResponse {
    let a = st.a_hat * sc.radius;
    SummitResponse {
        in_contact: true,
        load_n: st.p_bar * sc.load,
        contact_radius_m: a,
        stiffness_n_per_m: st.dp_bar_da / st.ddelta_bar_da * sc.load / sc.interference,
        max_pressure_pa: p.hertz_peak_pressure_pa(a),
    }
}

fn jkr_response(p: &AsperityParams, sc: &Scales, delta: f64, branch: Branch) -> SummitResponse {
    let d = delta / sc.interference;
    let start = match branch {
        Branch::Loading => 0.0,
        Branch::Unloading => jkr_interference_minimum().delta_bar,
    };
    if d.is_nan() || d < start {
        return SummitResponse::NO_CONTACT;
    }
    normalized_response(p, sc, &jkr_state_at_interference(d))
}

fn md_response(
    p: &AsperityParams,
    sc: &Scales,
    curve: &MaugisCurve,
    solve: impl Fn(f64) -> Option<MaugisState>,
    delta: f64,
    branch: Branch,
) -> SummitResponse {
    let d = delta / sc.interference;
    let start = match branch {
        Branch::Loading => curve.zero_radius.delta_bar,
        Branch::Unloading => curve.interference_minimum.delta_bar,
    };
    if d.is_nan() || d < start {
        return SummitResponse::NO_CONTACT;
    }
    match solve(d) {
        Some(st) => normalized_response(p, sc, &st),
        None => SummitResponse::NO_CONTACT,
    }
}

/// A summit law with everything precomputed for repeated [`SummitModel::response`] calls (for
/// Maugis-Dugdale a [`MaugisTable`], about 1 ms to build).
#[derive(Clone, Debug, PartialEq)]
pub struct SummitModel {
    law: AdhesionLaw,
    params: AsperityParams,
    scales: Scales,
    table: Option<Box<MaugisTable>>,
}

impl SummitModel {
    /// Validate `params` and precompute.
    pub fn new(law: AdhesionLaw, params: AsperityParams) -> Result<Self, ContactError> {
        params.validate()?;
        let law = effective_law(law, &params);
        let table = if law == AdhesionLaw::MaugisDugdale {
            Some(Box::new(MaugisTable::new(params.maugis_parameter())?))
        } else {
            None
        };
        Ok(SummitModel { law, params, scales: Scales::new(&params), table })
    }

    /// The law in use (Hertz if the work of adhesion is 0).
    pub fn law(&self) -> AdhesionLaw {
        self.law
    }

    /// The parameters.
    pub fn params(&self) -> &AsperityParams {
        &self.params
    }

    /// Same as [`summit_response`] with this model's law and parameters.
    #[inline]
    pub fn response(&self, interference_m: f64, branch: Branch) -> SummitResponse {
        match self.law {
            AdhesionLaw::Hertz => hertz_dmt_response(&self.params, interference_m, 0.0),
            AdhesionLaw::Dmt => hertz_dmt_response(&self.params, interference_m, self.params.dmt_adhesion_n()),
            AdhesionLaw::Jkr => jkr_response(&self.params, &self.scales, interference_m, branch),
            AdhesionLaw::MaugisDugdale => match &self.table {
                Some(t) => md_response(
                    &self.params,
                    &self.scales,
                    &t.curve,
                    |d| t.state_at_interference(d),
                    interference_m,
                    branch,
                ),
                None => SummitResponse::NO_CONTACT,
            },
        }
    }

    /// Interference at which contact starts on `branch` (m): `delta_in` for Loading, `delta_c`
    /// for Unloading (both 0 for Hertz and DMT).
    pub fn contact_start_interference_m(&self, branch: Branch) -> f64 {
        let d = match (self.law, branch) {
            (AdhesionLaw::Hertz | AdhesionLaw::Dmt, _) | (AdhesionLaw::Jkr, Branch::Loading) => 0.0,
            (AdhesionLaw::Jkr, Branch::Unloading) => jkr_interference_minimum().delta_bar,
            (AdhesionLaw::MaugisDugdale, b) => match &self.table {
                Some(t) => match b {
                    Branch::Loading => t.curve.zero_radius.delta_bar,
                    Branch::Unloading => t.curve.interference_minimum.delta_bar,
                },
                None => 0.0,
            },
        };
        d * self.scales.interference
    }
}
