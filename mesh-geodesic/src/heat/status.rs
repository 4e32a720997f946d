//! What the heat method reports per vertex, and what continues it where
//! the heat flow is not resolved (see the `far` module of [`super`]).

use crate::error::GeodesicError;

/// What computes the distance where the heat flow is not resolved.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum HeatFarField {
    /// Fast Marching (Kimmel and Sethian 1998, the crate's
    /// [`crate::FastMarching`]) continues the heat distance from the
    /// vertices where the heat flow is resolved with a margin. Cost, only
    /// when there is a far field: O(F) to cut out the far region (plus one
    /// ring of faces), stencils and an O(V log V) march on it. Exact on
    /// developable meshes; on curved ones as accurate as Fast Marching,
    /// which is more accurate than the heat method.
    #[default]
    FastMarching,
    /// The heat flow is restarted from the band where it was last
    /// resolved, with the band's heat values, rescaled, as initial data:
    /// since they decay like exp(-d / sqrt(t)), they carry the distances
    /// reached so far as offsets, and the new flow continues the old one.
    /// A pure heat-method field; cost one more pair of triangular solves
    /// per restart, each covering about 1300 more mean edge lengths, at
    /// most 64 restarts (farther vertices are flagged
    /// [`HeatStatus::Unresolved`]).
    Restart,
    /// No continuation: those vertices keep the Poisson step's value (flat
    /// there) and are flagged [`HeatStatus::Unresolved`].
    None,
}

impl HeatFarField {
    /// Every choice; their [`name`](Self::name)s are what [`FromStr`](std::str::FromStr)
    /// accepts and [`Display`](std::fmt::Display) writes.
    pub const ALL: [HeatFarField; 3] = [HeatFarField::FastMarching, HeatFarField::Restart, HeatFarField::None];

    /// The name used on the command line: `fmm`, `restart`, `none`.
    pub fn name(self) -> &'static str {
        match self {
            HeatFarField::FastMarching => "fmm",
            HeatFarField::Restart => "restart",
            HeatFarField::None => "none",
        }
    }
}

mesh_kernel::named_choice!(HeatFarField, "far_field", GeodesicError);

/// How the distance of one vertex was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum HeatStatus {
    /// By the heat method: the heat flow is resolved at the vertex (with
    /// [`HeatFarField::Restart`], by one of the restarted flows).
    Heat,
    /// By Fast Marching beyond the heat flow's resolved range
    /// ([`HeatFarField::FastMarching`]), or where the heat flow is negative
    /// (next to negative weights of the Laplacian, which the intrinsic
    /// Delaunay triangulation keeps on boundary edges opposite obtuse
    /// angles).
    FarField,
    /// Not trustworthy: beyond the heat flow's resolved range and not
    /// continued ([`HeatFarField::None`]).
    Unresolved,
    /// No source on its component: `+infinity`.
    Unreached,
}

/// The result of [`HeatGeodesics::solve`](crate::HeatGeodesics::solve): one distance and one status per
/// vertex.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct HeatDistance {
    /// Distance from the nearest source; `+infinity` where unreached.
    pub distance: Vec<f64>,
    /// How each distance was obtained.
    pub status: Vec<HeatStatus>,
}

impl HeatDistance {
    /// Number of vertices with the given status. O(V).
    pub fn count(&self, status: HeatStatus) -> usize {
        self.status.iter().filter(|s| **s == status).count()
    }
}
