//! The limits on counts and lengths of the commands, for a front end that takes the same
//! quantities as arrays or integers (Python checks its arguments against these before any work,
//! and names its own argument in the message).

/// Most loads of one `stiction contact` sweep by default (`--max-sweep-steps`).
pub use crate::contact::DEFAULT_MAX_SWEEP_STEPS;
/// Most calibration draws of `stiction fit --draws`.
pub use stiction_fit::MAX_DRAWS;
/// Most data rows of `stiction fit`.
pub use stiction_fit::MAX_FIT_ROWS;
/// Most surface realisations of `stiction fit --surfaces`.
pub use stiction_fit::models::MAX_SURFACES;
/// Most worker threads of `stiction study --threads`.
pub use stiction_study::MAX_THREADS;
/// The sample limit of `stiction study --samples` in force (`STICTION_MAX_SAMPLES` raises it).
pub use stiction_study::max_samples;

/// Most steps of a `stiction bem --sweep` or `--gap-sweep` path (FROM:TO:STEPS), so also most
/// pressures of a front end's vector of pressures. The check is `bem`'s own (`parse_path`);
/// the test `bem_limits_are_the_commands` fails if the two ever differ.
pub const BEM_MAX_PATH_STEPS: usize = 10_000;
/// Most grid points per side of `stiction bem --grid` (checked by `bem` itself; same test).
pub const BEM_MAX_GRID_SIDE: usize = 4096;
/// Most relative humidities of `--rh` (`stiction bem`, `stiction plot humidity`), checked by
/// [`crate::rh::check_rh_values`] (same test).
pub const MAX_RH: usize = 1000;

/// A front end's vector of `len` loads for one sweep (Python's `contact(load=[...])`, named
/// `name`), checked against `max` before any load is solved: the limit and the reason of
/// `--sweep STEPS` (`parse_sweep`), with the front end's `advice` ("raise it with
/// max_sweep_steps=N if you mean it").
pub fn check_sweep_len(name: &str, len: usize, max: usize, advice: &str) -> Result<(), String> {
    if len == 0 {
        return Err(format!("{name}: expected at least one load"));
    }
    if len > max {
        return Err(format!(
            "{name}: {len} loads, more than the limit of {max} loads of a sweep (one equilibrium solve and about \
             100 bytes of output each: {:.1e} bytes); {advice}",
            len as f64 * 100.0
        ));
    }
    Ok(())
}

/// A front end's vector of `len` mean pressures for `stiction bem` (named `name`): 1 to
/// [`BEM_MAX_PATH_STEPS`], the limit of `--sweep FROM:TO:STEPS`.
pub fn check_pressures_len(name: &str, len: usize) -> Result<(), String> {
    if len == 0 || len > BEM_MAX_PATH_STEPS {
        return Err(format!(
            "{name}: {len} pressures; expected 1 to {BEM_MAX_PATH_STEPS} mean pressures (the limit of bem's sweep \
             FROM:TO:STEPS)"
        ));
    }
    Ok(())
}

/// A BEM grid of `nx` x `ny` points from an array named `name`, checked against the solver's
/// grid limit (`stiction bem --map`'s check, [`stiction_bem::Grid::new`]) before the array is
/// read or copied.
pub fn check_bem_grid(name: &str, nx: usize, ny: usize) -> Result<(), String> {
    stiction_bem::Grid::new(nx, ny, 1.0, 1.0).map(|_| ()).map_err(|e| format!("{name}: {e} (the BEM grid limit)"))
}
