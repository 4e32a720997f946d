//! Exact polyhedral geodesic distances by window propagation, organised as
//! vertex-oriented triangle propagation (VTP).
//!
//! A *window* is an interval of a mesh edge together with the position,
//! unfolded into the plane of the face it enters, of the point it is seen
//! from (the source or a pseudo-source vertex) and that point's distance
//! `sigma` (Mitchell, Mount and Papadimitriou 1987; the planar window
//! geometry of Surazhsky, Surazhsky, Kirsanov, Gortler and Hoppe 2005). A
//! geodesic can only bend at a vertex whose total angle exceeds 2 pi
//! (saddles) or that lies on the boundary; such vertices (and the sources)
//! become pseudo-sources that emit windows across the far edge of each of
//! their faces.
//!
//! The order is that of Qin, Han, Yu, Yu and Zhang 2016 ("Fast and exact
//! discrete geodesic computation based on triangle-oriented wavefront
//! propagation"): the windows that crossed an edge into a face wait there
//! in that half-edge's list; a Dijkstra-like vertex queue pops vertices in
//! order of their current distance, and each popped vertex sends the lists
//! of the half-edges around it across their faces, first in first out, as
//! long as they touch a popped vertex. A list crosses its face A B C as a
//! group:
//! 1. the vertex filter of Xin and Wang 2009 ("improved Chen and Han")
//!    has dropped, when it was created, a window on A B with
//!    `d(A) + |A P| < sigma + |s P|` at its end P farthest from A (or the
//!    same with B): every point of it is then reached more shortly along
//!    the edge;
//! 2. every two overlapping windows are trimmed against each other as in
//!    MMP: where one reaches a point of the edge longer than the other, its
//!    rays there are useless (the equal-distance points are the roots of a
//!    quadratic, polished by Newton steps);
//! 3. C gets the shortest route through the list (straight, or bent at the
//!    window end nearest to the ray to C), and every window is split at C
//!    into its rays towards A C and towards C B, minus the rays that cross
//!    the last segment of the shortest route to C found through this edge
//!    (Chen and Han 1990, "one angle, one split").
//!
//! Every test drops rays only where a real path is shorter by a relative
//! margin of 1e-12, so the result is the exact polyhedral distance up to
//! rounding; the order of processing affects only the cost. Each popped
//! vertex also relaxes its edges, so every vertex of the source's
//! component is popped and every list is eventually propagated.
//!
//! Cost: windows created grow like V^1.5 on the icospheres (7.8k, 56k,
//! 0.49M, 4.0M for 642 .. 40,962 vertices; 65 per vertex on the bunny Loop
//! x2, 29,394 vertices), measured; 40 bytes each while they wait; worst
//! case O(V^2 log V) time, bounded by [`ExactOptions::max_windows`].

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
/// Papadimitriou 1987; Surazhsky et al. 2005) in the vertex-oriented order
/// of Qin et al. 2016, with MMP's pairwise window trimming, the
/// vertex-distance filter of Xin and Wang 2009 and Chen and Han's one split
/// per angle (see the [module documentation](self)). `+infinity` where no
/// source is reachable.
///
/// Needs an oriented 2-manifold ([`mesh_kernel::MeshError::NonManifold`]
/// otherwise) without zero-area triangles ([`crate::GeodesicError::Degenerate`]).
/// Cost: about V^1.5 windows on the icospheres (measured), worst case
/// O(V^2 log V) time; at most
/// [`ExactOptions::max_windows`] windows, then [`crate::GeodesicError::WorkLimit`].
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
