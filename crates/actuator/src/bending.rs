//! Finger bending: each movable plate is a cantilever clamped at the spine that bends towards
//! the front electrode under its own electrostatic load, which narrows the gap near its tip.
//!
//! Euler-Bernoulli cantilever of total length `L_tot = L_root + l` (the root part `L_root` does
//! not overlap the electrode and carries no load), bending stiffness `EI = E t w^3 / 12`
//! (`w` in-plane finger width, `t` thickness). The overlap is cut into `m` segments; the
//! deflection follows from the cantilever influence function
//!
//! `G(s, a) = s^2 (3a - s) / (6 EI)` for `s <= a`, `a^2 (3s - a) / (6 EI)` for `s > a`
//!
//! (deflection at `s` per unit point load at `a`), and the load per unit length at a local gap
//! is the rigid-plate force of [`crate::plates::PlateArray`] divided by the overlap. The shape is
//! solved self-consistently by fixed-point iteration; if it does not converge the finger has
//! collapsed onto its electrode (finger pull-in) and the force is reported as infinite.
//! The fixed electrode fingers are taken as rigid (they are anchored and usually wider).

use serde::{Deserialize, Serialize};

use crate::error::{ActuatorError, nonnegative, positive};
use crate::plates::PlateArray;

/// Cantilever description of every movable finger.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FingerBending {
    /// Length at the finger root that does not overlap the electrode (m).
    pub root_length_m: f64,
    /// In-plane finger width `w` (m).
    pub width_m: f64,
    /// Young's modulus used for bending (Pa), plane-strain if the caller wants it.
    pub youngs_modulus_pa: f64,
}

/// Number of segments the overlap is cut into.
const SEGMENTS: usize = 24;

impl FingerBending {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ActuatorError> {
        nonnegative("finger_bending.root_length", self.root_length_m)?;
        positive("finger_bending.width", self.width_m)?;
        positive("finger_bending.youngs_modulus", self.youngs_modulus_pa)?;
        Ok(())
    }

    /// Net electrostatic force on the array (N) at rigid travel `x` (m) and voltage `V` (V),
    /// with every finger bent into its self-consistent shape; also returns the tip deflection
    /// (m). `f64::INFINITY` force if the finger collapses.
    pub fn force_and_tip_deflection(&self, plates: &PlateArray, travel_m: f64, voltage_v: f64) -> (f64, f64) {
        let l = plates.overlap_length_m;
        let ei = self.youngs_modulus_pa * plates.thickness_m * self.width_m.powi(3) / 12.0;
        let ds = l / SEGMENTS as f64;
        let s: Vec<f64> = (0..SEGMENTS).map(|j| self.root_length_m + (j as f64 + 0.5) * ds).collect();
        let tip = self.root_length_m + l;
        let influence = |si: f64, a: f64| {
            if si <= a { si * si * (3.0 * a - si) / (6.0 * ei) } else { a * a * (3.0 * si - a) / (6.0 * ei) }
        };
        let v2 = voltage_v * voltage_v;
        let per_length = |y: f64| -> f64 {
            if plates.front_gap_m - travel_m - y <= 0.0 {
                return f64::INFINITY;
            }
            // The local line load is the rigid array's at travel x + y (front gap g_f - x - y,
            // back gap g_b + x + y), per plate and unit overlap length.
            v2 * plates.line_force_per_volt2(travel_m + y)
        };
        let mut y = vec![0.0; SEGMENTS];
        let gap_scale = plates.front_gap_m - travel_m;
        for _ in 0..200 {
            let loads: Vec<f64> = y.iter().map(|&yj| per_length(yj) * ds).collect();
            if loads.iter().any(|p| !p.is_finite()) {
                return (f64::INFINITY, gap_scale);
            }
            let mut change: f64 = 0.0;
            let mut next = vec![0.0; SEGMENTS];
            for (i, yi) in next.iter_mut().enumerate() {
                *yi = s.iter().zip(&loads).map(|(&a, &p)| influence(s[i], a) * p).sum();
                change = change.max((*yi - y[i]).abs());
            }
            y = next;
            if y.iter().any(|&yi| yi >= gap_scale) {
                return (f64::INFINITY, gap_scale);
            }
            if change <= 1e-13 * gap_scale {
                let total: f64 = y.iter().map(|&yj| per_length(yj) * ds).sum();
                let tip_y: f64 =
                    s.iter().zip(y.iter().map(|&yj| per_length(yj) * ds)).map(|(&a, p)| influence(tip, a) * p).sum();
                return (f64::from(plates.plate_count) * total, tip_y);
            }
        }
        (f64::INFINITY, gap_scale)
    }
}
