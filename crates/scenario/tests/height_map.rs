//! A scenario's surface sourced from a height map (the bundled example map,
//! data/topography-example/wall.gsf): patches, seeds, errors, and the explicit solver on the
//! map's summits against Greenwood-Williamson on the same summits' statistics.

use std::path::{Path, PathBuf};

use stiction_contact::explicit::{Detail, ExplicitSolver, ShoeMode, SolverConfig};
use stiction_contact::gw::GwSurface;
use stiction_contact::single::{AdhesionLaw, AsperityParams};
use stiction_scenario::Scenario;

fn scenarios() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

fn surface_of(surface_json: &str) -> Result<stiction_surface::Surface, String> {
    let text = format!(r#"{{"format_version": 1, "surface": {surface_json}}}"#);
    let origin = scenarios().join("inline.json");
    let s = Scenario::from_str_with_sets(&text, &origin, &[]).map_err(|e| e.to_string())?;
    s.surface.unwrap().build(&scenarios()).map_err(|e| e.to_string())
}

#[test]
fn patches_are_stated_or_drawn_from_the_seed() {
    let map = r#""height_map": {"file": "../data/topography-example/wall.gsf", "patch_x": "2 um", "patch_y": "1 um"}"#;
    let a = surface_of(&format!(
        r#"{{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map", {map}, "seed": 1}}"#
    ))
    .unwrap();
    let b = surface_of(&format!(
        r#"{{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map", {map}, "seed": 2}}"#
    ))
    .unwrap();
    assert_eq!(a, b, "a stated corner does not depend on the seed");
    // Table 1's density is 4e12 m^-2; the example map was made for about 4.6e12 (see its README).
    let st = a.stats();
    assert!(st.count > 300 && st.count < 600, "{}", st.count);
    let random = |seed: u64| {
        surface_of(&format!(
            r#"{{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map",
                "height_map": {{"file": "../data/topography-example/wall.gsf"}}, "seed": {seed}}}"#
        ))
        .unwrap()
    };
    assert_eq!(random(7), random(7));
    assert_ne!(random(7), random(8));
    // Both faces: the composite of two patches has summits of higher curvature.
    let both = surface_of(
        r#"{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/wall.gsf", "patch_x": "0 um", "patch_y": "0 um"},
            "counter_height_map": {"file": "../data/topography-example/wall.gsf", "patch_x": "5 um", "patch_y": "3 um"}}"#,
    )
    .unwrap();
    assert!(both.stats().radius_mean_m < st.radius_mean_m);
}

#[test]
fn height_map_errors_name_the_problem() {
    let e = surface_of(
        r#"{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/wall.gsf"}, "summit_sd": "40 nm"}"#,
    )
    .unwrap_err();
    assert!(e.contains("`summit_sd` must be absent"), "{e}");
    let e = surface_of(
        r#"{"apparent_length": "30 um", "apparent_width": "5 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/wall.gsf"}}"#,
    )
    .unwrap_err();
    assert!(e.contains("750 x 125 pixels") && e.contains("640 x 200"), "{e}");
    let e = surface_of(
        r#"{"apparent_length": "20 um", "apparent_width": "5 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/none.gsf"}}"#,
    )
    .unwrap_err();
    assert!(e.contains("none.gsf"), "{e}");
    let e = surface_of(
        r#"{"apparent_length": "20 um", "apparent_width": "5 um",
            "height_map": {"file": "../data/topography-example/wall.gsf"}, "summit_density": "4e12 m^-2",
            "summit_sd": "40 nm", "summit_radius": "0.5 um"}"#,
    )
    .unwrap_err();
    assert!(e.contains("only allowed when `source` is \"height_map\""), "{e}");
}

/// The explicit solver on the map's own summits (flat rigid shoe, Hertz, no adhesion) against a
/// direct summation written here: at separation d every summit above d carries the Hertz force
/// F_i = sqrt(R_i) (z_i - d)^(3/2) / D (eq. 3b, E* = 3/(4D)) and the area pi R_i (z_i - d); d is
/// found by bisection for the load. The solver's relative tolerance is 1e-9; tolerances: the same
/// contacts, area and separation to 1e-6 relative.
///
/// Greenwood-Williamson on the same summits' statistics is printed beside it, not asserted: GW
/// assumes Gaussian summit heights and one mean radius, and how far the map's summits depart from
/// that is not pinned by any independent reference here.
#[test]
fn explicit_solver_on_map_summits_matches_a_direct_hertz_sum() {
    let surface = surface_of(
        r#"{"apparent_length": "25.2 um", "apparent_width": "7.8 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/wall.gsf", "patch_x": "0 um", "patch_y": "0 um"}}"#,
    )
    .unwrap();
    let st = surface.stats();
    let d = 9.1e-12;
    let summits: Vec<(f64, f64)> = (0..surface.len()).map(|i| (surface.height_m(i), surface.radius_m(i))).collect();
    // Direct Hertz sum at separation `sep`: (load, contacts, area).
    let hertz = |sep: f64| {
        let mut out = (0.0, 0usize, 0.0);
        for &(z, r) in &summits {
            let delta = z - sep;
            if delta > 0.0 {
                out.0 += r.sqrt() * delta.powf(1.5) / d;
                out.1 += 1;
                out.2 += std::f64::consts::PI * r * delta;
            }
        }
        out
    };
    let separation_at = |load: f64| {
        let top = summits.iter().fold(f64::NEG_INFINITY, |m, s| m.max(s.0));
        let (mut lo, mut hi) = (top - 1e-6, top);
        assert!(hertz(lo).0 > load, "bracket");
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if hertz(mid).0 > load { lo = mid } else { hi = mid }
        }
        0.5 * (lo + hi)
    };
    let gw = GwSurface {
        summit_density_per_m2: st.summit_density_per_m2,
        summit_radius_m: st.radius_mean_m,
        summit_sd_m: st.height_sd_m,
        compliance_per_pa: d,
        work_of_adhesion_j_per_m2: 0.0,
        apparent_area_m2: surface.apparent_area_m2(),
    };
    let params = AsperityParams {
        radius_m: st.radius_mean_m,
        compliance_per_pa: d,
        work_of_adhesion_j_per_m2: 0.0,
        equilibrium_spacing_m: 0.3e-9,
    };
    let config = SolverConfig { mode: ShoeMode::Flat, detail: Detail::Summary, ..Default::default() };
    let mut solver = ExplicitSolver::new(surface, AdhesionLaw::Hertz, params, config).unwrap();
    for l_star in [0.01, 0.02, 0.05] {
        let load = l_star * gw.load_scale_n();
        let e = solver.solve(load).unwrap();
        let sep = separation_at(load);
        let (_, contacts, area) = hertz(sep);
        assert!(contacts >= 25, "L* = {l_star}: {contacts} contacts");
        assert_eq!(e.contacts, contacts, "L* = {l_star}: contacts");
        assert!((e.real_area_m2 / area - 1.0).abs() < 1e-6, "L* = {l_star}: area {:e} vs sum {area:e}", e.real_area_m2);
        let scale = st.height_sd_m;
        assert!((e.separation_m - sep).abs() < 1e-6 * scale, "L* = {l_star}: d {:e} vs {sep:e}", e.separation_m);
        let g = gw.solve_load(load, false).unwrap();
        eprintln!("L* = {l_star}: contacts {contacts} (GW {:.1}), area {area:e} (GW {:e})", g.contacts, g.real_area_m2);
    }
}
