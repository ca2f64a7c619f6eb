//! PLACEHOLDER (the planning branch replaces this): one direct step.

use serde::Serialize;

use crate::border::Point;
use crate::fold::reflect::{folded_vertices, reflect_xy};

#[derive(Debug, Clone, Serialize)]
pub struct Pick {
    pub vertex: usize,
    pub from: [f64; 3],
    pub to: [f64; 3],
}

#[derive(Debug, Clone, Serialize)]
pub struct PlanStep {
    pub action: String,
    pub fold: [f64; 2],
    pub corners: Vec<usize>,
    pub picks: Vec<Pick>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Plan {
    pub case: String,
    pub steps: Vec<PlanStep>,
}

pub fn plan(flat: &[Point], corner_vertices: &[usize], _current_folds: &[[f64; 2]], goal: [f64; 2]) -> crate::Result<Plan> {
    let n = flat.len();
    let folded = folded_vertices(n, goal);
    let corners: Vec<usize> = corner_vertices.iter().copied().filter(|c| folded.contains(c)).take(2).collect();
    let to_param = |f: f64| f.rem_euclid(2.0 * std::f64::consts::PI) * n as f64 / (2.0 * std::f64::consts::PI);
    let (a, b) = (crate::border::point_at(flat, to_param(goal[0])), crate::border::point_at(flat, to_param(goal[1])));
    let picks = corners
        .iter()
        .map(|&v| {
            let to = reflect_xy(&flat[v], &a, &b);
            Pick { vertex: v, from: [flat[v].x, flat[v].y, flat[v].z], to: [to.x, to.y, to.z] }
        })
        .collect();
    Ok(Plan { case: "direct".into(), steps: vec![PlanStep { action: "fold".into(), fold: goal, corners, picks }] })
}
