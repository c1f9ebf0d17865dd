//! Reading an instrument file in parts (the header, then the chosen channel's samples straight
//! into the map, the route `read_file` takes for a file over 512 KiB) gives the whole-file route's
//! result bit for bit: every height's bits, the grid, the pixel sizes and the metadata, or the
//! same error. Held on every shared instrument file (every channel, several header prefixes, so
//! that the first parse sees from a few bytes to the whole header), on synthetic files that take
//! each branch of the decoder (rows flipped along y and x, padded rows, rows longer than a chunk,
//! missing-pixel markers), and through `read_file` on a file larger than the prefix. The fuzz
//! harness (`fuzz.rs`) holds the two routes equal on its mutated files too.

use std::path::Path;

use stiction_topography::{
    ChannelSelector, HeightMap, MapFormat, MapInfo, MapMetadata, TopographyError, detect, list_channels, read_file,
    read_instrument, read_instrument_in_parts,
};

#[path = "support/synth.rs"]
mod synth;

/// A result as comparable text: every height's bits, the grid, the pixel sizes' bits and the
/// metadata, or the error.
fn fingerprint(r: &Result<(HeightMap, MapInfo), TopographyError>) -> String {
    match r {
        Ok((m, info)) => {
            let h = m
                .heights_m()
                .iter()
                .fold(0xcbf2_9ce4_8422_2325u64, |a, x| (a ^ x.to_bits()).wrapping_mul(0x0100_0000_01b3));
            format!(
                "{} x {} dx {:x} dy {:x} heights {h:x} {info:?}",
                m.nx(),
                m.ny(),
                m.dx_m().to_bits(),
                m.dy_m().to_bits()
            )
        }
        Err(e) => format!("error: {e}"),
    }
}

/// Both routes on `bytes`, each prefix; returns how many prefixes read the samples in parts.
fn same_both_ways(
    bytes: &[u8],
    format: MapFormat,
    ch: Option<&ChannelSelector>,
    meta: &MapMetadata,
    what: &str,
) -> usize {
    let whole = fingerprint(&read_instrument(bytes, format, "f", ch, meta));
    let mut in_parts = 0;
    for prefix in [16, 512, 4096, 1 << 16, 1 << 20] {
        let (r, parts) = read_instrument_in_parts(bytes, prefix, format, "f", ch, meta);
        assert_eq!(fingerprint(&r), whole, "{what}, channel {ch:?}, prefix {prefix}");
        in_parts += usize::from(parts);
    }
    in_parts
}

#[test]
fn every_shared_instrument_file_reads_the_same_in_parts() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/topography-formats");
    let mut files = 0;
    let mut read_in_parts = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let Some(format) = detect(&bytes) else { continue };
        let Ok((_, list)) = list_channels(&path, None, &MapMetadata::default()) else { continue };
        files += 1;
        // A file that states no unit or pixel size is read with both given.
        let given = MapMetadata { pixel_size_x_m: Some(1e-8), height_unit_m: Some(1e-9), ..MapMetadata::default() };
        for meta in [MapMetadata::default(), given] {
            for k in 0..list.len() {
                let sel = ChannelSelector::Index(k);
                read_in_parts += same_both_ways(&bytes, format, Some(&sel), &meta, &path.display().to_string());
            }
            read_in_parts += same_both_ways(&bytes, format, None, &meta, &path.display().to_string());
        }
    }
    assert!(files >= 14, "{files} instrument files in {}", dir.display());
    // Most channels are rasters read in parts once the prefix holds their header.
    assert!(read_in_parts > 40, "{read_in_parts} reads in parts");
}

fn ints(n: usize) -> Vec<i32> {
    (0..n).map(|k| ((k as i64 * 7919) % 60001 - 30000) as i32).collect()
}

#[test]
fn each_branch_of_the_decoder_reads_the_same_in_parts() {
    let meta = MapMetadata::default();
    let nm = MapMetadata { height_unit_m: Some(1e-9), ..meta };
    // Rows flipped along y (NanoScope), 2-byte samples, several chunks of whole rows.
    let (nx, ny) = (300, 700);
    let v = ints(nx * ny);
    let spm = synth::nanoscope(nx, ny, 40960.0, 20.0, 10.0, 2, &v);
    assert!(same_both_ways(&spm, MapFormat::Nanoscope, None, &meta, "nanoscope") >= 2);
    // Big-endian int32 with the invalid-phase marker (MetroPro).
    let mut phase = ints(nx * ny);
    phase[7] = 2_147_483_641;
    let dat = synth::metropro(nx, ny, 1e-8, &phase);
    assert!(same_both_ways(&dat, MapFormat::Metropro, None, &meta, "metropro") >= 2);
    // Float32 with the non-measured marker (Sensofar).
    let h: Vec<Option<f32>> = v.iter().enumerate().map(|(k, &x)| (k % 97 != 0).then_some(x as f32 * 1e-4)).collect();
    let plu = synth::plu(nx, ny, 0.5, &h);
    assert!(same_both_ways(&plu, MapFormat::Plu, None, &meta, "plu") >= 2);
    // WSxM (rows flipped along x and y) is read whole: its listing needs bytes of its samples
    // (the line end after `[Header end]`; an int16 image's scale is the Z amplitude over the
    // samples' range). The route in parts gave other bits for int16 before it declined, and the
    // fuzz harness found a file whose samples started two bytes later. Float64 rows longer than a
    // chunk (20,000 x 8 bytes) and short int16 rows, whole.
    let (wx, wy) = (20_000, 3);
    let samples: Vec<u8> = (0..wx * wy).flat_map(|k| ((k % 1013) as f64 * 0.25 - 100.0).to_le_bytes()).collect();
    let stp = synth::wsxm(wx, wy, 2000.0, "1 nm", "double", &samples);
    assert_eq!(same_both_ways(&stp, MapFormat::Wsxm, None, &nm, "wsxm wide"), 0);
    // Each height of the wide map is its sample in nm (double, Z amplitude in nm: scale 1), the
    // map turned by 180 degrees: pixel (ix, iy) is the file's sample (nx-1-ix, ny-1-iy). Exact.
    let (m, _) = read_instrument(&stp, MapFormat::Wsxm, "f", None, &nm).unwrap();
    for iy in 0..wy {
        for ix in 0..wx {
            let k = (wy - 1 - iy) * wx + (wx - 1 - ix);
            let want = ((k % 1013) as f64 * 0.25 - 100.0) * 1e-9;
            assert_eq!(m.at(ix, iy).to_bits(), want.to_bits(), "wsxm wide ({ix}, {iy})");
        }
    }
    let (sx, sy) = (101, 40);
    let samples: Vec<u8> = (0..sx * sy).flat_map(|k| ((k % 17) as i16 - 8).to_le_bytes()).collect();
    let stp = synth::wsxm(sx, sy, 2000.0, "10 nm", "short", &samples);
    assert_eq!(same_both_ways(&stp, MapFormat::Wsxm, None, &nm, "wsxm int16"), 0);
    // Padded rows (Alicona: 4-byte samples in rows of a multiple of 8 bytes), long and short,
    // with invalid pixels.
    for (ax, ay) in [(40_001, 2), (301, 50)] {
        let d: Vec<f32> =
            (0..ax * ay).map(|k| if k % 31 == 0 { 3.0e15_f32 } else { (k % 211) as f32 * 1e-9 }).collect();
        let al3d = synth::al3d(ax, ay, 1e-6, &d);
        assert!(same_both_ways(&al3d, MapFormat::Al3d, None, &meta, "al3d") >= 2);
        // Each height is its float32 depth in metres, NaN where invalid; row 0 first. Exact.
        let (parts, _) = read_instrument_in_parts(&al3d, 4096, MapFormat::Al3d, "f", None, &meta);
        let (m, _) = parts.unwrap();
        for (k, (&h, &want)) in m.heights_m().iter().zip(&d).enumerate() {
            let want = if want == 3.0e15 { f64::NAN } else { f64::from(want) };
            assert_eq!(h.to_bits(), want.to_bits(), "al3d {ax} x {ay}, pixel {k}");
        }
    }
}

#[test]
fn read_file_takes_the_route_in_parts_and_gives_the_whole_route_s_map() {
    let (nx, ny) = (512, 520);
    let v = ints(nx * ny);
    let dir = std::env::temp_dir().join(format!("stiction-parts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let files = [
        ("map.spm", synth::nanoscope(nx, ny, 40960.0, 20.0, 10.0, 2, &v)),
        ("map.sdf", synth::sdf_binary(nx, ny, 1e-8, 1e-8, 1e-11, &v.iter().map(|&x| x as i16).collect::<Vec<_>>())),
        (
            "map.ibw",
            synth::ibw(
                nx,
                ny,
                1,
                1e-8,
                "m",
                "m",
                &["Height"],
                &v.iter().map(|&x| x as f32 * 1e-12).collect::<Vec<_>>(),
            ),
        ),
        ("map.dat", synth::metropro(nx, ny, 1e-8, &v)),
    ];
    for (name, bytes) in files {
        assert!(bytes.len() > 1 << 19, "{name}: {} bytes, not over the 512 KiB of the route in parts", bytes.len());
        let path = dir.join(name);
        std::fs::write(&path, &bytes).unwrap();
        let format = detect(&bytes).unwrap();
        let via_file = read_file(&path, None, &MapMetadata::default());
        let whole = read_instrument(&bytes, format, &path.display().to_string(), None, &MapMetadata::default());
        assert!(via_file.is_ok(), "{name}: {:?}", via_file.err());
        assert_eq!(fingerprint(&via_file), fingerprint(&whole), "{name}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
