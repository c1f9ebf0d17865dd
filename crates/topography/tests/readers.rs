//! Readers: the same map in every supported format gives the same statistics (to the last bit, or
//! to float32 rounding for the float32 formats); malformed files give clear errors.

use stiction_topography::*;

/// A 64 x 32 map (powers of two, so `nx dx / nx == dx` exactly) with 0.25 um pixels and a few
/// missing pixels.
fn sample_map() -> HeightMap {
    let dx = parse_length_unit("0.25 um").unwrap();
    let g = generate(&GeneratorSpec {
        nx: 64,
        ny: 32,
        pixel_size_m: dx,
        rms_height_m: 20e-9,
        spectrum: Spectrum::GaussianAcf { correlation_length_m: 1e-6 },
        seed: 11,
    })
    .unwrap();
    let mut h = g.heights_m().to_vec();
    for k in [5, 100, 777, 1500] {
        h[k] = f64::NAN;
    }
    // A tilt, so that levelling has work to do.
    for (k, z) in h.iter_mut().enumerate() {
        *z += 1e-9 * (k % 64) as f64;
    }
    HeightMap::new(64, 32, dx, dx, h).unwrap()
}

fn stats_json(map: &HeightMap) -> String {
    let (p, _) = prepare(map, &Preparation { levelling: Levelling::Plane, ..Default::default() }).unwrap();
    let s = find_summits(&p);
    serde_json::to_string(&statistics(&p, &s)).unwrap()
}

fn f32_rounded(map: &HeightMap) -> HeightMap {
    let h = map.heights_m().iter().map(|&z| f64::from(z as f32)).collect();
    HeightMap::new(map.nx(), map.ny(), map.dx_m(), map.dy_m(), h).unwrap()
}

fn meta_pixel() -> MapMetadata {
    MapMetadata {
        pixel_size_x_m: Some(parse_length_unit("0.25 um").unwrap()),
        height_unit_m: Some(1.0),
        ..Default::default()
    }
}

#[test]
fn every_format_gives_the_same_statistics() {
    let map = sample_map();
    let want = stats_json(&map);
    let want32 = stats_json(&f32_rounded(&map));
    assert_ne!(want, want32, "the float32 rounding is visible, so the comparison below can fail");

    for fortran in [false, true] {
        let (m, info) = read_npy(&map.to_npy_bytes(NpyDtype::F64, fortran), "t.npy", &meta_pixel()).unwrap();
        assert_eq!(info.missing_pixels, 4);
        assert_eq!(stats_json(&m), want, "npy float64 fortran={fortran}");
        let (m, _) = read_npy(&map.to_npy_bytes(NpyDtype::F32, fortran), "t.npy", &meta_pixel()).unwrap();
        assert_eq!(stats_json(&m), want32, "npy float32 fortran={fortran}");
    }
    // Text grid with Gwyddion's header: pixel size and unit from the file.
    let (m, info) = read_text_grid(&map.to_text_grid(), "t.txt", &MapMetadata::default()).unwrap();
    assert_eq!(info.pixel_size_from, MetaSource::File);
    assert_eq!(stats_json(&m), want, "text grid");
    // The same grid as CSV without a header, metadata from flags.
    let csv: String =
        map.to_text_grid().lines().filter(|l| !l.starts_with('#')).map(|l| l.replace('\t', ",") + "\n").collect();
    let (m, info) = read_text_grid(&csv, "t.csv", &meta_pixel()).unwrap();
    assert_eq!(info.pixel_size_from, MetaSource::Given);
    assert_eq!(stats_json(&m), want, "csv grid");
    // Space-separated in nm (height unit from the flag).
    let nm: String = (0..map.ny())
        .map(|iy| map.row(iy).iter().map(|z| format!("{}", z * 1e9)).collect::<Vec<_>>().join(" ") + "\n")
        .collect();
    let meta_nm = MapMetadata { height_unit_m: Some(1e-9), ..meta_pixel() };
    let (m, _) = read_text_grid(&nm, "t.txt", &meta_nm).unwrap();
    let max_diff = m
        .heights_m()
        .iter()
        .zip(map.heights_m())
        .filter(|(a, _)| !a.is_nan())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(max_diff < 1e-22, "nm text differs by {max_diff} m (only the nm -> m rounding)");
    // Gwyddion simple field: float32.
    let (m, info) = read_gsf(&map.to_gsf_bytes(), "t.gsf", &MapMetadata::default()).unwrap();
    assert_eq!((info.pixel_size_from, info.height_unit_from), (MetaSource::File, MetaSource::File));
    assert_eq!(stats_json(&m), want32, "gsf");
    // x-y-z list in um (coordinates k * 0.25 are exact in binary), heights in m, in reverse order.
    let mut lines: Vec<String> = vec!["x,y,z".into()];
    for iy in 0..map.ny() {
        for ix in 0..map.nx() {
            let z = map.at(ix, iy);
            if !z.is_nan() {
                lines.push(format!("{},{},{}", ix as f64 * 0.25, iy as f64 * 0.25, z));
            }
        }
    }
    lines[1..].reverse();
    let meta_xyz = MapMetadata { xy_unit_m: Some(1e-6), height_unit_m: Some(1.0), ..Default::default() };
    let (m, info) = read_xyz(&(lines.join("\n") + "\n"), "t.xyz", &meta_xyz).unwrap();
    assert_eq!(info.missing_pixels, 4);
    assert_eq!(stats_json(&m), want, "xyz");
}

/// Fixtures written by other programs (crates/topography/tools/make_reader_fixtures.py): .npy by
/// numpy's np.save (C and Fortran order, little- and big-endian, float64 and float32) and a .gsf
/// written from Gwyddion's documented layout. The map is known in closed form,
/// z(ix, iy) = (ix + 100 iy + 0.5) nm on 5 columns x 3 rows (every value distinct, non-square), with
/// one missing pixel at (3, 1) in the .npy files; every pixel is checked at its place, exactly (to
/// float32 rounding for the float32 files), so a row/column or byte-order bug in the readers fails
/// even when this crate's writers share it.
#[test]
fn fixtures_written_by_numpy_and_to_gwyddions_spec_read_pixel_by_pixel() {
    let known = |ix: usize, iy: usize| (ix as f64 + 100.0 * iy as f64 + 0.5) * 1e-9;
    let check = |m: &HeightMap, what: &str, float32: bool, missing: Option<(usize, usize)>| {
        assert_eq!((m.nx(), m.ny()), (5, 3), "{what}: shape");
        for iy in 0..3 {
            for ix in 0..5 {
                let got = m.at(ix, iy);
                if missing == Some((ix, iy)) {
                    assert!(got.is_nan(), "{what}: ({ix}, {iy}) should be missing, got {got}");
                    continue;
                }
                let want = if float32 { f64::from(known(ix, iy) as f32) } else { known(ix, iy) };
                assert_eq!(got, want, "{what}: z({ix}, {iy})");
            }
        }
    };
    for (name, bytes, float32) in [
        ("known_c_f8.npy", &include_bytes!("fixtures/known_c_f8.npy")[..], false),
        ("known_fortran_f8.npy", &include_bytes!("fixtures/known_fortran_f8.npy")[..], false),
        ("known_big_f8.npy", &include_bytes!("fixtures/known_big_f8.npy")[..], false),
        ("known_c_f4.npy", &include_bytes!("fixtures/known_c_f4.npy")[..], true),
        ("known_big_fortran_f4.npy", &include_bytes!("fixtures/known_big_fortran_f4.npy")[..], true),
    ] {
        let (m, info) = read_npy(bytes, name, &meta_pixel()).unwrap();
        assert_eq!(info.missing_pixels, 1, "{name}");
        check(&m, name, float32, Some((3, 1)));
    }
    let (m, info) = read_gsf(include_bytes!("fixtures/known.gsf"), "known.gsf", &MapMetadata::default()).unwrap();
    assert_eq!((info.pixel_size_from, info.height_unit_from), (MetaSource::File, MetaSource::File));
    assert!((m.dx_m() / 0.25e-6 - 1.0).abs() < 1e-12 && (m.dy_m() / 0.25e-6 - 1.0).abs() < 1e-12);
    check(&m, "known.gsf", true, None);
}

#[test]
fn files_are_read_through_the_checked_reader() {
    let dir = std::env::temp_dir().join(format!("stiction-topo-read-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = sample_map();
    let p = dir.join("m.gsf");
    std::fs::write(&p, map.to_gsf_bytes()).unwrap();
    let (m, info) = read_file(&p, None, &MapMetadata::default()).unwrap();
    assert_eq!((m.nx(), m.ny(), info.format), (64, 32, MapFormat::Gsf));
    // A folder is refused before reading.
    let e = read_file(&dir, Some(MapFormat::Npy), &meta_pixel()).unwrap_err().to_string();
    assert!(e.contains("folder"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

fn err(r: Result<(HeightMap, MapInfo), TopographyError>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn malformed_files_give_clear_errors() {
    let map = sample_map();
    let m = meta_pixel();
    // npy
    let e = err(read_npy(b"PK\x03\x04 not npy at all", "a.npy", &m));
    assert!(e.contains("a.npy") && e.contains("magic"), "{e}");
    let mut b = map.to_npy_bytes(NpyDtype::F64, false);
    let hdr = String::from_utf8_lossy(&b[10..80]).replace("<f8", "<i4");
    b[10..80].copy_from_slice(hdr.as_bytes());
    let e = err(read_npy(&b, "a.npy", &m));
    assert!(e.contains("`<i4`") && e.contains("float32 or float64"), "{e}");
    let b = map.to_npy_bytes(NpyDtype::F64, false);
    let e = err(read_npy(&b[..b.len() - 8], "a.npy", &m));
    assert!(e.contains("data bytes") && e.contains("64 x 32 x 8"), "{e}");
    // An absurd shape is refused from the header, before any allocation.
    let mut b = map.to_npy_bytes(NpyDtype::F64, false);
    let hdr = String::from_utf8_lossy(&b[10..80]).replace("(32, 64)", "(99999, 99999)");
    let hdr = hdr[..70].to_string();
    b[10..80].copy_from_slice(hdr.as_bytes());
    let e = err(read_npy(&b, "a.npy", &m));
    assert!(e.contains("99999 x 99999") && e.contains("limit"), "{e}");
    // Missing metadata says what is missing and how to give it.
    let e = err(read_npy(&map.to_npy_bytes(NpyDtype::F64, false), "a.npy", &MapMetadata::default()));
    assert!(e.contains("missing metadata") && e.contains("pixel size") && e.contains("--pixel-size"), "{e}");
    let no_unit = MapMetadata { height_unit_m: None, ..m };
    let e = err(read_npy(&map.to_npy_bytes(NpyDtype::F64, false), "a.npy", &no_unit));
    assert!(e.contains("height unit") && e.contains("--height-unit"), "{e}");
    // Text: ragged row, bad number, conflicting pixel size.
    let e = err(read_text_grid("1 2 3\n4 5\n", "g.txt", &m));
    assert!(e.contains("g.txt, line 2") && e.contains("same length"), "{e}");
    let e = err(read_text_grid("1,2,3\n4,x5,6\n", "g.csv", &m));
    assert!(e.contains("line 2") && e.contains("`x5`"), "{e}");
    let e = err(read_text_grid("1,2,inf\n4,5,6\n", "g.csv", &m));
    assert!(e.contains("line 1") && e.contains("`inf`"), "{e}");
    let e = err(read_text_grid("# Width: 10 um\n# Height: 2 um\n# Value units: m\n1 2\n3 4\n", "g.txt", &m));
    assert!(e.contains("`pixel size`") && e.contains("the value in g.txt"), "{e}");
    let e = err(read_text_grid("# Value units: V\n1 2\n3 4\n", "g.txt", &m));
    assert!(e.contains("line 1") && e.contains("Value units"), "{e}");
    // GSF: wrong magic, missing key, truncated data.
    let e = err(read_gsf(b"Gwyddion Simple Field 2.0\n", "f.gsf", &m));
    assert!(e.contains("f.gsf, line 1") && e.contains("not a Gwyddion simple field"), "{e}");
    let e = err(read_gsf(b"Gwyddion Simple Field 1.0\nYRes = 2\n\0\0\0", "f.gsf", &m));
    assert!(e.contains("`XRes` is missing"), "{e}");
    let g = map.to_gsf_bytes();
    let e = err(read_gsf(&g[..g.len() - 3], "f.gsf", &m));
    assert!(e.contains("data bytes") && e.contains("8192"), "{e}");
    // xyz: irregular grid, missing xy unit, duplicate point.
    let xyz = MapMetadata { xy_unit_m: Some(1e-6), height_unit_m: Some(1.0), ..Default::default() };
    let e = err(read_xyz("0 0 1\n1 0 1\n2.5 0 1\n0 1 1\n1 1 1\n2.5 1 1\n", "p.xyz", &xyz));
    assert!(e.contains("not on a regular grid"), "{e}");
    let e = err(read_xyz("0 0 1\n1 0 1\n0 1 1\n1 1 1\n", "p.xyz", &MapMetadata::default()));
    assert!(e.contains("--xy-unit"), "{e}");
    let e = err(read_xyz("0 0 1\n1 0 1\n0 1 1\n1 1 1\n1 1 2\n", "p.xyz", &xyz));
    assert!(e.contains("appears twice"), "{e}");
    let e = err(read_xyz("0 0 1\n1 0 1\n0 1\n", "p.xyz", &xyz));
    assert!(e.contains("line 3"), "{e}");
}

#[test]
fn bundled_example_map_is_the_generators_output() {
    // data/topography-example/README.md: the exact generator call (examples/make_example_map.rs).
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/topography-example/wall.gsf");
    let shipped = std::fs::read(&path).unwrap();
    let map = generate(&GeneratorSpec {
        nx: 640,
        ny: 200,
        pixel_size_m: 40e-9,
        rms_height_m: 20e-9,
        spectrum: Spectrum::GaussianAcf { correlation_length_m: 0.2e-6 },
        seed: 2000,
    })
    .unwrap();
    assert!(
        shipped == map.to_gsf_bytes(),
        "regenerate with `cargo run --release -p stiction-topography --example make_example_map`"
    );
}
