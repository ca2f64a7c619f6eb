//! The handlers of the HTTP API, one module per kind of request: each reads a typed request,
//! runs the library on a blocking worker (with the request's deadline and the server's
//! budget), and writes a typed response there too, so the async threads only move bytes.
//! Which path goes to which handler is the router's table ([`crate::app`]).

mod analysis;
mod analyze;
mod disk;
mod distance;
mod interpolate;
mod json;
mod pictures;
mod plan;
mod samples;
mod service;
mod uploads;

pub use analyze::analyze;
pub use disk::{disk, disk_cells};
pub use distance::distance;
pub use interpolate::interpolate;
pub use json::JsonBytes;
pub use pictures::{cell_picture, image, readout};
pub use plan::{plan, verify};
pub use samples::{recording, sample};
pub use service::{healthz, not_found};
pub use uploads::analysis_by_key;
