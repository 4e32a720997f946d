//! Geodesic distances on triangle meshes (work in progress).
#![deny(missing_docs)]
