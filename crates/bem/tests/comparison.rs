//! The asperity (summit) model against the BEM on the same height grid and loads (issue 15's
//! comparison): where they agree and where the BEM's area exceeds the summit model's.

use stiction_bem::{BemSolver, Grid, SolverOptions, asperity};

/// A smooth, sparse surface: nine axisymmetric Gaussian bumps `A_k exp(-r^2/(2 s^2))`,
/// `s = L/10` (25.6 pixels), on a 3 x 3 lattice of pitch L/3 (3.3 s apart, slightly jittered),
/// heights falling by 4 % from bump to bump, on a 256 x 256 periodic cell of side L = 1.
fn bumps() -> (Grid, Vec<f64>, f64) {
    let (n, l) = (256usize, 1.0f64);
    let dx = l / n as f64;
    let (s, a) = (0.1 * l, 0.01 * l);
    let mut h = vec![0.0; n * n];
    for k in 0..9 {
        let (cx, cy) = ((k % 3) as f64 / 3.0 + 0.17 + 0.01 * k as f64, (k / 3) as f64 / 3.0 + 0.17 - 0.007 * k as f64);
        let amp = a * (1.0 - 0.04 * k as f64);
        for (i, v) in h.iter_mut().enumerate() {
            // Periodic distance to the bump centre.
            let wrap = |d: f64| d - d.round();
            let (x, y) = (wrap((i % n) as f64 * dx - cx), wrap((i / n) as f64 * dx - cy));
            *v += amp * (-(x * x + y * y) / (2.0 * s * s)).exp();
        }
    }
    (Grid::new(n, n, dx, dx).unwrap(), h, s * s / a)
}

/// Light load (loads of 0.3, 1 and 3 times the Hertz load for a contact radius of 0.35 s on the
/// top bump: 2-4 contacts of radius ~5-12 pixels inside their paraboloid caps, 3 s apart): the BEM
/// area and the summit model's agree within 8 % (measured +5.5 to +6.9 %: pixel counting, which
/// over-counts the edge of a contact of ~10 pixels radius by about that much and converges from
/// above with refinement, plus the weak elastic interaction of contacts 3 s apart). Heavier load
/// (100 times: all nine bumps in contact, radii beyond s, still separate patches): the BEM area
/// exceeds the summit model's by more than 20 % (measured +33 %; the peers report 12-33 %),
/// growing with load from 10 times on (+7 %, +13 %, +33 % at 10, 30, 100 times), because a
/// Gaussian bump lies above its osculating paraboloid away from the top, so contact spreads wider
/// than Hertz on the summit curvature predicts; this outweighs the elastic interaction (the other
/// bumps' pressure lowering a contact), which alone would reduce the BEM area.
#[test]
fn summit_model_agrees_at_light_load_and_falls_short_at_heavy_load() {
    let (grid, h, r_top) = bumps();
    let e_star: f64 = 1.0;
    let summits = asperity::summits(&h, grid);
    assert_eq!(summits.len(), 9, "one summit per bump");
    let mut s = BemSolver::new(grid.nx, grid.ny, grid.dx_m, grid.dy_m, &h, e_star).unwrap();
    let opts = SolverOptions { tolerance: 1e-8, ..Default::default() };
    // Hertz load for a contact radius of 0.35 s on the top bump: P = 4 E* a^3/(3 R).
    let s_len: f64 = 0.1;
    let unit = 4.0 * e_star * (0.35 * s_len).powi(3) / (3.0 * r_top);
    let mut ratios = Vec::new();
    for f in [0.3, 1.0, 3.0, 10.0, 30.0, 100.0] {
        let load = f * unit;
        let b = s.solve_load(load / grid.area_m2(), &opts, None).unwrap();
        let a = asperity::at_load(&summits, e_star, load).unwrap();
        let r = b.contact_area_m2 / a.contact_area_m2;
        println!("load x{f}: BEM/asperity area {r:.4} ({} summits in contact, {} patches)", a.contacts, b.patches);
        ratios.push(r);
    }
    for r in &ratios[..3] {
        assert!((r - 1.0).abs() < 0.08, "light load: BEM/asperity = {r}");
    }
    assert!(ratios[5] > 1.2, "heavy load: BEM/asperity = {}", ratios[5]);
    assert!(ratios[3] < ratios[4] && ratios[4] < ratios[5], "ratio should grow with load: {ratios:?}");
}
