//! Times reading one 4096 x 4096 instrument file, for profiling (`perf stat`, `perf record`):
//! `cargo run --release -p stiction-topography --example read_timing -- nanoscope|sdf|ibw|metropro|plu [reads]`
//! writes the synthetic file of `benches/formats.rs` to a temporary folder, then reads it `reads`
//! times (default 20) with `read_file` and with `std::fs::read`, and prints the median of each.

use std::time::Instant;

use stiction_topography::{MapMetadata, read_file};

#[path = "../tests/support/synth.rs"]
mod synth;

const N: usize = 4096;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map(String::as_str).unwrap_or("nanoscope");
    let reads: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(20);
    let ints: Vec<i32> = (0..N * N).map(|k| ((k as i64 * 7919) % 60001 - 30000) as i32).collect();
    let (file, bytes) = match which {
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
    };
    drop(ints);
    let dir = std::env::temp_dir().join(format!("stiction-read-timing-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(file);
    std::fs::write(&path, &bytes).unwrap();
    drop(bytes);
    let meta = MapMetadata::default();
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _ in 0..reads {
        let t = Instant::now();
        let (m, _) = read_file(&path, None, &meta).unwrap();
        a.push(t.elapsed().as_secs_f64() * 1e3);
        drop(m);
        let t = Instant::now();
        let v = std::fs::read(&path).unwrap();
        b.push(t.elapsed().as_secs_f64() * 1e3);
        drop(v);
    }
    let (ra, rb) = (median(a), median(b));
    println!("{which}: read_file {ra:.1} ms, std::fs::read {rb:.1} ms, ratio {:.2} (medians of {reads})", ra / rb);
    std::fs::remove_dir_all(&dir).ok();
}
