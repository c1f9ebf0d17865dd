//! Fast evaluation pass for Hertz/DMT summits of one radius on a tilt-free or flat shoe (the hot
//! path of large surfaces): the same quantities as the generic pass in `solver.rs`, computed
//! branch-free over blocks of 64 summits (one word of the contact bit set) with fixed per-lane
//! partial sums, so the compiler vectorises it and the result does not depend on the instruction
//! set (no fused multiply-add; the summation order is fixed by the lane layout).
//!
//! Per summit i (u, v = (x - x0)/l, (y - y0)/l; q the pose; c = 2 pi dgamma R, 0 for Hertz):
//! `z = h - (q0 + q1 u + q2 v)`, `a = sqrt(R z+)`, `P = a z+ / D - c`, `k = 3 a / (2 D)` (eq. 3, 4)
//! for members and summits touching at this pose; non-members carry nothing.

use super::{Eval, Geom, State};

/// Lanes of the partial sums (one SSE2 register per sum).
const W: usize = 2;
/// Summits per block: one word of the contact bit set.
const B: usize = 64;

/// Constants of one pass.
pub(crate) struct Kernel {
    pub q: [f64; 3],
    pub x0: f64,
    pub y0: f64,
    pub inv_ell: f64,
    pub radius: f64,
    pub inv_d: f64,
    /// One summit's adhesive pull 2 pi dgamma R (0 for Hertz) \[N\].
    pub c0: f64,
    /// Summits out of contact may join at this pose.
    pub allow_touch: bool,
    /// Contact radius above which q0 exceeds the hardness \[m\] (infinite without one).
    pub a_hard: f64,
}

#[derive(Clone, Copy)]
struct Acc {
    p: [f64; W],
    pu: [f64; W],
    pv: [f64; W],
    pabs: [f64; W],
    k: [f64; W],
    ku: [f64; W],
    kv: [f64; W],
    kuu: [f64; W],
    kuv: [f64; W],
    kvv: [f64; W],
    zc: [f64; W],
    el: [f64; W],
    n: [f64; W],
    amax: [f64; W],
    over: [f64; W],
    rel: [f64; W],
}

impl Acc {
    fn zero() -> Self {
        let z = [0.0; W];
        Self {
            p: z,
            pu: z,
            pv: z,
            pabs: z,
            k: z,
            ku: z,
            kv: z,
            kuu: z,
            kuv: z,
            kvv: z,
            zc: z,
            el: z,
            n: z,
            amax: z,
            over: z,
            rel: z,
        }
    }
}

/// Membership of a block: all members, none, or mixed (bits read per lane).
const ALL: u8 = 0;
const NONE: u8 = 1;
const MIXED: u8 = 2;

/// Accumulates one block of 64 summits; returns the number of summits touching at this pose.
/// (Indexed lanes on purpose: the fixed lane layout is what the compiler vectorises.)
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn block<const M: u8>(acc: &mut Acc, xs: &[f32; B], ys: &[f32; B], hs: &[f64; B], word: u64, k: &Kernel) -> u32 {
    let touch_zero = k.c0 != 0.0;
    let mut touches = [0u32; W];
    for grp in 0..B / W {
        for l in 0..W {
            let j = grp * W + l;
            let u = (f64::from(xs[j]) - k.x0) * k.inv_ell;
            let v = (f64::from(ys[j]) - k.y0) * k.inv_ell;
            let z = hs[j] - (k.q[0] + k.q[1] * u + k.q[2] * v);
            let mem = match M {
                ALL => true,
                NONE => false,
                _ => (word >> j) & 1 == 1,
            };
            // Touch rule of the generic pass: z >= z_in = 0, and z = 0 only with adhesion.
            let pos = z > 0.0 || (touch_zero && z == 0.0);
            let act = mem || (k.allow_touch && pos);
            touches[l] += u32::from(!mem && k.allow_touch && pos);
            let zc = if z > 0.0 { z } else { 0.0 };
            let a = (k.radius * zc).sqrt();
            let el = a * zc * k.inv_d;
            let stiff = 1.5 * a * k.inv_d;
            let (p, kk, zc, el, a, one) =
                if act { (el - k.c0, stiff, zc, el, a, 1.0) } else { (0.0, 0.0, 0.0, 0.0, 0.0, 0.0) };
            acc.p[l] += p;
            acc.pu[l] += p * u;
            acc.pv[l] += p * v;
            acc.pabs[l] += p.abs();
            acc.k[l] += kk;
            let ku = kk * u;
            let kv = kk * v;
            acc.ku[l] += ku;
            acc.kv[l] += kv;
            acc.kuu[l] += ku * u;
            acc.kuv[l] += ku * v;
            acc.kvv[l] += kv * v;
            acc.zc[l] += zc;
            acc.el[l] += el;
            acc.n[l] += one;
            acc.amax[l] = if a > acc.amax[l] { a } else { acc.amax[l] };
            acc.over[l] += if a > k.a_hard { 1.0 } else { 0.0 };
            acc.rel[l] += if mem && z < 0.0 { 1.0 } else { 0.0 };
        }
    }
    touches.iter().sum()
}

#[inline(never)]
fn block_dispatch(acc: &mut Acc, xs: &[f32; B], ys: &[f32; B], hs: &[f64; B], word: u64, k: &Kernel) -> u32 {
    match word {
        u64::MAX => block::<ALL>(acc, xs, ys, hs, word, k),
        0 => block::<NONE>(acc, xs, ys, hs, word, k),
        _ => block::<MIXED>(acc, xs, ys, hs, word, k),
    }
}

/// The pass over the summits `0..end` (every member has an index below `end`; summits at or
/// beyond it cannot touch). Touching summits are pushed to `touch` in ascending order.
pub(crate) fn evaluate(g: &Geom, st: &State, k: &Kernel, end: usize, load: f64, touch: &mut Vec<u32>) -> Eval {
    touch.clear();
    let n = g.hs.len();
    let mut acc = Acc::zero();
    let full = end.div_ceil(B).min(n / B);
    for blk in 0..full {
        let r = blk * B..(blk + 1) * B;
        let xs: &[f32; B] = g.xs[r.clone()].try_into().expect("block");
        let ys: &[f32; B] = g.ys[r.clone()].try_into().expect("block");
        let hs: &[f64; B] = g.hs[r].try_into().expect("block");
        let word = st.member[blk];
        if block_dispatch(&mut acc, xs, ys, hs, word, k) > 0 {
            push_touches(xs, ys, hs, word, blk * B, k, touch);
        }
    }
    if full * B < end {
        // Last partial block: pad with summits that cannot touch (and are no members).
        let base = full * B;
        let len = n - base;
        let (mut xs, mut ys, mut hs) = ([0.0f32; B], [0.0f32; B], [f64::MIN; B]);
        xs[..len].copy_from_slice(&g.xs[base..]);
        ys[..len].copy_from_slice(&g.ys[base..]);
        hs[..len].copy_from_slice(&g.hs[base..]);
        let word = st.member[full];
        if block_dispatch(&mut acc, &xs, &ys, &hs, word, k) > 0 {
            push_touches(&xs, &ys, &hs, word, base, k, touch);
        }
    }
    let s = |v: &[f64; W]| v.iter().sum::<f64>();
    let (p, pu, pv) = (s(&acc.p), s(&acc.pu), s(&acc.pv));
    let (kk, ku, kv, kuu, kuv, kvv) = (s(&acc.k), s(&acc.ku), s(&acc.kv), s(&acc.kuu), s(&acc.kuv), s(&acc.kvv));
    let ell = 1.0 / k.inv_ell;
    let amax = acc.amax.iter().copied().fold(0.0, f64::max);
    let mut ev = Eval {
        g: [load - p, -pu, -pv],
        h: [[kk, ku, kv], [ku, kuu, kuv], [kv, kuv, kvv]],
        force: p,
        force_abs: s(&acc.pabs),
        releases: s(&acc.rel) as usize,
        contacts: s(&acc.n) as usize,
        area: std::f64::consts::PI * k.radius * s(&acc.zc),
        elastic: s(&acc.el),
        q0_max: 1.5 * amax * k.inv_d / (std::f64::consts::PI * k.radius),
        over_limit: s(&acc.over) as usize,
        moment_x: pu * ell,
        moment_y: pv * ell,
    };
    if g.ndof == 1 {
        ev.g[1] = 0.0;
        ev.g[2] = 0.0;
        ev.h = [[kk, 0.0, 0.0], [0.0; 3], [0.0; 3]];
    }
    ev
}

#[cold]
fn push_touches(xs: &[f32; B], ys: &[f32; B], hs: &[f64; B], word: u64, base: usize, k: &Kernel, touch: &mut Vec<u32>) {
    let touch_zero = k.c0 != 0.0;
    for j in 0..B {
        if (word >> j) & 1 == 1 {
            continue;
        }
        let u = (f64::from(xs[j]) - k.x0) * k.inv_ell;
        let v = (f64::from(ys[j]) - k.y0) * k.inv_ell;
        let z = hs[j] - (k.q[0] + k.q[1] * u + k.q[2] * v);
        if z > 0.0 || (touch_zero && z == 0.0) {
            touch.push((base + j) as u32);
        }
    }
}
