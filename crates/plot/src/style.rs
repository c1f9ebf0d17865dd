//! One style for every figure: a series keeps its colour and marker by name.
//!
//! A series is looked up by its style key ([`crate::Series::key`]) or, without one, by its legend
//! name: the longest registry key that appears in the name as a whole word (`gw-dmt fit` ->
//! `gw-dmt`, `measured (mean, error bar: SD of repeats)` -> `measured`). A series that matches no
//! key takes the palette colour of its position, skipping the registry's colours. Series styled
//! as measured are drawn last, on top of the models.

use crate::canvas::Rgb;

/// Marker shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Marker {
    /// A filled circle.
    #[default]
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle pointing up.
    Triangle,
    /// A filled diamond.
    Diamond,
    /// A filled triangle pointing down.
    TriangleDown,
}

/// The colour and marker of a named series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Look {
    /// Line and marker colour.
    pub color: Rgb,
    /// Marker shape.
    pub marker: Marker,
    /// Drawn after (on top of) every other series.
    pub on_top: bool,
}

/// The registry: key, colour, marker, on top. Colours from the colour-blind-safe Okabe-Ito set.
pub const STYLES: &[(&str, Rgb, Marker, bool)] = &[
    ("measured", Rgb(0x00, 0x00, 0x00), Marker::Circle, true),
    ("data", Rgb(0x00, 0x00, 0x00), Marker::Circle, true),
    ("virtual meter", Rgb(0x00, 0x72, 0xb2), Marker::Square, false),
    ("virtual meters", Rgb(0x00, 0x72, 0xb2), Marker::Square, false),
    ("explicit", Rgb(0xd5, 0x5e, 0x00), Marker::Square, false),
    ("explicit-ensemble", Rgb(0xd5, 0x5e, 0x00), Marker::Square, false),
    ("gw", Rgb(0x00, 0x9e, 0x73), Marker::Triangle, false),
    ("gw-dmt", Rgb(0x56, 0xb4, 0xe9), Marker::Diamond, false),
    ("dmt", Rgb(0xcc, 0x79, 0xa7), Marker::TriangleDown, false),
    ("discrete", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("discrete-n", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("eq. 10", Rgb(0x59, 0x59, 0x59), Marker::Circle, false),
    ("eq. 12", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("bem", Rgb(0x00, 0x72, 0xb2), Marker::Circle, false),
];

/// Colours for series that match no registry key.
pub(crate) const PALETTE: [Rgb; 8] = [
    Rgb(0x1f, 0x77, 0xb4),
    Rgb(0xd6, 0x27, 0x28),
    Rgb(0x2c, 0xa0, 0x2c),
    Rgb(0xff, 0x7f, 0x0e),
    Rgb(0x94, 0x67, 0xbd),
    Rgb(0x8c, 0x56, 0x4b),
    Rgb(0xe3, 0x77, 0xc2),
    Rgb(0x17, 0xbe, 0xcf),
];

/// Whether `key` appears in `name` as a whole word (not inside a longer word).
fn has_word(name: &str, key: &str) -> bool {
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '-');
    name.match_indices(key)
        .any(|(i, _)| !word(name[..i].chars().next_back()) && !word(name[i + key.len()..].chars().next()))
}

/// The registered look of a series key or name (case-insensitive), if any.
pub fn look(name: &str) -> Option<Look> {
    let lower = name.to_lowercase();
    STYLES
        .iter()
        .filter(|(k, ..)| has_word(&lower, k))
        .max_by_key(|(k, ..)| k.len())
        .map(|&(_, color, marker, on_top)| Look { color, marker, on_top })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_name_keeps_its_look_and_longer_keys_win() {
        assert_eq!(look("gw-dmt").unwrap().color, Rgb(0x56, 0xb4, 0xe9));
        assert_eq!(look("GW fit").unwrap().color, Rgb(0x00, 0x9e, 0x73));
        assert_eq!(look("explicit: median").unwrap().color, look("explicit").unwrap().color);
        assert!(look("measured (mean, error bar: SD of repeats)").unwrap().on_top);
        assert!(look("unmeasured thing").is_none());
        assert!(look("4 contacts").is_none());
    }
}
