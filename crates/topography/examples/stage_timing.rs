//! CPU time (user + system, from /proc/thread-self/stat, 10 ms resolution) and wall time of each
//! stage of the 4096 x 4096 pipeline, one thread: a cross-check of the criterion benchmarks on a
//! shared, loaded machine, where wall time overstates the work.
//!
//! Run: `cargo run --release -p stiction-topography --example stage_timing`.

use std::time::Instant;

use stiction_topography::*;

fn cpu_s() -> f64 {
    let s = std::fs::read_to_string("/proc/thread-self/stat").unwrap_or_default();
    let after = s.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = after.split_whitespace().collect();
    // fields 14 and 15 of stat (utime, stime) are 12 and 13 after the command name
    let t = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(f64::NAN);
    (t(11) + t(12)) / 100.0
}

fn timed<T>(name: &str, f: impl FnOnce() -> T) -> T {
    let (c0, w0) = (cpu_s(), Instant::now());
    let out = f();
    println!("{name:<28} cpu {:6.2} s   wall {:6.2} s", cpu_s() - c0, w0.elapsed().as_secs_f64());
    out
}

fn main() {
    let spec = GeneratorSpec {
        nx: 4096,
        ny: 4096,
        pixel_size_m: 10e-9,
        rms_height_m: 5e-9,
        spectrum: Spectrum::SelfAffine {
            hurst: 0.8,
            rolloff_wavelength_m: 2e-6,
            short_cutoff_wavelength_m: None,
            long_cutoff_wavelength_m: None,
        },
        seed: 1,
    };
    let map = timed("generate_4096", || generate(&spec).unwrap());
    let path = std::env::temp_dir().join(format!("stiction-timing-{}.npy", std::process::id()));
    std::fs::write(&path, map.to_npy_bytes(NpyDtype::F64, false)).unwrap();
    let meta = MapMetadata { pixel_size_x_m: Some(10e-9), height_unit_m: Some(1.0), ..Default::default() };
    let (m, _) = timed("  read npy", || read_file(&path, None, &meta).unwrap());
    let (p, _) = timed("  level plane", || prepare(&m, &Preparation::default()).unwrap());
    let s = timed("  summits", || find_summits(&p));
    println!("  ({} summits)", s.len());
    timed("read_level_summits_4096", || {
        let (m, _) = read_file(&path, None, &meta).unwrap();
        let (p, _) = prepare(&m, &Preparation::default()).unwrap();
        find_summits(&p).len()
    });
    timed("psd_4096", || radial_psd(&map, PsdWindow::Hann).f_per_m.len());
    timed("statistics_4096 (with ACF)", || statistics(&p, &s).rms_height_m);
    std::fs::remove_file(&path).ok();
}
