//! Electrostatics of a gap-closing plate (finger) array.
//!
//! Geometry: `n` movable plates (fingers), each facing a fixed *front* electrode across the front
//! gap `g_f` and, optionally, a fixed *back* (anti-gap) electrode across the back gap `g_b`. The
//! plates overlap the electrodes over the length `l` (m) and the full structural thickness `t` (m).
//! A travel `x` (m, positive towards the front electrode) closes the front gap to `g_f - x` and
//! opens the back gap to `g_b + x`.
//!
//! The force is always taken from the co-energy (voltage-driven):
//!
//! `W*(x, V) = 1/2 V^2 [C(g_f - x) + s_b C(g_b + x)]`, `F = dW*/dx = 1/2 V^2 [-C'(g_f - x) + s_b C'(g_b + x)]`
//!
//! per plate, with `C'(g) = dC/dg < 0` and `s_b = 1` when the back electrode is at the front
//! electrode's potential (it pulls the other way) and `s_b = 0` when it is at the plate's
//! potential (grounded with the moving structure: no field, no force).

use serde::{Deserialize, Serialize};

use crate::cross_section::{CombGeometry, CrossSectionTable};
use crate::error::{ActuatorError, nonnegative, positive};
use std::sync::Arc;

/// Vacuum permittivity eps0 (F/m), CODATA 2018 (defined with the field solution it enters).
pub use crate::cross_section::VACUUM_PERMITTIVITY;

/// How the capacitance of one plate pair is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Fringing {
    /// Ideal parallel plate: `C = eps l t / g`.
    Off,
    /// Palmer's formula (H. B. Palmer, Trans. AIEE 56, 363, 1937), applied to both edges of both
    /// plate dimensions:
    /// `C = eps l t / g * p(g, t) * p(g, l)`, `p(g, d) = 1 + g/(pi d) (1 + ln(2 pi d / g))`.
    /// The force follows from `dC/dg` of this expression (not from a scaled parallel-plate force):
    /// for one dimension `d(l t p/g)/dg` gives the factor `1 + g/(pi d)` on the parallel-plate
    /// force.
    Palmer,
    /// Two-dimensional cross-section of the comb ([`crate::cross_section`]): the capacitance per
    /// unit length of one finger between its front and back electrodes from a finite-difference
    /// Laplace solve (fringing through the top and bottom of both gaps, the finger's own width,
    /// the neighbouring electrode's shielding, optional substrate), tabulated once per geometry.
    /// The finger ends keep Palmer's length factor:
    /// `C = n [eps l t/g_f p(g_f, l) + s_b eps l t/g_b p(g_b, l) + l dC'_2D(x)]`,
    /// `dC'_2D = C'_2D - eps t (1/g_f + 1/g_b)` the 2D excess over the two parallel plates.
    /// Needs [`PlateArray::comb`] and a back electrode at the front potential (or none).
    CrossSection,
}

/// Potential of the back (anti-gap) electrode.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BackPotential {
    /// Same potential as the front electrode: the back gap sees the full voltage and pulls the
    /// plates away from the front electrode.
    SameAsFront,
    /// At the potential of the moving plates (grounded with them): no force.
    Grounded,
}

/// The back (anti-gap) electrode of every plate.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BackElectrode {
    /// Back gap at zero travel, `g_b` (m).
    pub gap_m: f64,
    /// Its potential.
    pub potential: BackPotential,
}

/// A gap-closing array of identical plates (rigid plates; finger bending lives in
/// [`crate::bending`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PlateArray {
    /// Number of movable plates (fingers), `n`.
    pub plate_count: u32,
    /// Overlap length of a plate with its electrode, `l` (m).
    pub overlap_length_m: f64,
    /// Plate (structural layer) thickness, `t` (m).
    pub thickness_m: f64,
    /// Front gap at zero travel, `g_f` (m).
    pub front_gap_m: f64,
    /// Optional back (anti-gap) electrode.
    pub back: Option<BackElectrode>,
    /// Capacitance model.
    pub fringing: Fringing,
    /// Relative permittivity of the gap medium (1 for vacuum; 1.0006 for air).
    pub relative_permittivity: f64,
    /// Cross-section geometry (finger and electrode widths, substrate), used by
    /// [`Fringing::CrossSection`] only; default none.
    #[serde(default)]
    pub comb: Option<CombGeometry>,
}

/// Palmer's edge factor `p(g, d) = 1 + g/(pi d) (1 + ln(2 pi d/g))` and its first two
/// derivatives with respect to `g`: `p' = ln(2 pi d/g)/(pi d)`, `p'' = -1/(pi d g)`.
fn palmer_factor(gap_m: f64, dimension_m: f64) -> (f64, f64, f64) {
    let pd = std::f64::consts::PI * dimension_m;
    let ln = (2.0 * std::f64::consts::PI * dimension_m / gap_m).ln();
    (1.0 + gap_m / pd * (1.0 + ln), ln / pd, -1.0 / (pd * gap_m))
}

impl PlateArray {
    /// Checks every field; the error names the field.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        if self.plate_count == 0 {
            return Err(ActuatorError::InvalidField {
                field: "plate_count".into(),
                value: 0.0,
                expected: "at least 1 plate".into(),
            });
        }
        positive("overlap_length", self.overlap_length_m)?;
        positive("thickness", self.thickness_m)?;
        positive("front_gap", self.front_gap_m)?;
        positive("relative_permittivity", self.relative_permittivity)?;
        if let Some(b) = self.back {
            positive("back_gap", b.gap_m)?;
        }
        if self.fringing == Fringing::CrossSection {
            let comb = self.comb.ok_or_else(|| {
                ActuatorError::Inconsistent("fringing `cross_section` needs the `comb` geometry".into())
            })?;
            comb.validate()?;
            if self.back.is_some_and(|b| b.potential == BackPotential::Grounded) {
                return Err(ActuatorError::Inconsistent(
                    "fringing `cross_section` models a back electrode at the front potential (or none), not `grounded`"
                        .into(),
                ));
            }
            self.cross_section_table()?;
        }
        Ok(())
    }

    /// The cross-section table of this array (computed on first use, then cached).
    fn cross_section_table(&self) -> Result<Arc<CrossSectionTable>, ActuatorError> {
        let comb = self
            .comb
            .ok_or_else(|| ActuatorError::Inconsistent("fringing `cross_section` needs the `comb` geometry".into()))?;
        crate::cross_section::table(self.thickness_m, self.front_gap_m, self.back.map(|b| b.gap_m), comb)
    }

    /// Cross-section excess of the whole plate `l dC'_2D(x)` and its first two travel
    /// derivatives (F, F/m, F/m^2); zero unless [`Fringing::CrossSection`]. NaN if the table
    /// cannot be computed (reported by [`Self::validate`]).
    fn cross_section_excess(&self, travel_m: f64) -> (f64, f64, f64) {
        if self.fringing != Fringing::CrossSection {
            return (0.0, 0.0, 0.0);
        }
        match self.cross_section_table() {
            Ok(t) => {
                let (c, c1, c2) = t.excess(travel_m);
                let s = self.relative_permittivity * self.overlap_length_m;
                (s * c, s * c1, s * c2)
            }
            Err(_) => (f64::NAN, f64::NAN, f64::NAN),
        }
    }

    /// Permittivity of the gap, `eps = eps_r eps0` (F/m).
    pub fn permittivity(&self) -> f64 {
        self.relative_permittivity * VACUUM_PERMITTIVITY
    }

    /// Capacitance of one plate pair at gap `g` and its derivatives `(C, dC/dg, d2C/dg2)`
    /// (F, F/m, F/m^2). Parallel plate: `C = eps l t/g`; Palmer: see [`Fringing::Palmer`].
    pub fn pair_capacitance(&self, gap_m: f64) -> (f64, f64, f64) {
        let e = self.permittivity() * self.overlap_length_m * self.thickness_m;
        let g = gap_m;
        match self.fringing {
            Fringing::Off => (e / g, -e / (g * g), 2.0 * e / (g * g * g)),
            Fringing::CrossSection => {
                // Palmer's factor on the length only; the thickness fringing is in the 2D excess.
                let (p, p1, p2) = palmer_factor(g, self.overlap_length_m);
                (e * p / g, e * (p1 / g - p / (g * g)), e * (p2 / g - 2.0 * p1 / (g * g) + 2.0 * p / (g * g * g)))
            }
            Fringing::Palmer => {
                let (pt, pt1, pt2) = palmer_factor(g, self.thickness_m);
                let (pl, pl1, pl2) = palmer_factor(g, self.overlap_length_m);
                let p = pt * pl;
                let p1 = pt1 * pl + pt * pl1;
                let p2 = pt2 * pl + 2.0 * pt1 * pl1 + pt * pl2;
                // u = p/g, u' = p'/g - p/g^2, u'' = p''/g - 2p'/g^2 + 2p/g^3
                (e * p / g, e * (p1 / g - p / (g * g)), e * (p2 / g - 2.0 * p1 / (g * g) + 2.0 * p / (g * g * g)))
            }
        }
    }

    /// Total capacitance of the array between plates and front (and, if at the same potential,
    /// back) electrodes at travel `x` (F): `n [C(g_f - x) + s_b C(g_b + x)]`.
    pub fn capacitance_f(&self, travel_m: f64) -> f64 {
        let n = f64::from(self.plate_count);
        let mut c = self.pair_capacitance(self.front_gap_m - travel_m).0;
        if let Some(b) = self.back
            && b.potential == BackPotential::SameAsFront
        {
            c += self.pair_capacitance(b.gap_m + travel_m).0;
        }
        n * (c + self.cross_section_excess(travel_m).0)
    }

    /// Co-energy `W* = 1/2 C(x) V^2` (J) at travel `x` (m) and voltage `V` (V).
    pub fn coenergy_j(&self, travel_m: f64, voltage_v: f64) -> f64 {
        0.5 * self.capacitance_f(travel_m) * voltage_v * voltage_v
    }

    /// Electrostatic force per volt squared at travel `x`, `f(x) = F/V^2 = dC/dx / 2` (N/V^2):
    /// `f = n/2 [-C'(g_f - x) + s_b C'(g_b + x)]`. This is the conversion factor `a` of the
    /// paper (section 5, `F = a V^2`) at the operating travel `x`.
    pub fn force_per_volt2(&self, travel_m: f64) -> f64 {
        self.force_per_volt2_and_slope(travel_m).0
    }

    /// `f(x)` (N/V^2) and `df/dx` (N/(V^2 m)): `df/dx = n/2 [C''(g_f - x) + s_b C''(g_b + x)]`.
    pub fn force_per_volt2_and_slope(&self, travel_m: f64) -> (f64, f64) {
        let n = f64::from(self.plate_count);
        let (_, c1f, c2f) = self.pair_capacitance(self.front_gap_m - travel_m);
        let mut f = -c1f;
        let mut df = c2f;
        if let Some(b) = self.back
            && b.potential == BackPotential::SameAsFront
        {
            let (_, c1b, c2b) = self.pair_capacitance(b.gap_m + travel_m);
            f += c1b;
            df += c2b;
        }
        // Travel derivatives of the 2D excess (d/dx, not d/dg).
        let (_, e1, e2) = self.cross_section_excess(travel_m);
        (0.5 * n * (f + e1), 0.5 * n * (df + e2))
    }

    /// Force per volt squared per unit overlap length of one plate at travel `x` (N/(V^2 m)):
    /// `f(x) / (n l)`, the line load used by the finger-bending model.
    pub fn line_force_per_volt2(&self, travel_m: f64) -> f64 {
        self.force_per_volt2(travel_m) / (f64::from(self.plate_count) * self.overlap_length_m)
    }

    /// Electrostatic force (N) at travel `x` (m) and voltage `V` (V): `F = f(x) V^2`.
    pub fn force_n(&self, travel_m: f64, voltage_v: f64) -> f64 {
        self.force_per_volt2(travel_m) * voltage_v * voltage_v
    }

    /// Applies a process undercut `u` (m per edge): gaps grow by `2u`, the overlap shortens by
    /// `u` (the plate tip recedes by `u`), the comb's finger and electrode widths shrink by `2u`.
    /// Thickness and the substrate gap are unchanged (vertical etch).
    pub fn with_undercut(&self, undercut_m: f64) -> Result<Self, ActuatorError> {
        nonnegative("undercut", undercut_m)?;
        let mut out = *self;
        out.front_gap_m += 2.0 * undercut_m;
        out.overlap_length_m -= undercut_m;
        if let Some(b) = out.back.as_mut() {
            b.gap_m += 2.0 * undercut_m;
        }
        if let Some(c) = out.comb.as_mut() {
            c.finger_width_m -= 2.0 * undercut_m;
            c.electrode_width_m -= 2.0 * undercut_m;
        }
        out.validate()?;
        Ok(out)
    }
}

/// Front gap at zero travel (m) for which the plate array gives the conversion factor `a`
/// (N/V^2) at travel `x_op` (m): solves `f(x_op; g_f) = a` by bisection on `g_f` (`f` falls
/// monotonically with the gap). Parallel plate, no back electrode:
/// `g_f = x_op + sqrt(n eps l t / (2 a))`.
pub fn infer_front_gap_m(
    template: &PlateArray,
    operating_travel_m: f64,
    conversion_factor: f64,
) -> Result<f64, ActuatorError> {
    nonnegative("operating_travel", operating_travel_m)?;
    positive("conversion_factor", conversion_factor)?;
    let f_at = |gap: f64| {
        let mut p = *template;
        p.front_gap_m = gap;
        p.force_per_volt2(operating_travel_m)
    };
    // Parallel-plate estimate, then a bracket around it.
    let n = f64::from(template.plate_count);
    let pp = (n * template.permittivity() * template.overlap_length_m * template.thickness_m
        / (2.0 * conversion_factor))
        .sqrt();
    let mut lo = operating_travel_m + pp * 1e-3;
    let mut hi = operating_travel_m + pp * 10.0;
    if f_at(lo) < conversion_factor || f_at(hi) > conversion_factor {
        return Err(ActuatorError::Solver(format!(
            "no front gap in [{lo:e}, {hi:e}] m gives conversion_factor = {conversion_factor:e} N/V^2"
        )));
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f_at(mid) > conversion_factor {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}
