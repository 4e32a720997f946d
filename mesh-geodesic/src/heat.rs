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

use mesh_core::glam::DVec2;
use mesh_core::operators::{self, IntrinsicOptions, IntrinsicTriangulation, MassKind};
use mesh_core::solver::Cholesky;
use mesh_core::sprs::CsMat;
use mesh_core::{clean, TriMesh, VertexId, VertexKind};

use crate::error::{GeodesicError, Result};
use crate::support::validate_sources;

/// Which Laplacian (and triangulation) the heat method works on.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum HeatLaplacian {
    /// The cotangent Laplacian of the mesh itself (the paper's choice).
    /// Zero-area triangles contribute nothing; if that disconnects part of
    /// the mesh, construction fails with [`GeodesicError::Degenerate`].
    Cotan,
    /// The cotangent Laplacian of the mollified intrinsic Delaunay
    /// triangulation (Sharp and Crane 2020): non-negative weights, finite on
    /// zero-area triangles, identical to [`HeatLaplacian::Cotan`] on
    /// Delaunay meshes.
    #[default]
    IntrinsicDelaunay,
}

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

/// Options of [`HeatGeodesics`] and [`heat_distance`].
#[derive(Debug, Clone, PartialEq)]
pub struct HeatOptions {
    /// The factor m of the time step t = m h^2, h the mean edge length.
    /// Default 1 (the paper's choice).
    pub time_factor: f64,
    /// The Laplacian. Default [`HeatLaplacian::IntrinsicDelaunay`].
    pub laplacian: HeatLaplacian,
    /// The boundary condition of the heat flow. Default [`HeatBoundary::Mean`].
    pub boundary: HeatBoundary,
    /// Options of the intrinsic Delaunay triangulation.
    pub intrinsic: IntrinsicOptions,
}

impl Default for HeatOptions {
    fn default() -> Self {
        Self {
            time_factor: 1.0,
            laplacian: HeatLaplacian::default(),
            boundary: HeatBoundary::default(),
            intrinsic: IntrinsicOptions::default(),
        }
    }
}

/// Below this relative area a triangle carries no gradient.
const DEGENERATE: f64 = mesh_core::operators::laplacian::DEGENERATE_TOLERANCE;

/// One triangle laid out in the plane: its vertices and the area-weighted
/// gradients of its hat functions, `w_k = A grad(phi_k)` (half the edge
/// opposite corner k turned by 90 degrees), or `None` when it has no area.
#[derive(Debug, Clone, Copy)]
struct FaceGradient {
    vertices: [u32; 3],
    w: Option<[DVec2; 3]>,
}

impl FaceGradient {
    /// Lays out the triangle with side lengths `l[k]` (from corner k to k+1).
    fn new(vertices: [u32; 3], l: [f64; 3]) -> Self {
        let area = operators::intrinsic::heron_area(l[0], l[1], l[2]);
        let longest = l[0].max(l[1]).max(l[2]);
        if !(l[0] > 0.0 && area > 0.5 * DEGENERATE * longest * longest) {
            return Self { vertices, w: None };
        }
        // Corner 0 at the origin, corner 1 on +x, corner 2 above.
        let x2 = (l[0] * l[0] + l[2] * l[2] - l[1] * l[1]) / (2.0 * l[0]);
        let p = [DVec2::ZERO, DVec2::new(l[0], 0.0), DVec2::new(x2, 2.0 * area / l[0])];
        let w = [0, 1, 2].map(|k| 0.5 * (p[(k + 2) % 3] - p[(k + 1) % 3]).perp());
        Self { vertices, w: Some(w) }
    }

    /// The unit vector -grad u / |grad u| (zero where grad u vanishes).
    #[inline]
    fn descent(&self, u: &[f64]) -> Option<DVec2> {
        let w = self.w?;
        let g: DVec2 = (0..3).map(|k| u[self.vertices[k] as usize] * w[k]).sum();
        let len = g.length();
        (len > 0.0 && len.is_finite()).then(|| -g / len)
    }
}

/// The prefactored heat method (Crane, Weischedel and Wardetzky 2013).
/// [`HeatGeodesics::new`] assembles and factors once: cost one symbolic
/// analysis and two numeric sparse Cholesky factorizations (three on meshes
/// with boundary and [`HeatBoundary::Mean`]), plus the intrinsic Delaunay
/// flips when chosen. [`HeatGeodesics::distance`] then answers any source
/// set with two (three) pairs of triangular solves and O(F) work.
///
/// ```
/// use mesh_core::{shapes, VertexId};
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
    /// One pinned vertex per connected piece of the Laplacian.
    pinned: Vec<u32>,
    /// Connected component of each vertex (`u32::MAX` when isolated).
    component: Vec<u32>,
    component_count: usize,
}

impl HeatGeodesics {
    /// Assembles and factors the heat and Poisson systems (see
    /// [`HeatGeodesics`]). Errors: an empty mesh, a non-positive time factor,
    /// a cotangent Laplacian disconnected by zero-area triangles, or a
    /// factorization failure.
    pub fn new(mesh: &TriMesh, options: &HeatOptions) -> Result<Self> {
        if !(options.time_factor.is_finite() && options.time_factor > 0.0) {
            return Err(GeodesicError::InvalidOption {
                name: "time_factor",
                reason: format!("{} is not a finite positive number", options.time_factor),
            });
        }
        if mesh.face_count() == 0 {
            return Err(mesh_core::MeshError::Empty.into());
        }
        let n = mesh.vertex_count();
        let extrinsic = || {
            let faces = extrinsic_faces(mesh);
            (faces, operators::cotan_laplacian(mesh), operators::lumped_mass(mesh, MassKind::Barycentric))
        };
        let (faces, laplacian, mass) = match options.laplacian {
            HeatLaplacian::Cotan => extrinsic(),
            HeatLaplacian::IntrinsicDelaunay => {
                let t = IntrinsicTriangulation::delaunay(mesh, &options.intrinsic)?;
                if t.flip_count() == 0 && unchanged_lengths(mesh, t.lengths()) {
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
                 use HeatLaplacian::IntrinsicDelaunay"
            )));
        }
        let mean_edge = mesh_core::geometry::mean_edge_length(mesh);
        let time = options.time_factor * mean_edge * mean_edge;
        if !(time > 0.0 && time.is_finite()) {
            return Err(GeodesicError::Degenerate("all edges have zero length".into()));
        }

        // Every matrix shares the pattern of L, so one symbolic analysis
        // serves all factorizations; removed rows keep explicit zeros.
        let isolated: Vec<bool> = (0..n).map(|v| conn.vertex_kind(VertexId::new(v)) == VertexKind::Isolated).collect();
        let heat_matrix = shifted(&laplacian, time, &mass, &isolated);
        let heat = Cholesky::new(&heat_matrix)?;
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
            time,
            faces,
            neumann,
            dirichlet,
            poisson,
            pinned,
            component: components.vertex_component.clone(),
            component_count: components.count,
        })
    }

    /// The time step t = m h^2 in use.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of vertices of the mesh this was built for.
    pub fn vertex_count(&self) -> usize {
        self.vertex_count
    }

    /// Approximate geodesic distance from the nearest of `sources` to every
    /// vertex; `+infinity` on components without a source (and on isolated
    /// vertices that are not sources). Sources are at 0; values are clamped
    /// at 0 from below. Cost: two (three with a boundary) pairs of sparse
    /// triangular solves and O(F).
    pub fn distance(&self, sources: &[VertexId]) -> Result<Vec<f64>> {
        let n = self.vertex_count;
        if sources.is_empty() {
            return Err(GeodesicError::NoSources);
        }
        if let Some(&vertex) = sources.iter().find(|s| s.idx() >= n) {
            return Err(GeodesicError::SourceOutOfRange { vertex, vertex_count: n });
        }
        let u = self.heat_flow(sources)?;
        let mut phi = self.divergence_of_descent(&u);
        self.poisson.solve_in_place(&mut phi)?;
        Ok(self.shift_to_sources(phi, sources))
    }

    /// Step 1: the backward Euler heat flow (M + t L) u = delta from the
    /// sources, averaged over the boundary conditions in use. In the
    /// Dirichlet system a source on the boundary is a boundary value of 1.
    fn heat_flow(&self, sources: &[VertexId]) -> Result<Vec<f64>> {
        let mut delta = vec![0.0; self.vertex_count];
        for s in sources {
            delta[s.idx()] = 1.0;
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
    /// of the normalized descent field, zero at pinned vertices.
    fn divergence_of_descent(&self, u: &[f64]) -> Vec<f64> {
        let mut b = vec![0.0; self.vertex_count];
        for face in &self.faces {
            let (Some(w), Some(x)) = (face.w, face.descent(u)) else { continue };
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
/// use mesh_core::{shapes, VertexId};
/// use mesh_geodesic::{heat_distance, HeatOptions};
///
/// let disk = shapes::disk(12, 3)?;
/// let d = heat_distance(&disk, &[VertexId(0)], &HeatOptions::default())?;
/// for (p, d) in disk.positions().iter().zip(&d) {
///     assert!((d - p.length()).abs() < 0.05);
/// }
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
pub fn heat_distance(mesh: &TriMesh, sources: &[VertexId], options: &HeatOptions) -> Result<Vec<f64>> {
    validate_sources(mesh, sources)?;
    HeatGeodesics::new(mesh, options)?.distance(sources)
}

/// The mesh's own triangles laid out from their 3D edge lengths; triangles
/// that [`mesh_core::clean::is_degenerate_triangle`] flags carry no gradient,
/// as they carry no cotangent weight.
fn extrinsic_faces(mesh: &TriMesh) -> Vec<FaceGradient> {
    mesh.face_ids()
        .map(|f| {
            let tri = mesh.triangle(f);
            let vertices = mesh.faces()[f.idx()];
            if clean::is_degenerate_triangle(tri, DEGENERATE) {
                return FaceGradient { vertices, w: None };
            }
            FaceGradient::new(vertices, [0, 1, 2].map(|k| tri[k].distance(tri[(k + 1) % 3])))
        })
        .collect()
}

/// `true` when the intrinsic half-edge lengths are the mesh's own (no
/// mollification happened).
fn unchanged_lengths(mesh: &TriMesh, lengths: &[f64]) -> bool {
    let p = mesh.positions();
    mesh.faces()
        .iter()
        .zip(lengths.chunks_exact(3))
        .all(|(f, l)| (0..3).all(|k| p[f[k] as usize].distance(p[f[(k + 1) % 3] as usize]) == l[k]))
}

/// `diag(mass) + t L` with 1 on the diagonal of isolated vertices. Same
/// pattern as `L`, whose diagonal entries are all stored.
fn shifted(laplacian: &CsMat<f64>, t: f64, mass: &[f64], isolated: &[bool]) -> CsMat<f64> {
    let mut a = laplacian.clone();
    let indptr = a.indptr().to_proper().into_owned();
    let indices = a.indices().to_vec();
    let data = a.data_mut();
    for row in 0..mass.len() {
        for k in indptr[row]..indptr[row + 1] {
            let value = t * data[k];
            data[k] = if indices[k] == row {
                if isolated[row] {
                    1.0
                } else {
                    value + mass[row]
                }
            } else {
                value
            };
        }
    }
    a
}

/// `a` with the rows and columns of `mask` replaced by the identity, the
/// removed entries kept as explicit zeros (same pattern).
fn with_identity_rows(a: &CsMat<f64>, mask: &[bool]) -> CsMat<f64> {
    let mut out = a.clone();
    let indptr = out.indptr().to_proper().into_owned();
    let indices = out.indices().to_vec();
    let data = out.data_mut();
    for row in 0..mask.len() {
        for k in indptr[row]..indptr[row + 1] {
            let col = indices[k];
            if mask[row] || mask[col] {
                data[k] = if row == col { 1.0 } else { 0.0 };
            }
        }
    }
    out
}

/// Pins one vertex per connected piece of the triangles that carry a
/// gradient (the null space of the Laplacian is one constant per piece).
/// Returns the pinned vertices and the number of pieces.
fn pin_pieces(n: usize, faces: &[FaceGradient]) -> (Vec<u32>, usize) {
    let labels = piece_labels(n, faces);
    let mut seen = vec![false; n];
    let mut pinned = Vec::new();
    for v in 0..n {
        let root = labels[v];
        if root != u32::MAX && !seen[root as usize] {
            seen[root as usize] = true;
            pinned.push(v as u32);
        }
    }
    let pieces = pinned.len();
    (pinned, pieces)
}

/// Union-find root of each vertex over the faces with a gradient;
/// `u32::MAX` for vertices in none.
fn piece_labels(n: usize, faces: &[FaceGradient]) -> Vec<u32> {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let mut used = vec![false; n];
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let p = parent[parent[i as usize] as usize];
            parent[i as usize] = p;
            i = p;
        }
        i
    }
    for f in faces.iter().filter(|f| f.w.is_some()) {
        let [a, b, c] = f.vertices;
        for v in [a, b, c] {
            used[v as usize] = true;
        }
        for (x, y) in [(a, b), (a, c)] {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry) as usize] = rx.min(ry);
            }
        }
    }
    (0..n as u32).map(|v| if used[v as usize] { find(&mut parent, v) } else { u32::MAX }).collect()
}

/// A vertex whose Laplacian piece differs from its component's (for the
/// error message).
fn first_split_vertex(faces: &[FaceGradient], n: usize, component: &[u32]) -> VertexId {
    let labels = piece_labels(n, faces);
    let mut piece_of_component: Vec<u32> = vec![u32::MAX; n];
    for v in 0..n {
        let c = component[v];
        if c == u32::MAX {
            continue;
        }
        if labels[v] == u32::MAX {
            return VertexId::new(v);
        }
        let slot = &mut piece_of_component[c as usize];
        if *slot == u32::MAX {
            *slot = labels[v];
        } else if *slot != labels[v] {
            return VertexId::new(v);
        }
    }
    VertexId::INVALID
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_gradients_reproduce_linear_functions() {
        // A scalene triangle; u linear with gradient (2, -1) in the layout.
        let l = [3.0, 2.5, 2.0];
        let f = FaceGradient::new([0, 1, 2], l);
        let w = f.w.unwrap();
        let area = operators::intrinsic::heron_area(l[0], l[1], l[2]);
        let x2 = (l[0] * l[0] + l[2] * l[2] - l[1] * l[1]) / (2.0 * l[0]);
        let p = [DVec2::ZERO, DVec2::new(l[0], 0.0), DVec2::new(x2, 2.0 * area / l[0])];
        let g = DVec2::new(2.0, -1.0);
        let u: Vec<f64> = p.iter().map(|q| g.dot(*q) + 5.0).collect();
        let grad: DVec2 = (0..3).map(|k| u[k] * w[k]).sum::<DVec2>() / area;
        assert!((grad - g).length() < 1e-12);
        // Hat gradients sum to zero.
        assert!((w[0] + w[1] + w[2]).length() < 1e-12);
        assert_eq!(f.descent(&u).map(|d| (d + g.normalize()).length() < 1e-12), Some(true));
    }

    #[test]
    fn zero_area_faces_carry_no_gradient() {
        assert!(FaceGradient::new([0, 1, 2], [1.0, 1.0, 2.0]).w.is_none());
        assert!(FaceGradient::new([0, 1, 2], [0.0, 1.0, 1.0]).w.is_none());
    }
}
