//! Derived quantities of a mesh, computed once on first use and kept with
//! it (in the spirit of geometry-central's `require*` quantities): every
//! crate that asks [`TriMesh::geometry`] for the bounding box, face areas,
//! angles, normals, lumped masses, cotangents, Laplacians, gradient or
//! divergence gets the same values, computed once. Moving vertices
//! ([`TriMesh::positions_mut`], [`TriMesh::set_positions`]) empties the
//! cache; [`TriMesh::forget_geometry`] frees it. A quantity is computed
//! outside its cell ([`crate::par::init_once`]), so a mesh shared by
//! parallel tasks never waits for itself.
//!
//! ```
//! use mesh_kernel::{operators::MassKind, shapes};
//!
//! let mesh = shapes::icosphere(3)?;
//! let g = mesh.geometry();
//! let area: f64 = g.face_areas().iter().sum();
//! let mass: f64 = g.lumped_mass(MassKind::MixedVoronoi).iter().sum();
//! assert!((area - mass).abs() < 1e-12 * area);
//! // The second request is the same memory, not a second computation.
//! assert!(std::ptr::eq(g.cotan_laplacian(), mesh.geometry().cotan_laplacian()));
//! # Ok::<(), mesh_kernel::MeshError>(())
//! ```

use std::sync::OnceLock;

use glam::DVec3;
use sprs::CsMat;

use crate::error::Result;
use crate::geometry::{self, Aabb, NormalWeighting};
use crate::mesh::TriMesh;
use crate::operators::{self, IntrinsicOptions, IntrinsicTriangulation, LaplacianKind, MassKind};
use crate::par::init_once;

/// The stored quantities; empty until asked for.
#[derive(Clone, Default)]
pub(crate) struct Cache {
    bounding_box: OnceLock<Option<Aabb>>,
    face_areas: OnceLock<Vec<f64>>,
    face_normals: OnceLock<Vec<DVec3>>,
    corner_angles: OnceLock<Vec<[f64; 3]>>,
    vertex_normals: [OnceLock<Vec<DVec3>>; NormalWeighting::ALL.len()],
    lumped_mass: [OnceLock<Vec<f64>>; MassKind::ALL.len()],
    halfedge_cotans: OnceLock<Vec<f64>>,
    cotan_laplacian: OnceLock<CsMat<f64>>,
    intrinsic: OnceLock<Result<IntrinsicTriangulation>>,
    intrinsic_laplacian: OnceLock<CsMat<f64>>,
    gradient: OnceLock<CsMat<f64>>,
    divergence: OnceLock<CsMat<f64>>,
}

/// The derived quantities of one mesh ([`TriMesh::geometry`]). Each method
/// computes its quantity on the first call (the cost is that of the free
/// function it names) and returns the stored one afterwards, in O(1).
#[derive(Clone, Copy)]
pub struct Geometry<'a> {
    mesh: &'a TriMesh,
    cache: &'a Cache,
}

impl<'a> Geometry<'a> {
    pub(crate) fn new(mesh: &'a TriMesh, cache: &'a Cache) -> Self {
        Self { mesh, cache }
    }

    /// The box of all vertices, `None` without vertices
    /// ([`geometry::bounding_box`]). Every operation that works in the
    /// mesh's [`crate::units::length_unit`] (normals, curvatures, geodesics,
    /// parameterizations) asks for it: at 470,274 vertices it took 1.2 ms on
    /// one thread each time, a tenth of the area-weighted normals
    /// (2026-12-06).
    pub fn bounding_box(&self) -> Option<Aabb> {
        *init_once(&self.cache.bounding_box, || geometry::bounding_box(self.mesh))
    }

    /// Area of every face ([`geometry::face_areas`]).
    pub fn face_areas(&self) -> &'a [f64] {
        init_once(&self.cache.face_areas, || geometry::face_areas(self.mesh)).as_slice()
    }

    /// Unit normal of every face, zero on zero-area faces ([`geometry::face_normals`]).
    pub fn face_normals(&self) -> &'a [DVec3] {
        init_once(&self.cache.face_normals, || geometry::face_normals(self.mesh)).as_slice()
    }

    /// The three corner angles of every face, summing to pi ([`geometry::corner_angles`]).
    pub fn corner_angles(&self) -> &'a [[f64; 3]] {
        init_once(&self.cache.corner_angles, || geometry::corner_angles(self.mesh)).as_slice()
    }

    /// Unit vertex normals with the given weighting ([`geometry::vertex_normals`]).
    pub fn vertex_normals(&self, weighting: NormalWeighting) -> &'a [DVec3] {
        init_once(&self.cache.vertex_normals[weighting as usize], || geometry::vertex_normals(self.mesh, weighting))
            .as_slice()
    }

    /// Lumped vertex areas of the given kind ([`operators::lumped_mass`]).
    pub fn lumped_mass(&self, kind: MassKind) -> &'a [f64] {
        init_once(&self.cache.lumped_mass[kind as usize], || operators::lumped_mass(self.mesh, kind)).as_slice()
    }

    /// The cotangent opposite every half-edge `3 f + k` ([`operators::halfedge_cotans`]).
    pub fn halfedge_cotans(&self) -> &'a [f64] {
        init_once(&self.cache.halfedge_cotans, || operators::halfedge_cotans(self.mesh)).as_slice()
    }

    /// The mesh's cotangent Laplacian ([`operators::cotan_laplacian`]).
    pub fn cotan_laplacian(&self) -> &'a CsMat<f64> {
        init_once(&self.cache.cotan_laplacian, || operators::cotan_laplacian(self.mesh))
    }

    /// The intrinsic Delaunay triangulation with [`IntrinsicOptions::default`]
    /// ([`IntrinsicTriangulation::delaunay`]).
    ///
    /// # Errors
    /// Those of [`IntrinsicTriangulation::delaunay`] (kept: asking again gives the same error).
    pub fn intrinsic_delaunay(&self) -> Result<&'a IntrinsicTriangulation> {
        let stored = init_once(&self.cache.intrinsic, || {
            IntrinsicTriangulation::delaunay(self.mesh, &IntrinsicOptions::default())
        });
        stored.as_ref().map_err(Clone::clone)
    }

    /// The Laplacian of the given kind: the cotangent one, or that of the
    /// intrinsic Delaunay triangulation; [`LaplacianKind::Auto`] is resolved
    /// by [`LaplacianKind::resolve`] (O(F) each time).
    ///
    /// # Errors
    /// Those of [`Geometry::intrinsic_delaunay`].
    pub fn laplacian(&self, kind: LaplacianKind) -> Result<&'a CsMat<f64>> {
        match kind.resolve_if_auto(self.mesh) {
            LaplacianKind::Cotan => Ok(self.cotan_laplacian()),
            _ => {
                let t = self.intrinsic_delaunay()?;
                Ok(init_once(&self.cache.intrinsic_laplacian, || t.cotan_laplacian()))
            }
        }
    }

    /// The face-wise gradient of piecewise-linear functions ([`operators::gradient()`]).
    pub fn gradient(&self) -> &'a CsMat<f64> {
        init_once(&self.cache.gradient, || operators::gradient(self.mesh))
    }

    /// The integrated divergence of face-wise vector fields ([`operators::divergence`]).
    pub fn divergence(&self) -> &'a CsMat<f64> {
        init_once(&self.cache.divergence, || operators::divergence(self.mesh))
    }
}

#[cfg(test)]
mod tests {
    use crate::operators::{self, LaplacianKind, MassKind};
    use crate::shapes;

    #[test]
    fn per_choice_slots_follow_the_declaration_order() {
        for (i, w) in crate::geometry::NormalWeighting::ALL.into_iter().enumerate() {
            assert_eq!(w as usize, i, "{w}");
        }
        for (i, k) in MassKind::ALL.into_iter().enumerate() {
            assert_eq!(k as usize, i, "{k}");
        }
    }

    #[test]
    fn cached_quantities_equal_the_free_functions_and_are_dropped_when_vertices_move() {
        let mut m = shapes::irregular_torus(2.0, 0.7, 20, 12, 0.3, 3).unwrap();
        let g = m.geometry();
        assert_eq!(g.lumped_mass(MassKind::Barycentric), &operators::lumped_mass(&m, MassKind::Barycentric)[..]);
        assert_eq!(g.laplacian(LaplacianKind::Cotan).unwrap(), &operators::cotan_laplacian(&m));
        assert_eq!(g.bounding_box(), crate::geometry::bounding_box(&m));
        let (first, first_box) = (g.face_areas().to_vec(), g.bounding_box().unwrap());
        m.positions_mut().iter_mut().for_each(|p| *p *= 2.0);
        let again = m.geometry().face_areas().to_vec();
        let again_box = m.geometry().bounding_box().unwrap();
        assert_eq!((2.0 * first_box.min, 2.0 * first_box.max), (again_box.min, again_box.max));
        for (a, b) in first.iter().zip(&again) {
            assert!((4.0 * a - b).abs() <= 1e-12 * b);
        }
        let copy = m.clone();
        assert_eq!(copy.geometry().face_areas(), m.geometry().face_areas());
    }

    /// Tasks on eight threads asking one cold mesh for its connectivity and
    /// normals (each after parallel work of its own, the pattern that hung
    /// `OnceLock::get_or_init`) all get the one stored value, equal to a
    /// computation on one thread.
    #[cfg(feature = "rayon")]
    #[test]
    fn parallel_first_requests_share_one_stored_value() {
        use crate::geometry::NormalWeighting;
        use rayon::prelude::*;
        let pool = rayon::ThreadPoolBuilder::new().num_threads(8).build().unwrap();
        let sphere = shapes::icosphere(5).unwrap();
        let expected = crate::geometry::vertex_normals(&sphere, NormalWeighting::Area);
        for _ in 0..4 {
            let mesh = crate::TriMesh::new(sphere.positions().to_vec(), sphere.faces().to_vec()).unwrap();
            let seen: Vec<(usize, usize)> = pool.install(|| {
                (0..64u32)
                    .into_par_iter()
                    .map(|i| {
                        let busy: u64 = (0..20_000u32).into_par_iter().map(|x| u64::from(x ^ i)).sum();
                        std::hint::black_box(busy);
                        let conn = mesh.connectivity() as *const _ as usize;
                        (conn, mesh.geometry().vertex_normals(NormalWeighting::Area).as_ptr() as usize)
                    })
                    .collect()
            });
            let stored =
                (mesh.connectivity() as *const _ as usize, mesh.geometry().vertex_normals(NormalWeighting::Area));
            assert!(seen.iter().all(|&(c, n)| c == stored.0 && n == stored.1.as_ptr() as usize));
            assert_eq!(stored.1, &expected[..]);
        }
    }
}
