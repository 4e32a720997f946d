//! The heat method for geodesic distance (Crane, Weischedel and Wardetzky
//! 2013, "Geodesics in heat"): integrate the heat flow from the sources for
//! a short time t, normalize its gradient into the unit field X pointing
//! away from the sources, and recover the distance phi whose gradient is
//! closest to X by a Poisson equation:
//!
//! 1. (M + t L) u = delta_sources (one backward Euler step, t = m h^2 with h
//!    the mean edge length);
//! 2. X = -grad u / |grad u| in every triangle;
//! 3. L phi = div X, then phi shifted so that the sources sit at 0.
//!
//! L is the cotangent Laplacian (positive semi-definite, eq. 2.15) of the
//! mesh or of its intrinsic Delaunay triangulation, M the lumped
//! (barycentric) mass. Gradients and divergences are computed intrinsically
//! from edge lengths, each triangle laid out in the plane, so the same code
//! serves both triangulations and zero-area triangles never divide by zero.
//! On meshes with boundary, u is the mean of the Neumann and Dirichlet heat
//! flows, as the paper recommends (section 3.2.2).
//!
//! [`HeatGeodesics`] factors the three (two without boundary) matrices once,
//! sharing one symbolic analysis; each query then costs two or three sparse
//! triangular solve pairs plus O(F).
//!
//! # Far from the sources
//!
//! The heat flow decays like exp(-d / sqrt(t)), about 0.42 decimal orders
//! of magnitude per mean edge length h with t = h^2. Two things used to cut
//! the method off and leave a flat plateau beyond (on a 1500 x 2 strip,
//! 72% of the vertices at about 427 instead of up to 1500):
//! - normalizing X by |grad u| = sqrt(g . g), whose square underflows once u
//!   is below about 1e-154 (370 h from a unit source); here the gradient is
//!   divided by the triangle's largest heat value first, which leaves the
//!   direction unchanged and is exact to rounding down to the denormals;
//! - the unit source itself, which wastes half the exponent range: the heat
//!   matrix is scaled to entries of order one (M / h^2 + m L) and the
//!   sources to 2^1000 over the square root of its largest diagonal entry;
//!   where M + t L is an M-matrix (non-negative weights, which the intrinsic
//!   Delaunay triangulation guarantees except on boundary edges opposite
//!   obtuse angles), A^-1 >= 0 and A^-1 M 1 = 1 bound every value by
//!   2^1000, and the triangular solves add only terms of one sign, so that
//!   each value is computed to full relative precision however small. The
//!   flow is then resolved (at least 2^-1000) for about 1400 h.
//!
//! Beyond that, [`HeatFarField`] continues the field (Fast Marching by
//! default, or restarted heat flows) or flags the vertices; negative heat
//! values, possible next to negative weights, are treated the same way. [`HeatGeodesics::solve`] reports how each vertex was
//! obtained ([`HeatStatus`]).

mod assembly;
mod face;
mod far;
mod status;

use mesh_kernel::glam::DVec2;
use mesh_kernel::operators::{IntrinsicOptions, IntrinsicTriangulation, LaplacianKind, MassKind};
use mesh_kernel::solver::{Cholesky, FillOrdering};
use mesh_kernel::{TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};
use crate::support::validate_sources;
use assembly::{first_split_vertex, heat_ceiling, pin_pieces, shifted, unchanged_lengths, with_identity_rows};
use face::{extrinsic_faces, FaceGradient};
pub use status::{HeatDistance, HeatFarField, HeatStatus};

/// Boundary condition of the heat flow on meshes with boundary.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum HeatBoundary {
    /// Zero normal derivative (natural boundary condition).
    Neumann,
    /// Zero temperature on the boundary.
    Dirichlet,
    /// The mean of the Neumann and Dirichlet solutions (the paper's
    /// recommendation, section 3.2.2): one more factorization.
    #[default]
    Mean,
}

impl HeatBoundary {
    /// Every condition; their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and
    /// [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 3] = [Self::Mean, Self::Neumann, Self::Dirichlet];

    /// The name used on the command line: `mean`, `neumann`, `dirichlet`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Mean => "mean",
            Self::Neumann => "neumann",
            Self::Dirichlet => "dirichlet",
        }
    }
}

mesh_kernel::named_choice!(HeatBoundary, "boundary", GeodesicError);

/// Options of [`HeatGeodesics`] and [`heat_distance`].
#[derive(Debug, Clone, PartialEq)]
pub struct HeatOptions {
    /// The factor m of the time step t = m h^2, h the mean edge length.
    /// Default 1 (the paper's choice).
    pub time_factor: f64,
    /// The Laplacian (and triangulation) the heat method works on. Default
    /// [`LaplacianKind::IntrinsicDelaunay`] (Sharp and Crane 2020): finite on
    /// zero-area triangles and identical to [`LaplacianKind::Cotan`] on
    /// Delaunay meshes. With [`LaplacianKind::Cotan`] (the paper's choice)
    /// zero-area triangles contribute nothing; if that disconnects part of
    /// the mesh, construction fails with [`GeodesicError::Degenerate`].
    /// [`LaplacianKind::Auto`] takes the cotangent one unless the mesh has
    /// zero-area faces.
    pub laplacian: LaplacianKind,
    /// The boundary condition of the heat flow. Default [`HeatBoundary::Mean`].
    pub boundary: HeatBoundary,
    /// Options of the intrinsic Delaunay triangulation.
    pub intrinsic: IntrinsicOptions,
    /// What computes the distance where the heat flow is below what double
    /// precision resolves. Default [`HeatFarField::FastMarching`].
    pub far_field: HeatFarField,
}

impl Default for HeatOptions {
    fn default() -> Self {
        Self {
            time_factor: 1.0,
            laplacian: LaplacianKind::IntrinsicDelaunay,
            boundary: HeatBoundary::default(),
            intrinsic: IntrinsicOptions::default(),
            far_field: HeatFarField::default(),
        }
    }
}

/// The prefactored heat method (Crane, Weischedel and Wardetzky 2013).
/// [`HeatGeodesics::new`] assembles and factors once: cost one symbolic
/// analysis and two numeric sparse Cholesky factorizations (three on meshes
/// with boundary and [`HeatBoundary::Mean`]), plus the intrinsic Delaunay
/// flips when chosen. [`HeatGeodesics::distance`] then answers any source
/// set with two (three) pairs of triangular solves and O(F) work, plus the
/// far field where the heat flow is not resolved (see the module
/// documentation; none on meshes spanning less than about 1400 mean edge
/// lengths from the sources).
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{HeatGeodesics, HeatOptions};
///
/// let sphere = shapes::icosphere(4)?;
/// let heat = HeatGeodesics::new(&sphere, &HeatOptions::default())?;
/// let p0 = sphere.position(VertexId(0));
/// let d = heat.distance(&[VertexId(0)])?;
/// for (p, d) in sphere.positions().iter().zip(&d) {
///     assert!((d - p.dot(p0).clamp(-1.0, 1.0).acos()).abs() < 0.05);
/// }
/// // Any other source set reuses the factorizations.
/// let d2 = heat.distance(&[VertexId(0), VertexId(1)])?;
/// assert_eq!((d2[0], d2[1]), (0.0, 0.0));
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
#[derive(Debug, Clone)]
pub struct HeatGeodesics {
    vertex_count: usize,
    time: f64,
    faces: Vec<FaceGradient>,
    /// The heat factor with Neumann boundary conditions (natural).
    neumann: Option<Cholesky>,
    /// The heat factor with the boundary rows fixed to zero.
    dirichlet: Option<Cholesky>,
    poisson: Cholesky,
    /// The lumped mass in units of h^2 (the heat matrix is M / h^2 + m L).
    mass: Vec<f64>,
    /// The heat value the sources are scaled to (see [`HeatGeodesics::heat_flow`]).
    ceiling: f64,
    /// One pinned vertex per connected piece of the Laplacian.
    pinned: Vec<u32>,
    far_field: HeatFarField,
    /// The mesh (without its connectivity), for the far field.
    mesh: TriMesh,
    /// Connected component of each vertex (`u32::MAX` when isolated).
    component: Vec<u32>,
    component_count: usize,
    /// The unit of length the operators are in: internal distances times
    /// `unit` are distances on the mesh.
    unit: f64,
}

impl HeatGeodesics {
    /// Assembles and factors the heat and Poisson systems (see
    /// [`HeatGeodesics`]). Errors: an empty mesh, a non-positive time factor,
    /// a cotangent Laplacian disconnected by zero-area triangles, or a
    /// factorization failure.
    ///
    /// # Errors
    /// `GeodesicError::InvalidOption` (`time_factor`) for a time factor that is not finite and positive;
    /// `GeodesicError::Mesh` with `MeshError::Empty` for a mesh without faces, or the errors of the intrinsic
    /// Delaunay triangulation and of the Cholesky factorization (`MeshError::Solver`);
    /// `GeodesicError::Degenerate` when zero-area triangles disconnect the cotangent Laplacian (choose
    /// `LaplacianKind::IntrinsicDelaunay`) or every edge has zero length.
    pub fn new(mesh: &TriMesh, options: &HeatOptions) -> Result<Self> {
        if !(options.time_factor.is_finite() && options.time_factor > 0.0) {
            return Err(GeodesicError::InvalidOption {
                name: "time_factor",
                reason: format!("{} is not a finite positive number", options.time_factor),
            });
        }
        if mesh.face_count() == 0 {
            return Err(mesh_kernel::MeshError::Empty.into());
        }
        // Masses are areas: work in a unit where they cannot over- or underflow.
        let (mesh, unit) = mesh_kernel::units::normalized(mesh);
        let mesh = mesh.as_ref();
        let n = mesh.vertex_count();
        let extrinsic = || {
            let faces = extrinsic_faces(mesh);
            let g = mesh.geometry();
            (faces, g.cotan_laplacian().clone(), g.lumped_mass(MassKind::Barycentric).to_vec())
        };
        let kind = match options.laplacian {
            LaplacianKind::Auto => options.laplacian.resolve(mesh).0,
            kind => kind,
        };
        let (faces, laplacian, mass) = match kind {
            LaplacianKind::Cotan => extrinsic(),
            LaplacianKind::Auto | LaplacianKind::IntrinsicDelaunay => {
                let own;
                let t = if options.intrinsic == IntrinsicOptions::default() {
                    mesh.geometry().intrinsic_delaunay()?
                } else {
                    own = IntrinsicTriangulation::delaunay(mesh, &options.intrinsic)?;
                    &own
                };
                if t.flip_count() == 0 && unchanged_lengths(mesh, &t.lengths()) {
                    // Already Delaunay and not mollified: the same operator,
                    // assembled faster from the mesh's edges.
                    extrinsic()
                } else {
                    let faces = t
                        .faces()
                        .iter()
                        .zip(t.lengths().chunks_exact(3))
                        .map(|(f, l)| FaceGradient::new(*f, [l[0], l[1], l[2]]))
                        .collect();
                    (faces, t.cotan_laplacian(), t.barycentric_mass())
                }
            }
        };
        let conn = mesh.connectivity();
        let components = conn.components();
        let (pinned, pieces) = pin_pieces(n, &faces);
        if pieces != components.count {
            let split = first_split_vertex(&faces, n, &components.vertex_component);
            return Err(GeodesicError::Degenerate(format!(
                "zero-area triangles disconnect the cotangent Laplacian (around vertex {split}); \
                 use LaplacianKind::IntrinsicDelaunay"
            )));
        }
        let mean_edge = mesh_kernel::geometry::mean_edge_length(mesh);
        let time = options.time_factor * mean_edge * mean_edge;
        if !(time > 0.0 && time.is_finite()) {
            return Err(GeodesicError::Degenerate("all edges have zero length".into()));
        }

        // Every matrix shares the pattern of L, so one symbolic analysis
        // serves all factorizations; removed rows keep explicit zeros.
        let isolated: Vec<bool> = (0..n).map(|v| conn.vertex_kind(VertexId::new(v)) == VertexKind::Isolated).collect();
        // The heat matrix divided by h^2: entries of order one whatever the
        // mesh's unit, so that the heat values' exponent range is known.
        let mass: Vec<f64> = mass.iter().map(|m| m / (mean_edge * mean_edge)).collect();
        let heat_matrix = shifted(&laplacian, options.time_factor, &mass, &isolated);
        let ceiling = heat_ceiling(&heat_matrix);
        let heat = Cholesky::with_ordering(&heat_matrix, &FillOrdering::of_points(mesh.positions()))?;
        let boundary: Vec<bool> = (0..n).map(|v| conn.is_boundary_vertex(VertexId::new(v))).collect();
        let dirichlet = if options.boundary != HeatBoundary::Neumann && boundary.iter().any(|b| *b) {
            let mut factor = heat.clone();
            factor.refactor(&with_identity_rows(&heat_matrix, &boundary))?;
            Some(factor)
        } else {
            None
        };
        let mut pinned_mask = isolated.clone();
        for &v in &pinned {
            pinned_mask[v as usize] = true;
        }
        let mut poisson = heat.clone();
        poisson.refactor(&with_identity_rows(&shifted(&laplacian, 1.0, &vec![0.0; n], &isolated), &pinned_mask))?;
        let neumann = match (options.boundary, &dirichlet) {
            (HeatBoundary::Dirichlet, Some(_)) => None,
            _ => Some(heat),
        };
        Ok(Self {
            vertex_count: n,
            time: time * unit * unit,
            unit,
            faces,
            neumann,
            dirichlet,
            poisson,
            mass,
            ceiling,
            pinned,
            far_field: options.far_field,
            mesh: TriMesh::new(mesh.positions().to_vec(), mesh.faces().to_vec())?,
            component: components.vertex_component.clone(),
            component_count: components.count,
        })
    }

    /// The time step t = m h^2 in use.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The continuation used where the heat flow is not resolved.
    pub fn far_field(&self) -> HeatFarField {
        self.far_field
    }

    /// Number of vertices of the mesh this was built for.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Approximate geodesic distance from the nearest of `sources` to every
    /// vertex; `+infinity` on components without a source (and on isolated
    /// vertices that are not sources). Sources are at 0; values are clamped
    /// at 0 from below. The same as [`HeatGeodesics::solve`] without the
    /// per-vertex status. Cost: two (three with a boundary) pairs of sparse
    /// triangular solves and O(F), plus the far field where there is one.
    ///
    /// # Errors
    /// As [`HeatGeodesics::solve`].
    pub fn distance(&self, sources: &[VertexId]) -> Result<Vec<f64>> {
        Ok(self.solve(sources)?.distance)
    }

    /// The distance of [`HeatGeodesics::distance`] with the status of every
    /// vertex: computed by the heat method, continued by the far field
    /// beyond the heat flow's resolved range, left unresolved (only with
    /// [`HeatFarField::None`]), or unreached.
    ///
    /// # Errors
    /// `GeodesicError::NoSources` for an empty `sources`; `GeodesicError::SourceOutOfRange` for a source that
    /// is not a vertex; `GeodesicError::Mesh` (`MeshError::Solver`) when a solve fails; the errors of Fast
    /// Marching when the far field is completed with it.
    pub fn solve(&self, sources: &[VertexId]) -> Result<HeatDistance> {
        let n = self.vertex_count;
        if sources.is_empty() {
            return Err(GeodesicError::NoSources);
        }
        if let Some(&vertex) = sources.iter().find(|s| s.idx() >= n) {
            return Err(GeodesicError::SourceOutOfRange { vertex, vertex_count: n });
        }
        let u = self.heat_flow(sources)?;
        let mut resolved: Vec<bool> = u.iter().map(|x| *x >= far::RESOLVED).collect();
        let mut phi = if self.far_field == HeatFarField::Restart {
            let mut directions: Vec<Option<DVec2>> = self.faces.iter().map(|f| f.resolved_descent(&u)).collect();
            self.restart(&u, &mut directions, &mut resolved)?;
            self.divergence(|f, _| directions[f])
        } else {
            self.divergence(|_, face| face.resolved_descent(&u))
        };
        self.poisson.solve_in_place(&mut phi)?;
        let phi = self.shift_to_sources(phi, sources);
        let mut out = self.finish(phi, &u, &resolved, sources)?;
        out.distance.iter_mut().for_each(|d| *d *= self.unit);
        Ok(out)
    }

    /// Step 1: the backward Euler heat flow (M / h^2 + m L) u = delta from
    /// the sources, averaged over the boundary conditions in use (in the
    /// Dirichlet system a source on the boundary is a boundary value).
    /// Every source gets delta_s = c min_s M_s with c the ceiling, so that
    /// u <= max_s delta_s / M_s = c by the maximum principle of the
    /// M-matrix (A^-1 >= 0, A^-1 M 1 = 1) and the values fill the exponent
    /// range from about 1e300 down.
    fn heat_flow(&self, sources: &[VertexId]) -> Result<Vec<f64>> {
        let smallest = sources.iter().map(|s| self.mass[s.idx()]).filter(|m| *m > 0.0).fold(1.0f64, f64::min);
        let mut delta = vec![0.0; self.vertex_count];
        for s in sources {
            delta[s.idx()] = self.ceiling * smallest;
        }
        let factors: Vec<&Cholesky> = self.neumann.iter().chain(&self.dirichlet).collect();
        let mut u = vec![0.0; self.vertex_count];
        for factor in &factors {
            let mut x = delta.clone();
            factor.solve_in_place(&mut x)?;
            for (a, b) in u.iter_mut().zip(&x) {
                *a += b / factors.len() as f64;
            }
        }
        Ok(u)
    }

    /// Steps 2 and 3: the integrated divergence b_i = sum_f A_f grad(phi_i) . X_f
    /// of the unit field X (`direction(f, face)`, none where unresolved),
    /// zero at pinned vertices. O(F).
    fn divergence(&self, direction: impl Fn(usize, &FaceGradient) -> Option<DVec2>) -> Vec<f64> {
        let mut b = vec![0.0; self.vertex_count];
        for (f, face) in self.faces.iter().enumerate() {
            let (Some(w), Some(x)) = (face.w, direction(f, face)) else { continue };
            for k in 0..3 {
                b[face.vertices[k] as usize] += w[k].dot(x);
            }
        }
        for &v in &self.pinned {
            b[v as usize] = 0.0;
        }
        b
    }

    /// Shifts each component so that its nearest source sits at 0; other
    /// components get `+infinity`.
    fn shift_to_sources(&self, mut phi: Vec<f64>, sources: &[VertexId]) -> Vec<f64> {
        let mut shift = vec![f64::INFINITY; self.component_count];
        for s in sources {
            if let Some(c) = self.component.get(s.idx()).filter(|c| **c != u32::MAX) {
                shift[*c as usize] = shift[*c as usize].min(phi[s.idx()]);
            }
        }
        for (v, value) in phi.iter_mut().enumerate() {
            let c = self.component[v];
            *value = match shift.get(c as usize) {
                Some(s) if s.is_finite() && value.is_finite() => (*value - s).max(0.0),
                _ => f64::INFINITY,
            };
        }
        for s in sources {
            phi[s.idx()] = 0.0; // isolated sources too
        }
        phi
    }
}

/// One-off heat-method distance from `sources` (see [`HeatGeodesics`]).
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{heat_distance, HeatOptions};
///
/// let disk = shapes::disk(12, 3)?;
/// let d = heat_distance(&disk, &[VertexId(0)], &HeatOptions::default())?;
/// for (p, d) in disk.positions().iter().zip(&d) {
///     assert!((d - p.length()).abs() < 0.05);
/// }
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// The errors of [`HeatGeodesics::new`] and [`HeatGeodesics::solve`].
pub fn heat_distance(mesh: &TriMesh, sources: &[VertexId], options: &HeatOptions) -> Result<Vec<f64>> {
    validate_sources(mesh, sources)?;
    HeatGeodesics::new(mesh, options)?.distance(sources)
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn heat_values_fill_the_exponent_range() {
        // The 1500 x 2 strip (1341 mean edge lengths): from just below
        // 2^1000 at the source, resolved all the way to the far end.
        let mesh = shapes::grid(1500.0, 2.0, 1500, 2).unwrap();
        let heat = HeatGeodesics::new(&mesh, &HeatOptions::default()).unwrap();
        let u = heat.heat_flow(&[VertexId(0)]).unwrap();
        let top = u.iter().copied().fold(0.0, f64::max);
        assert!(top <= 2f64.powi(1000) && top > 2f64.powi(990), "{top:e}");
        let bottom = u.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(bottom >= far::RESOLVED, "{bottom:e}");
        // The decay: about 0.42 decimal orders per mean edge length.
        let h = mesh_kernel::geometry::mean_edge_length(&mesh);
        let per_h = (top.log10() - u[1500].log10()) / (1500.0 / h);
        assert!((0.38..0.46).contains(&per_h), "{per_h}");
    }

    #[test]
    fn the_mesh_unit_does_not_matter() {
        // With a unit source, a mesh in units of 1e60 started the heat flow
        // near 1e-120 and lost it within a hundred edge lengths.
        let mesh = shapes::grid(1500.0, 2.0, 1500, 2).unwrap();
        for scale in [1e-60, 1.0, 1e60] {
            let p: Vec<_> = mesh.positions().iter().map(|p| *p * scale).collect();
            let scaled = TriMesh::new(p, mesh.faces().to_vec()).unwrap();
            let d = heat_distance(&scaled, &[VertexId(0)], &HeatOptions::default()).unwrap();
            for (x, p) in d.iter().zip(mesh.positions()) {
                assert!((x / scale - p.length()).abs() < 0.5, "{scale}: {} vs {}", x / scale, p.length());
            }
        }
    }
}
