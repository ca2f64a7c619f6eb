//! Walking a dataset folder the user named, safely: every folder once, never out of it.
//!
//! - A folder is entered once, known by its device and inode: a link back up (`-> .`,
//!   `-> ..` inside the tree, the loops of build folders) is skipped, so the walk ends and
//!   lists each file once; a file reached by two names is listed once too.
//! - A link whose target is outside the named folder is not followed: it is reported (the
//!   user named the folder, not what its links point at). Naming the target itself is how
//!   to include it.
//! - A folder that cannot be listed (no permission) is reported by name; its siblings are
//!   walked.
//!
//! Files are listed, not read or opened: whether one is a regular file is the reader's
//! check ([`crate::formats::read_file`]), made on the open handle.
//!
//! ```
//! use close_io::catalog::walk::walk;
//! let dir = std::env::temp_dir().join(format!("close-walk-doc-{}", std::process::id()));
//! std::fs::create_dir_all(dir.join("sub")).unwrap();
//! std::fs::write(dir.join("sub/a.json"), "{}").unwrap();
//! #[cfg(unix)]
//! std::os::unix::fs::symlink(".", dir.join("sub/again")).unwrap();
//! let tree = walk(&dir, &|_| true).unwrap();
//! assert_eq!(tree.files().count(), 1);
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```

use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// One walked folder: its entries in name order.
#[derive(Debug, Default)]
pub struct Folder {
    pub path: PathBuf,
    pub entries: Vec<Node>,
}

/// An entry of a walked folder.
#[derive(Debug)]
pub enum Node {
    /// Anything that is not a folder (a regular file, or a special file the reader refuses).
    File(PathBuf),
    Folder(Folder),
    /// What could not be walked, and why.
    Unreadable(PathBuf, String),
}

impl Folder {
    /// Every file under this folder, depth first in name order.
    pub fn files(&self) -> Box<dyn Iterator<Item = &PathBuf> + '_> {
        Box::new(self.entries.iter().flat_map(|node| -> Box<dyn Iterator<Item = &PathBuf> + '_> {
            match node {
                Node::File(path) => Box::new(std::iter::once(path)),
                Node::Folder(folder) => folder.files(),
                Node::Unreadable(..) => Box::new(std::iter::empty()),
            }
        }))
    }

    /// Every entry that could not be walked, with its reason.
    pub fn unreadable(&self) -> Box<dyn Iterator<Item = (&PathBuf, &String)> + '_> {
        Box::new(self.entries.iter().flat_map(
            |node| -> Box<dyn Iterator<Item = (&PathBuf, &String)> + '_> {
                match node {
                    Node::Unreadable(path, why) => Box::new(std::iter::once((path, why))),
                    Node::Folder(folder) => folder.unreadable(),
                    Node::File(_) => Box::new(std::iter::empty()),
                }
            },
        ))
    }
}

/// Identity of a file or folder: device and inode.
type Identity = (u64, u64);

#[cfg(unix)]
fn identity(meta: &std::fs::Metadata) -> Option<Identity> {
    use std::os::unix::fs::MetadataExt;
    Some((meta.dev(), meta.ino()))
}

#[cfg(not(unix))]
fn identity(_: &std::fs::Metadata) -> Option<Identity> {
    None
}

struct Walker<'a> {
    root: PathBuf,
    seen: HashSet<Identity>,
    wanted: &'a dyn Fn(&Path) -> bool,
}

/// Walk folder `root`. Files for which `wanted` is false are left out (and so are the links
/// among them that leave the folder: only what the caller would read is reported). Fails
/// only when `root` itself cannot be listed.
pub fn walk(root: &Path, wanted: &dyn Fn(&Path) -> bool) -> std::io::Result<Folder> {
    let canonical = root.canonicalize()?;
    let mut walker = Walker { root: canonical, seen: HashSet::new(), wanted };
    let meta = std::fs::metadata(root)?;
    walker.seen.extend(identity(&meta));
    let entries = walker.listing(root)?;
    Ok(walker.folder(root.to_path_buf(), entries))
}

impl Walker<'_> {
    /// Sorted paths in `dir`; entries that vanish while listed are skipped.
    fn listing(&self, dir: &Path) -> std::io::Result<Vec<PathBuf>> {
        let mut paths: Vec<PathBuf> =
            std::fs::read_dir(dir)?.filter_map(|e| e.ok().map(|e| e.path())).collect();
        paths.sort();
        Ok(paths)
    }

    fn folder(&mut self, path: PathBuf, listed: Vec<PathBuf>) -> Folder {
        let entries = listed.into_iter().filter_map(|p| self.node(p)).collect();
        Folder { path, entries }
    }

    /// The node of `path`, or `None` when it is left out (unwanted, or already walked).
    fn node(&mut self, path: PathBuf) -> Option<Node> {
        let link = std::fs::symlink_metadata(&path).is_ok_and(|m| m.file_type().is_symlink());
        let Ok(meta) = std::fs::metadata(&path) else {
            // A dangling link or a racing delete: the reader names the problem if wanted.
            return (self.wanted)(&path).then_some(Node::File(path));
        };
        if !meta.is_dir() && !(self.wanted)(&path) {
            return None;
        }
        if link {
            match path.canonicalize() {
                Ok(target) if target.starts_with(&self.root) => {}
                Ok(target) => {
                    return Some(Node::Unreadable(path, format!("links to {}, outside the dataset folder: not followed (name it as a dataset to include it)", target.display())));
                }
                Err(e) => {
                    return Some(Node::Unreadable(path, format!("cannot resolve the link: {e}")))
                }
            }
        }
        if let Some(id) = identity(&meta) {
            if !self.seen.insert(id) {
                return None;
            }
        }
        if !meta.is_dir() {
            return Some(Node::File(path));
        }
        match self.listing(&path) {
            Ok(listed) => Some(Node::Folder(self.folder(path, listed))),
            Err(e) => Some(Node::Unreadable(path, format!("cannot read the folder: {e}"))),
        }
    }
}
