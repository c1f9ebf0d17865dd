//! `.npy` summit files end to end: `stiction surface --npy`, a scenario with "source": "npy",
//! `stiction topography --summits FILE.npy`, and a broken file.

use crate::util::{num, stiction, stiction_json, temp_dir};

fn from_npy_sets(npy: &std::path::Path) -> Vec<String> {
    [
        "surface.source=\"npy\"".to_string(),
        format!("surface.npy_path={:?}", npy.to_str().unwrap()),
        "surface.summit_density=null".into(),
        "surface.summit_sd=null".into(),
        "surface.summit_radius=null".into(),
    ]
    .into_iter()
    .flat_map(|s| ["--set".to_string(), s])
    .collect()
}

#[test]
fn summits_written_as_npy_give_the_same_contact_and_hash() {
    let dir = temp_dir("surface-npy");
    let npy = dir.join("summits.npy");
    let out = stiction(&["surface", "scenarios/tas2000.json", "--npy", npy.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let bytes = std::fs::read(&npy).unwrap();
    assert!(bytes.starts_with(b"\x93NUMPY\x01\x00"));
    let sets = from_npy_sets(&npy);
    let mut args = vec!["surface", "scenarios/tas2000.json", "--json"];
    let generated = stiction_json(&args);
    args.extend(sets.iter().map(String::as_str));
    let read = stiction_json(&args);
    assert_eq!(generated["content_hash"], read["content_hash"], "the same summits, bit for bit");
    assert_eq!(num(&read["stats"], "count"), num(&generated["stats"], "count"));
    let mut args = vec!["contact", "scenarios/tas2000.json", "--load", "3 uN", "--json"];
    let generated = stiction_json(&args);
    args.extend(sets.iter().map(String::as_str));
    let from_npy = stiction_json(&args);
    for key in ["friction_capacity_n", "real_area_m2", "separation_m", "tilt_x_rad", "tilt_y_rad", "contacts"] {
        assert_eq!(generated[key], from_npy[key], "{key}");
    }
}

#[test]
fn a_truncated_npy_is_refused_with_exit_2_naming_the_file() {
    let dir = temp_dir("surface-npy-bad");
    let npy = dir.join("cut.npy");
    let out = stiction(&["surface", "scenarios/tas2000.json", "--npy", npy.to_str().unwrap()]);
    assert!(out.status.success());
    let bytes = std::fs::read(&npy).unwrap();
    std::fs::write(&npy, &bytes[..bytes.len() - 20]).unwrap();
    let sets = from_npy_sets(&npy);
    let mut args = vec!["surface", "scenarios/tas2000.json"];
    args.extend(sets.iter().map(String::as_str));
    let out = stiction(&args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("cut.npy") && err.contains("truncated"), "{err}");
    // A folder instead of a file.
    let sets = from_npy_sets(&dir);
    let mut args = vec!["surface", "scenarios/tas2000.json"];
    args.extend(sets.iter().map(String::as_str));
    let out = stiction(&args);
    assert_eq!(out.status.code(), Some(2), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn topography_writes_npy_summits_when_the_name_ends_in_npy() {
    let dir = temp_dir("topography-summits-npy");
    let (csv, npy) = (dir.join("s.csv"), dir.join("s.npy"));
    for f in [&csv, &npy] {
        let out = stiction(&[
            "topography",
            "data/topography-example/wall.gsf",
            "--cutoff",
            "80 nm",
            "--summits",
            f.to_str().unwrap(),
        ]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let rows = std::fs::read_to_string(&csv).unwrap().lines().count() - 1;
    let bytes = std::fs::read(&npy).unwrap();
    assert!(bytes.starts_with(b"\x93NUMPY"));
    let header = String::from_utf8_lossy(&bytes[10..128]);
    assert!(header.contains(&format!("'shape': ({rows}, 4)")) && header.contains("'<f8'"), "{header}");
    let header_len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
    assert_eq!(bytes.len(), 10 + header_len + rows * 32);
}
