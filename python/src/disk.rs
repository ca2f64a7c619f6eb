//! The dGLI disk of one border state, and where its pairs sit on the disk.

use close_core::budget::Budget;
use numpy::IntoPyArray;
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::convert::{points, Floats};
use crate::errors::{close_error, invalid};

/// The dGLI disk of one border state ((N, 3) array) as the condensed pair vector of
/// `close analyze --disks`: pairs (i, j), i < j, row-major (index i·N − i(i+1)/2 + j − i − 1),
/// N(N−1)/2 values. Computed on the border normalised by `reference` (the flat start frame,
/// whose normalisation and orientation apply, as in an analysis; default: the border itself).
/// `close.disk_layout(N)` gives each pair's place on the disk.
#[pyfunction]
#[pyo3(signature = (border, *, reference = None))]
pub(crate) fn dgli_disk<'py>(
    py: Python<'py>,
    border: &Bound<'py, PyAny>,
    reference: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let border = points(border, "border")?;
    let reference = reference.map(|r| points(r, "reference")).transpose()?;
    Budget::SERVER.analysis(1, border.len()).map_err(close_error)?;
    let disk = py
        .detach(|| close_core::disk::of_state(border, reference, &Default::default()))
        .map_err(close_error)?;
    Ok(disk.values().to_vec().into_pyarray(py))
}

/// Where each pair of `dgli_disk`'s vector sits on the disk of an N-edge border: radius
/// (L − d + 1)/L for cyclic distance d (the rim is 1) and angle π(2a + d + 1)/N (radians),
/// two (N(N−1)/2,) arrays in the same order. For `matplotlib`'s polar axes.
#[pyfunction]
pub(crate) fn disk_layout(py: Python<'_>, n: usize) -> PyResult<(Floats<'_>, Floats<'_>)> {
    if !(close_core::border::MIN_VERTICES..=close_core::border::MAX_VERTICES).contains(&n) {
        return Err(invalid(format!(
            "a disk has {} to {} edges, not {n}",
            close_core::border::MIN_VERTICES,
            close_core::border::MAX_VERTICES
        )));
    }
    let (radius, angle): (Vec<f64>, Vec<f64>) = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| close_core::disk::position(n, i, j)))
        .map(|p| (p.radius, p.angle))
        .unzip();
    Ok((radius.into_pyarray(py), angle.into_pyarray(py)))
}
