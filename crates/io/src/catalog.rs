//! A user's own datasets, browsed next to the built-in set (`close serve --dataset PATH`).
//!
//! A dataset is a folder of sample files — Sample JSON, text/CSV, OBJ, PLY or MATLAB `.mat`,
//! one sample per file, or one per sub-folder holding one file per frame — or a VR-Folding
//! Zarr store (feature `vrfolding`), cut into its fold actions (fold 1 and fold 2 of every
//! video, see [`crate::vrfolding`]). Opening a catalog lists every entry once: a file sample
//! is parsed for its vertex and frame counts (in parallel), a store is cut from its grips
//! alone (no mesh is read). A sample is loaded only when asked for ([`Catalog::load`]), and
//! kept in a bounded cache. An entry that cannot be read carries its error and does not
//! hide the others.
//!
//! The folder is the user's, but not trusted: it is walked once per folder and never left
//! ([`walk`]); only regular files are read, each through a byte cap, and a sample's files
//! together are capped at [`MAX_SAMPLE_BYTES`] from their sizes before any is read; a load
//! checks its deadline between files; a load that fails (other than by its deadline) is
//! remembered, so asking again costs nothing.
//!
//! ```
//! use close_io::catalog::{Catalog, Query};
//! let dir = std::env::temp_dir().join(format!("close-catalog-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("square.json"), r#"{"name": "square", "category": "napkin",
//!     "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}"#).unwrap();
//! std::fs::write(dir.join("broken.json"), "{").unwrap();
//! let catalog = Catalog::open(&[dir.clone()]);
//! assert_eq!(catalog.entries().len(), 2);
//! let napkins = catalog.filter(&Query { category: Some("napkin".into()), ..Query::default() });
//! assert_eq!((napkins[0].n, napkins[0].frames), (Some(4), 1));
//! assert!(catalog.entries().iter().any(|e| e.error.is_some()));
//! assert_eq!(catalog.load(&napkins[0].id, &Default::default()).unwrap().name, "square");
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

pub mod walk;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::cache::Lru;
use crate::formats::{read_file, read_files, Sample, MAX_FILE_BYTES};
use close_core::budget::Deadline;
use close_core::error::{Error, Result};
use walk::{Folder, Node};

/// Samples kept loaded at once.
const CACHED_SAMPLES: usize = 64;
/// Their largest total size (bytes of coordinates and face indices).
const CACHE_BYTES: usize = 256 * 1024 * 1024;
/// Most bytes of files one sample may have: the same as one file (an upload), so a folder of
/// frames costs no more than one file of them.
pub const MAX_SAMPLE_BYTES: u64 = MAX_FILE_BYTES as u64;
/// Files that are one sample each in a dataset folder.
const SAMPLE_FILES: [&str; 8] = ["json", "mat", "txt", "csv", "xyz", "dat", "obj", "ply"];
/// The category suffix of fold sequences.
const SECOND_FOLD: &str = "_second_fold";
/// Files that are one frame each in a sub-folder of frames.
const FRAME_FILES: [&str; 6] = ["txt", "csv", "xyz", "dat", "obj", "ply"];

/// One sample of a user's dataset, as the list shows it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// Unique across the catalog and safe in a URL path segment.
    pub id: String,
    pub name: String,
    pub category: String,
    /// Border vertex count, when known without analysing (a store's fold: after loading).
    pub n: Option<usize>,
    pub frames: usize,
    /// Whether it is a mesh sample (its border is extracted from a triangle mesh).
    pub mesh: bool,
    /// The dataset folder or store it comes from.
    pub source: String,
    /// Why it cannot be loaded, when it cannot.
    pub error: Option<String>,
}

/// Filtering and paging of the list (`?category=&q=&offset=&limit=`).
#[derive(Debug, Clone, Default, Deserialize)]
pub struct Query {
    /// Exact category.
    pub category: Option<String>,
    /// Case-insensitive text in the name, id or category.
    pub q: Option<String>,
    #[serde(default)]
    pub offset: usize,
    pub limit: Option<usize>,
}

impl Query {
    /// Whether a sample with this name, id and category passes the filters.
    pub fn matches(&self, id: &str, name: &str, category: &str) -> bool {
        let category_ok = self.category.as_deref().is_none_or(|c| c.is_empty() || c == category);
        let text_ok = self
            .q
            .as_deref()
            .map(str::to_lowercase)
            .is_none_or(|q| [id, name, category].iter().any(|t| t.to_lowercase().contains(&q)));
        category_ok && text_ok
    }
}

/// Where an entry's sample comes from.
enum Origin {
    /// The files of one sample (one Sample JSON / .mat, or one file per frame).
    Files(Vec<PathBuf>),
    /// Fold `fold` of video `video` of store `store`.
    #[cfg(feature = "vrfolding")]
    Fold { store: usize, video: usize, fold: usize },
    /// Nothing to load (the error says why).
    Broken,
}

/// A user's datasets: the list, and samples loaded on demand.
pub struct Catalog {
    entries: Vec<Entry>,
    origins: Vec<Origin>,
    index: HashMap<String, usize>,
    #[cfg(feature = "vrfolding")]
    stores: Vec<(crate::vrfolding::Store, Vec<crate::vrfolding::Video>)>,
    cache: Mutex<Lru<Arc<Sample>>>,
    /// Loads that failed, by id (at most one per entry): asking again answers at once.
    refused: Mutex<HashMap<String, Error>>,
}

/// Lower-case extension of a path.
fn extension(path: &Path) -> String {
    path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()).unwrap_or_default()
}

/// `text` made safe for a URL path segment.
fn slug(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '-' })
        .collect()
}

/// Read a sample's files into a sample: their total size is checked against
/// [`MAX_SAMPLE_BYTES`] before any is read, each is read as a regular file through its cap
/// ([`read_file`]), and `deadline` is checked between files.
fn read_sample(files: &[PathBuf], deadline: &Deadline) -> Result<Sample> {
    let size = |p: &PathBuf| std::fs::metadata(p).map(|m| m.len()).unwrap_or(0);
    let total = files.iter().map(size).fold(0u64, u64::saturating_add);
    if total > MAX_SAMPLE_BYTES {
        return Err(Error::TooLarge {
            what: "bytes in the files of one sample",
            got: Some(total),
            limit: MAX_SAMPLE_BYTES,
        });
    }
    let mut read = 0u64;
    let named = files
        .iter()
        .map(|p| {
            deadline.check()?;
            let bytes = read_file(p)?;
            // Sizes may change between the check and the read: count what was read.
            read += bytes.len() as u64;
            if read > MAX_SAMPLE_BYTES {
                return Err(Error::TooLarge {
                    what: "bytes in the files of one sample",
                    got: Some(read),
                    limit: MAX_SAMPLE_BYTES,
                });
            }
            Ok((p.display().to_string(), bytes))
        })
        .collect::<Result<Vec<_>>>()?;
    deadline.check()?;
    read_files(&named)
}

/// Whether a file may hold a sample or a frame (the walk leaves out the others).
fn sample_file(path: &Path) -> bool {
    SAMPLE_FILES.contains(&extension(path).as_str())
}

/// One thing found in a dataset folder: its files (or why it could not be walked), where it
/// is (the file or frame folder) and its category (the sub-folder it is in).
type Found = (std::result::Result<Vec<PathBuf>, String>, PathBuf, String);

/// What a walked dataset folder holds: each sample file, each sub-folder of frame files (a
/// sub-folder holding sample files is a folder of samples itself, named as a category), and
/// each entry that could not be walked, with the category (sub-folder) it is in.
fn file_samples(root: &Path, folder: &Folder, out: &mut Vec<Found>) {
    let category =
        folder.path.strip_prefix(root).ok().map(|r| r.display().to_string()).unwrap_or_default();
    for node in &folder.entries {
        match node {
            Node::Folder(sub) => {
                let files: Vec<&PathBuf> = sub
                    .entries
                    .iter()
                    .filter_map(|n| if let Node::File(p) = n { Some(p) } else { None })
                    .collect();
                let frames: Vec<PathBuf> = files
                    .iter()
                    .filter(|p| FRAME_FILES.contains(&extension(p).as_str()))
                    .map(|p| p.to_path_buf())
                    .collect();
                if files.iter().any(|p| ["json", "mat"].contains(&extension(p).as_str()))
                    || frames.is_empty()
                {
                    file_samples(root, sub, out);
                } else {
                    out.push((Ok(frames), sub.path.clone(), category.clone()));
                }
            }
            Node::File(path) => out.push((Ok(vec![path.clone()]), path.clone(), category.clone())),
            Node::Unreadable(path, why) => {
                out.push((Err(why.clone()), path.clone(), category.clone()))
            }
        }
    }
}

impl Catalog {
    /// List every dataset; a path that cannot be read becomes one entry with its error.
    pub fn open(paths: &[PathBuf]) -> Catalog {
        let mut catalog = Catalog {
            entries: Vec::new(),
            origins: Vec::new(),
            index: HashMap::new(),
            #[cfg(feature = "vrfolding")]
            stores: Vec::new(),
            cache: Mutex::new(Lru::new(CACHED_SAMPLES, CACHE_BYTES)),
            refused: Mutex::new(HashMap::new()),
        };
        for (k, path) in paths.iter().enumerate() {
            let source = path.display().to_string();
            let prefix = format!("d{k}");
            #[cfg(feature = "vrfolding")]
            if crate::vrfolding::is_store(path) {
                catalog.add_store(&prefix, path);
                continue;
            }
            let tree = match walk::walk(path, &sample_file) {
                Ok(tree) => tree,
                Err(e) => {
                    catalog.push(
                        &prefix,
                        Entry::broken(
                            &source,
                            &source,
                            format!("cannot read the dataset folder: {e}"),
                        ),
                        Origin::Broken,
                    );
                    continue;
                }
            };
            let mut samples = Vec::new();
            file_samples(path, &tree, &mut samples);
            let fallback =
                path.file_name().map_or("dataset".into(), |n| n.to_string_lossy().to_string());
            let listed: Vec<Entry> = samples
                .par_iter()
                .map(|(files, at, folder)| {
                    let name = at.strip_prefix(path).unwrap_or(at).display().to_string();
                    let fallback =
                        if folder.is_empty() { fallback.clone() } else { folder.clone() };
                    let read = files.as_ref().map_err(Clone::clone).and_then(|files| {
                        read_sample(files, &Deadline::default()).map_err(|e| e.to_string())
                    });
                    match read {
                        Ok(sample) => {
                            let frames = sample
                                .mesh
                                .as_ref()
                                .map_or(sample.frames.len(), |m| m.frames.len());
                            let category =
                                if sample.category.is_empty() || sample.category == "upload" {
                                    fallback
                                } else {
                                    sample.category.clone()
                                };
                            let (n, error) = match sample.border_frames() {
                                Ok(b) => (Some(b.len()), None),
                                Err(e) => (None, Some(e.to_string())),
                            };
                            let first = files
                                .as_ref()
                                .ok()
                                .and_then(|f| f.first())
                                .and_then(|f| f.file_name())
                                .map(|n| n.to_string_lossy().to_string())
                                .unwrap_or_default();
                            let shown = if sample.name.is_empty() || sample.name == first {
                                name.clone()
                            } else {
                                sample.name.clone()
                            };
                            Entry {
                                id: String::new(),
                                name: shown,
                                category,
                                n,
                                frames,
                                mesh: sample.mesh.is_some(),
                                source: source.clone(),
                                error,
                            }
                        }
                        Err(e) => Entry { category: fallback, ..Entry::broken(&name, &source, e) },
                    }
                })
                .collect();
            for ((files, _, _), entry) in samples.into_iter().zip(listed) {
                let stem = entry.name.clone();
                let origin = files.map_or(Origin::Broken, Origin::Files);
                catalog.push_named(&prefix, &stem, entry, origin);
            }
        }
        catalog
    }

    /// The videos of a store, cut into folds from their grips (in parallel).
    #[cfg(feature = "vrfolding")]
    fn add_store(&mut self, prefix: &str, path: &Path) {
        use crate::vrfolding::{Store, FOLDS};
        let source = path.display().to_string();
        let opened =
            Store::open(path).and_then(|store| store.videos().map(|videos| (store, videos)));
        let (store, (videos, unreadable)) = match opened {
            Ok(found) => found,
            Err(e) => {
                return self.push(
                    prefix,
                    Entry::broken(&source, &source, e.to_string()),
                    Origin::Broken,
                )
            }
        };
        for e in unreadable {
            let name = match &e {
                Error::Store { path, .. } => path.trim_start_matches('/').to_string(),
                _ => source.clone(),
            };
            self.push(prefix, Entry::broken(&name, &source, e.to_string()), Origin::Broken);
        }
        let cuts: Vec<Result<usize>> =
            videos.par_iter().map(|v| store.cut(v).map(|c| c.actions.len().min(FOLDS))).collect();
        let index = self.stores.len();
        for (v, (video, cut)) in videos.iter().zip(cuts).enumerate() {
            let name = format!("{}/{}", video.category, video.id);
            match cut {
                Ok(folds) => {
                    for fold in 1..=folds {
                        let entry = Entry {
                            id: String::new(),
                            name: format!("{name} fold {fold}"),
                            category: video.category.clone(),
                            n: None,
                            frames: fold + 1,
                            mesh: true,
                            source: source.clone(),
                            error: None,
                        };
                        self.push_named(
                            prefix,
                            &format!("{}-{}-fold{fold}", video.category, video.id),
                            entry,
                            Origin::Fold { store: index, video: v, fold },
                        );
                    }
                }
                Err(e) => self.push_named(
                    prefix,
                    &name,
                    Entry {
                        category: video.category.clone(),
                        ..Entry::broken(&name, &source, e.to_string())
                    },
                    Origin::Broken,
                ),
            }
        }
        self.stores.push((store, videos));
    }

    fn push(&mut self, prefix: &str, entry: Entry, origin: Origin) {
        let stem = entry.name.clone();
        self.push_named(prefix, &stem, entry, origin);
    }

    /// Add an entry under a unique id `<prefix>-<slug of stem>`. A sequence (more than two
    /// frames: a fold after a fold) is filed under `<category>_second_fold`, as the built-in
    /// sequences are.
    fn push_named(&mut self, prefix: &str, stem: &str, mut entry: Entry, origin: Origin) {
        if entry.frames > 2 && !entry.category.ends_with(SECOND_FOLD) {
            entry.category.push_str(SECOND_FOLD);
        }
        let base = format!("{prefix}-{}", slug(stem));
        let mut id = base.clone();
        let mut k = 1;
        while self.index.contains_key(&id) {
            k += 1;
            id = format!("{base}-{k}");
        }
        entry.id = id.clone();
        self.index.insert(id, self.entries.len());
        self.entries.push(entry);
        self.origins.push(origin);
    }

    /// Every entry, in listing order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The entry with this id.
    pub fn get(&self, id: &str) -> Option<&Entry> {
        self.index.get(id).map(|&k| &self.entries[k])
    }

    /// The entries that pass `query`'s filters (paging is left to the caller, which may
    /// merge other lists first).
    pub fn filter(&self, query: &Query) -> Vec<&Entry> {
        self.entries.iter().filter(|e| query.matches(&e.id, &e.name, &e.category)).collect()
    }

    /// Load sample `id` (cached), stopping with [`Error::Cancelled`] once `deadline`
    /// expires. A load that fails for any other reason is remembered and answered again
    /// without reading.
    pub fn load(&self, id: &str, deadline: &Deadline) -> Result<Arc<Sample>> {
        let &k = self.index.get(id).ok_or_else(|| Error::UnknownSample { id: id.to_string() })?;
        let cache = || self.cache.lock().unwrap_or_else(|e| e.into_inner());
        let refused = || self.refused.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(hit) = cache().get(id) {
            return Ok(hit);
        }
        if let Some(error) = refused().get(id) {
            return Err(error.clone());
        }
        match self.read(k, deadline) {
            Ok(sample) => {
                let sample = Arc::new(sample);
                cache().insert(id.to_string(), sample.clone(), sample.weight());
                Ok(sample)
            }
            Err(Error::Cancelled) => Err(Error::Cancelled),
            Err(error) => {
                refused().insert(id.to_string(), error.clone());
                Err(error)
            }
        }
    }

    /// Read entry `k`'s sample from its origin.
    fn read(&self, k: usize, deadline: &Deadline) -> Result<Sample> {
        let entry = &self.entries[k];
        deadline.check()?;
        let mut sample = match &self.origins[k] {
            Origin::Files(files) => read_sample(files, deadline)?,
            #[cfg(feature = "vrfolding")]
            &Origin::Fold { store, video, fold } => {
                let (store, videos) = &self.stores[store];
                let folds = store.folds(&videos[video])?;
                folds.sample(&videos[video], fold).ok_or_else(|| Error::Store {
                    store: entry.source.clone(),
                    path: entry.name.clone(),
                    problem: "dropped: a mesh of this fold is broken (BiFold's z-score test)"
                        .into(),
                })?
            }
            Origin::Broken => {
                return Err(Error::InvalidArgument(entry.error.clone().unwrap_or_default()))
            }
        };
        sample.name = entry.name.clone();
        sample.category = entry.category.clone();
        Ok(sample)
    }
}

impl Entry {
    fn broken(name: &str, source: &str, error: String) -> Entry {
        Entry {
            id: String::new(),
            name: name.to_string(),
            category: String::new(),
            n: None,
            frames: 0,
            mesh: false,
            source: source.to_string(),
            error: Some(error),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("close-catalog-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    const SQUARE: &str = "0,0,0\n1,0,0\n1,1,0\n0,1,0\n";

    #[test]
    fn files_and_frame_folders_are_samples_and_errors_stay_in_the_list() {
        let dir = folder("mixed");
        std::fs::write(dir.join("a.json"), r#"{"name": "a", "category": "napkin", "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]],[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}"#).unwrap();
        std::fs::write(dir.join("bad.json"), "[1, 2").unwrap();
        std::fs::create_dir_all(dir.join("towel_run")).unwrap();
        std::fs::write(dir.join("towel_run/f0.csv"), SQUARE).unwrap();
        std::fs::write(dir.join("towel_run/f1.csv"), SQUARE).unwrap();
        std::fs::write(dir.join("notes.md"), "ignored").unwrap();
        let catalog = Catalog::open(&[dir.clone(), dir.join("missing")]);
        let entries = catalog.entries();
        assert_eq!(entries.len(), 4, "{entries:#?}");
        let run = entries.iter().find(|e| e.name == "towel_run").unwrap();
        assert_eq!((run.n, run.frames, run.error.as_deref()), (Some(4), 2, None));
        assert!(entries.iter().any(
            |e| e.name == "bad.json" && e.error.as_deref().is_some_and(|m| m.contains("parse"))
        ));
        assert!(entries.iter().any(|e| e
            .error
            .as_deref()
            .is_some_and(|m| m.contains("cannot read the dataset folder"))));
        let ids: std::collections::HashSet<&str> = entries.iter().map(|e| e.id.as_str()).collect();
        assert_eq!(ids.len(), 4);
        assert!(ids
            .iter()
            .all(|id| id.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c))));
        let forever = Deadline::default();
        let loaded = catalog.load(&run.id, &forever).unwrap();
        assert_eq!(loaded.frames.len(), 2);
        assert!(
            Arc::ptr_eq(&loaded, &catalog.load(&run.id, &forever).unwrap()),
            "the second load is the cached one"
        );
        assert!(matches!(catalog.load("nope", &forever), Err(Error::UnknownSample { .. })));
        let bad = entries.iter().find(|e| e.name == "bad.json").unwrap();
        assert!(catalog.load(&bad.id, &forever).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn queries_filter_by_category_and_text() {
        let q =
            Query { category: Some("napkin".into()), q: Some("DIAG".into()), ..Query::default() };
        assert!(q.matches("d0-x", "napkin_diag_half", "napkin"));
        assert!(!q.matches("d0-x", "napkin_half", "napkin"));
        assert!(!q.matches("d0-x", "towel_diag", "towel"));
        assert!(Query::default().matches("a", "b", "c"));
    }
}
