//! A user's file as bytes: read bounded (a regular file only, never more than
//! [`MAX_FILE_BYTES`]), and written whole or not at all ([`write_atomic`]). The CLI, the
//! server and the Python package read and write through these, so a FIFO, a device or a
//! growing file is refused the same way everywhere.

use std::fmt;
use std::io::{Read, Write};
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

/// Most temporary names [`write_atomic`] tries beside one file before it gives up.
const TEMP_NAMES: usize = 100;

/// Write `bytes` to `path` so that no fault loses data: into a new temporary file beside it
/// (created exclusively, `O_EXCL`, so never through a link planted there; a name taken is
/// passed over), synced, renamed over `path`, and the folder synced (on unix) so that the
/// rename outlasts a power cut. A full disk or a kill leaves the old file, or none, never a
/// truncated one, and a link at `path` is replaced, not followed. The error names `path`;
/// the temporary file is removed on any failure.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let named =
        |e: std::io::Error| std::io::Error::new(e.kind(), format!("{}: {e}", path.display()));
    let name = path.file_name().map_or("out".into(), |n| n.to_string_lossy().to_string());
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let mut created = None;
    for k in 0..TEMP_NAMES {
        let temp = dir.join(format!(".{name}.{}.{k}.tmp", std::process::id()));
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&temp) {
            Ok(file) => {
                created = Some((temp, file));
                break;
            }
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(named(e)),
        }
    }
    let Some((temp, mut file)) = created else {
        return Err(named(std::io::Error::new(
            std::io::ErrorKind::AlreadyExists,
            format!("{TEMP_NAMES} temporary names beside it are taken"),
        )));
    };
    let written = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| std::fs::rename(&temp, path));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&temp);
        return Err(named(e));
    }
    #[cfg(unix)]
    std::fs::File::open(dir).and_then(|d| d.sync_all()).map_err(named)?;
    Ok(())
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

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_write_replaces_the_file_whole_and_leaves_no_temporary_file() {
        let dir = scratch("write");
        let path = dir.join("out.json");
        write_atomic(&path, b"first").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"first");
        write_atomic(&path, b"second, longer").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"second, longer");
        write_atomic(&path, b"").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"");
        assert_eq!(names(&dir), ["out.json"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_link_is_replaced_and_a_planted_temporary_name_passed_over() {
        use std::os::unix::fs::symlink;
        let dir = scratch("links");
        let precious = dir.join("precious.txt");
        std::fs::write(&precious, "keep me").unwrap();
        let path = dir.join("out.json");
        symlink(&precious, &path).unwrap();
        // Links where the first temporary files would go: never written through.
        for k in 0..3 {
            symlink(&precious, dir.join(format!(".out.json.{}.{k}.tmp", std::process::id())))
                .unwrap();
        }
        write_atomic(&path, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&precious).unwrap(), "keep me");
        assert!(std::fs::symlink_metadata(&path).unwrap().is_file(), "the link is replaced");
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        assert_eq!(names(&dir).len(), 2 + 3, "{:?}", names(&dir));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_names_the_path_and_leaves_nothing() {
        let dir = scratch("fail");
        // The target is a folder that holds a file: the rename over it fails.
        let path = dir.join("taken");
        std::fs::create_dir_all(path.join("inside")).unwrap();
        let e = write_atomic(&path, b"x").unwrap_err();
        assert!(e.to_string().starts_with(&format!("{}: ", path.display())), "{e}");
        assert_eq!(names(&dir), ["taken"]);
        let missing = dir.join("no/such/folder/out.json");
        let e = write_atomic(&missing, b"x").unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::NotFound);
        assert!(e.to_string().contains(&missing.display().to_string()), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
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
