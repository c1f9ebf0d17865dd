//! Thread CPU time of summit generation (docs/performance.md), for a machine shared with other
//! work where criterion's wall times are inflated.
//!
//! `cargo run --release -p stiction-surface --example generate_timing -- N [--repeat K] [--generator 2]`
//!
//! Generates the Table 1 surface (eta = 4e12 m^-2, sigma = 0.04 um, R = 0.5 um, Poisson, seed
//! 2000) on a 4:1 rectangle holding about N summits, K times, with generator version 1 (default)
//! or 2, and prints the median CPU time per run and per summit and the mean over all runs, summed
//! over all threads of the process (`/proc/self/task/*/schedstat`, Linux; version 2 draws its
//! blocks on rayon's threads: `RAYON_NUM_THREADS=1` for one core).

use stiction_surface::{FaceParams, Layout, Placement, generate, generate_v2};

/// CPU time of all threads of this process, ns.
fn thread_cpu_ns() -> Option<u64> {
    let mut total = 0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let text = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += text.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1e6);
    let repeat: usize = args
        .iter()
        .position(|a| a == "--repeat")
        .and_then(|k| args.get(k + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let version: u32 = args
        .iter()
        .position(|a| a == "--generator")
        .and_then(|k| args.get(k + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let area = n / 4e12;
    let width = (area / 4.0).sqrt();
    let layout =
        Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed: 2000 };
    let face = FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6);
    let mut cpu = Vec::new();
    let cpu_start = thread_cpu_ns();
    let mut wall = Vec::new();
    let mut count = 0;
    for _ in 0..repeat {
        let (c0, t0) = (thread_cpu_ns(), std::time::Instant::now());
        let s = if version == 2 { generate_v2(&layout, &face) } else { generate(&layout, &face) }.expect("generate");
        let (c1, dt) = (thread_cpu_ns(), t0.elapsed().as_secs_f64());
        count = s.len();
        drop(s);
        if let (Some(a), Some(b)) = (c0, c1) {
            cpu.push((b - a) as f64 * 1e-9);
        }
        wall.push(dt);
    }
    // The thread clock ticks in steps of about 4 ms on this machine: the mean over all runs (one
    // reading at each end) is the precise figure, the median of single runs is quantised.
    let cpu_total = match (cpu_start, thread_cpu_ns()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
        _ => f64::NAN,
    };
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
    };
    let (c, w) = (median(&mut cpu), median(&mut wall));
    println!("summits {count}  runs {repeat}  generator {version}");
    println!("cpu_s {c:.4}  cpu_ns_per_summit {:.1}  (median of runs)", c / count as f64 * 1e9);
    let mean = cpu_total / repeat as f64;
    println!(
        "mean_cpu_s {mean:.4}  mean_cpu_ns_per_summit {:.1}  (all runs, includes freeing)",
        mean / count as f64 * 1e9
    );
    println!("wall_s {w:.4}  wall_ns_per_summit {:.1}", w / count as f64 * 1e9);
}
