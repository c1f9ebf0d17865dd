//! Gaussian random height maps by FFT filtering of white noise.
//!
//! The spectrum of filtered white noise, `W(f) DFT(n)` with `W(f) = sqrt(S(|f|))`, is drawn
//! directly: a complex Gaussian per frequency pair `(k, -k)` with `X_-k = conj(X_k)` (standard
//! normals from `ChaCha8Rng::seed_from_u64(seed)`, in the order of the frequency grid), and
//! transformed back: `z = IDFT(X)`, real. The map is periodic, Gaussian and isotropic with the PSD
//! shape `S`, scaled so that the expected mean square height is `rms_height^2`
//! (`sum_f W^2 = N rms^2`, the DC bin set to 0 so the map's mean is 0). One inverse transform,
//! no forward one. The transforms use the
//! portable scalar FFT, so a seed gives the same bytes on every machine and thread count.
//!
//! Spectra (`f` = 1/wavelength):
//! * Gaussian autocorrelation `ACF(r) = rms^2 exp(-r^2 / l^2)` (falls to 1/e at the correlation
//!   length `l`): `S(f) = pi l^2 exp(-pi^2 l^2 f^2)`.
//! * Self-affine with Hurst exponent H: `S = 1` for `f_l <= f < f_r` (the roll-off),
//!   `S = (f/f_r)^(-2(1+H))` for `f_r <= f <= f_s`, 0 outside `[f_l, f_s]`, with `f_r` = 1/roll-off
//!   wavelength, `f_s` = 1/short cut-off wavelength (default: none, up to the grid's Nyquist
//!   frequency), `f_l` = 1/long cut-off wavelength (default: none).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rustfft::num_complex::Complex64;

use crate::error::check_positive;
use crate::map::check_grid_size;
use crate::{HeightMap, TopographyError, fft};

/// The PSD shape of a generated map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spectrum {
    /// Gaussian autocorrelation with correlation length (1/e) `correlation_length_m`.
    GaussianAcf {
        /// Correlation length l \[m\].
        correlation_length_m: f64,
    },
    /// Self-affine (fractal) with a roll-off.
    SelfAffine {
        /// Hurst exponent H, 0 < H <= 1.
        hurst: f64,
        /// Roll-off wavelength \[m\]: the PSD is flat at longer wavelengths.
        rolloff_wavelength_m: f64,
        /// Short-wavelength cut-off \[m\] (no power at shorter wavelengths); None = none.
        short_cutoff_wavelength_m: Option<f64>,
        /// Long-wavelength cut-off \[m\] (no power at longer wavelengths); None = none.
        long_cutoff_wavelength_m: Option<f64>,
    },
}

impl Spectrum {
    /// The unnormalised PSD shape at frequency `f` \[1/m\].
    pub fn shape(&self, f: f64) -> f64 {
        match *self {
            Spectrum::GaussianAcf { correlation_length_m: l } => {
                std::f64::consts::PI * l * l * (-(std::f64::consts::PI * l * f).powi(2)).exp()
            }
            Spectrum::SelfAffine {
                hurst,
                rolloff_wavelength_m,
                short_cutoff_wavelength_m,
                long_cutoff_wavelength_m,
            } => {
                let fr = 1.0 / rolloff_wavelength_m;
                if short_cutoff_wavelength_m.is_some_and(|s| f > 1.0 / s)
                    || long_cutoff_wavelength_m.is_some_and(|l| f < 1.0 / l)
                {
                    0.0
                } else if f < fr {
                    1.0
                } else {
                    (f / fr).powf(-2.0 * (1.0 + hurst))
                }
            }
        }
    }

    fn validate(&self) -> Result<(), TopographyError> {
        match *self {
            Spectrum::GaussianAcf { correlation_length_m } => {
                check_positive("correlation_length", correlation_length_m, "m")
            }
            Spectrum::SelfAffine {
                hurst,
                rolloff_wavelength_m,
                short_cutoff_wavelength_m,
                long_cutoff_wavelength_m,
            } => {
                if !(hurst > 0.0 && hurst <= 1.0) {
                    return Err(TopographyError::invalid("hurst", hurst, "a Hurst exponent in (0, 1]"));
                }
                check_positive("rolloff_wavelength", rolloff_wavelength_m, "m")?;
                if let Some(s) = short_cutoff_wavelength_m {
                    check_positive("short_cutoff_wavelength", s, "m")?;
                    if s >= rolloff_wavelength_m {
                        return Err(TopographyError::invalid(
                            "short_cutoff_wavelength",
                            s,
                            "a wavelength below the roll-off wavelength",
                        ));
                    }
                }
                if let Some(l) = long_cutoff_wavelength_m {
                    check_positive("long_cutoff_wavelength", l, "m")?;
                    if l < rolloff_wavelength_m {
                        return Err(TopographyError::invalid(
                            "long_cutoff_wavelength",
                            l,
                            "a wavelength at or above the roll-off wavelength",
                        ));
                    }
                }
                Ok(())
            }
        }
    }
}

/// What to generate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneratorSpec {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Pixel size (both directions) \[m\].
    pub pixel_size_m: f64,
    /// Expected RMS height \[m\].
    pub rms_height_m: f64,
    /// PSD shape.
    pub spectrum: Spectrum,
    /// Seed of the ChaCha8 noise.
    pub seed: u64,
}

/// Generates a Gaussian random map (see the module documentation).
pub fn generate(spec: &GeneratorSpec) -> Result<HeightMap, TopographyError> {
    check_grid_size("generator", spec.nx as u64, spec.ny as u64)?;
    check_positive("pixel_size", spec.pixel_size_m, "m")?;
    check_positive("rms_height", spec.rms_height_m, "m")?;
    spec.spectrum.validate()?;
    let (nx, ny, d) = (spec.nx, spec.ny, spec.pixel_size_m);
    let n = nx * ny;
    // Filter weights in the transposed spectrum layout [kx * ny + ky].
    let (dfx, dfy) = (1.0 / (nx as f64 * d), 1.0 / (ny as f64 * d));
    let fy: Vec<f64> = (0..ny).map(|k| fft::signed_index(k, ny) * dfy).collect();
    let mut weights = vec![0.0; n];
    let mut total = 0.0;
    for kx in 0..nx {
        let fx = fft::signed_index(kx, nx) * dfx;
        for ky in 0..ny {
            if kx == 0 && ky == 0 {
                continue;
            }
            let s = spec.spectrum.shape((fx * fx + fy[ky] * fy[ky]).sqrt());
            weights[kx * ny + ky] = s;
            total += s;
        }
    }
    if !(total > 0.0 && total.is_finite()) {
        return Err(TopographyError::invalid(
            "spectrum",
            format!("{:?}", spec.spectrum),
            format!("a spectrum with power between the map's frequencies 1/{} m and Nyquist", nx.max(ny) as f64 * d),
        ));
    }
    // A Hermitian spectrum drawn directly: X_k = sqrt(N) W_k (a + i b)/sqrt(2) and X_-k = conj(X_k)
    // (a, b standard normal), X_k = sqrt(N) W_k a where k = -k; then E|X_k|^2 = N W_k^2, as for
    // the DFT of white noise filtered by W, and the inverse DFT is real. With W^2 = N rms^2 S / sum S
    // and the inverse DFT's 1/N folded in, the factor is sqrt(N rms^2 / sum S) / sqrt(N).
    let k = (spec.rms_height_m * spec.rms_height_m / total).sqrt();
    let mut rng = ChaCha8Rng::seed_from_u64(spec.seed);
    let mut spectrum = vec![Complex64::new(0.0, 0.0); n];
    let half = std::f64::consts::FRAC_1_SQRT_2;
    for kx in 0..nx {
        let mx = (nx - kx) % nx;
        for ky in 0..ny {
            let my = (ny - ky) % ny;
            let (i, m) = (kx * ny + ky, mx * ny + my);
            if m < i {
                continue; // drawn with its mirror
            }
            let w = weights[i].sqrt() * k;
            let a: f64 = StandardNormal.sample(&mut rng);
            if m == i {
                spectrum[i] = Complex64::new(w * a, 0.0);
            } else {
                let b: f64 = StandardNormal.sample(&mut rng);
                spectrum[i] = Complex64::new(w * a * half, w * b * half);
                spectrum[m] = spectrum[i].conj();
            }
        }
    }
    drop(weights);
    let grid = fft::inverse_2d(spectrum, nx, ny, true);
    HeightMap::new(nx, ny, d, d, grid.into_iter().map(|c| c.re).collect())
}
