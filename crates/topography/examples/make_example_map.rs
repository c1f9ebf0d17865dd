//! Writes the bundled example height map, `data/topography-example/wall.gsf`, with stiction's own
//! generator: a Gaussian random surface with a Gaussian autocorrelation, correlation length 0.2 um
//! and RMS height 20 nm, 640 x 200 pixels of 40 nm (25.6 um x 8 um), seed 2000, float32 heights
//! in metres (Gwyddion simple field).
//!
//! Run: `cargo run --release -p stiction-topography --example make_example_map [OUT.gsf]`.

use std::path::PathBuf;

use stiction_topography::{GeneratorSpec, Spectrum, generate};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let spec = GeneratorSpec {
        nx: 640,
        ny: 200,
        pixel_size_m: 40e-9,
        rms_height_m: 20e-9,
        spectrum: Spectrum::GaussianAcf { correlation_length_m: 0.2e-6 },
        seed: 2000,
    };
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../data/topography-example/wall.gsf"));
    let map = generate(&spec)?;
    stiction_units::io::write_atomic(&out, &map.to_gsf_bytes())?;
    eprintln!("wrote {} ({} x {} pixels)", out.display(), map.nx(), map.ny());
    Ok(())
}
