//! Uploads kept on disk (`close serve --data-dir DIR`), so that an upload's links (its
//! pictures, its Interpolate and Plan views) outlive the server's caches, a reload of the
//! page and a restart of the server.
//!
//! Each upload's sample is written, as Sample JSON with its frame range, to
//! `DIR/uploads/<key>.json`, `<key>` being the content key its answer gave (a hex digest:
//! the same upload has the same key after a restart). The folder is bounded: at most
//! [`crate::Config::kept_uploads`] files and [`crate::Config::kept_upload_bytes`] bytes;
//! past either, the oldest (by the time it was written) go first. A file is written whole
//! under a temporary name, synced and then renamed ([`close_io::formats::write_atomic`]), so
//! a reader never sees half of one, even after a power cut.
//!
//! The folder is the user's, and anything may be put in it behind the server's back, so it
//! is treated as hostile: `uploads` must be a folder (not a link to one); a temporary file
//! is created new under a name no one else holds (`O_EXCL`, which never follows a link), so
//! a planted link is never written through; an upload is read as a listed dataset file is
//! ([`close_io::formats::read_listed`]: no link followed, a regular file only, bounded in
//! size), and what it holds is parsed as any upload is. A file refused says why.

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use serde::{Deserialize, Serialize};

use close_io::formats::Sample;

/// An upload as kept: its sample and the frames analysed.
#[derive(Debug, Serialize, Deserialize)]
pub(crate) struct Stored {
    pub start: Option<usize>,
    pub end: Option<usize>,
    pub sample: Sample,
}

/// The uploads folder and its bounds.
#[derive(Debug)]
pub(crate) struct Uploads {
    dir: PathBuf,
    files: usize,
    bytes: u64,
    /// Writes (and the pruning after them) one at a time.
    writing: Mutex<()>,
}

/// Whether `key` is a content key (hex digits), the only names this folder holds.
fn is_key(key: &str) -> bool {
    !key.is_empty() && key.len() <= 128 && key.bytes().all(|b| b.is_ascii_hexdigit())
}

impl Uploads {
    /// The uploads under `data_dir`, at most `files` of them and `bytes` in all.
    pub fn new(data_dir: &Path, files: usize, bytes: u64) -> Uploads {
        Uploads { dir: data_dir.join("uploads"), files, bytes, writing: Mutex::new(()) }
    }

    /// Where the folder is.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// How many uploads and bytes it keeps at most.
    pub fn bounds(&self) -> (usize, u64) {
        (self.files, self.bytes)
    }

    fn path(&self, key: &str) -> PathBuf {
        self.dir.join(format!("{key}.json"))
    }

    /// Keep `stored` under `key`, then drop the oldest uploads past the bounds.
    pub fn save(&self, key: &str, stored: &Stored) -> std::io::Result<()> {
        if !is_key(key) {
            return Err(std::io::Error::other(format!("{key:?} is not an upload key")));
        }
        let bytes = serde_json::to_vec(stored).map_err(std::io::Error::other)?;
        let _one_at_a_time = self.writing.lock().unwrap_or_else(|e| e.into_inner());
        std::fs::create_dir_all(&self.dir)?;
        if !std::fs::symlink_metadata(&self.dir)?.is_dir() {
            return Err(std::io::Error::other(format!(
                "{} is not a folder (a link is not followed)",
                self.dir.display()
            )));
        }
        // Through a temporary file of our own, created new: an existing file or link there
        // is never written through.
        close_io::formats::write_atomic(&self.path(key), &bytes)?;
        self.prune(key)
    }

    /// Drop the oldest uploads (never `kept`) until the folder is within its bounds.
    fn prune(&self, kept: &str) -> std::io::Result<()> {
        let mut files: Vec<(std::time::SystemTime, u64, PathBuf)> = std::fs::read_dir(&self.dir)?
            .filter_map(|entry| {
                let entry = entry.ok()?;
                let path = entry.path();
                let name = path.file_name()?.to_str()?;
                let key = name.strip_suffix(".json")?;
                let meta = entry.metadata().ok()?;
                let written = meta.modified().ok()?;
                (is_key(key) && meta.is_file()).then_some((written, meta.len(), path))
            })
            .collect();
        files.sort_by_key(|(written, _, _)| *written);
        let mut total: u64 = files.iter().map(|(_, len, _)| len).sum();
        let mut count = files.len();
        for (_, len, path) in files {
            if count <= self.files && total <= self.bytes {
                break;
            }
            if path == self.path(kept) {
                continue;
            }
            std::fs::remove_file(&path)?;
            count -= 1;
            total = total.saturating_sub(len);
        }
        Ok(())
    }

    /// Whether the folder holds something under `key` (a link counts: [`Uploads::load`]
    /// then says why it is refused).
    pub fn has(&self, key: &str) -> bool {
        is_key(key) && std::fs::symlink_metadata(self.path(key)).is_ok()
    }

    /// The upload kept under `key`: `Ok(None)` when the folder no longer holds it, an error
    /// saying why when what is there is refused (a link, not a regular file, too large, or
    /// not an upload this server wrote).
    pub fn load(&self, key: &str) -> Result<Option<Stored>, String> {
        if !self.has(key) {
            return Ok(None);
        }
        let path = self.path(key);
        let bytes = close_io::formats::read_listed(&path, None).map_err(|e| e.to_string())?;
        serde_json::from_slice(&bytes)
            .map(Some)
            .map_err(|e| format!("{}: not an upload this server kept ({e})", path.display()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(name: &str) -> Stored {
        let square = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
        Stored {
            start: None,
            end: Some(1),
            sample: Sample {
                name: name.into(),
                category: "upload".into(),
                frames: vec![square.clone(), square],
                mesh: None,
                truth: None,
            },
        }
    }

    #[test]
    fn uploads_are_kept_and_the_oldest_dropped_past_the_bounds() {
        let dir = std::env::temp_dir().join(format!("close-uploads-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let uploads = Uploads::new(&dir, 2, 1 << 20);
        for key in ["aa01", "aa02", "aa03"] {
            uploads.save(key, &sample(key)).unwrap();
            // Distinct write times, so the order is the oldest's.
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        assert!(uploads.load("aa01").unwrap().is_none(), "the oldest is dropped");
        let kept = uploads.load("aa03").unwrap().expect("the newest is kept");
        assert_eq!((kept.sample.name.as_str(), kept.end), ("aa03", Some(1)));
        assert!(uploads.load("aa02").unwrap().is_some());
        // Only keys: nothing outside the folder is ever named.
        assert!(uploads.load("../aa02").unwrap().is_none() && uploads.load("").unwrap().is_none());
        assert!(uploads.save("../x", &sample("x")).is_err());
        // A byte bound keeps fewer.
        let small = Uploads::new(&dir, 10, 10);
        small.save("aa04", &sample("aa04")).unwrap();
        assert!(small.load("aa04").unwrap().is_some(), "the upload just kept stays");
        assert!(small.load("aa03").unwrap().is_none() && small.load("aa02").unwrap().is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_hostile_folder_is_never_followed_or_read_past_its_bounds() {
        use std::os::unix::fs::symlink;
        let dir =
            std::env::temp_dir().join(format!("close-uploads-hostile-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let uploads = Uploads::new(&dir, 10, 1 << 20);
        uploads.save("bb01", &sample("bb01")).unwrap();
        let outside = dir.join("outside.json");
        std::fs::write(&outside, serde_json::to_vec(&sample("outside")).unwrap()).unwrap();
        // An upload swapped for a link to a file outside: refused, and said so.
        std::fs::remove_file(uploads.path("bb01")).unwrap();
        symlink(&outside, uploads.path("bb01")).unwrap();
        let refused = uploads.load("bb01").unwrap_err();
        assert!(refused.contains("link"), "{refused}");
        // A FIFO is refused unread (no hang), and so is a file past the size bound.
        let fifo = {
            use std::os::unix::ffi::OsStrExt;
            std::ffi::CString::new(uploads.path("bb02").as_os_str().as_bytes()).unwrap()
        };
        assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o644) }, 0);
        assert!(uploads.load("bb02").unwrap_err().contains("not a regular file"));
        let huge = std::fs::File::create(uploads.path("bb03")).unwrap();
        huge.set_len(1 << 40).unwrap();
        let too_large = uploads.load("bb03").unwrap_err();
        assert!(too_large.contains("bytes"), "{too_large}");
        // Not an upload: a clear error, not a panic.
        std::fs::write(uploads.path("bb04"), b"{ not json").unwrap();
        assert!(uploads.load("bb04").unwrap_err().contains("not an upload"));
        // Planted links where a temporary file would go are never written through: the
        // temporary names are our own, created new.
        let target = dir.join("target.txt");
        std::fs::write(&target, b"keep me").unwrap();
        for k in 0..4 {
            let name = format!(".bb05.json.{}.{k}.tmp", std::process::id());
            symlink(&target, uploads.dir().join(name)).unwrap();
        }
        uploads.save("bb05", &sample("bb05")).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"keep me");
        assert!(uploads.load("bb05").unwrap().is_some());
        // `uploads` a link to another folder: refused, not written through.
        let other =
            std::env::temp_dir().join(format!("close-uploads-other-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&other);
        std::fs::create_dir_all(other.join("real")).unwrap();
        symlink(other.join("real"), other.join("uploads")).unwrap();
        let linked = Uploads::new(&other, 10, 1 << 20);
        let err = linked.save("bb06", &sample("bb06")).unwrap_err().to_string();
        assert!(err.contains("not a folder"), "{err}");
        assert_eq!(std::fs::read_dir(other.join("real")).unwrap().count(), 0);
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&other).unwrap();
    }
}
