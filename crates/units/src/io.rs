//! Safe file input and output at the edge of stiction.
//!
//! Every file a user names goes through [`read_input`]: it must be a regular file (not a FIFO, a
//! device such as `/dev/zero`, or a folder) no larger than a stated limit, checked before a byte is
//! read, so no input can block or exhaust memory. Every output goes through [`write_atomic`]: the
//! bytes go to a temporary file in the same folder, which is flushed to disk and then renamed over
//! the target, so a killed run leaves the earlier complete file or the new complete file, never a
//! partial one. A target must be a new name or a regular file ([`check_output`]): a symbolic link,
//! folder, device, FIFO or socket is refused, and so is any file this process read as an input
//! (by identity, device and inode, recorded by [`read_input`] or [`declare_input`]), so a hard
//! link or another name for an input is caught too.
//!
//! Written by hand (about 100 lines) because the two crates that do part of this (`tempfile`'s
//! `persist`, `atomic-write-file`) either follow symlinks at the target or add dependencies for
//! one `rename`.

use std::fmt;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The default size limit of an input file: 1 GiB.
pub const DEFAULT_INPUT_LIMIT_BYTES: u64 = 1 << 30;

/// An input or output file could not be used.
#[derive(Debug)]
pub enum FileError {
    /// The path does not exist or cannot be inspected.
    Open {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The path exists but is not a regular file (a folder, FIFO, socket or device).
    NotRegular {
        /// The file.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },
    /// The file is larger than the limit.
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Its size, bytes.
        size_bytes: u64,
        /// The limit, bytes.
        limit_bytes: u64,
    },
    /// An output path is a symbolic link.
    Symlink {
        /// The link.
        path: PathBuf,
    },
    /// An output path is one of the files this command read (same device and inode: the same
    /// file, a hard link to it, or another name for it).
    SameAsInput {
        /// The output path.
        path: PathBuf,
        /// The input, as it was named when it was read.
        input: PathBuf,
    },
    /// Reading or writing failed.
    Io {
        /// The file.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The operating system's error.
        source: std::io::Error,
    },
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FileError::Open { path, source } => write!(f, "cannot open {}: {source}", path.display()),
            FileError::NotRegular { path, kind } => {
                write!(f, "{} is {kind}, expected a regular file", path.display())
            }
            FileError::TooLarge { path, size_bytes, limit_bytes } => write!(
                f,
                "{} is {size_bytes} bytes, more than the limit of {limit_bytes} bytes for this input",
                path.display()
            ),
            FileError::Symlink { path } => write!(
                f,
                "{} is a symbolic link; outputs never write through a link (remove it or choose another path)",
                path.display()
            ),
            FileError::SameAsInput { path, input } => write!(
                f,
                "output {} is the input {} of this command (the same file on disk); an output never replaces \
                 an input: choose another output path",
                path.display(),
                input.display()
            ),
            FileError::Io { path, action, source } => write!(f, "cannot {action} {}: {source}", path.display()),
        }
    }
}

impl std::error::Error for FileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            FileError::Open { source, .. } | FileError::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

fn kind_of(ft: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if ft.is_char_device() || ft.is_block_device() {
            return "a device";
        }
        if ft.is_socket() {
            return "a socket";
        }
    }
    if ft.is_dir() { "a folder" } else { "not a regular file" }
}

/// Checks that `path` is a regular file of at most `limit_bytes` and returns its size in bytes.
pub fn check_input(path: &Path, limit_bytes: u64) -> Result<u64, FileError> {
    let meta = std::fs::metadata(path).map_err(|source| FileError::Open { path: path.to_path_buf(), source })?;
    if !meta.file_type().is_file() {
        return Err(FileError::NotRegular { path: path.to_path_buf(), kind: kind_of(&meta.file_type()) });
    }
    if meta.len() > limit_bytes {
        return Err(FileError::TooLarge { path: path.to_path_buf(), size_bytes: meta.len(), limit_bytes });
    }
    Ok(meta.len())
}

/// Reads a whole input file after [`check_input`]; reads at most `limit_bytes` even if the file
/// grows while it is read.
pub fn read_input(path: &Path, limit_bytes: u64) -> Result<Vec<u8>, FileError> {
    let size = check_input(path, limit_bytes)?;
    let file = std::fs::File::open(path).map_err(|source| FileError::Open { path: path.to_path_buf(), source })?;
    if let Ok(meta) = file.metadata() {
        record_input(path, &meta);
    }
    let mut bytes = Vec::with_capacity(size as usize);
    file.take(limit_bytes.saturating_add(1)).read_to_end(&mut bytes).map_err(|source| FileError::Io {
        path: path.to_path_buf(),
        action: "read",
        source,
    })?;
    if bytes.len() as u64 > limit_bytes {
        return Err(FileError::TooLarge { path: path.to_path_buf(), size_bytes: bytes.len() as u64, limit_bytes });
    }
    Ok(bytes)
}

/// An input file opened for reading in parts ([`open_input`]): a regular file whose size, checked
/// against the limit on the opened handle, bounds every read. A reader that needs only some of a
/// large file (a header, then one channel's samples straight into their final buffer) reads those
/// parts, never more than the size it was opened with, even if the file grows meanwhile.
#[derive(Debug)]
pub struct InputFile {
    file: std::fs::File,
    path: PathBuf,
    size_bytes: u64,
}

/// Opens an input file to be read in parts: the same rules as [`read_input`] (a regular file, at
/// most `limit_bytes`, recorded as an input of this process so no output replaces it), the type
/// and size taken from the opened handle.
pub fn open_input(path: &Path, limit_bytes: u64) -> Result<InputFile, FileError> {
    check_input(path, limit_bytes)?;
    let file = std::fs::File::open(path).map_err(|source| FileError::Open { path: path.to_path_buf(), source })?;
    let meta = file.metadata().map_err(|source| FileError::Open { path: path.to_path_buf(), source })?;
    if !meta.file_type().is_file() {
        return Err(FileError::NotRegular { path: path.to_path_buf(), kind: kind_of(&meta.file_type()) });
    }
    if meta.len() > limit_bytes {
        return Err(FileError::TooLarge { path: path.to_path_buf(), size_bytes: meta.len(), limit_bytes });
    }
    record_input(path, &meta);
    Ok(InputFile { file, path: path.to_path_buf(), size_bytes: meta.len() })
}

impl InputFile {
    /// The file's size when it was opened, bytes: no read goes past it.
    pub fn size_bytes(&self) -> u64 {
        self.size_bytes
    }

    /// The path the file was opened by.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Fills `buf` with the file's bytes from `offset`. A part beyond the size the file was opened
    /// with is refused before any read; a file that shrank meanwhile is an error, never zeros.
    pub fn read_at(&self, offset: u64, buf: &mut [u8]) -> Result<(), FileError> {
        let io_err = |source| FileError::Io { path: self.path.clone(), action: "read", source };
        if offset.checked_add(buf.len() as u64).is_none_or(|end| end > self.size_bytes) {
            return Err(io_err(std::io::Error::new(
                std::io::ErrorKind::UnexpectedEof,
                format!("{} bytes from byte {offset} lie past its size of {} bytes", buf.len(), self.size_bytes),
            )));
        }
        read_exact_at(&self.file, offset, buf).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                io_err(std::io::Error::new(e.kind(), "the file became shorter while it was read"))
            } else {
                io_err(e)
            }
        })
    }

    /// The whole file (its size when opened), as [`read_input`] gives it.
    pub fn read_all(&self) -> Result<Vec<u8>, FileError> {
        use std::io::Seek;
        let io_err = |source| FileError::Io { path: self.path.clone(), action: "read", source };
        let mut file = &self.file;
        file.seek(std::io::SeekFrom::Start(0)).map_err(io_err)?;
        let mut bytes = Vec::with_capacity(self.size_bytes as usize);
        file.take(self.size_bytes).read_to_end(&mut bytes).map_err(io_err)?;
        if bytes.len() as u64 != self.size_bytes {
            return Err(io_err(std::io::Error::new(
                std::io::ErrorKind::UnexpectedEof,
                "the file became shorter while it was read",
            )));
        }
        Ok(bytes)
    }
}

/// Smallest buffer [`advise_huge_pages`] asks huge pages for: 4 MiB (two huge pages), so that a
/// small buffer never splits the heap's mappings.
pub const HUGE_PAGE_ADVICE_MIN_BYTES: usize = 4 << 20;

/// Asks the kernel to back `buf` with transparent huge pages (Linux `madvise(MADV_HUGEPAGE)` on the
/// whole 4 KiB pages inside it), before it is first written: a fresh 128 MiB buffer is then faulted
/// in 2 MiB pages instead of 32,768 pages of 4 KiB, which is most of the cost of filling it
/// (docs/performance.md, "Instrument files"). A hint only: the contents are never changed, and
/// where the kernel refuses (no transparent huge pages, a region that is not anonymous memory) or
/// on another system nothing happens. Buffers under [`HUGE_PAGE_ADVICE_MIN_BYTES`] are left alone.
pub fn advise_huge_pages<T>(buf: &mut [T]) {
    let bytes = std::mem::size_of_val(buf);
    if bytes < HUGE_PAGE_ADVICE_MIN_BYTES {
        return;
    }
    #[cfg(target_os = "linux")]
    {
        const PAGE: usize = 4096;
        let start = buf.as_mut_ptr() as usize;
        let (first, end) = (start.next_multiple_of(PAGE), (start + bytes) & !(PAGE - 1));
        if end > first {
            madvise_huge_pages(first, end - first);
        }
    }
}

/// `madvise(first, len, MADV_HUGEPAGE)`, its result ignored (a hint).
#[cfg(target_os = "linux")]
#[allow(unsafe_code)]
fn madvise_huge_pages(first: usize, len: usize) {
    // SAFETY: `first..first + len` are whole pages inside one live buffer that the caller holds
    // by `&mut` (so no other code uses it meanwhile). MADV_HUGEPAGE only sets how the kernel backs
    // those pages: it never unmaps them, changes their protection or changes a byte of their
    // contents (unlike MADV_DONTNEED or MADV_FREE), so no Rust reference to them is invalidated.
    // An address range that is not anonymous memory gives EINVAL, which is ignored.
    let _ = unsafe { libc::madvise(first as *mut libc::c_void, len, libc::MADV_HUGEPAGE) };
}

#[cfg(unix)]
fn read_exact_at(file: &std::fs::File, offset: u64, buf: &mut [u8]) -> std::io::Result<()> {
    std::os::unix::fs::FileExt::read_exact_at(file, buf, offset)
}

#[cfg(not(unix))]
fn read_exact_at(mut file: &std::fs::File, offset: u64, buf: &mut [u8]) -> std::io::Result<()> {
    use std::io::Seek;
    file.seek(std::io::SeekFrom::Start(offset))?;
    file.read_exact(buf)
}

/// Reads a whole input file as UTF-8 text (a leading byte-order mark is removed).
pub fn read_input_text(path: &Path, limit_bytes: u64) -> Result<String, FileError> {
    let bytes = read_input(path, limit_bytes)?;
    let mut text = String::from_utf8(bytes).map_err(|e| FileError::Io {
        path: path.to_path_buf(),
        action: "read (not UTF-8 text)",
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })?;
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(text)
}

/// The identities (device, inode) of the files this process read through [`read_input`], with
/// the name each was read by: outputs are checked against them ([`check_output`]).
static INPUTS: std::sync::Mutex<Vec<(u64, u64, PathBuf)>> = std::sync::Mutex::new(Vec::new());

#[cfg(unix)]
fn identity(meta: &std::fs::Metadata) -> Option<(u64, u64)> {
    use std::os::unix::fs::MetadataExt;
    Some((meta.dev(), meta.ino()))
}

#[cfg(not(unix))]
fn identity(_meta: &std::fs::Metadata) -> Option<(u64, u64)> {
    None
}

/// Records an opened input file's identity, so that no output of this process replaces it.
fn record_input(path: &Path, meta: &std::fs::Metadata) {
    if let Some(id) = identity(meta) {
        let mut inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
        if !inputs.iter().any(|(d, i, _)| (*d, *i) == id) {
            inputs.push((id.0, id.1, path.to_path_buf()));
        }
    }
}

/// Lists an existing file as an input of this command without reading it (a file the command's
/// arguments name as its data even when this run does not read it), so no output replaces it.
pub fn declare_input(path: &Path) {
    if let Ok(meta) = std::fs::metadata(path) {
        record_input(path, &meta);
    }
}

/// The input (as it was named when read) that `path` is, by identity (device and inode), if any.
pub fn input_at(path: &Path) -> Option<PathBuf> {
    let id = std::fs::metadata(path).ok().as_ref().and_then(identity)?;
    let inputs = INPUTS.lock().unwrap_or_else(|e| e.into_inner());
    inputs.iter().find(|(d, i, _)| (*d, *i) == id).map(|(_, _, p)| p.clone())
}

/// Reads a small text file that the output layer itself owns (an output folder's manifest)
/// without listing it as an input of the command: it is read to be replaced.
pub fn read_own_output_text(path: &Path, limit_bytes: u64) -> Result<String, FileError> {
    check_input(path, limit_bytes)?;
    let bytes =
        std::fs::read(path).map_err(|source| FileError::Io { path: path.to_path_buf(), action: "read", source })?;
    String::from_utf8(bytes).map_err(|e| FileError::Io {
        path: path.to_path_buf(),
        action: "read (not UTF-8 text)",
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, e.utf8_error()),
    })
}

/// Checks that `path` may receive an output file: it does not exist yet, or it is a regular file
/// (never a symbolic link, folder, FIFO, socket or device, which a rename would replace or a write
/// would block on) that is none of the files this process read ([`read_input`]).
pub fn check_output(path: &Path) -> Result<(), FileError> {
    match std::fs::symlink_metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(source) => Err(FileError::Open { path: path.to_path_buf(), source }),
        Ok(meta) => {
            let ft = meta.file_type();
            if ft.is_symlink() {
                return Err(FileError::Symlink { path: path.to_path_buf() });
            }
            if !ft.is_file() {
                return Err(FileError::NotRegular { path: path.to_path_buf(), kind: kind_of(&ft) });
            }
            match input_at(path) {
                Some(input) => Err(FileError::SameAsInput { path: path.to_path_buf(), input }),
                None => Ok(()),
            }
        }
    }
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, flushed, then renamed
/// over `path`. Refuses a `path` that [`check_output`] refuses (a link, folder, device, FIFO,
/// socket, or one of this process's inputs).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    check_output(path)?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let io = |action: &'static str, p: &Path| {
        let p = p.to_path_buf();
        move |source| FileError::Io { path: p, action, source }
    };
    let result = (|| {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(io("create a temporary file for", path))?;
        f.write_all(bytes).map_err(io("write", path))?;
        f.sync_all().map_err(io("flush", path))?;
        // Checked again just before the rename: the target may have been made since.
        check_output(path)?;
        std::fs::rename(&tmp, path).map_err(io("replace", path))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmpdir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("stiction-io-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn an_input_read_in_parts_is_bounded_by_its_size_when_opened() {
        let d = tmpdir("parts");
        let p = d.join("in.bin");
        std::fs::write(&p, b"0123456789").unwrap();
        // The rules of read_input: a regular file within the limit, recorded as an input.
        assert!(matches!(open_input(&p, 9), Err(FileError::TooLarge { size_bytes: 10, limit_bytes: 9, .. })));
        assert!(matches!(open_input(&d, 100), Err(FileError::NotRegular { .. })));
        #[cfg(unix)]
        assert!(matches!(open_input(Path::new("/dev/zero"), 100), Err(FileError::NotRegular { .. })));
        let f = open_input(&p, 10).unwrap();
        assert_eq!(f.size_bytes(), 10);
        assert!(input_at(&p).is_some());
        let mut buf = [0u8; 4];
        f.read_at(3, &mut buf).unwrap();
        assert_eq!(&buf, b"3456");
        f.read_at(6, &mut buf).unwrap();
        assert_eq!(&buf, b"6789");
        // Past the size it was opened with: refused before a read, even after the file grows.
        std::fs::write(&p, b"0123456789abcdef").unwrap();
        assert!(matches!(f.read_at(7, &mut buf), Err(FileError::Io { .. })));
        assert!(matches!(f.read_at(u64::MAX, &mut buf), Err(FileError::Io { .. })));
        assert_eq!(f.read_all().unwrap(), b"0123456789");
        // A file that shrank while read: an error, never zeros.
        std::fs::write(&p, b"01").unwrap();
        let e = f.read_at(4, &mut buf).unwrap_err();
        assert!(e.to_string().contains("shorter"), "{e}");
        assert!(f.read_all().unwrap_err().to_string().contains("shorter"));
    }

    #[test]
    fn huge_page_advice_changes_no_value() {
        // 8 MiB written, advised (as a buffer already in use would be), then read back; and the
        // spare capacity of a new vector advised before it is filled, as the readers do.
        let n = (8 << 20) / 8;
        let mut v: Vec<f64> = (0..n).map(|k| k as f64 * 0.5).collect();
        advise_huge_pages(&mut v);
        assert!(v.iter().enumerate().all(|(k, &x)| x == k as f64 * 0.5));
        let mut w: Vec<u64> = Vec::with_capacity(n);
        advise_huge_pages(w.spare_capacity_mut());
        w.extend(0..n as u64);
        assert!(w.iter().enumerate().all(|(k, &x)| x == k as u64));
        let mut small = vec![1u8; 100];
        advise_huge_pages(&mut small);
        assert_eq!(small, vec![1u8; 100]);
    }

    #[test]
    fn atomic_write_replaces_and_refuses_symlinks() {
        let d = tmpdir("atomic");
        let p = d.join("out.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"two");
        // no temporary file is left behind
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        #[cfg(unix)]
        {
            let target = d.join("target.txt");
            std::fs::write(&target, b"keep").unwrap();
            let link = d.join("link.txt");
            std::os::unix::fs::symlink(&target, &link).unwrap();
            assert!(matches!(write_atomic(&link, b"x"), Err(FileError::Symlink { .. })));
            assert_eq!(std::fs::read(&target).unwrap(), b"keep");
        }
    }

    #[test]
    #[cfg(unix)]
    fn outputs_never_replace_devices_fifos_or_inputs() {
        let d = tmpdir("targets");
        // A character device: refused, and left alone. As root, a private null device node (a
        // broken write_atomic would rename over it, not over the system's /dev/null); otherwise
        // /dev/null itself, which a non-root process cannot replace.
        let node = d.join("null");
        let made = std::process::Command::new("mknod")
            .args(["-m", "666"])
            .arg(&node)
            .args(["c", "1", "3"])
            .status()
            .is_ok_and(|s| s.success());
        let device = if made { node.as_path() } else { Path::new("/dev/null") };
        let e = write_atomic(device, b"x").unwrap_err();
        assert!(matches!(e, FileError::NotRegular { kind: "a device", .. }), "{e}");
        // A FIFO (made with mkfifo(1): no unsafe code here).
        let fifo = d.join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success());
        if made {
            let e = write_atomic(&fifo, b"x").unwrap_err();
            assert!(e.to_string().contains("FIFO"), "{e}");
        }
        // An input of this process, by its own name and by a hard link.
        let input = d.join("input.csv");
        std::fs::write(&input, b"data").unwrap();
        read_input(&input, 100).unwrap();
        let link = d.join("link.csv");
        std::fs::hard_link(&input, &link).unwrap();
        for target in [&input, &link] {
            let e = write_atomic(target, b"x").unwrap_err();
            assert!(matches!(e, FileError::SameAsInput { .. }), "{e}");
            assert!(e.to_string().contains("input.csv"), "{e}");
        }
        assert_eq!(std::fs::read(&input).unwrap(), b"data");
        // Another file is fine.
        write_atomic(&d.join("other.csv"), b"x").unwrap();
    }

    #[test]
    fn inputs_must_be_small_regular_files() {
        let d = tmpdir("input");
        assert!(matches!(read_input(&d, 10), Err(FileError::NotRegular { .. })));
        let p = d.join("f.txt");
        std::fs::write(&p, "\u{feff}hello").unwrap();
        assert_eq!(read_input_text(&p, 100).unwrap(), "hello");
        assert!(matches!(read_input(&p, 3), Err(FileError::TooLarge { .. })));
        #[cfg(unix)]
        assert!(matches!(read_input(Path::new("/dev/zero"), 10), Err(FileError::NotRegular { .. })));
    }
}
