//! `stiction`: a virtual MEMS friction meter.
//!
//! The binary only parses arguments, calls the libraries and prints. Every quantity flag accepts a
//! bare number in SI or a number with a unit ("0.5 um", "1.4 GPa", "3 uN").

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use stiction_cli::{cmd, output};

/// stiction: a virtual MEMS friction meter (static friction in elastic adhesive MEMS contacts).
///
/// Quantities accept a bare number (SI) or a number with a unit: "0.5 um", "1.4 GPa", "3 uN",
/// "0.1 J/m^2", "9.1e-12 1/Pa". Add --json for machine-readable output.
#[derive(Parser, Debug)]
#[command(name = "stiction", version, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Greenwood-Williamson with DMT adhesion (eq. 5-9): separation h, N*, A* at a normalized load L*.
    Gw(cmd::gw::Args),
    /// The discrete N-contact model (eq. 12): friction, its slope and the apparent adhesion force at a load.
    Discrete(cmd::discrete::Args),
    /// Generate (or read) a scenario's rough sidewall: summit statistics and a CSV export.
    Surface(cmd::surface::Args),
    /// The explicit asperity-by-asperity solver on a scenario's surface at a load or over a sweep.
    Contact(cmd::contact::Args),
    /// A gap-closing actuator array of a scenario: pull-in, release, conversion factor, sweeps, validation.
    Actuator(cmd::actuator::Args),
    /// Run the friction meter experiment of a scenario (the paper's Fig. 5), with plots and tables.
    Run(cmd::run::Args),
    /// Recompute a figure of the paper (fig2, fig3, fig7) or the actuator hysteresis, as SVG or PNG.
    Plot(cmd::plot::Args),
    /// Monte Carlo over a scenario's uncertain parameters and surface realisations: the spread of mu_e,a and F_a0.
    Study(cmd::study::Args),
    /// Combine the output folders of a study's shards into the outputs one run would have written.
    Merge(cmd::merge::Args),
    /// Fit measured voltages: eq. 10 with regression and calibration intervals, s per contact model, ranked.
    Fit(cmd::fit::Args),
    /// FFT boundary-element contact (optionally Maugis-Dugdale adhesive) on a generated self-affine rough surface.
    Bem(Box<cmd::bem::Args>),
    /// Check a scenario file (and --set overrides) and print it in SI units, or print the format's JSON Schema.
    Scenario(cmd::scenario::Args),
    /// A measured height map (AFM, profiler): levelling, cut-offs, summits, statistics beside Nayak's predictions, figures.
    Topography(cmd::topography::Args),
}

fn main() -> ExitCode {
    // A flag's error quotes the value given; a value of a megabyte is cut, as every message is.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            stiction_cli::errln!("{}", stiction_units::text::bounded_message(e.render().to_string().trim_end()));
            return ExitCode::from(2);
        }
    };
    output::install_interrupt_handler();
    let result = match cli.command {
        Command::Gw(a) => cmd::gw::run(a),
        Command::Discrete(a) => cmd::discrete::run(a),
        Command::Surface(a) => cmd::surface::run(a),
        Command::Contact(a) => cmd::contact::run(a),
        Command::Actuator(a) => cmd::actuator::run(a),
        Command::Run(a) => cmd::run::run(a),
        Command::Plot(a) => cmd::plot::run(a),
        Command::Scenario(a) => cmd::scenario::run(a),
        Command::Study(a) => cmd::study::run(a),
        Command::Merge(a) => cmd::merge::run(a),
        Command::Fit(a) => cmd::fit::run(a),
        Command::Topography(a) => cmd::topography::run(a),
        Command::Bem(a) => cmd::bem::run(*a),
    };
    output::flush_stdout();
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.is::<output::Interrupted>() => {
            stiction_cli::errln!("{e}");
            ExitCode::from(130)
        }
        Err(e) => {
            stiction_cli::errln!("error: {}", stiction_units::text::bounded_message(&e.to_string()));
            ExitCode::from(2)
        }
    }
}
