//! The append-only sample log `samples.log` of a study folder.
//!
//! Line 1 is `# ` and a one-line JSON [`Header`] that identifies the study (scenario fingerprint,
//! fingerprints of the files the scenario points to, program version, seed, sample count,
//! settings) and the shard; every further line is one finished sample, in index order: its row
//! of samples.csv ([`columns`]). Every line ends with a tab and its checksum (16 hex digits of
//! FNV-1a over the line before the tab), so an edited or damaged line is refused, naming it; line
//! ends are LF only (a log converted to CR LF is refused with what to do). Each line is written
//! with one `write_all` and flushed at once, so a killed study leaves at most a torn last line,
//! which [`LogWriter::resume`] cuts off. samples.csv is the column line followed by the rows
//! (without the checksums).

use std::fs::{File, OpenOptions};
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use stiction_meter::SlipPath;

use crate::calibration::Calibration;
use crate::error::StudyError;
use crate::sample_result::SampleResult;

/// Version of the log format (2: checksums on every line, input-file fingerprints and the program
/// version in the header; 3: each sample's interface coefficient and the widths of its eq. 10
/// intervals, and the calibration draws behind them in the header).
pub const FORMAT: u32 = 3;

/// The per-sample result columns after `mean_contacts` (before the drawn parameters).
pub const RESULT_COLUMNS: [&str; 5] = [
    "interface_mu",
    "mu_ci95_width",
    "mu_ci95_width_with_calibration",
    "fa0_ci95_width_n",
    "fa0_ci95_width_with_calibration_n",
];

/// Fields before the drawn parameters: sample, mu_apparent, apparent_adhesion_force_n,
/// mean_contacts and [`RESULT_COLUMNS`].
const LEAD: usize = 4 + RESULT_COLUMNS.len();

/// File name of the log in a study folder.
pub const LOG_NAME: &str = "samples.log";

/// Longest header line accepted when reading a log (bytes).
const MAX_HEADER_BYTES: u64 = 1 << 20;

/// A file the scenario points to, with the fingerprint of its content.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InputFile {
    /// The scenario field that names it (`surface.height_map.file`).
    pub field: String,
    /// The path as written in the scenario.
    pub path: String,
    /// FNV-1a (64 bit, hex) of the file's bytes.
    pub content_hash: String,
}

/// What identifies a study and one shard of it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Log format version.
    pub format: u32,
    /// The scenario file as given on the command line.
    pub scenario: String,
    /// FNV-1a fingerprint of the scenario tree after `--set`.
    pub scenario_hash: String,
    /// Samples of the whole study.
    pub samples: usize,
    /// Base seed.
    pub seed: u64,
    /// Whether each sample has its own surface.
    pub vary_surface: bool,
    /// How voltages are reduced to forces.
    pub calibration: Calibration,
    /// How the slip is followed.
    pub slip_path: SlipPath,
    /// This shard's K.
    pub shard_index: usize,
    /// M, the number of shards.
    pub shard_count: usize,
    /// The nominal reduction (a_clamp N/V^2, a_pull N/V^2, F_spring N), as exact decimal text.
    pub reduction: [String; 3],
    /// The uncertain parameters `(path, unit)`.
    pub parameters: Vec<(String, String)>,
    /// The scenario's measured reference values (its `reference` section), carried so that the
    /// outputs computed from the log alone (resume, merge) can show them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<stiction_scenario::ReferenceSpec>,
    /// The version of stiction that wrote the log.
    #[serde(default)]
    pub program_version: String,
    /// The files the scenario points to (maps, CSVs), with their content fingerprints.
    #[serde(default)]
    pub input_files: Vec<InputFile>,
    /// Calibration draws per sample behind the `*_with_calibration` interval widths (0: none).
    #[serde(default)]
    pub calibration_draws: usize,
}

impl Header {
    /// Why `other` is not a piece of the same study (None: it is). Shard and scenario path may
    /// differ (shards run on other machines).
    pub fn mismatch(&self, other: &Header) -> Option<String> {
        let files = |h: &Header| -> String {
            h.input_files
                .iter()
                .map(|f| format!("{} = {} (content {})", f.field, f.path, f.content_hash))
                .collect::<Vec<_>>()
                .join(", ")
        };
        for (a, b) in self.input_files.iter().zip(&other.input_files) {
            if a.field == b.field && a.content_hash != b.content_hash {
                return Some(format!(
                    "the file of `{}` differs: {} has content fingerprint {} vs {} has {}",
                    a.field, a.path, a.content_hash, b.path, b.content_hash
                ));
            }
        }
        let field_list = |h: &Header| h.input_files.iter().map(|f| f.field.clone()).collect::<Vec<_>>();
        if field_list(self) != field_list(other) {
            return Some(format!("input files: {} vs {}", files(self), files(other)));
        }
        let checks: [(&str, String, String); 10] = [
            ("calibration draws per sample", self.calibration_draws.to_string(), other.calibration_draws.to_string()),
            ("log format", self.format.to_string(), other.format.to_string()),
            ("program version", self.program_version.clone(), other.program_version.clone()),
            ("scenario (fingerprint of the file after --set)", self.scenario_hash.clone(), other.scenario_hash.clone()),
            ("--samples", self.samples.to_string(), other.samples.to_string()),
            ("--seed", self.seed.to_string(), other.seed.to_string()),
            ("--fixed-surface", (!self.vary_surface).to_string(), (!other.vary_surface).to_string()),
            ("--calibration", self.calibration.to_string(), other.calibration.to_string()),
            ("--slip-path", self.slip_path.to_string(), other.slip_path.to_string()),
            ("uncertain parameters", format!("{:?}", self.parameters), format!("{:?}", other.parameters)),
        ];
        checks.into_iter().find(|(_, a, b)| a != b).map(|(what, a, b)| format!("{what}: {a} vs {b}"))
    }

    /// Number of samples of this shard.
    pub fn shard_len(&self) -> usize {
        if self.shard_index >= self.samples {
            0
        } else {
            (self.samples - self.shard_index).div_ceil(self.shard_count.max(1))
        }
    }

    fn line(&self) -> String {
        String::from_utf8_lossy(&log_line(format!("# {}", serde_json::to_string(self).unwrap_or_default()).as_bytes()))
            .into_owned()
    }
}

/// The column names of samples.csv: the unit at the end of every name that holds a quantity
/// (`name_unit`, as every other CSV and JSON key: `apparent_adhesion_force_n`,
/// `surface.summit_radius_m`); pure numbers and counts have none.
pub fn columns(header: &Header) -> Vec<String> {
    let mut c =
        vec!["sample".to_string(), "mu_apparent".into(), "apparent_adhesion_force_n".into(), "mean_contacts".into()];
    c.extend(RESULT_COLUMNS.map(String::from));
    c.extend(header.parameters.iter().map(|(p, u)| stiction_units::key_with_unit(p, u)));
    c.push("reason".into());
    c.push("detail".into());
    c
}

fn csv_line(fields: &[String]) -> Result<Vec<u8>, StudyError> {
    let mut w = csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(Vec::new());
    w.write_record(fields).map_err(|e| StudyError::Log(format!("formatting a sample row: {e}")))?;
    w.into_inner().map_err(|e| StudyError::Log(format!("formatting a sample row: {e}")))
}

/// FNV-1a, 64 bit: the scenario and input-file fingerprints of the header and the line checksums.
/// Hand-written (three lines) rather than a dependency: it detects edits and damage, it does not
/// protect against deliberate tampering.
pub(crate) fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// A log line: `content` (without its newline), a tab, its checksum, a newline.
fn log_line(content: &[u8]) -> Vec<u8> {
    let content = content.strip_suffix(b"\n").unwrap_or(content);
    let mut l = Vec::with_capacity(content.len() + 18);
    l.extend_from_slice(content);
    l.extend_from_slice(format!("\t{:016x}\n", fnv1a(content)).as_bytes());
    l
}

/// The content of log line `line_no` (without checksum and newline), after checking its line end
/// and checksum; errors name the file and line, never echo the content.
fn checked_content<'a>(path: &Path, line_no: usize, line: &'a [u8]) -> Result<&'a [u8], StudyError> {
    let at = || format!("{} line {line_no}", path.display());
    let body = line.strip_suffix(b"\n").ok_or_else(|| {
        StudyError::Log(format!("{}: torn last line (the study was interrupted): finish it with --resume", at()))
    })?;
    if body.ends_with(b"\r") {
        return Err(StudyError::Log(format!(
            "{}: ends with CR LF (Windows line ends); a study log has LF line ends only, so it was converted after \
             it was written: convert it back (dos2unix) or run the study again in a new --out",
            at()
        )));
    }
    let tab = body.iter().rposition(|&b| b == b'\t').ok_or_else(|| {
        StudyError::Log(format!(
            "{}: no checksum at the end of the line (every line of a study log ends with a tab and 16 hex digits); \
             the line was damaged or the log was written by an older stiction",
            at()
        ))
    })?;
    let (content, sum) = (&body[..tab], &body[tab + 1..]);
    let expected = format!("{:016x}", fnv1a(content));
    if sum != expected.as_bytes() {
        return Err(StudyError::Log(format!(
            "{}: the checksum does not match the line (it was edited or damaged after the study wrote it); \
             the log cannot be trusted: run the study again in a new --out",
            at()
        )));
    }
    Ok(content)
}

/// The column line of samples.csv.
pub fn column_line(header: &Header) -> Result<Vec<u8>, StudyError> {
    csv_line(&columns(header))
}

/// One sample as its samples.csv row (numbers in Rust's shortest round-trip form).
pub fn row(s: &SampleResult) -> Result<Vec<u8>, StudyError> {
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:e}"));
    let w = &s.intervals;
    let mut f = vec![
        s.index.to_string(),
        opt(s.mu_apparent),
        opt(s.apparent_adhesion_force_n),
        opt(s.mean_contacts),
        opt(s.interface_mu),
        opt(w.mu_ci95_width),
        opt(w.mu_ci95_width_with_calibration),
        opt(w.fa0_ci95_width_n),
        opt(w.fa0_ci95_width_with_calibration_n),
    ];
    f.extend(s.draws.iter().map(|&d| opt(d.is_finite().then_some(d))));
    f.push(s.reason.clone().unwrap_or_default());
    // One sample, one line.
    f.push(s.detail.as_deref().unwrap_or("").replace(['\n', '\r'], " "));
    csv_line(&f)
}

/// A sample read back from a log.
#[derive(Debug, Clone)]
pub struct Row {
    /// Sample index.
    pub index: usize,
    /// mu_e,a.
    pub mu_apparent: Option<f64>,
    /// F_a0, N.
    pub apparent_adhesion_force_n: Option<f64>,
    /// The sample's interface coefficient s / p_mean.
    pub interface_mu: Option<f64>,
    /// The widths of its eq. 10 intervals.
    pub intervals: crate::FitIntervals,
    /// Draws, SI (NaN: not drawn).
    pub draws: Vec<f64>,
    /// Reason code, empty with a fit.
    pub reason: String,
}

fn parse_row(rec: &[&str], n_params: usize, what: &dyn Fn() -> String) -> Result<Row, StudyError> {
    let bad = |m: String| StudyError::Log(format!("{}: {m}", what()));
    let num = |k: usize| -> Result<Option<f64>, StudyError> {
        let t = rec[k];
        if t.is_empty() {
            return Ok(None);
        }
        t.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .map(Some)
            .ok_or_else(|| bad(format!("field {k} = {t:?} is not a number")))
    };
    Ok(Row {
        index: rec[0].parse().map_err(|_| bad(format!("sample index {:?} is not a whole number", rec[0])))?,
        mu_apparent: num(1)?,
        apparent_adhesion_force_n: num(2)?,
        interface_mu: num(4)?,
        intervals: crate::FitIntervals {
            mu_ci95_width: num(5)?,
            mu_ci95_width_with_calibration: num(6)?,
            fa0_ci95_width_n: num(7)?,
            fa0_ci95_width_with_calibration_n: num(8)?,
        },
        draws: (0..n_params).map(|k| num(LEAD + k).map(|x| x.unwrap_or(f64::NAN))).collect::<Result<_, _>>()?,
        reason: rec[LEAD + n_params].to_string(),
    })
}

/// Reads the header of a log (its checksum checked; a log of another format refused).
pub fn read_header(path: &Path) -> Result<Header, StudyError> {
    let f = File::open(path).map_err(|e| StudyError::Log(format!("cannot open {}: {e}", path.display())))?;
    let mut line = Vec::new();
    BufReader::new(f.take(MAX_HEADER_BYTES))
        .read_until(b'\n', &mut line)
        .map_err(|e| StudyError::Log(format!("cannot read {}: {e}", path.display())))?;
    let not_header = || StudyError::Log(format!("{}: the first line is not a study log header", path.display()));
    if !line.starts_with(b"# ") {
        return Err(not_header());
    }
    let content = checked_content(path, 1, &line)?;
    let json = std::str::from_utf8(&content[2..]).map_err(|_| not_header())?;
    let h: Header = serde_json::from_str(json)
        .map_err(|e| StudyError::Log(format!("{}: the study log header is not valid ({e})", path.display())))?;
    if h.format != FORMAT {
        return Err(StudyError::Log(format!(
            "{}: a study log of format {}, this stiction reads format {FORMAT}: run the study again with this version",
            path.display(),
            h.format
        )));
    }
    Ok(h)
}

/// Streams the rows of a log after its header, checking each line's checksum and that they are
/// the shard's samples in order. `f` gets each row and its samples.csv line (with the newline,
/// without the checksum).
pub fn for_each_row<F>(path: &Path, mut f: F) -> Result<usize, StudyError>
where
    F: FnMut(Row, &[u8]) -> Result<(), StudyError>,
{
    let header = read_header(path)?;
    let file = File::open(path).map_err(|e| StudyError::Log(format!("cannot open {}: {e}", path.display())))?;
    let mut r = BufReader::with_capacity(1 << 16, file);
    let mut line = Vec::new();
    r.read_until(b'\n', &mut line).map_err(|e| StudyError::Log(format!("{}: {e}", path.display())))?;
    let mut n = 0usize;
    let mut line_no = 1usize;
    loop {
        line.clear();
        let got = r.read_until(b'\n', &mut line).map_err(|e| StudyError::Log(format!("{}: {e}", path.display())))?;
        if got == 0 {
            break;
        }
        line_no += 1;
        let content = checked_content(path, line_no, &line)?;
        let what = || format!("{} line {line_no}", path.display());
        // The number and code fields are never quoted (written by `row`); only the last field,
        // the detail text, may be: split off the first LEAD + 1 + p fields.
        let text = std::str::from_utf8(content).map_err(|_| StudyError::Log(format!("{}: not UTF-8 text", what())))?;
        let n_fields = LEAD + 1 + header.parameters.len();
        let fields: Vec<&str> = text.splitn(n_fields + 1, ',').collect();
        if fields.len() != n_fields + 1 {
            return Err(StudyError::Log(format!("{}: {} fields, expected {}", what(), fields.len(), n_fields + 1)));
        }
        let row = parse_row(&fields[..n_fields], header.parameters.len(), &what)?;
        let expected = header.shard_index + n * header.shard_count;
        if row.index != expected {
            return Err(StudyError::Log(format!(
                "{}: sample {} where sample {expected} was expected (the log is not this shard's, in order)",
                what(),
                row.index
            )));
        }
        let mut csv_row = Vec::with_capacity(content.len() + 1);
        csv_row.extend_from_slice(content);
        csv_row.push(b'\n');
        f(row, &csv_row)?;
        n += 1;
    }
    Ok(n)
}

/// The append-only writer of a log.
pub struct LogWriter {
    file: File,
    path: PathBuf,
}

impl LogWriter {
    /// Starts a new log in `dir`; refuses when one exists (finish it with resume, or use another
    /// folder).
    pub fn create(dir: &Path, header: &Header) -> Result<LogWriter, StudyError> {
        let path = dir.join(LOG_NAME);
        if std::fs::symlink_metadata(&path).is_ok() {
            return Err(StudyError::Log(format!(
                "{} exists: this folder holds a study already; add --resume to finish it, or choose another --out",
                path.display()
            )));
        }
        let mut file = OpenOptions::new()
            .create_new(true)
            .append(true)
            .open(&path)
            .map_err(|e| StudyError::Log(format!("cannot create {}: {e}", path.display())))?;
        file.write_all(header.line().as_bytes())
            .and_then(|()| file.flush())
            .map_err(|e| StudyError::Log(format!("cannot write {}: {e}", path.display())))?;
        Ok(LogWriter { file, path })
    }

    /// Reopens the log in `dir` to finish it: checks that it belongs to the same study and shard
    /// (`header`), cuts a torn last line, and returns the writer and the number of samples done.
    /// Without a log (or with only a torn header) it starts a new one.
    pub fn resume(dir: &Path, header: &Header) -> Result<(LogWriter, usize), StudyError> {
        let path = dir.join(LOG_NAME);
        let meta = match std::fs::symlink_metadata(&path) {
            Ok(m) => m,
            Err(_) => return Ok((LogWriter::create(dir, header)?, 0)),
        };
        if !meta.file_type().is_file() {
            return Err(StudyError::Log(format!("{} is not a regular file", path.display())));
        }
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .open(&path)
            .map_err(|e| StudyError::Log(format!("cannot open {}: {e}", path.display())))?;
        // Cut a torn last line: keep everything up to the last newline.
        let len = meta.len();
        let mut keep = len;
        let mut buf = [0u8; 4096];
        while keep > 0 {
            let start = keep.saturating_sub(buf.len() as u64);
            let n = (keep - start) as usize;
            file.seek(SeekFrom::Start(start))
                .and_then(|_| file.read_exact(&mut buf[..n]))
                .map_err(|e| StudyError::Log(format!("cannot read {}: {e}", path.display())))?;
            match buf[..n].iter().rposition(|&b| b == b'\n') {
                Some(p) => {
                    keep = start + p as u64 + 1;
                    break;
                }
                None => keep = start,
            }
        }
        if keep != len {
            file.set_len(keep).map_err(|e| StudyError::Log(format!("cannot cut {}: {e}", path.display())))?;
        }
        drop(file);
        if keep == 0 {
            std::fs::remove_file(&path)
                .map_err(|e| StudyError::Log(format!("cannot remove {}: {e}", path.display())))?;
            return Ok((LogWriter::create(dir, header)?, 0));
        }
        let old = read_header(&path)?;
        if let Some(m) = header.mismatch(&old) {
            return Err(StudyError::Log(format!(
                "{} belongs to another study ({m}); resume with the same scenario and flags, or choose another --out",
                path.display()
            )));
        }
        if (old.shard_index, old.shard_count) != (header.shard_index, header.shard_count) {
            return Err(StudyError::Log(format!(
                "{} holds shard {}/{}, not {}/{}",
                path.display(),
                old.shard_index,
                old.shard_count,
                header.shard_index,
                header.shard_count
            )));
        }
        let done = for_each_row(&path, |_, _| Ok(()))?;
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(|e| StudyError::Log(format!("cannot open {}: {e}", path.display())))?;
        Ok((LogWriter { file, path }, done))
    }

    /// Appends one row ([`row`]: a samples.csv line) with its checksum, and flushes it.
    pub fn append(&mut self, row: &[u8]) -> Result<(), StudyError> {
        self.file
            .write_all(&log_line(row))
            .and_then(|()| self.file.flush())
            .map_err(|e| StudyError::Log(format!("cannot append to {}: {e}", self.path.display())))
    }

    /// The log's path.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Merges complete shard logs (`inputs`, any order) into one log at `out_dir` for the whole
/// study, as a single run would have written it. Refuses pieces of different studies, missing
/// or repeated shards and unfinished shards, each with what differs.
pub fn merge(inputs: &[PathBuf], out_dir: &Path) -> Result<Header, StudyError> {
    if inputs.is_empty() {
        return Err(StudyError::Setting("merge needs at least one study folder".into()));
    }
    let mut logs: Vec<(Header, PathBuf)> = Vec::new();
    for dir in inputs {
        let p = dir.join(LOG_NAME);
        let h = read_header(&p)?;
        if let Some((first, fp)) = logs.first()
            && let Some(m) = first.mismatch(&h)
        {
            return Err(StudyError::Setting(format!(
                "{} and {} are pieces of different studies ({m}); merge only shards of one study",
                fp.display(),
                p.display()
            )));
        }
        logs.push((h, p));
    }
    let m = logs[0].0.shard_count;
    let mut seen: Vec<Option<PathBuf>> = vec![None; m];
    for (h, p) in &logs {
        if h.shard_count != m {
            return Err(StudyError::Setting(format!(
                "{} is shard {}/{} but {} is one of {m} shards",
                p.display(),
                h.shard_index,
                h.shard_count,
                logs[0].1.display()
            )));
        }
        if let Some(q) = &seen[h.shard_index] {
            return Err(StudyError::Setting(format!(
                "shard {}/{m} given twice: {} and {}",
                h.shard_index,
                q.display(),
                p.display()
            )));
        }
        seen[h.shard_index] = Some(p.clone());
    }
    if let Some(k) = seen.iter().position(Option::is_none) {
        return Err(StudyError::Setting(format!("shard {k}/{m} is missing (give every shard's folder)")));
    }
    logs.sort_by_key(|(h, _)| h.shard_index);
    // Whole shards only.
    let mut rows: Vec<Vec<Vec<u8>>> = Vec::with_capacity(m);
    for (h, p) in &logs {
        let mut lines = Vec::new();
        let n = for_each_row(p, |_, l| {
            lines.push(l.to_vec());
            Ok(())
        })?;
        if n != h.shard_len() {
            return Err(StudyError::Setting(format!(
                "{} holds {n} of the {} samples of shard {}/{m}: finish it first (stiction study ... --resume)",
                p.display(),
                h.shard_len(),
                h.shard_index
            )));
        }
        rows.push(lines);
    }
    let mut header = logs[0].0.clone();
    header.shard_index = 0;
    header.shard_count = 1;
    let out = out_dir.join(LOG_NAME);
    if std::fs::symlink_metadata(&out).is_ok() {
        return Err(StudyError::Log(format!("{} exists: merge into an empty folder", out.display())));
    }
    let mut bytes = header.line().into_bytes();
    for i in 0..header.samples {
        bytes.extend_from_slice(&log_line(&rows[i % m][i / m]));
    }
    stiction_units::io::write_atomic(&out, &bytes).map_err(|e| StudyError::Log(e.to_string()))?;
    Ok(header)
}
