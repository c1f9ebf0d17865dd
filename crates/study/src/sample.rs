//! Drawing one realisation of a scenario: every uncertain parameter object in the JSON tree is
//! replaced by a number drawn from its distribution, in SI.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution as _, StandardNormal};
use serde_json::{Map, Value};
use stiction_units::{Distribution, ScalarInput, UncertainInput, parse_any};

use crate::error::StudyError;

/// One drawn parameter: its JSON path and SI value.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Draw {
    /// JSON path, like `surface.summit_radius`.
    pub path: String,
    /// The drawn value, SI.
    pub value: f64,
}

const UNCERTAIN_KEYS: [&str; 5] = ["value", "sd", "distribution", "min", "max"];

/// Whether a JSON object is an uncertain parameter (has `value` and only the uncertain keys).
fn is_uncertain(map: &Map<String, Value>) -> bool {
    map.contains_key("value") && map.keys().all(|k| UNCERTAIN_KEYS.contains(&k.as_str()))
}

fn si(s: &ScalarInput, path: &str, what: &str) -> Result<(f64, stiction_units::DimensionVector), StudyError> {
    match s {
        ScalarInput::Number(x) => Ok((*x, stiction_units::DimensionVector::default())),
        ScalarInput::Text(t) => {
            parse_any(t).map_err(|e| StudyError::Sample { path: path.into(), message: format!("{what}: {e}") })
        }
    }
}

/// Draws one value of an uncertain parameter, in SI.
///
/// * normal: `value + sd * N(0, 1)`, redrawn (up to 1000 times) while the sign differs from the
///   nominal's, so that a positive quantity stays positive (a normal truncated at zero);
/// * lognormal with mean m = `value` and standard deviation s = `sd`:
///   `exp(mu + sigma N(0, 1))` with `sigma^2 = ln(1 + s^2/m^2)`, `mu = ln m - sigma^2 / 2`;
/// * uniform on `[min, max]`, or on `value -/+ sqrt(3) sd` (the same standard deviation).
pub fn draw(u: &UncertainInput, path: &str, rng: &mut ChaCha8Rng) -> Result<f64, StudyError> {
    Sampler::new(u, path)?.sample(path, rng)
}

/// An uncertain parameter with its text parsed once, for drawing it many times: [`Sampler::sample`]
/// draws exactly what [`draw`] draws from the same generator state (same distribution, same
/// numbers taken from the generator), without parsing the unit strings again.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sampler {
    /// Normal `m + sd N(0, 1)`, redrawn while the sign differs from m's (SI).
    Normal {
        /// Mean, SI.
        m: f64,
        /// Standard deviation, SI.
        sd: f64,
    },
    /// `exp(mu + sigma N(0, 1))`.
    Lognormal {
        /// Mean of the logarithm.
        mu: f64,
        /// Standard deviation of the logarithm.
        sigma: f64,
    },
    /// Uniform on `[a, b)` (the point a when b = a).
    Uniform {
        /// Lower end, SI.
        a: f64,
        /// Upper end, SI.
        b: f64,
    },
}

impl Sampler {
    /// Parses `u` (errors name `path`, as [`draw`]'s do).
    pub fn new(u: &UncertainInput, path: &str) -> Result<Sampler, StudyError> {
        let err = |message: String| StudyError::Sample { path: path.into(), message };
        let (m, dim) = si(&u.value, path, "value")?;
        let sd = match &u.sd {
            Some(s) => {
                let (sd, d) = si(s, path, "sd")?;
                if d != dim && !matches!(s, ScalarInput::Number(_)) && !matches!(u.value, ScalarInput::Number(_)) {
                    return Err(err(format!("`sd` has another unit than `value` ({:?} vs {:?})", d.0, dim.0)));
                }
                if !(sd.is_finite() && sd >= 0.0) {
                    return Err(err(format!("`sd` = {sd} must be finite and >= 0")));
                }
                sd
            }
            None => 0.0,
        };
        let bound =
            |b: &Option<ScalarInput>, what: &str| b.as_ref().map(|b| si(b, path, what).map(|x| x.0)).transpose();
        let (lo, hi) = (bound(&u.min, "min")?, bound(&u.max, "max")?);
        Ok(match u.distribution {
            Distribution::Normal => Sampler::Normal { m, sd },
            Distribution::Lognormal => {
                if m <= 0.0 {
                    return Err(err(format!("a lognormal parameter needs a positive value, got {m}")));
                }
                let sigma2 = (1.0 + (sd / m).powi(2)).ln();
                Sampler::Lognormal { mu: m.ln() - 0.5 * sigma2, sigma: sigma2.sqrt() }
            }
            Distribution::Uniform => {
                let (a, b) = match (lo, hi) {
                    (Some(a), Some(b)) => (a, b),
                    _ => (m - 3f64.sqrt() * sd, m + 3f64.sqrt() * sd),
                };
                if !(a.is_finite() && b.is_finite() && (b - a).is_finite()) {
                    return Err(err(format!(
                        "uniform bounds [{a:e}, {b:e}]: the bounds and their width b - a must be finite numbers \
                         (|b - a| < 1.8e308)"
                    )));
                }
                if b < a {
                    return Err(err(format!("uniform bounds [{a}, {b}] are reversed")));
                }
                Sampler::Uniform { a, b }
            }
        })
    }

    /// Draws one value, SI (`path` names the parameter in the error of a non-finite draw).
    pub fn sample(&self, path: &str, rng: &mut ChaCha8Rng) -> Result<f64, StudyError> {
        let value = match *self {
            Sampler::Normal { m, sd } => {
                let mut x = m;
                for _ in 0..1000 {
                    let z: f64 = StandardNormal.sample(rng);
                    x = m + sd * z;
                    if m == 0.0 || x.signum() == m.signum() {
                        break;
                    }
                }
                x
            }
            Sampler::Lognormal { mu, sigma } => {
                let z: f64 = StandardNormal.sample(rng);
                (mu + sigma * z).exp()
            }
            Sampler::Uniform { a, b } => {
                if b == a {
                    a
                } else {
                    rng.random_range(a..b)
                }
            }
        };
        if !value.is_finite() {
            return Err(StudyError::Sample {
                path: path.into(),
                message: format!("the drawn value {value:e} is not a finite number ({self:?})"),
            });
        }
        Ok(value)
    }
}

/// The uncertain parameters of a scenario tree, in draw order (the order of [`sample_tree`]):
/// `(JSON path, SI unit of the drawn value)`. The unit comes from the `value` text ("0.5 um" ->
/// "m"); a bare number is already SI, its unit is given as "SI".
pub fn uncertain_parameters(value: &Value) -> Result<Vec<(String, String)>, StudyError> {
    fn go(v: &Value, path: String, out: &mut Vec<(String, String)>) -> Result<(), StudyError> {
        match v {
            Value::Object(map) if is_uncertain(map) => {
                let u: UncertainInput = serde_json::from_value(Value::Object(map.clone()))
                    .map_err(|e| StudyError::Sample { path: path.clone(), message: e.to_string() })?;
                let unit = match &u.value {
                    ScalarInput::Number(_) => "SI".to_string(),
                    ScalarInput::Text(_) => {
                        let dim = si(&u.value, &path, "value")?.1;
                        unit_of(dim)
                    }
                };
                out.push((path, unit));
            }
            Value::Object(map) => {
                let mut keys: Vec<&String> = map.keys().collect();
                keys.sort();
                for k in keys {
                    let child = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                    go(&map[k], child, out)?;
                }
            }
            Value::Array(items) => {
                for (i, c) in items.iter().enumerate() {
                    go(c, format!("{path}.{i}"), out)?;
                }
            }
            _ => {}
        }
        Ok(())
    }
    let mut out = Vec::new();
    go(value, String::new(), &mut out)?;
    Ok(out)
}

/// The SI unit of a dimension vector, by the names the scenario format uses.
fn unit_of(dim: stiction_units::DimensionVector) -> String {
    use stiction_units::Dimension as D;
    const ALL: [D; 16] = [
        D::Dimensionless,
        D::Length,
        D::Area,
        D::Force,
        D::Pressure,
        D::SurfaceEnergy,
        D::Compliance,
        D::ArealDensity,
        D::ForcePerVoltageSquared,
        D::Voltage,
        D::Stiffness,
        D::Angle,
        D::Time,
        D::Mass,
        D::Damping,
        D::MolarVolume,
    ];
    match ALL.iter().find(|d| d.vector() == dim) {
        Some(D::Dimensionless) => "1".into(),
        Some(d) => d.si_unit().into(),
        None => {
            let names = ["m", "kg", "s", "A", "mol"];
            let parts: Vec<String> =
                dim.0.iter().zip(names).filter(|(e, _)| **e != 0).map(|(e, n)| format!("{n}^{e}")).collect();
            parts.join(" ")
        }
    }
}

/// Replaces every uncertain parameter in `value` (depth first, keys in sorted order, so the
/// order of draws is fixed) by a drawn SI number, and returns the draws.
pub fn sample_tree(value: &mut Value, rng: &mut ChaCha8Rng) -> Result<Vec<Draw>, StudyError> {
    let mut draws = Vec::new();
    walk(value, String::new(), rng, &mut draws)?;
    Ok(draws)
}

fn walk(v: &mut Value, path: String, rng: &mut ChaCha8Rng, draws: &mut Vec<Draw>) -> Result<(), StudyError> {
    match v {
        Value::Object(map) if is_uncertain(map) => {
            let u: UncertainInput = serde_json::from_value(Value::Object(map.clone()))
                .map_err(|e| StudyError::Sample { path: path.clone(), message: e.to_string() })?;
            let x = draw(&u, &path, rng)?;
            draws.push(Draw { path, value: x });
            *v = Value::from(x);
        }
        Value::Object(map) => {
            let mut keys: Vec<String> = map.keys().cloned().collect();
            keys.sort();
            for k in keys {
                let child = if path.is_empty() { k.clone() } else { format!("{path}.{k}") };
                if let Some(c) = map.get_mut(&k) {
                    walk(c, child, rng, draws)?;
                }
            }
        }
        Value::Array(items) => {
            for (i, c) in items.iter_mut().enumerate() {
                walk(c, format!("{path}.{i}"), rng, draws)?;
            }
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    fn moments(u: &UncertainInput, n: usize) -> (f64, f64) {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let xs: Vec<f64> = (0..n).map(|_| draw(u, "x", &mut rng).unwrap()).collect();
        let m = xs.iter().sum::<f64>() / n as f64;
        let v = xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n as f64 - 1.0);
        (m, v.sqrt())
    }

    #[test]
    fn each_distribution_has_the_requested_mean_and_sd() {
        // 40000 draws: the standard error of the mean is sd / 200, of the SD about sd / 280;
        // tolerance 4 standard errors (and a little more for the skewed lognormal's SD).
        let n = 40_000;
        for (dist, m, sd) in [
            (Distribution::Normal, 7e-6, 2e-6),
            (Distribution::Lognormal, 0.5e-6, 0.3e-6),
            (Distribution::Uniform, 1.0, 0.1),
        ] {
            let u = UncertainInput {
                value: ScalarInput::Number(m),
                sd: Some(ScalarInput::Number(sd)),
                distribution: dist,
                min: None,
                max: None,
            };
            let (gm, gs) = moments(&u, n);
            assert!((gm - m).abs() < 4.0 * sd / 200.0, "{dist:?}: mean {gm} vs {m}");
            assert!((gs - sd).abs() < 8.0 * sd / 280.0, "{dist:?}: sd {gs} vs {sd}");
        }
    }

    #[test]
    fn units_are_converted_and_the_tree_is_replaced_in_order() {
        let mut v = serde_json::json!({
            "b": {"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"},
            "a": [{"value": "7 uN", "sd": "2 uN"}, 3],
            "c": "1 um"
        });
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let draws = sample_tree(&mut v, &mut rng).unwrap();
        assert_eq!(draws.iter().map(|d| d.path.as_str()).collect::<Vec<_>>(), vec!["a.0", "b"]);
        assert!(v["a"][0].as_f64().unwrap() > 0.0 && v["a"][0].as_f64().unwrap() < 2e-5);
        assert!(v["b"].as_f64().unwrap() > 0.0 && v["b"].as_f64().unwrap() < 1e-5);
        assert_eq!(v["c"], "1 um");
        assert_eq!(v["a"][1], 3);
    }

    #[test]
    fn an_overflowing_uniform_range_is_an_error_not_a_panic() {
        // Issue 9: min -1.7e308, max 1.7e308 made rand panic (the width overflows to inf).
        let u: UncertainInput = serde_json::from_value(serde_json::json!({
            "value": 0.0, "distribution": "uniform", "min": -1.7e308, "max": 1.7e308
        }))
        .unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let e = draw(&u, "meter.spring_force", &mut rng).unwrap_err().to_string();
        assert!(e.contains("meter.spring_force") && e.contains("finite"), "{e}");
    }

    #[test]
    fn parameters_are_listed_in_draw_order_with_their_units() {
        let v = serde_json::json!({
            "b": {"value": "0.5 um", "sd": "0.3 um", "distribution": "lognormal"},
            "a": [{"value": "1.4e-8 N/V^2", "sd": "0.5e-8 N/V^2"}, 3],
            "c": {"value": 0.7, "sd": 0.1}
        });
        let p = uncertain_parameters(&v).unwrap();
        let want = [("a.0", "N/V^2"), ("b", "m"), ("c", "SI")];
        assert_eq!(p.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect::<Vec<_>>(), want);
        let mut w = v.clone();
        let draws = sample_tree(&mut w, &mut ChaCha8Rng::seed_from_u64(1)).unwrap();
        assert_eq!(draws.iter().map(|d| d.path.as_str()).collect::<Vec<_>>(), vec!["a.0", "b", "c"]);
    }

    #[test]
    fn mismatched_units_are_an_error_naming_the_path() {
        let u: UncertainInput = serde_json::from_value(serde_json::json!({"value": "0.5 um", "sd": "0.3 uN"})).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let e = draw(&u, "surface.summit_radius", &mut rng).unwrap_err().to_string();
        assert!(e.contains("surface.summit_radius") && e.contains("another unit"), "{e}");
    }
}
