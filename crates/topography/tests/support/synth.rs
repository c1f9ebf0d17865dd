//! Synthetic instrument files written from the formats' documented layouts, for the fuzz harness
//! and the benchmark (the readers are checked against real files in tests/formats.rs).
#![allow(dead_code)]

/// A NanoScope file of one int16 (or int32) image, `nx x ny`, scan size `size_nm` square, Z scale
/// chain `zscale_v` V x `sens_nm_per_v` nm/V; samples row by row as the file stores them.
pub fn nanoscope(
    nx: usize,
    ny: usize,
    size_nm: f64,
    zscale_v: f64,
    sens_nm_per_v: f64,
    bpp: usize,
    samples: &[i32],
) -> Vec<u8> {
    let header_len = 8192usize;
    let mut h = String::new();
    h.push_str("\\*File list\r\n\\Version: 0x09200000\r\n");
    h.push_str(&format!("\\Data length: {header_len}\r\n"));
    h.push_str("\\*Scanner list\r\n\\Scanner type: Dimension\r\n");
    h.push_str(&format!("\\@Sens. Zsens: V {sens_nm_per_v} nm/V\r\n"));
    h.push_str("\\*Ciao scan list\r\n\\Scan Size: 1 nm\r\n");
    h.push_str("\\*Ciao image list\r\n");
    h.push_str(&format!("\\Data offset: {header_len}\r\n\\Data length: {}\r\n", nx * ny * bpp));
    h.push_str(&format!("\\Bytes/pixel: {bpp}\r\n\\Samps/line: {nx}\r\n\\Number of lines: {ny}\r\n"));
    h.push_str(&format!("\\Scan Size: {size_nm} {size_nm} nm\r\n"));
    h.push_str("\\@2:Image Data: S [Height] \"Height\"\r\n");
    h.push_str(&format!("\\@2:Z scale: V [Sens. Zsens] (0.0003 V/LSB) {zscale_v} V\r\n"));
    h.push_str("\\*File list end\r\n");
    let mut b = h.into_bytes();
    assert!(b.len() <= header_len);
    b.resize(header_len, 0x1a);
    for &s in samples {
        if bpp == 2 {
            b.extend_from_slice(&(s as i16).to_le_bytes());
        } else {
            b.extend_from_slice(&s.to_le_bytes());
        }
    }
    b
}

/// An Igor binary wave v5 of float32 `layers` layers of `nx x ny` (dimension 0 fastest), pixel
/// step `step` in `xy_unit`, data unit `z_unit`, layer labels `names`.
#[allow(clippy::too_many_arguments)] // the layout's fields, named at the call
pub fn ibw(
    nx: usize,
    ny: usize,
    layers: usize,
    step: f64,
    xy_unit: &str,
    z_unit: &str,
    names: &[&str],
    values: &[f32],
) -> Vec<u8> {
    let n = nx * ny * layers;
    assert_eq!(values.len(), n);
    let mut b = vec![0u8; 384];
    let wfm = 320 + 4 * n;
    let labels = if names.is_empty() { 0 } else { (layers + 1) * 32 };
    b[0..2].copy_from_slice(&5i16.to_le_bytes());
    b[4..8].copy_from_slice(&(wfm as i32).to_le_bytes());
    b[44..48].copy_from_slice(&(labels as i32).to_le_bytes());
    b[76..80].copy_from_slice(&(n as i32).to_le_bytes());
    b[80..82].copy_from_slice(&2i16.to_le_bytes());
    for (d, v) in [nx, ny, if layers > 1 || !names.is_empty() { layers } else { 0 }, 0].iter().enumerate() {
        b[132 + 4 * d..136 + 4 * d].copy_from_slice(&(*v as i32).to_le_bytes());
    }
    for d in 0..2 {
        b[148 + 8 * d..156 + 8 * d].copy_from_slice(&step.to_le_bytes());
    }
    let put = |b: &mut Vec<u8>, at: usize, s: &str| {
        for (k, c) in s.bytes().take(3).enumerate() {
            b[at + k] = c;
        }
    };
    put(&mut b, 212, z_unit);
    put(&mut b, 216, xy_unit);
    put(&mut b, 220, xy_unit);
    let sum = b.chunks_exact(2).fold(0u16, |s, c| s.wrapping_add(u16::from_le_bytes([c[0], c[1]])));
    b[2..4].copy_from_slice(&(0u16.wrapping_sub(sum)).to_le_bytes());
    for v in values {
        b.extend_from_slice(&v.to_le_bytes());
    }
    if !names.is_empty() {
        b.extend(std::iter::repeat_n(0u8, 32));
        for k in 0..layers {
            let mut l = [0u8; 32];
            for (i, c) in names.get(k).copied().unwrap_or("").bytes().take(31).enumerate() {
                l[i] = c;
            }
            b.extend_from_slice(&l);
        }
    }
    b
}

/// An ASCII SDF of `nx x ny` doubles (`None` = BAD), steps in metres, Zscale in metres.
pub fn sdf_ascii(nx: usize, ny: usize, xs: f64, ys: f64, zs: f64, values: &[Option<f64>]) -> Vec<u8> {
    let mut s = format!(
        "aISO-1.0\nManufacID = stiction\nCreateDate = 010120260000\nModDate = 010120260000\nNumPoints = {nx}\nNumProfiles = {ny}\nXscale = {xs:e}\nYscale = {ys:e}\nZscale = {zs:e}\nZresolution = -1\nCompression = 0\nDataType = 7\nCheckType = 0\n*\n"
    );
    for row in values.chunks(nx) {
        let cells: Vec<String> = row.iter().map(|v| v.map_or("BAD".into(), |v| format!("{v}"))).collect();
        s.push_str(&cells.join(" "));
        s.push('\n');
    }
    s.push_str("*\n*\n");
    s.into_bytes()
}

/// A binary SDF of `nx x ny` int16 (`i16::MIN` = missing).
pub fn sdf_binary(nx: usize, ny: usize, xs: f64, ys: f64, zs: f64, values: &[i16]) -> Vec<u8> {
    let mut b = b"bISO-1.0".to_vec();
    b.extend_from_slice(&[b' '; 34]);
    b.extend_from_slice(&(nx as u16).to_le_bytes());
    b.extend_from_slice(&(ny as u16).to_le_bytes());
    for v in [xs, ys, zs, zs] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b.extend_from_slice(&[0, 5, 0]);
    for v in values {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

fn crc32(data: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 == 1 { (c >> 1) ^ 0xedb8_8320 } else { c >> 1 };
        }
    }
    !c
}

/// A zip archive of `entries` (name, method 0 = stored or 8 = deflate, stored bytes, uncompressed
/// size and CRC as declared), written from the zip file format (PKWARE APPNOTE 4.3.7, 4.3.12,
/// 4.3.16).
pub fn zip(entries: &[(&str, u16, Vec<u8>, u32, u32)]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, method, data, size, crc) in entries {
        let offset = out.len() as u32;
        let mut h = Vec::new();
        h.extend_from_slice(&[20, 0, 0, 0]);
        h.extend_from_slice(&method.to_le_bytes());
        h.extend_from_slice(&[0, 0, 0x21, 0]);
        h.extend_from_slice(&crc.to_le_bytes());
        h.extend_from_slice(&(data.len() as u32).to_le_bytes());
        h.extend_from_slice(&size.to_le_bytes());
        h.extend_from_slice(&(name.len() as u16).to_le_bytes());
        h.extend_from_slice(&[0, 0]);
        out.extend_from_slice(b"PK\x03\x04");
        out.extend_from_slice(&h);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        central.extend_from_slice(b"PK\x01\x02");
        central.extend_from_slice(&[20, 0]);
        central.extend_from_slice(&h);
        central.extend_from_slice(&[0; 10]);
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_offset = out.len() as u32;
    out.extend_from_slice(&central);
    out.extend_from_slice(b"PK\x05\x06\0\0\0\0");
    out.extend_from_slice(&(entries.len() as u16).to_le_bytes());
    out.extend_from_slice(&(entries.len() as u16).to_le_bytes());
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&cd_offset.to_le_bytes());
    out.extend_from_slice(&[0, 0]);
    out
}

/// A stored zip entry (its true size and CRC).
pub fn stored<'a>(name: &'a str, data: &[u8]) -> (&'a str, u16, Vec<u8>, u32, u32) {
    (name, 0, data.to_vec(), data.len() as u32, crc32(data))
}

/// An X3P main.xml for an `nx x ny` grid of `data_type` (I, L, F, D) with steps in metres.
pub fn x3p_xml(nx: usize, ny: usize, dx: f64, dy: f64, data_type: &str, z_increment: Option<f64>) -> String {
    let inc = z_increment.map_or(String::new(), |z| format!("<Increment>{z:e}</Increment>"));
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\
<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>\
<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{dx:e}</Increment><Offset>0</Offset></CX>\
<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{dy:e}</Increment><Offset>0</Offset></CY>\
<CZ><AxisType>A</AxisType><DataType>{data_type}</DataType>{inc}</CZ></Axes></Record1>\
<Record3><MatrixDimension><SizeX>{nx}</SizeX><SizeY>{ny}</SizeY><SizeZ>1</SizeZ></MatrixDimension>\
<DataLink><PointDataLink>bindata/data.bin</PointDataLink></DataLink></Record3></p:ISO5436_2>\n"
    )
}

/// A Digital Surf `.sur` of `nx x ny` int32 samples (steps in µm, height step in m), with the
/// non-measured flag set and `zmin` 0 (so -2 is a missing point).
pub fn sur(nx: usize, ny: usize, step_um: f32, dz_m: f32, samples: &[i32]) -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[..12].copy_from_slice(b"DIGITAL SURF");
    b[14..16].copy_from_slice(&1u16.to_le_bytes());
    b[16..18].copy_from_slice(&1u16.to_le_bytes());
    b[18..20].copy_from_slice(&2u16.to_le_bytes());
    b[86..88].copy_from_slice(&1u16.to_le_bytes());
    b[98..100].copy_from_slice(&32u16.to_le_bytes());
    b[108..112].copy_from_slice(&(nx as i32).to_le_bytes());
    b[112..116].copy_from_slice(&(ny as i32).to_le_bytes());
    b[116..120].copy_from_slice(&((nx * ny) as u32).to_le_bytes());
    b[120..124].copy_from_slice(&step_um.to_le_bytes());
    b[124..128].copy_from_slice(&step_um.to_le_bytes());
    b[128..132].copy_from_slice(&dz_m.to_le_bytes());
    for (at, u) in [(180, "um"), (196, "um"), (212, "m")] {
        b[at..at + u.len()].copy_from_slice(u.as_bytes());
    }
    for s in samples {
        b.extend_from_slice(&s.to_le_bytes());
    }
    b
}

/// A Wyko `.opd` of one int16 `Raw` array (`nx x ny`, y fastest, last y first), wavelength in nm,
/// `Mult`, pixel size in mm.
pub fn opd(nx: usize, ny: usize, wavelength_nm: f32, mult: i16, pixel_mm: f32, samples: &[i16]) -> Vec<u8> {
    let mut raw = Vec::new();
    raw.extend_from_slice(&(nx as u16).to_le_bytes());
    raw.extend_from_slice(&(ny as u16).to_le_bytes());
    raw.extend_from_slice(&2u16.to_le_bytes());
    for s in samples {
        raw.extend_from_slice(&s.to_le_bytes());
    }
    let blocks: Vec<(&str, i16, Vec<u8>)> = vec![
        ("Raw", 3, raw),
        ("Wavelength", 7, wavelength_nm.to_le_bytes().to_vec()),
        ("Mult", 6, mult.to_le_bytes().to_vec()),
        ("Pixel_size", 7, pixel_mm.to_le_bytes().to_vec()),
        ("Aspect", 7, 1.0f32.to_le_bytes().to_vec()),
    ];
    let entry = |name: &str, kind: i16, len: usize| {
        let mut e = vec![0u8; 24];
        e[..name.len()].copy_from_slice(name.as_bytes());
        e[16..18].copy_from_slice(&kind.to_le_bytes());
        e[18..22].copy_from_slice(&(len as i32).to_le_bytes());
        e
    };
    let mut b = vec![1u8, 0];
    b.extend(entry("Directory", 3, 24 * (blocks.len() + 1)));
    for (name, kind, data) in &blocks {
        b.extend(entry(name, *kind, data.len()));
    }
    for (_, _, data) in &blocks {
        b.extend_from_slice(data);
    }
    b
}

/// A Sensofar `.plu` topography of one layer: float32 heights in µm (x fastest), 1000001 where
/// `None`, pixel size in µm.
pub fn plu(nx: usize, ny: usize, pixel_um: f32, heights_um: &[Option<f32>]) -> Vec<u8> {
    let mut b = vec![0u8; 500];
    b[..24].copy_from_slice(b"Fri Mar 10 16:35:59 2023");
    b[388..392].copy_from_slice(&(ny as u32).to_le_bytes());
    b[392..396].copy_from_slice(&(nx as u32).to_le_bytes());
    b[404..408].copy_from_slice(&pixel_um.to_le_bytes());
    b[408..412].copy_from_slice(&pixel_um.to_le_bytes());
    b[428..432].copy_from_slice(&3u32.to_le_bytes());
    b[489] = 1;
    b.extend_from_slice(&(ny as u32).to_le_bytes());
    b.extend_from_slice(&(nx as u32).to_le_bytes());
    for h in heights_um {
        b.extend_from_slice(&h.unwrap_or(1_000_001.0).to_le_bytes());
    }
    b.extend_from_slice(&[0; 8]);
    b
}

/// A Zygo MetroPro `.dat` (header format 1, 834 bytes) without intensity data: int32 phase
/// (big-endian, x fastest), S = 0.5, O = 1, W = 633 nm, R = 32768, lateral resolution in m.
pub fn metropro(nx: usize, ny: usize, lateral_m: f32, phase: &[i32]) -> Vec<u8> {
    let mut b = vec![0u8; 834];
    b[..4].copy_from_slice(&[0x88, 0x1b, 0x03, 0x6f]);
    b[4..6].copy_from_slice(&1u16.to_be_bytes());
    b[6..10].copy_from_slice(&834u32.to_be_bytes());
    b[68..70].copy_from_slice(&(nx as u16).to_be_bytes());
    b[70..72].copy_from_slice(&(ny as u16).to_be_bytes());
    b[72..76].copy_from_slice(&((nx * ny * 4) as u32).to_be_bytes());
    b[164..168].copy_from_slice(&0.5f32.to_be_bytes());
    b[168..172].copy_from_slice(&633e-9f32.to_be_bytes());
    b[176..180].copy_from_slice(&1.0f32.to_be_bytes());
    b[184..188].copy_from_slice(&lateral_m.to_be_bytes());
    b[218..220].copy_from_slice(&1i16.to_be_bytes());
    for p in phase {
        b.extend_from_slice(&p.to_be_bytes());
    }
    b
}

/// A netCDF classic file (version 1) of a map as contact.engineering writes it: dimensions x, y;
/// variables `x` and `y` (double, with `length` and `unit`), `heights(x, y)` (short, with `unit`,
/// `scale_factor`, `_FillValue`) and, if given, `mask(x, y)` (byte). Values x slowest.
#[allow(clippy::too_many_arguments)]
pub fn netcdf(
    nx: usize,
    ny: usize,
    unit: &str,
    length_x: f64,
    length_y: f64,
    heights: &[i16],
    scale: f64,
    fill: i16,
    mask: Option<&[i8]>,
) -> Vec<u8> {
    fn pad(b: &mut Vec<u8>) {
        while !b.len().is_multiple_of(4) {
            b.push(0);
        }
    }
    fn name(b: &mut Vec<u8>, s: &str) {
        b.extend_from_slice(&(s.len() as u32).to_be_bytes());
        b.extend_from_slice(s.as_bytes());
        pad(b);
    }
    fn attr(b: &mut Vec<u8>, n: &str, kind: u32, count: usize, data: &[u8]) {
        name(b, n);
        b.extend_from_slice(&kind.to_be_bytes());
        b.extend_from_slice(&(count as u32).to_be_bytes());
        b.extend_from_slice(data);
        pad(b);
    }
    let be32 = |v: u32| v.to_be_bytes();
    // Variables: (name, dims, attrs builder, type, bytes).
    let xs: Vec<u8> = (0..nx).flat_map(|k| (k as f64).to_be_bytes()).collect();
    let ys: Vec<u8> = (0..ny).flat_map(|k| (k as f64).to_be_bytes()).collect();
    let hs: Vec<u8> = heights.iter().flat_map(|h| h.to_be_bytes()).collect();
    let ms: Vec<u8> = mask.map(|m| m.iter().map(|&v| v as u8).collect()).unwrap_or_default();
    // (name, dimension ids, attribute list bytes, type, values)
    type Var<'a> = (&'a str, Vec<u32>, Vec<u8>, u32, Vec<u8>);
    let mut vars: Vec<Var> = Vec::new();
    for (n, dim, len, data) in [("x", 0u32, length_x, xs), ("y", 1, length_y, ys)] {
        let mut a = Vec::new();
        a.extend_from_slice(&be32(12));
        a.extend_from_slice(&be32(2));
        attr(&mut a, "length", 6, 1, &len.to_be_bytes());
        attr(&mut a, "unit", 2, unit.len(), unit.as_bytes());
        vars.push((n, vec![dim], a, 6, data));
    }
    let mut a = Vec::new();
    a.extend_from_slice(&be32(12));
    a.extend_from_slice(&be32(3));
    attr(&mut a, "unit", 2, unit.len(), unit.as_bytes());
    attr(&mut a, "scale_factor", 6, 1, &scale.to_be_bytes());
    attr(&mut a, "_FillValue", 3, 1, &fill.to_be_bytes());
    vars.push(("heights", vec![0, 1], a, 3, hs));
    if mask.is_some() {
        vars.push(("mask", vec![0, 1], vec![0; 8], 1, ms));
    }
    let mut head = b"CDF\x01".to_vec();
    head.extend_from_slice(&be32(0));
    head.extend_from_slice(&be32(10));
    head.extend_from_slice(&be32(2));
    name(&mut head, "x");
    head.extend_from_slice(&be32(nx as u32));
    name(&mut head, "y");
    head.extend_from_slice(&be32(ny as u32));
    head.extend_from_slice(&[0; 8]);
    head.extend_from_slice(&be32(11));
    head.extend_from_slice(&be32(vars.len() as u32));
    // Header size first (begin offsets depend on it): every variable entry, begin left to patch.
    let mut begins = Vec::new();
    for (n, dims, attrs, kind, data) in &vars {
        name(&mut head, n);
        head.extend_from_slice(&be32(dims.len() as u32));
        for d in dims {
            head.extend_from_slice(&be32(*d));
        }
        head.extend_from_slice(attrs);
        head.extend_from_slice(&be32(*kind));
        head.extend_from_slice(&be32(data.len().div_ceil(4) as u32 * 4));
        begins.push(head.len());
        head.extend_from_slice(&be32(0));
    }
    let mut at = head.len();
    let mut body = Vec::new();
    for ((_, _, _, _, data), b) in vars.iter().zip(&begins) {
        head[*b..*b + 4].copy_from_slice(&be32(at as u32));
        body.extend_from_slice(data);
        pad(&mut body);
        at = head.len() + body.len();
    }
    head.extend(body);
    head
}

/// A WSxM image: the text header (X/Y amplitude in nm, Z amplitude with its unit) and int16 or
/// double samples as given (little-endian), stored as WSxM stores them (turned by 180 degrees is
/// the caller's business).
pub fn wsxm(nx: usize, ny: usize, size_nm: f64, z_amplitude: &str, data_type: &str, samples: &[u8]) -> Vec<u8> {
    let head = format!(
        "WSxM file copyright UAM\r\nSxM Image file\r\nImage header size: 0\r\n\r\n[Control]\r\n\r\n    \
         X Amplitude: {size_nm} nm\r\n    Y Amplitude: {size_nm} nm\r\n\r\n[General Info]\r\n\r\n    \
         Acquisition channel: Topography\r\n    Image Data Type: {data_type}\r\n    Number of columns: {nx}\r\n    \
         Number of rows: {ny}\r\n    Z Amplitude: {z_amplitude}\r\n\r\n[Header end]\r\n"
    );
    let mut b = head.into_bytes();
    b.extend_from_slice(samples);
    b
}

/// A PicoView `.mi` image: header lines (14-character keys), one `Topography` buffer in um with
/// `range_um` and a `Deflection` buffer in V, int16 (`BINARY`) samples, the last row first.
pub fn mi(nx: usize, ny: usize, length_m: f64, range_um: f64, samples: &[i16]) -> Vec<u8> {
    let line = |k: &str, v: &str| format!("{k:<14}{v}\n");
    let mut h = String::new();
    h += &line("fileType", "Image");
    h += &line("xPixels", &nx.to_string());
    h += &line("yPixels", &ny.to_string());
    h += &line("xLength", &format!("{length_m:e}"));
    h += &line("yLength", &format!("{length_m:e}"));
    for (label, unit) in [("Topography", "um"), ("Deflection", "V")] {
        h += &line("bufferLabel", label);
        h += &line("bufferRange", &format!("{range_um:e}"));
        h += &line("bufferUnit", unit);
    }
    h += &line("data", "BINARY");
    let mut b = h.into_bytes();
    for _ in 0..2 {
        for s in samples {
            b.extend_from_slice(&s.to_le_bytes());
        }
    }
    b
}

/// A Nanosurf `.nid` of one group of two data sets (Z-Axis in m, then Deflection in N), int32
/// Intel samples (x fastest, the last row first), scan size `length_m`, Z range `range_m`.
pub fn nid(nx: usize, ny: usize, length_m: f64, range_m: f64, samples: &[i32]) -> Vec<u8> {
    let mut h = String::from("[DataSet]\r\nVersion=2\r\nGroupCount=1\r\nGr0-Name=Scan forward\r\nGr0-Count=2\r\n");
    h += "Gr0-Ch0=DataSet-0:0\r\nGr0-Ch1=DataSet-0:1\r\n\r\n";
    for (k, (name, unit)) in [("Z-Axis", "m"), ("Deflection", "N")].iter().enumerate() {
        h += &format!(
            "[DataSet-0:{k}]\r\nPoints={nx}\r\nLines={ny}\r\nFrame=Scan forward\r\nDim0Unit=m\r\nDim0Range={length_m:e}\r\n\
             Dim1Unit=m\r\nDim1Range={length_m:e}\r\nDim2Name={name}\r\nDim2Unit={unit}\r\nDim2Range={range_m:e}\r\n\
             Dim2Min={:e}\r\nSaveMode=Binary\r\nSaveBits=32\r\nSaveSign=Signed\r\nSaveOrder=Intel\r\n\r\n",
            -range_m / 2.0
        );
    }
    h += "#!";
    let mut b = h.into_bytes();
    for _ in 0..2 {
        for s in samples {
            b.extend_from_slice(&s.to_le_bytes());
        }
    }
    b
}

/// An Alicona `.al3d` (version 1) with a `Cols x Rows` float32 depth image in metres, rows padded
/// to a multiple of 8 bytes, InvalidPixelValue 3e15, pixel size in metres.
pub fn al3d(nx: usize, ny: usize, pixel_m: f64, depth_m: &[f32]) -> Vec<u8> {
    let tag = |k: &str, v: &str| {
        let mut t = vec![0u8; 52];
        t[..k.len()].copy_from_slice(k.as_bytes());
        t[20..20 + v.len()].copy_from_slice(v.as_bytes());
        t[50..52].copy_from_slice(b"\r\n");
        t
    };
    let tags = 7;
    let offset = 17 + (tags + 2) * 52 + 256;
    let mut b = b"AliconaImaging\x00\r\n".to_vec();
    b.extend(tag("Version", "1"));
    b.extend(tag("TagCount", &tags.to_string()));
    b.extend(tag("Cols", &nx.to_string()));
    b.extend(tag("Rows", &ny.to_string()));
    b.extend(tag("PixelSizeXMeter", &format!("{pixel_m:e}")));
    b.extend(tag("PixelSizeYMeter", &format!("{pixel_m:e}")));
    b.extend(tag("InvalidPixelValue", "3.000000028082e+15"));
    b.extend(tag("DepthImageOffset", &offset.to_string()));
    b.extend(tag("CreatingApplication", "stiction tests"));
    b.extend(vec![0u8; 256]);
    let row = (nx * 4).div_ceil(8) * 8;
    for y in 0..ny {
        for x in 0..nx {
            b.extend_from_slice(&depth_m[y * nx + x].to_le_bytes());
        }
        b.extend(vec![0u8; row - nx * 4]);
    }
    b
}

/// A Park Systems TIFF (version 2, float32 data, µm) of one IFD with the four Park tags; scan size
/// in µm, gain 1, scale 1, offset 0; samples x fastest, the last row first.
pub fn park(nx: usize, ny: usize, size_um: f64, samples_um: &[f32]) -> Vec<u8> {
    let mut header = vec![0u8; 352];
    for (k, c) in "Z Height".encode_utf16().enumerate() {
        header[4 + 2 * k..6 + 2 * k].copy_from_slice(&c.to_le_bytes());
    }
    header[100..104].copy_from_slice(&(nx as u32).to_le_bytes());
    header[104..108].copy_from_slice(&(ny as u32).to_le_bytes());
    header[140..148].copy_from_slice(&size_um.to_le_bytes());
    header[148..156].copy_from_slice(&size_um.to_le_bytes());
    header[220..228].copy_from_slice(&1.0f64.to_le_bytes());
    header[228..236].copy_from_slice(&1.0f64.to_le_bytes());
    header[348..352].copy_from_slice(&2u32.to_le_bytes());
    let data: Vec<u8> = samples_um.iter().flat_map(|s| s.to_le_bytes()).collect();
    let ifd_at = 8u32;
    let entries = 4u32;
    let data_at = ifd_at + 2 + 12 * entries + 4;
    let header_at = data_at + data.len() as u32;
    let mut b = b"II*\0".to_vec();
    b.extend_from_slice(&ifd_at.to_le_bytes());
    b.extend_from_slice(&(entries as u16).to_le_bytes());
    for (tag, kind, count, value) in [
        (50432u16, 4u16, 1u32, 0x0E03_1301u32),
        (50433, 4, 1, 0x0100_0002),
        (50434, 1, data.len() as u32, data_at),
        (50435, 7, 352, header_at),
    ] {
        b.extend_from_slice(&tag.to_le_bytes());
        b.extend_from_slice(&kind.to_le_bytes());
        b.extend_from_slice(&count.to_le_bytes());
        b.extend_from_slice(&value.to_le_bytes());
    }
    b.extend_from_slice(&0u32.to_le_bytes());
    b.extend(data);
    b.extend(header);
    b
}
