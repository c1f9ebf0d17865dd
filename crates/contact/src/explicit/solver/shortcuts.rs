//! The two shortcuts of the Newton iteration ([`super::ExplicitSolver::set_shortcuts`]): the first
//! step of a solve extrapolated from the last three equilibria ([`predictor`]) and the last step
//! applied by linearisation without a confirming pass ([`linear_step`]).

use super::eval::{Eval, Linear};
use super::geometry::{Geom, State, interference};
use crate::explicit::laws::LawEval;

/// Pose predicted for `load` by quadratic extrapolation of the last three equilibria along the
/// load path (Lagrange in the load), when the solver stands at the last of them and the loads
/// run monotonically in nearly even steps towards `load`; None otherwise.
pub(super) fn predictor(st: &State, load: f64) -> Option<[f64; 3]> {
    if st.history_len < 3 {
        return None;
    }
    let [(l1, q1), (l2, q2), (l3, q3)] = st.history;
    if q3 != st.q {
        return None;
    }
    let (s1, s2, s3) = (l2 - l1, l3 - l2, load - l3);
    // Same direction, steps within a factor 2 of each other.
    let even = |a: f64, b: f64| a * b > 0.0 && (0.5..=2.0).contains(&(a / b));
    if !(even(s1, s2) && even(s2, s3)) {
        return None;
    }
    let w1 = (load - l2) * (load - l3) / ((l1 - l2) * (l1 - l3));
    let w2 = (load - l1) * (load - l3) / ((l2 - l1) * (l2 - l3));
    let w3 = (load - l1) * (load - l2) / ((l3 - l1) * (l3 - l2));
    Some([0, 1, 2].map(|j| w1 * q1[j] + w2 * q2[j] + w3 * q3[j]))
}

/// Applies the Newton step `dq` (plane movement `mv` over the apparent area) without a pass over
/// the summits when that is exact to within half the tolerance `tol`, and returns whether it did.
///
/// The last evaluation `ev` (a fast pass at the current pose with its statistics, the contact set
/// consistent: no member past release) knows the smallest z of the contacts (`gap_in`), the
/// smallest |z| of all other summits (`gap_out`) and of |z - z_hard| of the contacts. If z falls
/// nowhere by more than `gap_in / 2`, rises nowhere by `gap_out` and moves by less than the
/// hardness gap (the plane's change is linear: its extremes are at the corners), no summit
/// touches, releases or crosses the hardness limit, so the contact set and every count stay; each
/// contact's force changes by `k dz + 1/2 P''(xi) dz^2` with |dz| <= m and, for Hertz/DMT,
/// `P'' = 3/4 R^1/2 / (D xi^1/2)`, `xi >= gap_in - fall`. The gradient after the step is therefore
/// `g + H dq` (exact linearisation, the sums of `ev`) up to at most
/// `1/2 m^2 n P''(gap_in - fall) max|phi_j|` per row (n contacts). When that bound plus
/// `|g + H dq|` is below `tol / 2` the step is applied: force, elastic load and moments by
/// `-H dq`, the real area exactly (`pi R sum z+` is linear in the pose for a fixed contact set; the
/// set keeps its members' coordinate sums), the largest pressure from the largest interference
/// rescanned at the new pose. The residuals of such a result are the linearised ones; the true
/// ones differ by at most the bound. It saves the pass that only confirmed the last Newton step
/// (one of three per load point on large surfaces).
pub(super) fn linear_step<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &mut State,
    ev: &mut Eval,
    dq: &[f64; 3],
    mv: f64,
    tol: f64,
) -> bool {
    let (Some(lin), Some((radius, inv_d, _)), Some((x0, y0, inv_ell))) = (ev.lin, law.uniform_hertz_dmt(), g.uv) else {
        return false;
    };
    if ev.releases != 0 {
        return false;
    }
    // Largest fall and rise of z (the plane's movement at the corners: it is linear), with room
    // for the rounding of z (a few ulp of the heights and the plane).
    let n_summits = g.hs.len();
    let magnitude = g.hs[0].abs() + g.hs[n_summits - 1].abs() + st.q.iter().map(|v| v.abs()).sum::<f64>();
    let slack = 1e-13 * magnitude;
    let (a, b, c) = g.plane(dq);
    let (mut fall, mut rise) = (0.0f64, 0.0f64);
    for (x, y) in [(0.0, 0.0), (g.length, 0.0), (0.0, g.width), (g.length, g.width)] {
        let dz = -(a + b * x + c * y);
        fall = fall.max(-dz);
        rise = rise.max(dz);
    }
    let (fall, rise) = (fall * (1.0 + 1e-9) + slack, rise * (1.0 + 1e-9) + slack);
    let m = mv.max(fall).max(rise) * (1.0 + 1e-9) + slack;
    // No contact releases (and the remainder below has xi >= gap_in / 2), none touches, none
    // crosses the hardness limit. With menisci the others' gaps (to 0 and -h_m) hold either way.
    let wet = lin.tail_k != 0.0;
    let out_move = if wet { fall.max(rise) } else { rise };
    if !(lin.gap_in > 2.0 * fall && lin.gap_out > out_move && lin.hard_gap > m) {
        return false;
    }
    let nd = g.ndof;
    let mut gl = ev.g;
    for (gj, hj) in gl.iter_mut().zip(&ev.h).take(nd) {
        *gj += hj.iter().zip(dq).take(nd).map(|(h, d)| h * d).sum::<f64>();
    }
    // Menisci: the bridged summits' tails, exactly linear in z (stiffness -f R / h_m each), which
    // the Hessian leaves out: their change of the gradient, force and moments.
    let [tn, tu, tv, tuu, tuv, tvv] = lin.tail;
    let tk = lin.tail_k;
    let th = [[-tk * tn, -tk * tu, -tk * tv], [-tk * tu, -tk * tuu, -tk * tuv], [-tk * tv, -tk * tuv, -tk * tvv]];
    if wet {
        for (gj, hj) in gl.iter_mut().zip(&th).take(nd) {
            *gj += hj.iter().zip(dq).take(nd).map(|(h, d)| h * d).sum::<f64>();
        }
    }
    // Every contact has z > 0 here (|z| >= gap > 0 and no member is past release); with menisci
    // n also counts the bridged summits, whose tails are linear (an upper bound).
    let n = ev.contacts as f64;
    let rem = 0.5 * m * m * n * 0.75 * radius.sqrt() * inv_d / (lin.gap_in - fall).sqrt();
    let phi_max = [1.0, x0.abs().max((g.length - x0).abs()) * inv_ell, y0.abs().max((g.width - y0).abs()) * inv_ell];
    let worst =
        (0..nd).map(|j| gl[j].abs() + rem * phi_max[j]).fold(0.0f64, |m, v| if v > m || v.is_nan() { v } else { m });
    if worst.is_nan() || worst > 0.5 * tol {
        return false;
    }
    let [d0, d1, d2] = *dq;
    let (k, [ku, kv]) = (ev.h[0][0], lin.k_uv);
    let (kuu, kuv, kvv) = (ev.h[1][1], ev.h[1][2], ev.h[2][2]);
    let dp = -(k * d0 + ku * d1 + kv * d2);
    let dpu = -(ku * d0 + kuu * d1 + kuv * d2);
    let dpv = -(kv * d0 + kuv * d1 + kvv * d2);
    let ell = 1.0 / inv_ell;
    ev.g = gl;
    if wet {
        // The tails' change (only d0 on a flat shoe: d1 = d2 = 0 there).
        let dpt = -(th[0][0] * d0 + th[0][1] * d1 + th[0][2] * d2);
        let dptu = -(th[1][0] * d0 + th[1][1] * d1 + th[1][2] * d2);
        let dptv = -(th[2][0] * d0 + th[2][1] * d1 + th[2][2] * d2);
        ev.force += dp + dpt;
        ev.elastic += dp;
        ev.capillary -= dpt;
        ev.moment_x += (dpu + dptu) * ell;
        ev.moment_y += (dpv + dptv) * ell;
        // Area over the summits in solid contact: the members but the bridged ones.
        let (su, sv) = (st.member_dx * inv_ell - tu, st.member_dy * inv_ell - tv);
        ev.area -= std::f64::consts::PI * radius * ((n - tn) * d0 + su * d1 + sv * d2);
    } else {
        ev.force += dp;
        ev.elastic += dp;
        // (sum |P_i| is only the tolerance's scale: it moves by at most sum k m, relative ~1e-7 here.)
        ev.moment_x += dpu * ell;
        ev.moment_y += dpv * ell;
        // Area pi R sum z+ over the contacts (all members, all with z > 0): linear in the pose, with
        // the members' coordinate sums kept by the contact set.
        let (su, sv) = (st.member_dx * inv_ell, st.member_dy * inv_ell);
        ev.area -= std::f64::consts::PI * radius * (n * d0 + su * d1 + sv * d2);
    }
    ev.lin =
        Some(Linear { gap_in: lin.gap_in - fall, gap_out: lin.gap_out - out_move, hard_gap: lin.hard_gap - m, ..lin });
    st.q = [st.q[0] + d0, st.q[1] + d1, st.q[2] + d2];
    // Largest interference at the new pose, exactly as a pass computes it: z_i <= h_i - w_min and
    // the heights descend, so only the first few summits can hold it.
    let (a, b, c) = g.plane(&st.q);
    let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
    let mut zmax = 0.0f64;
    for i in 0..n_summits {
        if g.hs[i] - wmin <= zmax {
            break;
        }
        if st.is_member(i) {
            zmax = zmax.max(interference(g, law, &st.q, i));
        }
    }
    ev.q0_max = 1.5 * (radius * zmax).sqrt() * inv_d / (std::f64::consts::PI * radius);
    true
}
