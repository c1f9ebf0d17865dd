//! Maximum-likelihood fits of the shear strength s (and optionally the summit radius R and the
//! spring force F_spring) to the measured pull voltages squared, with profile-likelihood intervals.
//!
//! Likelihood: each measured `Y_i = V_pull,i^2` is normal about the model's `(s g_i + h_i) / a_pull`
//! with standard deviation `2 V_pull,i sigma_i` (a pull-voltage noise `sigma_i` in volts carried to
//! V^2 to first order). `sigma_i` is the file's `v_pull_sd_v` when it has the column; otherwise one
//! `sigma` for all rows, from the repeats (pooled within-group SD of rows with the same device and
//! clamp voltage, when there are at least two degrees of freedom) or else from the model's own
//! residuals. The model is linear in s, so for fixed (R, F_spring) the best s and the minimum of
//! chi^2 are closed forms; R and F_spring (when free) are found by Nelder-Mead on the profiled
//! chi^2 (ln R and F_spring in uN; at most two dimensions, so a hand-written simplex of forty lines
//! beats pulling an optimisation framework into the build).
//!
//! Interval: **profile likelihood**, the set of s with `chi2_prof(s) - chi2_min <= q`, where
//! `chi2_prof(s)` minimises over the other free parameters and `q` is `t_{0.975}(nu)^2` (nu the
//! degrees of freedom of sigma: infinite with a known sigma, so q = 3.84; `n_rep - groups` from
//! repeats; `n - k` from residuals). With s alone this is the exact t interval of a linear model.
//! Profile likelihood, not bootstrap: it is exact here for s alone, follows the curved valley of
//! (s, R) when R is free, and costs a few hundred model evaluations rather than thousands of
//! refits (which the explicit solver with a 100-surface band could not afford).

use serde::Serialize;

use crate::error::FitError;
use crate::models::{ModelContext, ModelKind, Parts};
use crate::stats::{chi2_sf, percentile, t975};
use stiction_meter::measured::Rejected;

/// The rows a model is fitted to.
#[derive(Debug, Clone)]
pub struct FitData {
    /// Distinct clamp voltages squared, V^2.
    pub x_unique_v2: Vec<f64>,
    /// For each row, its index in `x_unique_v2`.
    pub row_unique: Vec<usize>,
    /// Measured V_pull^2 of each row, V^2.
    pub y_v2: Vec<f64>,
    /// Weight of each row, 1 / (2 V_pull sd)^2 with sd = the row's `v_pull_sd_v`, or 1 V.
    pub weight: Vec<f64>,
    /// File line of each row.
    pub line: Vec<u64>,
}

/// Where the noise level comes from.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "source", rename_all = "kebab-case")]
pub enum Noise {
    /// Each row's `v_pull_sd_v` (sigma known).
    Column,
    /// Pooled SD of repeated rows (same device and clamp voltage).
    Repeats {
        /// Pull-voltage SD, V.
        sigma_v: f64,
        /// Its degrees of freedom (rows in repeated groups minus groups).
        dof: usize,
    },
    /// Each model's own residuals (chi^2 then equals its dof by construction).
    Residuals,
}

/// Which parameters besides s are free.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Free {
    /// The summit radius R.
    pub radius: bool,
    /// The spring force F_spring.
    pub spring: bool,
}

impl Free {
    /// Parses a list `s[,R,F_spring]`; `name` (the flag `--free`, the argument `free`) names
    /// it in errors.
    pub fn parse(list: &str, name: &str) -> Result<Free, FitError> {
        let mut f = Free::default();
        let mut has_s = false;
        for item in list.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            match item {
                "s" => has_s = true,
                "R" | "r" => f.radius = true,
                "F_spring" | "f_spring" => f.spring = true,
                other => {
                    return Err(FitError::Setting(format!(
                        "{name}: unknown parameter `{other}`; expected s, R, F_spring (s is always free)"
                    )));
                }
            }
        }
        if !has_s {
            return Err(FitError::Setting(format!(
                "{name}: the list must contain s (the shear strength is always fitted)"
            )));
        }
        Ok(f)
    }

    fn count(&self) -> usize {
        self.radius as usize + self.spring as usize
    }
}

/// A fitted parameter.
#[derive(Debug, Clone, Serialize)]
pub struct Param {
    /// Best estimate, SI.
    pub value: f64,
    /// 95 % profile-likelihood interval (the other free parameters minimised at each trial value).
    pub ci95: Option<[f64; 2]>,
    /// Why the interval is null or one-sided, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The fitted shear strength with its two intervals.
#[derive(Debug, Clone, Serialize, Default)]
pub struct ShearStrength {
    /// Best estimate, Pa.
    pub value: f64,
    /// 95 % profile-likelihood interval from the noise of the pull voltages alone (the nominal
    /// a_clamp, a_pull and F_spring taken as exact), Pa.
    pub ci95: Option<[f64; 2]>,
    /// What `ci95` covers, in words.
    pub ci95_meaning: String,
    /// Why the interval is null or one-sided, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// 95 % interval with the noise and the calibration (a_clamp, a_pull, F_spring drawn from their
    /// stated uncertainties) together, Pa (Monte Carlo percentiles; see `crate::scal`).
    pub ci95_with_calibration: Option<[f64; 2]>,
    /// How `ci95_with_calibration` was made, or why it is null.
    pub ci95_with_calibration_note: String,
    /// Share of the variance of s by source (`noise`, `a_clamp`, `a_pull`, `spring_force`), summing
    /// to 1 (first order: each source drawn alone); empty when there is no calibration interval.
    pub variance_shares: std::collections::BTreeMap<String, f64>,
}

/// What the noise-only interval of s covers.
pub const S_NOISE_MEANING: &str = "noise only: the spread of the pull voltages, with a_clamp, a_pull and F_spring taken as exact (see ci95_with_calibration for their uncertainty)";

/// The spread over surface realisations (explicit ensemble).
#[derive(Debug, Clone, Serialize)]
pub struct Roughness {
    /// Realisations.
    pub surfaces: usize,
    /// Realisations where some used row had no contact state (left out of the spread).
    pub surfaces_failed: usize,
    /// 2.5 and 97.5 percentiles of the s each realisation alone would need, Pa.
    pub shear_strength_ci95_pa: Option<[f64; 2]>,
    /// Median of those, Pa.
    pub shear_strength_median_pa: Option<f64>,
}

/// One point of a model curve for the figures.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct CurvePoint {
    /// V_clamp^2, V^2.
    pub v_clamp_sq_v2: f64,
    /// Load, N.
    pub load_n: f64,
    /// Best-fit V_pull^2, V^2 (None: no state).
    pub v_pull_sq_v2: Option<f64>,
    /// Band low and high, V^2.
    pub band_v2: Option<[f64; 2]>,
}

/// The fit of one model.
#[derive(Debug, Clone, Serialize)]
pub struct ModelFit {
    /// Model name.
    pub name: String,
    /// Free parameters.
    pub free: Vec<String>,
    /// Shear strength s, Pa.
    pub shear_strength_pa: ShearStrength,
    /// Summit radius R, m (when free).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub summit_radius_m: Option<Param>,
    /// Spring force, N (when free).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spring_force_n: Option<Param>,
    /// chi^2 at the best fit.
    pub chi2: f64,
    /// Degrees of freedom, rows - free parameters.
    pub dof: usize,
    /// P(chi^2 >= observed) with a known sigma (null when sigma comes from the residuals).
    pub p_value: Option<f64>,
    /// Akaike information criterion (-2 ln L + 2 k, up to a constant common to the models).
    pub aic: f64,
    /// Bayesian information criterion (-2 ln L + k ln n).
    pub bic: f64,
    /// AIC minus the best comparable model's.
    pub delta_aic: Option<f64>,
    /// Akaike weight among the comparable models.
    pub akaike_weight: Option<f64>,
    /// Whether the model was fitted to all used rows (else its AIC is not comparable).
    pub comparable: bool,
    /// Noise SD in volts used for this model's chi^2 (from the column: null).
    pub sigma_v: Option<f64>,
    /// Rows fitted.
    pub rows_fitted: usize,
    /// Rows where the model had no contact state, with the reason.
    pub rows_without_state: Vec<Rejected>,
    /// Why a value is null: p_value without a known sigma, delta_aic and akaike_weight for a model
    /// not comparable with the others, sigma_v when the noise is the data's own column.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
    /// For the ensemble: the spread over surfaces.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub roughness: Option<Roughness>,
    /// Best-fit curve and band (for the figures).
    #[serde(skip)]
    pub curve: Vec<CurvePoint>,
    /// Residuals Y - model (V^2) per fitted row, with the row's line (for the figures).
    #[serde(skip)]
    pub residuals: Vec<(u64, f64, f64)>,
}

/// Sums of the linear problem at fixed nuisance parameters.
#[derive(Debug, Clone, Copy, Default)]
struct Lin {
    sxx: f64,
    sxy: f64,
    syy: f64,
    rows: usize,
}

impl Lin {
    fn s_hat(&self) -> f64 {
        self.sxy / self.sxx
    }
    fn rss_min(&self) -> f64 {
        (self.syy - self.sxy * self.sxy / self.sxx).max(0.0)
    }
    fn rss_at(&self, s: f64) -> f64 {
        (self.syy - 2.0 * s * self.sxy + s * s * self.sxx).max(0.0)
    }
}

fn lin(data: &FitData, parts: &[Parts], a_pull: f64, failed_as_zero: bool) -> Lin {
    let mut l = Lin::default();
    for i in 0..data.y_v2.len() {
        let (g, h) = match &parts[data.row_unique[i]] {
            Ok(p) => *p,
            Err(_) if failed_as_zero => (0.0, 0.0),
            Err(_) => continue,
        };
        let (x, r) = (g / a_pull, data.y_v2[i] - h / a_pull);
        let w = data.weight[i];
        l.sxx += w * x * x;
        l.sxy += w * x * r;
        l.syy += w * r * r;
        l.rows += 1;
    }
    l
}

/// Nelder-Mead minimisation of `f` from `x0` with initial steps `step` (dimension 1 or 2).
fn nelder_mead(f: &mut dyn FnMut(&[f64]) -> f64, x0: &[f64], step: &[f64], max_evals: usize) -> (Vec<f64>, f64) {
    let d = x0.len();
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(d + 1);
    simplex.push((x0.to_vec(), f(x0)));
    for k in 0..d {
        let mut x = x0.to_vec();
        x[k] += step[k];
        let v = f(&x);
        simplex.push((x, v));
    }
    let mut evals = d + 1;
    while evals < max_evals {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (best, worst) = (simplex[0].1, simplex[d].1);
        if (worst - best).abs() <= 1e-12 * best.abs().max(1e-300) + 1e-300 {
            break;
        }
        let centroid: Vec<f64> = (0..d).map(|k| simplex[..d].iter().map(|p| p.0[k]).sum::<f64>() / d as f64).collect();
        let along =
            |t: f64, w: &[f64]| -> Vec<f64> { (0..d).map(|k| centroid[k] + t * (w[k] - centroid[k])).collect() };
        let xr = along(-1.0, &simplex[d].0);
        let fr = f(&xr);
        evals += 1;
        if fr < simplex[0].1 {
            let xe = along(-2.0, &simplex[d].0);
            let fe = f(&xe);
            evals += 1;
            simplex[d] = if fe < fr { (xe, fe) } else { (xr, fr) };
        } else if fr < simplex[d - 1].1 {
            simplex[d] = (xr, fr);
        } else {
            let xc = along(0.5, &simplex[d].0);
            let fc = f(&xc);
            evals += 1;
            if fc < simplex[d].1.min(fr) {
                simplex[d] = (xc, fc);
            } else {
                let x0b = simplex[0].0.clone();
                for p in simplex.iter_mut().skip(1) {
                    p.0 = (0..d).map(|k| x0b[k] + 0.5 * (p.0[k] - x0b[k])).collect();
                    p.1 = f(&p.0);
                    evals += 1;
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    (simplex[0].0.clone(), simplex[0].1)
}

/// How a model's threshold parts are obtained for given (R, F_spring).
pub enum Source<'a> {
    /// Build the model (cached while R does not change).
    Build {
        /// The context.
        ctx: &'a ModelContext,
        /// The model.
        kind: ModelKind,
        /// The last built model and its radius.
        cache: Option<(f64, stiction_meter::ContactModel)>,
    },
    /// Fixed parts (the ensemble mean), at the nominal R and F_spring.
    Fixed(Vec<Parts>),
}

impl Source<'_> {
    fn parts(&mut self, ctx: &ModelContext, radius: f64, spring: f64, x: &[f64]) -> Result<Vec<Parts>, FitError> {
        match self {
            Source::Fixed(p) => Ok(p.clone()),
            Source::Build { ctx: c, kind, cache } => {
                let rebuild = !matches!(cache, Some((r, _)) if *r == radius);
                if rebuild {
                    let r_arg = (radius != c.nominal_radius_m).then_some(radius);
                    *cache = Some((radius, c.build(*kind, r_arg, None)?));
                }
                let Some((_, model)) = cache.as_mut() else { unreachable!("built above") };
                Ok(ctx.parts(model, &ctx.loads(x, spring)))
            }
        }
    }
}

/// Fits one model. `grid_v2`: clamp voltages squared for the curve.
#[allow(clippy::too_many_arguments)]
pub fn fit_model(
    ctx: &ModelContext,
    name: String,
    source: &mut Source,
    free: Free,
    data: &FitData,
    noise: Noise,
    grid_v2: &[f64],
) -> Result<ModelFit, FitError> {
    let a_pull = ctx.device.a_pull_n_per_v2;
    let (r0, f0) = (ctx.nominal_radius_m, ctx.device.spring_force_n);
    let free = if matches!(source, Source::Fixed(_)) { Free::default() } else { free };
    let f_max = ctx.device.a_clamp_n_per_v2 * data.x_unique_v2.iter().cloned().fold(0.0, f64::max);
    // theta -> (R, F).
    let unpack = |th: &[f64]| -> (f64, f64) {
        let mut k = 0;
        let r = if free.radius {
            k += 1;
            r0 * th[0].exp()
        } else {
            r0
        };
        let f = if free.spring { th[k] * 1e-6 } else { f0 };
        (r, f)
    };
    let error: std::cell::RefCell<Option<FitError>> = std::cell::RefCell::new(None);
    let objective = |th: &[f64], s_fixed: Option<f64>, source: &mut Source| -> f64 {
        let (r, f) = unpack(th);
        if free.radius && th[0].abs() > 4.6 || free.spring && !(0.0..=f_max).contains(&f) {
            return f64::INFINITY;
        }
        match source.parts(ctx, r, f, &data.x_unique_v2) {
            Ok(p) => {
                let l = lin(data, &p, a_pull, true);
                match s_fixed {
                    Some(s) => l.rss_at(s),
                    None if l.sxx > 0.0 => l.rss_min(),
                    None => f64::INFINITY,
                }
            }
            Err(e) => {
                error.borrow_mut().get_or_insert(e);
                f64::INFINITY
            }
        }
    };
    let theta0: Vec<f64> =
        [free.radius.then_some(0.0), free.spring.then_some(f0 * 1e6)].into_iter().flatten().collect();
    let steps: Vec<f64> = [free.radius.then_some(0.2), free.spring.then_some(1.0)].into_iter().flatten().collect();
    let theta = if theta0.is_empty() {
        theta0.clone()
    } else {
        nelder_mead(&mut |th| objective(th, None, source), &theta0, &steps, 400).0
    };
    if let Some(e) = error.borrow_mut().take() {
        return Err(e);
    }
    let (r_best, f_best) = unpack(&theta);
    let parts = source.parts(ctx, r_best, f_best, &data.x_unique_v2)?;
    let l = lin(data, &parts, a_pull, false);
    if !(l.sxx > 0.0) || l.rows == 0 {
        return Err(FitError::Model {
            model: name,
            message: "the model predicts no friction at any used row (no contact at these loads)".into(),
        });
    }
    let k = 1 + free.count();
    let n = l.rows;
    let s_hat = l.s_hat();
    let rss = l.rss_min();
    let dof = n.saturating_sub(k);
    let (sigma2, nu) = match noise {
        Noise::Column => (1.0, f64::INFINITY),
        Noise::Repeats { sigma_v, dof } => (sigma_v * sigma_v, dof as f64),
        Noise::Residuals => (if dof > 0 { rss / dof as f64 } else { f64::NAN }, dof as f64),
    };
    let chi2 = rss / sigma2;
    let q = t975(nu).map(|t| t * t);
    let (aic, bic) = match noise {
        Noise::Residuals => {
            let m2ll = n as f64 * (rss / n as f64).ln();
            (m2ll + 2.0 * (k + 1) as f64, m2ll + (k + 1) as f64 * (n as f64).ln())
        }
        _ => (chi2 + 2.0 * k as f64, chi2 + k as f64 * (n as f64).ln()),
    };
    // Profile-likelihood interval of s.
    let mut note = None;
    let mut ends: Vec<(f64, Vec<f64>)> = Vec::new();
    let ci95 = match q {
        None => {
            note = Some(format!("no interval: {dof} degrees of freedom for the noise level"));
            None
        }
        Some(q) if theta.is_empty() => {
            let half = (q * sigma2 / l.sxx).sqrt();
            Some([s_hat - half, s_hat + half])
        }
        Some(q) => {
            let se = (sigma2 / l.sxx).sqrt();
            let mut th_at = theta.clone();
            let excess = |s: f64, th_start: &[f64], source: &mut Source| -> (f64, Vec<f64>) {
                let (th, v) = nelder_mead(&mut |th| objective(th, Some(s), source), th_start, &steps, 300);
                ((v - rss) / sigma2 - q, th)
            };
            let mut bounds = [f64::NAN; 2];
            for (side, dir) in [-1.0f64, 1.0].into_iter().enumerate() {
                let mut inner = s_hat;
                let mut outer = s_hat + dir * se;
                let mut found = false;
                for _ in 0..60 {
                    let (e, th) = excess(outer, &th_at, source);
                    if e > 0.0 {
                        found = true;
                        break;
                    }
                    th_at = th;
                    inner = outer;
                    outer = s_hat + 2.0 * (outer - s_hat);
                    if outer <= 0.0 {
                        break;
                    }
                }
                if !found {
                    bounds[side] = if dir < 0.0 { 0.0 } else { f64::INFINITY };
                    note = Some("the profile likelihood does not cross the 95 % level on this side within the parameter bounds; the interval is open there".into());
                    continue;
                }
                for _ in 0..40 {
                    let mid = 0.5 * (inner + outer);
                    let (e, th) = excess(mid, &th_at, source);
                    if e > 0.0 {
                        outer = mid;
                    } else {
                        inner = mid;
                        th_at = th;
                    }
                    if (outer - inner).abs() <= 1e-6 * s_hat.abs() {
                        break;
                    }
                }
                bounds[side] = 0.5 * (inner + outer);
                ends.push((bounds[side], th_at.clone()));
                th_at = theta.clone();
            }
            if let Some(e) = error.borrow_mut().take() {
                return Err(e);
            }
            Some(bounds).filter(|b| b[1].is_finite())
        }
    };
    // Profile-likelihood intervals of the free nuisance parameters (in their fitted coordinates,
    // ln(R / R0) and F_spring in uN), the other one and s minimised at each trial value.
    let bounds_of = |j: usize| -> (f64, f64) { if free.radius && j == 0 { (-4.6, 4.6) } else { (0.0, f_max * 1e6) } };
    let mut nuisance_ci: Vec<(Option<[f64; 2]>, Option<String>)> = Vec::new();
    for j in 0..theta.len() {
        let Some(q) = q else {
            nuisance_ci.push((None, Some("no interval: too few degrees of freedom for the noise level".into())));
            continue;
        };
        let (lo_b, hi_b) = bounds_of(j);
        let excess = |t: f64, source: &mut Source| -> f64 {
            let mut th = theta.clone();
            th[j] = t;
            let v = if theta.len() == 1 {
                objective(&th, None, source)
            } else {
                let o = 1 - j;
                let mut f1 = |x: &[f64]| {
                    let mut t2 = th.clone();
                    t2[o] = x[0];
                    objective(&t2, None, source)
                };
                nelder_mead(&mut f1, &[theta[o]], &[steps[o]], 200).1
            };
            (v - rss) / sigma2 - q
        };
        let mut ends = [f64::NAN; 2];
        let mut open = false;
        for (side, dir) in [-1.0f64, 1.0].into_iter().enumerate() {
            let limit = if dir < 0.0 { lo_b } else { hi_b };
            let mut inner = theta[j];
            let mut outer = theta[j] + dir * steps[j] * 0.25;
            let mut found = false;
            for _ in 0..40 {
                if (outer - limit) * dir >= 0.0 {
                    outer = limit;
                }
                if excess(outer, source) > 0.0 {
                    found = true;
                    break;
                }
                if outer == limit {
                    break;
                }
                inner = outer;
                outer = theta[j] + 2.0 * (outer - theta[j]);
            }
            if !found {
                ends[side] = limit;
                open = true;
                continue;
            }
            for _ in 0..40 {
                let mid = 0.5 * (inner + outer);
                if excess(mid, source) > 0.0 {
                    outer = mid;
                } else {
                    inner = mid;
                }
                if (outer - inner).abs() < 1e-6 {
                    break;
                }
            }
            ends[side] = 0.5 * (inner + outer);
        }
        let to_si = |t: f64| if free.radius && j == 0 { r0 * t.exp() } else { t * 1e-6 };
        nuisance_ci.push((
            Some([to_si(ends[0]), to_si(ends[1])]),
            open.then(|| {
                "the 95 % profile level is not reached within the parameter bounds: the interval ends at the bound"
                    .to_string()
            }),
        ));
    }
    if let Some(e) = error.borrow_mut().take() {
        return Err(e);
    }
    let mut nuisance_iter = nuisance_ci.into_iter();
    let radius_param = free.radius.then(|| {
        let (ci95, note) = nuisance_iter.next().unwrap_or((None, None));
        Param { value: r_best, ci95, note }
    });
    let spring_param = free.spring.then(|| {
        let (ci95, note) = nuisance_iter.next().unwrap_or((None, None));
        Param { value: f_best, ci95, note }
    });
    // Curve and band on the grid, at the best nuisance (and the interval ends' for the band).
    let grid_parts = source.parts(ctx, r_best, f_best, grid_v2)?;
    let mut band_parts: Vec<(f64, Vec<Parts>)> = Vec::new();
    if let Some([lo, hi]) = ci95 {
        if theta.is_empty() {
            band_parts.push((lo, grid_parts.clone()));
            band_parts.push((hi, grid_parts.clone()));
        } else {
            for (s_end, th) in &ends {
                let (r, f) = unpack(th);
                band_parts.push((*s_end, source.parts(ctx, r, f, grid_v2)?));
            }
        }
    }
    let curve = grid_v2
        .iter()
        .enumerate()
        .map(|(j, &x)| {
            let y = grid_parts[j].as_ref().ok().map(|(g, h)| (s_hat * g + h) / a_pull);
            let ys: Vec<f64> =
                band_parts.iter().filter_map(|(s, p)| p[j].as_ref().ok().map(|(g, h)| (s * g + h) / a_pull)).collect();
            let band = (ys.len() == 2).then(|| [ys[0].min(ys[1]), ys[0].max(ys[1])]);
            CurvePoint {
                v_clamp_sq_v2: x,
                load_n: ctx.device.a_clamp_n_per_v2 * x - f_best,
                v_pull_sq_v2: y,
                band_v2: band,
            }
        })
        .collect();
    let mut residuals = Vec::new();
    let mut rows_without_state = Vec::new();
    for i in 0..data.y_v2.len() {
        match &parts[data.row_unique[i]] {
            Ok((g, h)) => residuals.push((
                data.line[i],
                data.x_unique_v2[data.row_unique[i]],
                data.y_v2[i] - (s_hat * g + h) / a_pull,
            )),
            Err(reason) => {
                rows_without_state.push(Rejected { line: data.line[i], reason: format!("{name}: {reason}") })
            }
        }
    }
    let p_value = match noise {
        Noise::Residuals => None,
        _ => chi2_sf(chi2, dof as f64),
    };
    let free_names: Vec<String> = ["s"]
        .into_iter()
        .chain(free.radius.then_some("R"))
        .chain(free.spring.then_some("F_spring"))
        .map(String::from)
        .collect();
    Ok(ModelFit {
        name,
        free: free_names,
        shear_strength_pa: ShearStrength {
            value: s_hat,
            ci95,
            ci95_meaning: S_NOISE_MEANING.into(),
            note,
            ..ShearStrength::default()
        },
        summit_radius_m: radius_param,
        spring_force_n: spring_param,
        chi2,
        dof,
        p_value,
        aic,
        bic,
        delta_aic: None,
        akaike_weight: None,
        comparable: rows_without_state.is_empty(),
        sigma_v: match noise {
            Noise::Column => None,
            _ => Some(sigma2.sqrt()),
        },
        rows_fitted: n,
        rows_without_state,
        note: Some(
            "null p_value: sigma is estimated from the residuals; null delta_aic, akaike_weight: not comparable \
             (rows without a contact state) or a single model; null sigma_v: the noise is the data's v_pull_sd_v",
        ),
        roughness: None,
        curve,
        residuals,
    })
}

/// The ensemble: parts on each realisation at the data's and the grid's clamp voltages; returns
/// the mean parts (data, grid), the roughness summary and the band (per grid point, for a given s).
pub struct Ensemble {
    /// Realisations' parts at the data's unique clamp voltages.
    pub data_parts: Vec<Vec<Parts>>,
    /// Realisations' parts at the grid.
    pub grid_parts: Vec<Vec<Parts>>,
}

impl Ensemble {
    /// Runs `surfaces` realisations of the explicit solver.
    pub fn run(ctx: &ModelContext, surfaces: usize, data: &FitData, grid_v2: &[f64]) -> Result<Ensemble, FitError> {
        let mut xs = data.x_unique_v2.clone();
        xs.extend_from_slice(grid_v2);
        let loads = ctx.loads(&xs, ctx.device.spring_force_n);
        let all = ctx.ensemble_parts(ModelKind::ExplicitEnsemble, None, surfaces, &loads)?;
        let nd = data.x_unique_v2.len();
        let (data_parts, grid_parts) = all.into_iter().map(|mut p| (p.drain(..nd).collect(), p)).unzip();
        Ok(Ensemble { data_parts, grid_parts })
    }

    pub(crate) fn mean(sets: &[Vec<Parts>]) -> Vec<Parts> {
        let m = sets.first().map_or(0, Vec::len);
        (0..m)
            .map(|j| {
                let ok: Vec<(f64, f64)> = sets.iter().filter_map(|p| p[j].as_ref().ok().copied()).collect();
                if ok.is_empty() {
                    let why = sets.iter().find_map(|p| p[j].as_ref().err().cloned()).unwrap_or_default();
                    Err(format!("no realisation has a contact state here ({why})"))
                } else {
                    let n = ok.len() as f64;
                    Ok((ok.iter().map(|p| p.0).sum::<f64>() / n, ok.iter().map(|p| p.1).sum::<f64>() / n))
                }
            })
            .collect()
    }

    /// Fits the ensemble mean, then adds the roughness spread and replaces the band by the
    /// realisations' 2.5-97.5 percentile band at the fitted s.
    pub fn fit(&self, ctx: &ModelContext, data: &FitData, noise: Noise, grid_v2: &[f64]) -> Result<ModelFit, FitError> {
        let a_pull = ctx.device.a_pull_n_per_v2;
        let mean_data = Ensemble::mean(&self.data_parts);
        let mean_grid = Ensemble::mean(&self.grid_parts);
        // Fit on the mean data parts; the grid curve uses the mean grid parts.
        let mut src = Source::Fixed(mean_data);
        let mut fit = fit_model(ctx, ModelKind::ExplicitEnsemble.name(), &mut src, Free::default(), data, noise, &[])?;
        let s = fit.shear_strength_pa.value;
        let mut per: Vec<f64> = Vec::new();
        let mut failed = 0;
        for p in &self.data_parts {
            let complete = (0..data.y_v2.len()).all(|i| p[data.row_unique[i]].is_ok());
            let l = lin(data, p, a_pull, false);
            if complete && l.sxx > 0.0 {
                per.push(l.s_hat());
            } else {
                failed += 1;
            }
        }
        per.sort_by(f64::total_cmp);
        fit.roughness = Some(Roughness {
            surfaces: self.data_parts.len(),
            surfaces_failed: failed,
            shear_strength_ci95_pa: percentile(&per, 0.025).zip(percentile(&per, 0.975)).map(|(a, b)| [a, b]),
            shear_strength_median_pa: percentile(&per, 0.5),
        });
        fit.curve = grid_v2
            .iter()
            .enumerate()
            .map(|(j, &x)| {
                let mut ys: Vec<f64> = self
                    .grid_parts
                    .iter()
                    .filter_map(|p| p[j].as_ref().ok().map(|(g, h)| (s * g + h) / a_pull))
                    .collect();
                ys.sort_by(f64::total_cmp);
                let band = percentile(&ys, 0.025).zip(percentile(&ys, 0.975)).map(|(a, b)| [a, b]);
                CurvePoint {
                    v_clamp_sq_v2: x,
                    load_n: ctx.device.a_clamp_n_per_v2 * x - ctx.device.spring_force_n,
                    v_pull_sq_v2: mean_grid[j].as_ref().ok().map(|(g, h)| (s * g + h) / a_pull),
                    band_v2: band,
                }
            })
            .collect();
        Ok(fit)
    }
}
