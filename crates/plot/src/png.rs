//! PNG encoding of an RGB8 buffer (with the pixel density when known), for rasters and the images
//! embedded in SVG.

/// Encodes an RGB8 buffer as PNG.
pub(crate) fn encode_png(rgb: &[u8], w: u32, h: u32, out: &mut Vec<u8>) -> Result<(), String> {
    encode_png_dpi(rgb, w, h, None, out)
}

/// Encodes an RGB8 buffer as PNG, with a `pHYs` chunk stating `dpi` when given (so a word
/// processor places the figure at its physical size).
pub(crate) fn encode_png_dpi(rgb: &[u8], w: u32, h: u32, dpi: Option<f64>, out: &mut Vec<u8>) -> Result<(), String> {
    use image::ImageEncoder;
    let mut plain = Vec::new();
    image::codecs::png::PngEncoder::new(&mut plain)
        .write_image(rgb, w, h, image::ColorType::Rgb8)
        .map_err(|e| e.to_string())?;
    let Some(dpi) = dpi else {
        *out = plain;
        return Ok(());
    };
    // Insert pHYs (pixels per metre) after IHDR: signature 8 bytes, IHDR chunk 25 bytes.
    let ppm = (dpi / 0.0254).round() as u32;
    let mut chunk = Vec::with_capacity(21);
    chunk.extend_from_slice(&9u32.to_be_bytes());
    let mut body = b"pHYs".to_vec();
    body.extend_from_slice(&ppm.to_be_bytes());
    body.extend_from_slice(&ppm.to_be_bytes());
    body.push(1);
    chunk.extend_from_slice(&body);
    chunk.extend_from_slice(&crc32(&body).to_be_bytes());
    out.clear();
    out.extend_from_slice(&plain[..33]);
    out.extend_from_slice(&chunk);
    out.extend_from_slice(&plain[33..]);
    Ok(())
}

/// CRC-32 (ISO 3309) of a PNG chunk's type and data.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xffff_ffffu32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 { 0xedb8_8320 ^ (c >> 1) } else { c >> 1 };
        }
    }
    !c
}
