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

#[test]
fn explicit_solver_on_map_summits_agrees_with_gw_on_their_statistics() {
    // The largest patch of the example map (about 800 summits), a flat rigid shoe without adhesion
    // (Hertz): GW's assumptions (independent summits, a flat counter face) hold except that the
    // summit heights are not exactly Gaussian and the radii vary (GW takes their mean). Compared at
    // equal load for 30-100 contacts: the number of contacts and the real area. Measured: the solver
    // finds 12-34 % more contacts and 20-22 % less real area than GW (GW gives every summit the
    // mean radius; the small-radius summits, which touch more often, carry less area); tolerances
    // 35 % and 30 %.
    let surface = surface_of(
        r#"{"apparent_length": "25.2 um", "apparent_width": "7.8 um", "source": "height_map",
            "height_map": {"file": "../data/topography-example/wall.gsf", "patch_x": "0 um", "patch_y": "0 um"}}"#,
    )
    .unwrap();
    let st = surface.stats();
    let d = 9.1e-12;
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
    let mut report = Vec::new();
    for l_star in [0.01, 0.02, 0.05] {
        let load = l_star * gw.load_scale_n();
        let g = gw.solve_load(load, false).unwrap();
        let e = solver.solve(load).unwrap();
        report.push((l_star, e.contacts, g.contacts, e.real_area_m2, g.real_area_m2));
    }
    for &(l_star, ec, gc, ea, ga) in &report {
        assert!(ec >= 25, "{report:?}");
        assert!((ec as f64 / gc - 1.0).abs() < 0.35, "L* = {l_star}: contacts {ec} vs GW {gc:.1}; {report:?}");
        assert!((ea / ga - 1.0).abs() < 0.3, "L* = {l_star}: area {ea:e} vs GW {ga:e}; {report:?}");
    }
    eprintln!("{report:?}");
}
