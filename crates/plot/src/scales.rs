//! Axis scales (linear, log, symmetric log) and their ticks: the choice of tick values and their
//! labels, powers of ten in superscript digits.

/// Superscript digits for a power of ten: `-3` -> `⁻³`.
pub fn superscript(n: i64) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            c => c,
        })
        .collect()
}

/// How an axis maps data to drawing coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Scale {
    Linear,
    Log,
    /// Symmetric log with linear threshold c: sign(v) log10(1 + |v|/c).
    SymLog(f64),
}

impl Scale {
    pub(crate) fn of(log: bool, symlog: Option<f64>) -> Scale {
        match (log, symlog) {
            (true, _) => Scale::Log,
            (false, Some(c)) if c > 0.0 && c.is_finite() => Scale::SymLog(c),
            _ => Scale::Linear,
        }
    }
    pub(crate) fn to_axis(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log => v.log10(),
            Scale::SymLog(c) => v.signum() * (v.abs() / c).ln_1p() / std::f64::consts::LN_10,
        }
    }
    pub(crate) fn to_data(self, t: f64) -> f64 {
        match self {
            Scale::Linear => t,
            Scale::Log => 10f64.powf(t),
            Scale::SymLog(c) => t.signum() * c * (10f64.powf(t.abs()) - 1.0),
        }
    }
}

/// A "nice" tick step (1, 2 or 5 times a power of ten) for about `n` intervals over `span`.
fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(f64::MIN_POSITIVE);
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    let m = raw / base;
    let k = if m <= 1.0 {
        1.0
    } else if m <= 2.0 {
        2.0
    } else if m <= 5.0 {
        5.0
    } else {
        10.0
    };
    k * base
}

/// The labelled (bold) and light tick positions of an axis over `[lo, hi]` in axis coordinates,
/// about `n` labelled intervals. Linear: multiples of a nice step, light lines at a fifth of it. Log: every decade (every
/// second or more on long axes), 2 and 5 times a power of ten on axes shorter than about two
/// decades, light lines at 2..9 times each power. Symmetric log: 0 and plus and minus powers of
/// ten, every one or every few decades counted from the largest.
pub(crate) fn ticks(scale: Scale, lo: f64, hi: f64, n: f64) -> (Vec<f64>, Vec<f64>) {
    let span = (hi - lo).abs().max(1e-300);
    let within = |v: &f64| *v >= lo - 1e-9 * span && *v <= hi + 1e-9 * span;
    match scale {
        Scale::Linear => {
            let step = nice_step(span, n);
            let multiples = |step: f64| -> Vec<f64> {
                let (a, b) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
                if b < a || b - a > 10_000 {
                    return Vec::new();
                }
                (a..=b).map(|k| k as f64 * step).collect()
            };
            (multiples(step), multiples(step / 5.0))
        }
        Scale::Log => {
            let (a, b) = (lo.floor() as i64, hi.ceil() as i64);
            if b - a > 400 {
                return (Vec::new(), Vec::new());
            }
            let every = nice_step(hi - lo, n).max(1.0) as i64;
            let mut bold: Vec<f64> = (a..=b).filter(|k| k.rem_euclid(every) == 0).map(|k| k as f64).collect();
            if hi - lo < 2.2 && n >= 4.0 {
                for k in a..=b {
                    bold.extend([2.0f64, 5.0].map(|m| k as f64 + m.log10()));
                }
            }
            let mut light = Vec::new();
            if hi - lo <= 12.0 {
                for k in a..=b {
                    light.extend((1..10).map(|m| k as f64 + (m as f64).log10()));
                }
            }
            bold.retain(within);
            bold.sort_by(f64::total_cmp);
            light.retain(within);
            (bold, light)
        }
        Scale::SymLog(c) => {
            let top = scale.to_data(lo.abs().max(hi.abs()));
            // Labels from 10 c outwards: c itself sits too close to 0 to be labelled.
            let (k0, k1) = (c.log10().ceil() as i64 + 1, top.log10().ceil() as i64);
            let mut bold = vec![0.0];
            let mut light = Vec::new();
            let decades = (k1 - k0).clamp(0, 400);
            let every = (decades as f64 / (n * 0.8).max(1.0)).ceil().max(1.0) as i64;
            // Every `every`-th decade counted down from the largest on the axis, none closer to 0
            // than three quarters of the spacing (its label would touch the 0).
            let kt = top.log10().floor() as i64;
            for k in k0..=k0 + decades {
                let p = 10f64.powi(k as i32);
                if (kt - k).rem_euclid(every) == 0 && scale.to_axis(p) >= 0.75 * every as f64 {
                    bold.extend([scale.to_axis(p), scale.to_axis(-p)]);
                }
                for m in 2..10 {
                    light.extend([scale.to_axis(m as f64 * p), scale.to_axis(-(m as f64) * p)]);
                }
            }
            bold.retain(within);
            bold.sort_by(f64::total_cmp);
            light.retain(within);
            (bold, light)
        }
    }
}

/// `10ⁿ` (or `−10ⁿ`) when `v` is a power of ten within rounding, else `a·10ⁿ` with one decimal.
fn power_label(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let sign = if v < 0.0 { "−" } else { "" };
    let l = v.abs().log10();
    let e = l.round();
    if (l - e).abs() < 1e-6 {
        return format!("{sign}10{}", superscript(e as i64));
    }
    let e = l.floor();
    let m = v.abs() / 10f64.powf(e);
    format!("{sign}{}·10{}", (m * 10.0).round() / 10.0, superscript(e as i64))
}

/// A tick label, one format per axis (`lo`, `hi`: the axis range in drawing coordinates). Log
/// axis (`v` is log10 of the value): `10ⁿ` at decades; on a short axis (under about two decades)
/// 2 and 5 times a power of ten too, all as plain numbers when the whole axis lies within
/// 0.001-100000 (`20, 50, 100, 200`), else as `a·10ⁿ`. Symmetric-log axis: `0`, `10ⁿ`, `−10ⁿ`.
/// Linear axis: plain numbers, or `a·10ⁿ` for very large or small values.
pub(crate) fn tick_label(v: f64, scale: Scale, lo: f64, hi: f64) -> String {
    let span = (hi - lo).abs();
    match scale {
        Scale::Log => {
            let short = span <= 2.2;
            let plain = short && lo.min(hi) >= -3.0 && lo.max(hi) < 5.0;
            let r = v.round();
            let at_decade = (v - r).abs() < 1e-6;
            if plain {
                if !at_decade && !is_2_or_5(v) {
                    return String::new();
                }
                let x = 10f64.powf(v);
                // Rounded to 4 significant digits: 0.002, 50, 200.
                let decimals = (3.0 - x.log10().floor()).clamp(0.0, 8.0) as usize;
                let t = format!("{x:.decimals$}");
                return if t.contains('.') { t.trim_end_matches('0').trim_end_matches('.').to_string() } else { t };
            }
            if at_decade {
                return format!("10{}", superscript(r as i64));
            }
            if !short || !is_2_or_5(v) {
                return String::new();
            }
            power_label(10f64.powf(v))
        }
        Scale::SymLog(_) => {
            if v.abs() < 1e-9 {
                "0".into()
            } else {
                power_label(scale.to_data(v))
            }
        }
        Scale::Linear => {
            let a = v.abs();
            if a != 0.0 && !(1e-3..1e5).contains(&a) {
                power_label(v)
            } else {
                let r = (v * 1e6).round() / 1e6;
                // No "-0".
                format!("{}", if r == 0.0 { 0.0 } else { r }).replace('-', "−")
            }
        }
    }
}

/// Whether log10 value `v` is at 2 or 5 times a power of ten.
fn is_2_or_5(v: f64) -> bool {
    let m = 10f64.powf(v - v.floor());
    [2.0f64, 5.0].iter().any(|k| (m - k).abs() < 0.02 * k)
}
