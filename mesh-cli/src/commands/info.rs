//! `mesh info`: counts, topology, manifoldness and defects.

use serde::Serialize;

use crate::input::InputArgs;
use crate::output::{print_json, CliResult};

/// Everything `mesh info` measures (`genus` is `null` when the mesh is not
/// an oriented manifold).
pub use mesh_kernel::summary::MeshSummary as Info;

/// Arguments of `mesh info`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub(crate) input: InputArgs,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
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
        print_text(&info, &args.input.describe());
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

/// `mesh info`'s text output of the measures.
fn print_text(info: &Info, name: &str) {
    let opt = |x: Option<usize>| x.map_or("n/a (not manifold)".to_owned(), |v| v.to_string());
    println!("mesh: {name}");
    println!("  vertices           {}", info.vertices);
    println!("  faces              {}", info.faces);
    println!("  edges              {}", info.edges);
    println!("  euler char. (2.6)  {}", info.euler_characteristic);
    println!("  genus (2.7)        {}", info.genus.map_or("n/a (not manifold)".to_owned(), |g| g.to_string()));
    println!("  components         {}", info.components);
    println!("  boundary loops     {}", opt(info.boundary_loops));
    println!("  manifold           {}", if info.manifold { "yes" } else { "no" });
    println!("  non-manifold edges {}", info.non_manifold_edges);
    println!("  non-manifold verts {}", info.non_manifold_vertices);
    println!("  inconsistent edges {}", info.inconsistent_edges);
    println!("  degenerate faces   {}", info.degenerate_faces);
    println!("  duplicate faces    {}", info.duplicate_faces);
    println!("  unreferenced verts {}", info.unreferenced_vertices);
    println!("  coincident verts   {}", info.coincident_vertices);
    if let Some(a) = info.area {
        println!("  area               {}", number(a));
    }
    if let Some(v) = info.volume {
        println!("  volume             {}", number(v));
    }
    for q in &info.out_of_range {
        println!("  {q} (outside the range of double precision)");
    }
    println!("  mean edge length   {}", number(info.mean_edge_length));
    if let (Some(lo), Some(hi)) = (info.bbox_min, info.bbox_max) {
        println!(
            "  bounding box       [{:.4}, {:.4}, {:.4}] .. [{:.4}, {:.4}, {:.4}]",
            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        );
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
