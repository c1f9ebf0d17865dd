//! Shared helpers of the subcommands: quantity flags, JSON and table printing, output folders.
//!
//! Standard output goes through [`write_stdout`] (the [`outln!`](crate::outln) macro): a closed
//! pipe (`stiction scenario F | head -3`) ends the program quietly with status 0, any other write
//! error (a full disk, `> /dev/full`) with a clean error and status 2; never a panic. Output
//! folders go through [`OutputSet`]: one run's files, with a `manifest.json`, swapped in whole.
//! Single output files go through `stiction_units::io::write_atomic`. Neither ever writes over a
//! device, FIFO, socket or symbolic link, nor over a file the command read (by identity: device
//! and inode, so a hard link or another name is caught too). Every JSON the program prints or
//! writes goes through [`json_text`] (`stiction_units::finite`): a NaN or infinity is an internal
//! error naming its key path, never a silent `null`.

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};

use stiction_plot::Chart;
use stiction_units::{Constraint, Dimension, parse_quantity_checked};

/// The result of a subcommand.
pub type CliResult = Result<(), Box<dyn std::error::Error>>;

/// `println!` for the subcommands: writes a line to standard output through [`write_stdout`].
#[macro_export]
macro_rules! outln {
    () => {
        $crate::output::write_stdout(format_args!(""))
    };
    ($($arg:tt)*) => {
        $crate::output::write_stdout(format_args!($($arg)*))
    };
}

/// `eprintln!` for the subcommands, without its panic when standard error is closed or full: a
/// message that cannot be shown is dropped (the exit status still tells the caller).
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// Writes `args` and a newline to standard output. On a closed pipe the program ends quietly
/// with status 0 (the reader has all it wanted); on any other error with a message and status 2.
pub fn write_stdout(args: fmt::Arguments) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_fmt(args).and_then(|()| out.write_all(b"\n")) {
        stdout_failed(&e);
    }
}

/// Flushes standard output at the end of the program (a full disk shows here).
pub fn flush_stdout() {
    if let Err(e) = std::io::stdout().lock().flush() {
        stdout_failed(&e);
    }
}

fn stdout_failed(e: &std::io::Error) -> ! {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        std::process::exit(0);
    }
    let _ = writeln!(std::io::stderr(), "error: cannot write to standard output: {e}");
    std::process::exit(2);
}

/// A clap value parser for a quantity of `dim` (bare SI number or number with a unit).
pub fn quantity(
    dim: Dimension,
    constraint: Constraint,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| parse_quantity_checked(s, dim, constraint).map_err(|e| e.to_string())
}

/// A quantity flag in the physical domain of the scenario quantity `path`
/// (`stiction_engine::check::domain_value`: the one table for the file, `--set`, flags and Python): outside
/// it the flag is refused with the domain and its reason; outside the usual range it runs with a
/// warning on standard error naming `flag`.
pub fn domain_quantity(
    dim: Dimension,
    constraint: Constraint,
    path: &'static str,
    flag: &'static str,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |s: &str| {
        let v = parse_quantity_checked(s, dim, constraint).map_err(|e| e.to_string())?;
        if let Some(w) = stiction_engine::check::domain_value(path, flag, v)? {
            crate::errln!("warning [{}]: {}", w.code, w.message);
        }
        Ok(v)
    }
}

/// Prints a value as pretty JSON on stdout ([`json_text`]: every number finite).
pub fn print_json<T: serde::Serialize>(value: &T) -> CliResult {
    let text = json_text(value)?;
    crate::outln!("{}", text.trim_end_matches('\n'));
    Ok(())
}

/// A value as pretty JSON with a final newline, for a file or standard output; refuses a NaN or
/// infinity anywhere in it with an internal error naming the key path.
pub fn json_text<T: serde::Serialize + ?Sized>(value: &T) -> Result<String, Box<dyn std::error::Error>> {
    Ok(stiction_units::finite::to_json_pretty(value)?)
}

/// Checks an output file named by `flag` before the work ([`stiction_units::io::check_output`]):
/// a regular file or a new name, never a device, FIFO, link or one of the command's inputs.
pub fn check_output_flag(flag: &str, path: &Path) -> CliResult {
    stiction_units::io::check_output(path).map_err(|e| format!("{flag}: {e}"))?;
    Ok(())
}

/// Prints a two-column table of (name, value with unit).
pub fn print_table(title: &str, rows: &[(&str, String)]) {
    crate::outln!("{title}");
    let width = rows.iter().map(|(n, _)| n.len()).max().unwrap_or(0);
    for (name, value) in rows {
        crate::outln!("  {name:<width$}  {value}");
    }
}

/// A text table with a header line, printed with every column aligned: numbers (and `-`, `n/a`,
/// signed percentages) to the right, text to the left; two spaces between columns, `indent`
/// before each line. Built on comfy-table without borders, so a cell of any width (a long
/// switch name, a NaN) widens its column instead of shifting the rest of the line.
pub struct TextTable {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl TextTable {
    /// A table with these column titles (units in brackets: `L (uN)`).
    pub fn new<S: AsRef<str>>(header: &[S]) -> TextTable {
        TextTable { header: header.iter().map(|h| h.as_ref().to_string()).collect(), rows: Vec::new() }
    }

    /// Adds a row (as many cells as titles; missing cells are empty).
    pub fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// The table as lines, each starting with `indent`, without trailing blanks.
    pub fn lines(&self, indent: &str) -> Vec<String> {
        use comfy_table::{CellAlignment, ColumnConstraint, ContentArrangement, Table};
        let numeric = |s: &str| {
            let t = s.trim().trim_end_matches('%').trim_end();
            t.is_empty() || t == "-" || t == "n/a" || t.parse::<f64>().is_ok()
        };
        let mut t = Table::new();
        t.load_preset(comfy_table::presets::NOTHING).set_content_arrangement(ContentArrangement::Disabled);
        t.set_header(self.header.clone());
        for r in &self.rows {
            t.add_row(r.clone());
        }
        for (k, col) in t.column_iter_mut().enumerate() {
            let right = self.rows.iter().all(|r| r.get(k).is_none_or(|c| numeric(c)));
            col.set_cell_alignment(if right { CellAlignment::Right } else { CellAlignment::Left });
            col.set_padding((0, 2));
            col.set_constraint(ColumnConstraint::ContentWidth);
        }
        // The header follows its column's alignment.
        let right: Vec<bool> =
            (0..self.header.len()).map(|k| self.rows.iter().all(|r| r.get(k).is_none_or(|c| numeric(c)))).collect();
        if let Some(h) = t.header().cloned() {
            let cells: Vec<comfy_table::Cell> = h
                .cell_iter()
                .zip(&right)
                .map(|(c, r)| c.clone().set_alignment(if *r { CellAlignment::Right } else { CellAlignment::Left }))
                .collect();
            t.set_header(cells);
        }
        t.lines().map(|l| format!("{indent}{}", l.trim_end())).collect()
    }

    /// Prints the table on standard output.
    pub fn print(&self, indent: &str) {
        for l in self.lines(indent) {
            crate::outln!("{l}");
        }
    }
}

/// Creates an output folder (and its parents); errors name the folder (the engine's rule: no
/// symbolic link).
pub use stiction_engine::study_folder::ensure_dir;

/// Formats an SI value with a prefix and unit.
pub fn q(value: f64, dim: Dimension) -> String {
    stiction_units::format_quantity(value, dim)
}

/// The name of an output folder's manifest: the list of files one stiction run wrote there.
pub const MANIFEST: &str = "manifest.json";

#[derive(serde::Serialize, serde::Deserialize)]
struct Manifest {
    /// Always "stiction".
    tool: String,
    /// The subcommand that wrote the folder.
    command: String,
    /// The files of that run, in the order written.
    files: Vec<String>,
}

/// A study or merge stopped by Ctrl-C or SIGTERM: the message says what was kept and how to go
/// on; the program exits with status 130 (128 + SIGINT), as a shell does.
#[derive(Debug)]
pub struct Interrupted(pub String);

impl fmt::Display for Interrupted {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Interrupted {}

/// Set by the first Ctrl-C or SIGTERM while a command that stops cleanly runs ([`stop_cleanly`]).
pub static INTERRUPT: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
static STOPS_CLEANLY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
/// Staging folders of the output sets in progress, removed when the program is interrupted.
static STAGING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Installs the Ctrl-C / SIGTERM handler. A command that called [`stop_cleanly`] (a study) gets
/// the first signal as [`INTERRUPT`] and finishes its samples in flight; otherwise (and on a
/// second signal) the staging folders of unfinished output sets are removed and the program
/// exits with status 130 at once, leaving the earlier outputs as they were and nothing hidden.
pub fn install_interrupt_handler() {
    use std::sync::atomic::Ordering;
    let _ = ctrlc::set_handler(|| {
        if STOPS_CLEANLY.load(Ordering::SeqCst) && !INTERRUPT.swap(true, Ordering::SeqCst) {
            crate::errln!("interrupted: finishing the samples in flight (press Ctrl-C again to stop at once)");
            return;
        }
        let dirs: Vec<PathBuf> = STAGING.lock().map(|mut g| std::mem::take(&mut *g)).unwrap_or_default();
        for d in dirs {
            let _ = std::fs::remove_dir_all(d);
        }
        crate::errln!("interrupted");
        std::process::exit(130);
    });
}

/// Says that this command handles [`INTERRUPT`] itself (finishes its work in flight and returns
/// [`Interrupted`]).
pub fn stop_cleanly() {
    STOPS_CLEANLY.store(true, std::sync::atomic::Ordering::SeqCst);
}

fn track_staging(dir: &Path, on: bool) {
    if let Ok(mut g) = STAGING.lock() {
        if on {
            g.push(dir.to_path_buf());
        } else {
            g.retain(|d| d != dir);
        }
    }
}

/// The file names an earlier stiction run listed in `dir`'s manifest (empty without one).
pub fn listed_files(dir: &Path) -> Result<Vec<String>, Box<dyn std::error::Error>> {
    let manifest_path = dir.join(MANIFEST);
    if !manifest_path.exists() {
        return Ok(Vec::new());
    }
    let text = stiction_units::io::read_own_output_text(&manifest_path, 1 << 20)?;
    let m: Manifest = serde_json::from_str(&text)
        .map_err(|e| format!("{}: not a stiction manifest ({e})", manifest_path.display()))?;
    Ok(m.files)
}

/// Writes `dir`'s manifest for a folder written in place (a study's folder, which grows sample by
/// sample and so cannot be swapped in whole): `files`, in order.
pub fn write_manifest(dir: &Path, command: &str, files: &[String]) -> CliResult {
    let manifest = Manifest { tool: "stiction".into(), command: command.into(), files: files.to_vec() };
    stiction_units::io::write_atomic(&dir.join(MANIFEST), json_text(&manifest)?.as_bytes())?;
    Ok(())
}

/// The `--out` rule for a folder written in place: the names in `dir` that neither an earlier
/// run's manifest nor `own` (this command's files) account for are refused unless `force`.
pub fn check_foreign(dir: &Path, own: &[&str], force: bool) -> CliResult {
    let Ok(entries) = std::fs::read_dir(dir) else { return Ok(()) };
    let foreign = unlisted_files(entries, &listed_files(dir)?, own);
    if !foreign.is_empty() && !force {
        return Err(foreign_refusal(dir, &foreign));
    }
    Ok(())
}

/// The names in a folder listing that are neither the manifest, nor `listed` (an earlier run's
/// manifest), nor `own` (this command's files), sorted.
fn unlisted_files(entries: std::fs::ReadDir, listed: &[String], own: &[&str]) -> Vec<String> {
    let mut foreign: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n != MANIFEST && !listed.contains(n) && !own.contains(&n.as_str()))
        .collect();
    foreign.sort();
    foreign
}

/// The refusal of an output folder that holds `foreign` files (the first five named) without --force.
fn foreign_refusal(dir: &Path, foreign: &[String]) -> Box<dyn std::error::Error> {
    let shown: Vec<&str> = foreign.iter().take(5).map(String::as_str).collect();
    format!(
        "output folder {} holds {} file(s) that no stiction run listed in its {MANIFEST} ({}{}); \
         choose a new or empty folder, or pass --force to write beside them",
        dir.display(),
        foreign.len(),
        shown.join(", "),
        if foreign.len() > 5 { ", ..." } else { "" }
    )
    .into()
}

/// The environment variable naming a folder where every figure's layout goes as JSON
/// ([`record_layout`]); unset in normal use. The end-to-end layout test sets it.
pub const LAYOUT_DIR_ENV: &str = "STICTION_LAYOUT_DIR";

/// When [`LAYOUT_DIR_ENV`] names a folder, writes the layout of the figure just written to `figure`
/// there as `NAME.layout.json` (NAME: the figure's file name; `-2`, `-3`, ... appended when a
/// figure of that name was recorded before): every element's box and the layout's problems
/// (`stiction_plot::Layout::to_json`), for a test that checks the program's figures from the drawn
/// elements. Nothing is written when the variable is unset.
pub fn record_layout(
    figure: &Path,
    layout: impl FnOnce() -> Result<stiction_plot::Layout, stiction_plot::PlotError>,
) -> CliResult {
    let Some(dir) = std::env::var_os(LAYOUT_DIR_ENV) else { return Ok(()) };
    let dir = PathBuf::from(dir);
    ensure_dir(&dir)?;
    let name = figure.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let mut path = dir.join(format!("{name}.layout.json"));
    let mut k = 2;
    while path.exists() {
        path = dir.join(format!("{name}-{k}.layout.json"));
        k += 1;
    }
    let json = layout()?.to_json();
    stiction_units::io::write_atomic(&path, json_text(&json)?.as_bytes())?;
    Ok(())
}

/// The image format of an output path: "svg" or "png" by its extension; any other is an error.
pub fn chart_format(path: &Path) -> Result<&'static str, String> {
    match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).as_deref() {
        Some("svg") => Ok("svg"),
        Some("png") => Ok("png"),
        other => Err(format!(
            "{}: unknown image extension {}; expected .svg or .png",
            path.display(),
            other.map_or("(none)".to_string(), |e| format!(".{e}"))
        )),
    }
}

/// Renders a chart to `path` (SVG or PNG by extension; any other is an error naming it). The plot
/// crate writes it atomically and never through a symbolic link.
pub fn render_chart(chart: &Chart, path: &Path) -> CliResult {
    chart_format(path)?;
    chart.write(path)?;
    crate::output::record_layout(path, || chart.layout())
}

/// Writes a chart straight into `dir` as `{stem}.svg`, `{stem}.png` and its data `{stem}.csv` (the
/// files [`OutputSet::add_chart`] writes, in the same CSV shape), for a folder that is not an
/// [`OutputSet`] (a study's resumable log folder). Returns the names written.
pub fn write_chart_files(
    dir: &Path,
    stem: &str,
    chart: &stiction_plot::Chart,
) -> Result<Vec<String>, Box<dyn std::error::Error>> {
    for ext in ["svg", "png"] {
        render_chart(chart, &dir.join(format!("{stem}.{ext}")))?;
    }
    stiction_units::io::write_atomic(&dir.join(format!("{stem}.csv")), chart.data_csv().as_bytes())?;
    Ok(["svg", "png", "csv"].map(|e| format!("{stem}.{e}")).to_vec())
}

/// One run's output folder, written as a whole.
///
/// The files go to a hidden staging folder beside the target (same file system). On
/// [`OutputSet::commit`] a `manifest.json` listing them is added and the staging folder replaces
/// the target: the old folder is renamed aside, the new one renamed in, the old one removed. A run
/// killed at any moment leaves the previous complete folder, the new complete folder, or (between
/// the two renames) no folder; never a partial file and never two runs' files side by side.
///
/// A target folder that holds files no earlier stiction run listed in its manifest is refused,
/// unless `force`: then each new file replaces its namesake atomically, the earlier run's other
/// files are removed and the foreign files are left alone.
pub struct OutputSet {
    dir: PathBuf,
    staging: PathBuf,
    command: String,
    files: Vec<String>,
    old_files: Vec<String>,
    in_place: bool,
    committed: bool,
}

fn io_err(action: &str, path: &Path, e: std::io::Error) -> Box<dyn std::error::Error> {
    format!("cannot {action} {}: {e}", path.display()).into()
}

/// Whether a process id is alive (Linux: /proc; elsewhere assumed alive).
fn pid_alive(pid: u32) -> bool {
    if cfg!(target_os = "linux") { Path::new(&format!("/proc/{pid}")).exists() } else { true }
}

impl OutputSet {
    /// Prepares to write the outputs of `command` into `dir`.
    pub fn begin(dir: &Path, command: &str, force: bool) -> Result<OutputSet, Box<dyn std::error::Error>> {
        let name = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| format!("output folder {}: expected a folder name", dir.display()))?;
        let parent = match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        ensure_dir(&parent)?;
        // Leftovers of killed runs into the same folder.
        let prefix = format!(".{name}.stiction-");
        if let Ok(entries) = std::fs::read_dir(&parent) {
            for e in entries.flatten() {
                let n = e.file_name().to_string_lossy().into_owned();
                if let Some(rest) = n.strip_prefix(&prefix) {
                    let pid = rest.rsplit('-').next().and_then(|p| p.parse::<u32>().ok());
                    if pid.is_some_and(|p| p != std::process::id() && !pid_alive(p)) {
                        let _ = std::fs::remove_dir_all(e.path());
                    }
                }
            }
        }
        let mut old_files = Vec::new();
        let mut in_place = false;
        match std::fs::symlink_metadata(dir) {
            Ok(m) if m.file_type().is_symlink() => {
                return Err(format!(
                    "output folder {} is a symbolic link; outputs never go through a link",
                    dir.display()
                )
                .into());
            }
            Ok(m) if !m.is_dir() => {
                return Err(format!("output folder {} exists and is not a folder", dir.display()).into());
            }
            Ok(_) => {
                old_files = listed_files(dir)?;
                let entries = std::fs::read_dir(dir).map_err(|e| io_err("list the output folder", dir, e))?;
                let foreign = unlisted_files(entries, &old_files, &[]);
                if !foreign.is_empty() {
                    if !force {
                        return Err(foreign_refusal(dir, &foreign));
                    }
                    in_place = true;
                }
            }
            Err(_) => {}
        }
        let staging = parent.join(format!("{prefix}staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&staging);
        std::fs::create_dir(&staging).map_err(|e| {
            format!("cannot write output folder {} (its staging folder {}): {e}", dir.display(), staging.display())
        })?;
        track_staging(&staging, true);
        let set = OutputSet {
            dir: dir.to_path_buf(),
            staging,
            command: command.to_string(),
            files: Vec::new(),
            old_files,
            in_place,
            committed: false,
        };
        set.check_inputs()?;
        Ok(set)
    }

    fn claim(&mut self, name: &str) -> Result<PathBuf, Box<dyn std::error::Error>> {
        if name == MANIFEST || name.contains(['/', '\\']) || self.files.iter().any(|f| f == name) {
            return Err(format!("internal: output name {name} is not allowed or used twice").into());
        }
        self.files.push(name.to_string());
        Ok(self.staging.join(name))
    }

    /// Refuses to replace or remove a file of the target folder that is one of the command's
    /// inputs (by identity; called again at [`OutputSet::commit`], after the inputs are read).
    fn check_inputs(&self) -> CliResult {
        for name in self.old_files.iter().chain(&self.files).map(String::as_str).chain([MANIFEST]) {
            let path = self.dir.join(name);
            if let Some(input) = stiction_units::io::input_at(&path) {
                return Err(format!(
                    "output folder {}: its {name} is the input {} of this command (the same file on disk); an \
                     output never replaces an input: choose another output folder, or move the input out of it",
                    self.dir.display(),
                    input.display()
                )
                .into());
            }
        }
        Ok(())
    }

    /// Adds a file with these bytes.
    pub fn add_bytes(&mut self, name: &str, bytes: &[u8]) -> CliResult {
        let path = self.claim(name)?;
        let target = self.dir.join(name);
        std::fs::write(&path, bytes).map_err(|e| io_err("write", &target, e))?;
        Ok(())
    }

    /// Adds a chart, SVG or PNG by the name's extension, and (once per stem) the plotted data as CSV
    /// beside it (`fig7.svg` -> `fig7.csv`, units in the column names).
    pub fn add_chart(&mut self, name: &str, chart: &stiction_plot::Chart) -> CliResult {
        let path = self.claim(name)?;
        render_chart(chart, &path).map_err(|e| format!("{}: {e}", self.dir.join(name).display()))?;
        let data_name = stiction_plot::data_path(Path::new(name)).display().to_string();
        if data_name != name && !self.files.contains(&data_name) {
            self.add_bytes(&data_name, chart.data_csv().as_bytes())?;
        }
        Ok(())
    }

    /// A figure as every command writes one: `{stem}.svg` and `{stem}.png` through
    /// [`OutputSet::add_chart`], with their data `{stem}.csv`.
    pub fn add_figure(&mut self, stem: &str, chart: &stiction_plot::Chart) -> CliResult {
        self.add_chart(&format!("{stem}.svg"), chart)?;
        self.add_chart(&format!("{stem}.png"), chart)
    }

    /// A map as every command writes one: `{stem}.svg` and `{stem}.png` through
    /// [`OutputSet::add_image_map`], with their data `{stem}.csv`.
    pub fn add_map_figure(&mut self, stem: &str, map: &stiction_plot::ImageMap) -> CliResult {
        self.add_image_map(&format!("{stem}.svg"), map)?;
        self.add_image_map(&format!("{stem}.png"), map)
    }

    /// The staging folder, for a writer that takes a folder (the study folder `merge` writes);
    /// [`OutputSet::adopt_staged`] then adds what it wrote.
    pub fn staging_dir(&self) -> &Path {
        &self.staging
    }

    /// Adds every file written straight into the staging folder that is not listed yet (in name
    /// order). Hidden files (leftovers of an atomic write) are removed, folders refused.
    pub fn adopt_staged(&mut self) -> CliResult {
        let mut names = Vec::new();
        for e in std::fs::read_dir(&self.staging).map_err(|e| io_err("list", &self.staging, e))? {
            let e = e.map_err(|e| io_err("list", &self.staging, e))?;
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') {
                let _ = std::fs::remove_file(e.path());
            } else if !e.file_type().is_ok_and(|t| t.is_file()) {
                return Err(format!("internal: {} in an output folder is not a file", e.path().display()).into());
            } else if !self.files.contains(&name) {
                names.push(name);
            }
        }
        names.sort();
        for name in names {
            self.claim(&name)?;
        }
        Ok(())
    }

    /// Adds a colour image (a field drawn as a heat map with a colour bar) as SVG or PNG by the
    /// name's extension. Its drawn cells go beside it as CSV under the same stem, once per stem
    /// (`height.svg`, `height.png`, `height.csv`).
    pub fn add_image_map(&mut self, name: &str, map: &stiction_plot::ImageMap) -> CliResult {
        let path = self.claim(name)?;
        map.write(&path).map_err(|e| format!("{}: {e}", self.dir.join(name).display()))?;
        record_layout(&path, || map.layout())?;
        let csv_name = Path::new(name).with_extension("csv").to_string_lossy().into_owned();
        if self.files.contains(&csv_name) {
            return Ok(());
        }
        self.add_bytes(&csv_name, map.data_csv().as_bytes())
    }

    /// The names of the files added so far, in order.
    pub fn file_names(&self) -> Vec<String> {
        self.files.clone()
    }

    /// Writes the manifest and puts the folder in place.
    pub fn commit(mut self) -> CliResult {
        self.check_inputs()?;
        let manifest = Manifest { tool: "stiction".into(), command: self.command.clone(), files: self.files.clone() };
        let text = json_text(&manifest)?;
        std::fs::write(self.staging.join(MANIFEST), &text).map_err(|e| io_err("write", &self.dir.join(MANIFEST), e))?;
        for f in self.files.iter().map(String::as_str).chain([MANIFEST]) {
            let p = self.staging.join(f);
            std::fs::File::open(&p).and_then(|h| h.sync_all()).map_err(|e| io_err("flush", &p, e))?;
        }
        if self.in_place {
            // Foreign files stay: replace ours one by one (each atomically), then drop stale ones,
            // then the manifest last.
            for f in &self.files {
                let bytes = std::fs::read(self.staging.join(f)).map_err(|e| io_err("read", &self.staging, e))?;
                stiction_units::io::write_atomic(&self.dir.join(f), &bytes)?;
            }
            for f in self.old_files.iter().filter(|f| !self.files.contains(f)) {
                let _ = std::fs::remove_file(self.dir.join(f));
            }
            stiction_units::io::write_atomic(&self.dir.join(MANIFEST), text.as_bytes())?;
            let _ = std::fs::remove_dir_all(&self.staging);
        } else if self.dir.exists() {
            let old = self.staging.with_file_name(
                self.staging.file_name().unwrap_or_default().to_string_lossy().replace("-staging-", "-old-"),
            );
            let _ = std::fs::remove_dir_all(&old);
            std::fs::rename(&self.dir, &old)
                .map_err(|e| io_err("move aside the earlier output folder", &self.dir, e))?;
            std::fs::rename(&self.staging, &self.dir).map_err(|e| io_err("put in place", &self.dir, e))?;
            let _ = std::fs::remove_dir_all(&old);
        } else {
            std::fs::rename(&self.staging, &self.dir).map_err(|e| io_err("put in place", &self.dir, e))?;
        }
        self.committed = true;
        Ok(())
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        track_staging(&self.staging, false);
    }
}
