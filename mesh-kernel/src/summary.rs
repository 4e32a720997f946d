//! A summary of a mesh: counts, topology, manifoldness, defects and extent,
//! as the `mesh info` command prints them. One composition of this crate's
//! queries, shared by every front end (the `mesh` command, the Python
//! package).

use crate::{clean, geometry, TriMesh};

/// The measures of a mesh that `mesh info` prints and `meshkit.info`
/// returns: counts, topology (eq. 2.6-2.7), manifoldness, defects, area,
/// volume and extent. `genus` is `None` when the mesh is not an oriented
/// manifold.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[non_exhaustive]
pub struct MeshSummary {
    /// Number of vertices (referenced or not).
    pub vertices: usize,
    /// Number of triangles.
    pub faces: usize,
    /// Number of undirected edges.
    pub edges: usize,
    /// chi = V - E + F over referenced vertices (eq. 2.6).
    pub euler_characteristic: i64,
    /// Genus from chi = 2(c - g) - b (eq. 2.7).
    pub genus: Option<u64>,
    /// Connected components.
    pub components: usize,
    /// Boundary loops (`null` when not manifold).
    pub boundary_loops: Option<usize>,
    /// Oriented 2-manifold (possibly with boundary).
    pub manifold: bool,
    /// Edges with more than two faces.
    pub non_manifold_edges: usize,
    /// Vertices with more than one fan of faces.
    pub non_manifold_vertices: usize,
    /// Edges whose two faces disagree on orientation.
    pub inconsistent_edges: usize,
    /// Zero-area faces.
    pub degenerate_faces: usize,
    /// Faces repeating the vertices of another.
    pub duplicate_faces: usize,
    /// Vertices no face uses.
    pub unreferenced_vertices: usize,
    /// Vertices at exactly the position of a lower-numbered vertex, which
    /// exact welding would merge (a surface cut along coincident vertices).
    pub coincident_vertices: usize,
    /// Total surface area (`null` when it lies outside the range of double
    /// precision, see `out_of_range`).
    pub area: Option<f64>,
    /// Signed enclosed volume of a closed mesh (`null` when open, or outside
    /// the range of double precision).
    pub volume: Option<f64>,
    /// Quantities whose value has no double-precision representation (a
    /// mesh in units of 1e-300 has areas of 1e-600), with their order of
    /// magnitude: never printed as 0 or infinity.
    pub out_of_range: Vec<String>,
    /// Mean edge length.
    pub mean_edge_length: f64,
    /// Bounding box minimum corner.
    pub bbox_min: Option<[f64; 3]>,
    /// Bounding box maximum corner.
    pub bbox_max: Option<[f64; 3]>,
}

impl MeshSummary {
    /// Measures a mesh: O(V + F) for the counts, O(V log V) for the
    /// coincident vertices. Area and volume are measured in the mesh's
    /// power-of-two unit ([`crate::units`]) and carried back, or listed in
    /// `out_of_range`.
    pub fn of(mesh: &TriMesh) -> Self {
        let c = mesh.connectivity();
        let report = c.non_manifold_report();
        let bbox = geometry::bounding_box(mesh);
        let closed = c.boundary_loop_count() == Some(0);
        // Area and volume measured on the mesh in its power-of-two unit,
        // then carried back (or reported as out of range).
        let (normalized, unit) = crate::units::normalized(mesh);
        let mut out_of_range = Vec::new();
        let mut carry = |name: &str, inner: f64, degree: i32| match rescaled(inner, unit, degree) {
            Ok(v) => Some(v),
            Err(magnitude) => {
                out_of_range.push(format!("{name} {magnitude}"));
                None
            }
        };
        let area = carry("area", geometry::surface_area(&normalized), 2);
        let volume = if closed { carry("volume", geometry::enclosed_volume(&normalized), 3) } else { None };
        Self {
            vertices: mesh.vertex_count(),
            faces: mesh.face_count(),
            edges: c.edge_count(),
            euler_characteristic: c.euler_characteristic(),
            genus: c.genus(),
            components: c.components().count,
            boundary_loops: c.boundary_loop_count(),
            manifold: c.is_manifold(),
            non_manifold_edges: report.edges.len(),
            non_manifold_vertices: report.vertices.len(),
            inconsistent_edges: report.inconsistent_edges.len(),
            degenerate_faces: clean::degenerate_faces(mesh, clean::CleanOptions::default().degenerate_tolerance).len(),
            duplicate_faces: clean::duplicate_faces(mesh.faces()).len(),
            unreferenced_vertices: clean::unreferenced_vertices(mesh.vertex_count(), mesh.faces()).len(),
            coincident_vertices: clean::weld_vertices(mesh.positions(), &[], 0.0).map_or(0, |(_, _, merged)| merged),
            area,
            volume,
            out_of_range,
            mean_edge_length: geometry::mean_edge_length(mesh),
            bbox_min: bbox.map(|b| b.min.to_array()),
            bbox_max: bbox.map(|b| b.max.to_array()),
        }
    }
}

/// A quantity of degree `degree` in lengths, measured as `inner` on the mesh
/// divided by `unit`: its value on the mesh, or its order of magnitude when
/// that value has no double-precision representation.
fn rescaled(inner: f64, unit: f64, degree: i32) -> Result<f64, String> {
    let value = (0..degree).fold(inner, |v, _| v * unit);
    if inner != 0.0 && inner.is_finite() && !(value.is_finite() && value.abs() >= f64::MIN_POSITIVE) {
        let exponent = (inner.abs().log10() + f64::from(degree) * unit.log10()).floor();
        Err(format!("about {}1e{exponent}", if inner < 0.0 { "-" } else { "" }))
    } else {
        Ok(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes;

    #[test]
    fn sphere_counts_and_measures() {
        let s = MeshSummary::of(&shapes::icosphere(3).unwrap());
        assert_eq!((s.vertices, s.faces, s.edges), (642, 1280, 1920));
        assert_eq!((s.euler_characteristic, s.genus, s.components, s.boundary_loops), (2, Some(0), 1, Some(0)));
        assert!(s.manifold && s.out_of_range.is_empty());
        // Inscribed polyhedron: area and volume just below the sphere's.
        let (area, volume) = (s.area.unwrap(), s.volume.unwrap());
        assert!(area < 4.0 * std::f64::consts::PI && area > 0.99 * 4.0 * std::f64::consts::PI);
        assert!(volume < 4.0 / 3.0 * std::f64::consts::PI && volume > 0.98 * 4.0 / 3.0 * std::f64::consts::PI);
    }

    #[test]
    fn measures_beyond_double_precision_are_named_not_zero() {
        let sphere = shapes::icosphere(1).unwrap();
        let tiny =
            TriMesh::new(sphere.positions().iter().map(|p| *p * 1e-300).collect(), sphere.faces().to_vec()).unwrap();
        let s = MeshSummary::of(&tiny);
        assert_eq!((s.area, s.volume), (None, None));
        assert_eq!(s.out_of_range.len(), 2, "{:?}", s.out_of_range);
        assert!(s.out_of_range[0].starts_with("area about 1e-599"), "{:?}", s.out_of_range);
    }
}
