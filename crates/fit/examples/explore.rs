//! Exploration.
use rand::SeedableRng;
use std::path::Path;
use stiction_fit::*;
fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let name = std::env::args().nth(1).unwrap_or("tas2000.json".into());
    let path = root.join("scenarios").join(&name);
    let sc = stiction_scenario::Scenario::load(&path, &[]).unwrap();
    let json = stiction_scenario::Scenario::load_json(&path, &[]).unwrap();
    let base = path.parent().unwrap();
    let ctx = ModelContext::new(&sc, base).unwrap();
    println!("device {:?} R {}", ctx.device, ctx.nominal_radius_m);
    let volts: Vec<f64> = (0..13).map(|k| 23.0 + 0.5 * k as f64).collect();
    let t = std::time::Instant::now();
    let rows = synth::from_meter(&sc, base, &volts, 3, 0.3, 7).unwrap();
    println!("synth {:?}", t.elapsed());
    let csv = synth::to_csv(&rows, "test").unwrap();
    let ds = parse_voltages(csv.as_bytes(), "x.csv").unwrap();
    let mut opts = FitOptions::default();
    if let Some(m) = std::env::args().nth(2) {
        opts.models = ModelKind::parse_list(&m).unwrap();
    }
    if let Some(f) = std::env::args().nth(3) {
        opts.free = Free::parse(&f).unwrap();
    }
    let t = std::time::Instant::now();
    let rep = analyse(&ds, &sc, &json, base, &opts).unwrap();
    println!("analyse {:?}", t.elapsed());
    println!("mu {:?}\nfa0 {:?}\nshares {:?}", rep.mu_apparent, rep.apparent_adhesion_force_n, rep.variance_shares);
    println!("{}", rep.noise_note);
    for m in &rep.models {
        println!(
            "{:20} s {:.4e} ci {:?} chi2 {:.2} dof {} aic {:.2} w {:?} rough {:?} R {:?} F {:?} {:?}",
            m.name,
            m.shear_strength_pa.value,
            m.shear_strength_pa.ci95,
            m.chi2,
            m.dof,
            m.aic,
            m.akaike_weight,
            m.roughness,
            m.summit_radius_m.as_ref().map(|p| p.value),
            m.spring_force_n.as_ref().map(|p| p.value),
            m.shear_strength_pa.note
        );
    }
    for f in &rep.models_failed {
        println!("FAILED {:?}", f);
    }
    println!("{:?}", rep.model_selection);
    let _ = rand_chacha::ChaCha8Rng::seed_from_u64(1);
}
