//! The light-load constant kappa of `A/A0 = kappa p/(E* h'_rms)` on self-affine surfaces, 3 seeds,
//! at p/(E* h'_rms) = 0.005, 0.01, 0.02, 0.05:
//! `cargo run --release -p stiction-bem --example kappa -- N ROLLOFF_DIVISOR SHORT_PIXELS HURST`
//! (grid N x N, roll-off wavelength L/ROLLOFF_DIVISOR, short cut-off SHORT_PIXELS dx).
use stiction_bem::*;
fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|s| s.parse().expect("numeric arguments")).collect();
    if args.len() != 4 {
        eprintln!("usage: kappa N ROLLOFF_DIVISOR SHORT_PIXELS HURST");
        std::process::exit(2);
    }
    let (n, rl, sl, hurst) = (args[0] as usize, args[1], args[2], args[3]);
    let l = 100e-6;
    let g = Grid::new(n, n, l / n as f64, l / n as f64).expect("valid case");
    for seed in 0..3 {
        let h = synth::self_affine(g, hurst, l / rl, sl * l / n as f64, 0.5e-6, seed).expect("valid case");
        let mut s = BemSolver::new(n, n, g.dx_m, g.dx_m, &h, 1e11).expect("valid case");
        let sl = s.slope_rms();
        let mut out = String::new();
        for pn in [0.005, 0.01, 0.02, 0.05] {
            let sol = s.solve_load(pn * 1e11 * sl, &SolverOptions::default(), None).expect("valid case");
            out += &format!(" {:.3}", sol.contact_fraction / pn);
        }
        println!("seed {seed} kappa {out}");
    }
}
