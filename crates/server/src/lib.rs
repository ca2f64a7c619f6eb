//! The CloSE web app: an axum server over the library, same JSON as `close analyze --json`
//! ([`server`]), over [`close_render`] (re-exported whole).

pub use close_render::*;

pub mod server;
