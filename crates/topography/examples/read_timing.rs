//! Times reading a 4096 x 4096 instrument file, for profiling (`perf stat`, `perf record`) and
//! for timing whole processes side by side:
//!
//! * `read_timing FORMAT [READS]` (FORMAT: nanoscope, sdf, ibw, metropro or plu) writes the
//!   synthetic file of `benches/formats.rs` to a temporary folder, reads it READS times (default
//!   20) with `read_file` and with `std::fs::read` in turn, and prints the median of each;
//! * `read_timing write FORMAT PATH` writes that file to PATH;
//! * `read_timing read_file PATH READS` and `read_timing fs_read PATH READS` only read PATH READS
//!   times, one way (two processes to compare as wholes, e.g. with `/usr/bin/time -v`).
//!
//! `cargo run --release -p stiction-topography --example read_timing -- nanoscope 30`

use std::path::Path;
use std::time::Instant;

use stiction_topography::{MapMetadata, read_file};

#[path = "../tests/support/synth.rs"]
mod synth;

const N: usize = 4096;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// The synthetic 4096 x 4096 file of `benches/formats.rs`: its usual name and bytes.
fn synthetic(which: &str) -> (&'static str, Vec<u8>) {
    let ints: Vec<i32> = (0..N * N).map(|k| ((k as i64 * 7919) % 60001 - 30000) as i32).collect();
    match which {
        "nanoscope" => ("map.spm", synth::nanoscope(N, N, 40960.0, 20.0, 10.0, 2, &ints)),
        "sdf" => {
            ("map.sdf", synth::sdf_binary(N, N, 1e-8, 1e-8, 1e-11, &ints.iter().map(|&v| v as i16).collect::<Vec<_>>()))
        }
        "ibw" => (
            "map.ibw",
            synth::ibw(
                N,
                N,
                1,
                1e-8,
                "m",
                "m",
                &["Height"],
                &ints.iter().map(|&v| v as f32 * 1e-12).collect::<Vec<_>>(),
            ),
        ),
        "metropro" => ("map.dat", synth::metropro(N, N, 1e-8, &ints)),
        "plu" => ("map.plu", synth::plu(N, N, 0.01, &ints.iter().map(|&v| Some(v as f32 * 1e-6)).collect::<Vec<_>>())),
        other => panic!("unknown format {other}: nanoscope, sdf, ibw, metropro or plu"),
    }
}

fn time_reads(path: &Path, reads: usize, with_read_file: bool) -> f64 {
    let meta = MapMetadata::default();
    let mut t = Vec::new();
    for _ in 0..reads {
        let start = Instant::now();
        if with_read_file {
            let (m, _) = read_file(path, None, &meta).unwrap();
            std::hint::black_box(m.nx());
        } else {
            let v = std::fs::read(path).unwrap();
            std::hint::black_box(v.len());
        }
        t.push(start.elapsed().as_secs_f64() * 1e3);
    }
    median(t)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |k: usize| args.get(k).map(String::as_str);
    match (arg(0), arg(1), arg(2)) {
        (Some("write"), Some(which), Some(path)) => std::fs::write(path, synthetic(which).1).unwrap(),
        (Some(how @ ("read_file" | "fs_read")), Some(path), reads) => {
            let reads = reads.and_then(|s| s.parse().ok()).unwrap_or(20);
            let ms = time_reads(Path::new(path), reads, how == "read_file");
            println!("{how} {path}: {ms:.1} ms (median of {reads})");
        }
        (which, reads, _) => {
            let which = which.unwrap_or("nanoscope");
            let reads: usize = reads.and_then(|s| s.parse().ok()).unwrap_or(20);
            let (file, bytes) = synthetic(which);
            let dir = std::env::temp_dir().join(format!("stiction-read-timing-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join(file);
            std::fs::write(&path, &bytes).unwrap();
            drop(bytes);
            let (mut a, mut b) = (Vec::new(), Vec::new());
            for _ in 0..reads {
                a.push(time_reads(&path, 1, true));
                b.push(time_reads(&path, 1, false));
            }
            let (ra, rb) = (median(a), median(b));
            println!(
                "{which}: read_file {ra:.1} ms, std::fs::read {rb:.1} ms, ratio {:.2} (medians of {reads})",
                ra / rb
            );
            std::fs::remove_dir_all(&dir).ok();
        }
    }
}
