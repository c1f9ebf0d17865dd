//! Design studies: the same Monte Carlo study at every point of a grid of design values.
//!
//! `--vary PATH=V1,V2,...` (repeatable) names a scenario field and the values it takes, written
//! as `--set` takes them. The design points are the grid of all combinations (the first `--vary`
//! changes slowest). Each design point is a complete study of the scenario with the user's
//! `--set`s and then `PATH=V` for every varied field: the same seed, so every design draws the
//! same uncertain parameters' random numbers and the same surface seeds (common random numbers:
//! two designs differ by their design, not by their luck), and each design's folder is byte for
//! byte the folder of `stiction study SCENARIO --set ... --set PATH=V ...`.
//!
//! Per design ([`DesignRow`]): the fraction of experiments with a usable eq. 10 line (and the
//! reasons of the others), the spread of mu_e,a and F_a0 with their Monte Carlo errors, the
//! width of the 5-95 % interval of mu_e,a (what the lab would quote for one device), and the
//! interface's own friction coefficient ([`interface_coefficient`]) with the bias of the median
//! mu_e,a against it.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;
use stiction_meter::Meter;
use stiction_scenario::Scenario;

use crate::StudyError;
use crate::summary::{Spread, StudySummary};

/// Largest number of design points in one design study.
pub const MAX_DESIGNS: usize = 1000;

/// One `--vary PATH=V1,V2,...`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Vary {
    /// The scenario field, as `--set` names it.
    pub path: String,
    /// Its values, as `--set` takes them.
    pub values: Vec<String>,
}

/// Splits `V1,V2,...` at the commas outside brackets, braces and quotes (a value may be a JSON
/// array or a quoted string with commas).
fn split_values(s: &str) -> Vec<String> {
    let (mut out, mut cur, mut depth, mut quote) = (Vec::new(), String::new(), 0i32, None::<char>);
    for c in s.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                out.push(std::mem::take(&mut cur).trim().to_string());
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    out.push(cur.trim().to_string());
    out
}

impl Vary {
    /// Parses `PATH=V1,V2,...`.
    pub fn parse(s: &str) -> Result<Vary, StudyError> {
        let bad = |m: &str| StudyError::Setting(format!("--vary {s:?}: {m}"));
        let (path, values) = s.split_once('=').ok_or_else(|| bad("expected PATH=V1,V2,..."))?;
        let path = path.trim();
        if path.is_empty() {
            return Err(bad("the field path before `=` is empty"));
        }
        let values = split_values(values);
        if let Some(k) = values.iter().position(String::is_empty) {
            return Err(bad(&format!("value {} is empty (expected V1,V2,... without empty entries)", k + 1)));
        }
        for (k, v) in values.iter().enumerate() {
            if values[..k].contains(v) {
                return Err(bad(&format!("the value {v:?} is given twice")));
            }
        }
        Ok(Vary { path: path.to_string(), values })
    }
}

/// The design points: every combination of the varied values, the first `--vary` slowest.
/// Refuses a path varied twice, a path also given with `--set` (one source of truth), and more
/// than [`MAX_DESIGNS`] points.
pub fn grid(varies: &[Vary], sets: &[String]) -> Result<Vec<Vec<String>>, StudyError> {
    for (k, v) in varies.iter().enumerate() {
        if varies[..k].iter().any(|w| w.path == v.path) {
            return Err(StudyError::Setting(format!("--vary {}: the field is varied twice", v.path)));
        }
        if let Some(s) = sets.iter().find(|s| s.split_once('=').is_some_and(|(p, _)| p.trim() == v.path)) {
            return Err(StudyError::Setting(format!(
                "--vary {} and --set {s}: the field is both set and varied; drop one",
                v.path
            )));
        }
    }
    let count = varies.iter().try_fold(1usize, |n, v| n.checked_mul(v.values.len())).unwrap_or(usize::MAX);
    if count > MAX_DESIGNS {
        return Err(StudyError::Setting(format!(
            "--vary: {count} design points, more than the limit of {MAX_DESIGNS}; vary fewer fields or values"
        )));
    }
    let mut points: Vec<Vec<String>> = vec![Vec::new()];
    for v in varies {
        points = points
            .into_iter()
            .flat_map(|p| {
                v.values.iter().map(move |x| {
                    let mut q = p.clone();
                    q.push(x.clone());
                    q
                })
            })
            .collect();
    }
    Ok(points)
}

/// The `--set`s of one design point: the user's, then `PATH=V` for each varied field.
pub fn sets_for(sets: &[String], varies: &[Vary], point: &[String]) -> Vec<String> {
    let mut all = sets.to_vec();
    all.extend(varies.iter().zip(point).map(|(v, x)| format!("{}={x}", v.path)));
    all
}

/// The friction coefficient of the interface itself, `s / p_mean = s A_r / N`, with s the
/// material's shear strength, A_r the real contact area and N = L + F_adh the total normal force
/// on the contacts (the true clamp load plus the adhesive load), from the explicit (or chosen)
/// contact model's state at each clamp voltage of the nominal device (uncertain parameters at
/// their nominal values, the file's surface) that brings the shoe into contact with L > 0.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InterfaceCoefficient {
    /// Mean of `s A_r / N` over those clamp voltages.
    pub mean: f64,
    /// Smallest of them.
    pub min: f64,
    /// Largest.
    pub max: f64,
    /// Number of clamp voltages.
    pub points: usize,
}

/// [`InterfaceCoefficient`] of the scenario at `path` with `sets`; Err: why it cannot be given.
pub fn interface_coefficient(path: &Path, sets: &[String]) -> Result<InterfaceCoefficient, String> {
    let value = Scenario::load_json(path, sets).map_err(|e| e.to_string())?;
    let scenario = Scenario::from_value(value, path).map_err(|e| e.to_string())?;
    let s = scenario.material.as_ref().map(|m| m.shear_strength).ok_or("the scenario has no material section")?;
    let base_dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut meter = Meter::from_scenario(&scenario, &base_dir).map_err(|e| e.to_string())?;
    let r = meter.run(&mut |_, _| {}).map_err(|e| e.to_string())?;
    let mu: Vec<f64> = r
        .points
        .iter()
        .filter(|p| p.in_contact && p.error.is_none() && p.true_load_n > 0.0 && p.real_area_m2 > 0.0)
        .map(|p| s * p.real_area_m2 / (p.true_load_n + p.adhesive_load_n))
        .filter(|m| m.is_finite())
        .collect();
    if mu.is_empty() {
        return Err("the nominal device is in contact with L > 0 at none of its clamp voltages".into());
    }
    Ok(InterfaceCoefficient {
        mean: mu.iter().sum::<f64>() / mu.len() as f64,
        min: mu.iter().copied().fold(f64::INFINITY, f64::min),
        max: mu.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        points: mu.len(),
    })
}

/// One design point's results.
#[derive(Debug, Clone, Serialize)]
pub struct DesignRow {
    /// Design number (0-based, grid order); its study is in the folder `design-NNN`.
    pub design: usize,
    /// The varied fields and their values, as given.
    pub values: BTreeMap<String, String>,
    /// Samples in the design's log.
    pub samples: usize,
    /// Samples with a usable eq. 10 line.
    pub with_fit: usize,
    /// `with_fit / samples`.
    pub usable_fraction: f64,
    /// Its binomial standard error `sqrt(f (1 - f) / n)`.
    pub usable_fraction_se: f64,
    /// Count of each reason for a sample without a line.
    pub reasons: BTreeMap<String, usize>,
    /// Spread of mu_e,a.
    pub mu_apparent: Option<Spread>,
    /// Spread of F_a0, N.
    pub apparent_adhesion_force_n: Option<Spread>,
    /// Width of the 5-95 % interval of mu_e,a over the virtual meters, p95 - p05.
    pub mu_interval_width: Option<f64>,
    /// Its standard error, from the order-statistic intervals of p05 and p95 (each half-width /
    /// 1.96, added in quadrature).
    pub mu_interval_width_se: Option<f64>,
    /// The interface's own coefficient s / p_mean on the nominal device.
    pub interface_mu: Option<InterfaceCoefficient>,
    /// Why there is no `interface_mu`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interface_mu_reason: Option<String>,
    /// Median mu_e,a minus the interface's mean coefficient.
    pub mu_bias: Option<f64>,
    /// Its standard error (the median's, from its order-statistic interval).
    pub mu_bias_se: Option<f64>,
}

/// Half-width / 1.96 of a 95 % interval: a standard error.
fn se_of(ci: Option<[f64; 2]>) -> Option<f64> {
    ci.map(|[a, b]| (b - a) / (2.0 * 1.96))
}

impl DesignRow {
    /// The row of design `design` at the point `values` from its study summary.
    pub fn new(
        design: usize,
        varies: &[Vary],
        point: &[String],
        summary: &StudySummary,
        interface: Result<InterfaceCoefficient, String>,
    ) -> DesignRow {
        let n = summary.samples_done;
        let f = if n > 0 { summary.with_fit as f64 / n as f64 } else { 0.0 };
        let mu = summary.mu_apparent.clone();
        let width = mu.as_ref().map(|s| s.p95 - s.p05);
        let width_se = mu.as_ref().and_then(|s| Some(se_of(s.p05_ci)?.hypot(se_of(s.p95_ci)?)));
        let (interface_mu, interface_mu_reason) = match interface {
            Ok(i) => (Some(i), None),
            Err(e) => (None, Some(e)),
        };
        let bias = match (&mu, &interface_mu) {
            (Some(s), Some(i)) => Some(s.median - i.mean),
            _ => None,
        };
        DesignRow {
            design,
            values: varies.iter().zip(point).map(|(v, x)| (v.path.clone(), x.clone())).collect(),
            samples: n,
            with_fit: summary.with_fit,
            usable_fraction: f,
            usable_fraction_se: if n > 0 { (f * (1.0 - f) / n as f64).sqrt() } else { 0.0 },
            reasons: summary.reasons.clone(),
            mu_bias_se: bias.and(mu.as_ref().and_then(|s| se_of(s.median_ci))),
            mu_apparent: mu,
            apparent_adhesion_force_n: summary.apparent_adhesion_force_n.clone(),
            mu_interval_width: width,
            mu_interval_width_se: width_se,
            interface_mu,
            interface_mu_reason,
            mu_bias: bias,
        }
    }
}

/// What ranks the designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RankBy {
    /// Smallest 5-95 % width of mu_e,a first.
    Narrowest,
    /// Smallest |median mu_e,a - interface coefficient| first.
    LeastBias,
    /// Largest fraction of usable experiments first.
    MostUsable,
}

impl RankBy {
    /// The criterion's value of a row (smaller is better), None: the row cannot be ranked by it.
    pub fn key(self, r: &DesignRow) -> Option<f64> {
        match self {
            RankBy::Narrowest => r.mu_interval_width,
            RankBy::LeastBias => r.mu_bias.map(f64::abs),
            RankBy::MostUsable => Some(-r.usable_fraction),
        }
    }

    /// The design numbers, best first; rows without a value last, in design order; ties by
    /// design order.
    pub fn rank(self, rows: &[DesignRow]) -> Vec<usize> {
        let mut order: Vec<usize> = (0..rows.len()).collect();
        order.sort_by(|&a, &b| match (self.key(&rows[a]), self.key(&rows[b])) {
            (Some(x), Some(y)) => x.total_cmp(&y).then(a.cmp(&b)),
            (Some(_), None) => std::cmp::Ordering::Less,
            (None, Some(_)) => std::cmp::Ordering::Greater,
            (None, None) => a.cmp(&b),
        });
        order
    }
}

/// designs.csv: one row per design, the varied values first (columns named by their paths),
/// then the results; an empty cell where a value cannot be given.
pub fn designs_csv(varies: &[Vary], rows: &[DesignRow]) -> Result<Vec<u8>, StudyError> {
    let err = |e: &dyn std::fmt::Display| StudyError::Log(format!("formatting designs.csv: {e}"));
    let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    let mut head = vec!["design".to_string()];
    head.extend(varies.iter().map(|v| v.path.clone()));
    head.extend(
        [
            "samples",
            "with_fit",
            "usable_fraction",
            "usable_fraction_se",
            "reasons",
            "mu_median",
            "mu_median_ci_low",
            "mu_median_ci_high",
            "mu_p05",
            "mu_p95",
            "mu_interval_width",
            "mu_interval_width_se",
            "mu_mean",
            "mu_mean_se",
            "mu_sd",
            "fa0_median_n",
            "fa0_p05_n",
            "fa0_p95_n",
            "fa0_sd_n",
            "interface_mu",
            "mu_bias",
            "mu_bias_se",
        ]
        .map(String::from),
    );
    w.write_record(&head).map_err(|e| err(&e))?;
    let o = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    for r in rows {
        let mut f = vec![r.design.to_string()];
        f.extend(varies.iter().map(|v| r.values.get(&v.path).cloned().unwrap_or_default()));
        let m = r.mu_apparent.as_ref();
        let fa = r.apparent_adhesion_force_n.as_ref();
        let reasons: Vec<String> = r.reasons.iter().map(|(k, n)| format!("{k}:{n}")).collect();
        f.extend([
            r.samples.to_string(),
            r.with_fit.to_string(),
            format!("{:e}", r.usable_fraction),
            format!("{:e}", r.usable_fraction_se),
            reasons.join(";"),
            o(m.map(|s| s.median)),
            o(m.and_then(|s| s.median_ci).map(|c| c[0])),
            o(m.and_then(|s| s.median_ci).map(|c| c[1])),
            o(m.map(|s| s.p05)),
            o(m.map(|s| s.p95)),
            o(r.mu_interval_width),
            o(r.mu_interval_width_se),
            o(m.map(|s| s.mean)),
            o(m.map(|s| s.mean_se)),
            o(m.map(|s| s.sd)),
            o(fa.map(|s| s.median)),
            o(fa.map(|s| s.p05)),
            o(fa.map(|s| s.p95)),
            o(fa.map(|s| s.sd)),
            o(r.interface_mu.as_ref().map(|i| i.mean)),
            o(r.mu_bias),
            o(r.mu_bias_se),
        ]);
        w.write_record(&f).map_err(|e| err(&e))?;
    }
    w.into_inner().map_err(|e| err(&e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_split_at_top_level_commas_only() {
        let v = Vary::parse("actuators.clamp.plate_count=30,60").unwrap();
        assert_eq!(
            (v.path.as_str(), v.values.clone()),
            ("actuators.clamp.plate_count", vec!["30".into(), "60".into()])
        );
        let v = Vary::parse(r#"x=[1,2],"a,b", 3 N/m"#).unwrap();
        assert_eq!(v.values, vec!["[1,2]", r#""a,b""#, "3 N/m"]);
        assert!(Vary::parse("x=1,,2").unwrap_err().to_string().contains("value 2 is empty"));
        assert!(Vary::parse("x").unwrap_err().to_string().contains("PATH=V1,V2"));
        assert!(Vary::parse("x=1,1").unwrap_err().to_string().contains("twice"));
    }

    /// Hostile --vary text (brackets, quotes, commas, `=` in any order, unbalanced): an answer,
    /// never a panic; an accepted value list has no empty value and no repeat.
    #[test]
    fn any_vary_text_is_parsed_or_refused_without_a_panic() {
        use rand::{Rng, SeedableRng};
        let alphabet: Vec<char> = "ab.=,[]{}\"' 1-".chars().collect();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..20_000 {
            let len = rng.random_range(0..16);
            let text: String = (0..len).map(|_| alphabet[rng.random_range(0..alphabet.len())]).collect();
            if let Ok(v) = Vary::parse(&text) {
                assert!(!v.path.is_empty() && v.values.iter().all(|x| !x.is_empty()), "{text:?} -> {v:?}");
                let _ = grid(std::slice::from_ref(&v), &[]);
            }
        }
    }

    #[test]
    fn ranking_puts_the_best_first_and_rows_without_a_value_last() {
        let summary = |with_fit: usize, width: Option<(f64, f64)>| {
            let mut mu = Spread::of(&[0.5, 0.6, 0.7]).unwrap();
            if let Some((a, b)) = width {
                (mu.p05, mu.p95) = (a, b);
            }
            StudySummary {
                scenario: String::new(),
                scenario_hash: String::new(),
                config: crate::summary::ConfigSummary {
                    samples: 10,
                    seed: 1,
                    vary_surface: true,
                    shard: "0/1".into(),
                    calibration: crate::Calibration::Nominal,
                    slip_path: stiction_meter::SlipPath::Light,
                },
                samples_done: 10,
                with_fit,
                without_fit: 10 - with_fit,
                failed: 0,
                reasons: BTreeMap::new(),
                reduction: crate::summary::ReductionSummary {
                    a_clamp_n_per_v2: 1.0,
                    a_pull_n_per_v2: 1.0,
                    spring_force_n: 1.0,
                },
                mu_apparent: width.map(|_| mu),
                apparent_adhesion_force_n: None,
                sensitivity: crate::sensitivity::table(&[], &[], &[], &[], true),
                reference: None,
            }
        };
        let v = [Vary::parse("a=1,2,3").unwrap()];
        let iface = |m: f64| Ok(InterfaceCoefficient { mean: m, min: m, max: m, points: 1 });
        let rows = vec![
            DesignRow::new(0, &v, &["1".into()], &summary(5, Some((0.2, 1.0))), iface(0.9)),
            DesignRow::new(1, &v, &["2".into()], &summary(0, None), iface(0.6)),
            DesignRow::new(2, &v, &["3".into()], &summary(9, Some((0.5, 0.7))), Err("no contact".into())),
        ];
        assert_eq!(RankBy::Narrowest.rank(&rows), vec![2, 0, 1]);
        assert_eq!(RankBy::MostUsable.rank(&rows), vec![2, 0, 1]);
        // Only design 0 has both a median (0.6) and an interface coefficient (0.9).
        assert_eq!(RankBy::LeastBias.rank(&rows), vec![0, 1, 2]);
        assert!((rows[0].mu_bias.unwrap() + 0.3).abs() < 1e-12);
        assert_eq!(rows[2].interface_mu_reason.as_deref(), Some("no contact"));
        let csv = String::from_utf8(designs_csv(&v, &rows).unwrap()).unwrap();
        assert_eq!(csv.lines().count(), 4);
        assert!(csv.lines().nth(2).unwrap().starts_with("1,2,10,0,0e0,"), "{csv}");
    }

    #[test]
    fn the_grid_is_every_combination_first_vary_slowest() {
        let a = Vary::parse("a=1,2").unwrap();
        let b = Vary::parse("b=x,y,z").unwrap();
        let g = grid(&[a.clone(), b.clone()], &[]).unwrap();
        assert_eq!(g.len(), 6);
        assert_eq!(g[0], vec!["1", "x"]);
        assert_eq!(g[1], vec!["1", "y"]);
        assert_eq!(g[3], vec!["2", "x"]);
        assert_eq!(sets_for(&["c=3".into()], &[a.clone(), b.clone()], &g[5]), vec!["c=3", "a=2", "b=z"]);
        assert!(
            grid(std::slice::from_ref(&a), &["a=5".into()]).unwrap_err().to_string().contains("both set and varied")
        );
        assert!(grid(&[a.clone(), a.clone()], &[]).unwrap_err().to_string().contains("twice"));
        let many = Vary::parse(&format!("m={}", (0..40).map(|i| i.to_string()).collect::<Vec<_>>().join(","))).unwrap();
        let e = grid(&[many.clone(), Vary { path: "n".into(), ..many }], &[]).unwrap_err().to_string();
        assert!(e.contains("1600 design points") && e.contains("1000"), "{e}");
    }
}
