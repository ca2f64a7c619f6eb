//! A user's file as bytes: read bounded (a regular file only, never more than
//! [`MAX_FILE_BYTES`]). The CLI, the server and the Python package read through these, so a
//! FIFO, a device or a growing file is refused the same way everywhere.

use std::fmt;
use std::io::Read;
use std::path::Path;

use super::MAX_FILE_BYTES;
use crate::error::{Error, Result};
use close_core::Error as CoreError;

/// Which file a path named when a walk listed it: its device and inode. A file read later
/// for that listing ([`read_listed`]) must be this one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FileId {
    device: u64,
    inode: u64,
}

impl FileId {
    /// The identity of the file `meta` describes (`None` where the platform has none).
    #[cfg(unix)]
    pub fn of(meta: &std::fs::Metadata) -> Option<FileId> {
        use std::os::unix::fs::MetadataExt;
        Some(FileId { device: meta.dev(), inode: meta.ino() })
    }

    #[cfg(not(unix))]
    pub fn of(_: &std::fs::Metadata) -> Option<FileId> {
        None
    }
}

/// Why a file was not read ([`read_file_io`]): the system's error, kept whole (a missing
/// file, a folder, no permission: a caller with conventions of its own maps its kind, as the
/// Python package raises `FileNotFoundError`), or the readers' refusal. Either way its
/// message names the file, and is the one [`read_file`] gives.
#[derive(Debug)]
pub enum ReadError {
    /// The system could not open or read `path`.
    Os { path: String, error: std::io::Error },
    /// The file is not one the readers read: not a regular file, too large, not the file
    /// listed.
    Refused(Error),
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReadError::Os { path, error } => write!(f, "{path}: {error}"),
            ReadError::Refused(e) => e.fmt(f),
        }
    }
}

impl std::error::Error for ReadError {}

impl From<ReadError> for Error {
    fn from(e: ReadError) -> Self {
        match e {
            os @ ReadError::Os { .. } => Error::invalid(os.to_string()),
            ReadError::Refused(e) => e,
        }
    }
}

/// Read a user's file: a regular file of at most [`MAX_FILE_BYTES`]. A FIFO, device or
/// socket is refused before a byte is read (opened non-blocking, so a FIFO without a writer
/// cannot stall the open, then checked on the open handle), and the read stops one byte
/// past the cap, so a file that grows, or reports a false length, cannot make it read more.
/// The user named the path, so a link is followed; a file a walk listed is read by
/// [`read_listed`].
pub fn read_file(path: &Path) -> Result<Vec<u8>> {
    Ok(read_file_io(path)?)
}

/// [`read_file`], with the system's error kept whole ([`ReadError::Os`]) for a caller that
/// maps it to errors of its own.
pub fn read_file_io(path: &Path) -> std::result::Result<Vec<u8>, ReadError> {
    read_checked(path, None)
}

/// Read a file a walk listed (in a dataset folder) as [`read_file`] does, but as it was
/// listed: the path is opened without following a link (`O_NOFOLLOW`), and the file opened
/// must be the one listed (`listed`, its device and inode). A file swapped after the
/// listing, for a link to `/etc/passwd` say, is refused unread.
pub fn read_listed(path: &Path, listed: Option<FileId>) -> Result<Vec<u8>> {
    Ok(read_checked(path, Some(listed))?)
}

/// [`read_file_io`] (`listed` None) or [`read_listed`].
fn read_checked(
    path: &Path,
    listed: Option<Option<FileId>>,
) -> std::result::Result<Vec<u8>, ReadError> {
    let name = path.display();
    let os = |error: std::io::Error| ReadError::Os { path: name.to_string(), error };
    let refused = |why: &str| ReadError::Refused(Error::invalid(format!("{name}: {why}")));
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    std::os::unix::fs::OpenOptionsExt::custom_flags(
        &mut options,
        libc::O_NONBLOCK | if listed.is_some() { libc::O_NOFOLLOW } else { 0 },
    );
    let file = options.open(path).map_err(|e| {
        #[cfg(unix)]
        if listed.flatten().is_some() && e.raw_os_error() == Some(libc::ELOOP) {
            return refused("a symbolic link now, not the file listed: not followed");
        }
        os(e)
    })?;
    let meta = file.metadata().map_err(os)?;
    if let Some(listed) = listed.flatten() {
        if FileId::of(&meta) != Some(listed) {
            return Err(refused("another file than the one listed is there now: not read (list the dataset again to read it)"));
        }
    }
    // A folder opens for reading: said as the system says it (Python's IsADirectoryError).
    if meta.is_dir() {
        #[cfg(unix)]
        let folder = std::io::Error::from_raw_os_error(libc::EISDIR);
        #[cfg(not(unix))]
        let folder = std::io::Error::from(std::io::ErrorKind::IsADirectory);
        return Err(os(folder));
    }
    if !meta.is_file() {
        return Err(refused("not a regular file (a FIFO, device or socket is never read)"));
    }
    let too_large = |got: u64| {
        ReadError::Refused(
            Error::from(CoreError::TooLarge {
                what: "bytes in one file",
                got: Some(got),
                limit: MAX_FILE_BYTES as u64,
            })
            .in_file(&name.to_string()),
        )
    };
    if meta.len() > MAX_FILE_BYTES as u64 {
        return Err(too_large(meta.len()));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(MAX_FILE_BYTES as u64 + 1).read_to_end(&mut bytes).map_err(os)?;
    if bytes.len() > MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh folder of this test's own.
    fn scratch(name: &str) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("close-io-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn the_reader_keeps_the_systems_error_and_refuses_a_folder() {
        let dir = scratch("read");
        let missing = dir.join("missing.json");
        match read_file_io(&missing) {
            Err(ReadError::Os { error, .. }) => {
                assert_eq!(error.kind(), std::io::ErrorKind::NotFound)
            }
            other => panic!("{other:?}"),
        }
        let e = read_file(&missing).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{}: ", missing.display())), "{e}");
        match read_file_io(&dir) {
            Err(ReadError::Os { error, .. }) => {
                assert_eq!(error.kind(), std::io::ErrorKind::IsADirectory)
            }
            other => panic!("{other:?}"),
        }
        std::fs::write(&missing, b"ok").unwrap();
        assert_eq!(read_file(&missing).unwrap(), b"ok");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_past_the_cap_is_refused_unread() {
        let dir = scratch("cap");
        let path = dir.join("large.csv");
        // Sparse: its length says more than the cap, without a byte on disk.
        std::fs::File::create(&path).unwrap().set_len(MAX_FILE_BYTES as u64 + 1).unwrap();
        let e = read_file_io(&path).unwrap_err();
        assert!(matches!(e, ReadError::Refused(_)), "{e:?}");
        assert!(e.to_string().contains("bytes in one file"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
