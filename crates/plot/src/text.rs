//! Text: the embedded font, the small symbol markup and text measurement.
//!
//! Every glyph is drawn from DejaVu Sans, carried inside the program (`fonts/DejaVuSans.ttf`,
//! Bitstream Vera licence, `fonts/DejaVuSans-LICENSE.txt`), so no system font is looked up and a
//! figure is the same bytes on every machine.
//!
//! Markup (in titles, labels, legend entries and captions):
//! - `X_{ab}` sets `ab` as a subscript, `X^{ab}` as a superscript;
//! - `X_ab` after a one-letter symbol (`F_a0`, `μ_e,a`, `A_r/A_0`, `V_pull²`) sets the following
//!   letters, digits and inner commas as a subscript; `X^2`, `X^-3` a superscript of digits;
//! - `\mu`, `\theta`, ... give Greek letters, `\_` a literal underscore;
//! - Markdown backticks are dropped.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use std::sync::LazyLock;

/// The bytes of the embedded font (DejaVu Sans 2.37).
pub static FONT_BYTES: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

/// The font family name written into SVG text.
pub const FONT_FAMILY: &str = "DejaVu Sans, Bitstream Vera Sans, Verdana, sans-serif";

pub(crate) static FONT: LazyLock<FontRef<'static>> =
    LazyLock::new(|| FontRef::try_from_slice(FONT_BYTES).expect("the embedded DejaVu Sans parses"));

/// Ascent and descent of the ink of ordinary characters (ascender of `d`, `l` and descender of
/// `p`, `g` in DejaVu Sans) as fractions of the em size: the text boxes of a layout.
pub(crate) const ASCENT: f64 = 0.76;
/// See [`ASCENT`].
pub(crate) const DESCENT: f64 = 0.24;
/// Size of a subscript or superscript relative to the text around it.
pub(crate) const SCRIPT_SIZE: f64 = 0.7;
/// Baseline shift of a subscript (down), em of the surrounding text.
pub(crate) const SUB_SHIFT: f64 = 0.22;
/// Baseline shift of a superscript (up), em of the surrounding text.
pub(crate) const SUP_SHIFT: f64 = 0.38;

/// Position of a run relative to the baseline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shift {
    /// On the baseline.
    Normal,
    /// Subscript.
    Sub,
    /// Superscript.
    Sup,
}

/// A piece of text set in one way.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Run {
    /// The characters.
    pub text: String,
    /// Where it sits.
    pub shift: Shift,
}

fn greek(name: &str) -> Option<char> {
    Some(match name {
        "alpha" => 'α',
        "beta" => 'β',
        "gamma" => 'γ',
        "delta" => 'δ',
        "Delta" => 'Δ',
        "epsilon" => 'ε',
        "eta" => 'η',
        "theta" => 'θ',
        "kappa" => 'κ',
        "lambda" => 'λ',
        "mu" => 'μ',
        "nu" => 'ν',
        "pi" => 'π',
        "rho" => 'ρ',
        "sigma" => 'σ',
        "tau" => 'τ',
        "phi" => 'φ',
        "omega" => 'ω',
        "infty" => '∞',
        "pm" => '±',
        "times" => '×',
        _ => return None,
    })
}

/// Splits marked-up text into runs (see the module documentation). Plain text is one run.
pub fn typeset(markup: &str) -> Vec<Run> {
    let chars: Vec<char> = markup.chars().filter(|&c| c != '`').collect();
    let mut runs: Vec<Run> = Vec::new();
    let push = |runs: &mut Vec<Run>, c: char, shift: Shift| match runs.last_mut() {
        Some(r) if r.shift == shift => r.text.push(c),
        _ => runs.push(Run { text: c.to_string(), shift }),
    };
    let symbolic = |c: char| c.is_alphabetic() || c.is_ascii_digit();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '\\' {
            if chars.get(i + 1) == Some(&'_') {
                push(&mut runs, '_', Shift::Normal);
                i += 2;
                continue;
            }
            let name: String = chars[i + 1..].iter().take_while(|c| c.is_ascii_alphabetic()).collect();
            if let Some(g) = greek(&name) {
                push(&mut runs, g, Shift::Normal);
                i += 1 + name.chars().count();
                continue;
            }
        }
        if (c == '_' || c == '^') && i + 1 < chars.len() {
            let shift = if c == '_' { Shift::Sub } else { Shift::Sup };
            if chars[i + 1] == '{'
                && let Some(end) = chars[i + 2..].iter().position(|&c| c == '}')
            {
                for &d in &chars[i + 2..i + 2 + end] {
                    let d = if d == '\\' { continue } else { d };
                    push(&mut runs, d, shift);
                }
                i += end + 3;
                continue;
            }
            // A one-letter symbol before the mark: `F_a0`, not `file_name`.
            let one_letter = i >= 1 && chars[i - 1].is_alphabetic() && (i < 2 || !chars[i - 2].is_alphanumeric())
                || i >= 1 && matches!(chars[i - 1], '*' | '\'' | ')');
            if c == '_' && one_letter {
                let mut j = i + 1;
                while j < chars.len()
                    && (symbolic(chars[j])
                        || chars[j] == ',' && j + 1 < chars.len() && symbolic(chars[j + 1]) && j > i + 1)
                {
                    j += 1;
                }
                if j > i + 1 {
                    for &d in &chars[i + 1..j] {
                        push(&mut runs, d, Shift::Sub);
                    }
                    i = j;
                    continue;
                }
            }
            if c == '^' {
                let mut j = i + 1;
                if chars[j] == '-' || chars[j] == '−' {
                    j += 1;
                }
                let start = j;
                while j < chars.len() && chars[j].is_ascii_digit() {
                    j += 1;
                }
                if j > start {
                    for &d in &chars[i + 1..j] {
                        push(&mut runs, if d == '-' { '−' } else { d }, Shift::Sup);
                    }
                    i = j;
                    continue;
                }
            }
        }
        push(&mut runs, c, Shift::Normal);
        i += 1;
    }
    runs
}

/// The text as it reads without markup (`F_{a0}` -> `Fa0`): for searching and tests.
pub fn plain(markup: &str) -> String {
    typeset(markup).into_iter().map(|r| r.text).collect()
}

/// The ab_glyph scale whose em is `size_px`.
pub(crate) fn px_scale(size_px: f64) -> PxScale {
    let f = &*FONT;
    let units = f.units_per_em().unwrap_or(2048.0) as f64;
    PxScale::from((size_px * f.height_unscaled() as f64 / units) as f32)
}

/// Advance width of plain characters at em size `size_px`, with kerning.
pub(crate) fn plain_width(text: &str, size_px: f64) -> f64 {
    let font = FONT.as_scaled(px_scale(size_px));
    let mut w = 0.0f64;
    let mut prev = None;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if let Some(p) = prev {
            w += font.kern(p, id) as f64;
        }
        w += font.h_advance(id) as f64;
        prev = Some(id);
    }
    w
}

/// Size and baseline offset (positive down) of a run in text of em size `size`.
pub(crate) fn run_metrics(shift: Shift, size: f64) -> (f64, f64) {
    match shift {
        Shift::Normal => (size, 0.0),
        Shift::Sub => (size * SCRIPT_SIZE, size * SUB_SHIFT),
        Shift::Sup => (size * SCRIPT_SIZE, -size * SUP_SHIFT),
    }
}

/// Width of marked-up text at em size `size` px.
pub fn text_width(markup: &str, size: f64) -> f64 {
    typeset(markup).iter().map(|r| plain_width(&r.text, run_metrics(r.shift, size).0)).sum()
}

/// Extent above and below the baseline (both positive) of marked-up text at em size `size`.
pub fn text_extent(markup: &str, size: f64) -> (f64, f64) {
    let mut up = ASCENT * size;
    let mut down = DESCENT * size;
    for r in typeset(markup) {
        let (s, dy) = run_metrics(r.shift, size);
        up = up.max(ASCENT * s - dy);
        down = down.max(DESCENT * s + dy);
    }
    (up, down)
}

/// Breaks marked-up text into lines no wider than `width` at em size `size`, at spaces (a word
/// longer than the line stands alone). `\n` always breaks.
pub fn wrap(markup: &str, width: f64, size: f64) -> Vec<String> {
    let mut lines = Vec::new();
    for para in markup.split('\n') {
        let mut line = String::new();
        for word in para.split(' ').filter(|w| !w.is_empty()) {
            let candidate = if line.is_empty() { word.to_string() } else { format!("{line} {word}") };
            if line.is_empty() || text_width(&candidate, size) <= width {
                line = candidate;
            } else {
                lines.push(std::mem::take(&mut line));
                line = word.to_string();
            }
        }
        if !line.is_empty() {
            lines.push(line);
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    fn show(m: &str) -> String {
        typeset(m)
            .iter()
            .map(|r| match r.shift {
                Shift::Normal => r.text.clone(),
                Shift::Sub => format!("[{}]", r.text),
                Shift::Sup => format!("^[{}]", r.text),
            })
            .collect()
    }

    #[test]
    fn symbols_are_typeset_and_no_underscore_is_printed() {
        assert_eq!(show("F_a0 = 2 µN"), "F[a0] = 2 µN");
        assert_eq!(show("measured μ_e,a = 0.7"), "measured μ[e,a] = 0.7");
        assert_eq!(show("\\mu_{e,a} and F_{a0}"), "μ[e,a] and F[a0]");
        assert_eq!(show("A_r/A_0"), "A[r]/A[0]");
        assert_eq!(show("V_pull² (V²)"), "V[pull]² (V²)");
        assert_eq!(show("friction F_f (µN)"), "friction F[f] (µN)");
        assert_eq!(show("x^{-3} and 10^-6"), "x^[-3] and 10^[−6]");
        assert_eq!(show("`fit_report.json`"), "fit_report.json");
        assert_eq!(show("a\\_b"), "a_b");
        assert!(text_width("F_a0", 10.0) < text_width("Fa0", 10.0));
    }

    #[test]
    fn wrapping_keeps_lines_within_the_width() {
        let text = "Static friction against load for the virtual meter and the paper's measurement";
        let lines = wrap(text, 120.0, 10.0);
        assert!(lines.len() > 2, "{lines:?}");
        assert!(lines.iter().all(|l| text_width(l, 10.0) <= 120.0));
        assert_eq!(lines.join(" "), text);
    }
}
