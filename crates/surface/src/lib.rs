//! stiction-surface
