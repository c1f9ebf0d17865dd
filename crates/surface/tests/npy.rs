//! `.npy` summit files: fixtures written by NumPy itself (crates/surface/tools/npy_fixtures.py),
//! round trips, the scenario's `source` = "npy", and malformed files.

use std::path::{Path, PathBuf};

use stiction_surface::*;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

/// The fixture values, computed with the same float64 operations as the NumPy script.
fn expected() -> [Vec<f64>; 4] {
    let k: Vec<f64> = (0..5).map(f64::from).collect();
    [
        k.iter().map(|k| (k + 1.0) * 1.5e-6).collect(),
        k.iter().map(|k| (k + 1.0) * 0.5e-6).collect(),
        k.iter().map(|k| (k - 2.0) * 1.25e-8).collect(),
        k.iter().map(|k| 0.5e-6 + k * 0.1e-6).collect(),
    ]
}

fn read(name: &str) -> Result<NpySummits, SurfaceError> {
    read_npy_summits_file(&data(name), 1 << 20)
}

fn columns(s: NpySummits) -> [Vec<f64>; 4] {
    match s {
        NpySummits::Summits { x_m, y_m, height_m, radius_m } => [x_m, y_m, height_m, radius_m.unwrap_or_default()],
        NpySummits::Heights(h) => [vec![], vec![], h, vec![]],
    }
}

fn to_f32(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| f64::from(x as f32)).collect()
}

#[test]
fn numpy_written_fixtures_read_bit_for_bit() {
    // Written by np.save (NumPy 2.4.6): C order little-endian float64, Fortran order big-endian
    // float64, big-endian float32, a structured array of mixed field types and byte orders (one
    // field float32), a structured array without radius in another field order, heights alone.
    let e = expected();
    assert_eq!(columns(read("summits_f8_c.npy").unwrap()), e, "N x 4 <f8, C order");
    assert_eq!(columns(read("summits_f8_fortran_big_endian.npy").unwrap()), e, "N x 4 >f8, Fortran order");
    let f4 = columns(read("summits_f4_big_endian.npy").unwrap());
    for c in 0..4 {
        assert_eq!(f4[c], to_f32(&e[c]), "N x 4 >f4, column {c}");
    }
    let st = columns(read("summits_structured.npy").unwrap());
    assert_eq!(st[..3], e[..3], "structured x <f8, y >f8, height <f8");
    assert_eq!(st[3], to_f32(&e[3]), "structured radius <f4");
    let NpySummits::Summits { x_m, y_m, height_m, radius_m: None } = read("summits_structured_no_radius.npy").unwrap()
    else {
        panic!("expected summits without radii")
    };
    assert_eq!([x_m, y_m, height_m], [e[0].clone(), e[1].clone(), e[2].clone()], "fields height_m, x_m, y_m");
    assert_eq!(read("heights_f8.npy").unwrap(), NpySummits::Heights(e[2].clone()));
}

#[test]
fn wrong_dtypes_and_shapes_are_named() {
    let e = read("wrong_int64.npy").unwrap_err().to_string();
    assert!(e.contains("wrong_int64.npy") && e.contains("'<i8'") && e.contains("float64"), "{e}");
    let e = read("wrong_shape_n_by_3.npy").unwrap_err().to_string();
    assert!(e.contains("wrong_shape_n_by_3.npy") && e.contains("(5, 3)") && e.contains("(N, 4)"), "{e}");
}

fn table1() -> Surface {
    let layout = Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 3 };
    let lognormal = FaceParams {
        radius_sd_m: 0.2e-6,
        radius_distribution: RadiusDistribution::Lognormal,
        ..FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)
    };
    generate(&layout, &lognormal).unwrap()
}

#[test]
fn written_files_round_trip_bit_for_bit() {
    for s in [table1(), generate(&table1_layout(), &FaceParams::gaussian_fixed(4e12, 0.04e-6, 0.5e-6)).unwrap()] {
        let bytes = s.to_npy_bytes();
        // NumPy's layout: magic, version 1.0, header padded so the data starts at a multiple of 64.
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        let header_len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
        assert_eq!((10 + header_len) % 64, 0);
        assert_eq!(bytes.len(), 10 + header_len + 32 * s.len());
        let back = npy_surface(read_npy_summits(&bytes, "mem").unwrap(), "mem", 20e-6, 5e-6, None, |_| {
            panic!("positions are in the file")
        })
        .unwrap();
        assert_eq!(back, s);
        assert_eq!(back.content_hash(), s.content_hash());
    }
}

fn table1_layout() -> Layout {
    Layout { apparent_length_m: 20e-6, apparent_width_m: 5e-6, placement: Placement::Poisson, seed: 1 }
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("stiction-npy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn spec(extra: &str) -> SurfaceSpec {
    serde_json::from_str(&format!(
        r#"{{"apparent_length": "20 um", "apparent_width": "5 um", "source": "npy" {extra}}}"#
    ))
    .unwrap()
}

#[test]
fn scenario_source_npy_reads_relative_to_the_scenario() {
    let dir = tmp("spec");
    let s = table1();
    s.write_npy_file(&dir.join("summits.npy")).unwrap();
    let back = spec(r#", "npy_path": "summits.npy""#).build(&dir).unwrap();
    let parts = |s: &Surface| (s.xs_m().to_vec(), s.ys_m().to_vec(), s.heights_m().to_vec(), s.radii().clone());
    assert!(parts(&back) == parts(&s), "the scenario's npy surface differs from the written one");
    // The file gives the radii: a scenario radius as well is a contradiction.
    let e = spec(r#", "npy_path": "summits.npy", "summit_radius": "1 um""#).build(&dir).unwrap_err().to_string();
    assert!(e.contains("summits.npy") && e.contains("summit_radius") && e.contains("absent"), "{e}");
    // Statistical fields are refused.
    let e = spec(r#", "npy_path": "summits.npy", "summit_sd": "1 nm""#).build(&dir).unwrap_err().to_string();
    assert!(e.contains("summit_sd") && e.contains("npy"), "{e}");
    // npy_path with another source.
    let e = serde_json::from_str::<SurfaceSpec>(
        r#"{"apparent_length": "20 um", "apparent_width": "5 um", "source": "csv", "csv_path": "a.csv", "npy_path": "summits.npy"}"#,
    )
    .unwrap()
    .build(&dir)
    .unwrap_err()
    .to_string();
    assert!(e.contains("npy_path"), "{e}");
    // Heights alone: the scenario's radius, positions drawn uniformly from the seed.
    std::fs::copy(data("heights_f8.npy"), dir.join("h.npy")).unwrap();
    let e = spec(r#", "npy_path": "h.npy""#).build(&dir).unwrap_err().to_string();
    assert!(e.contains("h.npy") && e.contains("summit_radius"), "{e}");
    let h = spec(r#", "npy_path": "h.npy", "summit_radius": "0.5 um", "seed": 4"#).build(&dir).unwrap();
    assert_eq!(h.heights_m(), &expected()[2][..]);
    assert_eq!(h.radii(), &Radii::Uniform(0.5e-6));
    let layout = Layout { seed: 4, ..table1_layout() };
    let (xs, ys) = uniform_positions(&layout, 5);
    assert_eq!((h.xs_m(), h.ys_m()), (&xs[..], &ys[..]));
    // Summit budget: the file size is checked against max_summits x 32 bytes before reading.
    let e = spec(r#", "npy_path": "summits.npy", "max_summits": 3"#).build(&dir).unwrap_err().to_string();
    assert!(e.contains("summits.npy") && (e.contains("larger") || e.contains("limit")), "{e}");
    // A summit outside the apparent area names the row.
    let e = serde_json::from_str::<SurfaceSpec>(
        r#"{"apparent_length": "5 um", "apparent_width": "5 um", "source": "npy", "npy_path": "summits.npy"}"#,
    )
    .unwrap()
    .build(&dir)
    .unwrap_err()
    .to_string();
    assert!(e.contains("summits.npy") && e.contains("row") && e.contains("outside"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn malformed_files_give_clear_errors() {
    let good = table1().to_npy_bytes();
    let err = |b: &[u8]| read_npy_summits(b, "f.npy").unwrap_err().to_string();
    // Truncated data.
    let e = err(&good[..good.len() - 3]);
    assert!(e.contains("f.npy") && e.contains("truncated"), "{e}");
    // A huge declared shape with little data: refused before any allocation.
    let huge = npy_header("'<f8'", false, "(1000000000000000000, 4)");
    let e = err(&huge);
    assert!(e.contains("more than") || e.contains("too large"), "{e}");
    let huge = npy_header("'<f8'", false, "(4000000000, 4)");
    let e = err(&huge);
    assert!(e.contains("data bytes") && e.contains("truncated"), "{e}");
    // Not a .npy file, a header running past the end, a header that is not a dict.
    assert!(err(b"x_m,y_m,height_m,radius_m\n").contains("magic"));
    let mut b = good.clone();
    b[8] = 0xff;
    b[9] = 0xff;
    assert!(err(&b).contains("past the end"));
    let mut b = npy_header("'<f8'", false, "(1,)");
    b.extend_from_slice(&f64::NAN.to_le_bytes());
    assert!(err(&b).contains("not a finite"), "{}", err(&b));
    let b = npy_header("'<f8'", false, "(0,)");
    assert!(err(&b).contains("no summit"));
    let mut b = npy_header("[('x', '<f8'), ('y', '<f8')]", false, "(1,)");
    b.extend_from_slice(&[0u8; 16]);
    assert!(err(&b).contains("height"), "{}", err(&b));
    let mut b = npy_header("[('x', '<f8'), ('y', '<f8'), ('height', '<f8'), ('id', '<i8')]", false, "(1,)");
    b.extend_from_slice(&[0u8; 32]);
    assert!(err(&b).contains("'id'"), "{}", err(&b));
}
