//! Synthetic height fields for tests and the `stiction bem` command: Gaussian self-affine surfaces
//! by Fourier filtering of seeded white noise, and the spectral rms slope.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use realfft::num_complex::Complex;

use crate::error::{BemError, check_positive};
use crate::fft::Fft2;
use crate::grid::{Grid, block_sum};

/// A Gaussian, isotropic, self-affine random surface on `grid` (m, row-major, zero mean): white
/// noise drawn from `ChaCha8Rng::seed_from_u64(seed)` in row-major order, filtered in Fourier
/// space by the amplitude `sqrt(C(q))` of the power spectrum
/// `C(q) = 1` for `q < q_r`, `(q/q_r)^(-2(1+H))` for `q_r <= q <= q_s`, 0 above `q_s` (and at
/// `q = 0`), with `q_r = 2 pi/roll_off_wavelength_m`, `q_s = 2 pi/short_wavelength_m` and Hurst
/// exponent `H` in (0, 1]; then scaled to the rms height `rms_height_m`. Same seed, same bytes.
pub fn self_affine(
    grid: Grid,
    hurst: f64,
    roll_off_wavelength_m: f64,
    short_wavelength_m: f64,
    rms_height_m: f64,
    seed: u64,
) -> Result<Vec<f64>, BemError> {
    if !(hurst > 0.0 && hurst <= 1.0) {
        return Err(BemError::Value { name: "hurst", value: hurst, expected: "a Hurst exponent in (0, 1]" });
    }
    check_positive("roll_off_wavelength_m", roll_off_wavelength_m, "a finite wavelength > 0 (m)")?;
    check_positive("short_wavelength_m", short_wavelength_m, "a finite wavelength > 0 (m)")?;
    check_positive("rms_height_m", rms_height_m, "a finite rms height > 0 (m)")?;
    if short_wavelength_m > roll_off_wavelength_m {
        return Err(BemError::Value {
            name: "short_wavelength_m",
            value: short_wavelength_m,
            expected: "a short-wavelength cut-off <= the roll-off wavelength",
        });
    }
    let n = grid.len();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut h: Vec<f64> = (0..n).map(|_| StandardNormal.sample(&mut rng)).collect();
    let fft = Fft2::new(grid.nx, grid.ny);
    let mut rows = vec![Complex::default(); fft.spectrum_len()];
    let mut spec = vec![Complex::default(); fft.spectrum_len()];
    fft.forward(&mut h, &mut rows, &mut spec);
    let (qr, qs) =
        (2.0 * std::f64::consts::PI / roll_off_wavelength_m, 2.0 * std::f64::consts::PI / short_wavelength_m);
    let ny = grid.ny;
    for kx in 0..fft.nxc() {
        for ky in 0..ny {
            let q = grid.wavenumber(kx, ky);
            let amp = if q == 0.0 || q > qs * (1.0 + 1e-12) {
                0.0
            } else if q < qr {
                1.0
            } else {
                (q / qr).powf(-(1.0 + hurst))
            };
            spec[kx * ny + ky] *= amp;
        }
    }
    fft.inverse(&mut spec, &mut rows, &mut h);
    let rms = (block_sum(n, |r| h[r].iter().map(|v| v * v).sum()) / n as f64).sqrt();
    if rms.is_nan() || rms <= 0.0 {
        return Err(BemError::Value {
            name: "short_wavelength_m",
            value: short_wavelength_m,
            expected: "a band that holds at least one wave vector of the grid (2 dx <= wavelengths <= cell size)",
        });
    }
    let f = rms_height_m / rms;
    h.iter_mut().for_each(|v| *v *= f);
    Ok(h)
}

/// Rms slope `h'_rms = sqrt(mean |grad h|^2)` (dimensionless), evaluated spectrally
/// (`sum q^2 |h(q)|^2 / N^2` by Parseval), the definition consistent with the solver's kernel.
pub fn rms_slope(heights_m: &[f64], grid: Grid) -> f64 {
    let fft = Fft2::new(grid.nx, grid.ny);
    let mut h = heights_m.to_vec();
    let mut rows = vec![Complex::default(); fft.spectrum_len()];
    let mut spec = vec![Complex::default(); fft.spectrum_len()];
    fft.forward(&mut h, &mut rows, &mut spec);
    let (nxc, ny) = (fft.nxc(), grid.ny);
    let mut s = 0.0;
    for kx in 0..nxc {
        // The half spectrum holds each kx in 1..nx/2 once for the pair (kx, -kx).
        let w = if kx == 0 || (grid.nx.is_multiple_of(2) && kx == nxc - 1) { 1.0 } else { 2.0 };
        let mut col = 0.0;
        for ky in 0..ny {
            let q = grid.wavenumber(kx, ky);
            col += q * q * spec[kx * ny + ky].norm_sqr();
        }
        s += w * col;
    }
    let n = grid.len() as f64;
    (s / (n * n)).sqrt()
}
