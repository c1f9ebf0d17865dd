//! Reading one channel of an instrument file in parts: the header, then the channel's samples
//! straight into the map's float64 buffer, a cache-sized chunk at a time.
//!
//! The whole-file route (read every byte into memory, parse the header, decode the samples into a
//! new vector, pass over the heights again to count the missing ones and check their range) writes
//! the file's bytes once into a buffer as large as the file and reads them back, then reads the
//! heights back once more. Reading in parts:
//!
//! 1. reads the first [`HEADER_PREFIX_BYTES`] into a buffer of the file's size whose other pages
//!    are not yet touched (zero-filled on demand by the kernel, so the unread part costs no memory
//!    traffic), detects the format and parses the channels there: this gives the chosen channel's
//!    samples, a byte range `R`;
//! 2. reads every byte outside `R` (the rest of the header, the other channels, trailers such as
//!    an Igor wave's note) and parses again: that parse has seen every byte but `R` and is the one
//!    used, if it gives the same range `R` for the chosen channel (else, and whenever the first parse
//!    fails, the rest of the file is read and the whole-file route decides, errors included);
//! 3. decodes `R` from the file a chunk of [`CHUNK_BYTES`] at a time (the chunk stays in the
//!    core's cache) into the map's vector, scaling to metres, in the map's row order, counting the
//!    missing pixels and the largest |height| on each chunk while it is in cache.
//!
//! The result is the whole-file route's, bit for bit, for every reader whose parse does not look at
//! the bytes of the samples it returns (none does: a header states where the samples are); a test
//! holds the two routes equal on every shared instrument file and on the fuzz harness's mutated
//! files (`crates/topography/tests/fuzz.rs`).

use std::mem::MaybeUninit;

use stiction_units::io::{InputFile, advise_huge_pages};

use super::{Channel, Missing, Raster, Sample, Values};
use crate::{MAX_PIXELS, TopographyError};

/// Bytes read first to find the header: 256 KiB (NanoScope headers are 20 to 80 kB, the other
/// formats' a few hundred bytes to a few kB; a longer header makes the first parse fail, and the
/// whole file is read).
pub(crate) const HEADER_PREFIX_BYTES: usize = 256 << 10;

/// Bytes of samples read and decoded at a time: 128 KiB, which with the 512 KiB of float64 they
/// become stays within a core's level-2 cache.
pub(crate) const CHUNK_BYTES: usize = 128 << 10;

/// Where bytes come from: a file ([`InputFile`], read with bounded positional reads) or bytes
/// already in memory.
pub(crate) trait ByteSource {
    /// The source's size, bytes.
    fn size_bytes(&self) -> usize;
    /// Fills `buf` from `offset`.
    fn read_at(&self, offset: usize, buf: &mut [u8]) -> Result<(), TopographyError>;
    /// `len` bytes from `offset`: borrowed where the source is memory, else read into `buf`.
    fn bytes_at<'a>(&'a self, offset: usize, len: usize, buf: &'a mut Vec<u8>) -> Result<&'a [u8], TopographyError> {
        buf.resize(len, 0);
        self.read_at(offset, buf)?;
        Ok(buf)
    }
}

impl ByteSource for InputFile {
    fn size_bytes(&self) -> usize {
        InputFile::size_bytes(self) as usize
    }
    fn read_at(&self, offset: usize, buf: &mut [u8]) -> Result<(), TopographyError> {
        Ok(InputFile::read_at(self, offset as u64, buf)?)
    }
}

impl ByteSource for [u8] {
    fn size_bytes(&self) -> usize {
        self.len()
    }
    fn read_at(&self, offset: usize, buf: &mut [u8]) -> Result<(), TopographyError> {
        match offset.checked_add(buf.len()).filter(|&e| e <= self.len()) {
            Some(end) => {
                buf.copy_from_slice(&self[offset..end]);
                Ok(())
            }
            None => Err(TopographyError::format("bytes", 0, "a read past the end of the bytes")),
        }
    }
    fn bytes_at<'a>(&'a self, offset: usize, len: usize, _buf: &'a mut Vec<u8>) -> Result<&'a [u8], TopographyError> {
        offset
            .checked_add(len)
            .filter(|&e| e <= self.len())
            .map(|e| &self[offset..e])
            .ok_or_else(|| TopographyError::format("bytes", 0, "a read past the end of the bytes"))
    }
}

/// The count of NaN heights and the largest |height| (NaN ignored, 0 for none).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct HeightTally {
    pub nan: usize,
    pub largest: f64,
}

impl HeightTally {
    /// Adds `h`: eight independent lanes, so the loop vectorises; a count and a maximum do not
    /// depend on the order, so the result is the one-by-one fold's exactly. The count is kept in
    /// float64 lanes (exact below 2^53, and a map has at most 2^25 pixels) so that it vectorises
    /// with the rest.
    pub(crate) fn add(&mut self, h: &[f64]) {
        let mut n = [0.0f64; 8];
        let mut m = [0.0f64; 8];
        let mut it = h.chunks_exact(8);
        for c in &mut it {
            for j in 0..8 {
                let a = c[j].abs();
                n[j] += if a.is_nan() { 1.0 } else { 0.0 };
                // `a > m` is false for NaN: NaN is left out, as `f64::max` leaves it out.
                m[j] = if a > m[j] { a } else { m[j] };
            }
        }
        for &x in it.remainder() {
            n[0] += if x.is_nan() { 1.0 } else { 0.0 };
            m[0] = m[0].max(x.abs());
        }
        self.nan += n.iter().sum::<f64>() as usize;
        self.largest = m.iter().fold(self.largest, |a, &b| a.max(b));
    }
}

/// The byte range `[start, end)` of a raster channel's samples, if it lies in a source of `size`
/// bytes (`None` for parsed values, a grid past [`MAX_PIXELS`] or a range past the end).
pub(crate) fn raster_span(ch: &Channel, size: usize) -> Option<(usize, usize)> {
    let Values::Raster(r) = &ch.values else { return None };
    let (nx, ny) = (ch.info.nx, ch.info.ny);
    nx.checked_mul(ny).filter(|&n| n as u64 <= MAX_PIXELS && n > 0)?;
    let line = nx * r.sample.bytes();
    let stride = r.row_bytes.unwrap_or(line).max(line);
    let span = stride.checked_mul(ny - 1)?.checked_add(line)?;
    let end = r.offset.checked_add(span)?;
    (end <= size).then_some((r.offset, end))
}

/// A channel's values in metres: sample x `scale` + `shift` (the raster's, times `unit`, the metres
/// per unit the file states, or 1), then x `post` (the metres per unit given when the file states
/// none, else 1: x 1 changes no bit), NaN where missing, row-major in the map's order; with their
/// tally. The vector is allocated once at its final size (huge pages asked for when large) and
/// filled in order, never zeroed first.
/// The checks made before a channel is decoded from a source of `size` bytes: its grid within
/// [`MAX_PIXELS`], its values all there (parsed) or its samples inside the source (raster).
pub(crate) fn check_channel(ch: &Channel, size: usize, origin: &str) -> Result<usize, TopographyError> {
    let (nx, ny) = (ch.info.nx, ch.info.ny);
    let n = nx.checked_mul(ny).filter(|&n| n as u64 <= MAX_PIXELS).ok_or_else(|| TopographyError::TooLarge {
        origin: origin.into(),
        nx: nx as u64,
        ny: ny as u64,
        limit: MAX_PIXELS,
    })?;
    match &ch.values {
        Values::Parsed(v) if v.len() != n => {
            Err(TopographyError::format(origin, 0, format!("{} values, expected {nx} x {ny}", v.len())))
        }
        Values::Raster(r) if n > 0 && raster_span(ch, size).is_none() => Err(TopographyError::format(
            origin,
            0,
            format!(
                "channel {} needs {nx} x {ny} x {} bytes from byte {}, but the file has {size} bytes",
                ch.info.index,
                r.sample.bytes(),
                r.offset,
            ),
        )),
        _ => Ok(n),
    }
}

/// A channel's values in metres: sample x `scale` + `shift` (the raster's, times `unit`, the metres
/// per unit the file states, or 1), then x `post` (the metres per unit given when the file states
/// none, else 1: x 1 changes no bit), NaN where missing, row-major in the map's order; with their
/// tally. The vector is allocated once at its final size (huge pages asked for when large) and
/// filled in order, never zeroed first.
pub(crate) fn decode_channel<S: ByteSource + ?Sized>(
    ch: &Channel,
    src: &S,
    origin: &str,
    unit: f64,
    post: f64,
) -> Result<(Vec<f64>, HeightTally), TopographyError> {
    let n = check_channel(ch, src.size_bytes(), origin)?;
    let (nx, ny) = (ch.info.nx, ch.info.ny);
    let mut tally = HeightTally::default();
    let r = match &ch.values {
        Values::Parsed(v) => {
            let out: Vec<f64> = v.iter().map(|x| x * unit * post).collect();
            tally.add(&out);
            return Ok((out, tally));
        }
        Values::Raster(r) => r,
    };
    let size = r.sample.bytes();
    let mut out: Vec<f64> = Vec::with_capacity(n);
    advise_huge_pages::<MaybeUninit<f64>>(out.spare_capacity_mut());
    if n == 0 {
        return Ok((out, tally));
    }
    let line = nx * size;
    let stride = r.row_bytes.unwrap_or(line).max(line);
    let k = (r.scale * unit, r.shift * unit, post);
    let mut buf = Vec::new();
    // The file row of the map's row `iy`.
    let file_row = |iy: usize| if r.flip_y { ny - 1 - iy } else { iy };
    if stride <= CHUNK_BYTES {
        // Whole rows a chunk: the file rows of map rows iy..iy+rows, contiguous in the file
        // (descending when flipped), read in one part.
        let rows_per = (CHUNK_BYTES / stride).max(1);
        let mut iy = 0;
        while iy < ny {
            let rows = rows_per.min(ny - iy);
            let lo = file_row(iy).min(file_row(iy + rows - 1));
            let bytes = src.bytes_at(r.offset + lo * stride, (rows - 1) * stride + line, &mut buf)?;
            for j in iy..iy + rows {
                let at = (file_row(j) - lo) * stride;
                let start = out.len();
                convert_row(&bytes[at..at + line], r, k, r.flip_x, &mut out);
                // Tallied while the row is in the level-1 cache.
                tally.add(&out[start..]);
            }
            iy += rows;
        }
    } else {
        // A row longer than a chunk: in pieces of whole samples, the pieces in the map's order
        // (from the row's end when the row is flipped along x).
        let per = (CHUNK_BYTES / size).max(1);
        for iy in 0..ny {
            let row_at = r.offset + file_row(iy) * stride;
            let mut done = 0;
            while done < nx {
                let m = per.min(nx - done);
                let c0 = if r.flip_x { nx - done - m } else { done };
                let bytes = src.bytes_at(row_at + c0 * size, m * size, &mut buf)?;
                let start = out.len();
                convert_row(bytes, r, k, r.flip_x, &mut out);
                tally.add(&out[start..]);
                done += m;
            }
        }
    }
    debug_assert_eq!(out.len(), n);
    Ok((out, tally))
}

/// Appends samples as values, in reverse when `reverse`: a tight loop per sample type and byte
/// order (`from` a function item, inlined, not a function pointer called per sample; the branch on
/// the missing-value marker only where the format has one).
fn convert<const N: usize, T: Into<f64>, F: Fn([u8; N]) -> T>(
    line: &[u8],
    out: &mut Vec<f64>,
    from: F,
    (scale, shift, post): (f64, f64, f64),
    invalid: Option<Missing>,
    reverse: bool,
) {
    let it = line.chunks_exact(N).map(|c| from(c.try_into().unwrap_or([0; N])).into());
    if reverse {
        push(it.rev(), out, scale, shift, post, invalid);
    } else {
        push(it, out, scale, shift, post, invalid);
    }
}

#[inline(always)]
fn push(
    it: impl Iterator<Item = f64>,
    out: &mut Vec<f64>,
    scale: f64,
    shift: f64,
    post: f64,
    invalid: Option<Missing>,
) {
    match invalid {
        // The value computed for every sample, then chosen: a select, not a branch, so it vectorises.
        Some(Missing::Equal(inv)) => out.extend(it.map(|v: f64| {
            let h = (v * scale + shift) * post;
            if v == inv { f64::NAN } else { h }
        })),
        Some(Missing::AtLeast(inv)) => out.extend(it.map(|v: f64| {
            let h = (v * scale + shift) * post;
            if v >= inv { f64::NAN } else { h }
        })),
        None => out.extend(it.map(|v: f64| (v * scale + shift) * post)),
    }
}

fn convert_row(line: &[u8], r: &Raster, k: (f64, f64, f64), reverse: bool, out: &mut Vec<f64>) {
    let inv = r.invalid;
    let be = r.big_endian;
    match r.sample {
        Sample::I8 => convert(line, out, i8::from_le_bytes, k, inv, reverse),
        Sample::U8 => convert(line, out, u8::from_le_bytes, k, inv, reverse),
        Sample::I16 if be => convert(line, out, i16::from_be_bytes, k, inv, reverse),
        Sample::I16 => convert(line, out, i16::from_le_bytes, k, inv, reverse),
        Sample::U16 if be => convert(line, out, u16::from_be_bytes, k, inv, reverse),
        Sample::U16 => convert(line, out, u16::from_le_bytes, k, inv, reverse),
        Sample::I32 if be => convert(line, out, i32::from_be_bytes, k, inv, reverse),
        Sample::I32 => convert(line, out, i32::from_le_bytes, k, inv, reverse),
        Sample::U32 if be => convert(line, out, u32::from_be_bytes, k, inv, reverse),
        Sample::U32 => convert(line, out, u32::from_le_bytes, k, inv, reverse),
        Sample::F32 if be => convert(line, out, f32::from_be_bytes, k, inv, reverse),
        Sample::F32 => convert(line, out, f32::from_le_bytes, k, inv, reverse),
        Sample::F64 if be => convert(line, out, f64::from_be_bytes, k, inv, reverse),
        Sample::F64 => convert(line, out, f64::from_le_bytes, k, inv, reverse),
    }
}
