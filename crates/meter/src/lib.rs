//! stiction-meter
