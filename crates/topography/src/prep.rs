//! Preparation of a map before its statistics: levelling and the Gaussian cut-off filters.
//!
//! * Levelling subtracts the least-squares polynomial of degree 0 (mean), 1 (plane), 2 or 3 in x
//!   and y over the valid pixels (coordinates scaled to [-1, 1] for conditioning).
//! * The short-wavelength cut-off lambda_s is a Gaussian low-pass filter and the long-wavelength
//!   cut-off lambda_c a Gaussian high-pass (the map minus its low-pass at lambda_c), both with the
//!   weighting function of ISO 16610-21, `s(x) = exp(-pi (x / (alpha lambda))^2) / (alpha lambda)`,
//!   `alpha = sqrt(ln 2 / pi)`: a sinusoid of wavelength lambda passes with 50 % amplitude. In two
//!   dimensions the filter is the product of the x and y filters (isotropic), applied as normalised
//!   convolution (`(s * (z m)) / (s * m)` with `m` the mask of valid pixels), so missing pixels and
//!   the map's edges do not pull heights towards zero. Missing pixels stay missing.
//!
//! Summit statistics depend on the scale at which they are taken; the cut-offs used are part of
//! every report ([`PreparationReport`]).

use std::str::FromStr;

use nalgebra::{DMatrix, DVector};
use rustfft::num_complex::Complex64;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::error::check_positive;
use crate::{HeightMap, TopographyError};

/// How the map is levelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Levelling {
    /// Heights as read.
    None,
    /// Subtract the mean height.
    Mean,
    /// Subtract the least-squares plane (default).
    #[default]
    Plane,
    /// Subtract the least-squares polynomial of degree 2 in x and y.
    Poly2,
    /// Subtract the least-squares polynomial of degree 3 in x and y.
    Poly3,
}
stiction_units::display_serde_name!(Levelling);

impl Levelling {
    /// Polynomial degree removed, `None` for no levelling.
    pub fn degree(self) -> Option<usize> {
        match self {
            Levelling::None => None,
            Levelling::Mean => Some(0),
            Levelling::Plane => Some(1),
            Levelling::Poly2 => Some(2),
            Levelling::Poly3 => Some(3),
        }
    }
}

impl FromStr for Levelling {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "none" => Ok(Levelling::None),
            "mean" => Ok(Levelling::Mean),
            "plane" => Ok(Levelling::Plane),
            "poly2" => Ok(Levelling::Poly2),
            "poly3" => Ok(Levelling::Poly3),
            _ => Err(format!("unknown levelling `{s}`: expected none, mean, plane, poly2 or poly3")),
        }
    }
}

/// What to do to a map before taking its statistics.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Preparation {
    /// Levelling (default: plane).
    pub levelling: Levelling,
    /// Short-wavelength cut-off lambda_s \[m\]: Gaussian low-pass; `None` = none.
    pub short_cutoff_m: Option<f64>,
    /// Long-wavelength cut-off lambda_c \[m\]: Gaussian high-pass; `None` = none.
    pub long_cutoff_m: Option<f64>,
}

/// What was done, for the report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PreparationReport {
    /// The levelling applied.
    pub levelling: Levelling,
    /// RMS of the polynomial that was subtracted \[m\] (0 for none).
    pub levelling_removed_rms_m: f64,
    /// Short-wavelength cut-off lambda_s \[m\] (Gaussian, 50 % transmission), null if none.
    pub short_cutoff_m: Option<f64>,
    /// Long-wavelength cut-off lambda_c \[m\] (Gaussian, 50 % transmission), null if none.
    pub long_cutoff_m: Option<f64>,
    /// Why a cut-off is null: none of that kind was applied.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cutoff_note: Option<&'static str>,
}

/// Levels and filters a map (see the module documentation).
pub fn prepare(map: &HeightMap, prep: &Preparation) -> Result<(HeightMap, PreparationReport), TopographyError> {
    if let Some(s) = prep.short_cutoff_m {
        check_positive("short_cutoff", s, "m")?;
    }
    if let Some(l) = prep.long_cutoff_m {
        check_positive("long_cutoff", l, "m")?;
    }
    // A cut-off longer than the map would filter with a kernel wider than the map (at 1 m on a
    // 5 um map, 10^6-pixel kernels on every line): refused, with the map's size.
    let longest_m = map.length_x_m().max(map.length_y_m());
    for (field, cut) in [("short_cutoff", prep.short_cutoff_m), ("long_cutoff", prep.long_cutoff_m)] {
        if let Some(c) = cut
            && c > longest_m
        {
            return Err(TopographyError::invalid(
                field,
                format!("{c:e} m"),
                format!(
                    "a wavelength no longer than the map, whose longer side is {:.4} um ({} x {} pixels of {:.4} x {:.4} nm)",
                    longest_m * 1e6,
                    map.nx(),
                    map.ny(),
                    map.dx_m() * 1e9,
                    map.dy_m() * 1e9
                ),
            ));
        }
    }
    if let (Some(s), Some(l)) = (prep.short_cutoff_m, prep.long_cutoff_m)
        && s >= l
    {
        return Err(TopographyError::invalid(
            "short_cutoff",
            format!("{s:e} m"),
            format!("a wavelength below the long-wavelength cut-off {l} m"),
        ));
    }
    let mut out = map.clone();
    let removed = match prep.levelling.degree() {
        Some(d) => level_polynomial(&mut out, d)?,
        None => 0.0,
    };
    if let Some(s) = prep.short_cutoff_m {
        let smooth = gaussian_smooth(&out, s);
        for (h, s) in out.heights_mut().iter_mut().zip(smooth) {
            *h = s;
        }
    }
    if let Some(l) = prep.long_cutoff_m {
        let smooth = gaussian_smooth(&out, l);
        for (h, s) in out.heights_mut().iter_mut().zip(smooth) {
            *h -= s;
        }
    }
    Ok((
        out,
        PreparationReport {
            levelling: prep.levelling,
            levelling_removed_rms_m: removed,
            short_cutoff_m: prep.short_cutoff_m,
            long_cutoff_m: prep.long_cutoff_m,
            cutoff_note: (prep.short_cutoff_m.is_none() || prep.long_cutoff_m.is_none())
                .then_some("a null cut-off was not applied (none given)"),
        },
    ))
}

/// Subtracts the least-squares polynomial of total degree `degree`; returns its RMS over the valid
/// pixels \[m\].
fn level_polynomial(map: &mut HeightMap, degree: usize) -> Result<f64, TopographyError> {
    let (nx, ny) = (map.nx(), map.ny());
    let terms: Vec<(usize, usize)> = (0..=degree).flat_map(|t| (0..=t).map(move |j| (t - j, j))).collect();
    let nt = terms.len();
    let scale = |i: usize, n: usize| if n > 1 { 2.0 * i as f64 / (n - 1) as f64 - 1.0 } else { 0.0 };
    let powers = |u: f64| -> [f64; 4] { [1.0, u, u * u, u * u * u] };
    let ux: Vec<[f64; 4]> = (0..nx).map(|i| powers(scale(i, nx))).collect();
    // Normal equations in plain arrays (at most 10 terms), upper triangle.
    let mut ata_a = [0.0f64; 100];
    let mut atz_a = [0.0f64; 10];
    let mut phi = [0.0f64; 10];
    let mut count = 0usize;
    for iy in 0..ny {
        let vy = powers(scale(iy, ny));
        for (ix, &z) in map.row(iy).iter().enumerate() {
            if z.is_nan() {
                continue;
            }
            count += 1;
            for (k, &(a, b)) in terms.iter().enumerate() {
                phi[k] = ux[ix][a] * vy[b];
            }
            for r in 0..nt {
                atz_a[r] += phi[r] * z;
                for c in r..nt {
                    ata_a[r * 10 + c] += phi[r] * phi[c];
                }
            }
        }
    }
    let mut ata = DMatrix::<f64>::zeros(nt, nt);
    let mut atz = DVector::<f64>::zeros(nt);
    for r in 0..nt {
        atz[r] = atz_a[r];
        for c in r..nt {
            ata[(r, c)] = ata_a[r * 10 + c];
        }
    }
    if count < nt {
        return Err(TopographyError::invalid(
            "levelling",
            format!("degree {degree}"),
            format!("at least {nt} valid pixels, found {count}"),
        ));
    }
    for r in 0..nt {
        for c in 0..r {
            ata[(r, c)] = ata[(c, r)];
        }
    }
    let coef = ata.cholesky().map(|ch| ch.solve(&atz)).ok_or_else(|| {
        TopographyError::invalid("levelling", format!("degree {degree}"), "valid pixels spread enough to fit it")
    })?;
    let mut sum2 = 0.0;
    let h = map.heights_mut();
    for iy in 0..ny {
        let vy = powers(scale(iy, ny));
        for ix in 0..nx {
            let z = &mut h[iy * nx + ix];
            if z.is_nan() {
                continue;
            }
            let p: f64 = terms.iter().enumerate().map(|(k, &(a, b))| coef[k] * ux[ix][a] * vy[b]).sum();
            *z -= p;
            sum2 += p * p;
        }
    }
    Ok((sum2 / count as f64).sqrt())
}

/// `alpha = sqrt(ln 2 / pi)` of ISO 16610-21.
const ALPHA: f64 = 0.469_718_639_349_826_3;

/// The Gaussian filter's standard deviation in pixels for cut-off `lambda` and pixel size `d`:
/// `exp(-pi (x/(alpha lambda))^2) = exp(-x^2 / (2 s^2))` gives `s = alpha lambda / sqrt(2 pi)`.
fn sigma_pixels(lambda: f64, d: f64) -> f64 {
    ALPHA * lambda / (2.0 * std::f64::consts::PI).sqrt() / d
}

/// Normalised Gaussian low-pass of the map at cut-off `lambda` \[m\]; NaN where the map is NaN.
pub(crate) fn gaussian_smooth(map: &HeightMap, lambda: f64) -> Vec<f64> {
    let (nx, ny) = (map.nx(), map.ny());
    // re = z m, im = m: one complex convolution filters both (the kernel is real).
    let mut g: Vec<Complex64> = map
        .heights_m()
        .iter()
        .map(|&z| if z.is_nan() { Complex64::new(0.0, 0.0) } else { Complex64::new(z, 1.0) })
        .collect();
    let sx = sigma_pixels(lambda, map.dx_m());
    let sy = sigma_pixels(lambda, map.dy_m());
    let fx = LineFilter::new(sx, nx);
    for iy in 0..ny {
        fx.apply(&mut g[iy * nx..(iy + 1) * nx]);
    }
    let fy = LineFilter::new(sy, ny);
    let mut col = vec![Complex64::new(0.0, 0.0); ny];
    for ix in 0..nx {
        for iy in 0..ny {
            col[iy] = g[iy * nx + ix];
        }
        fy.apply(&mut col);
        for iy in 0..ny {
            g[iy * nx + ix] = col[iy];
        }
    }
    map.heights_m()
        .iter()
        .zip(g)
        .map(|(&z, c)| if z.is_nan() || c.im <= 1e-12 { f64::NAN } else { c.re / c.im })
        .collect()
}

/// A sampled Gaussian of SD `sigma` pixels (truncated at 5 sigma, normalised to unit sum) for
/// lines of length `n`, zero outside the line: direct for short kernels, by FFT otherwise.
struct LineFilter {
    w: Vec<f64>,
    /// Forward and inverse plans and the kernel's spectrum (scaled by 1/len) for long kernels.
    fft: Option<(FftPlan, FftPlan, Vec<Complex64>)>,
}

type FftPlan = std::sync::Arc<dyn rustfft::Fft<f64>>;

impl LineFilter {
    fn new(sigma: f64, n: usize) -> Self {
        // Truncated at 5 sigma and at the line's length (weights beyond it never meet a pixel; the
        // normalised convolution divides the normalisation out), so the kernel is bounded by the
        // map whatever sigma is.
        let r = (5.0 * sigma).ceil().clamp(1.0, n.max(1) as f64) as usize;
        let w: Vec<f64> = (0..=r).map(|k| (-(k as f64).powi(2) / (2.0 * sigma * sigma)).exp()).collect();
        let norm: f64 = w[0] + 2.0 * w[1..].iter().sum::<f64>();
        let w: Vec<f64> = w.iter().map(|v| v / norm).collect();
        let fft = (r > 48).then(|| {
            let len = (n + 2 * r + 1).next_power_of_two();
            let mut ker = vec![Complex64::new(0.0, 0.0); len];
            for k in 0..=r.min(len / 2 - 1) {
                ker[k] = Complex64::new(w[k] / len as f64, 0.0);
                if k > 0 {
                    ker[len - k] = ker[k];
                }
            }
            let fwd = crate::fft::plan(len, false, false);
            fwd.process(&mut ker);
            (fwd, crate::fft::plan(len, true, false), ker)
        });
        LineFilter { w, fft }
    }

    fn apply(&self, line: &mut [Complex64]) {
        let n = line.len();
        match &self.fft {
            None => {
                let r = self.w.len() - 1;
                let src = line.to_vec();
                for (i, out) in line.iter_mut().enumerate() {
                    let lo = i.saturating_sub(r);
                    let hi = (i + r).min(n - 1);
                    let mut acc = Complex64::new(0.0, 0.0);
                    for (j, s) in src.iter().enumerate().take(hi + 1).skip(lo) {
                        acc += s * self.w[i.abs_diff(j)];
                    }
                    *out = acc;
                }
            }
            Some((fwd, inv, ker)) => {
                let mut buf = vec![Complex64::new(0.0, 0.0); ker.len()];
                buf[..n].copy_from_slice(line);
                fwd.process(&mut buf);
                for (b, k) in buf.iter_mut().zip(ker) {
                    *b *= k;
                }
                inv.process(&mut buf);
                line.copy_from_slice(&buf[..n]);
            }
        }
    }
}
