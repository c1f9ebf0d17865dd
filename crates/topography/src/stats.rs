//! Statistics of a (prepared) height map and its summits, and Nayak's random-process predictions.
//!
//! # Moments
//! Over the valid pixels, with the mean height removed: `m0 = <z^2>` (`rms_height = sqrt(m0)`,
//! ISO 25178 Sq); with forward differences `z_x = (z(x+dx) - z(x))/dx` and second differences
//! `z_xx = (z(x+dx) - 2 z(x) + z(x-dx))/dx^2` over the pixel pairs and triples that have heights,
//! the profile moments averaged over x and y, `m2 = (<z_x^2> + <z_y^2>)/2`,
//! `m4 = (<z_xx^2> + <z_yy^2>)/2`; `rms_slope = sqrt(<z_x^2> + <z_y^2>)` (Sdq), and
//! `rms_curvature = sqrt(m4)`. These are the moments of the map as sampled, with the same
//! differences that give the summit curvature, so the prediction and the count see the same scale.
//!
//! # Nayak (1971, 1973) for an isotropic Gaussian surface
//! Bandwidth `alpha = m0 m4 / m2^2`; summit density `D = m4 / (6 pi sqrt(3) m2)` (exact for every
//! alpha); and for large alpha (McCool 1986, Wear 107, 37-60, eq. 9-12): mean summit height
//! `4 sqrt(m0 / (pi alpha))`, summit height SD `sqrt(1 - 0.8968/alpha) sqrt(m0)`, mean summit
//! curvature `(8/3) sqrt(m4 / pi)`.

use rustfft::num_complex::Complex64;
use serde::Serialize;

use crate::summits::Summits;
use crate::{HeightMap, fft};

/// Counted summit statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SummitStats {
    /// Number of summits.
    pub count: usize,
    /// Area in which summits were sought (candidate pixels times `dx dy`) \[m^2\].
    pub area_m2: f64,
    /// Summits per area, eta \[m^-2\].
    pub density_per_m2: f64,
    /// Mean summit height above the mean plane \[m\] (null without summits).
    pub height_mean_m: Option<f64>,
    /// Summit height SD, sigma_s \[m\] (n - 1; null below 2 summits).
    pub height_sd_m: Option<f64>,
    /// Mean summit curvature \[1/m\].
    pub curvature_mean_per_m: Option<f64>,
    /// Mean summit radius `<1/kappa>` \[m\].
    pub radius_mean_m: Option<f64>,
    /// Summit radius SD \[m\].
    pub radius_sd_m: Option<f64>,
    /// Median summit radius \[m\].
    pub radius_median_m: Option<f64>,
    /// Smallest summit radius \[m\].
    pub radius_min_m: Option<f64>,
    /// Largest summit radius \[m\].
    pub radius_max_m: Option<f64>,
    /// Why a statistic is null: too few summits for it (none for means, one for an SD).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

/// Nayak's predictions from the spectral moments.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Nayak {
    /// m0 \[m^2\].
    pub m0_m2: f64,
    /// m2 (dimensionless).
    pub m2: f64,
    /// m4 \[1/m^2\].
    pub m4_per_m2: f64,
    /// Bandwidth parameter alpha = m0 m4 / m2^2.
    pub bandwidth_alpha: f64,
    /// Summit density m4 / (6 pi sqrt 3 m2) \[m^-2\].
    pub summit_density_per_m2: f64,
    /// Mean summit height 4 sqrt(m0/(pi alpha)) \[m\] (large alpha).
    pub summit_height_mean_m: f64,
    /// Summit height SD sqrt(1 - 0.8968/alpha) sqrt(m0) \[m\] (large alpha; null for alpha < 0.8968).
    pub summit_height_sd_m: Option<f64>,
    /// Mean summit curvature (8/3) sqrt(m4/pi) \[1/m\] (large alpha).
    pub summit_curvature_mean_per_m: f64,
    /// Radius of the mean curvature, 1 / curvature \[m\].
    pub summit_radius_m: f64,
}

impl Nayak {
    /// Whether every prediction is finite.
    pub fn is_finite(&self) -> bool {
        [
            self.m0_m2,
            self.m2,
            self.m4_per_m2,
            self.bandwidth_alpha,
            self.summit_density_per_m2,
            self.summit_height_mean_m,
            self.summit_height_sd_m.unwrap_or(0.0),
            self.summit_curvature_mean_per_m,
            self.summit_radius_m,
        ]
        .iter()
        .all(|v| v.is_finite())
    }

    /// The predictions from m0 \[m^2\], m2, m4 \[1/m^2\] (all > 0).
    pub fn from_moments(m0: f64, m2: f64, m4: f64) -> Nayak {
        let alpha = m0 * m4 / (m2 * m2);
        let curv = 8.0 / 3.0 * (m4 / std::f64::consts::PI).sqrt();
        Nayak {
            m0_m2: m0,
            m2,
            m4_per_m2: m4,
            bandwidth_alpha: alpha,
            summit_density_per_m2: m4 / (6.0 * std::f64::consts::PI * 3f64.sqrt() * m2),
            summit_height_mean_m: 4.0 * (m0 / (std::f64::consts::PI * alpha)).sqrt(),
            summit_height_sd_m: (alpha > 0.8968).then(|| ((1.0 - 0.8968 / alpha) * m0).sqrt()),
            summit_curvature_mean_per_m: curv,
            summit_radius_m: 1.0 / curv,
        }
    }
}

/// Statistics of a map and its summits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Statistics {
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
    /// Pixel size along x \[m\].
    pub dx_m: f64,
    /// Pixel size along y \[m\].
    pub dy_m: f64,
    /// Pixels with a height.
    pub valid_pixels: usize,
    /// Pixels without (NaN), excluded everywhere.
    pub missing_pixels: usize,
    /// Mean height \[m\].
    pub mean_height_m: f64,
    /// RMS height about the mean, Sq \[m\].
    pub rms_height_m: f64,
    /// RMS slope sqrt(<z_x^2> + <z_y^2>), Sdq.
    pub rms_slope: f64,
    /// Profile RMS curvature sqrt(m4) \[1/m\].
    pub rms_curvature_per_m: f64,
    /// Lag at which the autocorrelation along x falls to 1/e \[m\] (null if not within half the map).
    pub autocorrelation_length_x_m: Option<f64>,
    /// Lag at which the autocorrelation along y falls to 1/e \[m\].
    pub autocorrelation_length_y_m: Option<f64>,
    /// Mean of the x and y autocorrelation lengths \[m\] (null if either is).
    pub autocorrelation_length_m: Option<f64>,
    /// Why an autocorrelation length is null (absent when both are known).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub autocorrelation_length_note: Option<&'static str>,
    /// Counted summits.
    pub summits: SummitStats,
    /// Nayak's predictions (null if a moment is 0 or a prediction is not finite).
    pub nayak: Option<Nayak>,
    /// Why `nayak` is null (absent when it is not).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub nayak_note: Option<&'static str>,
}

/// Mean, SD (n - 1), min, max; None for an empty list, SD None below 2 values. Sums are taken
/// on values scaled by the largest magnitude, so finite values (summit radii up to 1e308 m on a map
/// of subnormal heights) give a finite mean and SD.
fn moments(v: &[f64]) -> (Option<f64>, Option<f64>, Option<f64>, Option<f64>) {
    if v.is_empty() {
        return (None, None, None, None);
    }
    let n = v.len() as f64;
    let scale = v.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(f64::MIN_POSITIVE);
    let mean = scale * (v.iter().map(|x| x / scale).sum::<f64>() / n);
    let sd = (v.len() > 1)
        .then(|| {
            let ms = mean / scale;
            let d = v.iter().fold(0.0f64, |m, x| m.max((x / scale - ms).abs()));
            if d == 0.0 {
                return 0.0;
            }
            scale * d * (v.iter().map(|x| ((x / scale - ms) / d).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
        })
        .filter(|s| s.is_finite());
    let min = v.iter().copied().fold(f64::INFINITY, f64::min);
    let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (Some(mean), sd, Some(min), Some(max))
}

/// Counted summit statistics of `summits` found on `map`.
pub fn summit_stats(map: &HeightMap, summits: &Summits) -> SummitStats {
    let area = summits.candidate_pixels as f64 * map.dx_m() * map.dy_m();
    let (hm, hsd, _, _) = moments(&summits.height_m);
    let (cm, _, _, _) = moments(&summits.curvature_per_m);
    let mut radii: Vec<f64> = summits.curvature_per_m.iter().map(|k| 1.0 / k).collect();
    let (rm, rsd, rmin, rmax) = moments(&radii);
    radii.sort_by(f64::total_cmp);
    let median = (!radii.is_empty()).then(|| {
        let n = radii.len();
        if n % 2 == 1 { radii[n / 2] } else { 0.5 * radii[n / 2 - 1] + 0.5 * radii[n / 2] }
    });
    SummitStats {
        count: summits.len(),
        area_m2: area,
        density_per_m2: if area > 0.0 { summits.len() as f64 / area } else { 0.0 },
        height_mean_m: hm,
        height_sd_m: hsd,
        curvature_mean_per_m: cm,
        radius_mean_m: rm,
        radius_sd_m: rsd,
        radius_median_m: median,
        radius_min_m: rmin,
        radius_max_m: rmax,
        note: [hm, hsd, cm, rm, rsd, median, rmin, rmax]
            .iter()
            .any(Option::is_none)
            .then_some("too few summits for this statistic (none for a mean or an extreme, one for an SD)"),
    }
}

/// The statistics of a map (normally prepared) and its summits (see the module documentation).
pub fn statistics(map: &HeightMap, summits: &Summits) -> Statistics {
    let (nx, ny) = (map.nx(), map.ny());
    let h = map.heights_m();
    let valid = map.valid_count();
    let mean = h.iter().filter(|z| !z.is_nan()).sum::<f64>() / valid.max(1) as f64;
    let m0 = h.iter().filter(|z| !z.is_nan()).map(|z| (z - mean).powi(2)).sum::<f64>() / valid.max(1) as f64;
    let (mut sx, mut nsx, mut sy, mut nsy) = (0.0, 0usize, 0.0, 0usize);
    let (mut sxx, mut nsxx, mut syy, mut nsyy) = (0.0, 0usize, 0.0, 0usize);
    let (dx, dy) = (map.dx_m(), map.dy_m());
    for iy in 0..ny {
        let row = map.row(iy);
        for ix in 0..nx {
            let z = row[ix];
            if ix + 1 < nx {
                let d = (row[ix + 1] - z) / dx;
                if !d.is_nan() {
                    sx += d * d;
                    nsx += 1;
                }
                if ix >= 1 {
                    let d2 = (row[ix + 1] - 2.0 * z + row[ix - 1]) / (dx * dx);
                    if !d2.is_nan() {
                        sxx += d2 * d2;
                        nsxx += 1;
                    }
                }
            }
            if iy + 1 < ny {
                let below = h[(iy + 1) * nx + ix];
                let d = (below - z) / dy;
                if !d.is_nan() {
                    sy += d * d;
                    nsy += 1;
                }
                if iy >= 1 {
                    let d2 = (below - 2.0 * z + h[(iy - 1) * nx + ix]) / (dy * dy);
                    if !d2.is_nan() {
                        syy += d2 * d2;
                        nsyy += 1;
                    }
                }
            }
        }
    }
    let avg = |s: f64, n: usize| if n > 0 { s / n as f64 } else { 0.0 };
    let (zx2, zy2, zxx2, zyy2) = (avg(sx, nsx), avg(sy, nsy), avg(sxx, nsxx), avg(syy, nsyy));
    let m2 = 0.5 * (zx2 + zy2);
    let m4 = 0.5 * (zxx2 + zyy2);
    let acf = autocorrelation(map);
    let (lx, ly) = (acf.length_x(), acf.length_y());
    let acf_note = lx.err().or(ly.err());
    let (lx, ly) = (lx.ok(), ly.ok());
    let nayak = (m0 > 0.0 && m2 > 0.0 && m4 > 0.0).then(|| Nayak::from_moments(m0, m2, m4));
    let (nayak, nayak_note) = match nayak {
        None => (None, Some("a spectral moment (m0, m2 or m4) is 0: the map is flat at the scale of its pixels")),
        Some(n) if !n.is_finite() => (None, Some("the spectral moments overflow the predictions (not finite)")),
        Some(n) => (Some(n), None),
    };
    Statistics {
        nx,
        ny,
        dx_m: dx,
        dy_m: dy,
        valid_pixels: valid,
        missing_pixels: nx * ny - valid,
        mean_height_m: mean,
        rms_height_m: m0.sqrt(),
        rms_slope: (zx2 + zy2).sqrt(),
        rms_curvature_per_m: m4.sqrt(),
        autocorrelation_length_x_m: lx,
        autocorrelation_length_y_m: ly,
        autocorrelation_length_m: lx.zip(ly).map(|(a, b)| 0.5 * (a + b)),
        autocorrelation_length_note: acf_note,
        summits: summit_stats(map, summits),
        nayak,
        nayak_note,
    }
}

/// Normalised autocorrelation along x and y (averaged over rows, respectively columns).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Autocorrelation {
    /// Pixel size along x \[m\].
    pub dx_m: f64,
    /// Pixel size along y \[m\].
    pub dy_m: f64,
    /// ACF along x at lags 0, dx, 2 dx, ... (nx/2 lags), 1 at lag 0.
    pub acf_x: Vec<f64>,
    /// ACF along y at lags 0, dy, ... (ny/2 lags).
    pub acf_y: Vec<f64>,
}

/// The lag where `acf` first falls below `level` (linear interpolation between the lags around
/// it), or why there is none: a flat map (the ACF is not defined), a lag without pixel pairs
/// before the crossing (rows or columns missing), or no crossing within the lags computed.
fn first_below(acf: &[f64], level: f64, d: f64) -> Result<f64, &'static str> {
    if acf.first().is_none_or(|a| !a.is_finite()) {
        return Err("the map is flat or has too few pixels: no autocorrelation");
    }
    for (k, &a) in acf.iter().enumerate() {
        if !a.is_finite() {
            return Err("a lag before the autocorrelation falls to 1/e has no pixel pairs (rows or columns missing)");
        }
        if a < level {
            if k == 0 {
                return Ok(0.0);
            }
            let a0 = acf[k - 1];
            return Ok(d * ((k - 1) as f64 + (a0 - level) / (a0 - a)));
        }
    }
    Err("the autocorrelation does not fall to 1/e within half the map")
}

impl Autocorrelation {
    /// Lag where the x ACF first falls below 1/e (linear interpolation) \[m\], or why it has none.
    pub fn length_x(&self) -> Result<f64, &'static str> {
        first_below(&self.acf_x, (-1f64).exp(), self.dx_m)
    }
    /// Lag where the y ACF first falls below 1/e \[m\], or why it has none.
    pub fn length_y(&self) -> Result<f64, &'static str> {
        first_below(&self.acf_y, (-1f64).exp(), self.dy_m)
    }
    /// [`Self::length_x`] without the reason.
    pub fn length_x_m(&self) -> Option<f64> {
        self.length_x().ok()
    }
    /// [`Self::length_y`] without the reason.
    pub fn length_y_m(&self) -> Option<f64> {
        self.length_y().ok()
    }
}

/// Sum over lines of the linear autocorrelation sums `S(tau) = sum_x a(x) a(x + tau)`,
/// `tau = 0 .. n-1`, for `lines` real lines of length `n` produced by `line(k, buf)`. Two lines share
/// one complex FFT (real and imaginary parts); the power spectra are summed and transformed back once.
fn line_autocorr_sums(lines: usize, n: usize, mut line: impl FnMut(usize, &mut [f64])) -> Vec<f64> {
    let len = (2 * n).next_power_of_two();
    let fwd = fft::plan(len, false, false);
    let mut power = vec![0.0; len];
    let mut buf = vec![Complex64::new(0.0, 0.0); len];
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    let mut k = 0;
    while k < lines {
        line(k, &mut a);
        if k + 1 < lines {
            line(k + 1, &mut b);
        } else {
            b.iter_mut().for_each(|v| *v = 0.0);
        }
        buf.iter_mut().for_each(|c| *c = Complex64::new(0.0, 0.0));
        for i in 0..n {
            buf[i] = Complex64::new(a[i], b[i]);
        }
        fwd.process(&mut buf);
        for q in 0..len {
            let m = (len - q) % len;
            power[q] += 0.5 * (buf[q].norm_sqr() + buf[m].norm_sqr());
        }
        k += 2;
    }
    let mut p: Vec<Complex64> = power.iter().map(|&v| Complex64::new(v, 0.0)).collect();
    fft::plan(len, true, false).process(&mut p);
    p[..n].iter().map(|c| c.re / len as f64).collect()
}

/// The autocorrelation of the map along x and y: `ACF(tau) = <z(x) z(x + tau)> / <z^2>` over the
/// pixel pairs that both have heights (mean removed), lags up to half the map.
pub fn autocorrelation(map: &HeightMap) -> Autocorrelation {
    let (nx, ny) = (map.nx(), map.ny());
    let h = map.heights_m();
    let valid = map.valid_count().max(1);
    let mean = h.iter().filter(|z| !z.is_nan()).sum::<f64>() / valid as f64;
    let missing = valid < nx * ny;
    let val = |z: f64| if z.is_nan() { 0.0 } else { z - mean };
    let mask = |z: f64| if z.is_nan() { 0.0 } else { 1.0 };
    let norm = |s: Vec<f64>, c: Vec<f64>, keep: usize| -> Vec<f64> {
        let a: Vec<f64> = s.iter().zip(&c).map(|(s, c)| if *c > 0.5 { s / c } else { f64::NAN }).collect();
        let a0 = a[0];
        a[..keep].iter().map(|v| v / a0).collect()
    };
    let sx = line_autocorr_sums(ny, nx, |k, buf| {
        for (o, &z) in buf.iter_mut().zip(map.row(k)) {
            *o = val(z);
        }
    });
    let cx = if missing {
        line_autocorr_sums(ny, nx, |k, buf| {
            for (o, &z) in buf.iter_mut().zip(map.row(k)) {
                *o = mask(z);
            }
        })
    } else {
        (0..nx).map(|t| ((nx - t) * ny) as f64).collect()
    };
    let sy = line_autocorr_sums(nx, ny, |k, buf| {
        for (iy, o) in buf.iter_mut().enumerate() {
            *o = val(h[iy * nx + k]);
        }
    });
    let cy = if missing {
        line_autocorr_sums(nx, ny, |k, buf| {
            for (iy, o) in buf.iter_mut().enumerate() {
                *o = mask(h[iy * nx + k]);
            }
        })
    } else {
        (0..ny).map(|t| ((ny - t) * nx) as f64).collect()
    };
    Autocorrelation { dx_m: map.dx_m(), dy_m: map.dy_m(), acf_x: norm(sx, cx, nx / 2), acf_y: norm(sy, cy, ny / 2) }
}

/// Window applied before the PSD's FFT.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PsdWindow {
    /// No window (right for periodic maps such as the generator's).
    None,
    /// A 2-D Hann window (default; measured maps are not periodic).
    #[default]
    Hann,
}
stiction_units::display_serde_name!(PsdWindow);

/// The radially averaged power spectral density.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Psd {
    /// Spatial frequency |f| = 1/wavelength of each bin \[1/m\].
    pub f_per_m: Vec<f64>,
    /// Isotropic 2-D PSD C(f) \[m^4\], normalised so that the integral of C over the frequency
    /// plane is the mean square height (sum of C df_x df_y = <z^2>).
    pub psd_m4: Vec<f64>,
    /// DFT bins averaged into each value.
    pub bins: Vec<u32>,
    /// The window used.
    pub window: PsdWindow,
}

/// The radially averaged PSD: `C(f_x, f_y) = dx dy |DFT(w z)|^2 / sum (w m)^2` (mean removed,
/// missing pixels as 0 and out of the normalisation), averaged over rings of width
/// `max(1/(nx dx), 1/(ny dy))` up to the lower Nyquist frequency; DC left out.
pub fn radial_psd(map: &HeightMap, window: PsdWindow) -> Psd {
    let (nx, ny) = (map.nx(), map.ny());
    let h = map.heights_m();
    let valid = map.valid_count().max(1);
    let mean = h.iter().filter(|z| !z.is_nan()).sum::<f64>() / valid as f64;
    let hann = |i: usize, n: usize| match window {
        PsdWindow::None => 1.0,
        PsdWindow::Hann => 0.5 - 0.5 * (2.0 * std::f64::consts::PI * (i as f64 + 0.5) / n as f64).cos(),
    };
    let wx: Vec<f64> = (0..nx).map(|i| hann(i, nx)).collect();
    let wy: Vec<f64> = (0..ny).map(|i| hann(i, ny)).collect();
    let mut w2 = 0.0;
    let mut buf = Vec::with_capacity(nx * ny);
    for iy in 0..ny {
        for ix in 0..nx {
            let z = h[iy * nx + ix];
            if z.is_nan() {
                buf.push(Complex64::new(0.0, 0.0));
            } else {
                let w = wx[ix] * wy[iy];
                w2 += w * w;
                buf.push(Complex64::new(w * (z - mean), 0.0));
            }
        }
    }
    let spec = fft::forward_2d(buf, nx, ny, false);
    let (dx, dy) = (map.dx_m(), map.dy_m());
    let (dfx, dfy) = (1.0 / (nx as f64 * dx), 1.0 / (ny as f64 * dy));
    let width = dfx.max(dfy);
    let fmax = (0.5 / dx).min(0.5 / dy);
    let nbins = (fmax / width).floor() as usize;
    let mut sum = vec![0.0; nbins + 1];
    let mut cnt = vec![0u32; nbins + 1];
    let scale = dx * dy / w2.max(f64::MIN_POSITIVE);
    for kx in 0..nx {
        let fx = fft::signed_index(kx, nx) * dfx;
        for ky in 0..ny {
            let fy = fft::signed_index(ky, ny) * dfy;
            let b = ((fx * fx + fy * fy).sqrt() / width).round() as usize;
            if b == 0 || b > nbins {
                continue;
            }
            sum[b] += spec[kx * ny + ky].norm_sqr() * scale;
            cnt[b] += 1;
        }
    }
    let mut out = Psd { f_per_m: vec![], psd_m4: vec![], bins: vec![], window };
    for b in 1..=nbins {
        if cnt[b] > 0 {
            out.f_per_m.push(b as f64 * width);
            out.psd_m4.push(sum[b] / f64::from(cnt[b]));
            out.bins.push(cnt[b]);
        }
    }
    out
}
