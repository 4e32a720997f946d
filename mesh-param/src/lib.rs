//! Surface parameterization for the mesh workspace (work in progress).
#![deny(missing_docs)]
