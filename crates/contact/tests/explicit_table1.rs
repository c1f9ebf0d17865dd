//! The paper's Table 1 surface (about 400 summits) under a tilt-free shoe, against eq. 12, N = 3.

use std::f64::consts::PI;

use stiction_contact::explicit::table1::{discrete_friction_n, friction_vs_load};
use stiction_contact::single::AdhesionLaw;

#[test]
fn a_tilt_free_shoe_rests_on_at_least_three_summits_and_three_contacts_obey_the_jensen_bound() {
    // With exactly 3 contacts statics fixes their loads w_i L (w_i barycentric weights of the load
    // point, sum 1). F = s pi R (D/R^1/2)^(2/3) sum (w_i L + c)^(2/3), c = 2 pi dgamma R (eq. 4).
    // x^(2/3) is concave, so F <= eq. 12 with N = 3 (equal sharing, Jensen). At L = 0
    // every contact carries zero net load, so F equals eq. 12 exactly. (No lower bound: a weight
    // may be negative, a summit held in tension by its adhesion when the load point lies outside
    // the triangle.)
    let r = 0.5e-6f64;
    let c = 2.0 * PI * 0.1 * r;
    let loads: Vec<f64> = (0..=10).map(|i| i as f64 * 1e-6).collect();
    let mut three = 0;
    for seed in 0..40 {
        let cmp = friction_vs_load(seed, &loads, AdhesionLaw::Dmt).unwrap();
        assert!((350..450).contains(&cmp.summits), "about 400 summits on 100 um^2: {}", cmp.summits);
        // Pull-off of the contact made at zero load: at most 3 DMT adhesions (eq. 12 N = 3 value,
        // reached only for equal sharing) and tensile.
        assert!(cmp.pull_off_load_n < 0.0 && cmp.pull_off_load_n >= -3.0 * c * (1.0 + 1e-6), "{}", cmp.pull_off_load_n);
        assert_eq!(cmp.points.len(), loads.len());
        for p in &cmp.points {
            assert!(p.contacts >= 3, "seed {seed} L = {}: {} contacts", p.load_n, p.contacts);
            assert!(p.max_pressure_pa < 9e9, "elastic: q0 below the 9 GPa hardness of polysilicon (section 5)");
            if p.contacts == 3 {
                three += 1;
                let upper = discrete_friction_n(p.load_n, 3);
                assert!(p.friction_explicit_n <= upper * (1.0 + 1e-9), "seed {seed}: {p:?}");
                if p.load_n == 0.0 {
                    assert!((p.friction_explicit_n / upper - 1.0).abs() < 1e-6, "seed {seed}: {p:?}");
                }
            }
        }
    }
    // Most configurations have exactly 3 contacts (the paper's assumption); measured 80-95 %.
    assert!(three > 40 * 11 * 7 / 10, "{three} of {} points with 3 contacts", 40 * 11);
}
