//! stiction-plot
