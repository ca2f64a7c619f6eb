//! Uploads kept on disk (`close serve --data-dir DIR`), so that an upload's links (its
//! pictures, its Interpolate and Plan views) outlive the server's caches, a reload of the
//! page and a restart of the server.
//!
//! Each upload's sample is written, as Sample JSON with its frame range, to
//! `DIR/uploads/<key>.json`, `<key>` being the content key its answer gave (a hex digest:
//! the same upload has the same key after a restart). The folder is bounded: at most
//! [`crate::Config::kept_uploads`] files and [`crate::Config::kept_upload_bytes`] bytes;
//! past either, the oldest (by the time it was written) go first. A file is written whole
//! under a temporary name and then renamed, so a reader never sees half of one.

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
        let partial = self.dir.join(format!("{key}.json.partial"));
        std::fs::write(&partial, &bytes)?;
        std::fs::rename(&partial, self.path(key))?;
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

    /// The upload kept under `key`, if it still is.
    pub fn load(&self, key: &str) -> Option<Stored> {
        if !is_key(key) {
            return None;
        }
        let bytes = std::fs::read(self.path(key)).ok()?;
        serde_json::from_slice(&bytes).ok()
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
        assert!(uploads.load("aa01").is_none(), "the oldest is dropped");
        let kept = uploads.load("aa03").expect("the newest is kept");
        assert_eq!((kept.sample.name.as_str(), kept.end), ("aa03", Some(1)));
        assert!(uploads.load("aa02").is_some());
        // Only keys: nothing outside the folder is ever named.
        assert!(uploads.load("../aa02").is_none() && uploads.load("").is_none());
        assert!(uploads.save("../x", &sample("x")).is_err());
        // A byte bound keeps fewer.
        let small = Uploads::new(&dir, 10, 10);
        small.save("aa04", &sample("aa04")).unwrap();
        assert!(small.load("aa04").is_some(), "the upload just kept stays");
        assert!(small.load("aa03").is_none() && small.load("aa02").is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
