//! Design studies: the same Monte Carlo study at every point of a grid of design values.
//!
//! `--vary PATH=V1,V2,...` (repeatable) names a scenario field and the values it takes, written
//! as `--set` takes them. The design points are the grid of all combinations (the first `--vary`
//! changes slowest). Each design point is a complete study of the scenario with the user's
//! `--set`s and then `PATH=V` for every varied field: the same seed, so every design draws the
//! same uncertain parameters' random numbers and the same surface seeds (common random numbers:
//! two designs differ by their design, not by their luck), and each design's folder is byte for
//! byte the folder of `stiction study SCENARIO --set ... --set PATH=V ...`.
//!
//! Per design ([`DesignRow`]): the fraction of experiments with a usable eq. 10 line (and the
//! reasons of the others), the spread of mu_e,a and F_a0 with their Monte Carlo errors, the
//! width of the 5-95 % interval of mu_e,a over the virtual meters, the widths of the 95 % intervals
//! each lab would quote for its own eq. 10 fit without and with the calibration uncertainty, and
//! the bias of each experiment's mu_e,a against its own device's interface coefficient
//! ([`crate::interface_mu`]).

use std::collections::BTreeMap;

use serde::Serialize;

use crate::StudyError;
use crate::summary::{Spread, StudySummary};

/// Largest number of design points in one design study.
pub const MAX_DESIGNS: usize = 1000;

/// One `--vary PATH=V1,V2,...`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Vary {
    /// The scenario field, as `--set` names it.
    pub path: String,
    /// Its values, as `--set` takes them (for a range: filled in by [`grid`] from the
    /// space-filling design).
    pub values: Vec<String>,
    /// A continuous range `LO..HI` (`--vary "PATH=20 V..40 V"`): the two ends as numbers in the
    /// unit written after them (the same unit at both ends, or none), sampled by a Latin hypercube.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub range: Option<VaryRange>,
    /// Given in the scenario's `design` section (errors name `design.vary.PATH`), not as `--vary`.
    #[serde(skip)]
    pub from_section: bool,
}

/// A continuous range of a varied field: `lo..hi` in `unit` (as written, e.g. "V" or "N/m";
/// empty for a bare number in SI).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VaryRange {
    /// The low end, in `unit`.
    pub lo: f64,
    /// The high end, in `unit`.
    pub hi: f64,
    /// The unit written after both ends ("" for SI numbers).
    pub unit: String,
}

/// Splits `"20 V"` (or `"20V"`, `"1nm"`: a unit may follow the number with or without a space, as
/// `--set` takes quantities) into 20 and "V" (a bare number has the unit ""). The number is the
/// longest prefix that parses as a finite f64.
fn number_and_unit(s: &str) -> Option<(f64, String)> {
    let s = s.trim();
    let longest = s.char_indices().map(|(k, c)| k + c.len_utf8()).rfind(|&end| s[..end].parse::<f64>().is_ok())?;
    let x: f64 = s[..longest].parse().ok()?;
    x.is_finite().then(|| (x, s[longest..].trim().to_string()))
}

impl VaryRange {
    /// Parses `LO..HI` (`"20 V..40 V"`, `"1..3"`); `None` when the text is not a range.
    fn parse(text: &str) -> Option<Result<VaryRange, String>> {
        let (lo, hi) = text.split_once("..")?;
        let (Some((lo, u1)), Some((hi, u2))) = (number_and_unit(lo), number_and_unit(hi)) else {
            return Some(Err("a range is LO..HI with two finite numbers (\"20 V..40 V\")".into()));
        };
        if u1 != u2 {
            return Some(Err(format!(
                "the two ends of a range have different units ({u1:?} and {u2:?}); write both in one unit"
            )));
        }
        if lo >= hi {
            return Some(Err(format!("a range LO..HI needs LO < HI (got {lo}..{hi})")));
        }
        Some(Ok(VaryRange { lo, hi, unit: u1 }))
    }

    /// The value at the fraction `t` of the range (0 at `lo`, 1 at `hi`), as `--set` takes it;
    /// for a field of whole numbers (`integer`), rounded to the nearest one.
    fn value_at(&self, t: f64, integer: bool) -> String {
        let x = self.lo + t * (self.hi - self.lo);
        let x = if integer { x.round() } else { x };
        if self.unit.is_empty() { format!("{x}") } else { format!("{x} {}", self.unit) }
    }
}

/// A centred Latin hypercube of `n` points in `dims` dimensions, seeded: in every dimension the
/// `n` points fall one in each of the `n` equal strata, at the stratum's centre, in an order
/// drawn (Fisher-Yates, ChaCha8 seeded with `seed` and the dimension) independently per dimension.
/// Returns `points[i][d]`, fractions in (0, 1).
pub fn latin_hypercube(n: usize, dims: usize, seed: u64) -> Vec<Vec<f64>> {
    use rand::{Rng, SeedableRng};
    let mut points = vec![vec![0.0; dims]; n];
    for d in 0..dims {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(0x4c48_5300 + d as u64);
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = rng.random_range(0..=i);
            order.swap(i, j);
        }
        for (i, p) in points.iter_mut().enumerate() {
            p[d] = (order[i] as f64 + 0.5) / n as f64;
        }
    }
    points
}

/// Splits `V1,V2,...` at the commas outside brackets, braces and quotes (a value may be a JSON
/// array or a quoted string with commas).
fn split_values(s: &str) -> Vec<String> {
    let (mut out, mut cur, mut depth, mut quote) = (Vec::new(), String::new(), 0i32, None::<char>);
    for c in s.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth -= 1,
            (None, ',') if depth == 0 => {
                out.push(std::mem::take(&mut cur).trim().to_string());
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    out.push(cur.trim().to_string());
    out
}

impl Vary {
    /// Parses `PATH=V1,V2,...`. The count is checked before the values are compared (a list of
    /// more than [`MAX_DESIGNS`] values can never run), and values are compared by what they mean
    /// ([`Vary::check_values`]), in O(n log n).
    pub fn parse(s: &str) -> Result<Vary, StudyError> {
        let shown = stiction_scenario::truncate(s, 60);
        let bad = |m: &str| StudyError::Setting(format!("--vary {shown:?}: {m}"));
        let (path, values) = s.split_once('=').ok_or_else(|| bad("expected PATH=V1,V2,..."))?;
        let path = path.trim();
        if path.is_empty() {
            return Err(bad("the field path before `=` is empty"));
        }
        if let Some(range) = VaryRange::parse(values) {
            let range = range.map_err(|m| bad(&m))?;
            return Ok(Vary { path: path.to_string(), values: Vec::new(), range: Some(range), from_section: false });
        }
        let values = split_values(values);
        let v = Vary { path: path.to_string(), values, range: None, from_section: false };
        if v.values.len() > MAX_DESIGNS {
            return Err(StudyError::Setting(format!(
                "{}: {} values, more than the limit of {MAX_DESIGNS} designs",
                v.flag(),
                v.values.len()
            )));
        }
        if let Some(k) = v.values.iter().position(String::is_empty) {
            return Err(bad(&format!("value {} is empty (expected V1,V2,... without empty entries)", k + 1)));
        }
        v.check_values()?;
        Ok(v)
    }

    /// A varied field from the scenario's `design` section: `path` with its listed `values`
    /// (as `--set` takes them), or a `range` "LO..HI"; errors name `design.vary.PATH` or
    /// `design.ranges.PATH`.
    pub fn from_section(path: &str, values: Vec<String>, range: Option<&str>) -> Result<Vary, StudyError> {
        if let Some(r) = range {
            let range = VaryRange::parse(r)
                .unwrap_or_else(|| Err("expected LO..HI".into()))
                .map_err(|m| StudyError::Setting(format!("`design.ranges.{path}` = {r:?}: {m}")))?;
            return Ok(Vary { path: path.to_string(), values: Vec::new(), range: Some(range), from_section: true });
        }
        let v = Vary { path: path.to_string(), values, range: None, from_section: true };
        if v.values.len() > MAX_DESIGNS {
            return Err(StudyError::Setting(format!(
                "{}: {} values, more than the limit of {MAX_DESIGNS} designs",
                v.flag(),
                v.values.len()
            )));
        }
        v.check_values()?;
        Ok(v)
    }

    /// How the user wrote this field: `--vary PATH`, or `design.vary.PATH` / `design.ranges.PATH`
    /// of the scenario's section.
    pub fn flag(&self) -> String {
        match (self.from_section, self.range.is_some()) {
            (false, _) => format!("--vary {}", self.path),
            (true, false) => format!("`design.vary.{}`", self.path),
            (true, true) => format!("`design.ranges.{}`", self.path),
        }
    }

    /// Refuses two listed values that mean the same: the same text, or the same JSON after the
    /// `--set` parse with every quantity in SI ("7 uN" and "0.007 mN"; 30 and 30.0; objects key
    /// by key), equal to 1e-12 relative. Sorted, then neighbours compared: O(n log n).
    pub fn check_values(&self) -> Result<(), StudyError> {
        let mut canon: Vec<Canon> = self.values.iter().map(|v| Canon::of_set_text(v)).collect();
        // A bare number is SI in the field's unit: with one unit among the values, it takes it.
        let mut dims: Vec<[i8; 5]> = Vec::new();
        canon.iter().for_each(|c| c.dims(&mut dims));
        dims.sort_unstable();
        dims.dedup();
        if let [dim] = dims[..] {
            canon.iter_mut().for_each(|c| c.assume_dim(dim));
        }
        let mut order: Vec<usize> = (0..canon.len()).collect();
        order.sort_by(|&a, &b| canon[a].cmp(&canon[b]).then(a.cmp(&b)));
        for w in order.windows(2) {
            let (a, b) = (w[0].min(w[1]), w[0].max(w[1]));
            if canon[a].close(&canon[b]) {
                let (x, y) = (&self.values[a], &self.values[b]);
                let (xs, ys) = (stiction_scenario::truncate(x, 40), stiction_scenario::truncate(y, 40));
                return Err(StudyError::Setting(if x == y {
                    format!("{}: the value {xs:?} is given twice", self.flag())
                } else {
                    format!(
                        "{}: the values {xs:?} and {ys:?} are the same value ({}); give each value once",
                        self.flag(),
                        canon[a].describe()
                    )
                }));
            }
        }
        Ok(())
    }
}

/// A `--set` value as it means: the JSON `--set` reads, each number and each string that parses
/// as a quantity in SI with its dimension (to compare "7 uN" with "0.007 mN").
#[derive(Debug, Clone)]
enum Canon {
    Null,
    Bool(bool),
    Num(f64, [i8; 5]),
    Text(String),
    List(Vec<Canon>),
    Map(Vec<(String, Canon)>),
}

impl Canon {
    fn of_set_text(text: &str) -> Canon {
        let raw = text.trim();
        let value = stiction_scenario::strict_json::from_str(raw)
            .unwrap_or_else(|_| serde_json::Value::String(raw.to_string()));
        Canon::of(&value)
    }

    fn of(v: &serde_json::Value) -> Canon {
        use serde_json::Value as V;
        match v {
            V::Null => Canon::Null,
            V::Bool(b) => Canon::Bool(*b),
            V::Number(n) => Canon::Num(n.as_f64().unwrap_or(f64::NAN), [0; 5]),
            V::String(s) => match stiction_units::parse_any(s) {
                Ok((x, d)) if x.is_finite() => Canon::Num(x, d.0),
                _ => Canon::Text(s.clone()),
            },
            V::Array(a) => Canon::List(a.iter().map(Canon::of).collect()),
            // An uncertain parameter without an sd or bounds is its value (drawn as itself).
            V::Object(m) if fixed_value(m).is_some() => Canon::of(fixed_value(m).unwrap_or(&V::Null)),
            // serde_json's map is sorted by key.
            V::Object(m) => Canon::Map(m.iter().map(|(k, v)| (k.clone(), Canon::of(v))).collect()),
        }
    }

    /// The units (other than none) of the numbers in it.
    fn dims(&self, out: &mut Vec<[i8; 5]>) {
        match self {
            Canon::Num(_, d) if *d != [0; 5] => out.push(*d),
            Canon::List(a) => a.iter().for_each(|c| c.dims(out)),
            Canon::Map(m) => m.iter().for_each(|(_, c)| c.dims(out)),
            _ => {}
        }
    }

    /// Gives its bare numbers the unit `dim`.
    fn assume_dim(&mut self, dim: [i8; 5]) {
        match self {
            Canon::Num(_, d) if *d == [0; 5] => *d = dim,
            Canon::List(a) => a.iter_mut().for_each(|c| c.assume_dim(dim)),
            Canon::Map(m) => m.iter_mut().for_each(|(_, c)| c.assume_dim(dim)),
            _ => {}
        }
    }

    fn rank(&self) -> u8 {
        match self {
            Canon::Null => 0,
            Canon::Bool(_) => 1,
            Canon::Num(..) => 2,
            Canon::Text(_) => 3,
            Canon::List(_) => 4,
            Canon::Map(_) => 5,
        }
    }

    /// A total order (numbers by dimension, then value).
    fn cmp(&self, other: &Canon) -> std::cmp::Ordering {
        use std::cmp::Ordering;
        match (self, other) {
            (Canon::Bool(a), Canon::Bool(b)) => a.cmp(b),
            (Canon::Num(x, d), Canon::Num(y, e)) => d.cmp(e).then(x.total_cmp(y)),
            (Canon::Text(a), Canon::Text(b)) => a.cmp(b),
            (Canon::List(a), Canon::List(b)) => {
                a.iter().zip(b).map(|(x, y)| x.cmp(y)).find(|o| *o != Ordering::Equal).unwrap_or(a.len().cmp(&b.len()))
            }
            (Canon::Map(a), Canon::Map(b)) => a
                .iter()
                .zip(b)
                .map(|((k, x), (l, y))| k.cmp(l).then_with(|| x.cmp(y)))
                .find(|o| *o != Ordering::Equal)
                .unwrap_or(a.len().cmp(&b.len())),
            _ => self.rank().cmp(&other.rank()),
        }
    }

    /// Equal, numbers to 1e-12 relative.
    fn close(&self, other: &Canon) -> bool {
        match (self, other) {
            (Canon::Null, Canon::Null) => true,
            (Canon::Bool(a), Canon::Bool(b)) => a == b,
            (Canon::Num(x, d), Canon::Num(y, e)) => d == e && (x == y || (x - y).abs() <= 1e-12 * x.abs().max(y.abs())),
            (Canon::Text(a), Canon::Text(b)) => a == b,
            (Canon::List(a), Canon::List(b)) => a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.close(y)),
            (Canon::Map(a), Canon::Map(b)) => {
                a.len() == b.len() && a.iter().zip(b).all(|((k, x), (l, y))| k == l && x.close(y))
            }
            _ => false,
        }
    }

    /// A short description for a message: the SI number, or "the same JSON".
    fn describe(&self) -> String {
        match self {
            Canon::Num(x, _) => format!("{x:e} in SI units"),
            _ => "the same JSON once units are read".into(),
        }
    }

    /// A key for hashing: numbers to 12 significant digits.
    fn key(&self, out: &mut String) {
        use std::fmt::Write;
        match self {
            Canon::Null => out.push('n'),
            Canon::Bool(b) => out.push(if *b { 't' } else { 'f' }),
            Canon::Num(x, d) => {
                let _ = write!(out, "#{x:.11e}{d:?}");
            }
            Canon::Text(s) => {
                let _ = write!(out, "{s:?}");
            }
            Canon::List(a) => {
                out.push('[');
                for x in a {
                    x.key(out);
                    out.push(',');
                }
                out.push(']');
            }
            Canon::Map(m) => {
                out.push('{');
                for (k, x) in m {
                    let _ = write!(out, "{k:?}:");
                    x.key(out);
                    out.push(',');
                }
                out.push('}');
            }
        }
    }
}

/// Largest number of varied fields in one design study.
pub const MAX_VARIED_FIELDS: usize = 32;

/// Why a design study cannot vary the field at `path` (dotted): a field the study overrides in
/// every sample or never reads, so its designs would run the same study. `vary_surface`: the
/// study gives each sample its own surface (no `--fixed-surface`).
pub fn ignored_field(path: &str, vary_surface: bool) -> Option<&'static str> {
    let segments: Vec<&str> = path.split('.').collect();
    match segments.as_slice() {
        ["description", ..] => Some("only printed: no result of a study depends on it"),
        ["format_version", ..] => Some("the file format's version, not a property of the device"),
        ["design", ..] => Some("the design study itself, not the device; a design cannot vary it"),
        ["actuators", _, "description", ..] => Some("only printed: no result of a study depends on it"),
        ["reference", ..] => Some(
            "a measured value drawn beside the results; no sample of a study reads it, so every design would run the same",
        ),
        ["measured", ..] => Some("the measured voltages `stiction run` compares with; a study never reads them"),
        ["surface", "seed", ..] if vary_surface => Some(
            "a study gives sample i the surface seed --seed + i, replacing it in every design; add --fixed-surface to \
             keep the file's surface (then its seed counts)",
        ),
        _ => None,
    }
}

/// Whether dotted path `a` is `b` or a parent of it (segment by segment: `a.b` is a parent of
/// `a.b.c`, not of `a.bc`).
fn covers(a: &str, b: &str) -> bool {
    b == a || (b.len() > a.len() && b.starts_with(a) && b.as_bytes()[a.len()] == b'.')
}

/// The checks of the varied fields, before any value is expanded: at most
/// [`MAX_VARIED_FIELDS`], no field that the study ignores ([`ignored_field`]), no field varied
/// twice or inside another varied field (the parent's value would replace the child's), and no
/// field that a `--set` also writes (the same field, a parent or a child: one source of truth).
pub fn check_fields(varies: &[Vary], sets: &[String], vary_surface: bool) -> Result<(), StudyError> {
    if varies.len() > MAX_VARIED_FIELDS {
        return Err(StudyError::Setting(format!(
            "--vary: {} varied fields, more than the limit of {MAX_VARIED_FIELDS}",
            varies.len()
        )));
    }
    for v in varies {
        if let Some(why) = ignored_field(&v.path, vary_surface) {
            return Err(StudyError::Setting(format!("{}: cannot be varied: {why}", v.flag())));
        }
    }
    // Sorted by path, a parent comes right before its children (and a repeat beside its twin).
    let mut order: Vec<usize> = (0..varies.len()).collect();
    order.sort_by(|&a, &b| varies[a].path.split('.').cmp(varies[b].path.split('.')).then(a.cmp(&b)));
    for w in order.windows(2) {
        let (p, c) = (&varies[w[0]], &varies[w[1]]);
        if p.path == c.path {
            let (a, b) = (&varies[w[0].min(w[1])], &varies[w[0].max(w[1])]);
            return Err(StudyError::Setting(format!("{} and {}: the field is varied twice", a.flag(), b.flag())));
        }
        if covers(&p.path, &c.path) {
            return Err(StudyError::Setting(format!(
                "{} and {}: the first contains the second, so its value would replace the second's and designs \
                 labelled differently would run the same scenario; vary one of them",
                p.flag(),
                c.flag()
            )));
        }
    }
    let mut set_paths: Vec<(&str, &String)> =
        sets.iter().filter_map(|s| s.split_once('=').map(|(p, _)| (p.trim(), s))).collect();
    set_paths.sort_unstable();
    for v in varies {
        // A --set of the same field, a parent or a child (binary search: the parents are the
        // prefixes of the path; the children sort right after it).
        let segs: Vec<&str> = v.path.split('.').collect();
        let parent = (1..=segs.len()).find_map(|k| {
            let p = segs[..k].join(".");
            set_paths.binary_search_by(|(q, _)| (*q).cmp(p.as_str())).ok().map(|i| set_paths[i].1)
        });
        let start = set_paths.partition_point(|(q, _)| *q <= v.path.as_str());
        let child = set_paths[start..]
            .iter()
            .take_while(|(q, _)| q.starts_with(v.path.as_str()))
            .find(|(q, _)| covers(&v.path, q))
            .map(|s| s.1);
        if let Some(s) = parent.or(child) {
            let s = stiction_scenario::truncate(s, 80);
            return Err(StudyError::Setting(format!(
                "{} and --set {s}: the field is both set and varied (the --set writes it, a field inside it or \
                 one around it); one source of truth: set it in the file or vary it, not both",
                v.flag()
            )));
        }
    }
    Ok(())
}

/// The design points: every combination of the varied values, the first `--vary` slowest.
/// Checks first, in linear or O(n log n) time: the number of designs against [`MAX_DESIGNS`],
/// then the fields ([`check_fields`]: overlaps, `--set`s, ignored fields). `vary_surface`: the
/// study gives each sample its own surface (no `--fixed-surface`).
///
/// Ranges (`PATH=LO..HI`) take `design_points` values each from one centred Latin hypercube over
/// all ranges (seeded by `seed`, so the same command gives the same designs): the ranges vary
/// together over `design_points` points, crossed with the grid of the listed values. On return
/// each range's [`Vary::values`] holds its values in design order of the hypercube.
pub fn grid(
    varies: &mut [Vary],
    sets: &[String],
    design_points: Option<usize>,
    seed: u64,
    vary_surface: bool,
) -> Result<Vec<Vec<String>>, StudyError> {
    let ranged: Vec<usize> = (0..varies.len()).filter(|&k| varies[k].range.is_some()).collect();
    let lhs_points = match (ranged.is_empty(), design_points) {
        (true, None) => 1,
        (true, Some(_)) => {
            return Err(StudyError::Setting("--design-points needs a range to fill: --vary \"PATH=LO..HI\"".into()));
        }
        (false, None) => {
            return Err(StudyError::Setting(
                "--vary PATH=LO..HI (a range) needs --design-points N, the number of space-filling design points"
                    .into(),
            ));
        }
        (false, Some(n)) if !(2..=MAX_DESIGNS).contains(&n) => {
            return Err(StudyError::Setting(format!("--design-points {n}: expected 2 to {MAX_DESIGNS}")));
        }
        (false, Some(n)) => n,
    };
    let count = varies
        .iter()
        .filter(|v| v.range.is_none())
        .try_fold(lhs_points, |n, v| n.checked_mul(v.values.len()))
        .unwrap_or(usize::MAX);
    if count > MAX_DESIGNS {
        let shown = if count == usize::MAX { "too many".to_string() } else { count.to_string() };
        return Err(StudyError::Setting(format!(
            "--vary: {shown} design points, more than the limit of {MAX_DESIGNS}; vary fewer fields or values"
        )));
    }
    check_fields(varies, sets, vary_surface)?;
    // The ranges' values, one per hypercube point.
    if !ranged.is_empty() {
        let cube = latin_hypercube(lhs_points, ranged.len(), seed);
        for (d, &k) in ranged.iter().enumerate() {
            let range = varies[k].range.clone().expect("a ranged field");
            // A count (the schema's integer) takes the hypercube's values rounded; its range must
            // hold at least one whole number per design point.
            let integer = stiction_scenario::Scenario::field_is_integer(&varies[k].path);
            if integer {
                let whole = (range.hi.floor() - range.lo.ceil() + 1.0).max(0.0);
                if !range.unit.is_empty() || whole < lhs_points as f64 {
                    return Err(StudyError::Setting(format!(
                        "--vary {}={}..{}: the field takes whole numbers without a unit, and the range needs at \
                         least {lhs_points} of them (one per --design-points)",
                        varies[k].path, range.lo, range.hi
                    )));
                }
            }
            varies[k].values = cube.iter().map(|p| range.value_at(p[d], integer)).collect();
        }
    }
    // The grid: the listed fields crossed (first --vary slowest), the ranges moving together
    // through the hypercube's points at the position of the first range.
    let mut points: Vec<(Vec<String>, usize)> = vec![(vec![String::new(); varies.len()], 0)];
    for (k, v) in varies.iter().enumerate() {
        if v.range.is_some() {
            if ranged.first() != Some(&k) {
                continue;
            }
            points = points.into_iter().flat_map(|(p, _)| (0..lhs_points).map(move |i| (p.clone(), i))).collect();
            continue;
        }
        points = points
            .into_iter()
            .flat_map(|(p, i)| {
                v.values.iter().map(move |x| {
                    let mut q = p.clone();
                    q[k] = x.clone();
                    (q, i)
                })
            })
            .collect();
    }
    Ok(points
        .into_iter()
        .map(|(mut p, i)| {
            for &k in &ranged {
                p[k] = varies[k].values[i].clone();
            }
            p
        })
        .collect())
}

/// The `--set`s of one design point: the user's, then `PATH=V` for each varied field.
pub fn sets_for(sets: &[String], varies: &[Vary], point: &[String]) -> Vec<String> {
    let mut all = sets.to_vec();
    all.extend(varies.iter().zip(point).map(|(v, x)| format!("{}={x}", v.path)));
    all
}

/// The scenario of each design as the study reads it: `base` (the scenario's JSON after the
/// user's `--set`s) without its `design` section, then `PATH=V` of every varied field applied as
/// `--set` applies it. Errors name the design and the field.
pub fn design_scenarios(
    base: &serde_json::Value,
    varies: &[Vary],
    points: &[Vec<String>],
) -> Result<Vec<serde_json::Value>, StudyError> {
    let mut base = base.clone();
    if let Some(m) = base.as_object_mut() {
        m.remove("design");
    }
    points
        .iter()
        .enumerate()
        .map(|(d, p)| {
            let mut v = base.clone();
            for (vary, x) in varies.iter().zip(p) {
                stiction_scenario::apply_set(&mut v, &format!("{}={x}", vary.path))
                    .map_err(|e| StudyError::Setting(format!("design {d} ({}): {e}", label(varies, p))))?;
            }
            Ok(v)
        })
        .collect()
}

/// `PATH=V, PATH=V` of a design point.
pub fn label(varies: &[Vary], point: &[String]) -> String {
    varies.iter().zip(point).map(|(v, x)| format!("{}={x}", v.path)).collect::<Vec<_>>().join(", ")
}

/// Refuses two designs whose studies would be the same: their scenarios ([`design_scenarios`]),
/// read as the study reads them, are equal: the typed scenario (every quantity in SI, every
/// default filled in) and every uncertain parameter (its value, sd, distribution and bounds in
/// SI, to 12 significant digits), without the fields a study ignores ([`ignored_field`]). A
/// scenario that does not parse is compared as its JSON with units read (its design is refused
/// when it is prepared). A safety net under [`check_fields`] and [`Vary::check_values`] (it
/// catches, say, a value equal to the field's default beside `null`); hashed, linear in the
/// number of designs.
pub fn check_distinct(
    base: &serde_json::Value,
    varies: &[Vary],
    points: &[Vec<String>],
    vary_surface: bool,
) -> Result<(), StudyError> {
    let scenarios = design_scenarios(base, varies, points)?;
    let mut seen: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    for (d, s) in scenarios.into_iter().enumerate() {
        let key = study_key(s, vary_surface);
        if let Some(&e) = seen.get(&key) {
            return Err(StudyError::Setting(format!(
                "designs {e} ({}) and {d} ({}) run the same study (equal once units, defaults and the fields a \
                 study ignores are read); vary values that differ",
                stiction_scenario::truncate(&label(varies, &points[e]), 70),
                stiction_scenario::truncate(&label(varies, &points[d]), 70)
            )));
        }
        seen.insert(key, d);
    }
    Ok(())
}

/// Whether a JSON object is an uncertain parameter (`value` and only the uncertain keys).
fn is_uncertain(m: &serde_json::Map<String, serde_json::Value>) -> bool {
    m.contains_key("value") && m.keys().all(|k| ["value", "sd", "distribution", "min", "max"].contains(&k.as_str()))
}

/// The value of an uncertain parameter that has no spread (`{"value": X}`, with at most a
/// `distribution`: drawn as X itself).
fn fixed_value(m: &serde_json::Map<String, serde_json::Value>) -> Option<&serde_json::Value> {
    (is_uncertain(m) && !m.contains_key("sd") && !m.contains_key("min") && !m.contains_key("max"))
        .then(|| m.get("value"))
        .flatten()
}

/// Appends every uncertain parameter of `v` (path and its object with units read) to `key`.
fn uncertain_key(v: &serde_json::Value, path: &str, key: &mut String) {
    use serde_json::Value;
    match v {
        Value::Object(m) if fixed_value(m).is_some() => {}
        Value::Object(m) if is_uncertain(m) => {
            key.push_str(path);
            key.push('=');
            Canon::of(v).key(key);
            key.push(';');
        }
        Value::Object(m) => m.iter().for_each(|(k, x)| uncertain_key(x, &format!("{path}.{k}"), key)),
        Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| uncertain_key(x, &format!("{path}.{i}"), key)),
        _ => {}
    }
}

/// Drops the fields a study ignores ([`ignored_field`]) from a scenario tree (JSON or typed).
fn strip_ignored(v: &mut serde_json::Value, vary_surface: bool) {
    use serde_json::Value;
    if let Some(m) = v.as_object_mut() {
        m.retain(|k, _| ignored_field(k, vary_surface).is_none());
        if vary_surface && let Some(surface) = m.get_mut("surface").and_then(Value::as_object_mut) {
            surface.remove("seed");
        }
        if let Some(a) = m.get_mut("actuators").and_then(Value::as_object_mut) {
            for spec in a.values_mut().filter_map(Value::as_object_mut) {
                spec.remove("description");
            }
        }
    }
}

/// What a study of scenario `s` depends on, as a text key (see [`check_distinct`]).
fn study_key(mut s: serde_json::Value, vary_surface: bool) -> String {
    let typed = stiction_scenario::Scenario::from_value(s.clone(), std::path::Path::new("design"));
    strip_ignored(&mut s, vary_surface);
    let mut key = String::new();
    match typed {
        Ok(typed) => {
            let mut t = serde_json::to_value(&typed).unwrap_or(serde_json::Value::Null);
            strip_ignored(&mut t, vary_surface);
            key.push_str("typed:");
            Canon::of(&t).key(&mut key);
            // The uncertain parameters (the typed scenario holds their nominal values only).
            key.push_str("|uncertain:");
            uncertain_key(&s, "", &mut key);
        }
        Err(_) => {
            key.push_str("json:");
            Canon::of(&s).key(&mut key);
        }
    }
    key
}

/// One design point's results.
#[derive(Debug, Clone, Serialize)]
pub struct DesignRow {
    /// Design number (0-based, grid order); its study is in the folder `design-NNN`.
    pub design: usize,
    /// The varied fields and their values, as given.
    pub values: BTreeMap<String, String>,
    /// Samples in the design's log.
    pub samples: usize,
    /// Samples with a usable eq. 10 line.
    pub with_fit: usize,
    /// `with_fit / samples`.
    pub usable_fraction: f64,
    /// Its binomial standard error `sqrt(f (1 - f) / n)`.
    pub usable_fraction_se: f64,
    /// Count of each reason for a sample without a line.
    pub reasons: BTreeMap<String, usize>,
    /// Spread of mu_e,a.
    pub mu_apparent: Option<Spread>,
    /// Spread of F_a0, N.
    pub apparent_adhesion_force_n: Option<Spread>,
    /// Width of the 5-95 % interval of mu_e,a over the virtual meters, p95 - p05.
    pub mu_interval_width: Option<f64>,
    /// Its standard error, from the order-statistic intervals of p05 and p95 (each half-width /
    /// 1.96, added in quadrature).
    pub mu_interval_width_se: Option<f64>,
    /// Widths of the 95 % intervals the lab quotes for each experiment's eq. 10 fit, without and
    /// with the calibration uncertainty (spreads over the experiments with a fit).
    pub lab_intervals: crate::summary::LabIntervals,
    /// The interface's own coefficient `s / p_mean` of each experiment's device
    /// ([`crate::interface_mu`]), over the experiments with a fit.
    pub interface_mu: Option<Spread>,
    /// Per-experiment bias `mu_e,a - s / p_mean` (each against its own device's coefficient).
    pub mu_bias_spread: Option<Spread>,
    /// Median of the per-experiment bias.
    pub mu_bias: Option<f64>,
    /// Its standard error (from the median's order-statistic interval).
    pub mu_bias_se: Option<f64>,
    /// Why a value of the row is null: too few experiments with a fit (or with a bound on a
    /// percentile) to give it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<&'static str>,
}

/// Half-width / 1.96 of a 95 % interval: a standard error.
fn se_of(ci: Option<[f64; 2]>) -> Option<f64> {
    ci.map(|[a, b]| (b - a) / (2.0 * 1.96))
}

impl DesignRow {
    /// The row of design `design` at the point `values` from its study summary.
    pub fn new(design: usize, varies: &[Vary], point: &[String], summary: &StudySummary) -> DesignRow {
        let n = summary.samples_done;
        let f = if n > 0 { summary.with_fit as f64 / n as f64 } else { 0.0 };
        let mu = summary.mu_apparent.clone();
        let width = mu.as_ref().map(|s| s.p95 - s.p05);
        let width_se = mu.as_ref().and_then(|s| Some(se_of(s.p05_ci)?.hypot(se_of(s.p95_ci)?)));
        let bias = summary.mu_bias.clone();
        DesignRow {
            design,
            values: varies.iter().zip(point).map(|(v, x)| (v.path.clone(), x.clone())).collect(),
            samples: n,
            with_fit: summary.with_fit,
            usable_fraction: f,
            usable_fraction_se: if n > 0 { (f * (1.0 - f) / n as f64).sqrt() } else { 0.0 },
            reasons: summary.reasons.clone(),
            mu_bias: bias.as_ref().map(|b| b.median),
            mu_bias_se: bias.as_ref().and_then(|b| se_of(b.median_ci)),
            mu_bias_spread: bias,
            lab_intervals: summary.lab_intervals.clone(),
            interface_mu: summary.interface_mu.clone(),
            mu_apparent: mu,
            apparent_adhesion_force_n: summary.apparent_adhesion_force_n.clone(),
            mu_interval_width: width,
            mu_interval_width_se: width_se,
            note: None,
        }
        .with_note()
    }

    fn with_note(mut self) -> DesignRow {
        let nulls = [self.mu_interval_width, self.mu_interval_width_se, self.mu_bias, self.mu_bias_se]
            .iter()
            .any(Option::is_none)
            || self.mu_apparent.is_none()
            || self.apparent_adhesion_force_n.is_none()
            || self.interface_mu.is_none()
            || self.mu_bias_spread.is_none();
        self.note = nulls.then_some(
            "null where the design's study has too few experiments with a fit to give the value (or to bound \
             a percentile of it)",
        );
        self
    }
}

/// What ranks the designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RankBy {
    /// Smallest 5-95 % width of mu_e,a first.
    Narrowest,
    /// Smallest |median mu_e,a - interface coefficient| first.
    LeastBias,
    /// Largest fraction of usable experiments first.
    MostUsable,
}

impl RankBy {
    /// The criterion's value of a row (smaller is better), None: the row cannot be ranked by it.
    pub fn key(self, r: &DesignRow) -> Option<f64> {
        match self {
            RankBy::Narrowest => r.mu_interval_width,
            RankBy::LeastBias => r.mu_bias.map(f64::abs),
            RankBy::MostUsable => Some(-r.usable_fraction),
        }
    }

    /// The design numbers, best first; rows without a value last, in design order; ties by
    /// design order.
    pub fn rank(self, rows: &[DesignRow]) -> Vec<usize> {
        let mut order: Vec<usize> = (0..rows.len()).collect();
        order.sort_by(|&a, &b| match (self.key(&rows[a]), self.key(&rows[b])) {
            (Some(x), Some(y)) => x.total_cmp(&y).then(a.cmp(&b)),
            (Some(_), None) => std::cmp::Ordering::Less,
            (None, Some(_)) => std::cmp::Ordering::Greater,
            (None, None) => a.cmp(&b),
        });
        order
    }
}

/// designs.csv: one row per design, the varied values first (columns named by their paths),
/// then the results; an empty cell where a value cannot be given.
pub fn designs_csv(varies: &[Vary], rows: &[DesignRow]) -> Result<Vec<u8>, StudyError> {
    let err = |e: &dyn std::fmt::Display| StudyError::Log(format!("formatting designs.csv: {e}"));
    let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    let mut head = vec!["design".to_string()];
    head.extend(varies.iter().map(|v| v.path.clone()));
    head.extend(
        [
            "samples",
            "with_fit",
            "usable_fraction",
            "usable_fraction_se",
            "reasons",
            "mu_median",
            "mu_median_ci_low",
            "mu_median_ci_high",
            "mu_p05",
            "mu_p95",
            "mu_interval_width",
            "mu_interval_width_se",
            "mu_mean",
            "mu_mean_se",
            "mu_sd",
            "fa0_median_n",
            "fa0_p05_n",
            "fa0_p95_n",
            "fa0_sd_n",
            "mu_ci95_width",
            "mu_ci95_width_with_calibration",
            "fa0_ci95_width_n",
            "fa0_ci95_width_with_calibration_n",
            "interface_mu",
            "mu_bias",
            "mu_bias_se",
            "mu_bias_mean",
            "mu_bias_mean_se",
            "mu_bias_p05",
            "mu_bias_p95",
        ]
        .map(String::from),
    );
    w.write_record(&head).map_err(|e| err(&e))?;
    let o = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    for r in rows {
        let mut f = vec![r.design.to_string()];
        f.extend(varies.iter().map(|v| r.values.get(&v.path).cloned().unwrap_or_default()));
        let m = r.mu_apparent.as_ref();
        let fa = r.apparent_adhesion_force_n.as_ref();
        let li = &r.lab_intervals;
        let b = r.mu_bias_spread.as_ref();
        let reasons: Vec<String> = r.reasons.iter().map(|(k, n)| format!("{k}:{n}")).collect();
        f.extend([
            r.samples.to_string(),
            r.with_fit.to_string(),
            format!("{:e}", r.usable_fraction),
            format!("{:e}", r.usable_fraction_se),
            reasons.join(";"),
            o(m.map(|s| s.median)),
            o(m.and_then(|s| s.median_ci).map(|c| c[0])),
            o(m.and_then(|s| s.median_ci).map(|c| c[1])),
            o(m.map(|s| s.p05)),
            o(m.map(|s| s.p95)),
            o(r.mu_interval_width),
            o(r.mu_interval_width_se),
            o(m.map(|s| s.mean)),
            o(m.map(|s| s.mean_se)),
            o(m.map(|s| s.sd)),
            o(fa.map(|s| s.median)),
            o(fa.map(|s| s.p05)),
            o(fa.map(|s| s.p95)),
            o(fa.map(|s| s.sd)),
            o(li.mu_ci95_width.as_ref().map(|s| s.median)),
            o(li.mu_ci95_width_with_calibration.as_ref().map(|s| s.median)),
            o(li.fa0_ci95_width_n.as_ref().map(|s| s.median)),
            o(li.fa0_ci95_width_with_calibration_n.as_ref().map(|s| s.median)),
            o(r.interface_mu.as_ref().map(|i| i.median)),
            o(r.mu_bias),
            o(r.mu_bias_se),
            o(b.map(|s| s.mean)),
            o(b.map(|s| s.mean_se)),
            o(b.map(|s| s.p05)),
            o(b.map(|s| s.p95)),
        ]);
        w.write_record(&f).map_err(|e| err(&e))?;
    }
    w.into_inner().map_err(|e| err(&e))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A range's ends take a unit with or without a space, as `--set` does ("1nm..2nm" as "1 nm..2 nm").
    #[test]
    fn range_ends_take_units_with_or_without_a_space() {
        for text in ["1nm..2nm", "1 nm..2 nm", " 1 nm .. 2nm "] {
            let r = VaryRange::parse(text).unwrap().unwrap();
            assert_eq!((r.lo, r.hi, r.unit.as_str()), (1.0, 2.0, "nm"), "{text}");
        }
        let r = VaryRange::parse("2.5e-1..1e0").unwrap().unwrap();
        assert_eq!((r.lo, r.hi, r.unit.as_str()), (0.25, 1.0, ""));
        let r = VaryRange::parse("20V..4e1 V").unwrap().unwrap();
        assert_eq!((r.lo, r.hi, r.unit.as_str()), (20.0, 40.0, "V"));
        for bad in ["nm..2nm", "inf..2", "1..nan", "..", "1 nm..2 um"] {
            assert!(VaryRange::parse(bad).unwrap().is_err(), "{bad}");
        }
    }

    #[test]
    fn values_split_at_top_level_commas_only() {
        let v = Vary::parse("actuators.clamp.plate_count=30,60").unwrap();
        assert_eq!(
            (v.path.as_str(), v.values.clone()),
            ("actuators.clamp.plate_count", vec!["30".into(), "60".into()])
        );
        let v = Vary::parse(r#"x=[1,2],"a,b", 3 N/m"#).unwrap();
        assert_eq!(v.values, vec!["[1,2]", r#""a,b""#, "3 N/m"]);
        assert!(Vary::parse("x=1,,2").unwrap_err().to_string().contains("value 2 is empty"));
        assert!(Vary::parse("x").unwrap_err().to_string().contains("PATH=V1,V2"));
        assert!(Vary::parse("x=1,1").unwrap_err().to_string().contains("twice"));
    }

    /// Hostile --vary text (brackets, quotes, commas, `=` in any order, unbalanced): an answer,
    /// never a panic; an accepted value list has no empty value and no repeat.
    #[test]
    fn any_vary_text_is_parsed_or_refused_without_a_panic() {
        use rand::{Rng, SeedableRng};
        let alphabet: Vec<char> = "ab.=,[]{}\"' 1-".chars().collect();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for _ in 0..20_000 {
            let len = rng.random_range(0..16);
            let text: String = (0..len).map(|_| alphabet[rng.random_range(0..alphabet.len())]).collect();
            if let Ok(v) = Vary::parse(&text) {
                assert!(!v.path.is_empty() && v.values.iter().all(|x| !x.is_empty()), "{text:?} -> {v:?}");
                let _ = grid(&mut [v.clone()], &[], Some(3), 1, true);
                let _ = grid(&mut [v], &[], None, 1, true);
            }
        }
    }

    #[test]
    fn ranking_puts_the_best_first_and_rows_without_a_value_last() {
        let summary = |with_fit: usize, width: Option<(f64, f64)>, bias: Option<f64>| {
            let mut mu = Spread::of(&[0.5, 0.6, 0.7]).unwrap();
            if let Some((a, b)) = width {
                (mu.p05, mu.p95) = (a, b);
            }
            StudySummary {
                statistics_method: String::new(),
                scenario: String::new(),
                scenario_hash: String::new(),
                config: crate::summary::ConfigSummary {
                    samples: 10,
                    seed: 1,
                    vary_surface: true,
                    shard: "0/1".into(),
                    calibration: crate::Calibration::Nominal,
                    slip_path: stiction_meter::SlipPath::Light,
                },
                samples_done: 10,
                with_fit,
                without_fit: 10 - with_fit,
                failed: 0,
                reasons: BTreeMap::new(),
                reduction: crate::summary::ReductionSummary {
                    a_clamp_n_per_v2: 1.0,
                    a_pull_n_per_v2: 1.0,
                    spring_force_n: 1.0,
                },
                mu_apparent: width.map(|_| mu),
                apparent_adhesion_force_n: None,
                lab_intervals: Default::default(),
                interface_mu: None,
                mu_bias: bias.and_then(|b| Spread::of(&[b - 0.1, b, b + 0.1])),
                sensitivity: crate::sensitivity::table(&[], &[], &[], &[], true),
                note: None,
                reference: None,
            }
        };
        let v = [Vary::parse("a=1,2,3").unwrap()];
        let rows = vec![
            DesignRow::new(0, &v, &["1".into()], &summary(5, Some((0.2, 1.0)), Some(-0.3))),
            DesignRow::new(1, &v, &["2".into()], &summary(0, None, None)),
            DesignRow::new(2, &v, &["3".into()], &summary(9, Some((0.5, 0.7)), None)),
        ];
        assert_eq!(RankBy::Narrowest.rank(&rows), vec![2, 0, 1]);
        assert_eq!(RankBy::MostUsable.rank(&rows), vec![2, 0, 1]);
        // Only design 0 has a per-experiment bias (median -0.3).
        assert_eq!(RankBy::LeastBias.rank(&rows), vec![0, 1, 2]);
        assert!((rows[0].mu_bias.unwrap() + 0.3).abs() < 1e-12);
        let csv = String::from_utf8(designs_csv(&v, &rows).unwrap()).unwrap();
        assert_eq!(csv.lines().count(), 4);
        assert!(csv.lines().nth(2).unwrap().starts_with("1,2,10,0,0e0,"), "{csv}");
    }

    #[test]
    fn the_grid_is_every_combination_first_vary_slowest() {
        let a = Vary::parse("a=1,2").unwrap();
        let b = Vary::parse("b=x,y,z").unwrap();
        let g = grid(&mut [a.clone(), b.clone()], &[], None, 1, true).unwrap();
        assert_eq!(g.len(), 6);
        assert_eq!(g[0], vec!["1", "x"]);
        assert_eq!(g[1], vec!["1", "y"]);
        assert_eq!(g[3], vec!["2", "x"]);
        assert_eq!(sets_for(&["c=3".into()], &[a.clone(), b.clone()], &g[5]), vec!["c=3", "a=2", "b=z"]);
        assert!(
            grid(&mut [a.clone()], &["a=5".into()], None, 1, true)
                .unwrap_err()
                .to_string()
                .contains("one source of truth")
        );
        assert!(grid(&mut [a.clone(), a.clone()], &[], None, 1, true).unwrap_err().to_string().contains("twice"));
        let many = Vary::parse(&format!("m={}", (0..40).map(|i| i.to_string()).collect::<Vec<_>>().join(","))).unwrap();
        let e =
            grid(&mut [many.clone(), Vary { path: "n".into(), ..many }], &[], None, 1, true).unwrap_err().to_string();
        assert!(e.contains("1600 design points") && e.contains("1000"), "{e}");
    }

    /// Overlapping fields (a parent beside its child, a field twice, a --set of the same field, a
    /// parent or a child), equal values in two units or as equal objects, fields a study ignores:
    /// refused naming both; a field `a.bc` is not a child of `a.b`. A list past the limit is
    /// refused by its count, in linear time. Deliberate bug caught: a parent found by a plain
    /// `starts_with` (seen failing: `a.bc` refused as a child of `a.b`).
    #[test]
    fn overlaps_equal_values_and_ignored_fields_are_refused_naming_both() {
        let g = |flags: &[&str], sets: &[&str], vary_surface: bool| -> Result<usize, String> {
            let mut v: Vec<Vary> =
                flags.iter().map(|f| Vary::parse(f)).collect::<Result<_, _>>().map_err(|e| e.to_string())?;
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            grid(&mut v, &sets, None, 1, vary_surface).map(|p| p.len()).map_err(|e| e.to_string())
        };
        let e = g(&["a.b=1,2", "a.b.c=3,4"], &[], true).unwrap_err();
        assert!(e.contains("--vary a.b and --vary a.b.c"), "{e}");
        assert_eq!(g(&["a.b=1,2", "a.bc=3,4"], &[], true), Ok(4));
        let e = g(&["a.b=1,2"], &["a=3"], true).unwrap_err();
        assert!(e.contains("--vary a.b and --set a=3"), "{e}");
        let e = g(&["a.b=1,2"], &["a.b.c=3"], true).unwrap_err();
        assert!(e.contains("--set a.b.c=3"), "{e}");
        assert_eq!(g(&["a.b=1,2"], &["a.bc=3"], true), Ok(2));
        for (flag, both) in [
            ("f=7 uN,0.007 mN", ["\"7 uN\"", "\"0.007 mN\""]),
            ("f=1 N/m,2 N/m,1000 mN/m", ["\"1 N/m\"", "\"1000 mN/m\""]),
            ("f=1,1000 mN/m", ["\"1\"", "\"1000 mN/m\""]),
            (r#"f={"value":"0.5 um"},{"value":"500 nm"}"#, ["0.5 um", "500 nm"]),
            (r#"f={"value":"0.5 um"},500 nm"#, ["0.5 um", "500 nm"]),
        ] {
            let e = Vary::parse(flag).unwrap_err().to_string();
            assert!(e.contains("--vary f") && both.iter().all(|b| e.contains(b)), "{flag}: {e}");
        }
        assert!(Vary::parse("f=7 uN,7.1 uN").is_ok());
        assert!(Vary::parse(r#"f={"value":"0.5 um","sd":"1 nm"},{"value":"0.5 um"}"#).is_ok());
        let e = g(&["surface.seed=1,2"], &[], true).unwrap_err();
        assert!(e.contains("--vary surface.seed") && e.contains("--fixed-surface"), "{e}");
        assert_eq!(g(&["surface.seed=1,2"], &[], false), Ok(2));
        for path in ["description", "reference.source", "design.points", "measured", "actuators.clamp.description"] {
            let e = g(&[&format!("{path}=1,2")], &[], true).unwrap_err();
            assert!(e.contains(&format!("--vary {path}")) && e.contains("cannot be varied"), "{e}");
        }
        let many = format!("n={}", (0..1_000_000).map(|i| i.to_string()).collect::<Vec<_>>().join(","));
        let t = std::time::Instant::now();
        let e = Vary::parse(&many).unwrap_err().to_string();
        assert!(e.contains("1000000 values") && t.elapsed().as_secs_f64() < 2.0, "{e} {:?}", t.elapsed());
    }

    /// A centred Latin hypercube (McKay, Beckman and Conover, Technometrics 21, 239 (1979)): in
    /// every dimension each of the n equal strata holds exactly one point, at its centre; the
    /// same seed gives the same points, another seed another order. Deliberate bug caught: one
    /// permutation shared by all dimensions (the points lie on the diagonal; the correlation test
    /// fails), and a stratum index off by one (a value outside the range).
    #[test]
    fn latin_hypercube_fills_every_stratum_once_in_every_dimension() {
        for (n, dims) in [(2, 1), (7, 3), (50, 4)] {
            let cube = latin_hypercube(n, dims, 11);
            assert_eq!(cube, latin_hypercube(n, dims, 11));
            for d in 0..dims {
                let mut strata: Vec<usize> = cube.iter().map(|p| (p[d] * n as f64).floor() as usize).collect();
                for p in &cube {
                    let centre = ((p[d] * n as f64).floor() + 0.5) / n as f64;
                    assert!((p[d] - centre).abs() < 1e-12 && p[d] > 0.0 && p[d] < 1.0, "{p:?}");
                }
                strata.sort_unstable();
                assert_eq!(strata, (0..n).collect::<Vec<_>>(), "dimension {d} of {n}");
            }
        }
        // Independent orders per dimension: at n = 50 the two columns are not the same permutation.
        let cube = latin_hypercube(50, 2, 11);
        assert!(cube.iter().any(|p| p[0] != p[1]));
        assert_ne!(latin_hypercube(50, 2, 11), latin_hypercube(50, 2, 12));
    }

    /// `PATH=LO..HI` ranges: parsed with their unit, filled by the hypercube, crossed with listed
    /// values; malformed ranges and a missing --design-points are refused with the reason.
    #[test]
    fn ranges_take_space_filling_values_crossed_with_the_lists() {
        let r = Vary::parse("meter.clamp_voltages.to=29 V..40 V").unwrap();
        assert_eq!(r.range, Some(VaryRange { lo: 29.0, hi: 40.0, unit: "V".into() }));
        let k = Vary::parse("k=1..3").unwrap();
        let list = Vary::parse("n=30,60").unwrap();
        let mut varies = [list, r, k];
        let g = grid(&mut varies, &[], Some(4), 7, true).unwrap();
        assert_eq!(g.len(), 8);
        // The listed field is slowest; the four hypercube points repeat for each listed value.
        assert!(g[..4].iter().all(|p| p[0] == "30") && g[4..].iter().all(|p| p[0] == "60"));
        assert_eq!(
            g[..4].iter().map(|p| &p[1..]).collect::<Vec<_>>(),
            g[4..].iter().map(|p| &p[1..]).collect::<Vec<_>>()
        );
        // Each range's four values sit one in each quarter of the range.
        let mut quarters: Vec<usize> = g[..4]
            .iter()
            .map(|p| {
                let v: f64 = p[1].strip_suffix(" V").unwrap().parse().unwrap();
                assert!((29.0..=40.0).contains(&v), "{v}");
                ((v - 29.0) / 11.0 * 4.0).floor() as usize
            })
            .collect();
        quarters.sort_unstable();
        assert_eq!(quarters, vec![0, 1, 2, 3]);
        assert_eq!(varies[1].values.len(), 4);
        for bad in ["a=40 V..29 V", "a=1 V..2 mV", "a=x..2", "a=1..inf"] {
            assert!(Vary::parse(bad).is_err(), "{bad}");
        }
        let e = grid(&mut [Vary::parse("a=1..2").unwrap()], &[], None, 1, true).unwrap_err().to_string();
        assert!(e.contains("--design-points"), "{e}");
        let e = grid(&mut [Vary::parse("a=1,2").unwrap()], &[], Some(3), 1, true).unwrap_err().to_string();
        assert!(e.contains("needs a range"), "{e}");
    }

    /// A range over a count (the schema's integer, e.g. the clamp array's plate count) gives whole
    /// numbers, one in each stratum of the range; a range with fewer whole numbers than design
    /// points, or with a unit, is refused naming the field.
    #[test]
    fn ranges_over_counts_give_whole_numbers() {
        let path = "actuators.clamp.plate_count";
        let mut varies = [Vary::parse(&format!("{path}=1..1000")).unwrap()];
        let g = grid(&mut varies, &[], Some(4), 1, true).unwrap();
        let mut quarters: Vec<usize> = g
            .iter()
            .map(|p| {
                let n: u32 = p[0].parse().unwrap_or_else(|_| panic!("{} is not a whole number", p[0]));
                ((f64::from(n) - 1.0) / 999.0 * 4.0).floor() as usize
            })
            .collect();
        quarters.sort_unstable();
        assert_eq!(quarters, vec![0, 1, 2, 3]);
        for bad in [format!("{path}=1..3"), format!("{path}=1 V..100 V")] {
            let e = grid(&mut [Vary::parse(&bad).unwrap()], &[], Some(4), 1, true).unwrap_err().to_string();
            assert!(e.contains(path) && e.contains("whole numbers"), "{e}");
        }
        // A quantity keeps the hypercube's fractions.
        let g = grid(&mut [Vary::parse("actuators.clamp.front_gap=1..1000").unwrap()], &[], Some(4), 1, true).unwrap();
        assert!(g.iter().any(|p| p[0].contains('.')), "{g:?}");
    }
}
