//! Checks of the 2D cross-section Laplace solver (`fringing: "cross_section"`) against closed
//! forms and limits. Each test names its source and tolerance.

use stiction_actuator::cross_section::{CellProblem, CombGeometry, capacitance_per_length, table};
use stiction_actuator::*;

const UM: f64 = 1e-6;

/// Force per unit length and volt squared on the finger, `1/2 dC'/dx`, central difference of
/// the 2D capacitance with the finger moved by `+/- d` (N/(V^2 m)).
fn line_force(t: f64, gf: f64, gb: Option<f64>, geo: CombGeometry, x: f64) -> f64 {
    let d = 0.002 * gf;
    let c = |xx: f64| {
        capacitance_per_length(&CellProblem {
            thickness_m: t,
            front_gap_m: gf - xx,
            back_gap_m: gb.map(|b| b + xx),
            geometry: geo,
            refinement: 1.0,
            grid_reference_gaps_m: Some((gf, gb)),
        })
        .unwrap()
    };
    0.5 * (c(x + d) - c(x - d)) / (2.0 * d)
}

#[test]
fn isolated_pair_matches_leus_elata_thick_plate_fringing() {
    // V. Leus, D. Elata, "Fringing field effect in electrostatic actuators", Technion report
    // ETR-2004-2 (2004): a plate of extent w (here the device thickness t) and thickness a (the
    // finger width, along the gap) at gap g: F/F_pp = 1 + g/(pi t) (1 + a/sqrt(a g + a^2)).
    // Thin plates (a -> 0) give Palmer's 1 + g/(pi t). Tolerance 0.3 % on F/F_pp (the formula
    // is itself a fit of field solutions to about that accuracy).
    let t = 40.0 * UM;
    for (a, g) in [(0.2 * UM, 2.0 * UM), (4.21 * UM, 5.63 * UM), (2.0 * UM, 1.0 * UM)] {
        let geo = CombGeometry { finger_width_m: a, electrode_width_m: a, substrate: None };
        let f = line_force(t, g, None, geo, 0.0);
        let f_pp = 0.5 * VACUUM_PERMITTIVITY * t / (g * g);
        let leus = 1.0 + g / (std::f64::consts::PI * t) * (1.0 + a / (a * g + a * a).sqrt());
        println!("a {:.2} um g {:.2} um: F/F_pp {:.5}, Leus-Elata {:.5}", a / UM, g / UM, f / f_pp, leus);
        assert!((f / f_pp - leus).abs() < 3e-3, "a {a:e} g {g:e}: {} vs {leus}", f / f_pp);
    }
}

#[test]
fn parallel_plate_limit_for_a_deep_narrow_gap() {
    // Gap 1 um in a 400 um thick layer: the fringing correction is of order g/(pi t) = 0.08 %
    // (Leus & Elata above); F/F_pp must be within 0.3 % of 1 (and above it: fringing adds force).
    let t = 400.0 * UM;
    let geo = CombGeometry { finger_width_m: 2.0 * UM, electrode_width_m: 2.0 * UM, substrate: None };
    let f = line_force(t, 1.0 * UM, None, geo, 0.0);
    let f_pp = 0.5 * VACUUM_PERMITTIVITY * t / (1.0 * UM).powi(2);
    println!("F/F_pp {:.5}", f / f_pp);
    assert!(f / f_pp > 1.0 && f / f_pp < 1.003);
}

#[test]
fn symmetric_periodic_cell_has_no_net_force_at_rest() {
    // Front and back gaps equal, no substrate: the cell is mirror-symmetric about the finger's
    // mid-plane, so the net force vanishes (symmetry; tolerance 1e-6 of the one-sided force).
    let t = 40.0 * UM;
    let geo = CombGeometry { finger_width_m: 4.0 * UM, electrode_width_m: 6.0 * UM, substrate: None };
    let f = line_force(t, 5.0 * UM, Some(5.0 * UM), geo, 0.0);
    let one_side = 0.5 * VACUUM_PERMITTIVITY * t / (5.0 * UM).powi(2);
    println!("net/one-sided {:.3e}", f / one_side);
    assert!((f / one_side).abs() < 1e-6);
}

#[test]
fn grid_refinement_changes_the_gca_force_by_less_than_half_a_percent() {
    // Convergence: the GCA cell (as built: gaps 5.63 / 8.55 um, finger 4.21 um, electrode
    // 6.2 um, t = 40 um) at the pull-in travel 1.9 um, default grid vs twice the cells in every
    // direction; tolerance 0.5 % of the net force (measured 0.2 %).
    let t = 40.0 * UM;
    let geo = CombGeometry { finger_width_m: 4.21 * UM, electrode_width_m: 6.2 * UM, substrate: None };
    let at = |r: f64| {
        let d = 0.01 * UM;
        let c = |x: f64| {
            capacitance_per_length(&CellProblem {
                thickness_m: t,
                front_gap_m: 5.63 * UM - x,
                back_gap_m: Some(8.55 * UM + x),
                geometry: geo,
                refinement: r,
                grid_reference_gaps_m: Some((5.63 * UM, Some(8.55 * UM))),
            })
            .unwrap()
        };
        (c(1.9 * UM + d) - c(1.9 * UM - d)) / (2.0 * d)
    };
    let (f1, f2) = (at(1.0), at(2.0));
    println!("refinement 1: {f1:e}, 2: {f2:e}, rel {:.2e}", f1 / f2 - 1.0);
    assert!((f1 / f2 - 1.0).abs() < 5e-3);
}

#[test]
fn table_spline_reproduces_the_direct_solve() {
    // The tabulated excess dC'(x) (natural spline in ln(g_f - x)) and its travel derivative
    // against direct solves between table nodes; tolerance 3 % of the excess force (the
    // excess is itself a few % of the total force, so about 1e-3 of the total; measured 1.2 %).
    let t = 40.0 * UM;
    let (gf, gb) = (5.63 * UM, 8.55 * UM);
    let geo = CombGeometry {
        finger_width_m: 4.21 * UM,
        electrode_width_m: 6.2 * UM,
        substrate: Some(Substrate { gap_m: 2.0 * UM, potential: SubstratePotential::Plates }),
    };
    let tab = table(t, gf, Some(gb), geo).unwrap();
    for x in [0.3 * UM, 1.9 * UM, 3.7 * UM] {
        let direct = line_force(t, gf, Some(gb), geo, x);
        let pp = 0.5 * VACUUM_PERMITTIVITY * t * (1.0 / (gf - x).powi(2) - 1.0 / (gb + x).powi(2));
        let from_table = pp + 0.5 * tab.excess(x).1;
        let excess = direct - pp;
        println!("x {:.1} um: direct excess {excess:e}, table {:e}", x / UM, from_table - pp);
        assert!((from_table - direct).abs() < 0.03 * excess.abs(), "x {x:e}");
    }
}

#[test]
fn cross_section_force_is_the_derivative_of_the_coenergy() {
    // F = dW*/dx at constant V for the whole array (Palmer length factor + 2D excess); central
    // difference of the capacitance, relative 1e-5.
    let p = PlateArray {
        plate_count: 70,
        overlap_length_m: 40.0 * UM,
        thickness_m: 40.0 * UM,
        front_gap_m: 5.63 * UM,
        back: Some(BackElectrode { gap_m: 8.55 * UM, potential: BackPotential::SameAsFront }),
        fringing: Fringing::CrossSection,
        relative_permittivity: 1.0,
        comb: Some(CombGeometry { finger_width_m: 4.21 * UM, electrode_width_m: 6.2 * UM, substrate: None }),
    };
    p.validate().unwrap();
    for x in [0.5 * UM, 1.9 * UM, 3.0 * UM] {
        let h = 1e-4 * UM;
        let dc = (p.capacitance_f(x + h) - p.capacitance_f(x - h)) / (2.0 * h);
        let f = p.force_per_volt2(x);
        assert!((0.5 * dc / f - 1.0).abs() < 1e-5, "x {x:e}: {} vs {f}", 0.5 * dc);
        let (_, df) = p.force_per_volt2_and_slope(x);
        let df_num = (p.force_per_volt2(x + h) - p.force_per_volt2(x - h)) / (2.0 * h);
        assert!((df / df_num - 1.0).abs() < 1e-4, "slope x {x:e}");
    }
    // Without the comb geometry the model is refused, naming it.
    let mut q = p;
    q.comb = None;
    assert!(q.validate().unwrap_err().to_string().contains("comb"));
}
