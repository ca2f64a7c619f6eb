//! VR-Folding (Xue et al., GarmentTracking, CVPR 2023), the dataset of the first and second
//! fold rows of Table I of Kamat, Borràs, Torras ("CloSE"), read from its Zarr v2 store.
//!
//! The store, as the dataset's own loaders read it: `<store>/<Category>/samples/<frame>/`,
//! one group per frame, whose attributes hold `video_id` (else `instance_id`),
//! `garment_name`, `sample_id` and `scale`, with the arrays `mesh/cloth_verts` (float [V, 3],
//! world positions), `mesh/cloth_faces_tri` (int [F, 3], the same in every frame of a
//! video), `mesh/cloth_nocs_verts` (float [V, 3], canonical positions) and
//! `grip_vertex_id/{left,right}_grip_vertex_id` (int `[k]`, `[-1]` while a hand holds nothing).
//! Chunks are Blosc-compressed: [`blosc`] decodes them and `zarrs` reads the arrays.
//!
//! A video's frames (sorted by `sample_id`) are cut into fold actions by BiFold's rule
//! ([`Store::cut`], [`bifold`]); an action whose start or end mesh fails BiFold's broken-mesh test
//! ([`broken`]) is dropped. The border is the paper's silhouette border (zenithal depth mask,
//! ε-cover with ε = [`crate::mesh::silhouette::EPSILON`]) of the video's first frame,
//! followed through the frames by mesh vertex. Fold 1 compares the start of action 1 with
//! its end; fold 2 is the sequence (start of action 1, end of action 1, end of action 2)
//! scored on its second step ([`VideoFolds::sample`]). `scale` is not needed: every
//! measure is taken on borders normalised by the start frame.
//!
//! A video is read as a stream: each frame's grips, then only the frames the folds use, each
//! chunk once; a whole mesh is alive only while its frame is tested.
//!
//! A store is the user's data, not trusted. Its files are read through [`files`]: never
//! out of the store, regular files only, each sized before a byte is read. Before an array
//! is read, its shape is checked against the mesh limits ([`MAX_MESH_VERTICES`] rows of
//! vertices, [`MAX_MESH_FACES`] of faces, as many grip ids as the mesh has vertices), its
//! chunk shape against the same bound and its chunk count against [`MAX_ARRAY_CHUNKS`];
//! each stored chunk's file size against what its chunk can hold, and its declared decoded
//! size (Blosc's header, which its decoder allocates) against its chunk shape; the chunk
//! decoded is the very bytes checked. Cutting a video reads its grips: what that reads is
//! counted from the arrays' metadata before any chunk is, against [`LISTING`] per video, and
//! per store when a catalog lists every video ([`Store::cut_all`]). A frame whose
//! attributes cannot be read is one error, and the other frames and videos are kept
//! ([`Store::videos`]).
//!
//! ```no_run
//! use close_io::vrfolding::Store;
//! let store = Store::open("vr_simulation_folding2_dataset.zarr".as_ref()).unwrap();
//! let (videos, unreadable) = store.videos().unwrap();
//! for e in unreadable {
//!     eprintln!("{e}");
//! }
//! for video in videos {
//!     let folds = store.folds(&video).unwrap();
//!     println!("{} {}: {} actions", video.category, video.id, folds.actions.len());
//! }
//! ```

pub mod bifold;
pub mod blosc;
pub mod broken;
pub mod files;

use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde_json::Value;
use zarrs::array::{Array, ArrayMetadata, ArrayMetadataV2};
use zarrs::config::MetadataRetrieveVersion;
use zarrs::group::Group;
use zarrs::plugin::{ExtensionName, ZarrVersion};
use zarrs::storage::store::MemoryStore;
use zarrs::storage::{ListableStorageTraits, StorePrefix, WritableStorageTraits};

use crate::error::{Error, Result};
use crate::formats::Sample;
use crate::mesh::silhouette::{Silhouette, EPSILON};
use crate::mesh::{MAX_MESH_FACES, MAX_MESH_VERTICES};
use bifold::Action;
use files::{StoreFiles, MAX_METADATA_BYTES};

/// Folds scored per video: the paper's Table I has first and second folds.
pub const FOLDS: usize = 2;

/// Most chunks one array may have: a store written by zarr has a few per array, and each
/// chunk is a file to open (a forged `chunks: [1]` would make millions of them).
pub const MAX_ARRAY_CHUNKS: u64 = 1024;

/// What cutting videos into actions reads: their grip arrays' ids and chunk files.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CutWork {
    pub ids: u64,
    pub chunks: u64,
}

/// The most cutting may read: for one video, and for every video of a store a catalog
/// lists. A real store's frames hold a few grip ids in one chunk per hand, so a million
/// frames are well inside it.
pub const LISTING: CutWork = CutWork { ids: 1 << 26, chunks: 1 << 22 };

impl CutWork {
    fn plus(self, other: CutWork) -> CutWork {
        CutWork {
            ids: self.ids.saturating_add(other.ids),
            chunks: self.chunks.saturating_add(other.chunks),
        }
    }

    /// Whether this work fits in `limit`.
    fn within(self, limit: CutWork) -> bool {
        self.ids <= limit.ids && self.chunks <= limit.chunks
    }
}

/// An open VR-Folding store (or one category folder of it).
pub struct Store {
    path: PathBuf,
    fs: Arc<StoreFiles>,
    /// Category name → node path of its `samples` group.
    categories: Vec<(String, String)>,
}

/// One recording: its frames' group paths in `sample_id` order.
#[derive(Debug, Clone, PartialEq)]
pub struct Video {
    pub category: String,
    pub id: String,
    pub garment: String,
    /// Node paths of the frame groups, in `sample_id` order.
    pub frames: Vec<String>,
}

/// A video cut into actions, with the border frames its folds need.
#[derive(Debug, Clone, PartialEq)]
pub struct VideoFolds {
    pub actions: Vec<Action>,
    /// A hand still gripped in the last frame: that action never ended and is not counted.
    pub unfinished: bool,
    /// For each of the first [`FOLDS`] actions: whether its start or end mesh is broken.
    pub broken: Vec<bool>,
    /// Mesh vertex count.
    pub vertices: usize,
    /// The silhouette border of the video's first frame, as mesh vertex ids.
    pub border_indices: Vec<usize>,
    /// Border positions at the start of action 1 and the ends of the usable actions.
    pub frames: Vec<Vec<[f64; 3]>>,
}

impl VideoFolds {
    /// Folds that can be scored: actions 1…k all present and none broken.
    pub fn usable(&self) -> usize {
        self.broken.iter().take_while(|b| !**b).count()
    }

    /// Folds that exist but cannot be scored because a mesh they use is broken.
    pub fn dropped(&self) -> usize {
        self.broken.len() - self.usable()
    }

    /// Fold `k` (1-based) as a border sample: frames (start of action 1, end of action 1, …,
    /// end of action k), so fold k is its k-th step; `None` when fold k is absent or dropped.
    pub fn sample(&self, video: &Video, k: usize) -> Option<Sample> {
        (k >= 1 && k <= self.usable()).then(|| {
            Sample::from_frames(
                format!("{}/fold{k}", video.id),
                format!("{}/fold{k}", video.category),
                self.frames[..=k].to_vec(),
            )
        })
    }
}

/// Whether `path` looks like a Zarr v2 group (a store or a category of one).
pub fn is_store(path: &Path) -> bool {
    path.join(".zgroup").is_file()
}

/// A JSON attribute as text (`video_id` may be stored as a string or a number).
fn attr_text(attrs: &serde_json::Map<String, Value>, key: &str) -> Option<String> {
    match attrs.get(key)? {
        Value::String(s) => Some(s.clone()),
        Value::Number(n) => Some(n.to_string()),
        _ => None,
    }
}

impl Store {
    /// Open a store, or one category folder of it (a group holding `samples/`).
    pub fn open(path: &Path) -> Result<Store> {
        let problem = |p: &str, m: String| Error::Store {
            store: path.display().to_string(),
            path: p.into(),
            problem: m,
        };
        if !path.is_dir() {
            return Err(problem("/", "not a folder".into()));
        }
        if !is_store(path) {
            return Err(problem("/", "not a Zarr v2 group (no .zgroup): expected a VR-Folding store or one of its category folders".into()));
        }
        let fs = Arc::new(StoreFiles::new(path).map_err(|e| problem("/", e.to_string()))?);
        let mut store = Store { path: path.to_path_buf(), fs, categories: Vec::new() };
        if store.group("/samples").is_ok() {
            let name = path
                .file_name()
                .map_or("store".into(), |n| n.to_string_lossy().trim_end_matches('/').to_string());
            store.categories.push((name, "/samples".into()));
        } else {
            for child in store.children("/")? {
                let samples = format!("/{child}/samples");
                if store.group(&samples).is_ok() {
                    store.categories.push((child, samples));
                }
            }
        }
        if store.categories.is_empty() {
            return Err(problem(
                "/",
                "no category group with a samples/ group (e.g. Tshirt/samples)".into(),
            ));
        }
        Ok(store)
    }

    /// The store's folder.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Category names, sorted.
    pub fn categories(&self) -> Vec<&str> {
        self.categories.iter().map(|(c, _)| c.as_str()).collect()
    }

    /// An error of `path` in this store; the problem's quotes of the store's files (a
    /// metadata parser's message may quote them) are left out.
    fn error(&self, path: &str, problem: impl ToString) -> Error {
        Error::Store {
            store: self.path.display().to_string(),
            path: path.into(),
            problem: crate::formats::redact(&problem.to_string()),
        }
    }

    fn group(&self, path: &str) -> Result<Group<StoreFiles>> {
        Group::open_opt(self.fs.clone(), path, &MetadataRetrieveVersion::V2)
            .map_err(|e| self.error(path, format!("missing or unreadable group: {e}")))
    }

    /// Names of the child groups/arrays of `path`, sorted.
    fn children(&self, path: &str) -> Result<Vec<String>> {
        let prefix = if path == "/" {
            StorePrefix::root()
        } else {
            StorePrefix::new(format!("{}/", path.trim_matches('/')))
                .map_err(|e| self.error(path, e))?
        };
        let listed = self.fs.list_dir(&prefix).map_err(|e| self.error(path, e))?;
        let mut names: Vec<String> = listed
            .prefixes()
            .iter()
            .filter_map(|p| p.as_str().trim_end_matches('/').rsplit('/').next().map(str::to_string))
            .filter(|n| !n.starts_with('.'))
            .collect();
        names.sort();
        Ok(names)
    }

    /// Every video of every category: frames grouped by `video_id` (else `instance_id`) and
    /// sorted by `sample_id`, and an error for each frame whose attributes cannot be read (an
    /// interrupted download, a forged `sample_id`): it is left out, the rest are kept. Reads
    /// each frame's attributes once.
    pub fn videos(&self) -> Result<(Vec<Video>, Vec<Error>)> {
        use rayon::prelude::*;
        let mut out = Vec::new();
        let mut unreadable = Vec::new();
        for (category, samples) in &self.categories {
            // Opening a group is a few small file reads: the frames are read in parallel.
            let frames = self
                .children(samples)?
                .into_par_iter()
                .map(|frame| {
                    let path = format!("{samples}/{frame}");
                    let group = self.group(&path)?;
                    let attrs = group.attributes();
                    let video = attr_text(attrs, "video_id")
                        .or_else(|| attr_text(attrs, "instance_id"))
                        .ok_or_else(|| {
                            self.error(
                                &path,
                                "the frame's attributes have no video_id or instance_id",
                            )
                        })?;
                    let sample_id =
                        attrs.get("sample_id").and_then(Value::as_i64).ok_or_else(|| {
                            self.error(&path, "the frame's attributes have no integer sample_id")
                        })?;
                    let garment =
                        attr_text(attrs, "garment_name").unwrap_or_else(|| category.clone());
                    Ok((video, sample_id, path, garment))
                })
                .collect::<Vec<Result<_>>>();
            let mut videos: BTreeMap<String, Vec<(i64, String, String)>> = BTreeMap::new();
            for frame in frames {
                match frame {
                    Ok((video, sample_id, path, garment)) => {
                        videos.entry(video).or_default().push((sample_id, path, garment))
                    }
                    Err(e) => unreadable.push(e),
                }
            }
            for (id, mut frames) in videos {
                frames.sort();
                let garment = frames[0].2.clone();
                out.push(Video {
                    category: category.clone(),
                    id,
                    garment,
                    frames: frames.into_iter().map(|f| f.1).collect(),
                });
            }
        }
        Ok((out, unreadable))
    }

    /// Open array `path` and check its shape: 1-D (`width` None) or [rows, width], with at
    /// most `max_rows` rows, chunks of at most as many elements and at most
    /// [`MAX_ARRAY_CHUNKS`] of them. Only its metadata is read; its compressor must be Blosc
    /// or none, and is taken out of what zarrs is given ([`blosc`] decodes the chunks).
    fn open_array(&self, path: &str, width: Option<u64>, max_rows: usize) -> Result<Opened> {
        let unreadable = |e: &dyn std::fmt::Display| {
            self.error(path, format!("missing or unreadable array: {e}"))
        };
        let key = format!("{}/.zarray", path.trim_matches('/'));
        let metadata = self
            .fs
            .read(&key, MAX_METADATA_BYTES)
            .map_err(|e| unreadable(&e))?
            .ok_or_else(|| unreadable(&"no .zarray"))?;
        let mut metadata: ArrayMetadataV2 =
            serde_json::from_slice(&metadata).map_err(|e| unreadable(&e))?;
        let blosc = match metadata.compressor.take() {
            None => false,
            Some(c) if c.id() == "blosc" => true,
            Some(c) => {
                // The store's own text is named only when it is a plain name.
                let plain = c.id().len() <= 40
                    && c.id().chars().all(|ch| ch.is_ascii_alphanumeric() || "_-.".contains(ch));
                let named = if plain { c.id() } else { "(not a codec's name)" };
                return Err(self.error(
                    path,
                    format!("compressor {named}: a VR-Folding store's chunks are Blosc-compressed or not compressed"),
                ));
            }
        };
        let array = Array::new_with_metadata(self.fs.clone(), path, ArrayMetadata::V2(metadata))
            .map_err(|e| unreadable(&e))?;
        let rows = match (array.shape(), width) {
            (&[rows], None) => rows,
            (&[rows, w], Some(width)) if w == width => rows,
            (shape, _) => {
                let expected = width.map_or("[k]".to_string(), |w| format!("[rows, {w}]"));
                return Err(self.error(path, format!("shape {shape:?}, expected {expected}")));
            }
        };
        if rows > max_rows as u64 {
            return Err(self.error(
                path,
                format!("shape {:?}: more than {max_rows} rows, the limit", array.shape()),
            ));
        }
        let rows = usize::try_from(rows).map_err(|_| self.error(path, "too many rows"))?;
        let most = (max_rows as u64).saturating_mul(width.unwrap_or(1));
        let chunk =
            array.chunk_shape(&vec![0; array.dimensionality()]).map_err(|e| self.error(path, e))?;
        let elements = chunk.iter().map(|d| d.get()).fold(1u64, u64::saturating_mul);
        if elements > most {
            return Err(self.error(
                path,
                format!(
                    "chunks of {elements} elements: more than {most}, the limit of the whole array"
                ),
            ));
        }
        let chunks = array.chunk_grid_shape().iter().fold(1u64, |a, &b| a.saturating_mul(b));
        if chunks > MAX_ARRAY_CHUNKS {
            return Err(self.error(
                path,
                format!(
                    "{chunks} chunks of shape {chunk:?}: more than {MAX_ARRAY_CHUNKS}, the limit of one array"
                ),
            ));
        }
        let kind = array
            .data_type()
            .name(ZarrVersion::V3)
            .map_or_else(|| array.data_type().to_string(), |n| n.to_string());
        Ok(Opened { array, blosc, rows, kind })
    }

    /// Read the whole of an opened array (at `path`). Each stored chunk is read once, through
    /// [`StoreFiles::read`] with its own cap (refused unread when its file is larger than the
    /// chunk can be encoded in), checked ([`Store::check_chunk`]), decoded from Blosc
    /// ([`blosc::decode`]) and handed to zarrs: the very bytes checked, from memory, so a
    /// file swapped after the check is never decoded.
    fn retrieve<T: zarrs::array::ElementOwned>(
        &self,
        opened: &Opened,
        path: &str,
    ) -> Result<Vec<T>> {
        let array = &opened.array;
        let element = array
            .data_type()
            .fixed_size()
            .ok_or_else(|| self.error(path, "a data type of variable size"))?;
        let checked = Arc::new(MemoryStore::new());
        let view = Array::new_with_metadata(checked.clone(), path, array.metadata().clone())
            .map_err(|e| self.error(path, e))?;
        let chunks =
            array.chunks_in_array_subset(&array.subset_all()).map_err(|e| self.error(path, e))?;
        for indices in chunks.iter().flat_map(|c| c.indices().into_iter()) {
            let shape = array.chunk_shape(&indices).map_err(|e| self.error(path, e))?;
            let size = shape.iter().map(|d| d.get()).fold(element as u64, u64::saturating_mul);
            // Blosc adds a 16-byte header and never more than that.
            let most = size.saturating_add(size / 16).saturating_add(64);
            let key = array.chunk_key(&indices);
            let Some(encoded) =
                self.fs.read(key.as_str(), most).map_err(|e| self.error(path, e))?
            else {
                continue;
            };
            self.check_chunk(opened.blosc, path, &indices, &shape, size, &encoded)?;
            let decoded = if opened.blosc {
                blosc::decode(&encoded).map_err(|e| {
                    self.error(path, format!("cannot decode chunk {indices:?}: {e}"))
                })?
            } else {
                encoded
            };
            checked.set(&key, decoded.into()).map_err(|e| self.error(path, e))?;
        }
        view.retrieve_array_subset(&view.subset_all())
            .map_err(|e| self.error(path, format!("cannot decode its chunks: {e}")))
    }

    /// Check a stored chunk before it is decoded: a Blosc chunk's declared decoded size (which
    /// the decoder allocates at once) and an uncompressed chunk's length must not exceed the
    /// chunk's own `size`, its shape × its element size. A forged header could otherwise ask
    /// for gigabytes from a few bytes.
    fn check_chunk(
        &self,
        blosc: bool,
        path: &str,
        indices: &[u64],
        shape: &[std::num::NonZeroU64],
        size: u64,
        encoded: &[u8],
    ) -> Result<()> {
        let declared =
            if blosc { blosc::declared_size(encoded).unwrap_or(0) } else { encoded.len() as u64 };
        if declared > size {
            return Err(self.error(path, format!("chunk {indices:?} decodes to {declared} bytes, but a chunk of shape {shape:?} holds {size}")));
        }
        Ok(())
    }

    /// A float [V, 3] array (float32 or float64) as points.
    fn points(&self, path: &str) -> Result<Vec<[f64; 3]>> {
        fn widen<T: Into<f64>>(v: Vec<T>) -> Vec<f64> {
            v.into_iter().map(Into::into).collect()
        }
        let opened = self.open_array(path, Some(3), MAX_MESH_VERTICES)?;
        let values = match opened.kind.as_str() {
            "float32" => widen(self.retrieve::<f32>(&opened, path)?),
            "float64" => self.retrieve::<f64>(&opened, path)?,
            other => {
                return Err(
                    self.error(path, format!("data type {other}, expected float32 or float64"))
                )
            }
        };
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(self.error(path, format!("non-finite coordinate at vertex {}", k / 3)));
        }
        Ok(values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
    }

    /// The integers of an open array (any width, signed or not) as i64.
    fn ints(&self, array: &Opened, path: &str) -> Result<Vec<i64>> {
        Ok(match array.kind.as_str() {
            "int8" => self.widen::<i8>(array, path)?,
            "int16" => self.widen::<i16>(array, path)?,
            "int32" => self.widen::<i32>(array, path)?,
            "int64" => self.retrieve::<i64>(array, path)?,
            "uint8" => self.widen::<u8>(array, path)?,
            "uint16" => self.widen::<u16>(array, path)?,
            "uint32" => self.widen::<u32>(array, path)?,
            "uint64" => self
                .retrieve::<u64>(array, path)?
                .into_iter()
                .map(|v| i64::try_from(v).unwrap_or(i64::MAX))
                .collect(),
            other => return Err(self.error(path, format!("data type {other}, expected integers"))),
        })
    }

    fn widen<T: zarrs::array::ElementOwned + Into<i64>>(
        &self,
        array: &Opened,
        path: &str,
    ) -> Result<Vec<i64>> {
        Ok(self.retrieve::<T>(array, path)?.into_iter().map(Into::into).collect())
    }

    /// The mesh's vertex count (from frame 0's `cloth_verts` metadata) and the grip arrays
    /// of every frame of `video`, both hands, opened (metadata only): a hand holds at most
    /// every vertex. With what reading them would read.
    fn grip_arrays(&self, video: &Video) -> Result<(usize, Vec<[Opened; 2]>, CutWork)> {
        let Some(first) = video.frames.first() else {
            return Err(self.error(&video.id, "the video has no frame"));
        };
        let vertices =
            self.open_array(&format!("{first}/mesh/cloth_verts"), Some(3), MAX_MESH_VERTICES)?.rows;
        let mut work = CutWork::default();
        let grips = video
            .frames
            .iter()
            .map(|f| {
                let hands = ["left", "right"]
                    .map(|hand| self.open_array(&grip_path(f, hand), None, vertices.max(1)));
                let [left, right] = hands;
                let hands = [left?, right?];
                for hand in &hands {
                    let chunks = hand
                        .array
                        .chunk_grid_shape()
                        .iter()
                        .fold(1u64, |a, &b| a.saturating_mul(b));
                    work = work.plus(CutWork { ids: hand.rows as u64, chunks });
                }
                Ok(hands)
            })
            .collect::<Result<Vec<_>>>()?;
        Ok((vertices, grips, work))
    }

    /// What cutting `video` reads ([`Store::cut`]), from its arrays' metadata alone.
    pub fn cut_work(&self, video: &Video) -> Result<CutWork> {
        self.grip_arrays(video).map(|(_, _, work)| work)
    }

    /// Cut `video` into fold actions from its grips alone (no mesh is read); a video with
    /// no finished action is an error, and so is one whose grips would read more than
    /// [`LISTING`] (counted before any is read).
    pub fn cut(&self, video: &Video) -> Result<bifold::Actions> {
        let (vertices, grips, work) = self.grip_arrays(video)?;
        if !work.within(LISTING) {
            return Err(self.over_listing(video, work, "its grips alone"));
        }
        let grips = video
            .frames
            .iter()
            .zip(&grips)
            .map(|(frame, [left, right])| {
                let left = self.grip(&grip_path(frame, "left"), left, vertices)?;
                Ok(left | self.grip(&grip_path(frame, "right"), right, vertices)?)
            })
            .collect::<Result<Vec<bool>>>()?;
        let cut = bifold::actions(&grips);
        if cut.actions.is_empty() {
            let why = if cut.unfinished {
                "a hand grips until the last frame and never lets go"
            } else {
                "no hand grips in any frame"
            };
            return Err(self.error(
                &format!("video {}", video.id),
                format!("no fold action in its {} frames: {why}", video.frames.len()),
            ));
        }
        Ok(cut)
    }

    /// Why `video` is not cut: reading `what` would pass [`LISTING`].
    fn over_listing(&self, video: &Video, work: CutWork, what: &str) -> Error {
        self.error(
            &format!("video {}", video.id),
            format!(
                "not cut: {what} would read {} grip ids in {} chunk files, more than the limit of {} ids in {} files (name the video's category folder as a dataset of its own to list it)",
                work.ids, work.chunks, LISTING.ids, LISTING.chunks
            ),
        )
    }

    /// Cut every video of `videos` (in parallel), within [`LISTING`] for them all: each
    /// video's work is counted from metadata first, in order, and a video that would take
    /// the total past the limit is an error, not read.
    pub fn cut_all(&self, videos: &[Video]) -> Vec<Result<bifold::Actions>> {
        use rayon::prelude::*;
        let works: Vec<Result<CutWork>> = videos.par_iter().map(|v| self.cut_work(v)).collect();
        let mut total = CutWork::default();
        let admitted: Vec<Result<()>> = videos
            .iter()
            .zip(works)
            .map(|(video, work)| {
                let work = work?;
                let after = total.plus(work);
                if !after.within(LISTING) {
                    return Err(self.over_listing(
                        video,
                        after,
                        "the store's videos up to this one",
                    ));
                }
                total = after;
                Ok(())
            })
            .collect();
        videos
            .par_iter()
            .zip(admitted)
            .map(|(video, admitted)| admitted.and_then(|()| self.cut(video)))
            .collect()
    }

    /// Whether the hand whose grip array is `path` (opened) grips; its vertex ids are
    /// checked against the mesh's `vertices`.
    fn grip(&self, path: &str, array: &Opened, vertices: usize) -> Result<bool> {
        let ids = self.ints(array, path)?;
        if let Some(&bad) = ids.iter().find(|&&v| v < -1 || v >= vertices as i64) {
            return Err(self.error(path, format!("gripped vertex {bad} is out of range: the mesh has {vertices} vertices (ids 0…{}, or -1 for none)", vertices.saturating_sub(1))));
        }
        Ok(bifold::holds(&ids))
    }

    /// Cut `video` into actions and read the border frames of its first [`FOLDS`] folds.
    pub fn folds(&self, video: &Video) -> Result<VideoFolds> {
        let cut = self.cut(video)?;
        let first = &video.frames[0];
        let verts0 = self.points(&format!("{first}/mesh/cloth_verts"))?;
        let vertices = verts0.len();
        if vertices < close_core::border::MIN_VERTICES {
            return Err(self.error(
                &format!("{first}/mesh/cloth_verts"),
                format!("{vertices} vertices: too few for a cloth"),
            ));
        }
        let faces = self.faces(&format!("{first}/mesh/cloth_faces_tri"), vertices)?;
        let nocs = self.points(&format!("{first}/mesh/cloth_nocs_verts"))?;
        if nocs.len() != vertices {
            return Err(self.error(
                &format!("{first}/mesh/cloth_nocs_verts"),
                format!("{} vertices, but cloth_verts has {vertices}", nocs.len()),
            ));
        }
        let canonical = broken::max_edge_zscore(&nocs, &faces);
        drop(nocs);
        let faces_poly: Vec<Vec<usize>> = faces.iter().map(|f| f.to_vec()).collect();
        let border_indices = Silhouette::render(&verts0, &faces_poly)?.border(&verts0, EPSILON)?;
        if border_indices.len() < close_core::border::MIN_VERTICES {
            return Err(self.error(
                first,
                format!(
                    "the silhouette from +z gives only {} border vertices",
                    border_indices.len()
                ),
            ));
        }
        // Each needed frame is read once: its border positions and its broken-mesh verdict.
        let mut seen: HashMap<usize, (Vec<[f64; 3]>, bool)> = HashMap::new();
        let mut frame = |k: usize| -> Result<(Vec<[f64; 3]>, bool)> {
            if let Some(hit) = seen.get(&k) {
                return Ok(hit.clone());
            }
            let path = format!("{}/mesh/cloth_verts", video.frames[k]);
            let read;
            let verts = if k == 0 {
                &verts0
            } else {
                read = self.points(&path)?;
                &read
            };
            if verts.len() != vertices {
                return Err(self.error(
                    &path,
                    format!("{} vertices, but the video's first frame has {vertices}", verts.len()),
                ));
            }
            let bad = broken::is_broken(broken::max_edge_zscore(verts, &faces), canonical);
            let found = (border_indices.iter().map(|&i| verts[i]).collect(), bad);
            seen.insert(k, found.clone());
            Ok(found)
        };
        let mut frames = Vec::new();
        let mut broken = Vec::new();
        for (a, action) in cut.actions.iter().take(FOLDS).enumerate() {
            let (start, start_bad) = frame(action.start)?;
            let (end, end_bad) = frame(action.end)?;
            if a == 0 {
                frames.push(start);
            }
            frames.push(end);
            broken.push(start_bad || end_bad);
        }
        let usable = broken.iter().take_while(|b| !**b).count();
        frames.truncate(usable + 1);
        Ok(VideoFolds {
            actions: cut.actions,
            unfinished: cut.unfinished,
            broken,
            vertices,
            border_indices,
            frames,
        })
    }

    /// The triangles of `path`, every id checked against the mesh's `vertices`.
    fn faces(&self, path: &str, vertices: usize) -> Result<Vec<[usize; 3]>> {
        let ids = self.ints(&self.open_array(path, Some(3), MAX_MESH_FACES)?, path)?;
        if let Some(&bad) = ids.iter().find(|&&v| v < 0 || v >= vertices as i64) {
            return Err(self.error(
                path,
                format!("face uses vertex {bad}, but the mesh has {vertices} vertices"),
            ));
        }
        Ok(ids.chunks_exact(3).map(|c| [c[0] as usize, c[1] as usize, c[2] as usize]).collect())
    }
}

/// An array opened ([`Store::open_array`]).
struct Opened {
    /// The array as zarrs reads it: without its compressor.
    array: Array<StoreFiles>,
    /// Whether its chunks are Blosc-compressed ([`blosc::decode`]); else stored as they are.
    blosc: bool,
    rows: usize,
    /// Its data type's name ("float32", "int64", …).
    kind: String,
}

/// The grip array of `hand` ("left" or "right") in frame group `frame`.
fn grip_path(frame: &str, hand: &str) -> String {
    format!("{frame}/grip_vertex_id/{hand}_grip_vertex_id")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn copy(from: &Path, to: &Path) {
        std::fs::create_dir_all(to).unwrap();
        for entry in std::fs::read_dir(from).unwrap() {
            let entry = entry.unwrap();
            let path = entry.path();
            if path.is_dir() {
                copy(&path, &to.join(entry.file_name()));
            } else {
                std::fs::copy(&path, to.join(entry.file_name())).unwrap();
            }
        }
    }

    /// The fixture store's chunks are Blosc lz4; one of them set to name Snappy (the flags'
    /// top three bits), as a store written with `numcodecs.Blosc(cname="snappy")` does: the
    /// video's folds are an error naming the array, the chunk and the codec.
    #[test]
    fn a_chunk_naming_snappy_is_refused_by_name() {
        let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr/Top");
        let dir = std::env::temp_dir().join(format!("close-snappy-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        copy(&fixture, &dir);
        let store = Store::open(&dir).unwrap();
        let (videos, unreadable) = store.videos().unwrap();
        assert!(unreadable.is_empty());
        assert_eq!(store.folds(&videos[0]).unwrap().usable(), FOLDS, "the fixture decodes");
        let chunk =
            dir.join(videos[0].frames[0].trim_start_matches('/')).join("mesh/cloth_verts/0.0");
        let mut bytes = std::fs::read(&chunk).unwrap();
        assert_eq!(blosc::Codec::of_flags(bytes[2]), Some(blosc::Codec::Lz4));
        bytes[2] = (bytes[2] & 0x1f) | (2 << 5);
        std::fs::write(&chunk, bytes).unwrap();
        let e = store.folds(&videos[0]).unwrap_err().to_string();
        assert!(
            e.contains("mesh/cloth_verts") && e.contains("chunk [0, 0]") && e.contains("snappy"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
