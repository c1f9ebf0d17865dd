//! The evaluation pass, the contact search of every Newton step: over the height-sorted prefix of
//! summits that can touch the shoe at a pose (found by binary search) plus the members, the
//! gradient and Hessian of the potential energy ([`Eval`]); Hertz/DMT summits of one radius on a
//! tilt-free or flat shoe go to the fast pass ([`super::fast`]), every other case is the generic
//! loop here.

use std::sync::atomic::Ordering;

use super::eval::Eval;
use super::fast;
use super::geometry::{Geom, State};
use crate::explicit::laws::LawEval;

/// One pass over the summits that can touch the shoe at pose `q`: gradient and Hessian of the
/// potential energy restricted to the members plus the summits touching at `q` (collected in
/// `touch`), and the members below their release interference.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(super) fn evaluate<L: LawEval + ?Sized>(
    g: &Geom,
    law: &L,
    st: &State,
    q: &[f64; 3],
    load: f64,
    allow_touch: bool,
    lin: bool,
    touch: &mut Vec<u32>,
) -> Eval {
    touch.clear();
    let (a, b, c) = g.plane(q);
    let phi0 = g.phi_at(g.load_point.0, g.load_point.1);
    let mut ev = Eval { g: [load * phi0[0], load * phi0[1], load * phi0[2]], ..Default::default() };
    let end = match g.support {
        Some(k) => k,
        None => {
            // Lowest point of the plane over the apparent area, minus the longest reach of the law.
            let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
            let thr = wmin + law.z_min();
            g.hs.partition_point(|&h| h >= thr).max(st.bound)
        }
    };
    g.passes.fetch_add(1, Ordering::Relaxed);
    if let (Some((x0, y0, inv_ell)), Some((radius, inv_d, c0))) = (g.uv, law.uniform_hertz_dmt()) {
        let a_hard = g.hardness * std::f64::consts::PI * radius / (1.5 * inv_d);
        let z_hard = a_hard * a_hard / radius;
        let lin = lin && g.shortcuts;
        let (cap_f, hm, inv_hm) = law.fast_meniscus().unwrap_or((0.0, 0.0, 0.0));
        let k = fast::Kernel {
            q: *q,
            x0,
            y0,
            inv_ell,
            radius,
            inv_d,
            c0,
            allow_touch,
            a_hard,
            z_hard,
            lin,
            cap_f,
            hm,
            inv_hm,
        };
        let mut ev = fast::evaluate(g, st, &k, end, load, touch);
        // The pass scans whole blocks of 64; a summit beyond them lies below the threshold
        // (h < w_min: DMT/Hertz reach nothing below the plane), so its |z| >= w_min - h.
        let scanned = (end.div_ceil(64) * 64).min(g.hs.len());
        g.scanned.fetch_add(scanned as u64, Ordering::Relaxed);
        if let (Some(lin), Some(&h_next)) = (ev.lin.as_mut(), g.hs.get(scanned)) {
            let wmin = a + (b * g.length).min(0.0) + (c * g.width).min(0.0);
            // (With menisci the summits beyond lie below -h_m: their distance to it.)
            let tail = if k.cap_f != 0.0 { wmin - k.hm - h_next } else { wmin - h_next };
            lin.gap_out = if tail > 0.0 { lin.gap_out.min(tail) } else { 0.0 };
        }
        return ev;
    }
    g.scanned.fetch_add(end as u64, Ordering::Relaxed);
    let bs = &g.basis;
    let (mut h00, mut h01, mut h02, mut h11, mut h12, mut h22) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let (mut g0, mut g1, mut g2) = (0.0, 0.0, 0.0);
    let (mut area, mut elastic, mut q0_max, mut over, mut mx, mut my) = (0.0, 0.0, 0.0f64, 0usize, 0.0, 0.0);
    for i in 0..end {
        let (x, y) = (f64::from(g.xs[i]), f64::from(g.ys[i]));
        let z = g.hs[i] - (a + b * x + c * y);
        let member = st.is_member(i);
        let on_branch = if member {
            if z < law.z_rel(i) {
                ev.releases += 1;
                false
            } else {
                true
            }
        } else if allow_touch && z >= law.z_in(i) && (z > 0.0 || law.z_in(i) < 0.0 || law.p_rel(i) != 0.0) {
            touch.push(i as u32);
            true
        } else {
            continue;
        };
        let (p, k) = if on_branch {
            let r = law.contact(i, z);
            ev.capillary += law.capillary_n(i, z);
            ev.solid += usize::from(r.radius > 0.0);
            area += r.radius * r.radius;
            elastic += r.elastic_n;
            q0_max = q0_max.max(r.q0);
            over += usize::from(r.q0 > g.hardness);
            (r.load_n, r.stiffness)
        } else {
            (law.p_rel(i), 0.0)
        };
        mx += p * (x - g.load_point.0);
        my += p * (y - g.load_point.1);
        ev.contacts += 1;
        ev.force += p;
        ev.force_abs += p.abs();
        let f0 = bs[0][0] + bs[0][1] * x + bs[0][2] * y;
        let f1 = bs[1][0] + bs[1][1] * x + bs[1][2] * y;
        let f2 = bs[2][0] + bs[2][1] * x + bs[2][2] * y;
        g0 += p * f0;
        g1 += p * f1;
        g2 += p * f2;
        h00 += k * f0 * f0;
        h01 += k * f0 * f1;
        h02 += k * f0 * f2;
        h11 += k * f1 * f1;
        h12 += k * f1 * f2;
        h22 += k * f2 * f2;
    }
    ev.g[0] -= g0;
    ev.g[1] -= g1;
    ev.g[2] -= g2;
    ev.h = [[h00, h01, h02], [h01, h11, h12], [h02, h12, h22]];
    ev.area = std::f64::consts::PI * area;
    ev.elastic = elastic;
    ev.q0_max = q0_max;
    ev.over_limit = over;
    ev.moment_x = mx;
    ev.moment_y = my;
    ev
}
