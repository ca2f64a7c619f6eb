//! A VR-Folding store's files, read as a user's untrusted files are: the storage `zarrs`
//! reads the store through.
//!
//! A Zarr store is a folder of small files, and nothing in it is trusted:
//!
//! - **Never out of the store.** A file's path is resolved first: a link is followed only
//!   when where it leads is inside the store (a link out of it, e.g. a frame's `.zattrs`
//!   linked to `/etc/passwd`, is an error naming the link, and nothing of it is read). The
//!   resolved file is then opened without following links (`O_NOFOLLOW`), and on Linux the
//!   kernel's own name of the open file (`/proc/self/fd`) must still be inside the store, so
//!   a folder swapped for a link between the check and the open is caught too.
//! - **Regular files only, sized before they are read.** Files are opened non-blocking (a
//!   FIFO without a writer cannot stall the open) and checked on the open handle: a FIFO,
//!   socket, device or folder is refused, and so is a file larger than its cap, before a
//!   byte is read (a sparse 1 TiB chunk costs nothing on disk and would otherwise be
//!   allocated whole). The read stops one byte past the cap, so a file that grows meanwhile
//!   cannot make it read more.
//! - **Caps.** Metadata (`.zgroup`, `.zattrs`, `.zarray`, `.zmetadata`) is at most
//!   [`MAX_METADATA_BYTES`]; a chunk is read only through [`StoreFiles::read`] with the cap
//!   its array allows (its decoded size and the codec's overhead); anything else through
//!   the storage traits at most [`MAX_CHUNK_BYTES`]. A folder lists at most
//!   [`MAX_LISTED`] entries.
//!
//! Errors name the store's key and the problem, never the file's contents.
//!
//! ```
//! use close_io::vrfolding::files::StoreFiles;
//! let dir = std::env::temp_dir().join(format!("close-files-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join(".zgroup"), r#"{"zarr_format": 2}"#).unwrap();
//! let files = StoreFiles::new(&dir).unwrap();
//! assert_eq!(files.read(".zgroup", 100).unwrap().unwrap().len(), 18);
//! assert!(files.read(".zgroup", 10).unwrap_err().to_string().contains("more than 10 bytes"));
//! assert!(files.read("missing", 10).unwrap().is_none());
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::io::Read;
use std::path::{Path, PathBuf};

use zarrs::storage::byte_range::{ByteRangeIterator, InvalidByteRangeError};
use zarrs::storage::{
    Bytes, ListableStorageTraits, MaybeBytesIterator, ReadableStorageTraits, StorageError,
    StoreKey, StoreKeys, StoreKeysPrefixes, StorePrefix,
};

/// Largest metadata file (`.zgroup`, `.zattrs`, `.zarray`, `.zmetadata`) read.
pub const MAX_METADATA_BYTES: u64 = 1 << 20;
/// Largest file read through the storage traits other than metadata: a chunk of the
/// largest array the mesh limits allow (faces: 4·10⁶ × 3 of 8 bytes), with room for a codec's
/// overhead.
pub const MAX_CHUNK_BYTES: u64 = 128 << 20;
/// Most entries one folder of the store may list (frames of a category, most of all).
pub const MAX_LISTED: usize = 1 << 20;

/// The files of a store folder, read safely ([module docs](self)).
#[derive(Debug)]
pub struct StoreFiles {
    /// The folder as named.
    root: PathBuf,
    /// Its canonical path: where every file read must be.
    canonical: PathBuf,
}

/// A storage error of `key`: `problem`.
fn fault(key: &str, problem: impl std::fmt::Display) -> StorageError {
    StorageError::Other(format!("{}: {problem}", if key.is_empty() { "/" } else { key }))
}

/// Whether `key` names a metadata file.
fn is_metadata(key: &str) -> bool {
    let name = key.rsplit('/').next().unwrap_or(key);
    matches!(name, ".zgroup" | ".zattrs" | ".zarray" | ".zmetadata")
}

impl StoreFiles {
    /// The files of the store at `root` (a folder).
    pub fn new(root: &Path) -> std::io::Result<StoreFiles> {
        Ok(StoreFiles { root: root.to_path_buf(), canonical: root.canonicalize()? })
    }

    /// Where `key` (`a/b/c`, or a prefix `a/b/`) leads, resolved and checked to stay in the
    /// store; `None` when nothing is there.
    fn resolve(&self, key: &str) -> Result<Option<PathBuf>, StorageError> {
        let path = self.root.join(key.trim_end_matches('/'));
        match path.canonicalize() {
            Ok(real) if real.starts_with(&self.canonical) => Ok(Some(real)),
            Ok(_) => Err(fault(
                key,
                "a link leads out of the store: not followed (a store's files must be inside it)",
            )),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(fault(key, e)),
        }
    }

    /// Open `key`'s file as described in the [module docs](self): `None` when there is none,
    /// else the open file and its length, at most `cap`.
    fn open(&self, key: &str, cap: u64) -> Result<Option<(std::fs::File, u64)>, StorageError> {
        let Some(real) = self.resolve(key)? else {
            return Ok(None);
        };
        let mut options = std::fs::OpenOptions::new();
        options.read(true);
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::custom_flags(
            &mut options,
            libc::O_NONBLOCK | libc::O_NOFOLLOW,
        );
        let file = match options.open(&real) {
            Ok(file) => file,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(fault(key, format!("cannot open it: {e}"))),
        };
        self.check_opened(key, &file)?;
        let meta = file.metadata().map_err(|e| fault(key, e))?;
        if !meta.is_file() {
            return Err(fault(
                key,
                "not a regular file (a FIFO, device, socket or folder is never read)",
            ));
        }
        if meta.len() > cap {
            return Err(fault(
                key,
                format!("{} bytes: more than {cap} bytes, the most it may hold", meta.len()),
            ));
        }
        Ok(Some((file, meta.len())))
    }

    /// On Linux, the kernel's name of the open file must be inside the store: a folder on the
    /// way swapped for a link after [`StoreFiles::resolve`] looked is caught here.
    #[cfg(target_os = "linux")]
    fn check_opened(&self, key: &str, file: &std::fs::File) -> Result<(), StorageError> {
        use std::os::fd::AsRawFd;
        match std::fs::read_link(format!("/proc/self/fd/{}", file.as_raw_fd())) {
            Ok(real) if !real.starts_with(&self.canonical) => {
                Err(fault(key, "it moved out of the store while it was opened"))
            }
            // Without /proc (a sandbox), the resolved path's check stands alone.
            _ => Ok(()),
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn check_opened(&self, _: &str, _: &std::fs::File) -> Result<(), StorageError> {
        Ok(())
    }

    /// The whole file of `key` (`None` when there is none), refused before a byte is read
    /// when it is not a regular file or holds more than `cap` bytes.
    pub fn read(&self, key: &str, cap: u64) -> Result<Option<Vec<u8>>, StorageError> {
        let Some((file, length)) = self.open(key, cap)? else {
            return Ok(None);
        };
        let mut bytes = Vec::with_capacity(usize::try_from(length).unwrap_or(0));
        file.take(cap.saturating_add(1)).read_to_end(&mut bytes).map_err(|e| fault(key, e))?;
        if bytes.len() as u64 > cap {
            return Err(fault(key, format!("it grew past {cap} bytes while it was read")));
        }
        Ok(Some(bytes))
    }

    /// The cap of a file read through the storage traits.
    fn cap(key: &str) -> u64 {
        if is_metadata(key) {
            MAX_METADATA_BYTES
        } else {
            MAX_CHUNK_BYTES
        }
    }
}

impl ReadableStorageTraits for StoreFiles {
    fn get_partial_many<'a>(
        &'a self,
        key: &StoreKey,
        byte_ranges: ByteRangeIterator<'a>,
    ) -> Result<MaybeBytesIterator<'a>, StorageError> {
        let Some(bytes) = self.read(key.as_str(), Self::cap(key.as_str()))? else {
            return Ok(None);
        };
        let bytes = Bytes::from(bytes);
        let length = bytes.len() as u64;
        let out: Vec<Result<Bytes, StorageError>> = byte_ranges
            .map(|range| {
                let (start, end) = (range.start(length), range.end(length));
                if start > end || end > length {
                    return Err(InvalidByteRangeError::new(range, length).into());
                }
                Ok(bytes.slice(start as usize..end as usize))
            })
            .collect();
        Ok(Some(Box::new(out.into_iter())))
    }

    fn size_key(&self, key: &StoreKey) -> Result<Option<u64>, StorageError> {
        Ok(self.open(key.as_str(), u64::MAX)?.map(|(_, length)| length))
    }

    fn supports_get_partial(&self) -> bool {
        false
    }
}

impl ListableStorageTraits for StoreFiles {
    fn list(&self) -> Result<StoreKeys, StorageError> {
        Err(StorageError::Unsupported("a VR-Folding store is listed one folder at a time".into()))
    }

    fn list_prefix(&self, _: &StorePrefix) -> Result<StoreKeys, StorageError> {
        self.list()
    }

    /// The files and sub-folders of one folder of the store, at most [`MAX_LISTED`]; a
    /// folder reached through a link out of the store is an error, not listed.
    fn list_dir(&self, prefix: &StorePrefix) -> Result<StoreKeysPrefixes, StorageError> {
        let key = prefix.as_str();
        let Some(dir) = self.resolve(key)? else {
            return Ok(StoreKeysPrefixes::new(Vec::new(), Vec::new()));
        };
        let entries = std::fs::read_dir(&dir).map_err(|e| fault(key, e))?;
        let (mut keys, mut prefixes) = (Vec::new(), Vec::new());
        for (k, entry) in entries.enumerate() {
            if k >= MAX_LISTED {
                return Err(fault(
                    key,
                    format!(
                        "more than {MAX_LISTED} entries, the most a folder of a store may list"
                    ),
                ));
            }
            let entry = entry.map_err(|e| fault(key, e))?;
            // Names that are not text cannot be keys: such an entry is no part of the store.
            let Some(name) = entry.file_name().to_str().map(str::to_string) else {
                continue;
            };
            // A link to a folder counts as a folder; opening it resolves it again.
            if entry.path().is_dir() {
                prefixes.push(StorePrefix::new(format!("{key}{name}/"))?);
            } else {
                keys.push(StoreKey::new(format!("{key}{name}"))?);
            }
        }
        Ok(StoreKeysPrefixes::new(keys, prefixes))
    }

    fn size_prefix(&self, _: &StorePrefix) -> Result<u64, StorageError> {
        Err(StorageError::Unsupported("a VR-Folding store's size is not summed".into()))
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("close-files-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("a")).unwrap();
        dir
    }

    #[test]
    fn links_stay_inside_and_special_or_huge_files_are_refused_unread() {
        let dir = folder("links");
        let outside = folder("links-outside");
        std::fs::write(outside.join("secret"), "root:x:0:0:root:/root:/bin/bash\n").unwrap();
        std::fs::write(dir.join("a/.zattrs"), "{}").unwrap();
        std::os::unix::fs::symlink(dir.join("a/.zattrs"), dir.join("inside")).unwrap();
        std::os::unix::fs::symlink(outside.join("secret"), dir.join("a/out")).unwrap();
        std::os::unix::fs::symlink(&outside, dir.join("elsewhere")).unwrap();
        let sparse = std::fs::File::create(dir.join("a/0.0")).unwrap();
        sparse.set_len(1 << 40).unwrap();
        let files = StoreFiles::new(&dir).unwrap();
        assert_eq!(files.read("inside", 10).unwrap().unwrap(), b"{}");
        for key in ["a/out", "elsewhere/secret"] {
            let e = files.read(key, 1000).unwrap_err().to_string();
            assert!(e.contains("out of the store") && !e.contains("root:"), "{key}: {e}");
        }
        let e = files.list_dir(&StorePrefix::new("elsewhere/").unwrap()).unwrap_err();
        assert!(e.to_string().contains("out of the store"), "{e}");
        let e = files.read("a/0.0", 1 << 20).unwrap_err().to_string();
        assert!(e.contains("1099511627776 bytes: more than 1048576"), "{e}");
        // The traits' own cap: a chunk's file past the largest chunk, a metadata file past
        // the metadata cap.
        let e = files.get(&StoreKey::new("a/0.0").unwrap()).unwrap_err().to_string();
        assert!(e.contains(&MAX_CHUNK_BYTES.to_string()), "{e}");
        std::fs::File::create(dir.join("a/.zarray"))
            .unwrap()
            .set_len(MAX_METADATA_BYTES + 1)
            .unwrap();
        let e = files.get(&StoreKey::new("a/.zarray").unwrap()).unwrap_err().to_string();
        assert!(e.contains(&MAX_METADATA_BYTES.to_string()), "{e}");
        let listed = files.list_dir(&StorePrefix::new("a/").unwrap()).unwrap();
        assert_eq!(listed.keys().len(), 4);
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&outside).unwrap();
    }

    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = folder("fifo");
        let fifo =
            std::ffi::CString::new(dir.join("a/.zattrs").as_os_str().as_encoded_bytes()).unwrap();
        // SAFETY: `fifo` is a valid NUL-terminated path for the duration of the call.
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
        let files = StoreFiles::new(&dir).unwrap();
        let e = files.read("a/.zattrs", 100).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
