//! stiction-scenario
