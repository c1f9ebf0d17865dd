//! The Newton direction of the exact-Hessian phase (the second phase of [`super::newton::iterate`]):
//! the Hessian of the exact forces by central differences of the gradient.

use nalgebra::Matrix3;

use super::direction::newton_ldlt;
use super::eval::Eval;
use super::geometry::{Geom, State};
use super::pass::evaluate;
use crate::explicit::laws::LawEval;

/// Hessian of the exact forces at `st.q` on the used degrees of freedom by central differences
/// of the gradient (step `h` in each pose coordinate; members only, as at the current pose), and
/// its Newton direction if it is positive definite ([`newton_ldlt`]); otherwise Newton along its
/// directions of positive curvature and a long step down the energy (to be capped by the trust
/// radius) along those of negative curvature, and of none where a force acts along them (`tol`:
/// the force tolerance). None if the differences are not finite.
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
pub(super) fn exact_newton_direction<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &State,
    touch: &mut Vec<u32>,
    load: f64,
    ev: &Eval,
    h: f64,
    tol: f64,
) -> Option<[f64; 3]> {
    let nd = g.ndof;
    let mut hs = [[0.0f64; 3]; 3];
    for j in 0..nd {
        let (mut qp, mut qm) = (st.q, st.q);
        qp[j] += h;
        qm[j] -= h;
        let ep = evaluate(g, law, st, &qp, load, false, false, touch);
        let em = evaluate(g, law, st, &qm, load, false, false, touch);
        let step = qp[j] - qm[j];
        for i in 0..nd {
            hs[i][j] = (ep.g[i] - em.g[i]) / step;
        }
    }
    touch.clear();
    for i in 0..nd {
        for j in 0..i {
            let m = 0.5 * (hs[i][j] + hs[j][i]);
            hs[i][j] = m;
            hs[j][i] = m;
        }
    }
    if let Some(d) = newton_ldlt(&hs, &ev.g, nd) {
        return Some(d);
    }
    // Not positive definite: Newton on the curvature directions (eigenvalue > 1e-8 of the
    // largest magnitude), and down the energy along the others (negative or no curvature: the
    // energy falls without bound there, so a long step, capped by the trust radius).
    // (Unused degrees of freedom padded with the largest used diagonal: their own eigenvectors.)
    let mut m = Matrix3::zeros();
    let mut diag_abs = 0.0f64;
    for i in 0..nd {
        for j in 0..nd {
            m[(i, j)] = hs[i][j];
        }
        diag_abs = diag_abs.max(hs[i][i].abs());
    }
    for j in nd..3 {
        m[(j, j)] = if diag_abs > 0.0 { diag_abs } else { 1.0 };
    }
    let eig = m.symmetric_eigen();
    let lam_abs = eig.eigenvalues.iter().take(3).fold(0.0f64, |a, &b| a.max(b.abs()));
    if !(lam_abs.is_finite() && lam_abs > 0.0) {
        return None;
    }
    let gv = nalgebra::Vector3::new(ev.g[0], ev.g[1], ev.g[2]);
    let mut d = nalgebra::Vector3::zeros();
    for k in 0..3 {
        let v = eig.eigenvectors.column(k);
        let (gk, lam) = (v.dot(&gv), eig.eigenvalues[k]);
        if lam > 1e-8 * lam_abs {
            d -= v * (gk / lam);
        } else if lam < -1e-8 * lam_abs || gk.abs() > 0.1 * tol {
            // (A direction of no curvature without a force along it, e.g. the tilt of a shoe on
            // one summit under its load point, is neutral: no step.)
            let sense = if gk > 0.0 { -1.0 } else { 1.0 };
            d += v * (sense * 1e3 * st.tau.max(1e-300));
        }
    }
    for j in nd..3 {
        d[j] = 0.0;
    }
    let out = [d[0], d[1], d[2]];
    out.iter().all(|x| x.is_finite()).then_some(out)
}
