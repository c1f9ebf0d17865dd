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
/// pressures of a front end's vector of pressures: the typed ranges' own limit (`crate::range`).
pub use crate::range::MAX_PATH_STEPS as BEM_MAX_PATH_STEPS;
/// Most grid points per side of `stiction bem --grid` (checked by `bem` itself; same test).
pub const BEM_MAX_GRID_SIDE: usize = 4096;
/// Most relative humidities of `--rh` (`stiction bem`, `stiction plot humidity`), checked by
/// [`crate::rh::check_rh_values`] (same test).
pub const MAX_RH: usize = 1000;

/// A front end's vector of `len` loads for one sweep (Python's `contact(load=[...])`, named
/// `name`), checked against `max` before any load is solved: the limit and the reason of
/// `--sweep STEPS` (`range::LoadRange::parse`), with the front end's `advice` ("raise it with
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bem::{BemHumidity, BemRequest, BemSurface, bem_json};

    fn request(grid: usize) -> BemRequest {
        BemRequest {
            preparation: stiction_topography::Preparation {
                levelling: stiction_topography::Levelling::Plane,
                short_cutoff_m: None,
                long_cutoff_m: None,
            },
            size_m: 100e-6,
            grid,
            hurst: 0.8,
            roll_off_m: None,
            short_m: None,
            rms_height_m: 0.5e-6,
            seed: 1,
            e_star_pa: None,
            pressure_pa: None,
            sweep: None,
            gap_sweep: None,
            gap_back: false,
            work_of_adhesion_j_per_m2: None,
            range_m: None,
            humidity: BemHumidity {
                rh: None,
                temperature_k: 298.15,
                contact_angle_rad: 0.0,
                rh_step_m: None,
                min_kelvin_radius_m: None,
            },
            shear_strength_pa: None,
            tolerance: 1e-6,
            compare_asperity: false,
            boundary: stiction_bem::Boundary::Periodic,
            tilt: false,
            hardness_pa: None,
        }
    }

    /// The limits stated here are those the engine checks: one past each is refused by the
    /// engine's own parser with a message that names it, the limit itself is taken.
    #[test]
    fn bem_limits_are_the_engines() {
        use crate::range::{GapRange, PressureRange};
        let bem = |req: BemRequest| bem_json(&req, BemSurface::Generated, None).map(|_| ()).map_err(|e| e.to_string());
        let over = format!("1MPa:2MPa:{}", BEM_MAX_PATH_STEPS + 1);
        let e = PressureRange::parse(&over, "--sweep").unwrap_err();
        assert!(e.contains(&format!("1..={BEM_MAX_PATH_STEPS}")), "{e}");
        let e = GapRange::parse(&over.replace("MPa", "um"), "--gap-sweep").unwrap_err();
        assert!(e.contains(&format!("1..={BEM_MAX_PATH_STEPS}")), "{e}");
        // A typed range built past the limit is refused by the engine, naming the field.
        let sweep = Some(PressureRange { from_pa: 1e6, to_pa: 2e6, steps: BEM_MAX_PATH_STEPS + 1 });
        let e = bem(BemRequest { sweep, ..request(32) }).unwrap_err();
        assert!(e.starts_with("sweep: ") && e.contains(&format!("1 to {BEM_MAX_PATH_STEPS}")), "{e}");
        let gap_sweep = Some(GapRange { from_m: 1e-6, to_m: 2e-6, steps: BEM_MAX_PATH_STEPS + 1 });
        let e = bem(BemRequest { gap_sweep, ..request(32) }).unwrap_err();
        assert!(e.starts_with("gap_sweep: ") && e.contains(&format!("1 to {BEM_MAX_PATH_STEPS}")), "{e}");
        let e = bem(BemRequest { pressure_pa: Some(1e6), ..request(BEM_MAX_GRID_SIDE + 1) }).unwrap_err();
        assert!(e.contains(&format!("2..={BEM_MAX_GRID_SIDE}")), "{e}");
        let e = crate::rh::check_rh_values(&[0.5; MAX_RH + 1]).unwrap_err();
        assert!(e.contains(&format!("1 to {MAX_RH}")), "{e}");
        crate::rh::check_rh_values(&[0.5; MAX_RH]).unwrap();
        let e = crate::humidity::rh_grid(Some(&format!("0:0.5:{}", MAX_RH + 1))).unwrap_err();
        assert!(e.contains(&format!("1..={MAX_RH}")), "{e}");
        assert!(check_bem_grid("heights", 4096, 4097).unwrap_err().starts_with("heights: "));
        check_bem_grid("heights", 4096, 4096).unwrap();
        check_pressures_len("pressure", BEM_MAX_PATH_STEPS).unwrap();
        assert!(check_pressures_len("pressure", BEM_MAX_PATH_STEPS + 1).unwrap_err().starts_with("pressure: "));
        assert_eq!(BEM_MAX_GRID_SIDE, crate::bem::MAX_SIDE);
    }

    /// A typed temperature outside the domain of `environment.temperature` (liquid water,
    /// 273.16 K to the critical point 647.096 K) is refused by the engine, named as the flag.
    #[test]
    fn a_typed_temperature_is_checked_against_its_domain() {
        let humid = |t: f64| {
            let mut req = request(16);
            req.humidity.rh = Some(vec![0.3]);
            req.humidity.temperature_k = t;
            bem_json(&req, BemSurface::Generated, None).map(|_| ()).map_err(|e| e.to_string())
        };
        for t in [273.15, 700.0, f64::NAN] {
            let e = humid(t).unwrap_err();
            assert!(e.starts_with("--temperature: ") && e.contains("is outside"), "{e}");
        }
        let e = crate::bem::humidity::parse_temperature("500 C", "temperature").unwrap_err();
        assert!(e.starts_with("temperature: 773.15 K is outside"), "{e}");
        assert_eq!(crate::bem::humidity::parse_temperature("25 C", "temperature"), Ok(298.15));
    }

    /// The sweep limit of a front end's vector of loads is a sweep text's: the same count refused
    /// by `LoadRange::parse` is refused here, one less taken.
    #[test]
    fn the_sweep_limit_of_a_vector_is_the_sweeps() {
        let max = 10;
        use crate::range::LoadRange;
        assert!(LoadRange::parse("0uN:1uN:11", "--sweep", max, "").is_err());
        assert_eq!(LoadRange::parse("0uN:1uN:10", "--sweep", max, "").unwrap().values_n().len(), 10);
        let e = check_sweep_len("load", 11, max, "raise it with max_sweep_steps=N").unwrap_err();
        assert!(e.starts_with("load: 11 loads") && e.contains("max_sweep_steps="), "{e}");
        check_sweep_len("load", 10, max, "").unwrap();
        assert!(check_sweep_len("load", 0, max, "").is_err());
        assert_eq!(DEFAULT_MAX_SWEEP_STEPS, 1_000_000);
    }
}
