//! Scaling of the explicit solver: summits 1e4 .. 1e8 (Table 1 statistics, square-ish area),
//! time per load point of a tilt-free loading curve from pull-off to L* = 0.1 and bytes per summit.
//!
//! `cargo run --release -p stiction-contact --example explicit_scaling -- 1e4 1e5 1e6 1e7 1e8 [--flat]`
//! (one line per size: summits, generation s, pull-off s, loading points, s per point, bytes per
//! summit of the solver, peak RSS in MB from /proc/self/status when available).
//! With `--csv PATH` the lines are also appended to PATH (header written when it is new); the
//! figures are drawn from that file by `--example explicit_figures -- scaling`.
//! With `--repeat K` the whole curve (reset, pull-off search, 100 points) is solved K times and the
//! CPU columns are the medians over the K runs (the thread CPU clock ticks in steps of a few ms);
//! each run's `curve_cpu_s` (pull-off + 100 points) is printed to stderr.
//! `--exact`: without the two shortcuts of the Newton iteration (`ExplicitSolver::set_shortcuts`).
//! `--dump PATH`: the last curve's points (pull-off first) with every digit, for comparisons.
//! `--stream`: also the memory reference, printed to stderr: thread CPU per summit of a plain
//! read of the summit arrays (x, y f32 and height f64: the 16 B a pass reads per summit, summed in
//! 4 lanes so the loop vectorises), over the whole surface and over its first 10 % (about the
//! prefix a pass scans on this curve), repeated until about 2e8 summits were read.

use std::time::Instant;

use stiction_contact::explicit::{Detail, ExplicitSolver, ShoeMode, SolverConfig};
use stiction_contact::single::{AdhesionLaw, AsperityParams, Branch};
use stiction_surface::{FaceParams, Layout, Placement, generate};

fn peak_rss_mb() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// CPU time of this thread in s (`/proc/thread-self/schedstat`, ns on the CPU; robust against
/// other processes sharing the machine), None where unavailable.
fn thread_cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// Sum of x + y + h over the summits (4 lanes): a plain read of the 16 B per summit.
fn stream(xs: &[f32], ys: &[f32], hs: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    for ((x, y), h) in xs.chunks_exact(4).zip(ys.chunks_exact(4)).zip(hs.chunks_exact(4)) {
        for l in 0..4 {
            acc[l] += f64::from(x[l]) + f64::from(y[l]) + h[l];
        }
    }
    acc.iter().sum()
}

/// Thread CPU per summit of [`stream`] over the first `n` summits \[ns\].
fn stream_ns(xs: &[f32], ys: &[f32], hs: &[f64], n: usize) -> Option<f64> {
    let reps = (2e8 / n as f64).ceil().max(1.0) as usize;
    let c0 = thread_cpu_s()?;
    let mut total = 0.0;
    for _ in 0..reps {
        total += stream(std::hint::black_box(&xs[..n]), &ys[..n], &hs[..n]);
    }
    std::hint::black_box(total);
    Some((thread_cpu_s()? - c0) / (reps * n) as f64 * 1e9)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let csv = args.iter().position(|a| a == "--csv").and_then(|k| args.get(k + 1)).map(std::path::PathBuf::from);
    let sizes: Vec<f64> = args
        .iter()
        .enumerate()
        .filter(|(k, _)| *k == 0 || (args[k - 1] != "--repeat" && args[k - 1] != "--dump"))
        .filter_map(|(_, a)| a.parse().ok())
        .collect();
    // --flat: the flat shoe (approach only) instead of the tilt-free one.
    let mode = if args.iter().any(|a| a == "--flat") { ShoeMode::Flat } else { ShoeMode::TiltFree };
    let sizes = if sizes.is_empty() { vec![1e4, 1e5, 1e6] } else { sizes };
    let exact = args.iter().any(|a| a == "--exact");
    let dump = args.iter().position(|a| a == "--dump").and_then(|k| args.get(k + 1)).map(std::path::PathBuf::from);
    let repeat: usize = args
        .iter()
        .position(|a| a == "--repeat")
        .and_then(|k| args.get(k + 1))
        .map_or(1, |v| v.parse().expect("--repeat K"));
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        if v.is_empty() { None } else { Some(0.5 * (v[(v.len() - 1) / 2] + v[v.len() / 2])) }
    };
    let points = 100;
    let header = "summits,gen_s,pull_off_s,points,s_per_point,newton_iterations_per_point,contacts_at_max,bytes_per_summit,peak_rss_mb,cpu_s_per_point,pull_off_cpu_s,passes_per_point,scanned_per_point,cpu_ns_per_scanned_summit";
    println!("{header}");
    let mut out = csv.map(|p| {
        let new = !p.exists();
        let mut f = std::fs::OpenOptions::new().create(true).append(true).open(&p).expect("open csv");
        if new {
            use std::io::Write;
            writeln!(f, "{header}").expect("write csv");
        }
        f
    });
    for n in sizes {
        let (eta, sigma, r, d) = (4e12, 0.04e-6, 0.5e-6f64, 9.1e-12);
        let area = n / eta;
        let width = (area / 4.0).sqrt();
        let layout =
            Layout { apparent_length_m: 4.0 * width, apparent_width_m: width, placement: Placement::Poisson, seed: 1 };
        let t = Instant::now();
        let surface = generate(&layout, &FaceParams::gaussian_fixed(eta, sigma, r)).expect("surface");
        let gen_s = t.elapsed().as_secs_f64();
        let m = surface.len() as f64;
        if args.iter().any(|a| a == "--stream") {
            let (xs, ys, hs) = (surface.xs_m(), surface.ys_m(), surface.heights_m());
            let all = stream_ns(xs, ys, hs, xs.len());
            let prefix = stream_ns(xs, ys, hs, xs.len() / 10);
            let f = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{v:.3}"));
            eprintln!("summits {m:.0}: stream_ns_per_summit all {} first_10_percent {}", f(all), f(prefix));
        }
        // L* = D L / (eta A_a R^1/2 sigma^3/2) = 0.1 (eq. 5c).
        let l_max = 0.1 * m * r.sqrt() * sigma.powf(1.5) / d;
        let cfg = SolverConfig { detail: Detail::Summary, mode, ..Default::default() };
        let mut solver = ExplicitSolver::new(surface, AdhesionLaw::Dmt, AsperityParams::table1(), cfg).expect("solver");
        solver.set_shortcuts(!exact);
        let (mut po_cpus, mut pt_cpus) = (Vec::new(), Vec::new());
        let (mut po_s, mut per, mut sweep, mut work, mut po_eq) = (0.0, 0.0, None, (0, 0), None);
        for _ in 0..repeat.max(1) {
            solver.reset();
            let t = Instant::now();
            let cpu_po = thread_cpu_s();
            let po = solver.pull_off(0.0, 1e-6).expect("pull-off");
            po_s = t.elapsed().as_secs_f64();
            po_eq = Some(po.clone());
            let po_cpu = cpu_po.and_then(|c0| Some(thread_cpu_s()? - c0));
            let loads: Vec<f64> =
                (0..points).map(|k| po.load_n + (l_max - po.load_n) * k as f64 / (points - 1) as f64).collect();
            let t = Instant::now();
            let cpu0 = thread_cpu_s();
            let w0 = solver.work();
            sweep = Some(solver.sweep(&loads, Branch::Loading).expect("sweep"));
            let cpu_per = cpu0.and_then(|c0| Some((thread_cpu_s()? - c0) / points as f64));
            let w1 = solver.work();
            work = (w1.passes - w0.passes, w1.summits_scanned - w0.summits_scanned);
            per = t.elapsed().as_secs_f64() / points as f64;
            if let (Some(a), Some(b)) = (po_cpu, cpu_per) {
                eprintln!("summits {m:.0}: curve_cpu_s {:.4}", a + b * points as f64);
                po_cpus.push(a);
                pt_cpus.push(b);
            }
        }
        let sweep = sweep.expect("at least one run");
        if let (Some(path), Some(po)) = (&dump, &po_eq) {
            let mut text = String::from(
                "load_n,separation_m,tilt_x_rad,tilt_y_rad,contacts,real_area_m2,elastic_load_n,force_residual_n,moment_residual_x_n_m,moment_residual_y_n_m,max_pressure_pa,iterations\n",
            );
            for e in std::iter::once(po).chain(&sweep.points) {
                text += &format!(
                    "{:.17e},{:.17e},{:.17e},{:.17e},{},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{}\n",
                    e.load_n,
                    e.separation_m,
                    e.tilt_x_rad,
                    e.tilt_y_rad,
                    e.contacts,
                    e.real_area_m2,
                    e.elastic_load_n,
                    e.force_residual_n,
                    e.moment_residual_x_n_m,
                    e.moment_residual_y_n_m,
                    e.max_pressure_pa,
                    e.iterations
                );
            }
            std::fs::write(path, text).expect("write dump");
        }
        let (po_cpu, cpu_per) = (median(po_cpus), median(pt_cpus));
        let its: usize = sweep.points.iter().map(|p| p.iterations).sum();
        let its = its as f64 / points as f64;
        let last = sweep.points.last().map_or(0, |e| e.contacts);
        let line = format!(
            "{m:.0},{gen_s:.3},{po_s:.4},{points},{per:.3e},{its:.1},{last},{:.2},{},{},{},{:.2},{:.0},{}",
            solver.bytes_per_summit(),
            peak_rss_mb().map_or("n/a".into(), |v| format!("{v:.0}")),
            cpu_per.map_or("n/a".into(), |v| format!("{v:.3e}")),
            po_cpu.map_or("n/a".into(), |v| format!("{v:.4}")),
            work.0 as f64 / points as f64,
            work.1 as f64 / points as f64,
            cpu_per.map_or("n/a".into(), |v| format!("{:.2}", v * points as f64 / work.1 as f64 * 1e9))
        );
        println!("{line}");
        if let Some(f) = out.as_mut() {
            use std::io::Write;
            writeln!(f, "{line}").expect("write csv");
        }
    }
}
