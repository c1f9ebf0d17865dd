//! A seeded structured-mutation fuzzer over the height-map formats (stable Rust, no extra tool),
//! in the style of `crates/meter/tests/fuzz.rs`: `.npy` headers, dtypes, shapes and data; `.gsf`
//! keys and padding; text grids (cells, headers, delimiters, rows, long lines); x-y-z lists;
//! NanoScope headers (offsets, lengths, sizes, scale chains set huge or nonsense, the end marker
//! removed), Igor binary wave headers (section sizes, dimensions, number type, pixel steps, units,
//! with the checksum fixed four times in five), SDF (ASCII keys and values, binary header
//! fields) X3P (main.xml values, nesting, inline data, truncated points, declared sizes) , Digital Surf
//! (header fields, steps, units, the compressed magic) and Wyko OPD (block lengths, types, names,
//! array sizes), each also truncated and byte-flipped. Each
//! case starts from a valid file written by this crate's writers, applies one to three mutations
//! and goes through the library code the binary calls (`read_npy`, `read_gsf`, `read_text_grid`,
//! `read_xyz`, then `prepare` with hostile cut-offs, `find_summits` and `statistics`). The contract:
//!
//! * no panic (caught and reported with the case);
//! * bounded time (each case under [`CASE_TIME_LIMIT`]);
//! * an error names the file, is short (under [`MAX_ERROR_CHARS`]) and never holds the secret
//!   marker a mutation planted in the file (no echo beyond a short excerpt);
//! * a success has no NaN or infinity in its statistics (a value that cannot be computed is null).
//!
//! Short mode (the default, 1500 cases per format, a few seconds in release) runs in `cargo test`;
//! `STICTION_FUZZ_CASES=20000 STICTION_FUZZ_SEED=1` gives a long run (cases per format), see
//! docs/reliability.md.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use stiction_topography::{
    ChannelSelector, HeightMap, Levelling, MapFormat, MapInfo, MapMetadata, NpyDtype, Preparation, TopographyError,
    detect, find_summits, prepare, read_gsf, read_instrument, read_instrument_in_parts, read_npy, read_text_grid,
    read_xyz, statistics,
};

#[path = "support/synth.rs"]
mod synth;

/// Longest a single case may take.
const CASE_TIME_LIMIT: Duration = Duration::from_secs(10);

/// Longest error message accepted (the origin is short here).
const MAX_ERROR_CHARS: usize = 400;

/// Planted in files by mutations; an error must never quote it whole.
const SECRET: &str = "SECRET-do-not-echo-this-line-0123456789";

const ORIGIN: &str = "fuzz-map";

/// The instrument formats (read through `read_instrument`); every one has a fuzz test below.
const INSTRUMENT: &[&str] =
    &["nanoscope", "ibw", "sdf", "x3p", "sur", "opd", "plu", "metropro", "netcdf", "wsxm", "mi", "nid", "al3d", "park"];

/// SplitMix64, as in the meter's fuzzer.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
    fn chance(&mut self, one_in: usize) -> bool {
        self.below(one_in) == 0
    }
}

fn cases() -> usize {
    std::env::var("STICTION_FUZZ_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(1500)
}

fn seed() -> u64 {
    std::env::var("STICTION_FUZZ_SEED").ok().and_then(|s| s.parse().ok()).unwrap_or(20)
}

/// Numbers and words a hostile file holds.
const NASTY: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e-308",
    "5e-324",
    "1e308",
    "1e400",
    "-1e400",
    "inf",
    "-inf",
    "NaN",
    "nan",
    "",
    " ",
    "1,5",
    "0x10",
    "1e",
    "--1",
    "+",
    "4294967296",
    "18446744073709551616",
    "99999999999999999999999",
    "1.0.0",
    "µm",
    "nm",
    "furlong",
    "m^2",
    "1e300 m",
    "1e-300 m",
    "5 um",
    "-5 um",
    SECRET,
    "\u{202e}evil",
    "\u{1b}[2J",
];

/// A small random map: `nx x ny` in 2..=24, heights in nm with a few missing pixels.
fn base_map(rng: &mut Rng) -> HeightMap {
    let nx = 2 + rng.below(23);
    let ny = 2 + rng.below(23);
    let heights = (0..nx * ny)
        .map(|k| {
            if rng.chance(40) {
                f64::NAN
            } else {
                let (x, y) = ((k % nx) as f64, (k / nx) as f64);
                1e-9 * (5.0 * (0.7 * x + 0.3 * y).sin() + (rng.below(1000) as f64) / 100.0)
            }
        })
        .collect();
    HeightMap::new(nx, ny, 1e-8, 1e-8 * (1.0 + rng.below(3) as f64), heights).unwrap()
}

/// The metadata a format needs from outside the file (two cases in three), else random.
fn meta(rng: &mut Rng, format: &str) -> MapMetadata {
    if !rng.chance(3) {
        return match format {
            "npy" => MapMetadata { pixel_size_x_m: Some(1e-8), height_unit_m: Some(1.0), ..Default::default() },
            "xyz" => MapMetadata { height_unit_m: Some(1.0), xy_unit_m: Some(1.0), ..Default::default() },
            _ => MapMetadata::default(),
        };
    }
    random_meta(rng)
}

fn random_meta(rng: &mut Rng) -> MapMetadata {
    let len = [None, Some(1e-8), Some(1e-300), Some(1e300), Some(1.0), Some(2e-9)];
    let unit = [None, Some(1e-9), Some(1.0), Some(1e-300), Some(1e300)];
    MapMetadata {
        pixel_size_x_m: *rng.pick(&len),
        pixel_size_y_m: if rng.chance(3) { *rng.pick(&len) } else { None },
        height_unit_m: *rng.pick(&unit),
        xy_unit_m: *rng.pick(&unit),
    }
}

/// Random byte edits: flip, insert, delete, truncate, append.
fn byte_noise(rng: &mut Rng, b: &mut Vec<u8>) {
    if b.is_empty() {
        b.push(rng.next() as u8);
        return;
    }
    match rng.below(5) {
        0 => {
            let k = rng.below(b.len());
            b[k] ^= 1 << rng.below(8);
        }
        1 => {
            let k = rng.below(b.len() + 1);
            b.insert(k, rng.next() as u8);
        }
        2 => {
            let k = rng.below(b.len());
            b.remove(k);
        }
        3 => b.truncate(rng.below(b.len())),
        _ => b.extend(std::iter::repeat_n(rng.next() as u8, 1 + rng.below(64))),
    }
}

fn npy_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let dtype = if rng.chance(2) { NpyDtype::F32 } else { NpyDtype::F64 };
    let mut b = map.to_npy_bytes(dtype, rng.chance(2));
    let header_end = 10 + u16::from_le_bytes([b[8], b[9]]) as usize;
    let header = String::from_utf8_lossy(&b[10..header_end]).into_owned();
    let data = b[header_end..].to_vec();
    let mut h = header.clone();
    for _ in 0..1 + rng.below(3) {
        match rng.below(9) {
            0 => {
                let d = rng.pick(&[
                    "'<f2'", "'|u1'", "'<i8'", "'<c16'", "'>f8'", "'>f4'", "'=f8'", "<f8", "''", "'<f8", SECRET,
                ]);
                h = h.replacen(if h.contains("<f4") { "'<f4'" } else { "'<f8'" }, d, 1);
            }
            1 => {
                let s = rng.pick(&[
                    "(0, 5)",
                    "(1, 3)",
                    "(3,)",
                    "(2, 2, 2)",
                    "()",
                    "(-1, 2)",
                    "(18446744073709551615, 2)",
                    "(100000, 100000)",
                    "(4294967296, 4294967296)",
                    "(a, b)",
                    "(2, 2",
                    SECRET,
                ]);
                if let Some(start) = h.find("'shape': ").map(|k| k + 9) {
                    let end = start + h[start..].find(')').map_or(0, |e| e + 1);
                    h.replace_range(start..end, s);
                }
            }
            2 => {
                let v = rng.pick(&["true", "1", "None", "'False'", SECRET, ""]);
                h = h.replacen(if h.contains("True") { "True" } else { "False" }, v, 1);
            }
            3 => {
                let d = rng.pick(&["'desc'", "\"descr\"", "'descr' 'descr'"]).to_string();
                h = h.replacen("'descr'", &d, 1);
            }
            4 => h.push_str(&SECRET.repeat(1 + rng.below(4))),
            5 => h = h.replacen("'shape'", "'shap'", 1),
            _ => {}
        }
    }
    let mut out = b[..8].to_vec();
    if rng.chance(6) {
        out[6] = *rng.pick(&[0u8, 2, 3, 4, 255]);
    }
    if out[6] == 1 {
        out.extend_from_slice(&(h.len() as u16).to_le_bytes());
    } else {
        out.extend_from_slice(&(h.len() as u32).to_le_bytes());
    }
    out.extend_from_slice(h.as_bytes());
    let mut d = data;
    if rng.chance(3) && d.len() >= 8 {
        let k = rng.below(d.len() / 8) * 8;
        let v = *rng.pick(&[f64::INFINITY, f64::NAN, 1e300, -1e300, 5e-324, 1e10]);
        if dtype == NpyDtype::F64 {
            d[k..k + 8].copy_from_slice(&v.to_le_bytes());
        } else {
            d[k..k + 4].copy_from_slice(&(v as f32).to_le_bytes());
        }
    }
    out.extend_from_slice(&d);
    if rng.chance(3) {
        if rng.chance(3) {
            // A header length that runs past the end or is huge.
            let n = *rng.pick(&[u32::MAX, 1 << 20, 70_000, 0]);
            out[8..10].copy_from_slice(&(n as u16).to_le_bytes());
        } else {
            byte_noise(rng, &mut out);
        }
    }
    b = out;
    b
}

fn gsf_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let b = map.to_gsf_bytes();
    let nul = b.iter().position(|&c| c == 0).unwrap();
    let mut header = String::from_utf8(b[..nul].to_vec()).unwrap();
    let data = b[nul + (4 - nul % 4)..].to_vec();
    for _ in 0..1 + rng.below(3) {
        let key = *rng.pick(&["XRes", "YRes", "XReal", "YReal", "XYUnits", "ZUnits", "Title"]);
        match rng.below(7) {
            0 => {
                // Replace a value.
                let v = rng.pick(NASTY);
                let lines: Vec<String> = header
                    .lines()
                    .map(|l| if l.starts_with(key) { format!("{key} = {v}") } else { l.to_string() })
                    .collect();
                header = lines.join("\n") + "\n";
            }
            1 => {
                let lines: Vec<&str> = header.lines().filter(|l| !l.starts_with(key)).collect();
                header = lines.join("\n") + "\n";
            }
            2 => header.push_str(&format!("{key} = {}\n", rng.pick(NASTY))),
            3 => header.push_str(&format!("{SECRET}\n")),
            4 => header.push_str(&format!("Title = {}\n", "x".repeat(1 + rng.below(3000)))),
            5 => {
                let n = *rng.pick(&["100000", "0", "1", "65536", "4294967296"]);
                header = header.replacen(&format!("{key} = "), &format!("{key} = {n}"), 1);
            }
            _ => {}
        }
    }
    let mut out = header.into_bytes();
    let pad = 4 - out.len() % 4;
    let skip_pad = rng.chance(8);
    if !skip_pad {
        out.extend(std::iter::repeat_n(0u8, pad));
    }
    out.extend_from_slice(&data);
    if rng.chance(4) {
        byte_noise(rng, &mut out);
    }
    out
}

fn text_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let text = map.to_text_grid();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let delim = *rng.pick(&["\t", ",", ";", " ", "  "]);
    for l in lines.iter_mut().filter(|l| !l.starts_with('#')) {
        *l = l.replace('\t', delim);
    }
    for _ in 0..rng.below(3) {
        let data_rows: Vec<usize> = (0..lines.len()).filter(|&k| !lines[k].starts_with('#')).collect();
        let Some(&r) = data_rows.get(rng.below(data_rows.len())) else { break };
        match rng.below(11) {
            0 | 1 => {
                let mut cells: Vec<String> = lines[r].split(delim).map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = rng.pick(NASTY).to_string();
                lines[r] = cells.join(delim);
            }
            2 => {
                let mut cells: Vec<&str> = lines[r].split(delim).collect();
                cells.pop();
                lines[r] = cells.join(delim);
            }
            3 => lines.insert(r, format!("1{delim}2{delim}3")),
            4 => {
                let k = rng.below(4);
                lines[k] = format!("# {}: {}", rng.pick(&["Width", "Height", "Value units"]), rng.pick(NASTY));
            }
            5 => lines.insert(0, SECRET.to_string()),
            6 => lines[r] = format!("{}{}", lines[r], delim.repeat(1 + rng.below(5000))),
            7 => lines[r].push_str(&"7".repeat(200 + rng.below(400))),
            8 => lines.retain(|l| l.starts_with('#')),
            9 => {
                // A long line (over the 1 MiB bound now and then).
                let n = if rng.chance(4) { (1 << 20) + 10 } else { 5000 };
                lines[r] = ",".repeat(n);
            }
            _ => lines.insert(0, "# Width: ".to_string() + &"9".repeat(300)),
        }
    }
    let eol = if rng.chance(5) { "\r\n" } else { "\n" };
    let mut out = lines.join(eol).into_bytes();
    if rng.chance(10) {
        out.splice(0..0, [0xEF, 0xBB, 0xBF]);
    }
    if rng.chance(6) {
        byte_noise(rng, &mut out);
    }
    out
}

fn xyz_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let text = map.to_xyz_text();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        let r = 1 + rng.below(lines.len().saturating_sub(1).max(1));
        let r = r.min(lines.len() - 1);
        match rng.below(9) {
            0 | 1 => {
                let mut cells: Vec<String> = lines[r].split(' ').map(str::to_string).collect();
                let c = rng.below(cells.len());
                cells[c] = rng.pick(NASTY).to_string();
                lines[r] = cells.join(" ");
            }
            2 => {
                let l = lines[r].clone();
                lines.push(l);
            }
            3 => lines.push(format!(
                "{} {} 1e-9",
                rng.pick(&["1e308", "-1e308", "3.3e-8", "1e-300"]),
                rng.pick(&["0", "1e308"])
            )),
            4 => lines.insert(1, SECRET.to_string()),
            5 => lines[r].push_str(" 4 5"),
            6 => {
                let d = rng.pick(&[",", ";", "\t", ", "]).to_string();
                lines[r] = lines[r].replace(' ', &d);
            }
            7 => lines.truncate(1 + rng.below(3)),
            _ => lines[0] = rng.pick(NASTY).to_string(),
        }
    }
    lines.join("\n").into_bytes()
}

/// Sets a little-endian integer field of `n` bytes at `at` (if in range) to a hostile value.
fn poke(rng: &mut Rng, b: &mut [u8], at: usize, n: usize) {
    let v: u64 = *rng.pick(&[0, 1, 2, 3, 5, 0x7fff, 0xffff, 0x7fff_ffff, 0xffff_ffff, u64::MAX, 1 << 20, 100_000]);
    if at + n <= b.len() {
        b[at..at + n].copy_from_slice(&v.to_le_bytes()[..n]);
    }
}

/// Integer samples of a base map (nm, clamped to int16).
fn samples(map: &HeightMap) -> Vec<i32> {
    map.heights_m()
        .iter()
        .map(|h| if h.is_nan() { -32768 } else { (h * 1e9 * 100.0).clamp(-32767.0, 32767.0) as i32 })
        .collect()
}

fn nanoscope_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let bpp = if rng.chance(3) { 4 } else { 2 };
    let b = synth::nanoscope(map.nx(), map.ny(), 100.0, 20.0, 10.0, bpp, &samples(&map));
    let header_end = 8192;
    let mut header = String::from_utf8_lossy(&b[..header_end]).trim_end_matches('\u{1a}').to_string();
    let data = b[header_end..].to_vec();
    for _ in 0..1 + rng.below(3) {
        let key = *rng.pick(&[
            "Data offset",
            "Data length",
            "Bytes/pixel",
            "Samps/line",
            "Number of lines",
            "Scan Size",
            "@2:Z scale",
            "@Sens. Zsens",
            "@2:Image Data",
        ]);
        match rng.below(7) {
            0 | 1 => {
                let v = rng.pick(NASTY);
                let lines: Vec<String> = header
                    .split("\r\n")
                    .map(|l| if l.starts_with(&format!("\\{key}:")) { format!("\\{key}: {v}") } else { l.to_string() })
                    .collect();
                header = lines.join("\r\n");
            }
            2 => {
                let lines: Vec<&str> = header.split("\r\n").filter(|l| !l.starts_with(&format!("\\{key}:"))).collect();
                header = lines.join("\r\n");
            }
            3 => {
                let n = *rng.pick(&["100000", "0", "1", "65536", "4294967296", "8192", "-1", "99999999999"]);
                header = header.replacen(&format!("\\{key}: "), &format!("\\{key}: {n} "), 1);
            }
            4 => header = header.replacen("\\*Ciao image list", &format!("\\*Ciao image list\r\n\\{SECRET}"), 1),
            5 => header = header.replacen("\\*File list end", &format!("{SECRET}\r\n\\*File list end"), 1),
            _ => header = header.replacen("\\*File list end", "", 1),
        }
    }
    let mut out = header.into_bytes();
    out.resize(out.len().max(header_end), 0x1a);
    out.truncate(header_end.max(out.len()));
    out.extend_from_slice(&data);
    if rng.chance(4) {
        byte_noise(rng, &mut out);
    }
    out
}

fn ibw_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let layers = 1 + rng.below(3);
    let mut values: Vec<f32> = Vec::new();
    for _ in 0..layers {
        values.extend(map.heights_m().iter().map(|&h| h as f32));
    }
    let names: Vec<&str> =
        (0..layers).map(|k| if k == 0 { "HeightTrace" } else { *rng.pick(&["Phase", SECRET, ""]) }).collect();
    let units = *rng.pick(&["m", "nm", "", "deg"]);
    let mut b =
        synth::ibw(map.nx(), map.ny(), layers, 1e-8, units, units, if rng.chance(4) { &[] } else { &names }, &values);
    for _ in 0..1 + rng.below(3) {
        match rng.below(8) {
            0 => {
                let at = *rng.pick(&[4usize, 8, 12, 16, 20, 36, 40, 44]);
                poke(rng, &mut b, at, 4)
            }
            1 => {
                let at = *rng.pick(&[76usize, 132, 136, 140, 144]);
                poke(rng, &mut b, at, 4)
            }
            2 => poke(rng, &mut b, 80, 2),
            3 => {
                let at = 148 + 8 * rng.below(2);
                let v = *rng.pick(&[0.0f64, -1.0, f64::NAN, f64::INFINITY, 1e300, 5e-324]);
                b[at..at + 8].copy_from_slice(&v.to_le_bytes());
            }
            4 => b.extend_from_slice(SECRET.as_bytes()),
            5 => b[212..216].copy_from_slice(&[0xff, b'\n', 0x1b, b'm']),
            _ => {}
        }
    }
    // Fix the checksum most of the time, so the mutations reach past it.
    if !rng.chance(5) && b.len() >= 384 {
        b[2..4].copy_from_slice(&[0, 0]);
        let sum = b[..384].chunks_exact(2).fold(0u16, |s, c| s.wrapping_add(u16::from_le_bytes([c[0], c[1]])));
        b[2..4].copy_from_slice(&0u16.wrapping_sub(sum).to_le_bytes());
    }
    if rng.chance(4) {
        byte_noise(rng, &mut b);
    }
    b
}

fn sdf_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    if rng.chance(2) {
        let ints: Vec<i16> = samples(&map).iter().map(|&v| v as i16).collect();
        let mut b = synth::sdf_binary(map.nx(), map.ny(), 1e-8, 1e-8, 1e-11, &ints);
        for _ in 0..1 + rng.below(3) {
            match rng.below(6) {
                0 => {
                    let at = 42 + 2 * rng.below(2);
                    poke(rng, &mut b, at, 2)
                }
                1 if b.len() > 70 => {
                    let at = 46 + 8 * rng.below(3);
                    let v = *rng.pick(&[0.0f64, -1.0, f64::NAN, f64::INFINITY, 1e300, 5e-324]);
                    b[at..at + 8].copy_from_slice(&v.to_le_bytes());
                }
                2 if b.len() > 80 => b[78 + rng.below(2)] = *rng.pick(&[0u8, 1, 4, 5, 6, 7, 8, 255]),
                3 => b.extend_from_slice(SECRET.as_bytes()),
                _ => byte_noise(rng, &mut b),
            }
        }
        return b;
    }
    let v: Vec<Option<f64>> = map.heights_m().iter().map(|h| if h.is_nan() { None } else { Some(h * 1e9) }).collect();
    let text = String::from_utf8(synth::sdf_ascii(map.nx(), map.ny(), 1e-8, 1e-8, 1e-9, &v)).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for _ in 0..1 + rng.below(3) {
        if lines.is_empty() {
            break;
        }
        let r = rng.below(lines.len());
        match rng.below(7) {
            0 | 1 => {
                let key =
                    *rng.pick(&["NumPoints", "NumProfiles", "Xscale", "Yscale", "Zscale", "DataType", "Compression"]);
                let val = rng.pick(NASTY);
                for l in lines.iter_mut().filter(|l| l.starts_with(key)) {
                    *l = format!("{key} = {val}");
                }
            }
            2 => lines[r] = format!("{} {}", lines[r], rng.pick(NASTY)),
            3 => lines.insert(r, SECRET.to_string()),
            4 => lines.retain(|l| l != "*"),
            5 => lines.truncate(r),
            _ => lines[r] = "7".repeat(1 + rng.below(3000)),
        }
    }
    let mut b = lines.join("\n").into_bytes();
    if rng.chance(6) {
        byte_noise(rng, &mut b);
    }
    b
}

fn x3p_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    let mut xml = synth::x3p_xml(nx, ny, 1e-8, 1e-8, "D", None);
    let mut data: Vec<u8> = map.heights_m().iter().flat_map(|h| h.to_le_bytes()).collect();
    for _ in 0..1 + rng.below(3) {
        match rng.below(8) {
            0 | 1 => {
                let tag = *rng.pick(&[
                    "SizeX",
                    "SizeY",
                    "SizeZ",
                    "Increment",
                    "DataType",
                    "AxisType",
                    "FeatureType",
                    "PointDataLink",
                ]);
                let v = *rng.pick(&[
                    "0",
                    "1",
                    "4294967296",
                    "18446744073709551616",
                    "-1",
                    "NaN",
                    "1e300",
                    "L",
                    "X",
                    "",
                    SECRET,
                ]);
                if let (Some(a), Some(b)) = (xml.find(&format!("<{tag}>")), xml.find(&format!("</{tag}>")))
                    && a < b
                {
                    xml.replace_range(a + tag.len() + 2..b, v);
                }
            }
            2 => xml = xml.replacen("</Record3>", &"<a>".repeat(1 + rng.below(100)), 1),
            3 => xml.insert_str(xml.len() / 2, SECRET),
            4 => data.truncate(rng.below(data.len() + 1)),
            5 => xml = xml.replacen("<Record3>", "<Record3><DataList><Datum>1</Datum></DataList>", 1),
            _ => {}
        }
    }
    let mut z = synth::zip(&[synth::stored("main.xml", xml.as_bytes()), synth::stored("bindata/data.bin", &data)]);
    if rng.chance(4) {
        byte_noise(rng, &mut z);
    }
    if rng.chance(6) {
        // A declared size set huge.
        let at = 22usize;
        let v = *rng.pick(&[u32::MAX, 1 << 30, 0]);
        if z.len() > at + 4 {
            z[at..at + 4].copy_from_slice(&v.to_le_bytes());
        }
    }
    z
}

fn sur_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let ints: Vec<i32> = samples(&map).iter().map(|&v| if v == -32768 { -2 } else { v }).collect();
    let mut b = synth::sur(map.nx(), map.ny(), 0.01, 1e-11, &ints);
    for _ in 0..1 + rng.below(3) {
        if b.len() < 512 {
            break;
        }
        match rng.below(7) {
            0 => {
                let at = *rng.pick(&[12usize, 14, 18, 86, 98, 290, 334, 336]);
                poke(rng, &mut b, at, 2)
            }
            1 => {
                let at = *rng.pick(&[100usize, 108, 112, 116]);
                poke(rng, &mut b, at, 4)
            }
            2 => {
                let at = *rng.pick(&[120usize, 124, 128]);
                let v = *rng.pick(&[0.0f32, -1.0, f32::NAN, f32::INFINITY, 1e30, 1e-45]);
                b[at..at + 4].copy_from_slice(&v.to_le_bytes());
            }
            3 => {
                let at = *rng.pick(&[180usize, 196, 212]);
                let n = SECRET.len().min(16);
                b[at..at + n].copy_from_slice(&SECRET.as_bytes()[..n]);
            }
            4 => b[..12].copy_from_slice(b"DSCOMPRESSED"),
            _ => byte_noise(rng, &mut b),
        }
    }
    b
}

fn opd_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    let ints: Vec<i16> = (0..nx * ny)
        .map(|k| {
            let (ix, jy) = (k / ny, k % ny);
            let h = map.at(ix, ny - 1 - jy);
            if h.is_nan() { 32767 } else { (h * 1e9 * 10.0).clamp(-32000.0, 32000.0) as i16 }
        })
        .collect();
    let mut b = synth::opd(nx, ny, 632.8, 2, 0.001, &ints);
    for _ in 0..1 + rng.below(3) {
        if b.len() < 2 + 24 * 6 {
            break;
        }
        match rng.below(6) {
            0 => {
                // A block length set huge, zero or negative.
                let at = 2 + 24 * rng.below(6) + 18;
                poke(rng, &mut b, at, 4)
            }
            1 => {
                let at = 2 + 24 * rng.below(6) + 16;
                poke(rng, &mut b, at, 2)
            }
            2 => {
                let at = 2 + 24 * (1 + rng.below(5));
                let n = SECRET.len().min(16);
                b[at..at + n].copy_from_slice(&SECRET.as_bytes()[..n]);
            }
            3 => {
                // The Raw array's nx, ny or sample size.
                let at = 2 + 24 * 6 + 2 * rng.below(3);
                poke(rng, &mut b, at, 2)
            }
            _ => byte_noise(rng, &mut b),
        }
    }
    b
}

/// Structured mutation of a binary file's header and payload: fields at the given offsets set to
/// extreme integers (`ints`: offset, width) or floats (`floats`: offset, big-endian), the text
/// `SECRET` written into a name field, the payload truncated, random byte edits.
fn mutate_header(
    rng: &mut Rng,
    b: &mut Vec<u8>,
    ints: &[(usize, usize)],
    floats: &[(usize, bool)],
    names: &[usize],
    payload_from: usize,
) {
    for _ in 0..1 + rng.below(3) {
        match rng.below(6) {
            0 | 1 if !ints.is_empty() => {
                let (at, n) = *rng.pick(ints);
                poke(rng, b, at, n);
            }
            2 if !floats.is_empty() => {
                let (at, big) = *rng.pick(floats);
                let v = *rng.pick(&[0.0f32, -1.0, f32::NAN, f32::INFINITY, 1e30, 1e-45]);
                if at + 4 <= b.len() {
                    b[at..at + 4].copy_from_slice(&if big { v.to_be_bytes() } else { v.to_le_bytes() });
                }
            }
            3 if !names.is_empty() => {
                let at = *rng.pick(names);
                let n = SECRET.len().min(b.len().saturating_sub(at));
                if n > 0 {
                    b[at..at + n].copy_from_slice(&SECRET.as_bytes()[..n]);
                }
            }
            4 => {
                let keep = payload_from + rng.below(b.len().saturating_sub(payload_from) + 1);
                b.truncate(keep);
            }
            _ => byte_noise(rng, b),
        }
    }
}

fn plu_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let h: Vec<Option<f32>> =
        map.heights_m().iter().map(|&h| if h.is_nan() { None } else { Some((h * 1e6) as f32) }).collect();
    let mut b = synth::plu(map.nx(), map.ny(), 0.01, &h);
    let ints = [(388, 4), (392, 4), (428, 4), (489, 1), (500, 4), (504, 4)];
    mutate_header(rng, &mut b, &ints, &[(404, false), (408, false)], &[0, 500], 500);
    b
}

fn metropro_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    // Phase units: 0.5 x 633 nm / 32768 per unit.
    let unit = 0.5 * 633e-9 / 32768.0;
    let phase: Vec<i32> = map
        .heights_m()
        .iter()
        .map(|&h| if h.is_nan() { i32::MAX } else { (h / unit).clamp(-1e9, 1e9) as i32 })
        .collect();
    let mut b = synth::metropro(map.nx(), map.ny(), 1e-8, &phase);
    let ints = [(4, 2), (6, 4), (56, 2), (60, 4), (68, 2), (70, 2), (72, 4), (218, 2), (232, 2)];
    let floats = [(164, true), (168, true), (176, true), (184, true)];
    mutate_header(rng, &mut b, &ints, &floats, &[], 834);
    b
}

fn netcdf_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    // heights(x, y), x slowest, in 0.01 nm steps; -32768 the fill.
    let h: Vec<i16> = (0..nx * ny)
        .map(|k| {
            let v = map.at(k / ny, k % ny);
            if v.is_nan() { -32768 } else { (v * 1e11).clamp(-32000.0, 32000.0) as i16 }
        })
        .collect();
    let mask: Vec<i8> = (0..nx * ny).map(|k| i8::from(k % 17 == 3)).collect();
    let with_mask = rng.chance(2);
    let mut b = synth::netcdf(
        nx,
        ny,
        "nm",
        nx as f64 * 10.0,
        ny as f64 * 10.0,
        &h,
        0.01,
        -32768,
        with_mask.then_some(&mask[..]),
    );
    // Every header word (counts, lengths, types, offsets) is a field to set.
    let header = b.len() - h.len() * 2 - if with_mask { nx * ny } else { 0 };
    let ints: Vec<(usize, usize)> = (4..header.saturating_sub(4)).step_by(4).map(|at| (at, 4)).collect();
    let names = [8usize, 16];
    let from = header.min(b.len());
    mutate_header(rng, &mut b, &ints, &[], &names, from);
    b
}

fn wsxm_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let doubles = rng.chance(2);
    let raw: Vec<u8> = if doubles {
        map.heights_m().iter().rev().flat_map(|h| (h * 1e9).to_le_bytes()).collect()
    } else {
        samples(&map).iter().rev().flat_map(|&v| (v as i16).to_le_bytes()).collect()
    };
    let kind = if doubles { "double" } else { "short" };
    let mut b = synth::wsxm(map.nx(), map.ny(), map.nx() as f64 * 10.0, "20 nm", kind, &raw);
    let mut text = String::from_utf8_lossy(&b[..b.len() - raw.len()]).to_string();
    for _ in 0..1 + rng.below(3) {
        match rng.below(6) {
            0 | 1 => {
                let key = *rng.pick(&[
                    "Number of columns",
                    "Number of rows",
                    "Image Data Type",
                    "Z Amplitude",
                    "X Amplitude",
                    "Y Amplitude",
                ]);
                let v =
                    *rng.pick(&["0", "-1", "4294967296", "1e300", "NaN", "", "2 V", "7 furlongs", "integer", SECRET]);
                if let Some(a) = text.find(&format!("{key}: ")) {
                    let from = a + key.len() + 2;
                    let to = from + text[from..].find('\r').unwrap_or(0);
                    text.replace_range(from..to, v);
                }
            }
            2 => text = text.replacen("[Header end]", "", 1),
            3 => text.insert_str(text.len() / 2, SECRET),
            _ => {}
        }
    }
    let head = text.into_bytes();
    b = head;
    b.extend_from_slice(&raw);
    mutate_header(rng, &mut b, &[], &[], &[], 0);
    b
}

fn mi_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    // Rows last first; 0.01 nm per unit (range 32768 x 1e-5 um).
    let ints: Vec<i16> = (0..ny)
        .rev()
        .flat_map(|iy| (0..nx).map(move |ix| (iy, ix)))
        .map(|(iy, ix)| {
            let h = map.at(ix, iy);
            if h.is_nan() { 0 } else { (h * 1e11).clamp(-32000.0, 32000.0) as i16 }
        })
        .collect();
    let b = synth::mi(nx, ny, nx as f64 * 1e-8, 0.32768, &ints);
    let at = b.windows(4).position(|w| w == b"data").unwrap_or(0);
    let mut text = String::from_utf8_lossy(&b[..at]).to_string();
    for _ in 0..rng.below(3) {
        let key = *rng.pick(&["xPixels", "yPixels", "xLength", "bufferRange", "bufferUnit", "bufferLabel", "fileType"]);
        let v = *rng.pick(&["0", "-1", "4294967296", "1e300", "NaN", "", "V", "nm", "Spectroscopy", SECRET]);
        if let Some(a) = text.find(key) {
            let from = a + 14;
            let to = from + text[from..].find('\n').unwrap_or(0);
            if from <= to {
                text.replace_range(from..to, v);
            }
        }
    }
    let mut out = text.into_bytes();
    out.extend_from_slice(&b[at..]);
    let from = at.min(out.len());
    mutate_header(rng, &mut out, &[], &[], &[], from);
    out
}

fn nid_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    // Z range 2^32 x 1e-12 m: 1 pm per unit, rows last first.
    let ints: Vec<i32> = (0..ny)
        .rev()
        .flat_map(|iy| (0..nx).map(move |ix| (ix, iy)))
        .map(|(ix, iy)| {
            let h = map.at(ix, iy);
            if h.is_nan() { 0 } else { (h * 1e12).clamp(-1e9, 1e9) as i32 }
        })
        .collect();
    let b = synth::nid(nx, ny, nx as f64 * 1e-8, 4294967296.0 * 1e-12, &ints);
    let at = b.windows(2).position(|w| w == b"#!").unwrap_or(0);
    let mut text = String::from_utf8_lossy(&b[..at]).to_string();
    for _ in 0..rng.below(3) {
        let key = *rng.pick(&[
            "GroupCount=",
            "Gr0-Count=",
            "Gr0-Ch0=",
            "Points=",
            "Lines=",
            "Dim0Range=",
            "Dim2Range=",
            "Dim2Min=",
            "Dim2Unit=",
            "SaveBits=",
            "SaveSign=",
            "SaveMode=",
            "SaveOrder=",
        ]);
        let v = *rng.pick(&[
            "0",
            "-1",
            "4294967296",
            "1e300",
            "NaN",
            "",
            "8",
            "16",
            "Unsigned",
            "Text",
            "Motorola",
            "nm",
            SECRET,
        ]);
        if let Some(a) = text.find(key) {
            let from = a + key.len();
            let to = from + text[from..].find('\r').unwrap_or(0);
            text.replace_range(from..to, v);
        }
    }
    let mut out = text.into_bytes();
    out.extend_from_slice(&b[at..]);
    let from = at.min(out.len());
    mutate_header(rng, &mut out, &[], &[], &[], from);
    out
}

fn al3d_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let depth: Vec<f32> = map.heights_m().iter().map(|&h| if h.is_nan() { 3.0e15 } else { h as f32 }).collect();
    let mut b = synth::al3d(map.nx(), map.ny(), 1e-8, &depth);
    // The tags' values (30 bytes after each 20-byte key) and the key of a tag.
    let values: Vec<usize> = (0..9).map(|k| 17 + k * 52 + 20).collect();
    let ints: Vec<(usize, usize)> = values.iter().map(|&at| (at, 4)).collect();
    if rng.chance(3) {
        let at = *rng.pick(&values);
        let v = *rng.pick(&["0", "-1", "4294967296", "1e300", "NaN", "", "99999999999", SECRET]);
        let n = v.len().min(30);
        b[at..at + 30].fill(0);
        b[at..at + n].copy_from_slice(&v.as_bytes()[..n]);
    }
    let from = 17 + 9 * 52 + 256;
    mutate_header(rng, &mut b, &ints, &[], &[17, 17 + 52 * 3], from);
    b
}

fn park_case(rng: &mut Rng) -> Vec<u8> {
    let map = base_map(rng);
    let (nx, ny) = (map.nx(), map.ny());
    let um: Vec<f32> = (0..ny)
        .rev()
        .flat_map(|iy| (0..nx).map(move |ix| (ix, iy)))
        .map(|(ix, iy)| (map.at(ix, iy) * 1e6) as f32)
        .collect();
    let mut b = synth::park(nx, ny, nx as f64 * 0.01, &um);
    // The IFD entries' counts and offsets, and the Park header's fields.
    let h = b.len() - 352;
    let mut ints: Vec<(usize, usize)> =
        (0..4).flat_map(|k| [(10 + 12 * k, 2), (14 + 12 * k, 4), (18 + 12 * k, 4)]).collect();
    ints.extend([(4, 4), (8, 2), (h, 4), (h + 100, 4), (h + 104, 4), (h + 348, 4)]);
    let floats: Vec<(usize, bool)> = Vec::new();
    if rng.chance(4) {
        let at = *rng.pick(&[h + 140, h + 148, h + 220, h + 228, h + 236]);
        let v = *rng.pick(&[0.0f64, -1.0, f64::NAN, f64::INFINITY, 1e300, 1e-300]);
        b[at..at + 8].copy_from_slice(&v.to_le_bytes());
    }
    mutate_header(rng, &mut b, &ints, &floats, &[h + 4, h + 244], 58);
    b
}

fn preparation(rng: &mut Rng) -> Preparation {
    let cut = [
        None,
        None,
        None,
        None,
        None,
        Some(1e-9),
        Some(5e-8),
        Some(1e-7),
        Some(1e-6),
        Some(1.0),
        Some(1e300),
        Some(-1.0),
        Some(f64::NAN),
    ];
    Preparation {
        levelling: *rng.pick(&[Levelling::None, Levelling::Mean, Levelling::Plane, Levelling::Poly2, Levelling::Poly3]),
        short_cutoff_m: *rng.pick(&cut),
        long_cutoff_m: *rng.pick(&cut),
    }
}

#[derive(Default, Debug)]
struct Counts {
    cases: usize,
    read: usize,
    analysed: usize,
    refused: usize,
}

/// A read's result as comparable text: the bits of every height, grid, pixel sizes, metadata; or
/// the error.
fn fingerprint(r: &Result<(HeightMap, MapInfo), TopographyError>) -> String {
    match r {
        Ok((m, info)) => {
            let bits: Vec<u64> = m.heights_m().iter().map(|h| h.to_bits()).collect();
            format!("{} {} {} {} {bits:?} {info:?}", m.nx(), m.ny(), m.dx_m(), m.dy_m())
        }
        Err(e) => format!("error: {e}"),
    }
}

fn check_error(e: &TopographyError, case: &str) {
    if std::env::var("FUZZ_SHOW").is_ok() {
        eprintln!("{case}: {e}");
    }
    let m = e.to_string();
    assert!(!m.contains(SECRET), "an error echoes the file ({case}): {m}");
    assert!(m.chars().count() <= MAX_ERROR_CHARS, "an error of {} chars ({case}): {m}", m.chars().count());
    let names_origin = m.contains(ORIGIN) || matches!(e, TopographyError::InvalidParameter { .. });
    assert!(names_origin, "an error does not name the file or the field ({case}): {m}");
    assert!(!m.chars().any(|c| c.is_control() && c != '\n'), "an error holds control characters ({case}): {m:?}");
}

fn run_format(name: &str, make: fn(&mut Rng) -> Vec<u8>, seed: u64) -> Counts {
    let mut rng = Rng(seed ^ name.bytes().fold(0u64, |h, b| h.wrapping_mul(31).wrapping_add(u64::from(b))));
    let mut counts = Counts::default();
    for case in 0..cases() {
        let bytes = make(&mut rng);
        let m = meta(&mut rng, name);
        let prep = preparation(&mut rng);
        let label = format!("{name} case {case} (seed {seed})");
        let start = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| {
            let read = match name {
                "npy" => read_npy(&bytes, ORIGIN, &m),
                "gsf" => read_gsf(&bytes, ORIGIN, &m),
                _ if INSTRUMENT.contains(&name) => {
                    let format: MapFormat = name.parse().unwrap();
                    // Detection never panics and, on an unmutated magic, names the format.
                    let _ = detect(&bytes);
                    let sel = match case % 8 {
                        0 => Some(ChannelSelector::Index(case % 3)),
                        4 => Some(ChannelSelector::Name(if case % 8 == 1 { SECRET.into() } else { "Phase".into() })),
                        _ => None,
                    };
                    let read = read_instrument(&bytes, format, ORIGIN, sel.as_ref(), &m);
                    // The route in parts (the header from a prefix, the samples decoded from the
                    // source) gives the same bits or the same error.
                    let prefix = [16, 300, 4096][case % 3];
                    let (parts, _) = read_instrument_in_parts(&bytes, prefix, format, ORIGIN, sel.as_ref(), &m);
                    assert_eq!(fingerprint(&parts), fingerprint(&read), "{label}: read in parts, prefix {prefix}");
                    read
                }
                "text" | "xyz" => {
                    // The text readers take what `read_input_text` gives: UTF-8 without a BOM.
                    let text = match std::str::from_utf8(&bytes) {
                        Ok(t) => t.trim_start_matches('\u{feff}').to_string(),
                        Err(_) => return (false, None),
                    };
                    if name == "text" { read_text_grid(&text, ORIGIN, &m) } else { read_xyz(&text, ORIGIN, &m) }
                }
                other => panic!("no reader for the fuzzed format {other}"),
            };
            let (map, _info) = match read {
                Ok(x) => x,
                Err(e) => {
                    check_error(&e, &label);
                    return (false, None);
                }
            };
            match prepare(&map, &prep) {
                Err(e) => {
                    check_error(&e, &label);
                    (true, None)
                }
                Ok((p, _)) => {
                    let s = find_summits(&p);
                    let st = statistics(&p, &s);
                    (true, Some(format!("{st:?}")))
                }
            }
        }));
        let took = start.elapsed();
        counts.cases += 1;
        match result {
            Err(_) => panic!("{label} panicked (meta {m:?}, preparation {prep:?})"),
            Ok((read, stats)) => {
                counts.read += usize::from(read);
                if let Some(st) = stats {
                    counts.analysed += 1;
                    assert!(
                        !st.contains("NaN") && !st.contains("inf"),
                        "{label}: a statistic is not finite (meta {m:?}, preparation {prep:?}): {st}"
                    );
                } else {
                    counts.refused += 1;
                }
            }
        }
        assert!(took < CASE_TIME_LIMIT, "{label} took {took:?}");
    }
    eprintln!("fuzz {name}: {counts:?}");
    counts
}

#[test]
fn npy_files_keep_the_contract() {
    let c = run_format("npy", npy_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn gsf_files_keep_the_contract() {
    let c = run_format("gsf", gsf_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn text_grids_keep_the_contract() {
    let c = run_format("text", text_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn nanoscope_files_keep_the_contract() {
    let c = run_format("nanoscope", nanoscope_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn igor_binary_waves_keep_the_contract() {
    let c = run_format("ibw", ibw_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn x3p_files_keep_the_contract() {
    let c = run_format("x3p", x3p_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn sur_files_keep_the_contract() {
    let c = run_format("sur", sur_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn opd_files_keep_the_contract() {
    let c = run_format("opd", opd_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn sdf_files_keep_the_contract() {
    let c = run_format("sdf", sdf_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn xyz_lists_keep_the_contract() {
    let c = run_format("xyz", xyz_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn plu_files_keep_the_contract() {
    let c = run_format("plu", plu_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn metropro_files_keep_the_contract() {
    let c = run_format("metropro", metropro_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn netcdf_files_keep_the_contract() {
    let c = run_format("netcdf", netcdf_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn wsxm_files_keep_the_contract() {
    let c = run_format("wsxm", wsxm_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn mi_files_keep_the_contract() {
    let c = run_format("mi", mi_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn nid_files_keep_the_contract() {
    let c = run_format("nid", nid_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn al3d_files_keep_the_contract() {
    let c = run_format("al3d", al3d_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}

#[test]
fn park_files_keep_the_contract() {
    let c = run_format("park", park_case, seed());
    assert!(c.analysed > 0 && c.refused > 0, "{c:?}");
}
