//! Exact polyhedral geodesic distances by window propagation.
//!
//! A *window* is an interval of a mesh edge together with the position,
//! unfolded into the plane of the edge's two faces, of the point it is seen
//! from (the source or a pseudo-source vertex) and that point's distance
//! `sigma` (Mitchell, Mount and Papadimitriou 1987; the planar window
//! geometry of Surazhsky, Surazhsky, Kirsanov, Gortler and Hoppe 2005).
//! Windows are propagated across faces in order of their smallest distance;
//! a geodesic can only bend at a vertex whose total angle exceeds 2 pi
//! (saddles) or that lies on the boundary, and such vertices become
//! pseudo-sources that emit windows in every direction.
//!
//! Instead of MMP's exact trimming of overlapping windows, a window is
//! dropped when the vertex distances already found prove it useless: a
//! window on edge UV is useless if `d(U) + |U P| < sigma + |s P|` at its end
//! P farthest from U (or the same with V), because every geodesic through
//! it is then beaten by the path through U along the edge (the filter of
//! Xin and Wang 2009, "improved Chen and Han", which VTP, Qin et al. 2016,
//! builds on). Rays of a window that cross the ray by which an earlier
//! window on the same edge reached the face's apex more shortly are cut
//! (Chen and Han 1990, "one angle, one split"). All tests are
//! conservative, so the result is the exact polyhedral distance up to
//! rounding. Worst case O(V^2 log V) time;
//! bounded by [`ExactOptions::max_windows`].

mod layout;
mod propagation;
mod window;

use mesh_kernel::{TriMesh, VertexId};

use crate::error::Result;
use crate::support::validate_sources;
use layout::Layout;
use propagation::Propagation;

/// Options of [`exact_distance`].
#[derive(Debug, Clone, PartialEq)]
pub struct ExactOptions {
    /// The work bound: at most this many windows are created; past it the
    /// call fails with [`crate::GeodesicError::WorkLimit`] instead of running on.
    /// Each window costs 40 bytes while it waits. Default 20 million.
    pub max_windows: usize,
}

impl Default for ExactOptions {
    fn default() -> Self {
        Self { max_windows: 20_000_000 }
    }
}

/// Exact geodesic distance (along the polyhedral surface) from the nearest
/// source to every vertex, by window propagation (Mitchell, Mount and
/// Papadimitriou 1987; Surazhsky et al. 2005) with the vertex-distance
/// filter of Xin and Wang 2009. `+infinity` where no source is reachable.
///
/// Needs an oriented 2-manifold ([`mesh_kernel::MeshError::NonManifold`]
/// otherwise) without zero-area triangles ([`GeodesicError::Degenerate`]).
/// Cost: about V^1.6 windows on the icospheres (measured), worst case
/// O(V^2 log V) time; at most
/// [`ExactOptions::max_windows`] windows, then [`GeodesicError::WorkLimit`].
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{exact_distance, ExactOptions};
///
/// // A flat grid: geodesics are straight lines.
/// let grid = shapes::grid(2.0, 1.0, 8, 4)?;
/// let d = exact_distance(&grid, &[VertexId(0)], &ExactOptions::default())?;
/// let p0 = grid.position(VertexId(0));
/// for (i, p) in grid.positions().iter().enumerate() {
///     assert!((d[i] - p.distance(p0)).abs() < 1e-12);
/// }
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::NoSources` / `GeodesicError::SourceOutOfRange` for bad sources; `GeodesicError::Mesh`
/// (`MeshError::NonManifold`) when the mesh is not an oriented manifold, or (`MeshError::Degenerate`) for
/// degenerate geometry; `GeodesicError::WorkLimit` past `ExactOptions::max_windows` windows.
pub fn exact_distance(mesh: &TriMesh, sources: &[VertexId], options: &ExactOptions) -> Result<Vec<f64>> {
    validate_sources(mesh, sources)?;
    // Unfoldings square lengths: work in a unit where nothing overflows.
    let (mesh, unit) = mesh_kernel::units::normalized(mesh);
    let conn = mesh.manifold_connectivity()?;
    let layout = Layout::new(&mesh)?;
    let mut state = Propagation::new(conn, &layout, options.max_windows);
    for &s in sources {
        state.set_source(s);
    }
    state.run()?;
    Ok(state.distance.iter().map(|d| d * unit).collect())
}
