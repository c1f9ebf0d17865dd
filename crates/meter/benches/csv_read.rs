//! Reading measured-voltage CSVs: 1e4 and 1e6 rows (the issue 9 target: 1e6 rows in under 2 s),
//! and a surface summit CSV of 1e6 rows, through the same parsers `stiction run` uses.
//!
//! `cargo bench -p stiction-meter --bench csv_read`

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use std::fmt::Write;

use criterion::{Criterion, criterion_group, criterion_main};
use stiction_meter::measured::parse_measured_voltages;
use stiction_surface::Surface;

fn measured(rows: usize) -> String {
    let mut t = String::from("v_clamp_v,v_pull_v\n");
    for i in 0..rows {
        let v = 20.0 + (i % 2000) as f64 * 0.01;
        let _ = writeln!(t, "{v:.3},{:.4}", 1.1 * v + 3.0);
    }
    t
}

fn summits(rows: usize) -> String {
    let mut t = String::from("x_m,y_m,height_m,radius_m\n");
    for i in 0..rows {
        let f = i as f64 / rows as f64;
        let _ = writeln!(t, "{:e},{:e},{:e},5e-7", f * 2e-5, (1.0 - f) * 5e-6, (f - 0.5) * 8e-8);
    }
    t
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("csv");
    g.sample_size(10);
    for rows in [10_000usize, 1_000_000] {
        let text = measured(rows);
        g.bench_function(format!("measured voltages, {rows} rows"), |b| {
            b.iter(|| {
                let r = parse_measured_voltages(text.as_bytes(), "m.csv").unwrap();
                assert_eq!(r.rows.len(), rows);
            })
        });
    }
    let text = summits(1_000_000);
    g.bench_function("surface summits, 1000000 rows", |b| {
        b.iter(|| Surface::read_csv(text.as_bytes(), 2e-5, 5e-6).unwrap().len())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
