//! stiction-actuator: electrostatic gap-closing actuator arrays with suspension springs.
//!
//! * [`plates`]: capacitance and force of a plate array (parallel plate or Palmer fringing,
//!   optional back gap), force from the co-energy.
//! * [`cross_section`]: 2D finite-difference Laplace solve of the comb cross-section (thick
//!   fingers, neighbours, substrate) for `fringing: "cross_section"`.
//! * [`spring`]: suspension stiffness from a value or from beams.
//! * [`bending`]: optional finger bending.
//! * [`actuator`]: quasi-static equilibrium, pull-in, release, hysteresis, sweeps.
//! * [`dynamics`]: the slip event in time (rapier rigid body), dynamic pull-in for a step voltage.
//! * [`protocol`]: pull-in protocol (quasi-static ramp or voltage step), shuttle mass and air
//!   damping from geometry.
//! * [`parts`]: the other test structures' actuators: lateral comb drive (side instability),
//!   plate electrode to the substrate through dielectric layers, a spring set and released.
//! * [`transients`]: pull-in and release times point by point against measured times.
//!
//! SI units and `f64` everywhere.

pub mod actuator;
pub mod bending;
pub mod conversion;
pub mod cross_section;
pub mod dynamics;
pub mod error;
pub mod meter;
pub mod parts;
pub mod plates;
pub mod protocol;
pub mod spec;
pub mod spring;
pub mod transients;
pub mod validate;

pub use actuator::{Equilibrium, GapClosingActuator, Hysteresis, PullIn, Sweep, SweepPoint};
pub use bending::FingerBending;
pub use conversion::{PullInCalibration, calibrate_from_pull_in};
pub use cross_section::{CombGeometry, Substrate, SubstratePotential};
pub use dynamics::{
    SimulationScale, SlipDynamics, SlipTrajectory, dynamic_pull_in_voltage, dynamic_pull_in_voltage_with_damping_law,
    rectangular_squeeze_film_damping_n_s_per_m, simulate_force_law, simulate_slip, squeeze_film_aspect_factor,
    squeeze_number, undamped_dynamic_pull_in_voltage_v, veijola_effective_viscosity_pa_s,
};
pub use error::ActuatorError;
pub use meter::{ClampForce, SlipResponse, clamp_force, pull_force_stuck_n, slip_response};
pub use parts::{
    DielectricLayer, LateralComb, LateralCombSpec, PlateElectrode, PlateElectrodeSpec, ReleasedSpring,
    ReleasedSpringSpec, ResonanceSpec,
};
pub use plates::{BackElectrode, BackPotential, Fringing, PlateArray, VACUUM_PERMITTIVITY};
pub use protocol::{MassBreakdown, PullInProtocol, Shuttle, ShuttleSpec, StepPullIn, step_pull_in};
pub use spec::{
    ArraySpec, BeamsSpec, CalibrationGeometry, CombSpec, FingerBendingSpec, SpringSpec, StopSpec, SubstrateSpec,
};
pub use spring::{BeamKind, BeamSuspension, Suspension};
pub use transients::{
    MAX_EXTERNAL_FORCE_N, MAX_FINGER_LENGTH_UM, MAX_TRANSIENT_TIME_US, MAX_TRANSIENT_VOLTAGE_V, MEASURED_MIN_FRACTION,
    MeasuredTransient, ReleaseKick, TransientComparison, TransientErrors, TransientEvent, TransientModel,
    TransientPhysics, TransientReport, TransientSwitchEffect, compare_transients, parse_transients, read_transients,
    transient_switch_effects,
};
pub use validate::{
    MAX_VALIDATION_FILE_BYTES, MeasuredPoint, SwitchEffect, ValidationPoint, ValidationReport,
    fit_stop_contact_standoff, parse_measurements, read_measurements, switch_effects, validate,
};
