//! Readers and mesh borders end to end: meshes made here (grid napkins and towels, a flat
//! T-shirt, a two-layer T-shirt shell with openings) folded by reflection, written as OBJ
//! and PLY, and the scipy-written `.mat` fixtures; each must give the same CloSE as the
//! equivalent border sample. Then every parser is fuzzed with arbitrary and mutated bytes.

use std::collections::HashSet;

use close::border::Point;
use close::formats::{read_files, Sample};
use close::io_error::Error as Read;
use close::mesh::MeshFrames;
use close::Line;
use close::{analyze, Analysis, Error, FrameRange};
use proptest::prelude::*;

const FIXTURES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/formats");

/// A grid of (w+1)×(h+1) vertices, id = j·(w+1) + i, with quads or triangles.
fn grid(
    w: usize,
    h: usize,
    keep: impl Fn(usize, usize) -> bool,
    triangles: bool,
) -> (Vec<[f64; 3]>, Vec<Vec<usize>>) {
    let id = |i: usize, j: usize| j * (w + 1) + i;
    let v = (0..=h).flat_map(|j| (0..=w).map(move |i| [i as f64, j as f64, 0.0])).collect();
    let mut faces = Vec::new();
    for j in 0..h {
        for i in 0..w {
            if !keep(i, j) {
                continue;
            }
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            if triangles {
                faces.extend([vec![q[0], q[1], q[2]], vec![q[0], q[2], q[3]]]);
            } else {
                faces.push(q.to_vec());
            }
        }
    }
    (v, faces)
}

/// Fold: every vertex left of the directed line a→b (in XY) is reflected across it and
/// stacked: z ↦ top − z.
fn fold(vertices: &[[f64; 3]], a: [f64; 2], b: [f64; 2], top: f64) -> Vec<[f64; 3]> {
    let line = Line::through(&Point::new(a[0], a[1], 0.0), &Point::new(b[0], b[1], 0.0));
    vertices
        .iter()
        .map(|v| {
            let side = (b[0] - a[0]) * (v[1] - a[1]) - (b[1] - a[1]) * (v[0] - a[0]);
            if side > 1e-9 {
                let p = Point::new(v[0], v[1], v[2]);
                let r = line.map_or(p, |l| l.reflect(&p));
                [r.x, r.y, top - v[2]]
            } else {
                *v
            }
        })
        .collect()
}

/// Integer points walked anticlockwise along a polygon with axis-parallel sides.
fn ring(corners: &[[i64; 2]]) -> Vec<[i64; 2]> {
    let mut out = Vec::new();
    for k in 0..corners.len() {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let steps = (b[0] - a[0]).abs().max((b[1] - a[1]).abs());
        out.extend(
            (0..steps)
                .map(|s| [a[0] + (b[0] - a[0]).signum() * s, a[1] + (b[1] - a[1]).signum() * s]),
        );
    }
    out
}

fn mesh_sample(faces: Vec<Vec<usize>>, frames: Vec<Vec<[f64; 3]>>) -> Sample {
    Sample {
        name: "mesh".into(),
        category: "test".into(),
        frames: Vec::new(),
        mesh: Some(MeshFrames::new(faces, frames)),
        truth: None,
    }
}

fn border_sample(ids: &[usize], frames: &[Vec<[f64; 3]>]) -> Sample {
    Sample::from_frames(
        "border",
        "test",
        frames.iter().map(|f| ids.iter().map(|&k| f[k]).collect()).collect(),
    )
}

fn analysis(sample: &Sample) -> Analysis {
    analyze(&sample.border_frames().unwrap(), FrameRange::default()).unwrap()
}

/// Same corners and folds (to `tol` radians), and the mesh's border indices are the ids.
fn assert_same_close(mesh: &Analysis, border: &Analysis, ids: &[usize], tol: f64) {
    let expected: Vec<usize> = border.border_indices.iter().map(|&k| ids[k]).collect();
    assert_eq!(mesh.border_indices, expected);
    assert_eq!(mesh.corners, border.corners);
    assert_eq!(mesh.folds.len(), border.folds.len());
    for (m, b) in mesh.folds.iter().zip(&border.folds) {
        for (m, b) in [(m.f1, b.f1), (m.f2, b.f2)] {
            let d = (m - b).rem_euclid(std::f64::consts::TAU);
            assert!(
                d.min(std::f64::consts::TAU - d) < tol,
                "{:?} vs {:?}",
                mesh.folds,
                border.folds
            );
        }
    }
}

#[test]
fn napkin_and_towel_meshes_match_their_border_samples() {
    // (width, height, fold line, triangles): a half fold, a diagonal corner fold, a towel.
    let cases = [
        (10, 10, [[5.0, 0.0], [5.0, 10.0]], false),
        (10, 10, [[10.0, 4.0], [4.0, 10.0]], true),
        (16, 8, [[6.0, 8.0], [6.0, 0.0]], true),
    ];
    for (w, h, line, triangles) in cases {
        let (flat, faces) = grid(w, h, |_, _| true, triangles);
        let frames = vec![flat.clone(), fold(&flat, line[0], line[1], 0.05)];
        let ids: Vec<usize> = ring(&[[0, 0], [w as i64, 0], [w as i64, h as i64], [0, h as i64]])
            .iter()
            .map(|p| p[1] as usize * (w + 1) + p[0] as usize)
            .collect();
        let mesh = analysis(&mesh_sample(faces, frames.clone()));
        let border = analysis(&border_sample(&ids, &frames));
        assert_eq!(mesh.border_source, "mesh boundary loop");
        assert_eq!(border.border_source, "border");
        assert_same_close(&mesh, &border, &ids, 1e-9);
        assert_eq!(mesh.corners.len(), 4, "{w}×{h}");
        assert_eq!(mesh.folds.len(), 1, "{w}×{h} {line:?}");
    }
}

/// The T-shirt outline (anticlockwise from the hem's left end) on a 10×8 grid, and its
/// openings: neck, sleeve ends, hem (the outline points strictly inside them).
const SHIRT: [[i64; 2]; 8] = [[2, 0], [8, 0], [8, 5], [10, 5], [10, 8], [0, 8], [0, 5], [2, 5]];

fn in_shirt(i: usize, j: usize) -> bool {
    (2..8).contains(&i) || j >= 5
}

fn in_opening(p: [i64; 2]) -> bool {
    (p[1] == 8 && (4..=6).contains(&p[0]))
        || (p[1] == 0 && (3..=7).contains(&p[0]))
        || ((p[0] == 0 || p[0] == 10) && (6..=7).contains(&p[1]))
}

#[test]
fn a_flat_triangulated_garment_uses_its_boundary_loop() {
    let (flat, faces) = grid(10, 8, in_shirt, true);
    let ids: Vec<usize> = ring(&SHIRT).iter().map(|p| p[1] as usize * 11 + p[0] as usize).collect();
    // Fold the left sleeve over the body.
    let frames = vec![flat.clone(), fold(&flat, [2.0, 8.0], [2.0, 0.0], 0.05)];
    let mesh = analysis(&mesh_sample(faces, frames.clone()));
    assert_eq!(mesh.border_source, "mesh boundary loop");
    assert_same_close(&mesh, &analysis(&border_sample(&ids, &frames)), &ids, 1e-9);
}

/// A two-layer shell: the back panel is the flat shirt (z = 0), the front a copy at z = h
/// sharing the seam vertices (outline points outside the openings, at z = h/2); the
/// openings' points exist twice, so each opening is a boundary loop of the shell.
fn shirt_shell(h: f64) -> (Vec<[f64; 3]>, Vec<Vec<usize>>, Vec<usize>) {
    let (back, back_faces) = grid(10, 8, in_shirt, true);
    let outline = ring(&SHIRT);
    let seam: HashSet<usize> = outline
        .iter()
        .filter(|p| !in_opening(**p))
        .map(|p| p[1] as usize * 11 + p[0] as usize)
        .collect();
    let mut vertices: Vec<[f64; 3]> = back
        .iter()
        .enumerate()
        .map(|(k, v)| [v[0], v[1], if seam.contains(&k) { h / 2.0 } else { 0.0 }])
        .collect();
    let front: Vec<usize> = (0..back.len())
        .map(|k| {
            if seam.contains(&k) {
                k
            } else {
                vertices.push([back[k][0], back[k][1], h]);
                vertices.len() - 1
            }
        })
        .collect();
    let mut faces = back_faces.clone();
    faces.extend(back_faces.iter().map(|f| f.iter().rev().map(|&k| front[k]).collect()));
    // What the silhouette should find: the outline, seen on the front layer.
    let border = outline.iter().map(|p| front[p[1] as usize * 11 + p[0] as usize]).collect();
    (vertices, faces, border)
}

#[test]
fn a_garment_shell_uses_the_silhouette_and_matches_its_outline() {
    let (flat, faces, ids) = shirt_shell(0.1);
    // Hem folded up over the body (the shell flips: z ↦ 0.3 − z keeps it on top).
    let frames = vec![flat.clone(), fold(&flat, [10.0, 3.0], [0.0, 3.0], 0.3)];
    let sample = mesh_sample(faces, frames.clone());
    let b = sample.border_frames().unwrap();
    assert_eq!(b.source, "mesh silhouette");
    let mesh = analysis(&sample);
    let border = analysis(&border_sample(&ids, &frames));
    assert_same_close(&mesh, &border, &ids, 1e-9);
    assert_eq!(mesh.folds.len(), 1, "{:?}", mesh.folds);
}

#[test]
fn a_coarser_epsilon_cover_still_gives_the_same_close() {
    // A fine shell (ε-cover thins its outline): compare with every second outline point.
    let (flat, faces, ids) = shirt_shell(0.1);
    let scale = |f: &Vec<[f64; 3]>| {
        f.iter().map(|v| [v[0] * 0.05, v[1] * 0.05, v[2] * 0.05]).collect::<Vec<_>>()
    };
    let frames = vec![scale(&flat), scale(&fold(&flat, [2.0, 8.0], [2.0, 0.0], 0.3))];
    let mesh = analysis(&mesh_sample(faces, frames.clone()));
    assert_eq!(mesh.border_source, "mesh silhouette");
    // Scaling does not change the ε-cover (normalised units): same border as before.
    let border = analysis(&border_sample(&ids, &frames));
    assert_same_close(&mesh, &border, &ids, 1e-9);
}

// ---- Files: OBJ, PLY (ASCII and binary), MATLAB ----

fn obj(v: &[[f64; 3]], faces: &[Vec<usize>]) -> Vec<u8> {
    let mut s = String::from("# napkin\no cloth\n");
    v.iter().for_each(|p| s += &format!("v {} {} {}\n", p[0], p[1], p[2]));
    faces.iter().for_each(|f| {
        s += &format!(
            "f {}\n",
            f.iter().map(|k| format!("{}//1", k + 1)).collect::<Vec<_>>().join(" ")
        )
    });
    s.into_bytes()
}

fn ply(v: &[[f64; 3]], faces: &[Vec<usize>], format: &str) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment made by tests/formats.rs\nelement vertex {}\nproperty double x\nproperty double y\nproperty float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        v.len(),
        faces.len()
    )
    .into_bytes();
    let big = format == "binary_big_endian";
    for p in v {
        match format {
            "ascii" => out.extend(format!("{} {} {}\n", p[0], p[1], p[2]).bytes()),
            _ if big => out.extend(
                [
                    p[0].to_be_bytes().to_vec(),
                    p[1].to_be_bytes().to_vec(),
                    (p[2] as f32).to_be_bytes().to_vec(),
                ]
                .concat(),
            ),
            _ => out.extend(
                [
                    p[0].to_le_bytes().to_vec(),
                    p[1].to_le_bytes().to_vec(),
                    (p[2] as f32).to_le_bytes().to_vec(),
                ]
                .concat(),
            ),
        }
    }
    for f in faces {
        if format == "ascii" {
            out.extend(
                format!(
                    "{} {}\n",
                    f.len(),
                    f.iter().map(|k| k.to_string()).collect::<Vec<_>>().join(" ")
                )
                .bytes(),
            );
        } else {
            out.push(f.len() as u8);
            f.iter().for_each(|&k| {
                out.extend(if big { (k as i32).to_be_bytes() } else { (k as i32).to_le_bytes() })
            });
        }
    }
    out
}

#[test]
fn obj_and_ply_frames_read_as_one_mesh_sample() {
    let (flat, faces) = grid(8, 8, |_, _| true, false);
    let folded = fold(&flat, [8.0, 3.0], [0.0, 3.0], 0.0625);
    let expected = MeshFrames::new(faces.clone(), vec![flat.clone(), folded.clone()]);
    type Writer<'a> = &'a dyn Fn(&[[f64; 3]]) -> Vec<u8>;
    let writers: [(&str, Writer); 4] = [
        ("obj", &|v| obj(v, &faces)),
        ("ply", &|v| ply(v, &faces, "ascii")),
        ("ply", &|v| ply(v, &faces, "binary_little_endian")),
        ("ply", &|v| ply(v, &faces, "binary_big_endian")),
    ];
    for (ext, write) in writers {
        let files =
            vec![(format!("a/f0.{ext}"), write(&flat)), (format!("a/f1.{ext}"), write(&folded))];
        let sample = read_files(&files).unwrap();
        assert_eq!(sample.mesh.as_ref(), Some(&expected), "{ext}");
        assert_eq!(sample.name, format!("f0.{ext}"));
        assert_eq!(analysis(&sample).folds.len(), 1);
    }
    // A frame with another vertex count is named.
    let files = vec![
        ("f0.obj".to_string(), obj(&flat, &faces)),
        ("f1.obj".to_string(), obj(&flat[1..], &[])),
    ];
    let err = read_files(&files).unwrap_err().to_string();
    assert!(err.contains("f1.obj has 80 vertices") && err.contains("f0.obj has 81"), "{err}");
    // OBJ then PLY frames mix; a text file does not.
    let mixed = vec![
        ("f0.obj".to_string(), obj(&flat, &faces)),
        ("f1.ply".to_string(), ply(&folded, &faces, "ascii")),
    ];
    assert_eq!(read_files(&mixed).unwrap().mesh.unwrap(), expected);
    let bad = vec![
        ("f0.obj".to_string(), obj(&flat, &faces)),
        ("f1.txt".to_string(), b"0 0 0\n".to_vec()),
    ];
    assert!(read_files(&bad).unwrap_err().to_string().contains(".txt"));
}

fn fixture(name: &str) -> (String, Vec<u8>) {
    (name.to_string(), std::fs::read(format!("{FIXTURES}/{name}")).unwrap())
}

#[test]
fn scipy_mat_files_dense_sparse_compressed_or_not() {
    let samples: Vec<Sample> = [
        "napkin_dense.mat",
        "napkin_dense_compressed.mat",
        "napkin_sparse.mat",
        "napkin_sparse_compressed.mat",
    ]
    .iter()
    .map(|f| read_files(&[fixture(f)]).unwrap())
    .collect();
    let mesh = samples[0].mesh.clone().unwrap();
    for s in &samples {
        assert_eq!(s.mesh.as_ref().unwrap().frames, mesh.frames);
        assert_eq!(s.mesh.as_ref().unwrap().border_edges, mesh.border_edges);
    }
    // The script's grid: vertex id = 4j + i, frame 1 folds x > 1.5 over x = 1.5.
    assert_eq!(mesh.frames.len(), 2);
    assert_eq!(mesh.frames[0][6], [2.0, 1.0, 0.0]);
    assert_eq!(mesh.frames[1][7], [0.0, 1.0, 0.05]);
    let ids = [0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4];
    let b = samples[3].border_frames().unwrap();
    assert_eq!(b.source, "mesh border edges");
    assert_eq!(b.border_indices, ids);
    let m = analysis(&samples[3]);
    assert_same_close(&m, &analysis(&border_sample(&ids, &mesh.frames)), &ids, 1e-9);
}

#[test]
fn mat_files_with_wrong_variables_are_named() {
    let err = read_files(&[fixture("wrong_names.mat")]).unwrap_err().to_string();
    assert!(
        err.contains("wrong_names.mat")
            && err.contains("phiPositions")
            && err.contains("positions"),
        "{err}"
    );
    let err =
        read_files(&[fixture("open_border.mat")]).unwrap().border_frames().unwrap_err().to_string();
    assert!(err.contains("do not close up"), "{err}");
    let mut v73 = fixture("napkin_dense.mat");
    v73.1[..10].copy_from_slice(b"MATLAB 7.3");
    assert!(read_files(&[v73]).unwrap_err().to_string().contains("HDF5"));
}

#[test]
fn bad_meshes_are_clear_errors() {
    let (flat, faces) = grid(3, 3, |_, _| true, false);
    let with_faces = |extra: Vec<Vec<usize>>| {
        let mut f = faces.clone();
        f.extend(extra);
        mesh_sample(f, vec![flat.clone()]).border_frames().unwrap_err()
    };
    assert!(with_faces(vec![vec![0, 1, 16]]).to_string().contains("vertex 16"));
    assert!(with_faces(vec![vec![0, 1, 7], vec![1, 0, 9]]).to_string().contains("non-manifold"));
    let no_faces = mesh_sample(Vec::new(), vec![flat.clone()]).border_frames().unwrap_err();
    assert!(matches!(no_faces, Error::Mesh(_)));
    let json = br#"{"mesh": {"faces": [[0, 1, 2]], "frames": [[[0,0,0],[1,0,0],[0,1,0]]]}}"#;
    let s = read_files(&[("t.json".into(), json.to_vec())]).unwrap();
    assert!(s.border_frames().unwrap_err().to_string().contains("too few"));
    let huge = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    let err = read_files(&[("h.ply".into(), huge.to_vec())]).unwrap_err();
    assert!(
        matches!(err.cause(), Read::Parse { .. } | Read::Core(Error::TooLarge { .. })),
        "{err}"
    );
    assert!(err.to_string().starts_with("h.ply: "), "{err}");
}

// ---- Bombs: inputs a few bytes long that would make a reader spin or balloon ----

/// `f()`, failing the test when it has not answered within `seconds` (the work is left
/// behind on its thread: on a reader that spins, the test fails instead of hanging).
fn answers_within<T: Send + 'static>(seconds: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || tx.send(f()));
    rx.recv_timeout(std::time::Duration::from_secs(seconds))
        .unwrap_or_else(|_| panic!("no answer within {seconds} s"))
}

/// A hang guard, not a speed test: the faults these tests guard against spun for minutes
/// or forever, while a debug build sharing a loaded machine took over 5 s for the large
/// ones (the bound was 5 s, and failed so).
const SECONDS: u64 = 60;

fn read_one(name: &'static str, bytes: Vec<u8>) -> Result<Sample, Read> {
    answers_within(SECONDS, move || read_files(&[(name.to_string(), bytes)]))
}

#[test]
fn ply_elements_without_properties_cannot_make_the_reader_spin() {
    // The 267-byte upload of issue 11: a property-less element announced 2^62 times.
    let (v, f) = grid(1, 1, |_, _| true, true);
    let plain = ply(&v, &f, "binary_little_endian");
    let bomb = [&plain[..], &[]].concat();
    let text = String::from_utf8_lossy(&bomb).into_owned();
    let header_end = text.find("element face").unwrap();
    let mut with_junk = bomb[..header_end].to_vec();
    with_junk.extend(b"element junk 4611686018427387904\n");
    with_junk.extend(&bomb[header_end..]);
    // Each element is counted for at least a byte: 2^62 cannot follow, in either encoding.
    let ascii = String::from_utf8(ply(&v, &f, "ascii")).unwrap().replacen(
        "element face",
        "element junk 4611686018427387904\nelement face",
        1,
    );
    for bomb in [with_junk, ascii.into_bytes()] {
        let err = read_one("junk.ply", bomb).unwrap_err();
        assert!(
            matches!(err.cause(), Read::Parse { .. })
                && err.to_string().contains("4611686018427387904 junk"),
            "{err}"
        );
    }
}

/// A MATLAB v5 file (little endian) of the given elements.
fn mat_file(elements: &[Vec<u8>]) -> Vec<u8> {
    let mut file = b"MATLAB 5.0 MAT-file, written by tests/formats.rs".to_vec();
    file.resize(124, b' ');
    file.extend([0, 1, b'I', b'M']);
    elements.iter().for_each(|e| file.extend(e));
    file
}

/// A tagged element, little endian, padded to 8 bytes.
fn mat_element(kind: u32, data: &[u8]) -> Vec<u8> {
    let mut v = kind.to_le_bytes().to_vec();
    v.extend((data.len() as u32).to_le_bytes());
    v.extend(data);
    v.resize(8 + data.len().div_ceil(8) * 8, 0);
    v
}

/// A double matrix (class 6) of `rows`×`cols` whose values are stored as `data_type`.
fn mat_matrix(name: &str, rows: u32, cols: u32, data_type: u32, data: &[u8]) -> Vec<u8> {
    let mut body = mat_element(6, &[6, 0, 0, 0, 0, 0, 0, 0]);
    body.extend(mat_element(5, &[rows.to_le_bytes(), cols.to_le_bytes()].concat()));
    body.extend(mat_element(1, name.as_bytes()));
    body.extend(mat_element(data_type, data));
    mat_element(14, &body)
}

fn compressed(element: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
    z.write_all(element).unwrap();
    let packed = z.finish().unwrap();
    // miCOMPRESSED is not padded.
    [15u32.to_le_bytes().to_vec(), (packed.len() as u32).to_le_bytes().to_vec(), packed].concat()
}

#[test]
fn mat_numbers_are_capped_once_widened_and_over_all_variables() {
    use close::formats::mat::MAX_WIDENED;
    // 17 M int8 values: 17 MB inflated, 136 MB once widened to f64, over the cap.
    let count = 17_000_000u32;
    assert!(count as u64 * 8 > MAX_WIDENED && (count as u64) < MAX_WIDENED);
    let bomb =
        mat_file(&[compressed(&mat_matrix("phiPositions", count, 1, 1, &vec![0; count as usize]))]);
    assert!(bomb.len() < 100_000, "{} bytes", bomb.len());
    let err = read_one("bomb.mat", bomb).unwrap_err();
    assert!(
        matches!(err.cause(), Read::Core(Error::TooLarge { limit, .. }) if *limit == MAX_WIDENED),
        "{err}"
    );
    // Three variables each under the cap, over it together.
    let third = (MAX_WIDENED / 8 / 3 + 1) as u32;
    let var = compressed(&mat_matrix("Eb", third, 1, 1, &vec![0; third as usize]));
    let err = read_one("three.mat", mat_file(&[var.clone(), var.clone(), var])).unwrap_err();
    assert!(
        matches!(err.cause(), Read::Core(Error::TooLarge { limit, .. }) if *limit == MAX_WIDENED),
        "{err}"
    );
    assert!(err.to_string().contains("widened"), "{err}");
}

#[test]
fn an_obj_polygon_with_many_corners_is_checked_in_n_log_n() {
    // One polygon through K = 100 000 distinct vertices: the repeated-vertex check was
    // O(K²) (K = 480 000 took 28.6 s in a release build); sorted, it takes well under a
    // second.
    let k = 100_000;
    let polygon = |repeat: Option<usize>| {
        let mut doc: String = (0..k).map(|i| format!("v {i} {} 0\n", i % 7)).collect();
        doc += &format!("f {}", (1..=k).map(|i| i.to_string()).collect::<Vec<_>>().join(" "));
        doc += &repeat.map_or("\n".into(), |r| format!(" {r}\n"));
        doc.into_bytes()
    };
    let check = |doc: Vec<u8>| {
        answers_within(SECONDS, move || {
            let mesh = read_files(&[("k.obj".into(), doc)])?
                .mesh
                .ok_or(Error::Empty { what: "no mesh" })?;
            Ok::<_, Read>(close::mesh::validate(&mesh)?)
        })
    };
    assert_eq!(check(polygon(None)), Ok(()));
    // A repeat among them is still found, naming the vertex (0-based).
    let err = check(polygon(Some(5))).unwrap_err();
    assert_eq!(
        err,
        Read::Core(Error::Mesh(close::error::MeshError::RepeatedVertex { face: 0, vertex: 4 }))
    );
}

#[test]
fn json_counts_and_nesting_are_refused_while_reading() {
    use close::border::{MAX_FRAMES, MAX_VERTICES};
    // More frames than allowed, each empty: refused at frame 1001, not after reading all.
    let frames = format!("{{\"frames\": [{}[]]}}", "[],".repeat(10 * MAX_FRAMES));
    let err = read_one("f.json", frames.into_bytes()).unwrap_err();
    assert!(
        matches!(err.cause(), Read::Core(Error::TooLarge { what: "frames", limit, .. }) if *limit == MAX_FRAMES as u64),
        "{err}"
    );
    // A frame with more vertices than a border may have.
    let one = format!("{{\"frames\": [[{}[0,0,0]]]}}", "[0,1,2],".repeat(2 * MAX_VERTICES));
    assert!(matches!(
        read_one("v.json", one.into_bytes()).unwrap_err().cause(),
        Read::Core(Error::TooLarge { .. })
    ));
    // A mesh with more frames than allowed.
    let mesh = format!(
        "{{\"mesh\": {{\"faces\": [[0,1,2]], \"frames\": [{}[]]}}}}",
        "[],".repeat(MAX_FRAMES + 1)
    );
    assert!(matches!(
        read_one("m.json", mesh.into_bytes()).unwrap_err().cause(),
        Read::Core(Error::TooLarge { what: "frames", .. })
    ));
    // Deep nesting, where a number is expected and in an ignored field: serde_json's
    // recursion limit answers, quickly, as a parse error.
    for doc in [
        format!("{{\"frames\": {}", "[".repeat(1_000_000)),
        format!("{{\"extra\": {}", "[".repeat(1_000_000)),
    ] {
        let err = read_one("deep.json", doc.into_bytes()).unwrap_err();
        assert!(matches!(err.cause(), Read::Parse { line: Some(1), .. }), "{err}");
    }
}

#[test]
fn degenerate_end_frames_are_refused_naming_the_frame() {
    use close::error::DegenerateReason;
    let square = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
    let prepared = |end: Vec<[f64; 3]>| {
        Sample::from_frames("s", "t", vec![square.to_vec(), end]).border_frames()
    };
    let reason = |r: Result<close::border::BorderFrames, Error>| match r {
        Err(Error::Degenerate { frame: 1, reason }) => reason,
        other => panic!("{other:?}"),
    };
    assert_eq!(reason(prepared(vec![[0.5, 0.5, 0.0]; 4])), DegenerateReason::Coincident);
    assert!(matches!(
        reason(prepared(square.iter().map(|p| p.map(|c| c * 1e300)).collect())),
        DegenerateReason::FarFromStart { .. }
    ));
    // The start frame near 1e300: too large to normalise, not "all vertices coincide".
    let huge: Vec<[f64; 3]> = square.iter().map(|p| p.map(|c| 1e300 + c * 1e299)).collect();
    let err = Sample::from_frames("s", "t", vec![huge]).border_frames().unwrap_err();
    assert_eq!(err, Error::Degenerate { frame: 0, reason: DegenerateReason::TooLargeToNormalise });
    assert!(!err.to_string().contains("coincide"), "{err}");
}

// ---- Fuzzing: no input may panic, hang or balloon ----

/// Every reader, then the border, on one named file. A case that takes seconds fails (a
/// reader looping on a declared count); a huge allocation aborts the run.
fn read_everything(name: &str, bytes: &[u8]) {
    let start = std::time::Instant::now();
    if let Ok(sample) = read_files(&[(name.to_string(), bytes.to_vec())]) {
        if let Ok(b) = sample.border_frames() {
            // One fold per step: this bounds the readers; the sequence search's own cost is
            // benched beside one fold's (benches/close.rs, analyze_quarters).
            let options = close::Options { max_folds: 1, ..close::Options::default() };
            let _ = close::analyze_with(&b, options);
        }
    }
    assert!(
        start.elapsed().as_secs() < 5,
        "{name}: {} bytes took {:?}",
        bytes.len(),
        start.elapsed()
    );
}

/// Element counts a header may announce: small, at the limits, and absurd.
fn counts() -> impl Strategy<Value = u64> {
    prop_oneof![0u64..6, Just(2_000_001), Just(4_000_000_000), Just(1 << 62), any::<u64>()]
}

/// A PLY header of random elements (vertex with x y z, face with an index list, property-
/// less or odd ones) with any counts, then a short random payload.
fn ply_with_counts() -> impl Strategy<Value = Vec<u8>> {
    let scalar = prop::sample::select(vec![
        "char", "uchar", "short", "ushort", "int", "uint", "float", "double",
    ]);
    let element = (
        prop::sample::select(vec!["vertex", "face", "junk"]),
        counts(),
        scalar.clone(),
        scalar,
        0usize..3,
    );
    let format = prop::sample::select(vec!["ascii", "binary_little_endian", "binary_big_endian"]);
    (
        format,
        proptest::collection::vec(element, 0..4),
        proptest::collection::vec(any::<u8>(), 0..200),
        any::<bool>(),
    )
        .prop_map(|(format, elements, payload, digits)| {
            let mut head = format!("ply\nformat {format} 1.0\n");
            for (name, count, t, u, extra) in elements {
                head += &format!("element {name} {count}\n");
                match name {
                    "vertex" => {
                        ["x", "y", "z"].iter().for_each(|a| head += &format!("property {t} {a}\n"))
                    }
                    "face" => head += &format!("property list {u} {t} vertex_indices\n"),
                    _ => (0..extra).for_each(|k| head += &format!("property {t} p{k}\n")),
                }
            }
            head += "end_header\n";
            // ASCII payloads of digits reach deeper than random bytes.
            let body = if digits {
                payload.iter().map(|b| b"0123456789 \n-"[*b as usize % 13]).collect()
            } else {
                payload
            };
            [head.into_bytes(), body].concat()
        })
}

/// OBJ statements with absurd indices and numbers.
fn obj_with_counts() -> impl Strategy<Value = Vec<u8>> {
    let index = prop_oneof![1i64..6, -5i64..0, Just(i64::MAX), Just(i64::MIN), any::<i64>()];
    let line = prop_oneof![
        (any::<f64>(), -2.0f64..2.0, prop_oneof![Just(1e308), Just(-1e308), Just(0.0)])
            .prop_map(|(x, y, z)| format!("v {x} {y} {z}")),
        proptest::collection::vec(index, 0..8).prop_map(|f| format!(
            "f {}",
            f.iter().map(|i| format!("{i}/1")).collect::<Vec<_>>().join(" ")
        )),
        Just("f 1 2 3 18446744073709551616".to_string()),
    ];
    proptest::collection::vec(line, 0..12).prop_map(|lines| (lines.join("\n") + "\n").into_bytes())
}

/// MATLAB elements whose tags, dimensions and classes claim anything, some compressed.
fn mat_with_counts() -> impl Strategy<Value = Vec<u8>> {
    let dims = prop_oneof![
        Just(vec![3u32, 4]),
        Just(vec![u32::MAX, u32::MAX]),
        Just(vec![1 << 31, 2]),
        proptest::collection::vec(any::<u32>(), 0..4)
    ];
    let matrix = (
        1u32..17,
        dims,
        1u32..16,
        proptest::collection::vec(any::<u8>(), 0..64),
        any::<bool>(),
        any::<u32>(),
    )
        .prop_map(|(class, dims, data_type, data, compress, claimed)| {
            let mut body = mat_element(6, &[class as u8, 0, 0, 0, 0, 0, 0, 0]);
            body.extend(mat_element(
                5,
                &dims.iter().flat_map(|d| d.to_le_bytes()).collect::<Vec<_>>(),
            ));
            body.extend(mat_element(1, b"phiPositions"));
            let mut data_el = mat_element(data_type, &data);
            if claimed % 3 == 0 {
                // A tag that claims more bytes than follow.
                data_el[4..8].copy_from_slice(&claimed.to_le_bytes());
            }
            body.extend(data_el);
            let element = mat_element(14, &body);
            if compress {
                compressed(&element)
            } else {
                element
            }
        });
    proptest::collection::vec(matrix, 0..3).prop_map(|elements| mat_file(&elements))
}

/// Sample JSON with absurd indices, deep nesting and odd shapes.
fn json_with_counts() -> impl Strategy<Value = Vec<u8>> {
    let nested = (0usize..3000, any::<bool>()).prop_map(|(depth, closed)| {
        format!("{}0{}", "[".repeat(depth), if closed { "]".repeat(depth) } else { String::new() })
    });
    let index = prop_oneof![
        Just("0".to_string()),
        Just("18446744073709551616".to_string()),
        Just("1e30".to_string()),
        Just("-1".to_string()),
        any::<u64>().prop_map(|i| i.to_string())
    ];
    (nested, proptest::collection::vec(index, 0..6), 0usize..8, any::<bool>()).prop_map(|(nested, face, vertices, mesh)| {
        let frame = format!("[{}]", vec!["[0, 0, 0]"; vertices].join(","));
        let doc = if mesh {
            format!("{{\"mesh\": {{\"faces\": [[{}]], \"frames\": [{frame}]}}, \"extra\": {nested}}}", face.join(","))
        } else {
            format!("{{\"frames\": [{frame}, {nested}], \"truth\": {{\"folded_vertices\": [{}]}}}}", face.join(","))
        };
        doc.into_bytes()
    })
}

fn valid_files() -> Vec<(&'static str, Vec<u8>)> {
    let (v, f) = grid(3, 3, |_, _| true, true);
    vec![
        ("x.obj", obj(&v, &f)),
        ("x.ply", ply(&v, &f, "ascii")),
        ("x.ply", ply(&v, &f, "binary_little_endian")),
        ("x.ply", ply(&v, &f, "binary_big_endian")),
        ("x.mat", fixture("napkin_sparse.mat").1),
        ("x.mat", fixture("napkin_sparse_compressed.mat").1),
        ("x.mat", fixture("napkin_dense_compressed.mat").1),
        (
            "x.json",
            br#"{"mesh": {"faces": [[0,1,2,3]], "frames": [[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]]}}"#
                .to_vec(),
        ),
    ]
}

/// Cases per fuzz property: 2000 in a normal run, `FUZZ_CASES=N` for a longer campaign.
fn fuzz_cases() -> u32 {
    std::env::var("FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(2000)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: fuzz_cases(), ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600), ext in prop::sample::select(vec!["obj", "ply", "mat", "json", "txt"])) {
        read_everything(&format!("x.{ext}"), &bytes);
    }

    #[test]
    fn headed_garbage_never_panics(body in proptest::collection::vec(any::<u8>(), 0..600), which in 0usize..3) {
        // Past the magic, so the parsers' inner paths are reached.
        let (name, head): (&str, Vec<u8>) = match which {
            0 => ("x.ply", b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n".to_vec()),
            1 => ("x.mat", fixture("napkin_dense.mat").1[..128].to_vec()),
            _ => ("x.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_vec()),
        };
        read_everything(name, &[head, body].concat());
    }

    #[test]
    fn mutated_valid_files_never_panic(
        which in 0usize..8,
        edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8),
        cut in any::<prop::sample::Index>(),
        truncate in any::<bool>(),
    ) {
        let (name, mut bytes) = valid_files().swap_remove(which);
        for (at, byte) in edits {
            let k = at.index(bytes.len());
            bytes[k] = byte;
        }
        if truncate {
            bytes.truncate(cut.index(bytes.len()));
        }
        read_everything(name, &bytes);
    }

    #[test]
    fn headers_with_any_counts_never_spin_or_balloon(
        ply in ply_with_counts(),
        obj in obj_with_counts(),
        mat in mat_with_counts(),
        json in json_with_counts(),
    ) {
        read_everything("x.ply", &ply);
        read_everything("x.obj", &obj);
        read_everything("x.mat", &mat);
        read_everything("x.json", &json);
    }

    #[test]
    fn random_meshes_never_panic(
        n in 3usize..30,
        faces in proptest::collection::vec(proptest::collection::vec(0usize..32, 3..5), 0..40),
        coords in proptest::collection::vec(-2.0f64..2.0, 90),
    ) {
        let v: Vec<[f64; 3]> = (0..n).map(|k| [coords[3 * k], coords[3 * k + 1], coords[3 * k + 2] * 0.1]).collect();
        if let Ok(b) = mesh_sample(faces, vec![v.clone(), v]).border_frames() {
            prop_assert!(b.border_indices.iter().all(|&k| k < n));
            let unique: HashSet<_> = b.border_indices.iter().collect();
            prop_assert_eq!(unique.len(), b.border_indices.len());
        }
    }
}
