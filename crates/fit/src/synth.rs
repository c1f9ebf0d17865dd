//! Synthetic measured voltages, made by stiction itself and labelled as such: the virtual meter
//! (or a contact model directly) at a known shear strength, plus a stated Gaussian noise on the
//! pull voltage. Used for the bundled example and for the validation tests.

use std::path::Path;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use stiction_scenario::Scenario;

use crate::error::FitError;
use crate::models::{ModelContext, ModelKind};
use stiction_meter::measured::Row;

/// Largest number of rows synthesised.
pub const MAX_SYNTH_ROWS: usize = 10_000_000;

fn check(voltages: &[f64], repeats: usize, noise_v: f64) -> Result<(), FitError> {
    if repeats == 0 || voltages.len().saturating_mul(repeats) > MAX_SYNTH_ROWS {
        return Err(FitError::Setting(format!(
            "{} clamp voltages x {repeats} repeats: expected 1 to {MAX_SYNTH_ROWS} rows",
            voltages.len()
        )));
    }
    if !(noise_v.is_finite() && noise_v >= 0.0) {
        return Err(FitError::Setting(format!("noise {noise_v} V: expected a finite SD >= 0 V")));
    }
    Ok(())
}

fn noisy(v: f64, noise_v: f64, rng: &mut ChaCha8Rng) -> f64 {
    let z: f64 = StandardNormal.sample(rng);
    (v + noise_v * z).max(0.0)
}

/// Runs the virtual meter of `scenario` (its own shear strength, contact model and pull ramp) at
/// `voltages` and records each slip `repeats` times with Gaussian noise of SD `noise_v` (V) on the
/// pull voltage, from ChaCha8 seed `seed`. Clamp voltages without slip give no row.
pub fn from_meter(
    scenario: &Scenario,
    base_dir: &Path,
    voltages: &[f64],
    repeats: usize,
    noise_v: f64,
    seed: u64,
) -> Result<Vec<Row>, FitError> {
    check(voltages, repeats, noise_v)?;
    let mut meter = stiction_meter::Meter::from_scenario(scenario, base_dir)?;
    let result = meter.run_at(voltages, &mut |_, _| {})?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut rows = Vec::new();
    for p in &result.points {
        if let Some(v) = p.v_pull {
            for _ in 0..repeats {
                rows.push(Row {
                    line: 0,
                    device: String::new(),
                    v_clamp_v: p.v_clamp,
                    v_pull_v: noisy(v, noise_v, &mut rng),
                    v_pull_sd_v: None,
                });
            }
        }
    }
    Ok(rows)
}

/// Data from a contact model directly (continuous slip threshold, no ramp): `V_pull =
/// sqrt((s g + h) / a_pull)` at each clamp voltage with L > 0, plus noise. Cheap: for the
/// coverage tests.
pub fn from_model(
    ctx: &ModelContext,
    kind: ModelKind,
    shear_strength_pa: f64,
    voltages: &[f64],
    repeats: usize,
    noise_v: f64,
    rng: &mut ChaCha8Rng,
) -> Result<Vec<Row>, FitError> {
    check(voltages, repeats, noise_v)?;
    let mut model = ctx.build(kind, None, None)?;
    let xs: Vec<f64> = voltages.iter().map(|v| v * v).collect();
    let parts = ctx.parts(&mut model, &ctx.loads(&xs, ctx.device.spring_force_n));
    let mut rows = Vec::new();
    for (v, p) in voltages.iter().zip(&parts) {
        let Ok((g, h)) = p else { continue };
        if *g <= 0.0 {
            continue;
        }
        let v_pull = ((shear_strength_pa * g + h) / ctx.device.a_pull_n_per_v2).sqrt();
        for _ in 0..repeats {
            rows.push(Row {
                line: 0,
                device: String::new(),
                v_clamp_v: *v,
                v_pull_v: noisy(v_pull, noise_v, rng),
                v_pull_sd_v: None,
            });
        }
    }
    for (k, r) in rows.iter_mut().enumerate() {
        r.line = k as u64 + 2;
    }
    Ok(rows)
}

/// The rows as CSV text (`v_clamp_v,v_pull_v`), each line of `comment` first as a `#` line.
pub fn to_csv(rows: &[Row], comment: &str) -> Result<String, FitError> {
    let mut out = String::new();
    for line in comment.lines() {
        out.push_str("# ");
        out.push_str(line);
        out.push('\n');
    }
    let mut w = csv::Writer::from_writer(Vec::new());
    let err = |e: csv::Error| FitError::Setting(format!("cannot write CSV: {e}"));
    w.write_record(["v_clamp_v", "v_pull_v"]).map_err(err)?;
    for r in rows {
        w.write_record([format!("{}", r.v_clamp_v), format!("{:.4}", r.v_pull_v)]).map_err(err)?;
    }
    let bytes = w.into_inner().map_err(|e| FitError::Setting(format!("cannot write CSV: {e}")))?;
    out.push_str(&String::from_utf8_lossy(&bytes));
    Ok(out)
}
