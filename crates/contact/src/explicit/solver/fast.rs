//! Fast evaluation pass for Hertz/DMT summits of one radius on a tilt-free or flat shoe (the hot
//! path of large surfaces): the same quantities as the generic pass in `pass.rs`, computed
//! branch-free over blocks of 64 summits (one word of the contact bit set).
//!
//! Per summit i (u, v = (x - x0)/l, (y - y0)/l; q the pose; c = 2 pi dgamma R, 0 for Hertz):
//! `z = h - (q0 + q1 u + q2 v)`, `a = sqrt(R z+)`, `P = a z+ / D - c`, `k = 3 a / (2 D)` (eq. 3, 4)
//! for members and summits touching at this pose; non-members carry nothing.
//!
//! # Layout (why it is fast, and why it gives the same bits everywhere)
//! A block is processed in three stages, each a simple loop over the 64 summits that the compiler
//! vectorises on its own:
//! 1. map: interference, contact radius (the square roots, all independent of each other, so
//!    their latency overlaps), force, activity, the smallest |z| (how far the plane may move
//!    before any summit changes its contact state); results go to small arrays on the stack (L1);
//! 2. force sums: P, P u, P v, |P|, z+, elastic load, largest z+, summits over the hardness;
//! 3. stiffness sums: k, k u, k v, and (tilt free only) k u^2, k u v, k v^2.
//!
//! With menisci (`CAP`), stage 1 also counts the active summits without solid contact, and a
//! stage 1b between 1 and 2 gives the bridged ones (-h_m <= z < 0) their meniscus tail
//! `-f R (1 + z/h_m)` and sums their pull, number and stiffness moments; it runs only on a block
//! holding such a summit (a thin band of blocks, the summits being stored by height).
//!
//! Splitting the stages keeps each loop's accumulators in registers (one pass with all 16 sums
//! spilled them to the stack) and breaks the square-root-to-add dependency chain. Every sum has
//! `W = 4` fixed lanes (summit j adds to lane j mod 4), combined in a fixed order at the end, so
//! the summation order does not depend on the instruction set. The pass runs through
//! [`pulp::Arch::dispatch`]: on x86-64 with AVX2+FMA (checked at run time) the same code is
//! compiled for 256-bit registers, elsewhere for the baseline (SSE2, NEON). Rust never contracts
//! `a * b + c` into a fused multiply-add and the square root, f32 -> f64 conversion, comparisons
//! and selections are exact in IEEE 754, so both versions give the same bits (tested).

use super::eval::{Eval, Linear};
use super::geometry::{Geom, State};

/// Lanes of the partial sums.
const W: usize = 4;
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
    /// The interference of that contact radius, `a_hard^2 / R` \[m\] (infinite without one).
    pub z_hard: f64,
    /// Also collect what a Newton step without a pass needs ([`super::pass::Linear`]).
    pub lin: bool,
    /// Meniscus pull of a summit in contact f R (already part of `c0`), 0 when dry \[N\].
    pub cap_f: f64,
    /// Meniscus height h_m (0 when dry) \[m\]: summits with z >= -h_m carry a meniscus.
    pub hm: f64,
    /// 1 / h_m, the inverse meniscus height (0 when dry) \[1/m\].
    pub inv_hm: f64,
}

#[derive(Clone, Copy)]
struct Acc {
    p: [f64; W],
    pu: [f64; W],
    pv: [f64; W],
    pabs: [f64; W],
    zc: [f64; W],
    el: [f64; W],
    zmax: [f64; W],
    over: [f64; W],
    /// Smallest z of the summits in contact with z >= 0 (how far the plane may approach... recede
    /// before one of them releases), smallest |z| of the others (before one touches).
    gap_in: [f64; W],
    gap_out: [f64; W],
    /// Smallest |z - z_hard| of the summits in contact (hardness only).
    hgap: [f64; W],
    k: [f64; W],
    ku: [f64; W],
    kv: [f64; W],
    kuu: [f64; W],
    kuv: [f64; W],
    kvv: [f64; W],
    /// CAP only: meniscus pull of the members out of solid contact (bridged, -h_m <= z < 0), their
    /// number, and the number of active summits without solid contact (contact radius a = 0: the
    /// bridged ones, those at z = 0 and members past release; the active ones less these are the
    /// summits in solid contact).
    cap_tail: [f64; W],
    wet_out: [f64; W],
    dry_touch: [f64; W],
}

/// CAP and LIN: sums of u, v, u^2, u v, v^2 over the bridged summits (their tails' stiffness
/// moments; their number is `Acc::wet_out`), apart from [`Acc`] (which the dry pass keeps as it is).
type TailSums = [[f64; W]; 5];

impl Acc {
    fn zero() -> Self {
        let z = [0.0; W];
        let inf = [f64::INFINITY; W];
        Self {
            p: z,
            pu: z,
            pv: z,
            pabs: z,
            zc: z,
            el: z,
            zmax: z,
            over: z,
            gap_in: inf,
            gap_out: inf,
            hgap: inf,
            k: z,
            ku: z,
            kv: z,
            kuu: z,
            kuv: z,
            kvv: z,
            cap_tail: z,
            wet_out: z,
            dry_touch: z,
        }
    }
}

/// Stage-1 results of one block (reused from block to block: no zeroing per block).
struct Buf {
    us: [f64; B],
    vs: [f64; B],
    ps: [f64; B],
    zcs: [f64; B],
    as_: [f64; B],
}

/// Per-block counts: summits touching at this pose, members past release.
#[derive(Clone, Copy, Default)]
struct Counts {
    touches: u32,
    releases: u32,
}

/// Membership of a block: all members, none, or mixed (bits read per lane).
const ALL: u8 = 0;
const NONE: u8 = 1;
const MIXED: u8 = 2;

/// Accumulates one block of 64 summits (see the module docs for the three stages).
/// `TILT`: accumulate the stiffness moments (tilt-free shoe); `HARD`: count summits over the hardness.
/// (Indexed lanes on purpose: the fixed lane layout is what the compiler vectorises.)
#[allow(clippy::needless_range_loop)]
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn block<const M: u8, const TILT: bool, const HARD: bool, const LIN: bool, const CAP: bool>(
    acc: &mut Acc,
    tails: &mut TailSums,
    buf: &mut Buf,
    xs: &[f32; B],
    ys: &[f32; B],
    hs: &[f64; B],
    word: u64,
    k: &Kernel,
) -> Counts {
    let touch_zero = k.c0 != 0.0;
    let Buf { us, vs, ps, zcs, as_ } = buf;
    // Counts as f64 lanes (exact below 2^53): mixing integer lanes into the float code costs packing.
    let mut touches = [0.0f64; W];
    let mut rels = [0.0f64; W];
    let (mut gap_in, mut gap_out) = (acc.gap_in, acc.gap_out);
    // CAP only: active summits out of solid contact (contact radius 0), the test for stage 1b.
    let mut no_solid = [0.0f64; W];
    // Stage 1: map.
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
            // Touch rule of the generic pass: z >= z_in = 0, and z = 0 only with adhesion; with
            // menisci z >= z_in = -h_m (and release below -h_m).
            let pos = if CAP { z >= -k.hm } else { z > 0.0 || (touch_zero && z == 0.0) };
            let act = mem || (k.allow_touch && pos);
            touches[l] += if !mem && k.allow_touch && pos { 1.0 } else { 0.0 };
            let rel = if CAP { z < -k.hm } else { z < 0.0 };
            rels[l] += if mem && rel { 1.0 } else { 0.0 };
            if LIN {
                // (Selects, then a plain minimum: this form vectorises.)
                let za = z.abs();
                let stays = act && z >= 0.0;
                let gi = if stays { za } else { f64::INFINITY };
                // With menisci the others also change state at z = -h_m (touch, release) and a
                // bridged summit at z = 0 (solid contact): the nearer of both, either direction.
                let zo = if CAP {
                    let zh = (z + k.hm).abs();
                    if zh < za { zh } else { za }
                } else {
                    za
                };
                let go = if stays { f64::INFINITY } else { zo };
                gap_in[l] = if gi < gap_in[l] { gi } else { gap_in[l] };
                gap_out[l] = if go < gap_out[l] { go } else { gap_out[l] };
            }
            let zc = if z > 0.0 { z } else { 0.0 };
            let a = (k.radius * zc).sqrt();
            let el = a * zc * k.inv_d;
            us[j] = u;
            vs[j] = v;
            ps[j] = if act { el - k.c0 } else { 0.0 };
            zcs[j] = if act { zc } else { 0.0 };
            as_[j] = if act { a } else { 0.0 };
            if CAP {
                no_solid[l] += if act && a <= 0.0 { 1.0 } else { 0.0 };
            }
        }
    }
    acc.gap_in = gap_in;
    acc.gap_out = gap_out;
    let touches: f64 = touches.iter().sum();
    let counts = Counts { touches: touches as u32, releases: rels.iter().sum::<f64>() as u32 };
    if M == NONE && touches == 0.0 {
        // Nothing active: every term below is +0 (skipping them leaves the same bits).
        return counts;
    }
    // Stage 1b changes only active summits with z < 0 and counts those without solid contact
    // (z <= 0): a block whose active summits all have z > 0 skips it, leaving the same bits (its terms
    // would be +0 and -0).
    if CAP && no_solid.iter().sum::<f64>() > 0.0 {
        for l in 0..W {
            acc.dry_touch[l] += no_solid[l];
        }
        let (mut cap_tail, mut wet_out) = (acc.cap_tail, acc.wet_out);
        // Stage 1b (menisci): an active summit out of solid contact (z < 0) pulls with its
        // meniscus while within h_m (bridged), with nothing beyond (a member there is past
        // release, p_rel = 0). Stage 1 gave it -c0, the load at z = 0+.
        for grp in 0..B / W {
            for l in 0..W {
                let j = grp * W + l;
                // (z again, from the same u, v: the same bits as stage 1's.)
                let z = hs[j] - (k.q[0] + k.q[1] * us[j] + k.q[2] * vs[j]);
                let mem = match M {
                    ALL => true,
                    NONE => false,
                    _ => (word >> j) & 1 == 1,
                };
                let bridged = (mem || k.allow_touch) && z >= -k.hm && z < 0.0;
                let pt = -k.cap_f * (1.0 + z * k.inv_hm);
                ps[j] = if bridged {
                    pt
                } else if z < 0.0 {
                    0.0
                } else {
                    ps[j]
                };
                // Their pull and number (the summary's capillary load).
                cap_tail[l] -= if bridged { pt } else { 0.0 };
                wet_out[l] += if bridged { 1.0 } else { 0.0 };
                if LIN {
                    // The tails' stiffness moments (a tail is linear in z: -f R / h_m).
                    let (u, v) = if bridged { (us[j], vs[j]) } else { (0.0, 0.0) };
                    tails[0][l] += u;
                    tails[1][l] += v;
                    if TILT {
                        tails[2][l] += u * u;
                        tails[3][l] += u * v;
                        tails[4][l] += v * v;
                    }
                }
            }
        }
        acc.cap_tail = cap_tail;
        acc.wet_out = wet_out;
    }
    // Stage 2: force sums.
    for grp in 0..B / W {
        for l in 0..W {
            let j = grp * W + l;
            let p = ps[j];
            acc.p[l] += p;
            acc.pu[l] += p * us[j];
            acc.pv[l] += p * vs[j];
            acc.pabs[l] += p.abs();
            acc.zc[l] += zcs[j];
            acc.el[l] += as_[j] * zcs[j] * k.inv_d;
            let zc = zcs[j];
            acc.zmax[l] = if zc > acc.zmax[l] { zc } else { acc.zmax[l] };
            if HARD {
                acc.over[l] += if as_[j] > k.a_hard { 1.0 } else { 0.0 };
            }
            if LIN && HARD {
                let dh = if zc > 0.0 { (zc - k.z_hard).abs() } else { f64::INFINITY };
                acc.hgap[l] = if dh < acc.hgap[l] { dh } else { acc.hgap[l] };
            }
        }
    }
    // Stage 3: stiffness sums.
    for grp in 0..B / W {
        for l in 0..W {
            let j = grp * W + l;
            let kk = 1.5 * as_[j] * k.inv_d;
            acc.k[l] += kk;
            if TILT || LIN {
                acc.ku[l] += kk * us[j];
                acc.kv[l] += kk * vs[j];
            }
            if TILT {
                let ku = kk * us[j];
                let kv = kk * vs[j];
                acc.kuu[l] += ku * us[j];
                acc.kuv[l] += ku * vs[j];
                acc.kvv[l] += kv * vs[j];
            }
        }
    }
    counts
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn block_dispatch<const TILT: bool, const HARD: bool, const LIN: bool, const CAP: bool>(
    acc: &mut Acc,
    tails: &mut TailSums,
    buf: &mut Buf,
    xs: &[f32; B],
    ys: &[f32; B],
    hs: &[f64; B],
    word: u64,
    k: &Kernel,
) -> Counts {
    match word {
        u64::MAX => block::<ALL, TILT, HARD, LIN, CAP>(acc, tails, buf, xs, ys, hs, word, k),
        0 => block::<NONE, TILT, HARD, LIN, CAP>(acc, tails, buf, xs, ys, hs, word, k),
        _ => block::<MIXED, TILT, HARD, LIN, CAP>(acc, tails, buf, xs, ys, hs, word, k),
    }
}

/// Totals of one pass before they become an [`Eval`].
struct Totals {
    acc: Acc,
    tails: TailSums,
    contacts: usize,
    releases: usize,
    /// First and last word of the contact bit set holding a member past release.
    release_words: Option<(usize, usize)>,
}

/// The loop over the blocks `0..end`, compiled once per instruction set by `pulp` (inlined into
/// its dispatch).
#[inline(always)]
fn pass<const TILT: bool, const HARD: bool, const LIN: bool, const CAP: bool>(
    g: &Geom,
    st: &State,
    k: &Kernel,
    end: usize,
    touch: &mut Vec<u32>,
) -> Totals {
    let n = g.hs.len();
    let mut acc = Acc::zero();
    let mut tails: TailSums = [[0.0; W]; 5];
    let z = [0.0; B];
    let mut buf = Buf { us: z, vs: z, ps: z, zcs: z, as_: z };
    let mut contacts = 0usize;
    let mut releases = 0usize;
    let mut release_words: Option<(usize, usize)> = None;
    let full = end.div_ceil(B).min(n / B);
    let mut on_block = |blk: usize, c: Counts, word: u64| {
        contacts += (word.count_ones() + c.touches) as usize;
        if c.releases > 0 {
            releases += c.releases as usize;
            release_words = Some(release_words.map_or((blk, blk), |(lo, _)| (lo, blk)));
        }
    };
    for blk in 0..full {
        let r = blk * B..(blk + 1) * B;
        let xs: &[f32; B] = g.xs[r.clone()].try_into().expect("block");
        let ys: &[f32; B] = g.ys[r.clone()].try_into().expect("block");
        let hs: &[f64; B] = g.hs[r].try_into().expect("block");
        let word = st.member[blk];
        let c = block_dispatch::<TILT, HARD, LIN, CAP>(&mut acc, &mut tails, &mut buf, xs, ys, hs, word, k);
        if c.touches > 0 {
            push_touches(xs, ys, hs, word, blk * B, k, touch);
        }
        on_block(blk, c, word);
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
        let c = block_dispatch::<TILT, HARD, LIN, CAP>(&mut acc, &mut tails, &mut buf, &xs, &ys, &hs, word, k);
        if c.touches > 0 {
            push_touches(&xs, &ys, &hs, word, base, k, touch);
        }
        on_block(full, c, word);
    }
    Totals { acc, tails, contacts, releases, release_words }
}

/// The pass as a `pulp` operation: `with_simd` is inlined into the function `pulp` compiles for
/// each instruction set (a closure would be called, and compiled for the baseline only).
/// `CAP`: the menisci's pass, compiled into its own function (the dry one stays as it is).
struct PassOp<'a, const CAP: bool> {
    g: &'a Geom,
    st: &'a State,
    k: &'a Kernel,
    end: usize,
    touch: &'a mut Vec<u32>,
    tilt: bool,
    hard: bool,
}

impl<const CAP: bool> pulp::WithSimd for PassOp<'_, CAP> {
    type Output = Totals;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Totals {
        let PassOp { g, st, k, end, touch, tilt, hard } = self;
        // One instance per CAP: the menisci's pass (with linear steps, the tails' stiffness
        // moments too) is compiled apart from the dry one.
        match (tilt, hard, k.lin) {
            (true, false, false) => pass::<true, false, false, CAP>(g, st, k, end, touch),
            (true, true, false) => pass::<true, true, false, CAP>(g, st, k, end, touch),
            (false, false, false) => pass::<false, false, false, CAP>(g, st, k, end, touch),
            (false, true, false) => pass::<false, true, false, CAP>(g, st, k, end, touch),
            (true, false, true) => pass::<true, false, true, CAP>(g, st, k, end, touch),
            (true, true, true) => pass::<true, true, true, CAP>(g, st, k, end, touch),
            (false, false, true) => pass::<false, false, true, CAP>(g, st, k, end, touch),
            (false, true, true) => pass::<false, true, true, CAP>(g, st, k, end, touch),
        }
    }
}

/// The pass over the summits `0..end` (every member has an index below `end`; summits at or
/// beyond it cannot touch). Touching summits are pushed to `touch` in ascending order.
/// `arch` selects the instruction set (`pulp::Arch::new()`: the best one this machine has).
#[allow(clippy::too_many_arguments)]
pub(crate) fn evaluate_with(
    arch: pulp::Arch,
    g: &Geom,
    st: &State,
    k: &Kernel,
    end: usize,
    load: f64,
    touch: &mut Vec<u32>,
) -> Eval {
    touch.clear();
    let tilt = g.ndof > 1;
    let hard = k.a_hard.is_finite();
    let t = if k.cap_f != 0.0 {
        arch.dispatch(PassOp::<true> { g, st, k, end, touch, tilt, hard })
    } else {
        arch.dispatch(PassOp::<false> { g, st, k, end, touch, tilt, hard })
    };
    let acc = &t.acc;
    let s = |v: &[f64; W]| (v[0] + v[1]) + (v[2] + v[3]);
    let (p, pu, pv) = (s(&acc.p), s(&acc.pu), s(&acc.pv));
    let (kk, ku, kv, kuu, kuv, kvv) = (s(&acc.k), s(&acc.ku), s(&acc.kv), s(&acc.kuu), s(&acc.kuv), s(&acc.kvv));
    let ell = 1.0 / k.inv_ell;
    let zmax = acc.zmax.iter().copied().fold(0.0, f64::max);
    let min = |v: &[f64; W]| v.iter().copied().fold(f64::INFINITY, |m, x| if x < m { x } else { m });
    // Largest contact radius: sqrt is monotone, so this is the largest of the summits' radii.
    let amax = (k.radius * zmax).sqrt();
    let mut ev = Eval {
        g: [load - p, -pu, -pv],
        h: [[kk, ku, kv], [ku, kuu, kuv], [kv, kuv, kvv]],
        force: p,
        force_abs: s(&acc.pabs),
        releases: t.releases,
        contacts: t.contacts,
        area: std::f64::consts::PI * k.radius * s(&acc.zc),
        elastic: s(&acc.el),
        q0_max: 1.5 * amax * k.inv_d / (std::f64::consts::PI * k.radius),
        over_limit: s(&acc.over) as usize,
        moment_x: pu * ell,
        moment_y: pv * ell,
        release_words: Some(t.release_words.unwrap_or((1, 0))),
        // Menisci: f R at every active summit but the bridged ones (out of solid contact), which
        // pull with their tails (meaningful at an equilibrium: no member past release).
        capillary: if k.cap_f != 0.0 {
            k.cap_f * (t.contacts as f64 - s(&acc.wet_out)) + s(&acc.cap_tail)
        } else {
            0.0
        },
        solid: t.contacts - s(&acc.dry_touch) as usize,
        released: false,
        lin: k.lin.then(|| Linear {
            gap_in: min(&acc.gap_in),
            gap_out: min(&acc.gap_out),
            hard_gap: min(&acc.hgap),
            k_uv: [s(&acc.ku), s(&acc.kv)],
            tail_k: k.cap_f * k.inv_hm,
            tail: if k.cap_f != 0.0 {
                let t = &t.tails;
                [s(&acc.wet_out), s(&t[0]), s(&t[1]), s(&t[2]), s(&t[3]), s(&t[4])]
            } else {
                [0.0; 6]
            },
        }),
    };
    if !tilt {
        ev.g[1] = 0.0;
        ev.g[2] = 0.0;
        ev.h = [[kk, 0.0, 0.0], [0.0; 3], [0.0; 3]];
    }
    ev
}

/// [`evaluate_with`] on the best instruction set of this machine.
pub(crate) fn evaluate(g: &Geom, st: &State, k: &Kernel, end: usize, load: f64, touch: &mut Vec<u32>) -> Eval {
    evaluate_with(pulp::Arch::new(), g, st, k, end, load, touch)
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
        let touches = if k.cap_f != 0.0 { z >= -k.hm } else { z > 0.0 || (touch_zero && z == 0.0) };
        if touches {
            touch.push((base + j) as u32);
        }
    }
}
