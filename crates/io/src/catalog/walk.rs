//! Walking a dataset folder the user named, safely: every folder once, never out of it.
//!
//! - A folder is entered once, known by its device and inode: a link back up (`-> .`,
//!   `-> ..` inside the tree, the loops of build folders) is skipped, so the walk ends and
//!   lists each file once; a file reached by two names is listed once too.
//! - A link whose target is outside the named folder is not followed: it is reported (the
//!   user named the folder, not what its links point at). Naming the target itself is how
//!   to include it. A link inside it is listed as where it leads.
//! - A folder that cannot be listed (no permission), or lies more than [`MAX_DEPTH`] folders
//!   down, is reported by name; its siblings are walked.
//! - A folder that holds a Zarr store (a `.zgroup`, `.zarray` or `.zattrs` file, or a name
//!   ending in `.zarr`) is not walked into: it is one [`Node::Store`], read as a store.
//!
//! Files are listed, not read: each with its identity ([`Listed`]), so that a reader can
//! check, on the handle it opens, that it reads the file listed and no link put there since
//! ([`crate::formats::read_listed`]), and that it is a regular file.
//!
//! ```
//! use close_io::catalog::walk::{walk, Node};
//! let dir = std::env::temp_dir().join(format!("close-walk-doc-{}", std::process::id()));
//! std::fs::create_dir_all(dir.join("sub")).unwrap();
//! std::fs::write(dir.join("sub/a.json"), "{}").unwrap();
//! #[cfg(unix)]
//! std::os::unix::fs::symlink(".", dir.join("sub/again")).unwrap();
//! let tree = walk(&dir, &|_| true).unwrap();
//! let Node::Folder(sub) = &tree.entries[0] else { panic!("{tree:?}") };
//! assert!(matches!(sub.entries.as_slice(), [Node::File(a)] if a.path.ends_with("sub/a.json")));
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::collections::HashSet;
use std::path::{Path, PathBuf};

use crate::formats::FileId;

/// Folders a walk goes down at most below the named one.
pub const MAX_DEPTH: usize = 32;

/// One walked folder: its entries in name order.
#[derive(Debug, Default)]
pub struct Folder {
    pub path: PathBuf,
    pub entries: Vec<Node>,
}

/// A file as the walk listed it: where to read it (a link inside the folder replaced by
/// where it leads) and which file it was then.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Listed {
    pub path: PathBuf,
    pub id: Option<FileId>,
}

/// An entry of a walked folder.
#[derive(Debug)]
pub enum Node {
    /// Anything that is not a folder (a regular file, or a special file the reader refuses).
    File(Listed),
    Folder(Folder),
    /// A folder holding a Zarr store, not walked into.
    Store(PathBuf),
    /// What could not be walked, and why.
    Unreadable(PathBuf, String),
}

/// Whether folder `path` holds a Zarr store (or was meant to: a `.zarr` folder without its
/// `.zgroup` is a broken store, not a folder of samples).
pub fn looks_like_store(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("zarr"))
        || [".zgroup", ".zarray", ".zattrs"]
            .iter()
            .any(|name| std::fs::symlink_metadata(path.join(name)).is_ok())
}

struct Walker<'a> {
    /// The named folder, as named and canonical.
    root: PathBuf,
    canonical: PathBuf,
    seen: HashSet<FileId>,
    wanted: &'a dyn Fn(&Path) -> bool,
}

/// Walk folder `root`. Files for which `wanted` is false are left out (and so are the links
/// among them that leave the folder: only what the caller would read is reported). Fails
/// only when `root` itself cannot be listed.
pub fn walk(root: &Path, wanted: &dyn Fn(&Path) -> bool) -> std::io::Result<Folder> {
    let canonical = root.canonicalize()?;
    let mut walker = Walker { root: root.to_path_buf(), canonical, seen: HashSet::new(), wanted };
    let meta = std::fs::metadata(root)?;
    walker.seen.extend(FileId::of(&meta));
    let entries = walker.listing(root)?;
    Ok(walker.folder(root.to_path_buf(), entries, 0))
}

impl Walker<'_> {
    /// Sorted paths in `dir`; entries that vanish while listed are skipped.
    fn listing(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut paths: Vec<PathBuf> =
            std::fs::read_dir(dir)?.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        Ok(paths)
    }

    /// Folder `path` (`depth` folders below the root) and its `listed` entries.
    fn folder(&mut self, path: PathBuf, listed: Vec<PathBuf>, depth: usize) -> Folder {
        let entries = listed.into_iter().filter_map(|p| self.node(p, depth + 1)).collect();
        Folder { path, entries }
    }

    /// The node of `path`, `depth` folders below the root, or `None` when it is left out
    /// (unwanted, or already walked).
    fn node(&mut self, path: PathBuf, depth: usize) -> Option<Node> {
        let link = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink());
        let Ok(meta) = std::fs::metadata(&path) else {
            // A dangling link or a racing delete: the reader names the problem if wanted.
            return (self.wanted)(&path).then_some(Node::File(Listed { path, id: None }));
        };
        if !meta.is_dir() && !(self.wanted)(&path) {
            return None;
        }
        let path = if link {
            match path.canonicalize() {
                // Where it leads, under the folder as named.
                Ok(target) => match target.strip_prefix(&self.canonical) {
                    Ok(inside) => self.root.join(inside),
                    Err(_) => return Some(Node::Unreadable(path, format!("links to {}, outside the dataset folder: not followed (name it as a dataset to include it)", target.display()))),
                },
                Err(e) => {
                    return Some(Node::Unreadable(path, format!("cannot resolve the link: {e}")))
                }
            }
        } else {
            path
        };
        let id = FileId::of(&meta);
        if let Some(id) = id {
            if !self.seen.insert(id) {
                return None;
            }
        }
        if !meta.is_dir() {
            return Some(Node::File(Listed { path, id }));
        }
        if looks_like_store(&path) {
            return Some(Node::Store(path));
        }
        if depth > MAX_DEPTH {
            return Some(Node::Unreadable(
                path,
                format!("more than {MAX_DEPTH} folders down: not walked (name it as a dataset to include it)"),
            ));
        }
        match self.listing(&path) {
            Ok(listed) => Some(Node::Folder(self.folder(path, listed, depth))),
            Err(e) => Some(Node::Unreadable(path, format!("cannot read the folder: {e}"))),
        }
    }
}
