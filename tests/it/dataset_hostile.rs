//! A dataset folder cannot take the catalog down (issue 18): every hostile item is made here —
//! symlink loops and links out of the folder, FIFOs and devices, frame folders too large to
//! read, VR-Folding stores with forged shapes, chunks and attributes — and each becomes one
//! error in the list while every good sample is listed once.
#![cfg(unix)]

use std::path::{Path, PathBuf};

use close::budget::Deadline;
use close::catalog::{Catalog, Entry, MAX_SAMPLE_BYTES};
use close::io_error::Error as Read;
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

/// Long enough for anything that does not hang, in a debug build on a busy 2-core machine.
const HANG: std::time::Duration = std::time::Duration::from_secs(120);

/// `work`'s result, on a thread of its own: a hang (a FIFO read without a writer) fails the
/// test after [`HANG`] instead of stopping the suite.
fn within_hang<T: Send + 'static>(what: &str, work: impl FnOnce() -> T + Send + 'static) -> T {
    let (done, result) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = done.send(work());
    });
    result.recv_timeout(HANG).unwrap_or_else(|_| panic!("{what}: still running after {HANG:?}"))
}

/// A sparse file of 1 TiB at `path` (in place of what was there): no byte of it on disk.
fn sparse(path: &Path) {
    let _ = std::fs::remove_file(path);
    std::fs::File::create(path).unwrap().set_len(1 << 40).unwrap();
}

/// Put `make(temporary)` in place of `path` by a rename, so the new file has an inode of
/// its own while the old one still exists (a file written after a delete may reuse it).
fn swap(path: &Path, make: impl FnOnce(&Path)) {
    let temporary = path.with_extension("swap");
    make(&temporary);
    std::fs::rename(&temporary, path).unwrap();
}

/// `close ARGS`, stopped and failed after [`HANG`].
fn close_within_hang(args: &[&std::ffi::OsStr]) -> std::process::Output {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_close"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let t = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t.elapsed() > HANG {
            let _ = child.kill();
            panic!("close {args:?} still running after {HANG:?}");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child.wait_with_output().unwrap()
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
        matches!(refused, Read::Core(Error::TooLarge { got: Some(got), .. }) if got == 3 * each),
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
    assert_eq!(catalog.load(&id, &expired).unwrap_err(), Read::Core(Error::Cancelled));
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

// Issue 27 item 6: a listed file replaced by a link to /etc/passwd was read, and the error
// quoted its first line. A listed file is opened without following links and must be the
// file listed; and no error quotes a file's text.
#[test]
fn a_listed_file_swapped_for_a_link_or_another_file_is_not_read() {
    let dir = scratch("swapped");
    let outside = scratch("swapped-outside");
    let secret = outside.0.join("passwd");
    std::fs::write(&secret, "root:x:0:0:root:/root:/bin/bash\n").unwrap();
    for name in ["victim.txt", "replaced.txt", "kept.txt"] {
        std::fs::write(dir.0.join(name), SQUARE).unwrap();
    }
    let catalog = Catalog::open(std::slice::from_ref(&dir.0));
    assert_eq!(good(&catalog).len(), 3);
    let id = |name: &str| catalog.entries().iter().find(|e| e.name == name).unwrap().id.clone();
    swap(&dir.0.join("victim.txt"), |t| std::os::unix::fs::symlink(&secret, t).unwrap());
    swap(&dir.0.join("replaced.txt"), |t| std::fs::write(t, SQUARE).unwrap());
    let forever = Deadline::default();
    let e = catalog.load(&id("victim.txt"), &forever).unwrap_err().to_string();
    assert!(e.contains("symbolic link") && !e.contains("root"), "{e}");
    let e = catalog.load(&id("replaced.txt"), &forever).unwrap_err().to_string();
    assert!(e.contains("another file than the one listed"), "{e}");
    assert!(catalog.load(&id("kept.txt"), &forever).is_ok());
    // Read as what it claims to be, a file of secrets is named, not quoted.
    let text = std::fs::read(&secret).unwrap();
    let json = br#"{"name": "x", "frames": "root:x:0:0:root"}"#.to_vec();
    for (name, bytes) in [
        ("passwd.txt", text.clone()),
        ("passwd.obj", [b"v ".to_vec(), text].concat()),
        ("x.json", json),
    ] {
        let e = close::formats::read_files(&[(name.to_string(), bytes)]).unwrap_err().to_string();
        assert!(!e.contains("root"), "{name}: {e}");
    }
}

// Issue 27 item 10: `close eval` scored only the `.json` files of a folder the server lists
// whole, and dropped a file nested in a frame folder with no row. One walk serves both: the
// same samples, and an error row for what cannot be walked (a folder too deep).
#[test]
fn eval_walks_a_folder_as_serve_does() {
    let dir = scratch("parity");
    let data = dir.0.join("data");
    std::fs::create_dir_all(data.join("run/later")).unwrap();
    let formats = crate::common::fixture("formats");
    std::fs::copy(formats.join("napkin_dense.mat"), data.join("napkin.mat")).unwrap();
    let sample = crate::common::samples_in("reference/folded").remove(0);
    std::fs::write(data.join("folded.json"), close::formats::json::to_json(&sample)).unwrap();
    // A folder of frame files, and inside it a sample of its own.
    for (k, frame) in sample.frames.iter().take(2).enumerate() {
        let text: String = frame.iter().map(|p| format!("{},{},{}\n", p[0], p[1], p[2])).collect();
        std::fs::write(data.join(format!("run/f{k}.csv")), text).unwrap();
    }
    std::fs::write(data.join("run/later/again.json"), close::formats::json::to_json(&sample))
        .unwrap();
    let deep = (0..40).fold(data.join("deep"), |p, k| p.join(format!("d{k}")));
    std::fs::create_dir_all(&deep).unwrap();
    std::fs::write(deep.join("lost.json"), close::formats::json::to_json(&sample)).unwrap();

    let catalog = Catalog::open(std::slice::from_ref(&data));
    let mut listed: Vec<&str> = good(&catalog).iter().map(|e| e.name.as_str()).collect();
    listed.sort();
    let errors = errors(&catalog);
    assert_eq!(listed.len(), 4, "{:#?}", catalog.entries());
    assert!(errors.len() == 1 && errors[0].1.contains("folders down"), "{errors:#?}");

    let out = close_within_hang(&["eval".as_ref(), data.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = report["samples"].as_array().unwrap();
    let (failed, scored): (Vec<&serde_json::Value>, Vec<&serde_json::Value>) =
        rows.iter().partition(|r| r["error"].is_string());
    assert_eq!(scored.len(), 4, "{rows:#?}");
    assert!(failed.len() == 1 && failed[0]["error"].as_str().unwrap().contains("folders down"));
    let mut scored: Vec<&str> = scored.iter().map(|r| r["name"].as_str().unwrap()).collect();
    scored.sort();
    assert_eq!(scored, listed, "eval names its rows as serve lists them");
}

#[cfg(feature = "vrfolding")]
mod stores {
    use super::*;
    use close::vrfolding::Store;
    use std::ffi::OsStr;

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

    fn errors_of(catalog: &Catalog) -> Vec<(String, String)> {
        errors(catalog).into_iter().map(|(n, m)| (n.to_string(), m.to_string())).collect()
    }

    // Issue 27 items 1 and 4: a sparse 1 TiB chunk costs nothing on disk and was allocated
    // whole (SIGABRT); a FIFO blocked the reader for good. Each is refused from its handle,
    // before a byte is read, as one error; the listing, `close eval` and the server go on.
    #[test]
    fn sparse_or_special_store_files_are_refused_unread_and_never_block() {
        let dir = store("special");
        let [tshirt, skirt, top, trousers] =
            ["Tshirt", "Skirt", "Top", "Trousers"].map(|c| frames(&dir.0, c));
        // A mesh chunk (read when a fold is loaded) and a grip chunk (read at listing).
        sparse(&tshirt[0].join("mesh/cloth_verts/0.0"));
        sparse(&skirt[0].join("grip_vertex_id/left_grip_vertex_id/0"));
        // FIFOs with no writer: a grip chunk, and a frame's attributes.
        let fifo = top[2].join("grip_vertex_id/right_grip_vertex_id/0");
        std::fs::remove_file(&fifo).unwrap();
        mkfifo(&fifo);
        std::fs::remove_file(trousers[0].join(".zattrs")).unwrap();
        mkfifo(&trousers[0].join(".zattrs"));

        let root = dir.0.clone();
        let catalog = within_hang("listing", move || Catalog::open(&[root]));
        let errors = errors_of(&catalog);
        assert_eq!(errors.len(), 3, "{errors:#?}");
        let has = |name: &str, words: &[&str]| {
            errors.iter().any(|(n, m)| n.contains(name) && words.iter().all(|w| m.contains(w)))
        };
        assert!(
            has("Skirt/", &["left_grip_vertex_id", "1099511627776 bytes", "more than"]),
            "{errors:#?}"
        );
        assert!(has("Top/", &["right_grip_vertex_id", "not a regular file"]), "{errors:#?}");
        assert!(has("Trousers", &[".zattrs", "not a regular file"]), "{errors:#?}");
        let fold = first_fold(&catalog, "Tshirt");
        let e = catalog.load(&fold, &Deadline::default()).unwrap_err().to_string();
        assert!(e.contains("cloth_verts") && e.contains("1099511627776 bytes"), "{e}");
        // The other video of each category is whole (a Tshirt's mesh is read on loading).
        for (category, listed) in [("Skirt", 2), ("Top", 2), ("Tshirt", 4)] {
            let count = good(&catalog).iter().filter(|e| e.category.starts_with(category)).count();
            assert_eq!(count, listed, "{category}");
        }

        // `close eval` reports each as an error row and exits normally (it was killed by
        // SIGABRT, or blocked).
        let out = close_within_hang(&[OsStr::new("eval"), dir.0.as_os_str(), OsStr::new("--json")]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let failed: Vec<&str> = report["samples"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(|s| s["error"].as_str())
            .collect();
        assert!(
            failed.iter().any(|e| e.contains("cloth_verts") && e.contains("1099511627776")),
            "{failed:#?}"
        );
        assert!(failed.iter().any(|e| e.contains("not a regular file")), "{failed:#?}");
        // Both folds of the video whose mesh is sparse are error rows, as the server lists
        // both (eval gave fold 1's alone, and fold 2 was missing).
        let sparse_rows = failed
            .iter()
            .filter(|e| e.contains("1099511627776") && e.contains("cloth_verts"))
            .count();
        assert_eq!(sparse_rows, 2, "{failed:#?}");
        let rows = report["samples"].as_array().unwrap().len();
        assert_eq!(rows, catalog.entries().len(), "eval has a row for each listed entry");

        // The server lists the store and answers the fold with its error.
        let runtime = tokio::runtime::Runtime::new().unwrap();
        runtime.block_on(async {
            use tower::ServiceExt;
            let state = close::server::AppState::with_config(close::server::Config {
                datasets: vec![dir.0.clone()],
                ..Default::default()
            });
            let app = close::server::app(state);
            let ask = axum::http::Request::get(format!("/api/samples/{fold}"))
                .body(axum::body::Body::empty())
                .unwrap();
            let answer = app.oneshot(ask).await.unwrap();
            assert_eq!(answer.status(), axum::http::StatusCode::UNPROCESSABLE_ENTITY);
        });
    }

    // Issue 27 item 3: four grip arrays of 2·10⁶ one-element chunks (no chunk file at all)
    // took a minute and 1.8 GiB to list. A chunk count is bounded from the metadata, before
    // any chunk is looked for.
    #[test]
    fn forged_chunk_counts_are_refused_from_the_metadata() {
        let dir = store("chunk-count");
        let skirt = frames(&dir.0, "Skirt");
        // The mesh is said to have 2·10⁶ vertices (within the limits; only its shape is read
        // at listing), so grip arrays of 2·10⁶ ids are within them too.
        edit_json(&skirt[0].join("mesh/cloth_verts/.zarray"), |z| {
            z["shape"] = serde_json::json!([2_000_000, 3]);
            z["chunks"] = serde_json::json!([2_000_000, 3]);
        });
        for frame in &skirt[..2] {
            for hand in ["left", "right"] {
                let grip = frame.join(format!("grip_vertex_id/{hand}_grip_vertex_id"));
                edit_json(&grip.join(".zarray"), |z| {
                    z["shape"] = serde_json::json!([2_000_000]);
                    z["chunks"] = serde_json::json!([1]);
                });
                std::fs::remove_file(grip.join("0")).unwrap();
            }
        }
        let root = dir.0.clone();
        let catalog = within_hang("listing", move || Catalog::open(&[root]));
        let errors = errors_of(&catalog);
        assert_eq!(errors.len(), 1, "{errors:#?}");
        assert!(
            errors[0].1.contains("2000000 chunks") && errors[0].1.contains("1024"),
            "{errors:?}"
        );
        assert_eq!(good(&catalog).len(), 14, "the other 7 videos keep their 2 folds");
    }

    // Issue 27 item 3: what listing a store reads of its grips is counted, from the metadata
    // and in listing order, against one budget for the whole store; a video past it is an
    // error row, never read.
    #[test]
    fn the_listing_counts_every_videos_grips_against_one_budget() {
        let dir = store("listing");
        let store = Store::open(&dir.0).unwrap();
        let (videos, _) = store.videos().unwrap();
        for video in &videos {
            let frame = |f: &String| dir.0.join(f.trim_start_matches('/'));
            edit_json(&frame(&video.frames[0]).join("mesh/cloth_verts/.zarray"), |z| {
                z["shape"] = serde_json::json!([2_000_000, 3]);
                z["chunks"] = serde_json::json!([2_000_000, 3]);
            });
            for f in &video.frames {
                for hand in ["left", "right"] {
                    let grip = frame(f).join(format!("grip_vertex_id/{hand}_grip_vertex_id"));
                    edit_json(&grip.join(".zarray"), |z| {
                        z["shape"] = serde_json::json!([2_000_000]);
                        z["chunks"] = serde_json::json!([2048]);
                    });
                    // A first chunk that declares 4 GB: refused unread if it is ever read.
                    let mut forged = vec![2u8, 1, 0x21, 4];
                    forged.extend(u32::MAX.to_le_bytes());
                    forged.extend([0u8; 8]);
                    std::fs::write(grip.join("0"), forged).unwrap();
                }
            }
        }
        // 10 frames × 2 hands × 2·10⁶ ids = 4·10⁷ for each video: one fits, two do not.
        let work = store.cut_work(&videos[0]).unwrap();
        assert_eq!(work.ids, 40_000_000);
        assert!(
            work.ids <= close::vrfolding::LISTING.ids
                && 2 * work.ids > close::vrfolding::LISTING.ids
        );
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        let errors = errors_of(&catalog);
        assert_eq!(errors.len(), 8, "{errors:#?}");
        let over: Vec<&(String, String)> =
            errors.iter().filter(|(_, m)| m.contains("not cut")).collect();
        assert_eq!(over.len(), 7, "{errors:#?}");
        assert!(over.iter().all(|(_, m)| m.contains(&close::vrfolding::LISTING.ids.to_string())));
        // The first video was read, and its forged chunk refused.
        assert!(
            errors.iter().any(|(_, m)| m.contains("decodes to 4294967295 bytes")),
            "{errors:#?}"
        );
    }

    // Issue 27 item 6: a frame's `.zattrs` linked to a file outside the store was parsed. A
    // link out of the store is an error (its target unread); one inside is followed.
    #[test]
    fn links_in_a_store_are_followed_only_inside_it() {
        let dir = store("links");
        let outside = scratch("store-links-outside");
        let secret = outside.0.join("passwd");
        std::fs::write(&secret, "root:x:0:0:root:/root:/bin/bash\n").unwrap();
        let skirt = frames(&dir.0, "Skirt");
        let top = frames(&dir.0, "Top");
        std::fs::remove_file(skirt[3].join(".zattrs")).unwrap();
        std::os::unix::fs::symlink(&secret, skirt[3].join(".zattrs")).unwrap();
        // Faces are the same in every frame of a video: frame 0's may be a link to frame 1's.
        std::fs::remove_dir_all(top[0].join("mesh/cloth_faces_tri")).unwrap();
        std::os::unix::fs::symlink(
            top[1].join("mesh/cloth_faces_tri"),
            top[0].join("mesh/cloth_faces_tri"),
        )
        .unwrap();
        let catalog = Catalog::open(std::slice::from_ref(&dir.0));
        let errors = errors_of(&catalog);
        assert_eq!(errors.len(), 1, "{errors:#?}");
        assert!(
            errors[0].1.contains("out of the store") && !errors[0].1.contains("root:"),
            "{errors:?}"
        );
        let loaded = catalog.load(&first_fold(&catalog, "Top"), &Deadline::default());
        assert!(loaded.is_ok(), "{loaded:?}");
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

// Issue 27 item 7: stores inside a dataset folder were left out with no row. Each is listed
// (its folds), a broken one is one error row, and `close eval` scores the same.
#[cfg(feature = "vrfolding")]
#[test]
fn stores_inside_a_dataset_folder_are_listed_and_scored() {
    let dir = scratch("nested");
    let data = dir.0.join("data");
    std::fs::create_dir_all(data.join("good")).unwrap();
    for (k, sample) in crate::common::samples_in("reference/folded").into_iter().take(2).enumerate()
    {
        std::fs::write(data.join(format!("good/{k}.json")), close::formats::json::to_json(&sample))
            .unwrap();
    }
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr");
    // A store of one category (2 videos, 4 folds), and one that lost its root `.zgroup`.
    std::fs::create_dir_all(data.join("skirts.zarr")).unwrap();
    std::fs::copy(fixture.join(".zgroup"), data.join("skirts.zarr/.zgroup")).unwrap();
    copy_dir(&fixture.join("Skirt"), &data.join("skirts.zarr/Skirt"));
    copy_dir(&fixture.join("Top"), &data.join("partial.zarr/Top"));

    let catalog = Catalog::open(std::slice::from_ref(&data));
    let good = good(&catalog);
    assert_eq!(good.iter().filter(|e| e.source.ends_with("skirts.zarr")).count(), 4);
    assert_eq!(good.len(), 6, "{:#?}", catalog.entries());
    let errors = errors(&catalog);
    assert!(
        errors.len() == 1
            && errors[0].0.ends_with("partial.zarr")
            && errors[0].1.contains(".zgroup"),
        "{errors:#?}"
    );

    let out = close_within_hang(&["eval".as_ref(), data.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let rows = report["samples"].as_array().unwrap();
    let folds = rows
        .iter()
        .filter(|r| r["category"].as_str().is_some_and(|c| c.starts_with("Skirt/")))
        .count();
    let failed: Vec<&serde_json::Value> = rows.iter().filter(|r| r["error"].is_string()).collect();
    assert_eq!((rows.len(), folds), (7, 4), "{rows:#?}");
    assert!(
        failed.len() == 1 && failed[0]["name"].as_str().unwrap().ends_with("partial.zarr"),
        "{failed:#?}"
    );
}

// Issue 27 item 9: video ids `a/b` and `a_b` were written to one file, and a 300-character id
// stopped the export at its first failure. Names are unique and short, and one file that
// cannot be written is reported while every other is written.
#[cfg(feature = "vrfolding")]
#[test]
fn store_exports_have_unique_short_names_and_survive_a_failure() {
    let dir = scratch("export");
    let root = dir.0.join("store.zarr");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/vrfolding/vr_simulation_folding2_dataset.zarr");
    std::fs::create_dir_all(&root).unwrap();
    std::fs::copy(fixture.join(".zgroup"), root.join(".zgroup")).unwrap();
    copy_dir(&fixture.join("Skirt"), &root.join("Skirt"));
    copy_dir(&fixture.join("Top"), &root.join("Top"));
    let store = close::vrfolding::Store::open(&root).unwrap();
    let (videos, _) = store.videos().unwrap();
    let long = "x".repeat(300);
    for (video, id) in videos.iter().zip(["a/b", "a_b", long.as_str(), "00006"]) {
        for frame in &video.frames {
            let attrs = root.join(frame.trim_start_matches('/')).join(".zattrs");
            let mut value: serde_json::Value =
                serde_json::from_slice(&std::fs::read(&attrs).unwrap()).unwrap();
            value["video_id"] = id.into();
            std::fs::write(&attrs, value.to_string()).unwrap();
        }
    }
    let out_dir = dir.0.join("out");
    // Something that is not a file where one fold goes: that one cannot be written.
    std::fs::create_dir_all(out_dir.join("Top_00006_fold1.json/held")).unwrap();
    let out = close_within_hang(&[
        "dataset".as_ref(),
        out_dir.as_os_str(),
        "--from".as_ref(),
        root.as_os_str(),
        "--force".as_ref(),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("Top_00006_fold1.json") && stderr.contains("1 of 8 files"), "{stderr}");
    let mut written: Vec<String> = std::fs::read_dir(&out_dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "Top_00006_fold1.json")
        .collect();
    written.sort();
    assert_eq!(written.len(), 7, "{written:#?}");
    assert!(written.iter().all(|n| n.len() <= 120 && n.ends_with(".json")), "{written:#?}");
    assert!(written.contains(&"Skirt_a_b_fold1.json".to_string()), "{written:#?}");
    assert_eq!(written.iter().filter(|n| n.starts_with("Skirt_a_b_fold1")).count(), 2);
    for name in &written {
        let sample =
            close::formats::json::parse_sample(&std::fs::read(out_dir.join(name)).unwrap());
        assert!(sample.is_ok(), "{name}: {sample:?}");
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
