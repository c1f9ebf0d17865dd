//! stiction-units
