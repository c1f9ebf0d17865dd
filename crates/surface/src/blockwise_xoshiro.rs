//! Version 2 of the summit generator (`surface.generator: 2`): block-parallel xoshiro256++ streams
//! drawing the heights already in descending order. The same random field as version 1
//! (Poisson or jittered-grid positions, Gaussian or exponential heights, fixed or lognormal radii),
//! drawn from another random stream, about twice as fast, and block-wise so that blocks can be
//! drawn on several threads with the same bytes as on one.
//!
//! # Random streams
//!
//! Every block of summits has its own xoshiro256++ generator ([`Xoshiro256pp`], a portable
//! 64-bit generator with 256 bits of state), seeded by SplitMix64 from the scenario's seed, the
//! quantity (count, height groups, heights, positions, radii, second face) and the block number.
//! A block's draws do not depend on any other block or on the thread that draws it.
//!
//! # Heights in descending order without a sort
//!
//! The solver wants the summits in descending height (its search structure). Version 1 draws the
//! heights and sorts them; version 2 draws them already in order. The exceedance probability
//! `q = P(X > x)` of the height law is cut into `M` equal bins, bin `b` holding the heights with
//! `q` in `[b/M, (b+1)/M)`, i.e. `x` in `[U((b+1)/M), U(b/M)]` with `U` the upper quantile
//! function. The numbers of summits in the bins are multinomial(n; 1/M, ..., 1/M): the bins come in
//! groups of `K` (a power of two), the group counts are drawn by conditional binomials and, inside
//! a group, each summit picks its bin from the top bits of one 64-bit draw (exactly uniform). In
//! each bin the heights are drawn from the law restricted to the bin: the two outermost bins by
//! exact tail samplers (Marsaglia's normal tail; the exponential's memoryless tail), the others by
//! rejection from the uniform law on the bin, accepting `x` with probability
//! `f(x) / f(m)` (`m` the bin's point nearest the mode), which is near 1 for the narrow inner
//! bins. A bin then holds about 8-16 heights, put in descending order by insertion. So the heights
//! are `n` independent draws of the law, listed in descending order: the same random field as a
//! sort of unordered draws.
//!
//! The normal bin edges are the quantiles of P. J. Acklam's rational approximation refined by one
//! Halley step with `erfc` (relative error near 1e-15); the exponential's are `ln(M / b)`.
//!
//! # What is sequential
//!
//! The summit count (Poisson), the group counts, and the jittered grid's shuffle (one
//! Fisher-Yates pass over all summits) are drawn by one generator each; everything else is
//! block-wise and drawn in parallel (rayon) when there are several blocks.

use rand::{Rng, RngCore};
use rand_distr::{Binomial, Distribution, Exp1, LogNormal, Poisson, StandardNormal};
use rayon::prelude::*;

use crate::face::{FaceParams, HeightDistribution, Layout, MAX_SUMMITS, Placement, RadiusDistribution};
use crate::{Radii, Surface, SurfaceError};

/// The xoshiro256++ generator of Blackman and Vigna (2019): 256 bits of state, period 2^256 - 1,
/// passes BigCrush and PractRand; about 1 ns per 64-bit output.
#[derive(Debug, Clone)]
pub struct Xoshiro256pp {
    s: [u64; 4],
}

/// One step of SplitMix64 (Steele, Lea and Flood 2014), the seeding function xoshiro's authors
/// recommend: a bijection of the state increment, so distinct inputs give distinct outputs.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Xoshiro256pp {
    /// The generator of block `block` of quantity `stream` for `seed`: SplitMix64 of the seed's
    /// SplitMix64 hash xor (stream << 48 | block), so for one seed every (stream, block) with
    /// block < 2^48 has its own state.
    pub fn for_block(seed: u64, stream: u64, block: u64) -> Self {
        let mut h = seed;
        let mut st = splitmix64(&mut h) ^ (stream << 48 | (block & ((1 << 48) - 1)));
        let s = [splitmix64(&mut st), splitmix64(&mut st), splitmix64(&mut st), splitmix64(&mut st)];
        Self { s }
    }
}

impl RngCore for Xoshiro256pp {
    #[inline]
    fn next_u64(&mut self) -> u64 {
        let s = &mut self.s;
        let result = s[0].wrapping_add(s[3]).rotate_left(23).wrapping_add(s[0]);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }
    #[inline]
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        for chunk in dst.chunks_mut(8) {
            let v = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&v[..chunk.len()]);
        }
    }
}

/// Uniform on [0, 1) from the top 53 bits.
#[inline]
fn unit(r: &mut Xoshiro256pp) -> f64 {
    (r.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Uniform on (0, 1] from the top 53 bits (for logarithms).
#[inline]
fn unit_open0(r: &mut Xoshiro256pp) -> f64 {
    ((r.next_u64() >> 11) + 1) as f64 * (1.0 / (1u64 << 53) as f64)
}

const STREAM_COUNT: u64 = 0;
const STREAM_GROUPS: u64 = 1;
const STREAM_HEIGHTS: u64 = 2;
const STREAM_POSITIONS: u64 = 3;
const STREAM_RADII: u64 = 4;
const STREAM_SECOND_HEIGHTS: u64 = 5;
const STREAM_SECOND_RADII: u64 = 6;

/// Summits per block of positions, radii and unordered heights.
const BLOCK: usize = 1 << 16;
/// Bins per height group at most (a group holds about `BLOCK` summits).
const GROUP_BINS_LOG2: u32 = 12;
/// A bin edge is computed as a quantile at least every this many edges (the others by a Taylor
/// step from the previous edge, [`Law::next_edge`]).
const EXACT_EDGE_EVERY: usize = 32;
/// Mean summits per height bin at least (up to twice this).
const BIN_MEAN: usize = 8;

/// Inverse of the standard normal distribution function for p in (0, 1): Acklam's rational
/// approximation (relative error 1.15e-9) refined by one Halley step with `erfc`.
fn normal_quantile(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] =
        [7.784_695_709_041_462e-3, 3.224_671_290_700_398e-1, 2.445_134_137_142_996, 3.754_408_661_907_416];
    let tail = |q: f64| {
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    let x = if p < 0.02425 {
        tail((-2.0 * p.ln()).sqrt())
    } else if p > 1.0 - 0.02425 {
        -tail((-2.0 * (1.0 - p).ln()).sqrt())
    } else {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    };
    let e = 0.5 * libm::erfc(-x / std::f64::consts::SQRT_2) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (0.5 * x * x).exp();
    x - u / (1.0 + 0.5 * x * u)
}

/// Standard height law of a face: X with mean 0 (Gaussian) or E ~ Exp(1) (exponential, shifted
/// to sigma (E - 1) afterwards).
#[derive(Clone, Copy)]
enum Law {
    Normal,
    Exponential,
}

impl Law {
    fn of(d: HeightDistribution) -> Self {
        match d {
            HeightDistribution::Gaussian => Law::Normal,
            HeightDistribution::Exponential => Law::Exponential,
        }
    }

    /// Upper quantile U(k / m): the x with P(X > x) = k / m, for 0 < k < m.
    fn upper_quantile(self, k: usize, m: usize) -> f64 {
        match self {
            // U(q) = -Phi^-1(q); for q > 1/2 through 1 - q = (m - k) / m, exact in the lower tail.
            Law::Normal if 2 * k <= m => -normal_quantile(k as f64 / m as f64),
            Law::Normal => normal_quantile((m - k) as f64 / m as f64),
            Law::Exponential => (m as f64 / k as f64).ln(),
        }
    }

    /// The next bin edge below `x = U(q)`, `U(q + h)`, by the Taylor series of the normal
    /// quantile function Q = Phi^-1 in p = 1 - q to fourth order (Q' = 1/phi, Q'' = x/phi^2,
    /// Q^(3) = (1 + 2x^2)/phi^3, Q^(4) = x(7 + 6x^2)/phi^4; with d = h/phi(x),
    /// U(q + h) = x - d + x d^2/2 - (1 + 2x^2) d^3/6 + x(7 + 6x^2) d^4/24), when the first omitted
    /// term, (7 + 46x^2 + 24x^4) d^5/120, is below 1e-18 (well under the rounding of x); `None`
    /// (compute the quantile) otherwise and for the exponential law.
    #[inline]
    fn next_edge(self, x: f64, h: f64) -> Option<f64> {
        match self {
            Law::Normal => {
                let x2 = x * x;
                let d = h * (2.0 * std::f64::consts::PI).sqrt() * (0.5 * x2).exp();
                let d2 = d * d;
                let omitted = (7.0 + x2 * (46.0 + 24.0 * x2)) * d2 * d2 * d * (1.0 / 120.0);
                (omitted < 1e-18).then(|| {
                    x - d + x * d2 * 0.5 - (1.0 + 2.0 * x2) * d2 * d * (1.0 / 6.0)
                        + x * (7.0 + 6.0 * x2) * d2 * d2 * (1.0 / 24.0)
                })
            }
            Law::Exponential => None,
        }
    }

    /// Lower end of the support.
    fn support_min(self) -> f64 {
        match self {
            Law::Normal => f64::NEG_INFINITY,
            Law::Exponential => 0.0,
        }
    }

    /// One draw of X given X > a (the top bin, a >= 0 for the normal law since m >= 2).
    fn upper_tail(self, r: &mut Xoshiro256pp, a: f64) -> f64 {
        match self {
            Law::Normal => loop {
                // Marsaglia (1964): exact for a > 0.
                let x = -unit_open0(r).ln() / a;
                let y = -unit_open0(r).ln();
                if 2.0 * y >= x * x {
                    break a + x;
                }
            },
            Law::Exponential => a - unit_open0(r).ln(),
        }
    }

    /// One draw of X given lo <= X <= hi (finite), by rejection from the uniform law on the bin.
    #[inline]
    fn in_bin(self, r: &mut Xoshiro256pp, lo: f64, hi: f64) -> f64 {
        let m = match self {
            Law::Normal => 0.0f64.clamp(lo, hi),
            Law::Exponential => lo,
        };
        loop {
            let bits = r.next_u64();
            let x = lo + (hi - lo) * ((bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64));
            // log f(m) - log f(x) >= 0
            let t = match self {
                Law::Normal => 0.5 * (x * x - m * m),
                Law::Exponential => x - m,
            };
            // The acceptance draw u = (c + v) / 2048 is uniform on [0, 1): its coarse part c is
            // the 11 bits x left unused, v a fresh uniform drawn only when c cannot decide.
            // exp(-t) >= 1 - t: almost every draw of a narrow bin is accepted on c alone.
            let coarse = (bits & 2047) as f64;
            if (coarse + 1.0) * (1.0 / 2048.0) <= 1.0 - t {
                break x;
            }
            let u = (coarse + unit(r)) * (1.0 / 2048.0);
            if u < (-t).exp() {
                break x;
            }
        }
    }

    /// An unordered draw of X.
    fn draw(self, r: &mut Xoshiro256pp) -> f64 {
        match self {
            Law::Normal => StandardNormal.sample(r),
            Law::Exponential => Exp1.sample(r),
        }
    }
}

fn to_height(law: Law, sd: f64, x: f64) -> f64 {
    match law {
        Law::Normal => sd * x,
        Law::Exponential => sd * (x - 1.0),
    }
}

/// `n` heights of `law` scaled by `sd`, in descending order (module docs).
fn sorted_heights(seed: u64, law: Law, sd: f64, n: usize) -> Vec<f64> {
    let mut out = vec![0.0f64; n];
    if n == 0 {
        return out;
    }
    // Bins: M = groups * 2^bins_log2, about BIN_MEAN..2 BIN_MEAN summits each, at least 4 so that
    // the outer bins of the normal law start away from 0 (|U(1/4)| = 0.674: the tail sampler
    // divides by its start).
    let bins_total_log2 = (n / BIN_MEAN).max(4).ilog2();
    let bins_log2 = bins_total_log2.min(GROUP_BINS_LOG2);
    let groups = 1usize << (bins_total_log2 - bins_log2);
    let k_bins = 1usize << bins_log2;
    let m = groups * k_bins;
    // Group counts: multinomial by conditional binomials.
    let mut r = Xoshiro256pp::for_block(seed, STREAM_GROUPS, 0);
    let mut counts = Vec::with_capacity(groups);
    let mut left = n as u64;
    for g in 0..groups {
        let c = if g + 1 == groups {
            left
        } else {
            Binomial::new(left, 1.0 / (groups - g) as f64).map_or(0, |b| b.sample(&mut r))
        };
        counts.push(c as usize);
        left -= c;
    }
    let mut chunks = Vec::with_capacity(groups);
    let mut rest: &mut [f64] = &mut out;
    for &c in &counts {
        let (head, tail) = rest.split_at_mut(c);
        chunks.push(head);
        rest = tail;
    }
    let fill = |(g, chunk): (usize, &mut [f64])| {
        let mut r = Xoshiro256pp::for_block(seed, STREAM_HEIGHTS, g as u64);
        let mut per_bin = vec![0u32; k_bins];
        let mut scratch = Vec::with_capacity(4 * BIN_MEAN);
        for _ in 0..chunk.len() {
            per_bin[(r.next_u64() >> (64 - bins_log2)) as usize] += 1;
        }
        let b0 = g * k_bins;
        let edge = |b: usize| {
            if b == 0 {
                f64::INFINITY
            } else if b == m {
                law.support_min()
            } else {
                law.upper_quantile(b, m)
            }
        };
        let mut hi = edge(b0);
        let mut pos = 0;
        let h = 1.0 / m as f64;
        let mut steps = 0;
        for (j, &c) in per_bin.iter().enumerate() {
            let b = b0 + j + 1;
            // Every EXACT_EDGE_EVERY-th edge is a quantile, the ones between Taylor steps from it.
            let stepped = if b < m && hi.is_finite() && steps < EXACT_EDGE_EVERY { law.next_edge(hi, h) } else { None };
            let lo = match stepped {
                Some(x) => {
                    steps += 1;
                    x
                }
                None => {
                    steps = 0;
                    edge(b)
                }
            };
            let c = c as usize;
            let bin = &mut chunk[pos..pos + c];
            scratch.clear();
            for _ in 0..c {
                let x = if hi.is_infinite() {
                    law.upper_tail(&mut r, lo)
                } else if lo.is_infinite() {
                    // Bottom bin of the normal law: by symmetry, minus a draw above -lo.
                    -law.upper_tail(&mut r, -hi)
                } else {
                    law.in_bin(&mut r, lo, hi)
                };
                scratch.push(to_height(law, sd, x));
            }
            place_descending(&scratch, bin);
            pos += c;
            hi = lo;
        }
    };
    if groups > 1 && parallel() {
        chunks.into_par_iter().enumerate().for_each(fill);
    } else {
        chunks.into_iter().enumerate().for_each(fill);
    }
    out
}

/// Writes `src` into `dst` in descending order: each value goes to its rank (the number of
/// larger values, plus the equal ones before it), counted without branches, which beats an
/// insertion sort's mispredicted branches on the 8-16 values of a bin; long bins (rare) use the
/// comparison sort.
fn place_descending(src: &[f64], dst: &mut [f64]) {
    if src.len() > 64 {
        dst.copy_from_slice(src);
        dst.sort_unstable_by(|a, b| b.total_cmp(a));
        return;
    }
    // Without ties the ranks are 0..c, summing to c (c - 1) / 2; tied values share a rank, so a
    // smaller sum reveals a tie and the comparison sort places the values instead.
    let mut rank_sum = 0;
    for &x in src {
        let larger: usize = src.iter().map(|&y| usize::from(y > x)).sum();
        dst[larger] = x;
        rank_sum += larger;
    }
    if rank_sum != src.len() * src.len().saturating_sub(1) / 2 {
        dst.copy_from_slice(src);
        dst.sort_unstable_by(|a, b| b.total_cmp(a));
    }
}

/// True when rayon has more than one thread: with one, the blocks run on the calling thread (the
/// same bytes, without handing the work to the pool's thread and waiting for it).
fn parallel() -> bool {
    rayon::current_num_threads() > 1
}

/// Fills `out` block by block (in parallel when there are several blocks) with `f(rng, slot)`.
fn blockwise<T: Send>(out: &mut [T], seed: u64, stream: u64, f: impl Fn(&mut Xoshiro256pp, &mut T) + Sync) {
    let run = |(k, chunk): (usize, &mut [T])| {
        let mut r = Xoshiro256pp::for_block(seed, stream, k as u64);
        for v in chunk {
            f(&mut r, v);
        }
    };
    if out.len() > BLOCK && parallel() {
        out.par_chunks_mut(BLOCK).enumerate().for_each(run);
    } else {
        out.chunks_mut(BLOCK).enumerate().for_each(run);
    }
}

/// [`blockwise`] over two arrays of the same length, `f(rng, index, a, b)`.
fn blockwise2<T: Send, U: Send>(
    a: &mut [T],
    b: &mut [U],
    seed: u64,
    stream: u64,
    f: impl Fn(&mut Xoshiro256pp, usize, &mut T, &mut U) + Sync,
) {
    let run = |(k, (ca, cb)): (usize, (&mut [T], &mut [U]))| {
        let mut r = Xoshiro256pp::for_block(seed, stream, k as u64);
        for (i, (x, y)) in ca.iter_mut().zip(cb).enumerate() {
            f(&mut r, k * BLOCK + i, x, y);
        }
    };
    if a.len() > BLOCK && parallel() {
        a.par_chunks_mut(BLOCK).zip(b.par_chunks_mut(BLOCK)).enumerate().for_each(run);
    } else {
        a.chunks_mut(BLOCK).zip(b.chunks_mut(BLOCK)).enumerate().for_each(run);
    }
}

/// Summit count and positions (module docs).
fn positions(layout: &Layout, density: f64, field: &str) -> Result<(Vec<f32>, Vec<f32>), SurfaceError> {
    let mean = density * layout.apparent_length_m * layout.apparent_width_m;
    if mean.is_nan() || mean > MAX_SUMMITS as f64 / 2.0 {
        return Err(SurfaceError::InvalidParameter {
            field: field.to_string(),
            value: density.to_string(),
            expected: format!(
                "a density giving at most {} summits over the apparent area (got a mean of {mean:.3e})",
                MAX_SUMMITS / 2
            ),
        });
    }
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    match layout.placement {
        Placement::Poisson => {
            let n = if mean > 0.0 {
                let p = Poisson::new(mean).map_err(|e| SurfaceError::InvalidParameter {
                    field: field.to_string(),
                    value: density.to_string(),
                    expected: format!("a density usable as a Poisson mean ({e})"),
                })?;
                let x: f64 = p.sample(&mut Xoshiro256pp::for_block(layout.seed, STREAM_COUNT, 0));
                x as usize
            } else {
                0
            };
            let (mut xs, mut ys) = (vec![0.0f32; n], vec![0.0f32; n]);
            // One 64-bit draw per summit: x from its high 32 bits, y from its low 32 bits, each
            // uniform on a grid of 2^32 steps (finer than f32 resolves near the far edge).
            let (sx, sy) = (l / 4_294_967_296.0, w / 4_294_967_296.0);
            blockwise2(&mut xs, &mut ys, layout.seed, STREAM_POSITIONS, |r, _, x, y| {
                let bits = r.next_u64();
                *x = crate::face::clamp_f32((bits >> 32) as f64 * sx, l);
                *y = crate::face::clamp_f32((bits & 0xFFFF_FFFF) as f64 * sy, w);
            });
            Ok((xs, ys))
        }
        Placement::JitteredGrid => {
            let target = mean.round().max(1.0);
            let nx = ((target * l / w).sqrt().round().clamp(1.0, target)) as usize;
            let ny = ((target / nx as f64).round() as usize).max(1);
            let (cx, cy) = (l / nx as f64, w / ny as f64);
            let (mut xs, mut ys) = (vec![0.0f32; nx * ny], vec![0.0f32; nx * ny]);
            blockwise2(&mut xs, &mut ys, layout.seed, STREAM_POSITIONS, |r, k, x, y| {
                *x = crate::face::clamp_f32(((k % nx) as f64 + unit(r)) * cx, l);
                *y = crate::face::clamp_f32(((k / nx) as f64 + unit(r)) * cy, w);
            });
            // Fisher-Yates shuffle so that the summit order carries no spatial information.
            let mut r = Xoshiro256pp::for_block(layout.seed, STREAM_COUNT, 0);
            for k in (1..xs.len()).rev() {
                let m = r.random_range(0..=k);
                xs.swap(k, m);
                ys.swap(k, m);
            }
            Ok((xs, ys))
        }
    }
}

fn lognormal(face: &FaceParams) -> Option<LogNormal<f64>> {
    match face.radius_distribution {
        RadiusDistribution::Fixed => None,
        RadiusDistribution::Lognormal => {
            let cv = face.radius_sd_m / face.summit_radius_m;
            let s2 = (1.0 + cv * cv).ln();
            LogNormal::new(face.summit_radius_m.ln() - 0.5 * s2, s2.sqrt()).ok()
        }
    }
}

fn radii(seed: u64, stream: u64, n: usize, face: &FaceParams) -> Option<Vec<f64>> {
    let ln = lognormal(face)?;
    let mut v = vec![0.0; n];
    blockwise(&mut v, seed, stream, |r, x| *x = ln.sample(r));
    Some(v)
}

/// Version 2 of [`crate::generate`]: the same parameters and checks, the same random field, the
/// stream of this module.
pub fn generate_v2(layout: &Layout, face: &FaceParams) -> Result<Surface, SurfaceError> {
    layout.validate()?;
    face.validate("")?;
    let (xs, ys) = positions(layout, face.summit_density_per_m2, "summit_density")?;
    let n = xs.len();
    let heights = sorted_heights(layout.seed, Law::of(face.height_distribution), face.summit_sd_m, n);
    let radii = match radii(layout.seed, STREAM_RADII, n, face) {
        Some(r) => Radii::PerSummit(r),
        None => Radii::Uniform(face.summit_radius_m),
    };
    Surface::from_generated_descending(layout.apparent_length_m, layout.apparent_width_m, xs, ys, heights, radii)
}

/// Version 2 of [`crate::generate_composite`]: two Gaussian faces give Gaussian heights of SD
/// sqrt(sigma1^2 + sigma2^2), drawn in order as by [`generate_v2`] (the same law as the sum of one
/// draw from each face); otherwise each height is the sum of one draw from each face, sorted.
pub fn generate_composite_v2(layout: &Layout, wall: &FaceParams, shoe: &FaceParams) -> Result<Surface, SurfaceError> {
    layout.validate()?;
    wall.validate("")?;
    shoe.validate("counter_face.")?;
    let density = wall.summit_density_per_m2 + shoe.summit_density_per_m2;
    let (xs, ys) = positions(layout, density, "summit_density")?;
    let n = xs.len();
    let seed = layout.seed;
    let heights = if wall.height_distribution == HeightDistribution::Gaussian
        && shoe.height_distribution == HeightDistribution::Gaussian
    {
        sorted_heights(seed, Law::Normal, wall.summit_sd_m.hypot(shoe.summit_sd_m), n)
    } else {
        let (lw, ls) = (Law::of(wall.height_distribution), Law::of(shoe.height_distribution));
        let mut a = vec![0.0; n];
        blockwise(&mut a, seed, STREAM_HEIGHTS, |r, h| *h = to_height(lw, wall.summit_sd_m, lw.draw(r)));
        let mut b = vec![0.0; n];
        blockwise(&mut b, seed, STREAM_SECOND_HEIGHTS, |r, h| *h = to_height(ls, shoe.summit_sd_m, ls.draw(r)));
        crate::sequential_chacha::sort_desc(a.iter().zip(&b).map(|(x, y)| x + y).collect())
    };
    let rw = radii(seed, STREAM_RADII, n, wall);
    let rs = radii(seed, STREAM_SECOND_RADII, n, shoe);
    let radii = match (rw, rs) {
        (None, None) => Radii::Uniform(1.0 / (1.0 / wall.summit_radius_m + 1.0 / shoe.summit_radius_m)),
        (a, b) => {
            let a = a.unwrap_or_else(|| vec![wall.summit_radius_m; n]);
            let b = b.unwrap_or_else(|| vec![shoe.summit_radius_m; n]);
            Radii::PerSummit(a.iter().zip(&b).map(|(x, y)| x * y / (x + y)).collect())
        }
    };
    Surface::from_generated_descending(layout.apparent_length_m, layout.apparent_width_m, xs, ys, heights, radii)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_quantile_matches_known_values() {
        // Phi^-1 at tabulated points (Abramowitz and Stegun, table 26.5; 1e-12 absolute).
        for (p, x) in [
            (0.5, 0.0),
            (0.975, 1.959_963_984_540_054),
            (0.841_344_746_068_542_9, 1.0),
            (1e-10, -6.361_340_902_404_056),
            (0.001, -3.090_232_306_167_813_5),
        ] {
            assert!((normal_quantile(p) - x).abs() < 1e-12, "p = {p}: {} against {x}", normal_quantile(p));
        }
    }

    #[test]
    fn taylor_edges_equal_the_quantiles() {
        // Every edge a Taylor step gives must be the quantile to 1e-14 (relative to max(1, |x|)):
        // the bins' probabilities are then 1/M to far better than any test of the law resolves.
        for m in [1usize << 16, 1 << 20, 1 << 23] {
            let h = 1.0 / m as f64;
            let mut stepped = 0;
            for k in (1..m - 1).step_by(m / 5000 + 1) {
                let (x, exact) = (Law::Normal.upper_quantile(k, m), Law::Normal.upper_quantile(k + 1, m));
                if let Some(next) = Law::Normal.next_edge(x, h) {
                    assert!((next - exact).abs() < 1e-14 * exact.abs().max(1.0), "m {m} k {k}: {next} vs {exact}");
                    stepped += 1;
                }
            }
            assert!(stepped > 4000, "m {m}: only {stepped} Taylor steps");
        }
    }

    #[test]
    fn xoshiro_matches_the_reference_output() {
        // Reference: the C implementation (xoshiro256plusplus.c) from state {1, 2, 3, 4}.
        let mut r = Xoshiro256pp { s: [1, 2, 3, 4] };
        let first: Vec<u64> = (0..3).map(|_| r.next_u64()).collect();
        assert_eq!(first, [41_943_041, 58_720_359, 3_588_806_011_781_223]);
    }
}
