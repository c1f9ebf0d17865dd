//! Short quotes of a user's text in messages.

/// `text` cut to at most `max` characters, with "..." when cut: errors quote at most a short piece
/// of a user's file.
pub fn truncate(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        Some((i, _)) => format!("{}...", &text[..i]),
        None => text.to_string(),
    }
}
