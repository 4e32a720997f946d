//! `mesh info`: counts, topology, manifoldness and defects.

use mesh_kernel::{clean, geometry, TriMesh};
use serde::Serialize;

use crate::input::InputArgs;
use crate::output::{print_json, CliResult};

/// Arguments of `mesh info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

/// Everything `mesh info` reports. `genus` is `null` when the mesh is not an
/// oriented manifold.
#[derive(Debug, Clone, Serialize)]
pub struct Info {
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

impl Info {
    /// Measures a mesh.
    pub fn of(mesh: &TriMesh) -> Self {
        let c = mesh.connectivity();
        let report = c.non_manifold_report();
        let bbox = geometry::bounding_box(mesh);
        let closed = c.boundary_loop_count() == Some(0);
        // Area and volume measured on the mesh in its power-of-two unit,
        // then carried back (or reported as out of range).
        let (normalized, unit) = mesh_kernel::units::normalized(mesh);
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
        Info {
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

    fn print_text(&self, name: &str) {
        let opt = |x: Option<usize>| x.map_or("n/a (not manifold)".to_owned(), |v| v.to_string());
        println!("mesh: {name}");
        println!("  vertices           {}", self.vertices);
        println!("  faces              {}", self.faces);
        println!("  edges              {}", self.edges);
        println!("  euler char. (2.6)  {}", self.euler_characteristic);
        println!("  genus (2.7)        {}", self.genus.map_or("n/a (not manifold)".to_owned(), |g| g.to_string()));
        println!("  components         {}", self.components);
        println!("  boundary loops     {}", opt(self.boundary_loops));
        println!("  manifold           {}", if self.manifold { "yes" } else { "no" });
        println!("  non-manifold edges {}", self.non_manifold_edges);
        println!("  non-manifold verts {}", self.non_manifold_vertices);
        println!("  inconsistent edges {}", self.inconsistent_edges);
        println!("  degenerate faces   {}", self.degenerate_faces);
        println!("  duplicate faces    {}", self.duplicate_faces);
        println!("  unreferenced verts {}", self.unreferenced_vertices);
        println!("  coincident verts   {}", self.coincident_vertices);
        if let Some(a) = self.area {
            println!("  area               {}", number(a));
        }
        if let Some(v) = self.volume {
            println!("  volume             {}", number(v));
        }
        for q in &self.out_of_range {
            println!("  {q} (outside the range of double precision)");
        }
        println!("  mean edge length   {}", number(self.mean_edge_length));
        if let (Some(lo), Some(hi)) = (self.bbox_min, self.bbox_max) {
            println!(
                "  bounding box       [{:.4}, {:.4}, {:.4}] .. [{:.4}, {:.4}, {:.4}]",
                lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
            );
        }
    }
}

/// What the reader changed, as `mesh info --json` prints it under `read`.
#[derive(Debug, Clone, Serialize)]
pub struct ReadSummary {
    /// Faces dropped because they repeat a vertex or have fewer than three corners.
    pub faces_dropped: usize,
    /// Polygons split into triangles.
    pub polygons_triangulated: usize,
    /// Vertices merged into an identical one (STL).
    pub vertices_welded: usize,
    /// What the file held that was not read.
    pub notes: Vec<String>,
}

impl From<&mesh_io::ReadReport> for ReadSummary {
    fn from(r: &mesh_io::ReadReport) -> Self {
        Self {
            faces_dropped: r.faces_dropped,
            polygons_triangulated: r.polygons_triangulated,
            vertices_welded: r.vertices_welded,
            notes: r.notes.clone(),
        }
    }
}

/// One attribute of the file, as `mesh info` lists it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct AttributeSummary {
    /// The name (`normals`, `uvs`, `colors` for the standard ones).
    pub name: String,
    /// `vertex`, `face` or `corner` (per face corner).
    pub element: String,
    /// `scalar`, `vector`, `label`, or `uv` and `color` for the standard ones.
    pub kind: String,
    /// Numbers per value.
    pub arity: usize,
}

impl AttributeSummary {
    /// Every attribute of `data`: the standard ones (normals, texture
    /// coordinates, colours), then the named ones in the order of
    /// [`mesh_io::MeshData::attributes`].
    pub fn list(data: &mesh_io::MeshData) -> Vec<Self> {
        let entry = |name: &str, element: &str, kind: &str, arity: usize| Self {
            name: name.to_owned(),
            element: element.to_owned(),
            kind: kind.to_owned(),
            arity,
        };
        let standard = [
            (data.normals.is_some(), entry("normals", "vertex", "vector", 3)),
            (data.uvs.is_some(), entry("uvs", "vertex", "uv", 2)),
            (data.corner_uvs.is_some(), entry("uvs", "corner", "uv", 2)),
            (data.colors.is_some(), entry("colors", "vertex", "color", 4)),
        ];
        let mut out: Vec<Self> = standard.into_iter().filter(|(on, _)| *on).map(|(_, a)| a).collect();
        out.extend(
            data.attributes().iter().map(|a| entry(a.name, &a.element.to_string(), &a.kind().to_string(), a.arity())),
        );
        out
    }
}

/// `mesh info --json`: the measures, the file's attributes and what reading changed.
#[derive(Serialize)]
struct InfoJson<'a> {
    #[serde(flatten)]
    info: &'a Info,
    attributes: Vec<AttributeSummary>,
    read: ReadSummary,
}

/// Runs `mesh info`.
pub fn run(args: &Args) -> CliResult<()> {
    let data = args.input.load()?;
    let info = Info::of(&data.mesh);
    let attributes = AttributeSummary::list(&data);
    if args.json {
        print_json(&InfoJson { info: &info, attributes, read: ReadSummary::from(&data.report) })
    } else {
        info.print_text(&args.input.describe());
        if attributes.is_empty() {
            println!("  attributes         none");
        }
        for a in &attributes {
            println!("  attribute          {} {} {} ({} per value)", a.element, a.kind, a.name, a.arity);
        }
        println!("  read               {}", data.report);
        Ok(())
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

/// Six significant figures, in scientific notation outside [1e-3, 1e6).
fn number(x: f64) -> String {
    if x != 0.0 && !(1e-3..1e6).contains(&x.abs()) {
        format!("{x:.6e}")
    } else {
        format!("{x:.6}")
    }
}
