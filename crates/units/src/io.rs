//! Safe file input and output at the edge of stiction.
//!
//! Every file a user names goes through [`read_input`]: it must be a regular file (not a FIFO, a
//! device such as `/dev/zero`, or a folder) no larger than a stated limit, checked before a byte is
//! read, so no input can block or exhaust memory. Every output goes through [`write_atomic`]: the
//! bytes go to a temporary file in the same folder, which is flushed to disk and then renamed over
//! the target, so a killed run leaves the earlier complete file or the new complete file, never a
//! partial one; a target that is a symbolic link is refused (an output never writes through a link).
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

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, flushed, then renamed
/// over `path`. Refuses a `path` that is a symbolic link.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), FileError> {
    if let Ok(meta) = std::fs::symlink_metadata(path) {
        if meta.file_type().is_symlink() {
            return Err(FileError::Symlink { path: path.to_path_buf() });
        }
        if meta.is_dir() {
            return Err(FileError::NotRegular { path: path.to_path_buf(), kind: "a folder" });
        }
    }
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
