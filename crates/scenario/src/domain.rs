//! The physical domain of every quantity a scenario, a flag or a Python argument takes: one table,
//! one check, for the file, `--set`, the command-line flags and Python alike.
//!
//! Each [`Domain`] gives a hard range (outside it the input is refused: the models are not valid
//! there, or the number cannot describe a MEMS device) and a usual range (outside it the input is
//! run, with a warning `unusual_value` that names the field, the value and the range). The reason
//! is part of the table and of every message. A typed scenario is checked by walking its
//! serialisation (SI numbers, the file's own key paths), so a field that the table does not cover
//! is found by a test over the JSON Schema (`every_quantity_of_the_schema_has_a_domain`).
//!
//! Cross-field rules that a single range cannot state (a Kelvin radius below the shoe) are in
//! [`crate::Scenario`]'s validation beside the call of [`check_tree`].

use serde_json::Value;

use crate::warning::Warning;

/// Highest voltage a scenario may apply (clamp voltages, `pull_voltage_max`), V: far above the
/// breakdown of any micrometre air gap (a few hundred volts), and low enough that V^2 and the
/// forces stay finite in f64. A limit of the physics, not raisable.
pub const MAX_VOLTAGE_V: f64 = 1e4;

/// The physical domain of one quantity (SI units).
#[derive(Debug, Clone, Copy)]
pub struct Domain {
    /// The key paths it applies to: dotted, `*` stands for one segment (an actuator array's name),
    /// `[]` for any list index.
    pub paths: &'static [&'static str],
    /// The SI unit the bounds are in, for messages ("" for a pure number).
    pub unit: &'static str,
    /// Smallest value; `min_inclusive` says whether it is allowed.
    pub min: f64,
    /// Whether `min` itself is in the domain.
    pub min_inclusive: bool,
    /// Largest value; `max_inclusive` says whether it is allowed.
    pub max: f64,
    /// Whether `max` itself is in the domain.
    pub max_inclusive: bool,
    /// Usual range: outside it (but inside `min..max`) the value runs with a warning.
    pub usual: (f64, f64),
    /// Why these bounds: the validity of the models or what a MEMS device can be.
    pub reason: &'static str,
}

/// A value outside its domain: the field, the value and the domain with its reason.
#[derive(Debug, Clone, PartialEq)]
pub struct OutsideDomain {
    /// The key path (or flag) as the user wrote it.
    pub field: String,
    /// The message: value, domain, reason.
    pub message: String,
}

impl std::fmt::Display for OutsideDomain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

impl std::error::Error for OutsideDomain {}

const fn d(
    paths: &'static [&'static str],
    unit: &'static str,
    min: f64,
    min_inclusive: bool,
    max: f64,
    usual: (f64, f64),
    reason: &'static str,
) -> Domain {
    Domain { paths, unit, min, min_inclusive, max, max_inclusive: true, usual, reason }
}

/// A length of the device's geometry in metres, up to `max` (m).
const GAPS: &str = "a gap, travel or width of a MEMS structure: nanometres to a millimetre";
const SIZES: &str = "a length of a MEMS structure: up to a centimetre (a die)";
const E_REASON: &str = "Young's modulus: 0.1 MPa (a soft elastomer) to 1.2 TPa (diamond, the stiffest solid)";

/// The table: every quantity field of the scenario format (and the flags that take the same
/// quantity name one of these paths).
pub static DOMAINS: &[Domain] = &[
    // --- surface ---
    d(
        &["surface.summit_radius", "surface.counter_face.summit_radius"],
        "m",
        0.0,
        false,
        1e-3,
        (1e-9, 100e-6),
        "a summit radius of a MEMS face: nanometres to micrometres; above 1 mm a summit is larger than the \
         device, and Hertz/DMT contact areas grow past the apparent area",
    ),
    d(
        &["surface.radius_sd", "surface.counter_face.radius_sd"],
        "m",
        0.0,
        true,
        1e-3,
        (0.0, 100e-6),
        "the spread of summit radii, below the largest summit radius (1 mm)",
    ),
    d(
        &["surface.summit_sd", "surface.counter_face.summit_sd"],
        "m",
        0.0,
        true,
        100e-6,
        (0.0, 1e-6),
        "the standard deviation of summit heights: a sidewall's roughness is nanometres; above 100 um it is \
         taller than a MEMS structure",
    ),
    d(
        &["surface.summit_density", "surface.counter_face.summit_density"],
        "m^-2",
        0.0,
        false,
        1e18,
        (1e8, 1e16),
        "summits per area: at most one per square nanometre (an atomic spacing)",
    ),
    d(
        &["surface.apparent_length", "surface.apparent_width"],
        "m",
        0.0,
        false,
        0.1,
        (100e-9, 10e-3),
        "the apparent contact (shoe) size: from a nanoscale tip to millimetre flats; 10 cm is no MEMS contact",
    ),
    d(
        &["surface.pair_reach"],
        "m",
        0.0,
        false,
        1e-3,
        (0.0, 10e-6),
        "how far apart two summits of two faces may be to meet: below the largest summit radius",
    ),
    d(
        &[
            "surface.height_map.pixel_size",
            "surface.height_map.pixel_size_y",
            "surface.counter_height_map.pixel_size",
            "surface.counter_height_map.pixel_size_y",
            "surface.height_map.generated.pixel_size",
            "surface.counter_height_map.generated.pixel_size",
        ],
        "m",
        1e-12,
        true,
        1.0,
        (1e-10, 1e-5),
        "the pixel size of a height map: 1 pm to 1 m (slopes and curvatures divide by it)",
    ),
    d(
        &[
            "surface.height_map.patch_x",
            "surface.height_map.patch_y",
            "surface.counter_height_map.patch_x",
            "surface.counter_height_map.patch_y",
            "surface.height_map.short_cutoff",
            "surface.height_map.long_cutoff",
            "surface.counter_height_map.short_cutoff",
            "surface.counter_height_map.long_cutoff",
            "surface.height_map.generated.correlation_length",
            "surface.counter_height_map.generated.correlation_length",
            "surface.height_map.generated.long_cutoff_wavelength",
            "surface.counter_height_map.generated.long_cutoff_wavelength",
            "surface.height_map.generated.rolloff_wavelength",
            "surface.counter_height_map.generated.rolloff_wavelength",
            "surface.height_map.generated.short_cutoff_wavelength",
            "surface.counter_height_map.generated.short_cutoff_wavelength",
        ],
        "m",
        0.0,
        true,
        1.0,
        (0.0, 10e-3),
        "an offset, cut-off or wavelength on a height map: below 1 m (the map itself is smaller)",
    ),
    d(
        &["surface.height_map.generated.rms_height", "surface.counter_height_map.generated.rms_height"],
        "m",
        0.0,
        false,
        100e-6,
        (1e-10, 1e-6),
        "the rms height of a generated wall: nanometres; above 100 um it is taller than a MEMS structure",
    ),
    d(
        &["surface.height_map.generated.hurst", "surface.counter_height_map.generated.hurst"],
        "",
        0.0,
        false,
        1.0,
        (0.3, 1.0),
        "the Hurst exponent of a self-affine surface lies in (0, 1]",
    ),
    // --- material ---
    d(
        &["material.compliance"],
        "1/Pa",
        1e-13,
        true,
        1e-5,
        (1e-13, 1e-9),
        "the composite compliance D = (3/4)(1 - nu^2)/E summed over both faces: E from 0.1 MPa (an \
         elastomer) to 1.2 TPa (diamond)",
    ),
    d(&["material.youngs_modulus"], "Pa", 1e5, true, 1.2e12, (1e9, 1.2e12), E_REASON),
    Domain {
        paths: &["material.poisson_ratio", "actuators.*.spring.beams.poisson_ratio"],
        unit: "",
        min: -1.0,
        min_inclusive: false,
        max: 0.5,
        max_inclusive: true,
        usual: (0.0, 0.5),
        reason: "Poisson's ratio of an isotropic elastic solid lies in (-1, 0.5]",
    },
    d(
        &["material.work_of_adhesion"],
        "J/m^2",
        0.0,
        true,
        10.0,
        (0.0, 2.5),
        "the work of adhesion 2 gamma of two faces: at most twice the surface energy of the most cohesive \
         solids (a few J/m^2); clean silicon in vacuum is about 2.4 J/m^2, the paper's 0.1 J/m^2",
    ),
    d(
        &["material.shear_strength"],
        "Pa",
        0.0,
        false,
        1e11,
        (1e5, 2e10),
        "an interfacial shear strength: at most the theoretical shear strength of the stiffest solids (about \
         G/(2 pi), 1e11 Pa for diamond)",
    ),
    d(
        &["material.hardness"],
        "Pa",
        0.0,
        false,
        1.5e11,
        (1e7, 1.2e11),
        "an indentation hardness: at most that of diamond (about 1.2e11 Pa)",
    ),
    d(
        &["material.equilibrium_spacing"],
        "m",
        0.0,
        false,
        10e-9,
        (0.1e-9, 1e-9),
        "the equilibrium spacing of surface forces: an interatomic distance, about 0.3 nm",
    ),
    d(
        &["material.contact_angle", "material.counter_face_contact_angle"],
        "rad",
        0.0,
        true,
        std::f64::consts::PI,
        (0.0, std::f64::consts::PI),
        "a contact angle lies between 0 and 180 deg",
    ),
    // --- environment ---
    Domain {
        paths: &["environment.relative_humidity"],
        unit: "",
        min: 0.0,
        min_inclusive: true,
        max: 1.0,
        max_inclusive: false,
        usual: (0.0, 0.95),
        reason: "a relative humidity (for another liquid its relative vapour pressure p/p_sat) is a \
                 fraction in [0, 1) (or a percentage); at saturation the Kelvin radius is infinite and the gap floods",
    },
    Domain {
        paths: &["environment.temperature"],
        unit: "K",
        min: stiction_contact::capillary::WATER_TRIPLE_POINT_K,
        min_inclusive: true,
        max: stiction_contact::capillary::WATER_CRITICAL_TEMPERATURE_K,
        max_inclusive: false,
        usual: (273.16, 373.15),
        reason: "the water correlations (IAPWS surface tension and saturated-liquid density) hold from the \
                 triple point (273.16 K, 0.01 C) to the critical point (647.096 K); a bare number is kelvin",
    },
    d(
        &["environment.liquid.surface_tension"],
        "N/m",
        0.0,
        false,
        1.0,
        (0.015, 0.08),
        "the surface tension of a liquid against its vapour: from about 10 mN/m (fluorocarbons) to 72 mN/m \
         (water) and 0.49 N/m (mercury)",
    ),
    d(
        &["environment.liquid.molar_volume"],
        "m^3/mol",
        0.0,
        false,
        1e-3,
        (1.5e-5, 3e-4),
        "the molar volume of a liquid: from 14.8 cm^3/mol (mercury) and 18 cm^3/mol (water) to a few hundred \
         cm^3/mol (long alcohols and alkanes)",
    ),
    d(
        &["environment.liquid.saturation_pressure"],
        "Pa",
        0.0,
        false,
        1e7,
        (1.0, 1.1e5),
        "the saturation vapour pressure of a liquid at the temperature: above 0, and below the critical \
         pressures of common liquids (about 10 MPa); a liquid that condenses at room temperature has a few Pa to \
         one atmosphere",
    ),
    d(
        &["environment.liquid.contact_angle", "environment.liquid.counter_face_contact_angle"],
        "rad",
        0.0,
        true,
        std::f64::consts::PI,
        (0.0, std::f64::consts::PI),
        "a contact angle lies between 0 and 180 deg",
    ),
    d(
        &["environment.min_kelvin_radius"],
        "m",
        0.0,
        false,
        1e-6,
        (0.1e-9, 10e-9),
        "the smallest Kelvin radius at which a meniscus condenses: a molecular size (0.28 nm for water)",
    ),
    // --- contact ---
    d(
        &["contact.bem.pixel_size"],
        "m",
        1e-12,
        true,
        1e-3,
        (1e-10, 1e-6),
        "the grid spacing of the boundary-element model",
    ),
    d(
        &["contact.bem.range"],
        "m",
        0.0,
        false,
        1e-6,
        (0.1e-9, 100e-9),
        "the Dugdale range of the adhesive stress: a few equilibrium spacings, at most a micrometre",
    ),
    d(
        &["contact.bem.tolerance"],
        "",
        0.0,
        false,
        0.1,
        (1e-12, 1e-3),
        "the relative tolerance of the boundary-element solver: below 0.1, or the result is not converged",
    ),
    // --- actuators ---
    d(
        &[
            "actuators.*.front_gap",
            "actuators.*.back_gap",
            "actuators.*.operating_travel",
            "actuators.*.undercut",
            "actuators.*.stop.travel",
            "actuators.*.stop.contact_standoff",
            "actuators.*.comb.electrode_width",
            "actuators.*.comb.finger_width",
            "actuators.*.comb.substrate.gap",
            "actuators.*.finger_bending.width",
            "actuators.*.shuttle.finger_width",
            "actuators.*.shuttle.spine_hole_size",
            "actuators.*.shuttle.spine_width",
            "actuators.*.shuttle.substrate_gap",
            "actuators.*.spring.beams.width",
            "meter.contact_travel",
        ],
        "m",
        0.0,
        true,
        1e-3,
        (0.0, 100e-6),
        GAPS,
    ),
    d(
        &["actuators.*.thickness", "actuators.*.calibrated_on.thickness", "actuators.*.spring.beams.thickness"],
        "m",
        0.0,
        false,
        1e-3,
        (100e-9, 100e-6),
        "the thickness of a MEMS structural layer: at most a wafer (1 mm)",
    ),
    d(
        &[
            "actuators.*.overlap_length",
            "actuators.*.calibrated_on.overlap_length",
            "actuators.*.finger_bending.root_length",
            "actuators.*.shuttle.extra_area",
            "actuators.*.shuttle.finger_root_length",
            "actuators.*.shuttle.spine_length",
            "actuators.*.spring.beams.length",
        ],
        "m",
        0.0,
        true,
        10e-3,
        (0.0, 5e-3),
        SIZES,
    ),
    d(
        &["actuators.*.shuttle.mean_free_path"],
        "m",
        0.0,
        true,
        1e-3,
        (1e-9, 1e-6),
        "the mean free path of the gas (68 nm in air at 1 bar)",
    ),
    d(
        &["actuators.*.conversion_factor"],
        "N/V^2",
        0.0,
        false,
        1.0,
        (1e-14, 1e-5),
        "an actuator conversion factor F/V^2: the paper's arrays give about 1e-8 N/V^2; 1 N/V^2 is no MEMS array",
    ),
    d(
        &["actuators.*.relative_permittivity"],
        "",
        1.0,
        true,
        1e4,
        (1.0, 100.0),
        "a relative permittivity is at least 1 (vacuum); 1 for air",
    ),
    d(
        &["actuators.*.finger_bending.youngs_modulus", "actuators.*.spring.beams.youngs_modulus"],
        "Pa",
        1e5,
        true,
        1.2e12,
        (1e9, 1.2e12),
        E_REASON,
    ),
    d(
        &["actuators.*.spring.stiffness", "actuators.*.spring.series_stiffness"],
        "N/m",
        0.0,
        false,
        1e6,
        (1e-3, 1e4),
        "a MEMS suspension's stiffness: millinewtons to kilonewtons per metre",
    ),
    d(
        &["actuators.*.spring.parallel_stiffness"],
        "N/m",
        0.0,
        true,
        1e6,
        (0.0, 1e4),
        "a MEMS suspension's stiffness: millinewtons to kilonewtons per metre",
    ),
    d(
        &["actuators.*.shuttle.density"],
        "kg/m^3",
        0.0,
        false,
        3e4,
        (1e3, 2.3e4),
        "a solid's density: at most that of osmium (22 600 kg/m^3); polysilicon is 2330 kg/m^3",
    ),
    d(
        &["actuators.*.shuttle.viscosity"],
        "Pa s",
        0.0,
        false,
        1.0,
        (1e-6, 1e-3),
        "the gas viscosity around the shuttle (air: 1.8e-5 Pa s)",
    ),
    // --- meter ---
    d(
        &["meter.spring_force"],
        "N",
        0.0,
        true,
        1.0,
        (0.0, 1e-3),
        "the spring force a MEMS suspension holds the shoe off the wall with: micronewtons (the paper: 7 uN)",
    ),
    d(
        &["meter.clamp_voltages[]", "meter.clamp_voltages.from", "meter.clamp_voltages.to", "meter.pull_voltage_max"],
        "V",
        0.0,
        true,
        MAX_VOLTAGE_V,
        (0.0, 500.0),
        "a voltage across a micrometre gap: above a few hundred volts the gap breaks down; 10 kV keeps V^2 finite",
    ),
    d(
        &["meter.pull_voltage_step"],
        "V",
        0.0,
        false,
        MAX_VOLTAGE_V,
        (1e-4, 10.0),
        "the step of the pull ramp, below pull_voltage_max",
    ),
    d(
        &["meter.slip.alpha"],
        "",
        0.0,
        true,
        10.0,
        (0.0, 1.0),
        "the pressure coefficient of the shear strength: a friction coefficient of the interface, below 10",
    ),
    d(
        &["meter.slip_dynamics.shuttle_mass"],
        "kg",
        0.0,
        false,
        1e-3,
        (1e-15, 1e-6),
        "the moving mass of a MEMS shuttle: nanograms (the paper's: 107 ng); 1 g is no MEMS part",
    ),
    d(
        &["meter.slip_dynamics.damping"],
        "N s/m",
        0.0,
        true,
        1.0,
        (0.0, 1e-3),
        "the air damping of a MEMS shuttle: micro-newton-seconds per metre",
    ),
    d(
        &["meter.slip_dynamics.kinetic_friction_coefficient"],
        "",
        0.0,
        true,
        10.0,
        (0.0, 5.0),
        "a kinetic friction coefficient: measured MEMS values lie between 0.1 and 5",
    ),
    // --- structure (test structures built from parts) ---
    d(
        &[
            "structure.normal.comb.gap",
            "structure.normal.comb.engagement",
            "structure.normal.contact_travel",
            "structure.normal.air_gap_at_contact",
            "structure.normal.travel_to_contact",
            "structure.tangential.gap",
            "structure.tangential.engagement",
        ],
        "m",
        0.0,
        true,
        1e-3,
        (0.0, 100e-6),
        GAPS,
    ),
    d(
        &["structure.normal.comb.thickness", "structure.tangential.thickness"],
        "m",
        0.0,
        false,
        1e-3,
        (100e-9, 100e-6),
        "the thickness of a MEMS structural layer: at most a wafer (1 mm)",
    ),
    d(
        &["structure.normal.dielectric[].thickness"],
        "m",
        0.0,
        false,
        1e-4,
        (1e-9, 5e-6),
        "a dielectric film on an electrode (nitride, oxide): nanometres to micrometres",
    ),
    d(
        &["structure.normal.dielectric[].relative_permittivity"],
        "",
        1.0,
        true,
        1e4,
        (1.0, 100.0),
        "a relative permittivity is at least 1 (vacuum); silicon nitride about 7.5, silicon dioxide 3.9",
    ),
    d(
        &[
            "actuators.*.plate_count",
            "actuators.*.calibrated_on.plate_count",
            "structure.normal.comb.finger_count",
            "structure.tangential.finger_count",
        ],
        "",
        1.0,
        true,
        1e5,
        (2.0, 2000.0),
        "a count of gap-closing plates or comb fingers: a MEMS array has a few to a few thousand; 1e5 is past any die",
    ),
    d(
        &["structure.normal.electrode_area"],
        "m^2",
        0.0,
        false,
        1e-4,
        (1e-12, 1e-6),
        "the electrode area under a MEMS plate or pad: at most a square centimetre (a die)",
    ),
    d(
        &["structure.normal.comb.fringing_factor", "structure.tangential.fringing_factor"],
        "",
        1.0,
        true,
        10.0,
        (1.0, 2.0),
        "the comb's fringing factor on the parallel-plate drive force: at least 1; finite-element comb drives give \
         1.1 to 1.5",
    ),
    d(
        &[
            "structure.normal.comb.stiffness",
            "structure.normal.comb.lateral_stiffness",
            "structure.tangential.stiffness",
            "structure.tangential.lateral_stiffness",
        ],
        "N/m",
        0.0,
        false,
        1e6,
        (1e-3, 1e4),
        "a MEMS suspension's stiffness: millinewtons to kilonewtons per metre",
    ),
    d(
        &["structure.normal.stiffness"],
        "N/m",
        0.0,
        true,
        1e6,
        (0.0, 1e4),
        "a MEMS suspension's stiffness (0: the plate rests on the substrate already)",
    ),
    d(
        &["structure.tangential.resonance.frequency"],
        "Hz",
        0.0,
        false,
        1e9,
        (10.0, 1e7),
        "a MEMS resonance: tens of hertz to megahertz",
    ),
    d(
        &["structure.tangential.resonance.mass"],
        "kg",
        0.0,
        false,
        1e-3,
        (1e-15, 1e-6),
        "the moving mass of a MEMS structure: nanograms; 1 g is no MEMS part",
    ),
    d(
        &["structure.geometry.radius"],
        "m",
        0.0,
        false,
        1e-3,
        (10e-9, 100e-6),
        "a dimple tip radius: tens of nanometres to micrometres",
    ),
    d(
        &[
            "structure.normal_voltages[]",
            "structure.normal_voltages.from",
            "structure.normal_voltages.to",
            "structure.protocol.tangential_voltages[]",
            "structure.protocol.tangential_voltages.from",
            "structure.protocol.tangential_voltages.to",
            "structure.protocol.voltage_max",
        ],
        "V",
        0.0,
        true,
        MAX_VOLTAGE_V,
        (0.0, 500.0),
        "a voltage across a micrometre gap: above a few hundred volts the gap breaks down; 10 kV keeps V^2 finite",
    ),
    d(
        &["structure.protocol.voltage_step"],
        "V",
        0.0,
        false,
        MAX_VOLTAGE_V,
        (1e-4, 10.0),
        "the step of the tangential ramp, below voltage_max",
    ),
    d(
        &["structure.protocol.displacement_step", "structure.protocol.displacement_max"],
        "m",
        0.0,
        false,
        1e-3,
        (1e-9, 100e-6),
        "a displacement a MEMS suspension is set to: nanometres to a hundred micrometres",
    ),
    d(
        &["structure.slip.alpha"],
        "",
        0.0,
        true,
        10.0,
        (0.0, 1.0),
        "the pressure coefficient of the shear strength: a friction coefficient of the interface, below 10",
    ),
    d(
        &["structure.lab_reduction.adhesion_force", "meter.lab_reduction.adhesion_force"],
        "N",
        0.0,
        true,
        1.0,
        (0.0, 1e-3),
        "an adhesion force a lab measured on a MEMS contact: nanonewtons to micronewtons",
    ),
    // --- loads given directly (flags and Python arguments, not a scenario field) ---
    Domain {
        paths: &["load"],
        unit: "N",
        min: -1.0,
        min_inclusive: true,
        max: 1.0,
        max_inclusive: true,
        usual: (-1e-3, 1e-3),
        reason: "a normal load on a MEMS contact: micronewtons to millinewtons; beyond a newton no MEMS actuator pushes",
    },
    // --- reference ---
    d(
        &["reference.mu_apparent", "reference.mu_apparent_uncertainty"],
        "",
        0.0,
        true,
        100.0,
        (0.0, 10.0),
        "a measured friction coefficient: the published MEMS values lie between 0.1 and 5",
    ),
];

/// Whether the pattern `pattern` (dotted, `*` one segment) matches `path` (dotted, list indices
/// written `[]`).
fn matches(pattern: &str, path: &str) -> bool {
    let (mut p, mut q) = (pattern.split('.'), path.split('.'));
    loop {
        match (p.next(), q.next()) {
            (None, None) => return true,
            (Some(a), Some(b)) if a == "*" || a == b => {}
            (Some(a), Some(b)) if a.starts_with("*[") && b.ends_with(&a[1..]) => {}
            _ => return false,
        }
    }
}

/// The domain of the quantity at `path` (dotted; list indices as `[]`), if the table has one.
pub fn lookup(path: &str) -> Option<&'static Domain> {
    DOMAINS.iter().find(|d| d.paths.iter().any(|p| matches(p, path)))
}

/// A number short enough for a message, at most four significant digits: `0.001`, `2.361`,
/// `9.1e-12`, `2.362e6`, `5e-324`.
pub fn short(v: f64) -> String {
    let plain = format!("{v}");
    if v == 0.0 || !v.is_finite() || (plain.len() <= 8 && v.abs() >= 1e-3) {
        return plain;
    }
    if (1e-3..1e6).contains(&v.abs()) {
        let decimals = (3 - v.abs().log10().floor() as i32).max(0) as usize;
        let fixed = format!("{v:.decimals$}");
        return if fixed.contains('.') { fixed.trim_end_matches('0').trim_end_matches('.').to_string() } else { fixed };
    }
    let exact = format!("{v:e}");
    if exact.len() <= 10 {
        return exact;
    }
    let rounded = format!("{v:.3e}");
    match rounded.split_once('e') {
        Some((m, x)) => format!("{}e{x}", m.trim_end_matches('0').trim_end_matches('.')),
        None => rounded,
    }
}

fn with_unit(v: f64, unit: &str) -> String {
    match unit {
        "" => short(v),
        "rad" => format!("{} rad ({} deg)", short(v), short(v.to_degrees())),
        _ => format!("{} {unit}", short(v)),
    }
}

impl Domain {
    /// The domain as text: `(0, 0.001] m`.
    pub fn range_text(&self) -> String {
        format!(
            "{}{}, {}{}{}",
            if self.min_inclusive { "[" } else { "(" },
            short(self.min),
            short(self.max),
            if self.max_inclusive { "]" } else { ")" },
            if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) }
        )
    }

    /// Whether `v` lies in the hard range.
    pub fn contains(&self, v: f64) -> bool {
        v.is_finite()
            && (if self.min_inclusive { v >= self.min } else { v > self.min })
            && (if self.max_inclusive { v <= self.max } else { v < self.max })
    }

    /// Checks `v` of the field named `field` (a key path or a flag): `Err` outside the hard range,
    /// `Ok(Some(warning))` outside the usual range, `Ok(None)` inside it.
    pub fn check(&self, field: &str, v: f64) -> Result<Option<Warning>, OutsideDomain> {
        if !self.contains(v) {
            return Err(OutsideDomain {
                field: field.to_string(),
                message: format!(
                    "{} is outside the physical domain {}: {}",
                    with_unit(v, self.unit),
                    self.range_text(),
                    self.reason
                ),
            });
        }
        if v < self.usual.0 || v > self.usual.1 {
            return Ok(Some(Warning::new(
                "unusual_value",
                format!(
                    "`{field}` = {} is outside the usual range [{}, {}]{}: it runs, but check it ({})",
                    with_unit(v, self.unit),
                    short(self.usual.0),
                    short(self.usual.1),
                    if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) },
                    self.reason
                ),
            )));
        }
        Ok(None)
    }
}

/// The table as Markdown (`stiction scenario --domains`; docs/reliability.md holds the same text,
/// checked by a test): one row per domain, its fields, range, usual range and reason.
pub fn markdown_table() -> String {
    let mut out = String::from("| fields | domain | usual range | why |\n|---|---|---|---|\n");
    for d in DOMAINS {
        let fields: Vec<String> = d.paths.iter().map(|p| format!("`{p}`")).collect();
        let unit = if d.unit.is_empty() { String::new() } else { format!(" {}", d.unit) };
        out.push_str(&format!(
            "| {} | {} | [{}, {}]{unit} | {} |\n",
            fields.join(", "),
            d.range_text(),
            short(d.usual.0),
            short(d.usual.1),
            d.reason
        ));
    }
    out
}

/// Checks the value of a flag or argument `field` against the domain of the scenario quantity
/// `path` (e.g. `gw --work-of-adhesion` against `material.work_of_adhesion`); a `path` without a
/// domain is accepted.
pub fn check_value(path: &str, field: &str, v: f64) -> Result<Option<Warning>, OutsideDomain> {
    match lookup(path) {
        Some(d) => d.check(field, v),
        None => Ok(None),
    }
}

/// Checks every number of `tree` (a typed scenario serialised: SI numbers under the file's key
/// paths) against its domain; the warnings of values outside their usual range come back. `Err`
/// names the first value outside its domain by its key path.
pub fn check_tree(tree: &Value) -> Result<Vec<Warning>, OutsideDomain> {
    let mut warnings = Vec::new();
    walk(tree, &mut String::new(), &mut String::new(), &mut warnings)?;
    Ok(warnings)
}

fn walk(v: &Value, path: &mut String, pattern: &mut String, warnings: &mut Vec<Warning>) -> Result<(), OutsideDomain> {
    match v {
        Value::Object(map) => {
            for (k, x) in map {
                let (pl, ql) = (path.len(), pattern.len());
                if !path.is_empty() {
                    path.push('.');
                    pattern.push('.');
                }
                path.push_str(k);
                pattern.push_str(k);
                walk(x, path, pattern, warnings)?;
                path.truncate(pl);
                pattern.truncate(ql);
            }
        }
        Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                let (pl, ql) = (path.len(), pattern.len());
                path.push_str(&format!("[{i}]"));
                pattern.push_str("[]");
                walk(x, path, pattern, warnings)?;
                path.truncate(pl);
                pattern.truncate(ql);
            }
        }
        Value::Number(n) => {
            if let (Some(x), Some(dom)) = (n.as_f64(), lookup(pattern))
                && let Some(w) = dom.check(path, x)?
            {
                warnings.push(w);
            }
        }
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_match_segments_and_list_indices() {
        assert!(matches("actuators.*.thickness", "actuators.clamp.thickness"));
        assert!(!matches("actuators.*.thickness", "actuators.clamp.shuttle.thickness"));
        assert!(matches("meter.clamp_voltages[]", "meter.clamp_voltages[]"));
        assert!(lookup("actuators.pull.front_gap").is_some());
        assert!(lookup("surface.seed").is_none());
        assert_eq!(short(1e-13), "1e-13");
        assert_eq!(short(0.001), "0.001");
        assert_eq!(short(2362e3 + 0.123), "2.362e6");
        assert_eq!(short(5e-324), "5e-324");
        assert_eq!(short(2.3609876), "2.361");
        assert_eq!(short(23.609876), "23.61");
        assert_eq!(short(0.0023609876), "0.002361");
    }

    /// The impossible inputs are refused naming the field, the value and the domain; the
    /// paper's values pass without a warning; an unusual one runs with a warning naming it.
    #[test]
    fn impossible_values_are_refused_and_unusual_ones_warned() {
        let e = check_value("surface.summit_radius", "surface.summit_radius", 1.0).unwrap_err();
        assert!(e.message.contains("1 m is outside the physical domain (0, 0.001] m"), "{e}");
        assert!(check_value("material.work_of_adhesion", "--work-of-adhesion", 1e30).is_err());
        let e = check_value("environment.temperature", "environment.temperature", 186.0).unwrap_err();
        assert!(e.message.contains("273.16"), "{e}");
        assert!(check_value("environment.relative_humidity", "x", 1.0).is_err());
        assert!(check_value("environment.relative_humidity", "x", 0.9999).unwrap().is_some());
        for (path, paper) in [
            ("surface.summit_radius", 0.5e-6),
            ("material.work_of_adhesion", 0.1),
            ("material.shear_strength", 1.4e9),
            ("material.compliance", 9.1e-12),
            ("environment.temperature", 298.15),
            ("actuators.clamp.thickness", 3e-6),
        ] {
            assert_eq!(check_value(path, path, paper), Ok(None), "{path}");
        }
        let w = check_value("material.work_of_adhesion", "material.work_of_adhesion", 5.0).unwrap().unwrap();
        assert!(w.code == "unusual_value" && w.message.contains("`material.work_of_adhesion` = 5 J/m^2"), "{w:?}");
        for d in DOMAINS {
            assert!(d.min < d.max && d.usual.0 <= d.usual.1, "{:?}", d.paths);
            assert!(d.contains(d.usual.0.max(d.min + (d.max - d.min) * 1e-9)) || !d.min_inclusive, "{:?}", d.paths);
        }
    }
}
