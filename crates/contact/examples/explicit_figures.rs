//! Figures of the explicit solver (docs/performance-explicit.md, docs/explicit-solver.md).
//!
//! * `cargo run --release -p stiction-contact --example explicit_figures -- scaling`: reads
//!   docs/figures/scaling.csv (written by `--example explicit_scaling -- ... --csv`) and draws
//!   docs/figures/scaling-time-per-point.{svg,png} and docs/figures/scaling-bytes-per-summit.{svg,png}.
//! * `... -- table1 [SEEDS]`: the Table 1 surface (about 400 summits) under a tilt-free DMT shoe for
//!   seeds 0..SEEDS (default 200), loads 0 to 10 uN in 0.25 uN steps, through
//!   `explicit::table1::friction_vs_load`; writes docs/figures/table1-explicit-vs-discrete.csv and
//!   draws friction against load (median and 10 / 90 % of the seeds beside eq. 12 with N = 3) as
//!   docs/figures/table1-explicit-vs-discrete.{svg,png} and the number of contacts against load
//!   as docs/figures/table1-contacts.{svg,png}.
//!
//! Paths are relative to the working directory (run from the repository root).

use std::fmt::Write as _;
use std::path::Path;

use stiction_contact::explicit::table1::{discrete_friction_n, friction_vs_load};
use stiction_contact::single::AdhesionLaw;
use stiction_plot::{Chart, Series};

fn quantile(sorted: &[f64], q: f64) -> f64 {
    let pos = q * (sorted.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    sorted[lo] + (sorted[hi] - sorted[lo]) * (pos - lo as f64)
}

fn save(chart: &Chart, stem: &str) {
    chart.write_svg(Path::new(&format!("{stem}.svg"))).expect("svg");
    chart.write_png(Path::new(&format!("{stem}.png"))).expect("png");
    println!("wrote {stem}.svg and .png");
}

fn scaling() {
    let text = std::fs::read_to_string("docs/figures/scaling.csv").expect("docs/figures/scaling.csv");
    let mut time = Vec::new();
    let mut bytes = Vec::new();
    let mut rss = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let n: f64 = f[0].parse().expect("summits");
        let per: f64 = f[4].parse().expect("s_per_point");
        let b: f64 = f[7].parse().expect("bytes_per_summit");
        time.push((n, per * 1e3));
        bytes.push((n, b));
        if let Ok(mb) = f[8].parse::<f64>() {
            rss.push((n, mb * 1024.0 * 1024.0 / n));
        }
    }
    let linear: Vec<(f64, f64)> = time.iter().map(|&(n, _)| (n, time[0].1 * n / time[0].0)).collect();
    let mut c = Chart::new(
        "Explicit solver: time per load point (tilt free, DMT, L* up to 0.1, one core)",
        "summits N",
        "time per load point (ms)",
    )
    .with(Series::line("measured", time))
    .with(Series::dashed("proportional to N", linear));
    c.x_log = true;
    c.y_log = true;
    save(&c, "docs/figures/scaling-time-per-point");
    let floor: Vec<(f64, f64)> = bytes.iter().map(|&(n, _)| (n, 48.0)).collect();
    let mut c = Chart::new("Explicit solver: memory per summit", "summits N", "bytes per summit")
        .with(Series::line("solver (summits + search + contact set)", bytes))
        .with(Series::markers("peak RSS / N (whole process)", rss))
        .with(Series::dashed("floor 48 B", floor));
    c.legend = stiction_plot::LegendPosition::UpperRight;
    c.x_log = true;
    c.y_log = true;
    save(&c, "docs/figures/scaling-bytes-per-summit");
}

fn table1(seeds: u64) {
    let loads: Vec<f64> = (0..=40).map(|k| k as f64 * 0.25e-6).collect();
    let runs: Vec<_> =
        (0..seeds).map(|s| friction_vs_load(s, &loads, AdhesionLaw::Dmt).expect("Table 1 solve")).collect();
    let mut csv = String::from(
        "load_n,friction_median_n,friction_p10_n,friction_p90_n,friction_eq12_n3_n,contacts_mean,share_3,share_4,share_5_or_more,seeds\n",
    );
    let (mut med, mut p10, mut p90, mut s3, mut s4, mut s5) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, &l) in loads.iter().enumerate() {
        let mut f: Vec<f64> = runs.iter().map(|r| r.points[k].friction_explicit_n).collect();
        let c: Vec<usize> = runs.iter().map(|r| r.points[k].contacts).collect();
        let share =
            |pred: &dyn Fn(usize) -> bool| 100.0 * c.iter().filter(|&&n| pred(n)).count() as f64 / c.len() as f64;
        let (sh3, sh4, sh5) = (share(&|n| n == 3), share(&|n| n == 4), share(&|n| n >= 5));
        let mean = c.iter().sum::<usize>() as f64 / c.len() as f64;
        assert!(runs.iter().all(|r| (r.points[k].load_n - l).abs() < 1e-18));
        f.sort_by(f64::total_cmp);
        let um = l * 1e6;
        med.push((um, quantile(&f, 0.5) * 1e6));
        p10.push((um, quantile(&f, 0.1) * 1e6));
        p90.push((um, quantile(&f, 0.9) * 1e6));
        s3.push((um, sh3));
        s4.push((um, sh4));
        s5.push((um, sh5));
        writeln!(
            csv,
            "{l:e},{:e},{:e},{:e},{:e},{mean},{sh3},{sh4},{sh5},{seeds}",
            quantile(&f, 0.5),
            quantile(&f, 0.1),
            quantile(&f, 0.9),
            discrete_friction_n(l, 3)
        )
        .expect("csv");
    }
    std::fs::write("docs/figures/table1-explicit-vs-discrete.csv", csv).expect("write csv");
    // Eq. 12 with N = 3 from its pull-off (-3 x 2 pi dgamma R = -0.94 uN) to 10 uN.
    let eq12: Vec<(f64, f64)> =
        (0..=109).map(|k| -0.9e-6 + k as f64 * 0.1e-6).map(|l| (l * 1e6, discrete_friction_n(l, 3) * 1e6)).collect();
    let some: Vec<(f64, f64)> = runs[0].points.iter().map(|p| (p.load_n * 1e6, p.friction_explicit_n * 1e6)).collect();
    let c = Chart::new(
        format!("Table 1 surface, tilt-free shoe (DMT, {seeds} surfaces) vs discrete N = 3 (eq. 12)"),
        "normal load L (µN)",
        "friction capacity s A_r (µN)",
    )
    .with(Series::line("explicit: median", med))
    .with(Series::dashed("explicit: 10 %", p10))
    .with(Series::dashed("explicit: 90 %", p90))
    .with(Series::markers("explicit: seed 0", some))
    .with(Series::line("eq. 12, N = 3", eq12));
    save(&c, "docs/figures/table1-explicit-vs-discrete");
    let mut c = Chart::new(
        format!("Table 1 surface, tilt-free shoe: summits carrying the shoe ({seeds} surfaces)"),
        "normal load L (µN)",
        "surfaces (%)",
    )
    .with(Series::line("3 contacts (the paper's N = 3)", s3))
    .with(Series::line("4 contacts", s4))
    .with(Series::line("5 or more contacts", s5));
    // Headroom above 100 % for the legend.
    c.y_range = Some((0.0, 118.0));
    c.legend = stiction_plot::LegendPosition::UpperRight;
    let mut po: Vec<f64> = runs.iter().map(|r| r.pull_off_load_n).collect();
    po.sort_by(f64::total_cmp);
    println!(
        "pull-off [uN]: min {:.3}, 10 % {:.3}, median {:.3}, 90 % {:.3}, max {:.3}",
        po[0] * 1e6,
        quantile(&po, 0.1) * 1e6,
        quantile(&po, 0.5) * 1e6,
        quantile(&po, 0.9) * 1e6,
        po[po.len() - 1] * 1e6
    );
    for &l in &[0.0, 1e-6, 3e-6, 5e-6, 10e-6] {
        let k = loads.iter().position(|&x| (x - l).abs() < 1e-12).expect("load");
        let mut ratio: Vec<f64> =
            runs.iter().map(|r| r.points[k].friction_explicit_n / r.points[k].friction_discrete_n3_n).collect();
        ratio.sort_by(f64::total_cmp);
        let n = |m: usize| runs.iter().filter(|r| r.points[k].contacts == m).count();
        println!(
            "L = {l:e}: contacts 3/4/5+ = {}/{}/{}; F/F_eq12: min {:.3}, 10 % {:.3}, median {:.3}, 90 % {:.3}, max {:.3}",
            n(3),
            n(4),
            runs.len() - n(3) - n(4),
            ratio[0],
            quantile(&ratio, 0.1),
            quantile(&ratio, 0.5),
            quantile(&ratio, 0.9),
            ratio[ratio.len() - 1]
        );
    }
    save(&c, "docs/figures/table1-contacts");
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("scaling") => scaling(),
        Some("table1") => table1(args.get(1).and_then(|s| s.parse().ok()).unwrap_or(200)),
        _ => eprintln!("usage: explicit_figures scaling | table1 [SEEDS]"),
    }
}
