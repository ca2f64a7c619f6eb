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
//! ([`walk`]); what it holds is split into [`items`] (a sample file, a folder of frame
//! files, a store nested in it, what could not be walked), the same split `close eval`
//! scores ([`crate::batch`]), and every item is listed, an error row for what cannot be
//! read. Only regular files are read, each through a byte cap, opened without following a
//! link and checked to be the file the walk listed ([`crate::formats::read_listed`]), and a
//! sample's files together are capped at [`MAX_SAMPLE_BYTES`] from their sizes before any
//! is read; a load checks its deadline between files; a load that fails (other than by its
//! deadline) is remembered, so asking again costs nothing.
//!
//! ```
//! use close_io::catalog::{Catalog, Filter};
//! let dir = std::env::temp_dir().join(format!("close-catalog-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("square.json"), r#"{"name": "square", "category": "napkin",
//!     "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}"#).unwrap();
//! std::fs::write(dir.join("broken.json"), "{").unwrap();
//! let catalog = Catalog::open(&[dir.clone()]);
//! assert_eq!(catalog.entries().len(), 2);
//! let napkins = catalog.filter(&Filter::new(Some("napkin"), None).unwrap());
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
use serde::Serialize;

use crate::cache::Lru;
use crate::error::{Error, Result};
use crate::formats::{read_files, read_listed, Sample, MAX_FILE_BYTES};
use close_core::budget::Deadline;
use close_core::Error as CoreError;
use walk::{Folder, Listed, Node};

/// Why a store cannot be read by a build without the `vrfolding` feature.
pub const NO_VRFOLDING: &str =
    "this close was built without the `vrfolding` feature: it cannot read Zarr stores";

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
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
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

/// Longest `q` (characters) a query may have.
pub const MAX_QUERY_CHARS: usize = 256;
/// Most words a `q` may have.
pub const MAX_QUERY_TERMS: usize = 8;

/// A query's filters, checked and made ready: matching a row costs at most
/// [`MAX_QUERY_TERMS`] substring searches of its text, each in time linear in the text.
#[derive(Debug, Clone)]
pub struct Filter {
    category: Option<String>,
    /// The words of `q`, lower case.
    terms: Vec<String>,
}

impl Filter {
    /// Rows of exactly `category` (none or empty: any) whose text holds every word of `q`
    /// (separated by white space, found case-insensitively in the id, name or category); a
    /// `q` over [`MAX_QUERY_CHARS`] characters or [`MAX_QUERY_TERMS`] words is refused.
    pub fn new(category: Option<&str>, q: Option<&str>) -> Result<Filter> {
        let q = q.unwrap_or_default();
        let chars = q.chars().count();
        if chars > MAX_QUERY_CHARS {
            return Err(Error::invalid(format!(
                "the search `q` has {chars} characters: at most {MAX_QUERY_CHARS}"
            )));
        }
        let terms: Vec<String> = q.split_whitespace().map(str::to_lowercase).collect();
        if terms.len() > MAX_QUERY_TERMS {
            return Err(Error::invalid(format!(
                "the search `q` has {} words: at most {MAX_QUERY_TERMS}",
                terms.len()
            )));
        }
        let category = category.filter(|c| !c.is_empty()).map(str::to_string);
        Ok(Filter { category, terms })
    }

    /// What a row's words are searched in: its id, name and category, lower case.
    pub fn text(id: &str, name: &str, category: &str) -> String {
        format!("{id}\n{name}\n{category}").to_lowercase()
    }

    /// Whether a row of this `category` and [`Filter::text`] `text` passes.
    pub fn matches(&self, category: &str, text: &str) -> bool {
        self.category.as_deref().is_none_or(|c| c == category)
            && self.terms.iter().all(|t| text.contains(t.as_str()))
    }
}

/// Where an entry's sample comes from.
enum Origin {
    /// The files of one sample (one Sample JSON / .mat, or one file per frame).
    Files(Vec<Listed>),
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

/// Most characters of a listed name or category.
const MAX_LISTED_CHARS: usize = 256;
/// Most characters of an id's stem (its prefix and a number keep it unique).
const MAX_ID_STEM: usize = 96;

/// `text`, cut to its first `chars` characters.
fn clipped(text: &str, chars: usize) -> String {
    text.char_indices().nth(chars).map_or(text, |(cut, _)| &text[..cut]).to_string()
}

/// `text` made safe for a URL path segment.
fn slug(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '-' })
        .collect()
}

/// Read a sample's files into a sample: their total size is checked against
/// [`MAX_SAMPLE_BYTES`] before any is read, each is read as the file the walk listed, a
/// regular file, through its cap ([`read_listed`]), and `deadline` is checked between files.
pub(crate) fn read_sample(files: &[Listed], deadline: &Deadline) -> Result<Sample> {
    let size = |f: &Listed| std::fs::symlink_metadata(&f.path).map(|m| m.len()).unwrap_or(0);
    let total = files.iter().map(size).fold(0u64, u64::saturating_add);
    if total > MAX_SAMPLE_BYTES {
        return Err(CoreError::TooLarge {
            what: "bytes in the files of one sample",
            got: Some(total),
            limit: MAX_SAMPLE_BYTES,
        }
        .into());
    }
    let mut read = 0u64;
    let named = files
        .iter()
        .map(|f| {
            deadline.check()?;
            let bytes = read_listed(&f.path, f.id)?;
            // Sizes may change between the check and the read: count what was read.
            read += bytes.len() as u64;
            if read > MAX_SAMPLE_BYTES {
                return Err(CoreError::TooLarge {
                    what: "bytes in the files of one sample",
                    got: Some(read),
                    limit: MAX_SAMPLE_BYTES,
                }
                .into());
            }
            Ok((f.path.display().to_string(), bytes))
        })
        .collect::<Result<Vec<_>>>()?;
    deadline.check()?;
    read_files(&named)
}

/// Whether a file may hold a sample or a frame (the walk leaves out the others).
fn sample_file(path: &Path) -> bool {
    SAMPLE_FILES.contains(&extension(path).as_str())
}

/// One thing a dataset folder holds ([`items`]): what the catalog lists as entries and
/// `close eval` scores as rows.
#[derive(Debug)]
pub enum Item {
    /// One sample's files (one sample file, or the frame files of a folder), where it is
    /// (the file or folder) and its category (the sub-folder it is in).
    Sample { files: Vec<Listed>, at: PathBuf, category: String },
    /// A VR-Folding store inside the folder (or a broken one: a `.zarr` folder, say).
    Store(PathBuf),
    /// What could not be walked, and why.
    Unreadable { at: PathBuf, why: String, category: String },
}

/// Everything dataset folder `root` holds, walked once ([`walk`]): each sample file; each
/// sub-folder of frame files (a sub-folder holding a Sample JSON or `.mat` file is a folder
/// of samples itself, named as a category), whose own sub-folders are walked on; each
/// store; each entry that could not be walked. Fails only when `root` cannot be listed.
pub fn items(root: &Path) -> std::io::Result<Vec<Item>> {
    let tree = walk::walk(root, &sample_file)?;
    let mut out = Vec::new();
    collect(root, &tree, true, &mut out);
    Ok(out)
}

/// The items of walked `folder` into `out`; its files too when `files`.
fn collect(root: &Path, folder: &Folder, files: bool, out: &mut Vec<Item>) {
    let category =
        folder.path.strip_prefix(root).ok().map(|r| r.display().to_string()).unwrap_or_default();
    for node in &folder.entries {
        match node {
            Node::Folder(sub) => {
                let listed: Vec<&Listed> = sub
                    .entries
                    .iter()
                    .filter_map(|n| if let Node::File(f) = n { Some(f) } else { None })
                    .collect();
                let frames: Vec<Listed> = listed
                    .iter()
                    .filter(|f| FRAME_FILES.contains(&extension(&f.path).as_str()))
                    .map(|f| (*f).clone())
                    .collect();
                let samples =
                    listed.iter().any(|f| ["json", "mat"].contains(&extension(&f.path).as_str()));
                if samples || frames.is_empty() {
                    collect(root, sub, true, out);
                } else {
                    let at = sub.path.clone();
                    out.push(Item::Sample { files: frames, at, category: category.clone() });
                    // Its sub-folders, stores and errors are items too: nothing is dropped.
                    collect(root, sub, false, out);
                }
            }
            Node::File(f) if files => out.push(Item::Sample {
                files: vec![f.clone()],
                at: f.path.clone(),
                category: category.clone(),
            }),
            Node::File(_) => {}
            Node::Store(at) => out.push(Item::Store(at.clone())),
            Node::Unreadable(at, why) => out.push(Item::Unreadable {
                at: at.clone(),
                why: why.clone(),
                category: category.clone(),
            }),
        }
    }
}

/// The name and category a sample read from item files is listed under: its own, else
/// the place it was found (`name`, the path in the dataset) and its sub-folder (`folder`,
/// the dataset's name at the top).
pub fn listed_as(sample: &Sample, files: &[Listed], name: &str, folder: &str) -> (String, String) {
    let category = if sample.category.is_empty() || sample.category == "upload" {
        folder.to_string()
    } else {
        sample.category.clone()
    };
    let first = files
        .first()
        .and_then(|f| f.path.file_name())
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let shown = if sample.name.is_empty() || sample.name == first {
        name.to_string()
    } else {
        sample.name.clone()
    };
    (shown, category)
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
            if walk::looks_like_store(path) {
                catalog.add_store(&prefix, path);
                continue;
            }
            let found = match items(path) {
                Ok(found) => found,
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
            let top =
                path.file_name().map_or("dataset".into(), |n| n.to_string_lossy().to_string());
            let name_of = |at: &Path| at.strip_prefix(path).unwrap_or(at).display().to_string();
            let folder_of = |category: &str| {
                if category.is_empty() {
                    top.clone()
                } else {
                    category.to_string()
                }
            };
            let listed: Vec<Option<Entry>> = found
                .par_iter()
                .map(|item| match item {
                    Item::Sample { files, at, category } => {
                        let (name, folder) = (name_of(at), folder_of(category));
                        Some(match read_sample(files, &Deadline::default()) {
                            Ok(sample) => Entry::of(&sample, files, &name, &folder, &source),
                            Err(e) => Entry {
                                category: folder,
                                ..Entry::broken(&name, &source, e.to_string())
                            },
                        })
                    }
                    Item::Unreadable { at, why, category } => Some(Entry {
                        category: folder_of(category),
                        ..Entry::broken(&name_of(at), &source, why.clone())
                    }),
                    Item::Store(_) => None,
                })
                .collect();
            for (item, entry) in found.into_iter().zip(listed) {
                match (item, entry) {
                    (Item::Sample { files, .. }, Some(entry)) => {
                        let stem = entry.name.clone();
                        catalog.push_named(&prefix, &stem, entry, Origin::Files(files));
                    }
                    (Item::Store(at), _) => catalog.add_store(&prefix, &at),
                    (_, Some(entry)) => catalog.push(&prefix, entry, Origin::Broken),
                    (_, None) => {}
                }
            }
        }
        catalog
    }

    /// The videos of a store, cut into folds from their grips (in parallel, within the
    /// store's listing budget: [`crate::vrfolding::Store::cut_all`]).
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
        let cuts = store.cut_all(&videos);
        let index = self.stores.len();
        for (v, (video, cut)) in videos.iter().zip(cuts).enumerate() {
            let name = format!("{}/{}", video.category, video.id);
            match cut {
                Ok(cut) => {
                    for fold in 1..=cut.actions.len().min(FOLDS) {
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

    /// Without the `vrfolding` feature a store is one error row.
    #[cfg(not(feature = "vrfolding"))]
    fn add_store(&mut self, prefix: &str, path: &Path) {
        let source = path.display().to_string();
        self.push(prefix, Entry::broken(&source, &source, NO_VRFOLDING.into()), Origin::Broken);
    }

    fn push(&mut self, prefix: &str, entry: Entry, origin: Origin) {
        let stem = entry.name.clone();
        self.push_named(prefix, &stem, entry, origin);
    }

    /// Add an entry under a unique id `<prefix>-<slug of stem>`. A sequence (more than two
    /// frames: a fold after a fold) is filed under `<category>_second_fold`, as the built-in
    /// sequences are.
    /// A name or category longer than [`MAX_LISTED_CHARS`] (a sample's own name may be
    /// megabytes) is cut, and so is the id's stem at [`MAX_ID_STEM`] characters.
    fn push_named(&mut self, prefix: &str, stem: &str, mut entry: Entry, origin: Origin) {
        entry.name = clipped(&entry.name, MAX_LISTED_CHARS);
        entry.category = clipped(&entry.category, MAX_LISTED_CHARS);
        if entry.frames > 2 && !entry.category.ends_with(SECOND_FOLD) {
            entry.category.push_str(SECOND_FOLD);
        }
        let base = format!("{prefix}-{}", clipped(&slug(stem), MAX_ID_STEM));
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

    /// The entries that pass `filter` (paging is left to the caller, which may merge other
    /// lists first).
    pub fn filter(&self, filter: &Filter) -> Vec<&Entry> {
        self.entries
            .iter()
            .filter(|e| filter.matches(&e.category, &Filter::text(&e.id, &e.name, &e.category)))
            .collect()
    }

    /// Load sample `id` (cached), stopping with [`close_core::Error::Cancelled`] once `deadline`
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
            Err(Error::Core(CoreError::Cancelled)) => Err(CoreError::Cancelled.into()),
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
            Origin::Broken => return Err(Error::invalid(entry.error.clone().unwrap_or_default())),
        };
        sample.name = entry.name.clone();
        sample.category = entry.category.clone();
        Ok(sample)
    }
}

impl Entry {
    /// The entry of `sample`, read from `files` found at `name` in sub-folder `folder` of
    /// dataset `source` ([`listed_as`]).
    fn of(sample: &Sample, files: &[Listed], name: &str, folder: &str, source: &str) -> Entry {
        let (name, category) = listed_as(sample, files, name, folder);
        let frames = sample.mesh.as_ref().map_or(sample.frames.len(), |m| m.frames.len());
        let (n, error) = match sample.border_frames() {
            Ok(b) => (Some(b.len()), None),
            Err(e) => (None, Some(e.to_string())),
        };
        Entry {
            id: String::new(),
            name,
            category,
            n,
            frames,
            mesh: sample.mesh.is_some(),
            source: source.to_string(),
            error,
        }
    }

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
    fn queries_filter_by_category_and_every_word_within_their_caps() {
        let f = Filter::new(Some("napkin"), Some(" DIAG  half ")).unwrap();
        let text = |id, name, category| Filter::text(id, name, category);
        assert!(f.matches("napkin", &text("d0-x", "napkin_diag_half", "napkin")));
        assert!(!f.matches("napkin", &text("d0-x", "napkin_diag", "napkin")));
        assert!(!f.matches("towel", &text("d0-x", "towel_diag_half", "towel")));
        assert!(Filter::new(None, None).unwrap().matches("c", &text("a", "b", "c")));
        // The caps: a 64 KB search, or nine words, is refused before any row is looked at.
        let e = Filter::new(None, Some(&"Σ".repeat(32_000))).unwrap_err().to_string();
        assert!(e.contains("32000 characters") && e.contains("256"), "{e}");
        let many = Filter::new(None, Some("a b c d e f g h i")).unwrap_err().to_string();
        assert!(many.contains("9 words"), "{many}");
        assert!(Filter::new(None, Some("a b c d e f g h")).is_ok());
    }
}
