//! What mesh files carry beyond positions and faces: [`MeshData`] (owned, as
//! read), [`MeshView`] (borrowed, for writing) and the [`ReadReport`] of what a
//! reader changed.

use glam::{DVec2, DVec3};
use mesh_kernel::{Reordering, Result as KernelResult, TriMesh};

use crate::attribute::{Attribute, AttributeElement, AttributeValues};
use crate::error::{IoError, Location, Result};

/// A mesh as read from a file, with the attributes the file carried.
///
/// Per-vertex attributes have one entry per vertex of [`MeshData::mesh`].
/// Texture coordinates are per vertex ([`MeshData::uvs`]) when every vertex
/// has a single one, and per face corner ([`MeshData::corner_uvs`]) when the
/// file has UV seams (a vertex with different coordinates in different
/// faces). Colours are linear RGBA in `[0, 1]`.
///
/// Named attributes ([`crate::attribute`]) come as lists of `(name, values)`
/// by element and kind: per vertex `scalars`, `vectors` and `labels`, per
/// face `face_scalars`, `face_vectors` and `face_labels`; a reader that
/// splits polygons into triangles gives each triangle its polygon's value.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshData {
    /// Positions and triangles.
    pub mesh: TriMesh,
    /// Per-vertex normals.
    pub normals: Option<Vec<DVec3>>,
    /// Per-vertex texture coordinates (OBJ/PLY convention: v points up).
    pub uvs: Option<Vec<DVec2>>,
    /// Per-face-corner texture coordinates, in the order of each face's vertices.
    pub corner_uvs: Option<Vec<[DVec2; 3]>>,
    /// Per-vertex RGBA colours in `[0, 1]`.
    pub colors: Option<Vec<[f32; 4]>>,
    /// Named per-vertex scalar fields (PLY `float`/`double` properties, glTF
    /// `_NAME` float `SCALAR` attributes).
    pub scalars: Vec<(String, Vec<f64>)>,
    /// Named per-vertex 3-vectors (PLY `NAMEx NAMEy NAMEz` or `NAME_x NAME_y
    /// NAME_z` float property triples, glTF `_NAME` `VEC3` attributes).
    pub vectors: Vec<(String, Vec<DVec3>)>,
    /// Named per-vertex integer labels (PLY integer properties, glTF `_NAME`
    /// integer `SCALAR` attributes).
    pub labels: Vec<(String, Vec<i64>)>,
    /// Named per-face scalar fields (PLY `face` element properties).
    pub face_scalars: Vec<(String, Vec<f64>)>,
    /// Named per-face 3-vectors (PLY `face` element property triples).
    pub face_vectors: Vec<(String, Vec<DVec3>)>,
    /// Named per-face integer labels (PLY `face` element integer properties).
    pub face_labels: Vec<(String, Vec<i64>)>,
    /// What the reader changed while building the mesh (empty when built in memory).
    pub report: ReadReport,
}

impl MeshData {
    /// Drops every normal, texture-coordinate or colour attribute holding
    /// a NaN or an infinity (a file's `nan`, `inf` or `1e309`), with a note
    /// in the read report naming the first bad element: positions are
    /// refused by the readers, attributes are optional, and no NaN leaves
    /// a reader unannounced. Named scalars and vectors are the file's own
    /// data (NaN may mean "no value" there): they are kept, with a note
    /// counting their non-finite values. O(V + F).
    pub fn without_non_finite_attributes(mut self) -> Self {
        let notes: Vec<String> = self.attributes().iter().filter_map(non_finite_note).collect();
        self.report.notes.extend(notes);
        let mut drop = |what: &str, first: Option<usize>| {
            if let Some(i) = first {
                self.report.notes.push(format!("{what} dropped: {what} of element {i} is not finite"));
                true
            } else {
                false
            }
        };
        if drop("normals", self.normals.as_ref().and_then(|n| n.iter().position(|x| !x.is_finite()))) {
            self.normals = None;
        }
        if drop("texture coordinates", self.uvs.as_ref().and_then(|u| u.iter().position(|x| !x.is_finite()))) {
            self.uvs = None;
        }
        let bad_corner = self.corner_uvs.as_ref().and_then(|u| u.iter().position(|t| t.iter().any(|x| !x.is_finite())));
        if drop("corner texture coordinates", bad_corner) {
            self.corner_uvs = None;
        }
        let bad_colour = self.colors.as_ref().and_then(|c| c.iter().position(|x| x.iter().any(|v| !v.is_finite())));
        if drop("colours", bad_colour) {
            self.colors = None;
        }
        self
    }

    /// A mesh with no attributes.
    pub fn new(mesh: TriMesh) -> Self {
        Self {
            mesh,
            normals: None,
            uvs: None,
            corner_uvs: None,
            colors: None,
            scalars: Vec::new(),
            vectors: Vec::new(),
            labels: Vec::new(),
            face_scalars: Vec::new(),
            face_vectors: Vec::new(),
            face_labels: Vec::new(),
            report: ReadReport::default(),
        }
    }

    /// The named per-vertex scalar field, if present. O(number of fields).
    pub fn scalar(&self, name: &str) -> Option<&[f64]> {
        find(&self.scalars, name)
    }

    /// The named per-vertex vector field, if present. O(number of fields).
    pub fn vector(&self, name: &str) -> Option<&[DVec3]> {
        find(&self.vectors, name)
    }

    /// The named per-vertex label, if present. O(number of fields).
    pub fn label(&self, name: &str) -> Option<&[i64]> {
        find(&self.labels, name)
    }

    /// The named per-face scalar field, if present. O(number of fields).
    pub fn face_scalar(&self, name: &str) -> Option<&[f64]> {
        find(&self.face_scalars, name)
    }

    /// The named per-face vector field, if present. O(number of fields).
    pub fn face_vector(&self, name: &str) -> Option<&[DVec3]> {
        find(&self.face_vectors, name)
    }

    /// The named per-face label, if present. O(number of fields).
    pub fn face_label(&self, name: &str) -> Option<&[i64]> {
        find(&self.face_labels, name)
    }

    /// Every named attribute (per-vertex scalars, vectors and labels, then
    /// per-face ones), with its element, kind and values. O(number of fields).
    pub fn attributes(&self) -> Vec<Attribute<'_>> {
        use AttributeElement::{Face, Vertex};
        use AttributeValues::{Label, Scalar, Vector};
        let mut out = Vec::new();
        out.extend(named(&self.scalars, Vertex, Scalar));
        out.extend(named(&self.vectors, Vertex, Vector));
        out.extend(named(&self.labels, Vertex, Label));
        out.extend(named(&self.face_scalars, Face, Scalar));
        out.extend(named(&self.face_vectors, Face, Vector));
        out.extend(named(&self.face_labels, Face, Label));
        out
    }

    /// The same data renumbered by `order` (see [`mesh_kernel::reorder`]):
    /// the mesh and every per-vertex, per-corner and per-face attribute
    /// follow, the read report is kept. Cost O(V + F) per attribute.
    ///
    /// # Errors
    /// [`mesh_kernel::MeshError::Dimension`] when `order` was made for a mesh
    /// of other vertex or face counts.
    pub fn reordered(&self, order: &Reordering) -> mesh_kernel::Result<Self> {
        fn opt<T: Clone>(v: &Option<Vec<T>>, f: impl Fn(&[T]) -> KernelResult<Vec<T>>) -> KernelResult<Option<Vec<T>>> {
            v.as_deref().map(f).transpose()
        }
        fn each<T: Clone>(
            fields: &[(String, Vec<T>)],
            f: impl Fn(&[T]) -> KernelResult<Vec<T>>,
        ) -> KernelResult<Vec<(String, Vec<T>)>> {
            fields.iter().map(|(n, v)| Ok((n.clone(), f(v)?))).collect()
        }
        Ok(Self {
            mesh: order.apply(&self.mesh)?,
            normals: opt(&self.normals, |v| order.vertex_values_from_input(v))?,
            uvs: opt(&self.uvs, |v| order.vertex_values_from_input(v))?,
            corner_uvs: opt(&self.corner_uvs, |v| order.face_values_from_input(v))?,
            colors: opt(&self.colors, |v| order.vertex_values_from_input(v))?,
            scalars: each(&self.scalars, |v| order.vertex_values_from_input(v))?,
            vectors: each(&self.vectors, |v| order.vertex_values_from_input(v))?,
            labels: each(&self.labels, |v| order.vertex_values_from_input(v))?,
            face_scalars: each(&self.face_scalars, |v| order.face_values_from_input(v))?,
            face_vectors: each(&self.face_vectors, |v| order.face_values_from_input(v))?,
            face_labels: each(&self.face_labels, |v| order.face_values_from_input(v))?,
            report: self.report.clone(),
        })
    }

    /// A borrowed view for the writers.
    pub fn view(&self) -> MeshView<'_> {
        MeshView {
            mesh: &self.mesh,
            normals: self.normals.as_deref(),
            uvs: self.uvs.as_deref(),
            corner_uvs: self.corner_uvs.as_deref(),
            colors: self.colors.as_deref(),
            attributes: self.attributes(),
        }
    }
}

/// The fields of one list as attributes.
fn named<'a, T>(
    fields: &'a [(String, Vec<T>)],
    element: AttributeElement,
    values: fn(&'a [T]) -> AttributeValues<'a>,
) -> impl Iterator<Item = Attribute<'a>> {
    fields.iter().map(move |(name, v)| Attribute { name, element, values: values(v) })
}

/// The values of the field named `name`.
fn find<'a, T>(fields: &'a [(String, Vec<T>)], name: &str) -> Option<&'a [T]> {
    fields.iter().find(|(n, _)| n == name).map(|(_, v)| v.as_slice())
}

/// A note for a scalar or vector attribute with NaN or infinite values:
/// how many, and the first element.
fn non_finite_note(a: &Attribute<'_>) -> Option<String> {
    let bad: Vec<usize> = match a.values {
        AttributeValues::Scalar(v) => v.iter().enumerate().filter(|(_, x)| !x.is_finite()).map(|(i, _)| i).collect(),
        AttributeValues::Vector(v) => v.iter().enumerate().filter(|(_, x)| !x.is_finite()).map(|(i, _)| i).collect(),
        AttributeValues::Label(_) => Vec::new(),
    };
    let first = *bad.first()?;
    Some(format!("{a}: {} values are not finite (first of {} {first}), kept as read", bad.len(), a.element))
}

impl From<TriMesh> for MeshData {
    fn from(mesh: TriMesh) -> Self {
        Self::new(mesh)
    }
}

/// What a reader changed to turn the file into a [`TriMesh`], and what it left out.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct ReadReport {
    /// Polygons with more than three corners, split into a fan of triangles.
    pub polygons_triangulated: usize,
    /// Faces dropped because they repeat a vertex (for example STL triangles
    /// that collapse when welded) or have fewer than three corners.
    pub faces_dropped: usize,
    /// Vertices merged into an identical one (STL welding).
    pub vertices_welded: usize,
    /// What the file held that was not read, one short sentence each.
    pub notes: Vec<String>,
}

impl std::fmt::Display for ReadReport {
    /// The changes in one line, e.g. `2 polygons triangulated, 1 face dropped`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let plural = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
        let mut parts = Vec::new();
        if self.polygons_triangulated > 0 {
            parts.push(format!("{} triangulated", plural(self.polygons_triangulated, "polygon")));
        }
        if self.faces_dropped > 0 {
            parts.push(format!("{} dropped", plural(self.faces_dropped, "face")));
        }
        if self.vertices_welded > 0 {
            parts.push(format!(
                "{} welded",
                if self.vertices_welded == 1 {
                    "1 vertex".into()
                } else {
                    format!("{} vertices", self.vertices_welded)
                }
            ));
        }
        parts.extend(self.notes.iter().cloned());
        if parts.is_empty() {
            f.write_str("nothing changed")
        } else {
            f.write_str(&parts.join("; "))
        }
    }
}

impl ReadReport {
    /// `true` when the mesh is exactly what the file says.
    pub fn is_clean(&self) -> bool {
        *self == Self::default()
    }

    /// Fan-triangulates one polygon `(0, i, i + 1)`, counting polygons and
    /// dropping (and counting) triangles that repeat a vertex. `emit` gets the
    /// corner numbers within the polygon and the triangle's vertex indices.
    #[inline]
    pub(crate) fn triangulate(&mut self, polygon: &[u32], mut emit: impl FnMut([usize; 3], [u32; 3])) {
        let n = polygon.len();
        if n < 3 {
            self.faces_dropped += 1;
            return;
        }
        if n > 3 {
            self.polygons_triangulated += 1;
        }
        for i in 1..n - 1 {
            let corners = [0, i, i + 1];
            let tri = corners.map(|k| polygon[k]);
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
                self.faces_dropped += 1;
            } else {
                emit(corners, tri);
            }
        }
    }

    /// Adds a note once.
    pub(crate) fn note(&mut self, note: impl Into<String>) {
        let note = note.into();
        if !self.notes.contains(&note) {
            self.notes.push(note);
        }
    }
}

/// A mesh and borrowed attributes, as the writers take them.
///
/// Built from a [`TriMesh`] (`MeshView::from(&mesh)`), from a [`MeshData`]
/// ([`MeshData::view`]) or step by step:
///
/// ```
/// # use mesh_io::MeshView;
/// # let mesh = mesh_kernel::TriMesh::new(vec![mesh_kernel::glam::DVec3::ZERO; 3], vec![])?;
/// let mean = vec![0.0; mesh.vertex_count()];
/// let d1 = vec![mesh_kernel::glam::DVec3::X; mesh.vertex_count()];
/// let chart = vec![0i64; mesh.face_count()];
/// let view = MeshView::new(&mesh).with_scalar("mean", &mean).with_vector("d1", &d1).with_face_label("chart", &chart);
/// assert_eq!(view.attributes.len(), 3);
/// assert_eq!(view.attributes[1].to_string(), "vertex vector `d1`");
/// # Ok::<(), mesh_kernel::MeshError>(())
/// ```
///
/// Each writer keeps what its format can hold (see the crate's format table)
/// and names the rest in [`crate::WriteReport::dropped`].
#[derive(Debug, Clone)]
pub struct MeshView<'a> {
    /// Positions and triangles.
    pub mesh: &'a TriMesh,
    /// Per-vertex normals.
    pub normals: Option<&'a [DVec3]>,
    /// Per-vertex texture coordinates.
    pub uvs: Option<&'a [DVec2]>,
    /// Per-face-corner texture coordinates (take precedence over `uvs`).
    pub corner_uvs: Option<&'a [[DVec2; 3]]>,
    /// Per-vertex RGBA colours in `[0, 1]`.
    pub colors: Option<&'a [[f32; 4]]>,
    /// Named per-vertex and per-face attributes, in the order they are
    /// written (PLY property order).
    pub attributes: Vec<Attribute<'a>>,
}

impl<'a> MeshView<'a> {
    /// A view of the mesh alone.
    pub fn new(mesh: &'a TriMesh) -> Self {
        Self { mesh, normals: None, uvs: None, corner_uvs: None, colors: None, attributes: Vec::new() }
    }

    /// Adds per-vertex normals.
    pub fn with_normals(mut self, normals: &'a [DVec3]) -> Self {
        self.normals = Some(normals);
        self
    }

    /// Adds per-vertex texture coordinates.
    pub fn with_uvs(mut self, uvs: &'a [DVec2]) -> Self {
        self.uvs = Some(uvs);
        self
    }

    /// Adds per-face-corner texture coordinates.
    pub fn with_corner_uvs(mut self, corner_uvs: &'a [[DVec2; 3]]) -> Self {
        self.corner_uvs = Some(corner_uvs);
        self
    }

    /// Adds per-vertex RGBA colours.
    pub fn with_colors(mut self, colors: &'a [[f32; 4]]) -> Self {
        self.colors = Some(colors);
        self
    }

    /// Adds a named attribute.
    pub fn with_attribute(mut self, name: &'a str, element: AttributeElement, values: AttributeValues<'a>) -> Self {
        self.attributes.push(Attribute { name, element, values });
        self
    }

    /// Adds a named per-vertex scalar field.
    pub fn with_scalar(self, name: &'a str, values: &'a [f64]) -> Self {
        self.with_attribute(name, AttributeElement::Vertex, AttributeValues::Scalar(values))
    }

    /// Adds a named per-vertex vector field (PLY `NAMEx NAMEy NAMEz`).
    pub fn with_vector(self, name: &'a str, values: &'a [DVec3]) -> Self {
        self.with_attribute(name, AttributeElement::Vertex, AttributeValues::Vector(values))
    }

    /// Adds a named per-vertex integer label.
    pub fn with_label(self, name: &'a str, values: &'a [i64]) -> Self {
        self.with_attribute(name, AttributeElement::Vertex, AttributeValues::Label(values))
    }

    /// Adds a named per-face scalar field.
    pub fn with_face_scalar(self, name: &'a str, values: &'a [f64]) -> Self {
        self.with_attribute(name, AttributeElement::Face, AttributeValues::Scalar(values))
    }

    /// Adds a named per-face vector field.
    pub fn with_face_vector(self, name: &'a str, values: &'a [DVec3]) -> Self {
        self.with_attribute(name, AttributeElement::Face, AttributeValues::Vector(values))
    }

    /// Adds a named per-face integer label.
    pub fn with_face_label(self, name: &'a str, values: &'a [i64]) -> Self {
        self.with_attribute(name, AttributeElement::Face, AttributeValues::Label(values))
    }

    /// The named per-vertex scalar fields, in order.
    pub fn scalars(&self) -> impl Iterator<Item = (&'a str, &'a [f64])> + '_ {
        self.attributes.iter().filter_map(|a| match (a.element, a.values) {
            (AttributeElement::Vertex, AttributeValues::Scalar(v)) => Some((a.name, v)),
            _ => None,
        })
    }

    /// Checks that every attribute has one entry per vertex (per face for
    /// corner UVs and face attributes) and that no name is used twice for
    /// the same element; writers call this first. O(V + F + a^2) for `a`
    /// named attributes.
    ///
    /// # Errors
    /// `IoError::AttributeLength` naming the first attribute whose length is not the vertex count (the face
    /// count for corner UVs and face attributes); `IoError::AttributeName` for an empty name or a name given
    /// twice to the same element.
    pub fn check(&self) -> Result<()> {
        let (nv, nf) = (self.mesh.vertex_count(), self.mesh.face_count());
        let mut lengths = vec![
            ("normals".to_owned(), self.normals.map(<[_]>::len), nv),
            ("uvs".to_owned(), self.uvs.map(<[_]>::len), nv),
            ("corner_uvs".to_owned(), self.corner_uvs.map(<[_]>::len), nf),
            ("colors".to_owned(), self.colors.map(<[_]>::len), nv),
        ];
        let count = |a: &Attribute<'_>| match a.element {
            AttributeElement::Vertex => nv,
            AttributeElement::Face => nf,
        };
        lengths.extend(self.attributes.iter().map(|a| (a.to_string(), Some(a.values.len()), count(a))));
        if let Some((what, found, expected)) =
            lengths.into_iter().find(|(_, found, expected)| found.is_some_and(|f| f != *expected))
        {
            return Err(IoError::AttributeLength { what, expected, found: found.unwrap_or_default() });
        }
        for (i, a) in self.attributes.iter().enumerate() {
            let problem = if a.name.is_empty() {
                "an attribute needs a name"
            } else if self.attributes[..i].iter().any(|b| b.element == a.element && b.name == a.name) {
                "the name is given twice to the same element"
            } else {
                continue;
            };
            return Err(IoError::AttributeName { what: a.to_string(), problem: problem.into() });
        }
        Ok(())
    }
}

impl<'a> From<&'a TriMesh> for MeshView<'a> {
    fn from(mesh: &'a TriMesh) -> Self {
        Self::new(mesh)
    }
}

impl<'a> From<&'a MeshData> for MeshView<'a> {
    fn from(data: &'a MeshData) -> Self {
        data.view()
    }
}

/// Builds the [`TriMesh`], mapping its validation error to `at`.
pub(crate) fn tri_mesh(positions: Vec<DVec3>, faces: Vec<[u32; 3]>, at: Location) -> Result<TriMesh> {
    TriMesh::new(positions, faces).map_err(|source| IoError::Mesh { at, source })
}

/// Per-vertex attributes resolved from per-corner indices (OBJ `vt`/`vn`):
/// `Ok(values)` when each vertex always uses the same value, or `Err(corner
/// values)` when some vertex has several (a seam).
pub(crate) fn per_vertex_or_corner<T: Copy + PartialEq + Default>(
    vertex_count: usize,
    faces: &[[u32; 3]],
    corner_values: &[[T; 3]],
) -> std::result::Result<Vec<T>, Vec<[T; 3]>> {
    let mut values = vec![None; vertex_count];
    for (face, corners) in faces.iter().zip(corner_values) {
        for (&v, &value) in face.iter().zip(corners) {
            match values[v as usize] {
                None => values[v as usize] = Some(value),
                Some(old) if old != value => return Err(corner_values.to_vec()),
                Some(_) => {}
            }
        }
    }
    Ok(values.into_iter().map(Option::unwrap_or_default).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fan_triangulation_counts_polygons_and_collapses() {
        let mut report = ReadReport::default();
        let mut tris = Vec::new();
        report.triangulate(&[0, 1, 2, 3, 4], |c, t| tris.push((c, t)));
        assert_eq!(tris.len(), 3);
        assert_eq!(tris[2], ([0, 3, 4], [0, 3, 4]));
        report.triangulate(&[5, 6, 6], |_, _| panic!("collapsed"));
        report.triangulate(&[5, 6], |_, _| panic!("too short"));
        assert_eq!((report.polygons_triangulated, report.faces_dropped), (1, 2));
        assert!(!report.is_clean());
        assert_eq!(report.to_string(), "1 polygon triangulated; 2 faces dropped");
        report.vertices_welded = 1;
        report.notes.push("normals ignored".into());
        assert_eq!(report.to_string(), "1 polygon triangulated; 2 faces dropped; 1 vertex welded; normals ignored");
        assert_eq!(ReadReport::default().to_string(), "nothing changed");
    }

    #[test]
    fn reordering_carries_every_attribute() {
        let mesh = mesh_kernel::shapes::icosphere(2).unwrap();
        let (n, f) = (mesh.vertex_count(), mesh.face_count());
        let mut data = MeshData::new(mesh.clone());
        let index: Vec<f64> = (0..n).map(|i| i as f64).collect();
        data.normals = Some(mesh.positions().to_vec());
        data.scalars.push(("index".into(), index));
        data.labels.push(("label".into(), (0..n as i64).collect()));
        data.face_labels.push(("face".into(), (0..f as i64).collect()));
        data.corner_uvs = Some((0..f).map(|i| [DVec2::splat(i as f64); 3]).collect());
        let order = Reordering::spatial(&mesh);
        let out = data.reordered(&order).unwrap();
        for v in out.mesh.vertex_ids() {
            let old = order.old_vertex(v);
            assert_eq!(out.scalar("index").unwrap()[v.idx()], old.idx() as f64);
            assert_eq!(out.label("label").unwrap()[v.idx()], old.idx() as i64);
            assert_eq!(out.normals.as_ref().unwrap()[v.idx()], mesh.position(old));
        }
        for face in out.mesh.face_ids() {
            let old = order.old_face(face).idx();
            assert_eq!(out.face_label("face").unwrap()[face.idx()], old as i64);
            assert_eq!(out.corner_uvs.as_ref().unwrap()[face.idx()][0].x, old as f64);
        }
        let other = MeshData::new(mesh_kernel::shapes::icosphere(1).unwrap());
        assert!(other.reordered(&order).is_err());
    }

    #[test]
    fn view_checks_lengths() {
        let mesh = TriMesh::new(vec![DVec3::ZERO, DVec3::X, DVec3::Y], vec![[0, 1, 2]]).unwrap();
        let short = [0.0; 2];
        let e = MeshView::new(&mesh).with_scalar("k", &short).check().unwrap_err();
        assert_eq!(e.to_string(), "vertex scalar `k` has 2 entries, expected 3");
        let (faces, two) = ([7i64], [0i64; 2]);
        let e = MeshView::new(&mesh).with_face_label("chart", &faces).with_label("chart", &two);
        assert!(matches!(e.check(), Err(IoError::AttributeLength { expected: 3, found: 2, .. })));
        let twice = [0.0; 3];
        let e = MeshView::new(&mesh).with_scalar("k", &twice).with_scalar("k", &twice).check().unwrap_err();
        assert!(matches!(e, IoError::AttributeName { .. }) && e.to_string().contains("twice"), "{e}");
        let view = MeshView::new(&mesh).with_scalar("k", &twice).with_face_label("k", &faces);
        assert!(view.check().is_ok(), "one name per element");
        assert!(MeshData::new(mesh).view().check().is_ok());
    }

    #[test]
    fn seams_give_corner_values() {
        let faces = [[0, 1, 2], [0, 2, 3]];
        assert_eq!(per_vertex_or_corner(4, &faces, &[[1, 2, 3], [1, 3, 4]]), Ok(vec![1, 2, 3, 4]));
        assert!(per_vertex_or_corner(4, &faces, &[[1, 2, 3], [9, 3, 4]]).is_err());
    }
}
