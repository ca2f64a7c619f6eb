//! Boundary loops: chaining edges into closed vertex cycles.
//!
//! An edge list in which every vertex has exactly two incident edges splits into disjoint
//! cycles; each is walked from its lowest-numbered vertex so the result does not depend on
//! the order the edges were listed in. A vertex with one incident edge (an open chain) or
//! more than two (two loops touching) has no single successor and is an error naming it.
//!
//! ```
//! use close_io::mesh::boundary::{chain_loops, single_loop};
//! // Two triangles' worth of loops, listed out of order.
//! let loops = chain_loops(&[[4, 5], [0, 1], [5, 3], [2, 0], [1, 2], [3, 4]]).unwrap();
//! assert_eq!(loops, vec![vec![0, 1, 2], vec![3, 4, 5]]);
//! assert!(single_loop(&[[0, 1], [1, 2], [2, 0], [3, 4], [4, 5], [5, 3]]).is_err());
//! assert!(single_loop(&[[0, 1], [1, 2]]).unwrap_err().to_string().contains("vertex 0"));
//! ```

use std::collections::{BTreeMap, HashMap};

use close_core::error::{MeshError, Result};

/// Split undirected edges into closed loops, each starting at its lowest vertex; loops are
/// listed by that vertex.
pub fn chain_loops(edges: &[[usize; 2]]) -> Result<Vec<Vec<usize>>> {
    // BTreeMap: walking vertices in increasing order makes every loop start at its lowest.
    let mut neighbours: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &[a, b] in edges {
        if a == b {
            return Err(MeshError::SelfEdge { vertex: a }.into());
        }
        neighbours.entry(a).or_default().push(b);
        neighbours.entry(b).or_default().push(a);
    }
    if let Some((v, n)) = neighbours.iter().find(|(_, n)| n.len() != 2) {
        let (vertex, edges) = (*v, n.len());
        return Err(if edges < 2 {
            MeshError::OpenBorder { vertex, edges }
        } else {
            MeshError::TouchingLoops { vertex, edges }
        }
        .into());
    }
    let mut visited: HashMap<usize, ()> = HashMap::with_capacity(neighbours.len());
    let mut loops = Vec::new();
    for &start in neighbours.keys() {
        if visited.contains_key(&start) {
            continue;
        }
        let mut cycle = vec![start];
        visited.insert(start, ());
        // Of the two neighbours of the start, go towards the smaller one (a fixed choice).
        let (mut prev, mut cur) =
            (start, neighbours[&start].iter().copied().min().unwrap_or(start));
        while cur != start {
            if visited.insert(cur, ()).is_some() {
                return Err(MeshError::ReachedTwice { vertex: cur }.into());
            }
            cycle.push(cur);
            let n = &neighbours[&cur];
            // A doubled edge (a–b listed twice) makes both neighbours equal: the loop is a–b.
            let next = if n[0] == prev { n[1] } else { n[0] };
            (prev, cur) = (cur, next);
        }
        loops.push(cycle);
    }
    Ok(loops)
}

/// The one closed loop the edges must form (the MATLAB files' `Eb`).
pub fn single_loop(edges: &[[usize; 2]]) -> Result<Vec<usize>> {
    let mut loops = chain_loops(edges)?;
    match loops.len() {
        0 => Err(MeshError::NoBorderEdges.into()),
        1 => Ok(loops.remove(0)),
        loops => Err(MeshError::SeveralLoops { loops }.into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loop_starts_at_lowest_vertex_whatever_the_edge_order() {
        let a = chain_loops(&[[7, 3], [3, 9], [9, 5], [5, 7]]).unwrap();
        let b = chain_loops(&[[9, 5], [5, 7], [3, 9], [7, 3]]).unwrap();
        assert_eq!(a, b);
        assert_eq!(a[0][0], 3);
        assert_eq!(a[0].len(), 4);
    }

    #[test]
    fn touching_loops_and_self_edges_are_errors() {
        let bowtie = [[0, 1], [1, 2], [2, 0], [0, 3], [3, 4], [4, 0]];
        assert!(chain_loops(&bowtie).unwrap_err().to_string().contains("vertex 0 has 4"));
        assert!(chain_loops(&[[2, 2]]).unwrap_err().to_string().contains("itself"));
        assert!(single_loop(&[]).is_err());
    }
}
