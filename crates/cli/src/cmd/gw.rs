//! `stiction gw`: Greenwood-Williamson with DMT adhesion in normalized form (eq. 5-9).

use stiction_engine::gw::{GwRequest, gw};

use crate::output::{CliResult, print_json, print_table};

/// The stable-branch GW(+DMT) state at a normalized load L* = D L / (eta A_a R^1/2 sigma^3/2).
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Adhesion parameter theta = sigma^3/2 R^1/2 / (D dgamma R) (eq. 9); "inf" for plain GW (no adhesion).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_theta)]
    pub theta: Theta,
    /// Normalized load L* (eq. 8); below the pull-off load there is no equilibrium.
    #[arg(long = "load-star", allow_hyphen_values = true)]
    pub load_star: f64,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// An adhesion parameter: finite and positive, or infinite (`None`, no adhesion).
#[derive(Clone, Copy, Debug)]
pub struct Theta(pub Option<f64>);

/// Parses a finite theta > 0 or "inf".
fn parse_theta(s: &str) -> Result<Theta, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("inf") || t.eq_ignore_ascii_case("infinity") {
        return Ok(Theta(None));
    }
    match t.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(Theta(Some(x))),
        Ok(x) if x.is_infinite() && x > 0.0 => {
            Err(format!("{s:?} overflows to infinity; write \"inf\" for plain GW (no adhesion), or a finite theta"))
        }
        _ => Err(format!("{s:?}: expected a positive adhesion parameter or \"inf\"")),
    }
}

/// Runs the subcommand.
pub fn run(args: Args) -> CliResult {
    let out = gw(&GwRequest { theta: args.theta.0, load_star: args.load_star }, "--load-star")?;
    if args.json {
        return print_json(&out);
    }
    let theta = out.theta.map_or("inf (no adhesion)".to_string(), |t| format!("{t}"));
    print_table(
        "Greenwood-Williamson + DMT (eq. 5, 8), stable branch",
        &[
            ("adhesion parameter theta", theta),
            ("normalized load L*", format!("{:.6e}", out.l_star)),
            ("separation h = d/sigma", format!("{:.6}", out.h)),
            ("summits in contact N*", format!("{:.6e}  (log10 {:.4})", out.n_star, out.log10_n_star)),
            ("real area A*", format!("{:.6e}  (log10 {:.4})", out.a_star, out.log10_a_star)),
            ("elastic load F_3/2(h)", format!("{:.6e}", out.elastic_l_star)),
            ("adhesive load (2 pi/theta) F_0", format!("{:.6e}", out.adhesive_l_star)),
            ("pull-off L*", out.pull_off_l_star.map_or("none (no adhesion)".into(), |l| format!("{l:.6e}"))),
        ],
    );
    Ok(())
}
