//! What the tests, benches, examples and `cargo xtask` of the mesh workspace
//! share, so that none of them writes it again:
//!
//! - [`data`]: where the real test meshes are, and what happens when they
//!   are absent (skipped loudly by default, a failure when
//!   `MESH_REQUIRE_SHARED_DATA=1`, as continuous integration sets it);
//! - [`SplitMix64`]: a seeded, platform-independent random generator;
//! - [`data::SHARED_MESHES`]: the ground-truth counts of the shared meshes;
//! - [`read_raw`]: a minimal OFF / OBJ reader, for crates whose tests must
//!   not depend on mesh-io;
//! - [`analytic`]: analytic ground truth (the unit disk's Neumann spectrum).
//!
//! Not published (`publish = false`): crates take it as a dev-dependency
//! with a path and no version, which `cargo publish` removes from the
//! packaged manifest; the tests and benches that use it are therefore left
//! out of the packages (see each crate's `include` list).
//!
//! ```
//! let mut rng = mesh_testkit::SplitMix64::new(7);
//! let x = rng.signed();
//! assert!((-1.0..1.0).contains(&x));
//! ```
#![deny(missing_docs)]

pub mod analytic;
pub mod data;
mod raw;
#[path = "../../mesh-kernel/src/random.rs"]
mod rng;

pub use data::{shared_data, shared_file};
pub use raw::{read_raw, shared_meshes, RawMesh};
pub use rng::SplitMix64;
