//! Helpers shared by the fit tests.

/// The first non-finite number in a value's `Debug` text (`NaN`, `inf`, `-inf` standing alone,
/// not inside a word), with a little context; None when there is none. serde_json writes a
/// non-finite f64 as `null`, so a JSON check cannot see them; the Debug text shows every f64.
pub fn non_finite_in_debug(text: &str) -> Option<String> {
    let b = text.as_bytes();
    for token in ["NaN", "inf"] {
        let mut from = 0;
        while let Some(k) = text[from..].find(token) {
            let i = from + k;
            let j = i + token.len();
            let before_ok = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'\'');
            let after_ok = j >= b.len() || !(b[j].is_ascii_alphanumeric() || b[j] == b'_');
            // Inside a string (a note) the word is preceded by a space and followed by a space.
            let prose = i > 0 && b[i - 1] == b' ' && j < b.len() && b[j] == b' ';
            if before_ok && after_ok && !prose {
                let mut lo = i.saturating_sub(60);
                while !text.is_char_boundary(lo) {
                    lo -= 1;
                }
                return Some(text[lo..j.min(text.len())].to_string());
            }
            from = j;
        }
    }
    None
}
