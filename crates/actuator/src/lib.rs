//! stiction-actuator
