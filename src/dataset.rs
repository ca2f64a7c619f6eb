//! PLACEHOLDER (the dataset branch replaces this): a few folded squares.

use std::f64::consts::PI;
use std::sync::OnceLock;

use crate::border::Point;
use crate::fold::reflect::apply_fold;
use crate::Sample;

pub struct Entry {
    pub id: String,
    pub sample: Sample,
}

fn square(n_side: usize) -> Vec<Point> {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    (0..4)
        .flat_map(|c| {
            let (a, b) = (corners[c], corners[(c + 1) % 4]);
            (0..n_side).map(move |k| {
                let t = k as f64 / n_side as f64;
                Point::new(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.0)
            })
        })
        .collect()
}

pub fn builtin() -> &'static [Entry] {
    static DATA: OnceLock<Vec<Entry>> = OnceLock::new();
    DATA.get_or_init(|| {
        let flat = square(10);
        let arr = |b: &[Point]| b.iter().map(|p| [p.x, p.y, p.z]).collect::<Vec<_>>();
        [("half", "napkin", [PI * 0.25, PI * 1.25]), ("diagonal", "napkin", [0.0, PI]), ("corner", "towel", [PI * 1.8, PI * 0.2])]
            .into_iter()
            .map(|(id, cat, fold)| {
                let end = apply_fold(&flat, fold);
                let mut sample = Sample::from_frames(format!("square {id}"), cat, vec![arr(&flat), arr(&end)]);
                sample.truth = Some(crate::formats::Truth { folds: vec![fold], folded_vertices: None });
                Entry { id: format!("{cat}-{id}"), sample }
            })
            .collect()
    })
}

pub fn find(id: &str) -> Option<&'static Entry> {
    builtin().iter().find(|e| e.id == id)
}
