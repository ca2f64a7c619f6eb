//! A dataset folder cannot take the catalog down (issue 18): every hostile item is made here —
//! symlink loops and links out of the folder, FIFOs and devices, frame folders too large to
//! read, VR-Folding stores with forged shapes, chunks and attributes — and each becomes one
//! error in the list while every good sample is listed once.
#![cfg(unix)]

use std::path::{Path, PathBuf};

use close::budget::Deadline;
use close::catalog::{Catalog, Entry, MAX_SAMPLE_BYTES};
use close::Error;

use crate::common::{copy_dir, TempDir};

/// A scratch folder of this file's tests.
fn scratch(name: &str) -> TempDir {
    TempDir::new(&format!("hostile-{name}"))
}

const SQUARE: &str = "0,0,0\n1,0,0\n1,1,0\n0,1,0\n";

fn mkfifo(path: &Path) {
    let c = std::ffi::CString::new(path.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: `c` is a valid NUL-terminated path for the duration of the call.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0, "mkfifo {}", path.display());
}

fn errors(catalog: &Catalog) -> Vec<(&str, &str)> {
    catalog
        .entries()
        .iter()
        .filter_map(|e| e.error.as_deref().map(|m| (e.name.as_str(), m)))
        .collect()
}

fn good(catalog: &Catalog) -> Vec<&Entry> {
    catalog.entries().iter().filter(|e| e.error.is_none()).collect()
}

#[test]
fn symlink_loops_are_walked_once_and_links_out_are_not_followed() {
    let dir = scratch("loops");
    let outside = scratch("loops-outside");
    std::fs::write(outside.0.join("far.csv"), SQUARE).unwrap();
    let root = dir.0.join("data");
    std::fs::create_dir_all(root.join("sub")).unwrap();
    std::fs::write(root.join("a.csv"), SQUARE).unwrap();
    std::fs::write(root.join("sub/b.csv"), SQUARE).unwrap();
    std::os::unix::fs::symlink(".", root.join("self1")).unwrap();
    std::os::unix::fs::symlink(".", root.join("self2")).unwrap();
    std::os::unix::fs::symlink("..", root.join("sub/up")).unwrap();
    std::os::unix::fs::symlink(&outside.0, root.join("elsewhere")).unwrap();
    std::os::unix::fs::symlink(outside.0.join("far.csv"), root.join("far.csv")).unwrap();
    // A second name for a file inside the folder is the same sample.
    std::os::unix::fs::symlink(root.join("a.csv"), root.join("alias.csv")).unwrap();

    let catalog = Catalog::open(std::slice::from_ref(&root));
    let mut names: Vec<&str> = good(&catalog).iter().map(|e| e.name.as_str()).collect();
    names.sort();
    // `sub` holds frame files only: it is one sample of frames.
    assert_eq!(names, ["a.csv", "sub"], "{:#?}", catalog.entries());
    let errors = errors(&catalog);
    assert_eq!(errors.len(), 2, "{errors:#?}");
    for (name, message) in &errors {
        assert!(
            ["elsewhere", "far.csv"].contains(name)
                && message.contains("outside the dataset folder"),
            "{name}: {message}"
        );
    }
    // Naming the target includes it.
    let both = Catalog::open(&[root, outside.0.clone()]);
    assert_eq!(good(&both).len(), 3);
}

#[test]
fn fifos_and_devices_are_never_read() {
    let dir = scratch("special");
    std::fs::write(dir.0.join("ok.csv"), SQUARE).unwrap();
    mkfifo(&dir.0.join("pipe.json"));
    mkfifo(&dir.0.join("frames.csv"));
    // Inside the folder (a bind mount, or the user's own /dev): the reader refuses it.
    assert!(close::formats::read_file(Path::new("/dev/zero"))
        .unwrap_err()
        .to_string()
        .contains("not a regular file"));
    std::os::unix::fs::symlink("/dev/zero", dir.0.join("zero.json")).unwrap();
    let catalog = Catalog::open(std::slice::from_ref(&dir.0));
    assert_eq!(good(&catalog).len(), 1);
    let errors = errors(&catalog);
    assert_eq!(errors.len(), 3, "{errors:#?}");
    for (name, message) in errors {
        let expected =
            if name == "zero.json" { "outside the dataset folder" } else { "not a regular file" };
        assert!(message.contains(expected), "{name}: {message}");
    }
    let fifo = close::formats::read_file(&dir.0.join("pipe.json")).unwrap_err();
    assert!(fifo.to_string().contains("not a regular file"), "{fifo}");
}

#[test]
fn a_sample_too_large_is_refused_from_its_sizes_and_the_refusal_is_kept() {
    let dir = scratch("large");
    let frames = dir.0.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    // Sparse files: their sizes say more than a sample may hold, without a byte on disk.
    let each = MAX_SAMPLE_BYTES / 3 + 1;
    for k in 0..3 {
        let file = std::fs::File::create(frames.join(format!("f{k}.obj"))).unwrap();
        file.set_len(each).unwrap();
    }
    std::fs::write(dir.0.join("small.csv"), SQUARE).unwrap();
    let catalog = Catalog::open(std::slice::from_ref(&dir.0));
    let entry = catalog.entries().iter().find(|e| e.name == "frames").unwrap();
    let message = entry.error.as_deref().unwrap();
    assert!(
        message.contains("bytes in the files of one sample")
            && message.contains(&MAX_SAMPLE_BYTES.to_string()),
        "{message}"
    );
    let refused = catalog.load(&entry.id, &Deadline::default()).unwrap_err();
    assert!(
        matches!(refused, Error::TooLarge { got: Some(got), .. } if got == 3 * each),
        "{refused:?}"
    );
    // The refusal is remembered: shrinking the files now does not make the load read them.
    for k in 0..3 {
        std::fs::write(frames.join(format!("f{k}.obj")), "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
            .unwrap();
    }
    assert_eq!(catalog.load(&entry.id, &Deadline::default()).unwrap_err(), refused);
}

#[test]
fn an_expired_deadline_stops_a_load_and_is_not_remembered() {
    let dir = scratch("deadline");
    std::fs::write(dir.0.join("small.csv"), SQUARE).unwrap();
    let catalog = Catalog::open(std::slice::from_ref(&dir.0));
    let id = good(&catalog)[0].id.clone();
    let expired = Deadline::after(std::time::Duration::ZERO);
    assert_eq!(catalog.load(&id, &expired).unwrap_err(), Error::Cancelled);
    assert_eq!(catalog.load(&id, &Deadline::default()).unwrap().frames.len(), 1);
}

#[test]
fn an_unreadable_sub_folder_is_one_error_and_the_rest_are_kept() {
    use std::os::unix::fs::PermissionsExt;
    let dir = scratch("unreadable");
    std::fs::write(dir.0.join("ok.csv"), SQUARE).unwrap();
    // A link to itself: no one reads it, root neither.
    std::os::unix::fs::symlink("spin.csv", dir.0.join("spin.csv")).unwrap();
    let locked = dir.0.join("locked");
    std::fs::create_dir_all(locked.join("inner")).unwrap();
    std::fs::write(locked.join("inner/x.csv"), SQUARE).unwrap();
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o000)).unwrap();
    // Root (CAP_DAC_OVERRIDE) lists a chmod-000 folder anyway.
    let listable = std::fs::read_dir(&locked).is_ok();
    let catalog = Catalog::open(std::slice::from_ref(&dir.0));
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o755)).unwrap();
    let mut names: Vec<&str> = good(&catalog).iter().map(|e| e.name.as_str()).collect();
    names.sort();
    let mut errors = errors(&catalog);
    errors.sort();
    let expected: &[&str] = if listable { &["locked/inner", "ok.csv"] } else { &["ok.csv"] };
    assert_eq!(names, expected, "listable: {listable}; errors: {errors:#?}");
    let (spin, rest) = errors.split_last().expect("errors");
    assert!(spin.0 == "spin.csv" && spin.1.contains("symbolic links"), "{errors:#?}");
    if listable {
        assert!(rest.is_empty(), "{errors:#?}");
    } else {
        assert!(
            rest.len() == 1
                && rest[0].0 == "locked"
                && rest[0].1.contains("cannot read the folder"),
            "{errors:?}"
        );
    }
}

#[test]
fn error_messages_quote_a_short_prefix_of_a_bad_line() {
    let line = "\u{1}".repeat(1 << 20);
    let text =
        close::formats::text::parse_frame(&format!("0,0,0\n{line}\n")).unwrap_err().to_string();
    assert!(text.contains("line 2") && text.len() < 400, "{} bytes", text.len());
    let obj = close::formats::obj::parse_frame(format!("v 0 0 {line}\n").as_bytes())
        .unwrap_err()
        .to_string();
    assert!(obj.contains("line 1") && obj.len() < 400, "{} bytes", obj.len());
}

#[test]
fn a_cached_mesh_weighs_its_faces_too() {
    let faces: Vec<Vec<usize>> = (0..1000).map(|k| vec![k, k + 1, k + 2]).collect();
    let mesh = close::formats::MeshFrames::new(faces, vec![vec![[0.0; 3]; 1002]]);
    let sample = close::formats::Sample {
        mesh: Some(mesh),
        ..close::formats::Sample::from_frames("m", "c", Vec::new())
    };
    // 1002 positions of 24 bytes, 1000 faces of a 24-byte list and three 8-byte corners.
    assert_eq!(sample.weight(), 1002 * 24 + 1000 * (24 + 3 * 8));
}

#[cfg(feature = "vrfolding")]
mod stores {
    use super::*;
    use close::vrfolding::Store;

    fn fixture() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr")
    }

    /// A private copy of the fixture store (4 categories, 8 videos, 16 folds).
    fn store(name: &str) -> TempDir {
        let dir = scratch(&format!("store-{name}"));
        copy_dir(&fixture(), &dir.0);
        dir
    }

    fn edit_json(path: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
        let mut value: serde_json::Value =
            serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
        edit(&mut value);
        std::fs::write(path, value.to_string()).unwrap();
    }

    /// The frame groups of the first video of `category`, in `sample_id` order.
    fn frames(root: &Path, category: &str) -> Vec<PathBuf> {
        let store = Store::open(root).unwrap();
        let (videos, _) = store.videos().unwrap();
        let video = videos.iter().find(|v| v.category == category).unwrap();
        video.frames.iter().map(|f| root.join(f.trim_start_matches('/'))).collect()
    }

    /// The id of fold 1 of the first video of `category`.
    fn first_fold(catalog: &Catalog, category: &str) -> String {
        catalog
            .entries()
            .iter()
            .find(|e| e.category == category && e.name.ends_with("fold 1"))
            .unwrap()
            .id
            .clone()
    }

    #[test]
    fn a_forged_grip_shape_is_one_error_at_listing() {
        let dir = store("grip-shape");
        let frame = &frames(&dir.0, "Skirt")[0];
        edit_json(&frame.join("grip_vertex_id/left_grip_vertex_id/.zarray"), |z| {
            z["shape"] = serde_json::json!([1u64 << 40]);
            z["chunks"] = serde_json::json!([1u64 << 40]);
        });
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        let errors = errors(&catalog);
        assert_eq!(errors.len(), 1, "{errors:#?}");
        assert!(
            errors[0].1.contains("left_grip_vertex_id") && errors[0].1.contains("limit"),
            "{errors:?}"
        );
        assert_eq!(good(&catalog).len(), 14, "the other 7 videos keep their 2 folds");
    }

    #[test]
    fn forged_vertex_shapes_and_chunks_are_refused_before_reading() {
        let dir = store("verts");
        // Frame 4 ends action 1: the listing reads only frame 0's shape, a load reads frame 4.
        let verts = frames(&dir.0, "Top")[4].join("mesh/cloth_verts");
        edit_json(&verts.join(".zarray"), |z| z["shape"] = serde_json::json!([1u64 << 40, 3]));
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        assert!(errors(&catalog).is_empty(), "{:#?}", errors(&catalog));
        let e = catalog
            .load(&first_fold(&catalog, "Top"), &Deadline::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("cloth_verts") && e.contains("limit"), "{e}");

        // A chunk shape far past the mesh limit.
        let dir = store("chunk-shape");
        let verts = self::frames(&dir.0, "Top")[0].join("mesh/cloth_verts");
        edit_json(&verts.join(".zarray"), |z| z["chunks"] = serde_json::json!([1u64 << 30, 3]));
        let store = Store::open(&dir.0).unwrap();
        let (videos, _) = store.videos().unwrap();
        let video = videos.iter().find(|v| v.category == "Top").unwrap();
        let e = store.folds(video).unwrap_err().to_string();
        assert!(e.contains("chunks of") && e.contains("limit"), "{e}");
    }

    #[test]
    fn a_forged_blosc_header_is_refused_and_the_refusal_is_kept() {
        let dir = store("blosc");
        let chunk = frames(&dir.0, "Tshirt")[0].join("mesh/cloth_verts/0.0");
        let original = std::fs::read(&chunk).unwrap();
        let mut forged = original.clone();
        // Blosc's header: bytes 4..8 are the decoded size, which the decoder allocates.
        forged[4..8].copy_from_slice(&(1_500_000_000u32).to_le_bytes());
        std::fs::write(&chunk, &forged).unwrap();
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        let fold = first_fold(&catalog, "Tshirt");
        let e = catalog.load(&fold, &Deadline::default()).unwrap_err();
        assert!(e.to_string().contains("decodes to 1500000000 bytes"), "{e}");
        std::fs::write(&chunk, &original).unwrap();
        assert_eq!(
            catalog.load(&fold, &Deadline::default()).unwrap_err(),
            e,
            "remembered, not read again"
        );
    }

    #[test]
    fn a_frame_without_attributes_or_with_a_string_sample_id_is_one_error_each() {
        let dir = store("attrs");
        std::fs::remove_file(frames(&dir.0, "Skirt")[3].join(".zattrs")).unwrap();
        edit_json(&frames(&dir.0, "Trousers")[2].join(".zattrs"), |a| {
            a["sample_id"] = "two".into()
        });
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        let errors = errors(&catalog);
        assert!(errors.len() >= 2, "{errors:#?}");
        assert!(errors.iter().any(|(_, m)| m.contains("no video_id")), "{errors:#?}");
        assert!(errors.iter().any(|(_, m)| m.contains("no integer sample_id")), "{errors:#?}");
        let categories: std::collections::HashSet<&str> =
            good(&catalog).iter().map(|e| e.category.as_str()).collect();
        assert!(["Top", "Tshirt"].iter().all(|c| categories.contains(c)), "{categories:?}");
        assert!(good(&catalog).len() >= 8, "{:#?}", catalog.entries());
    }
}

fn close_cli(args: &[&std::ffi::OsStr]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_close")).args(args).output().unwrap()
}

/// `close eval` walks a folder as the catalog does: loops once, FIFOs and links out as
/// errors, and ends.
#[test]
fn eval_counts_each_sample_once_and_names_what_it_cannot_read() {
    let dir = scratch("eval");
    let data = dir.0.join("data");
    std::fs::create_dir_all(data.join("sub")).unwrap();
    let out = close_cli(&["dataset".as_ref(), dir.0.join("builtin").as_os_str()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut exported: Vec<PathBuf> =
        std::fs::read_dir(dir.0.join("builtin")).unwrap().map(|e| e.unwrap().path()).collect();
    exported.sort();
    for (k, file) in exported.iter().take(3).enumerate() {
        let to = if k == 0 {
            data.join("sub").join(file.file_name().unwrap())
        } else {
            data.join(file.file_name().unwrap())
        };
        std::fs::copy(file, to).unwrap();
    }
    std::os::unix::fs::symlink(".", data.join("again")).unwrap();
    std::os::unix::fs::symlink("..", data.join("sub/up")).unwrap();
    std::os::unix::fs::symlink(&exported[5], data.join("far.json")).unwrap();
    mkfifo(&data.join("pipe.json"));
    let out = close_cli(&["eval".as_ref(), data.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let samples = report["samples"].as_array().unwrap();
    let failed: Vec<&serde_json::Value> =
        samples.iter().filter(|s| !s["error"].is_null()).collect();
    assert_eq!(samples.len() - failed.len(), 3, "{samples:#?}");
    assert_eq!(failed.len(), 2, "{failed:#?}");
    let errors: Vec<&str> = failed.iter().map(|s| s["error"].as_str().unwrap()).collect();
    assert!(
        errors.iter().any(|e| e.contains("outside the dataset folder"))
            && errors.iter().any(|e| e.contains("not a regular file")),
        "{errors:?}"
    );
}

/// `close dataset OUT` keeps what a user has: a non-empty OUT needs --force, a link inside
/// OUT is replaced and not written through, and no temporary file is left behind.
#[test]
fn dataset_out_refuses_a_non_empty_folder_and_never_writes_through_links() {
    let dir = scratch("out");
    let out = dir.0.join("out");
    let outside = dir.0.join("precious.txt");
    std::fs::write(&outside, "keep me").unwrap();
    let first = close_cli(&["dataset".as_ref(), out.as_os_str()]);
    assert!(first.status.success(), "{}", String::from_utf8_lossy(&first.stderr));
    let names: Vec<PathBuf> = std::fs::read_dir(&out).unwrap().map(|e| e.unwrap().path()).collect();
    let victim = names.iter().find(|p| p.extension().is_some_and(|e| e == "json")).unwrap().clone();
    std::fs::remove_file(&victim).unwrap();
    std::os::unix::fs::symlink(&outside, &victim).unwrap();

    let again = close_cli(&["dataset".as_ref(), out.as_os_str()]);
    let stderr = String::from_utf8_lossy(&again.stderr);
    assert!(!again.status.success() && stderr.contains("--force"), "{stderr}");
    assert!(
        std::fs::symlink_metadata(&victim).unwrap().file_type().is_symlink(),
        "refused: nothing touched"
    );

    let forced = close_cli(&["dataset".as_ref(), out.as_os_str(), "--force".as_ref()]);
    assert!(forced.status.success(), "{}", String::from_utf8_lossy(&forced.stderr));
    assert_eq!(std::fs::read_to_string(&outside).unwrap(), "keep me", "written through the link");
    assert!(
        std::fs::symlink_metadata(&victim).unwrap().file_type().is_file(),
        "the link is replaced by the sample"
    );
    close::formats::json::parse_sample(&std::fs::read(&victim).unwrap()).unwrap();
    let after: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(after.len(), names.len(), "{after:?}");
    assert!(after.iter().all(|n| !n.ends_with(".tmp")), "{after:?}");
}
