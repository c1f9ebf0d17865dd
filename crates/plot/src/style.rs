//! One style for every figure: a series keeps its colour and marker by name.
//!
//! A series is looked up by its style key ([`crate::Series::key`]) or, without one, by its legend
//! name: the registry key that appears first in the name as a whole word (`gw-dmt fit` ->
//! `gw-dmt`, `measured (mean, error bar: SD of repeats)` -> `measured`, `eq. 10 fit of the
//! measured points` -> `eq. 10`). A series that matches no
//! key takes the colour index it was given ([`crate::Series::with_color`]) or the next palette
//! colour. The registry wins over a colour index, so a model has one colour in every figure; to
//! pair a band or an unnamed line with a registered series, give it the same key
//! ([`crate::Series::keyed`]). Marker series styled as measured are drawn last, on top of the
//! models; two marker series that would look alike get different shapes.

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
    ("explicit-ensemble", Rgb(0x99, 0x33, 0x00), Marker::Square, false),
    ("gw", Rgb(0x00, 0x9e, 0x73), Marker::Triangle, false),
    ("gw-dmt", Rgb(0x56, 0xb4, 0xe9), Marker::Diamond, false),
    ("dmt", Rgb(0xcc, 0x79, 0xa7), Marker::TriangleDown, false),
    ("discrete", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("discrete-n", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("eq. 10", Rgb(0x59, 0x59, 0x59), Marker::Circle, false),
    ("eq. 12", Rgb(0xe6, 0x9f, 0x00), Marker::Diamond, false),
    ("bem", Rgb(0x00, 0x72, 0xb2), Marker::Circle, false),
];

/// Colours for series that match no registry key (a colour index or the next free one): chosen
/// apart from the registry's colours, so an unregistered curve is not mistaken for a model.
pub(crate) const PALETTE: [Rgb; 8] = [
    Rgb(0x7b, 0x32, 0x94),
    Rgb(0xd6, 0x27, 0x28),
    Rgb(0x17, 0xbe, 0xcf),
    Rgb(0xe7, 0x29, 0x8a),
    Rgb(0x9c, 0x9c, 0x00),
    Rgb(0x1f, 0x3a, 0x93),
    Rgb(0xa6, 0x76, 0x1d),
    Rgb(0x66, 0xa6, 0x1e),
];

/// Where `key` first appears in `name` as a whole word.
fn word_at(name: &str, key: &str) -> Option<usize> {
    let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '-');
    name.match_indices(key)
        .map(|(i, _)| i)
        .find(|&i| !word(name[..i].chars().next_back()) && !word(name[i + key.len()..].chars().next()))
}

/// The registered look of a series key or name (case-insensitive), if any: the key that appears
/// first in the name (`eq. 10 fit of the measured points` -> `eq. 10`), the longer of two at the
/// same place.
pub fn look(name: &str) -> Option<Look> {
    let lower = name.to_lowercase();
    STYLES
        .iter()
        .filter_map(|s| word_at(&lower, s.0).map(|i| (i, s)))
        .min_by_key(|(i, s)| (*i, std::cmp::Reverse(s.0.len())))
        .map(|(_, &(_, color, marker, on_top))| Look { color, marker, on_top })
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
        assert_eq!(look("eq. 10 fit of the measured points").unwrap().color, look("eq. 10").unwrap().color);
        assert_eq!(look("pull-in, measured (mean, SD of 3)").unwrap().color, look("measured").unwrap().color);
        assert_ne!(look("explicit-ensemble").unwrap().color, look("explicit").unwrap().color);
    }
}
