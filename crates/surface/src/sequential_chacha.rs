//! Version 1 of the summit generator (the default, `surface.generator: 1`): sequential ChaCha8
//! streams, heights drawn unordered and then radix-sorted into descending order. One face, the
//! paper's composite of two faces, and an explicit pairing of shoe summits with wall summits.
//!
//! # Random streams
//!
//! This is version 1 of the generator (the default; `surface.generator: 2` selects
//! [`crate::generate_v2`], another stream for the same random field). All randomness comes from [`ChaCha8Rng`] seeded with [`SeedableRng::seed_from_u64`]`(seed)`,
//! a portable generator: the same seed gives the same surface, bit for bit, on every machine.
//! Independent quantities use independent ChaCha streams ([`ChaCha8Rng::set_stream`]):
//! stream 0 positions (and the Poisson count), 1 heights, 2 radii of the wall (or only) face,
//! 3, 4, 5 the same for the second face. So changing the placement does not change the heights.
//!
//! # Summit order
//!
//! The generators return summits in descending height. Positions and radii are drawn independently
//! of the heights (jittered-grid positions are shuffled first), so this order carries no
//! information and the surface is the same random field as in any other order; the contact solver
//! uses it as its search structure (a shoe can only touch a prefix of the list).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Exp1, LogNormal, Poisson, StandardNormal};

use crate::face::{FaceParams, HeightDistribution, Layout, MAX_SUMMITS, Placement, RadiusDistribution, clamp_f32};
use crate::surface::check_positive;
use crate::{Radii, Surface, SurfaceError};

fn rng(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    r.set_stream(stream);
    r
}

/// Draws positions (count and coordinates) on the given stream.
fn positions(layout: &Layout, density: f64, stream: u64, field: &str) -> Result<(Vec<f32>, Vec<f32>), SurfaceError> {
    let mean = density * layout.area();
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
    let mut r = rng(layout.seed, stream);
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    match layout.placement {
        Placement::Poisson => {
            let n = if mean > 0.0 {
                let p = Poisson::new(mean).map_err(|e| SurfaceError::InvalidParameter {
                    field: field.to_string(),
                    value: density.to_string(),
                    expected: format!("a density usable as a Poisson mean ({e})"),
                })?;
                p.sample(&mut r) as usize
            } else {
                0
            };
            let mut xs = Vec::with_capacity(n);
            let mut ys = Vec::with_capacity(n);
            for _ in 0..n {
                xs.push(clamp_f32(r.random::<f64>() * l, l));
                ys.push(clamp_f32(r.random::<f64>() * w, w));
            }
            Ok((xs, ys))
        }
        Placement::JitteredGrid => {
            // nx ny ~ target cells, nearly square; on a very elongated area (1 m x 1e-12 m) the
            // square-cell count along x alone would exceed the target, so nx is capped at the
            // target and the cells become elongated: the count always follows the density.
            let target = mean.round().max(1.0);
            let nx = ((target * l / w).sqrt().round().clamp(1.0, target)) as usize;
            let ny = ((target / nx as f64).round() as usize).max(1);
            let (cx, cy) = (l / nx as f64, w / ny as f64);
            let n = nx * ny;
            let mut xs = Vec::with_capacity(n);
            let mut ys = Vec::with_capacity(n);
            for j in 0..ny {
                for i in 0..nx {
                    xs.push(clamp_f32((i as f64 + r.random::<f64>()) * cx, l));
                    ys.push(clamp_f32((j as f64 + r.random::<f64>()) * cy, w));
                }
            }
            // Fisher-Yates shuffle so that the summit order carries no spatial information.
            for k in (1..n).rev() {
                let m = r.random_range(0..=k);
                xs.swap(k, m);
                ys.swap(k, m);
            }
            Ok((xs, ys))
        }
    }
}

/// `n` positions drawn uniformly over the apparent area from `layout.seed` (stream 0, x then y
/// for each summit, as the Poisson placement draws them after its count), for summit heights read
/// without positions (a heights-only `.npy` file).
pub fn uniform_positions(layout: &Layout, n: usize) -> (Vec<f32>, Vec<f32>) {
    let mut r = rng(layout.seed, 0);
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    let mut xs = Vec::with_capacity(n);
    let mut ys = Vec::with_capacity(n);
    for _ in 0..n {
        xs.push(clamp_f32(r.random::<f64>() * l, l));
        ys.push(clamp_f32(r.random::<f64>() * w, w));
    }
    (xs, ys)
}

fn draw_height(r: &mut ChaCha8Rng, face: &FaceParams) -> f64 {
    match face.height_distribution {
        HeightDistribution::Gaussian => {
            let g: f64 = StandardNormal.sample(r);
            face.summit_sd_m * g
        }
        HeightDistribution::Exponential => {
            let e: f64 = Exp1.sample(r);
            face.summit_sd_m * (e - 1.0)
        }
    }
}

fn radius_sampler(face: &FaceParams) -> Option<LogNormal<f64>> {
    match face.radius_distribution {
        RadiusDistribution::Fixed => None,
        RadiusDistribution::Lognormal => {
            let cv = face.radius_sd_m / face.summit_radius_m;
            let s2 = (1.0 + cv * cv).ln();
            let mu = face.summit_radius_m.ln() - 0.5 * s2;
            LogNormal::new(mu, s2.sqrt()).ok()
        }
    }
}

fn draw_radii(seed: u64, stream: u64, n: usize, face: &FaceParams) -> Option<Vec<f64>> {
    let ln = radius_sampler(face)?;
    let mut r = rng(seed, stream);
    Some((0..n).map(|_| ln.sample(&mut r)).collect())
}

/// Sorts the heights in descending [`f64::total_cmp`] order: the same result, bit for bit, as
/// `h.sort_unstable_by(|a, b| b.total_cmp(a))` (equal keys are equal bit patterns, so the order of
/// ties cannot show), in O(n) for generated heights.
///
/// Each height maps to a `u64` key whose ascending order is the heights' descending total order
/// ([`desc_key`]). A least-significant-digit radix sort orders the keys by their top 32 bits (four
/// stable counting passes of 8 bits; five passes, 40 bits, above 2^22 keys; a pass whose digit is
/// the same for every key is skipped); keys that agree in those bits (heights within a relative
/// 2^-20, or 2^-28, of each other: about one summit in ten at 1e6, a few per thousand at 1e8) are
/// then put in order by one insertion-sort pass over the whole array with the full key. Should that pass
/// have to move more than `n` keys (heights far more concentrated than a generator makes them),
/// it gives up and the comparison sort finishes the nearly sorted array: the result is exact in
/// every case. About 90 instructions per summit against about 300 for the comparison sort
/// (docs/performance.md). Extra memory: one `u64` buffer of the same length (the heights are
/// turned into keys in place).
pub(crate) fn sort_desc(h: Vec<f64>) -> Vec<f64> {
    if h.len() < RADIX_MIN_LEN {
        let mut h = h;
        h.sort_unstable_by(|a, b| b.total_cmp(a));
        return h;
    }
    // In-place collect: Vec<f64> -> Vec<u64> reuses the allocation (same size and alignment).
    let mut keys: Vec<u64> = h.into_iter().map(desc_key).collect();
    radix_sort_top_bits(&mut keys);
    insertion_finish(&mut keys);
    keys.into_iter().map(from_desc_key).collect()
}

/// Below this length the comparison sort is as fast as the radix passes.
const RADIX_MIN_LEN: usize = 4096;
const RADIX_BITS: u32 = 8;
const RADIX_BUCKETS: usize = 1 << RADIX_BITS;
/// The radix passes order the keys by bits 24..64 (digits 3..8 of 8 bits), or by bits 32..64 up
/// to `RADIX_SHORT_MAX_LEN` keys.
const RADIX_FIRST_DIGIT: u32 = 3;
const RADIX_SHORT_MAX_LEN: usize = 1 << 22;
const RADIX_DIGITS: u32 = 64 / RADIX_BITS;

/// A key whose ascending unsigned order is the descending [`f64::total_cmp`] order: the IEEE bits
/// with the sign bit set for non-negative values and all bits flipped for negative ones give the
/// ascending total order; the final complement reverses it.
fn desc_key(v: f64) -> u64 {
    let b = v.to_bits();
    let ascending = if b >> 63 == 1 { !b } else { b | (1 << 63) };
    !ascending
}

/// The inverse of [`desc_key`].
fn from_desc_key(k: u64) -> f64 {
    let ascending = !k;
    f64::from_bits(if ascending >> 63 == 1 { ascending & !(1 << 63) } else { !ascending })
}

/// Stable LSD radix sort of `keys` by their top 32 bits (up to [`RADIX_SHORT_MAX_LEN`] keys) or
/// top 40 bits (more keys: with only 32 bits the insertion pass would have more to move).
fn radix_sort_top_bits(keys: &mut Vec<u64>) {
    let n = keys.len();
    let first = if n <= RADIX_SHORT_MAX_LEN { RADIX_FIRST_DIGIT + 1 } else { RADIX_FIRST_DIGIT };
    let mut counts = vec![[0u32; RADIX_BUCKETS]; (RADIX_DIGITS - first) as usize];
    for &k in keys.iter() {
        for (p, c) in counts.iter_mut().enumerate() {
            c[((k >> ((p as u32 + first) * RADIX_BITS)) as usize) & (RADIX_BUCKETS - 1)] += 1;
        }
    }
    let mut scratch = vec![0u64; n];
    for (p, c) in counts.iter().enumerate() {
        if c.iter().any(|&m| m as usize == n) {
            continue; // every key has the same digit here: the pass would not move anything
        }
        let mut offsets = [0usize; RADIX_BUCKETS];
        let mut sum = 0usize;
        for (o, &m) in offsets.iter_mut().zip(c) {
            *o = sum;
            sum += m as usize;
        }
        let shift = (p as u32 + first) * RADIX_BITS;
        for &k in keys.iter() {
            let d = ((k >> shift) as usize) & (RADIX_BUCKETS - 1);
            scratch[offsets[d]] = k;
            offsets[d] += 1;
        }
        std::mem::swap(keys, &mut scratch);
    }
}

/// Insertion sort of nearly sorted `keys` by the full key; falls back to the comparison sort after
/// `keys.len()` moves, so the cost stays O(n) whatever the input.
fn insertion_finish(keys: &mut [u64]) {
    let budget = keys.len();
    let mut moves = 0usize;
    for i in 1..keys.len() {
        let k = keys[i];
        if keys[i - 1] <= k {
            continue;
        }
        let mut j = i;
        while j > 0 && keys[j - 1] > k {
            keys[j] = keys[j - 1];
            j -= 1;
        }
        keys[j] = k;
        moves += i - j;
        if moves > budget {
            keys.sort_unstable();
            return;
        }
    }
}

/// Generates one rough face (or an already composite one, as in the paper's Table 1).
///
/// Count and positions follow `layout.placement` at density eta; heights follow
/// `face.height_distribution` with SD sigma; radii are fixed or lognormal. Summits are returned in
/// descending height. Errors name the invalid parameter.
pub fn generate(layout: &Layout, face: &FaceParams) -> Result<Surface, SurfaceError> {
    layout.validate()?;
    face.validate("")?;
    let (xs, ys) = positions(layout, face.summit_density_per_m2, 0, "summit_density")?;
    let n = xs.len();
    let mut hr = rng(layout.seed, 1);
    let heights = sort_desc((0..n).map(|_| draw_height(&mut hr, face)).collect());
    let radii = match draw_radii(layout.seed, 2, n, face) {
        Some(r) => Radii::PerSummit(r),
        None => Radii::Uniform(face.summit_radius_m),
    };
    Surface::new(layout.apparent_length_m, layout.apparent_width_m, xs, ys, heights, radii)
}

/// Generates the paper's composite surface of two rough faces (section 3.1) summit by summit:
/// eta = eta1 + eta2, each summit height is the sum of one draw from each face's height
/// distribution (so sigma^2 = sigma1^2 + sigma2^2, and Gaussian + Gaussian is Gaussian), and each
/// radius is the harmonic combination 1/R = 1/R1 + 1/R2 of one draw from each face's radius
/// distribution (uniform when both are fixed).
pub fn generate_composite(layout: &Layout, wall: &FaceParams, shoe: &FaceParams) -> Result<Surface, SurfaceError> {
    layout.validate()?;
    wall.validate("")?;
    shoe.validate("counter_face.")?;
    let density = wall.summit_density_per_m2 + shoe.summit_density_per_m2;
    let (xs, ys) = positions(layout, density, 0, "summit_density")?;
    let n = xs.len();
    let mut hw = rng(layout.seed, 1);
    let mut hs = rng(layout.seed, 4);
    let heights = sort_desc((0..n).map(|_| draw_height(&mut hw, wall) + draw_height(&mut hs, shoe)).collect());
    let rw = draw_radii(layout.seed, 2, n, wall);
    let rs = draw_radii(layout.seed, 5, n, shoe);
    let radii = match (rw, rs) {
        (None, None) => Radii::Uniform(1.0 / (1.0 / wall.summit_radius_m + 1.0 / shoe.summit_radius_m)),
        (a, b) => {
            let a = a.unwrap_or_else(|| vec![wall.summit_radius_m; n]);
            let b = b.unwrap_or_else(|| vec![shoe.summit_radius_m; n]);
            Radii::PerSummit(a.iter().zip(&b).map(|(x, y)| x * y / (x + y)).collect())
        }
    };
    Surface::new(layout.apparent_length_m, layout.apparent_width_m, xs, ys, heights, radii)
}

/// Generates both rough faces explicitly and pairs shoe summits with wall summits.
///
/// The wall face (streams 0-2) has summit `i` at `p_i` with height `h_i` and radius `R_i` above the
/// wall's mean summit plane; the shoe face (streams 3-5) has summit `j` at `p_j` pointing down, its
/// height `g_j` measured downwards from the shoe's mean summit plane. With the shoe plane at
/// separation d, the two parabolic caps at lateral offset `r = |p_i - p_j|` first touch at the point
/// `p = p_i + (p_j - p_i) R_i / (R_i + R_j)` and their interference is
/// `z = h_i + g_j - r^2 / (2 (R_i + R_j)) - d`. Such a pair acts like one summit of composite radius
/// `R = R_i R_j / (R_i + R_j)` and effective height `h_i + g_j - r^2 / (2 (R_i + R_j))` against a flat
/// (the Hertz contact of two spheres); the returned surface holds one such effective summit per pair
/// with `r^2 / (2 (R_i + R_j)) <= pair_reach_m`, i.e. the lateral offset costs at most `pair_reach_m`
/// of height. Pairs are independent (a summit touching two partners is counted twice, with no
/// interaction between its two contacts). A solver that treats the returned surface against a flat
/// shoe is then the explicit two-face contact. Summits return in descending effective height.
pub fn generate_two_face(
    layout: &Layout,
    wall: &FaceParams,
    shoe: &FaceParams,
    pair_reach_m: f64,
) -> Result<Surface, SurfaceError> {
    generate_two_face_limited(layout, wall, shoe, pair_reach_m, MAX_SUMMITS)
}

/// [`generate_two_face`] that stops with an error naming `pair_reach` as soon as more than
/// `max_pairs` pairs are found (a large reach pairs every wall summit with every shoe summit:
/// n_wall x n_shoe pairs), so memory stays bounded whatever the reach.
pub fn generate_two_face_limited(
    layout: &Layout,
    wall: &FaceParams,
    shoe: &FaceParams,
    pair_reach_m: f64,
    max_pairs: usize,
) -> Result<Surface, SurfaceError> {
    layout.validate()?;
    wall.validate("")?;
    shoe.validate("counter_face.")?;
    check_positive("pair_reach", pair_reach_m, "m")?;
    let (wx, wy) = positions(layout, wall.summit_density_per_m2, 0, "summit_density")?;
    let (sx, sy) = positions(layout, shoe.summit_density_per_m2, 3, "counter_face.summit_density")?;
    let mut hr = rng(layout.seed, 1);
    let wh: Vec<f64> = (0..wx.len()).map(|_| draw_height(&mut hr, wall)).collect();
    let mut hr = rng(layout.seed, 4);
    let sh: Vec<f64> = (0..sx.len()).map(|_| draw_height(&mut hr, shoe)).collect();
    let wr = draw_radii(layout.seed, 2, wx.len(), wall);
    let sr = draw_radii(layout.seed, 5, sx.len(), shoe);
    let wrad = |i: usize| wr.as_ref().map_or(wall.summit_radius_m, |v| v[i]);
    let srad = |j: usize| sr.as_ref().map_or(shoe.summit_radius_m, |v| v[j]);
    let wmax = wr.as_ref().map_or(wall.summit_radius_m, |v| v.iter().copied().fold(0.0, f64::max));
    let smax = sr.as_ref().map_or(shoe.summit_radius_m, |v| v.iter().copied().fold(0.0, f64::max));
    let reach_xy = (2.0 * (wmax + smax) * pair_reach_m).sqrt();

    // Bucket the shoe summits on a grid of cells at least reach_xy wide (counting sort, CSR
    // layout), so every partner lies in the 3 x 3 cells around a wall summit. (Measured against a
    // parry3d-f64 BVH over the shoe summits: the grid is faster and smaller, see
    // docs/explicit-solver.md.)
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    let nx = ((l / reach_xy).floor() as usize).clamp(1, 1 << 15);
    let ny = ((w / reach_xy).floor() as usize).clamp(1, 1 << 15);
    let cell = |x: f32, y: f32| -> (usize, usize) {
        let cx = ((f64::from(x) / l * nx as f64) as usize).min(nx - 1);
        let cy = ((f64::from(y) / w * ny as f64) as usize).min(ny - 1);
        (cx, cy)
    };
    let mut start = vec![0u32; nx * ny + 1];
    for j in 0..sx.len() {
        let (cx, cy) = cell(sx[j], sy[j]);
        start[cy * nx + cx + 1] += 1;
    }
    for k in 0..nx * ny {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut members = vec![0u32; sx.len()];
    for j in 0..sx.len() {
        let (cx, cy) = cell(sx[j], sy[j]);
        let k = cy * nx + cx;
        members[fill[k] as usize] = j as u32;
        fill[k] += 1;
    }

    let (mut px, mut py, mut ph, mut pr) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for i in 0..wx.len() {
        let (cx, cy) = cell(wx[i], wy[i]);
        let (xi, yi, ri) = (f64::from(wx[i]), f64::from(wy[i]), wrad(i));
        for gy in cy.saturating_sub(1)..=(cy + 1).min(ny - 1) {
            for gx in cx.saturating_sub(1)..=(cx + 1).min(nx - 1) {
                let k = gy * nx + gx;
                for &j in &members[start[k] as usize..start[k + 1] as usize] {
                    let j = j as usize;
                    let (dx, dy) = (f64::from(sx[j]) - xi, f64::from(sy[j]) - yi);
                    let rj = srad(j);
                    let drop = (dx * dx + dy * dy) / (2.0 * (ri + rj));
                    if drop <= pair_reach_m {
                        if px.len() >= max_pairs.min(MAX_SUMMITS) {
                            return Err(SurfaceError::InvalidParameter {
                                field: "pair_reach".into(),
                                value: format!("{pair_reach_m} m"),
                                expected: format!(
                                    "a reach giving at most {} summit pairs (the limit `max_summits`; more \
                                     were found before wall summit {i} of {}): lower `pair_reach` or raise \
                                     `surface.max_summits` if the machine has the memory",
                                    max_pairs.min(MAX_SUMMITS),
                                    wx.len()
                                ),
                            });
                        }
                        let t = ri / (ri + rj);
                        px.push(clamp_f32(xi + t * dx, l));
                        py.push(clamp_f32(yi + t * dy, w));
                        ph.push(wh[i] + sh[j] - drop);
                        pr.push(ri * rj / (ri + rj));
                    }
                }
            }
        }
    }
    let uniform = wr.is_none() && sr.is_none();
    let radii = if uniform {
        Radii::Uniform(wall.summit_radius_m * shoe.summit_radius_m / (wall.summit_radius_m + shoe.summit_radius_m))
    } else {
        Radii::PerSummit(pr)
    };
    let mut s = Surface::new(l, w, px, py, ph, radii)?;
    s.sort_by_height_descending();
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radix_sort_equals_the_comparison_sort_bit_for_bit() {
        // The radix sort must give exactly what `sort_unstable_by(b.total_cmp(a))` gave before
        // (the generated surfaces' bits depend on it): Gaussian heights with ties, both zeros,
        // infinities, subnormals, values of every binade, and a length that leaves some passes
        // with a constant digit (all keys positive and small).
        let mut r = rng(3, 9);
        let mut v: Vec<f64> = (0..50_000)
            .map(|_| {
                let g: f64 = StandardNormal.sample(&mut r);
                4e-8 * g
            })
            .collect::<Vec<f64>>();
        v.extend([0.0, -0.0, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE / 3.0, -5e-324, 1e300, -1e-300]);
        v.extend(v[..1000].to_vec()); // exact ties
        v.extend(
            (0..5000).map(|k| f64::from_bits(r.random::<u64>() & !(1 << 63)) * if k % 2 == 0 { 1.0 } else { -1.0 }),
        );
        v.retain(|x| !x.is_nan());
        let mut expected = v.clone();
        expected.sort_unstable_by(|a, b| b.total_cmp(a));
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&sort_desc(v.clone())), bits(&expected));
        let small: Vec<f64> = (0..10_000).map(|k| f64::from(k % 977) * 1e-9).collect();
        let mut expected = small.clone();
        expected.sort_unstable_by(|a, b| b.total_cmp(a));
        assert_eq!(bits(&sort_desc(small)), bits(&expected));
        // Heights within a relative 1e-12 of each other: the top 40 bits cannot order them, the
        // insertion pass runs out of its budget and the comparison sort finishes.
        let close: Vec<f64> = (0..20_000).map(|_| 1e-7 * (1.0 + 1e-12 * r.random::<f64>())).collect();
        let mut expected = close.clone();
        expected.sort_unstable_by(|a, b| b.total_cmp(a));
        assert_eq!(bits(&sort_desc(close)), bits(&expected));
        for x in [0.0, -0.0, 1.5, -2.5e-8, f64::INFINITY, f64::NEG_INFINITY, 5e-324] {
            assert_eq!(from_desc_key(desc_key(x)).to_bits(), x.to_bits());
        }
    }

    #[test]
    fn two_face_pairs_equal_a_brute_force_search() {
        // A face 2.5 lateral reaches wide: grid cells must not be narrower than the reach (a
        // ceil-sized grid of 3 cells missed partners two cells away). Every pair with
        // r^2 / (2 (R1 + R2)) <= reach is found, none else.
        let (r1, r2, reach) = (1e-6f64, 1e-6f64, 0.1e-6f64);
        let reach_xy = (2.0 * (r1 + r2) * reach).sqrt();
        let side = 2.5 * reach_xy;
        for seed in 0..5 {
            let layout =
                Layout { apparent_length_m: side, apparent_width_m: side, placement: Placement::Poisson, seed };
            let wall = FaceParams::gaussian_fixed(2e14, 0.03e-6, r1);
            let shoe = FaceParams::gaussian_fixed(2e14, 0.04e-6, r2);
            let (wx, wy) = positions(&layout, wall.summit_density_per_m2, 0, "summit_density").unwrap();
            let (sx, sy) = positions(&layout, shoe.summit_density_per_m2, 3, "counter_face.summit_density").unwrap();
            let mut brute = 0;
            for i in 0..wx.len() {
                for j in 0..sx.len() {
                    let dx = f64::from(sx[j]) - f64::from(wx[i]);
                    let dy = f64::from(sy[j]) - f64::from(wy[i]);
                    brute += usize::from((dx * dx + dy * dy) / (2.0 * (r1 + r2)) <= reach);
                }
            }
            let s = generate_two_face(&layout, &wall, &shoe, reach).unwrap();
            assert!(brute > 100, "seed {seed}: {brute} pairs");
            assert_eq!(s.len(), brute, "seed {seed}");
        }
    }
}
