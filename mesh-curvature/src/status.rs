//! Per-vertex validity flags shared by every estimator.

/// How trustworthy the value computed at a vertex is. Every estimator returns
/// finite numbers at every vertex; this flag says which of them are estimates
/// of the smooth curvature and which are conventions (documented per
/// quantity) at vertices where the surface gives no estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum VertexStatus {
    /// Interior manifold vertex with a usable neighbourhood: a real estimate.
    #[default]
    Valid,
    /// On a boundary: the value is a one-sided estimate (tensor, mean) or a
    /// convention (Gaussian curvature 0, the defect going to the geodesic
    /// curvature).
    Boundary,
    /// Incident faces form several fans or share an edge with more than two
    /// faces: values are computed from all incident faces but do not estimate
    /// a surface curvature.
    NonManifold,
    /// Referenced by no face: every value is 0.
    Isolated,
    /// The neighbourhood has no area, no normal or too few points for the
    /// estimator (zero-area faces, collinear or coincident neighbours): values
    /// are 0 or the best finite fallback.
    Degenerate,
    /// A fit whose least-squares problem amplifies the data's errors beyond
    /// the conditioning limit on every neighbourhood and degree tried (the
    /// points nearly lie on a curve of the polynomial space): the values are
    /// those of the best-conditioned fit, finite but not trusted.
    IllConditioned,
}

impl VertexStatus {
    /// `true` for [`VertexStatus::Valid`].
    #[inline]
    pub fn is_valid(self) -> bool {
        self == Self::Valid
    }

    /// Short lowercase name, for reports.
    pub fn name(self) -> &'static str {
        match self {
            Self::Valid => "valid",
            Self::Boundary => "boundary",
            Self::NonManifold => "non-manifold",
            Self::Isolated => "isolated",
            Self::Degenerate => "degenerate",
            Self::IllConditioned => "ill-conditioned",
        }
    }
}

/// Status from the connectivity alone (no geometry): interior vertices are
/// `Valid` until an estimator finds them degenerate. O(V).
pub(crate) fn topological_status(mesh: &mesh_kernel::TriMesh) -> Vec<VertexStatus> {
    mesh.connectivity().vertex_kinds().iter().map(|&k| status_of_kind(k)).collect()
}

/// [`topological_status`] of one vertex of the given kind.
#[inline]
pub(crate) fn status_of_kind(kind: mesh_kernel::VertexKind) -> VertexStatus {
    use mesh_kernel::VertexKind;
    match kind {
        VertexKind::Interior => VertexStatus::Valid,
        VertexKind::Boundary => VertexStatus::Boundary,
        VertexKind::NonManifold => VertexStatus::NonManifold,
        VertexKind::Isolated => VertexStatus::Isolated,
    }
}

/// Counts of each status, for summaries.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct StatusCounts {
    /// Vertices with [`VertexStatus::Valid`].
    pub valid: usize,
    /// Vertices with [`VertexStatus::Boundary`].
    pub boundary: usize,
    /// Vertices with [`VertexStatus::NonManifold`].
    pub non_manifold: usize,
    /// Vertices with [`VertexStatus::Isolated`].
    pub isolated: usize,
    /// Vertices with [`VertexStatus::Degenerate`].
    pub degenerate: usize,
    /// Vertices with [`VertexStatus::IllConditioned`].
    pub ill_conditioned: usize,
}

impl StatusCounts {
    /// Counts the statuses of a slice. O(V).
    pub fn of(status: &[VertexStatus]) -> Self {
        let mut c = Self::default();
        for s in status {
            match s {
                VertexStatus::Valid => c.valid += 1,
                VertexStatus::Boundary => c.boundary += 1,
                VertexStatus::NonManifold => c.non_manifold += 1,
                VertexStatus::Isolated => c.isolated += 1,
                VertexStatus::Degenerate => c.degenerate += 1,
                VertexStatus::IllConditioned => c.ill_conditioned += 1,
            }
        }
        c
    }
}
