//! Measurement: parry3d-f64's BVH against the explicit solver's height-sorted prefix, and against
//! the bucket grid of the explicit two-face pairing (`stiction_surface::generate_two_face`).
//!
//! `cargo run --release -p stiction-contact --example explicit_bvh -- 1e4 1e5 1e6`
//!
//! Part 1 (solver search). Summits of the Table 1 statistics on a 4:1 face, sorted by height. For
//! the equilibrium poses of a tilt-free loading curve (pull-off to L* = 0.1; poses at 10, 50 and
//! 100 % of the curve) both structures answer "which summits can reach the shoe plane": the BVH
//! over point AABBs (x, y, height) by a traversal that prunes a node when its top lies below the
//! lowest point of the plane over the node's footprint; the sorted prefix by one binary search
//! (summits above the plane's lowest point over the whole face). Reported: candidates, query time
//! (BVH: traversal that collects the leaf indices; prefix: the binary search) and the time of one
//! solver-like pass over the candidates (gathered for the BVH, contiguous for the prefix), and
//! heap bytes per summit of each structure.
//!
//! Part 2 (two-face pairing). Two Poisson faces of the same density; for every wall summit, the
//! shoe summits within the lateral reach `sqrt(2 (R1 + R2) pair_reach)`: bucket grid (as in
//! `generate_two_face`) against a BVH over the shoe summits queried with the reach box.

use std::hint::black_box;
use std::time::Instant;

use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::math::Vector;
use parry3d_f64::partitioning::{Bvh, BvhBuildStrategy, TraversalAction};
use stiction_contact::explicit::{Detail, ExplicitSolver, SolverConfig};
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch};
use stiction_surface::{FaceParams, Layout, Placement, Surface, generate};

fn face(n: f64, seed: u64) -> (Layout, Surface) {
    let eta = 4e12;
    let width = (n / eta / 4.0).sqrt();
    let layout =
        Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed };
    let s = generate(&layout, &FaceParams::gaussian_fixed(eta, 0.04e-6, 0.5e-6)).expect("surface");
    (layout, s)
}

/// Median of `reps` timings of `f` \[s\].
fn time<R>(reps: usize, mut f: impl FnMut() -> R) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            black_box(f());
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[reps / 2]
}

/// A solver-like pass (DMT force, stiffness and moments) over the summits `idx` of the plane
/// w = a + b x + c y.
fn pass(xs: &[f32], ys: &[f32], hs: &[f64], idx: impl Iterator<Item = usize>, plane: (f64, f64, f64)) -> [f64; 6] {
    let (a, b, c) = plane;
    let (r, inv_d, c0) = (0.5e-6f64, 1.0 / 9.1e-12, 2.0 * std::f64::consts::PI * 0.1 * 0.5e-6);
    let mut acc = [0.0; 6];
    for i in idx {
        let (x, y) = (f64::from(xs[i]), f64::from(ys[i]));
        let z = hs[i] - (a + b * x + c * y);
        let zc = z.max(0.0);
        let s = (r * zc).sqrt();
        let act = if z >= 0.0 { 1.0 } else { 0.0 };
        let p = act * (s * zc * inv_d - c0);
        let k = act * 1.5 * s * inv_d;
        acc[0] += p;
        acc[1] += p * x;
        acc[2] += p * y;
        acc[3] += k;
        acc[4] += k * x;
        acc[5] += k * x * y;
    }
    acc
}

fn solver_search(n: f64) {
    let (layout, surface) = face(n, 1);
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    let m = surface.len();
    let xs: Vec<f32> = (0..m).map(|i| surface.x_m(i) as f32).collect();
    let ys: Vec<f32> = (0..m).map(|i| surface.y_m(i) as f32).collect();
    let hs: Vec<f64> = (0..m).map(|i| surface.height_m(i)).collect();
    // Equilibrium poses along the loading curve.
    let l_max = 0.1 * m as f64 * 0.5e-6f64.sqrt() * 0.04e-6f64.powf(1.5) / 9.1e-12;
    let cfg = SolverConfig { detail: Detail::Summary, ..Default::default() };
    let mut solver = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver");
    let po = solver.pull_off(0.0, 1e-6).expect("pull-off").load_n;
    let loads: Vec<f64> = (0..100).map(|k| po + (l_max - po) * k as f64 / 99.0).collect();
    let sweep = solver.sweep(&loads, Branch::Loading).expect("sweep");

    let t = Instant::now();
    let bvh = Bvh::from_iter(
        BvhBuildStrategy::Binned,
        (0..m).map(|i| {
            let p = Vector::new(f64::from(xs[i]), f64::from(ys[i]), hs[i]);
            (i, Aabb::new(p, p))
        }),
    );
    let build_s = t.elapsed().as_secs_f64();
    let bvh_bytes = bvh.heap_memory_size() as f64 / m as f64;
    for pct in [10usize, 50, 100] {
        let e = &sweep.points[pct - 1];
        let (x0, y0) = (e.load_point_x_m, e.load_point_y_m);
        let (b, c) = (e.tilt_x_rad, e.tilt_y_rad);
        let a = e.separation_m - b * x0 - c * y0;
        let plane = (a, b, c);
        // BVH: prune nodes whose top is below the lowest point of the plane over their footprint.
        let query = |out: &mut Vec<u32>| {
            out.clear();
            bvh.traverse(|node| {
                let (lo, hi) = (node.mins(), node.maxs());
                let wmin = a + (b * lo.x).min(b * hi.x) + (c * lo.y).min(c * hi.y);
                if hi.z < wmin {
                    return TraversalAction::Prune;
                }
                if let Some(i) = node.leaf_data() {
                    out.push(i);
                }
                TraversalAction::Continue
            });
        };
        let mut cand = Vec::new();
        query(&mut cand);
        let t_bvh_query = time(21, || {
            query(&mut cand);
            cand.len()
        });
        let t_bvh_pass = time(21, || pass(&xs, &ys, &hs, cand.iter().map(|&i| i as usize), plane));
        // Sorted prefix: one binary search for the plane's lowest point over the face.
        let wmin = a + (b * l).min(0.0) + (c * w).min(0.0);
        let end = hs.partition_point(|&h| h >= wmin);
        let t_prefix_query = time(21, || hs.partition_point(|&h| h >= black_box(wmin)));
        let t_prefix_pass = time(21, || pass(&xs, &ys, &hs, 0..end, plane));
        println!(
            "solver,{m},{pct},{},{},{},{:.3e},{:.3e},{:.3e},{:.3e},{bvh_bytes:.1},{build_s:.3}",
            e.contacts,
            cand.len(),
            end,
            t_bvh_query,
            t_bvh_pass,
            t_prefix_query,
            t_prefix_pass
        );
    }
}

fn two_face(n: f64) {
    let (layout, wall) = face(n, 1);
    let (_, shoe) = face(n, 2);
    let (l, w) = (layout.apparent_length_m, layout.apparent_width_m);
    let (r1, r2, pair_reach) = (0.5e-6f64, 0.5e-6f64, 0.2e-6f64);
    let reach = (2.0 * (r1 + r2) * pair_reach).sqrt();
    let sx: Vec<f64> = (0..shoe.len()).map(|j| shoe.x_m(j)).collect();
    let sy: Vec<f64> = (0..shoe.len()).map(|j| shoe.y_m(j)).collect();
    let wx: Vec<f64> = (0..wall.len()).map(|j| wall.x_m(j)).collect();
    let wy: Vec<f64> = (0..wall.len()).map(|j| wall.y_m(j)).collect();
    let count_pair = |i: usize, j: usize| {
        let (dx, dy) = (sx[j] - wx[i], sy[j] - wy[i]);
        u64::from((dx * dx + dy * dy) / (2.0 * (r1 + r2)) <= pair_reach)
    };
    // Grid of cell size `reach` (counting sort), as generate_two_face.
    let grid = || {
        let nx = ((l / reach).floor() as usize).clamp(1, 1 << 15);
        let ny = ((w / reach).floor() as usize).clamp(1, 1 << 15);
        let cell =
            |x: f64, y: f64| (((x / l * nx as f64) as usize).min(nx - 1), ((y / w * ny as f64) as usize).min(ny - 1));
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
        let mut pairs = 0u64;
        for i in 0..wx.len() {
            let (cx, cy) = cell(wx[i], wy[i]);
            for gy in cy.saturating_sub(1)..=(cy + 1).min(ny - 1) {
                for gx in cx.saturating_sub(1)..=(cx + 1).min(nx - 1) {
                    let k = gy * nx + gx;
                    for &j in &members[start[k] as usize..start[k + 1] as usize] {
                        pairs += count_pair(i, j as usize);
                    }
                }
            }
        }
        (pairs, (start.len() + members.len()) * 4)
    };
    let bvh_pairs = || {
        let bvh = Bvh::from_iter(
            BvhBuildStrategy::Binned,
            (0..sx.len()).map(|j| {
                let p = Vector::new(sx[j], sy[j], 0.0);
                (j, Aabb::new(p, p))
            }),
        );
        let mut pairs = 0u64;
        for i in 0..wx.len() {
            let q = Aabb::new(
                Vector::new(wx[i] - reach, wy[i] - reach, -1.0),
                Vector::new(wx[i] + reach, wy[i] + reach, 1.0),
            );
            for j in bvh.intersect_aabb(&q) {
                pairs += count_pair(i, j as usize);
            }
        }
        (pairs, bvh.heap_memory_size())
    };
    let (pg, bytes_g) = grid();
    let (pb, bytes_b) = bvh_pairs();
    assert_eq!(pg, pb, "both searches find the same pairs");
    let tg = time(5, grid);
    let tb = time(5, bvh_pairs);
    let m = shoe.len() as f64;
    println!("two_face,{},{pg},{tg:.3e},{tb:.3e},{:.1},{:.1}", shoe.len(), bytes_g as f64 / m, bytes_b as f64 / m);
}

fn main() {
    let sizes: Vec<f64> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![1e4, 1e5, 1e6] } else { sizes };
    println!(
        "part,summits,curve_pct,contacts,bvh_candidates,prefix_candidates,bvh_query_s,bvh_pass_s,prefix_query_s,prefix_pass_s,bvh_bytes_per_summit,bvh_build_s"
    );
    for &n in &sizes {
        solver_search(n);
    }
    println!("part,summits,pairs,grid_s,bvh_s,grid_bytes_per_summit,bvh_bytes_per_summit");
    for &n in &sizes {
        two_face(n);
    }
}
