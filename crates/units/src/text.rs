//! Bounds and quoting for text inputs, shared by every reader of stiction.
//!
//! A reader of a text format (height-map grids and point lists, transients and validation CSVs)
//! checks the whole text with [`check_lines`] before it splits a line (a grid that is one 300 MB
//! line of commas is refused before a cell is allocated), refuses a cell longer than
//! [`MAX_CELL_BYTES`] before parsing it, and quotes input in its errors only through [`excerpt`]:
//! at most [`EXCERPT_CHARS`] characters, control and formatting characters replaced by `?`, so an
//! error never echoes a whole line of a file that is not the format's (`/etc/passwd`) and a 1 MB
//! header line does not come back as a 1 MB message.

use std::fmt;

use crate::QuantityError;

/// Longest line of a text input: 1 MiB (a 4096-column grid of 25-character numbers is 100 kB).
pub const MAX_LINE_BYTES: usize = 1 << 20;

/// Longest cell (one number, one header value) of a text input: 256 bytes.
pub const MAX_CELL_BYTES: usize = 256;

/// Most characters of an input that an error quotes.
pub const EXCERPT_CHARS: usize = 20;

/// A short, sanitised quotation of input text for an error message: the first
/// [`EXCERPT_CHARS`] characters in backticks, `…` and the length in bytes when there is more;
/// characters that are not printable (controls, bidirectional overrides, other format characters)
/// and backticks become `?`.
pub fn excerpt(text: &str) -> String {
    let mut out = String::with_capacity(EXCERPT_CHARS + 16);
    out.push('`');
    let mut chars = text.chars();
    for c in chars.by_ref().take(EXCERPT_CHARS) {
        let keep = c == ' ' || (c.is_ascii_graphic() && c != '`') || (!c.is_ascii() && c.is_alphanumeric());
        out.push(if keep { c } else { '?' });
    }
    out.push('`');
    if chars.next().is_some() {
        out.insert(out.len() - 1, '…');
        out.push_str(&format!(" ({} bytes)", text.len()));
    }
    out
}

/// A text input has a line longer than its limit.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LineTooLong {
    /// 1-based line.
    pub line: u64,
    /// Its length, bytes (counted up to the limit plus one when longer).
    pub length_bytes: usize,
    /// The limit, bytes.
    pub limit_bytes: usize,
}

impl fmt::Display for LineTooLong {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "line {} is {} bytes long, more than the limit of {} bytes for a line of this input",
            self.line, self.length_bytes, self.limit_bytes
        )
    }
}

impl std::error::Error for LineTooLong {}

/// Longest error message a front end prints, characters: a message is a sentence or three; one
/// that quotes a whole argument or prints numbers in full decimal is cut here.
pub const MAX_MESSAGE_CHARS: usize = 1000;

/// `message` cut to at most [`MAX_MESSAGE_CHARS`] characters (control characters but newlines
/// and tabs shown as `?`), with the length of what was left out: the edge's guarantee that no
/// error floods a terminal or a log whatever a layer below quoted.
pub fn bounded_message(message: &str) -> String {
    let clean = |c: char| if c.is_control() && c != '\n' && c != '\t' { '?' } else { c };
    let total = message.chars().count();
    if total <= MAX_MESSAGE_CHARS {
        return message.chars().map(clean).collect();
    }
    let kept: String = message.chars().take(MAX_MESSAGE_CHARS - 60).map(clean).collect();
    format!("{kept}… (message cut: {total} characters)")
}

/// Checks that no line of `text` (split at `\n`, a `\r` before it counted) is longer than
/// `limit_bytes`; one pass, no allocation.
pub fn check_lines(text: &str, limit_bytes: usize) -> Result<(), LineTooLong> {
    check_line_bytes(text.as_bytes(), limit_bytes)
}

/// [`check_lines`] for bytes (a binary format's text header).
pub fn check_line_bytes(bytes: &[u8], limit_bytes: usize) -> Result<(), LineTooLong> {
    for (k, line) in bytes.split(|&b| b == b'\n').enumerate() {
        if line.len() > limit_bytes {
            return Err(LineTooLong { line: k as u64 + 1, length_bytes: line.len(), limit_bytes });
        }
    }
    Ok(())
}

/// Checks a cell's length against [`MAX_CELL_BYTES`]; the error says how long it is, without its
/// content beyond an [`excerpt`].
pub fn check_cell(cell: &str) -> Result<(), String> {
    if cell.len() > MAX_CELL_BYTES {
        Err(format!(
            "{} is {} bytes long, more than the limit of {MAX_CELL_BYTES} bytes for one value",
            excerpt(cell),
            cell.len()
        ))
    } else {
        Ok(())
    }
}

impl QuantityError {
    /// The error with the input quoted only through [`excerpt`] (the value and the problem, which
    /// can quote a piece of the value, are shortened): for messages about file contents.
    pub fn brief(&self) -> String {
        let problem = if self.problem.chars().count() > 3 * EXCERPT_CHARS {
            excerpt(&self.problem)
        } else {
            excerpt(&self.problem).trim_matches('`').to_string()
        };
        format!("{}: {problem}; expected {}", excerpt(&self.value), self.expected)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpts_are_short_and_printable() {
        assert_eq!(excerpt("1.5e-9"), "`1.5e-9`");
        let line = "root:x:0:0:root:/root:/bin/bash";
        let e = excerpt(line);
        assert!(!e.contains(line) && e.starts_with("`root:x:0:0:root:/roo…`"), "{e}");
        assert!(e.ends_with("(31 bytes)"), "{e}");
        assert_eq!(excerpt("a\u{1b}[2Jb\u{202e}c`"), "`a?[2Jb?c?`");
        assert_eq!(excerpt("5 µm"), "`5 µm`");
        let long = "x".repeat(1 << 20);
        assert!(excerpt(&long).len() < 60);
    }

    #[test]
    fn long_lines_are_found_without_allocating() {
        assert_eq!(check_lines("a\nbb\r\nccc", 3), Ok(()));
        assert_eq!(check_lines("a\nbb\r\ncccc", 3), Err(LineTooLong { line: 3, length_bytes: 4, limit_bytes: 3 }));
        assert_eq!(check_lines("abc\r\n", 3).unwrap_err().line, 1);
        assert!(check_cell(&"1".repeat(MAX_CELL_BYTES)).is_ok());
        let e = check_cell(&"1".repeat(MAX_CELL_BYTES + 1)).unwrap_err();
        assert!(e.len() < 150 && e.contains("257 bytes"), "{e}");
    }

    #[test]
    fn brief_quantity_errors_quote_little() {
        let v = format!("1 {}", "furlong".repeat(1000));
        let e = crate::parse_quantity(&v, crate::Dimension::Length).unwrap_err();
        let b = e.brief();
        assert!(b.len() < 300, "{b}");
        assert!(b.contains("expected a length"), "{b}");
    }

    #[test]
    fn messages_are_bounded() {
        assert_eq!(bounded_message("at `x`: 1 m"), "at `x`: 1 m");
        let long = format!("value {}", "9".repeat(1_500_000));
        let b = bounded_message(&long);
        assert!(b.chars().count() <= MAX_MESSAGE_CHARS && b.ends_with("(message cut: 1500006 characters)"), "{b}");
        assert_eq!(bounded_message("a\u{1b}[31mb"), "a?[31mb");
    }
}
