//! `mesh figures`: the figures of the "Digital Shape Processing" thesis
//! chapter, reproduced by the workspace's own algorithms on the shared
//! meshes and built-in shapes. Each figure is a PNG (`figure-2.4.png`)
//! and a one-line caption file (`figure-2.4.txt`) in the output folder.
//!
//! Every figure is one function from a [`Context`] (panel size, where the
//! shared meshes are) to a [`Made`] figure, listed once in [`FIGURES`]:
//! adding a figure is adding a function and a line there.
//!
//! The shared meshes come from `--data DIR`, else from the folder named by
//! `MESH_SHARED_DATA`; a file missing there is a [`FiguresError`]. With
//! neither, each figure uses a built-in stand-in and says so in its caption.

use std::path::PathBuf;

use mesh_curvature::{pointwise_curvature, PointwiseOptions};
use mesh_geodesic::{dijkstra, trace_path, DijkstraOptions, FastMarching, FmmOptions, SurfacePoint, TraceOptions};
use mesh_kernel::glam::{DQuat, DVec2, DVec3};
use mesh_kernel::{shapes, TriMesh, VertexId};
use mesh_param::{parameterize, ParamMethod, ParamOptions};
use mesh_render::legend::{self, BAR_HEIGHT};
use mesh_render::{
    corner_uvs, isolines, normalize_uvs, ColorScale, CurvatureClasses, Drawing, Figure, Image, Levels, LineStyle,
    Paint, Panel, Scene, Shading, Texture, View,
};
use mesh_wavelet::{subdivide, MultiresOptions, Multiresolution, Scheme, SubdivideOptions, WaveletKind};

use crate::output::CliResult;
use crate::render::write_png;

/// The environment variable naming the folder of the shared meshes.
pub const DATA_VAR: &str = "MESH_SHARED_DATA";

/// Arguments of `mesh figures`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder (created if missing): figure-2.4.png and
    /// figure-2.4.txt (its caption) for each figure.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Only these figures, comma-separated (e.g. 2.4,2.9); default: all.
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    only: Vec<String>,
    /// Size of each panel of a figure in pixels, WxH (each side 64..2048).
    #[arg(long, value_name = "WxH", default_value = "320x300")]
    size: String,
    /// Folder of the shared meshes (cgal_nefertiti.off, npm_bunny.obj);
    /// default: $MESH_SHARED_DATA; without either, built-in stand-ins.
    #[arg(long, value_name = "DIR")]
    data: Option<PathBuf>,
}

/// What `mesh figures` refuses, in its own terms.
#[derive(Debug, thiserror::Error)]
pub enum FiguresError {
    /// `--only` names a figure that is not in the list.
    #[error("--only {given}: no such figure (the figures are {known})")]
    UnknownFigure {
        /// The id as typed.
        given: String,
        /// The ids there are.
        known: String,
    },
    /// `--size` is not `WxH` with sides in range.
    #[error("--size {given}: expected WxH with each side in 64..2048 pixels (e.g. 320x300)")]
    BadSize {
        /// The value as typed.
        given: String,
    },
    /// The data folder lacks a shared mesh a figure needs.
    #[error(
        "{file} is missing from the shared-mesh folder {dir} (give --data the folder that holds it, or unset \
         {DATA_VAR} and leave out --data to draw built-in stand-ins)"
    )]
    MissingFile {
        /// The file name.
        file: String,
        /// The folder it was looked for in.
        dir: PathBuf,
    },
    /// The data folder does not exist.
    #[error("the shared-mesh folder {dir} does not exist")]
    NoDataFolder {
        /// The folder.
        dir: PathBuf,
    },
}

/// One figure of the chapter: its number, and the function that makes it.
pub struct FigureSpec {
    /// The chapter's number, e.g. `2.4` (the files are `figure-2.4.*`).
    pub id: &'static str,
    /// Makes the figure.
    pub make: fn(&Context) -> CliResult<Made>,
}

/// Every figure, in the chapter's order.
pub const FIGURES: &[FigureSpec] = &[
    FigureSpec { id: "2.2", make: figure_2_2 },
    FigureSpec { id: "2.4", make: figure_2_4 },
    FigureSpec { id: "2.7", make: figure_2_7 },
    FigureSpec { id: "2.8", make: figure_2_8 },
    FigureSpec { id: "2.9", make: figure_2_9 },
    FigureSpec { id: "2.10", make: figure_2_10 },
    FigureSpec { id: "2.11", make: figure_2_11 },
    FigureSpec { id: "2.12", make: figure_2_12 },
    FigureSpec { id: "2.13", make: figure_2_13 },
    FigureSpec { id: "2.14", make: figure_2_14 },
];

/// A figure, made: the panels and the caption line of its `.txt` file.
pub struct Made {
    /// The picture.
    pub figure: Figure,
    /// One line saying what the figure shows and how it was computed.
    pub caption: String,
}

/// What every figure function gets.
#[derive(Debug, Clone)]
pub struct Context {
    /// Panel width in pixels.
    pub width: usize,
    /// Panel height in pixels.
    pub height: usize,
    /// The folder of the shared meshes, when there is one.
    pub data: Option<PathBuf>,
}

/// A mesh for a figure and how to name it in captions.
struct Source {
    mesh: TriMesh,
    name: String,
    /// The file's up axis (y for OBJ and OFF), z for built-in shapes.
    up: DVec3,
}

impl Context {
    /// The shared mesh `file`, or `stand_in` (named `stand_in_name`) when
    /// there is no data folder.
    fn shared(
        &self,
        file: &str,
        stand_in_name: &str,
        stand_in: impl FnOnce() -> CliResult<TriMesh>,
    ) -> CliResult<Source> {
        match &self.data {
            Some(dir) => {
                let path = dir.join(file);
                if !path.is_file() {
                    return Err(FiguresError::MissingFile { file: file.into(), dir: dir.clone() }.into());
                }
                let data = crate::input::read_mesh(&path)?;
                let up = mesh_io::Format::from_path(&path).map_or(DVec3::Y, |f| f.conventional_up());
                Ok(Source { mesh: data.mesh, name: file.into(), up })
            }
            None => {
                Ok(Source { mesh: stand_in()?, name: format!("{stand_in_name} (stand-in for {file})"), up: DVec3::Z })
            }
        }
    }

    /// A scene rendered into one panel, with room at the bottom for a
    /// legend when `legend` is set.
    fn render(&self, scene: &Scene<'_>, view: &View, legend: bool) -> CliResult<Image> {
        let margins = if legend { [0, 0, 0, BAR_HEIGHT] } else { [0; 4] };
        Ok(scene.render(view, self.width, self.height, margins)?)
    }
}

/// Parses `WxH`.
fn parse_size(s: &str) -> Result<(usize, usize), FiguresError> {
    let bad = || FiguresError::BadSize { given: s.into() };
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (usize, usize) = (w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?);
    if !((64..=2048).contains(&w) && (64..=2048).contains(&h)) {
        return Err(bad());
    }
    Ok((w, h))
}

/// The figures `--only` selects (all when empty), in the list's order.
fn select(only: &[String]) -> Result<Vec<&'static FigureSpec>, FiguresError> {
    for given in only {
        if !FIGURES.iter().any(|f| f.id == given.trim()) {
            let known = FIGURES.iter().map(|f| f.id).collect::<Vec<_>>().join(", ");
            return Err(FiguresError::UnknownFigure { given: given.clone(), known });
        }
    }
    Ok(FIGURES.iter().filter(|f| only.is_empty() || only.iter().any(|o| o.trim() == f.id)).collect())
}

/// Runs `mesh figures`.
pub fn run(args: &Args) -> CliResult<()> {
    let (width, height) = parse_size(&args.size)?;
    let figures = select(&args.only)?;
    let data = args.data.clone().or_else(|| std::env::var_os(DATA_VAR).filter(|v| !v.is_empty()).map(PathBuf::from));
    if let Some(dir) = &data {
        if !dir.is_dir() {
            return Err(FiguresError::NoDataFolder { dir: dir.clone() }.into());
        }
    }
    std::fs::create_dir_all(&args.out).map_err(|e| format!("cannot create {}: {e}", args.out.display()))?;
    let context = Context { width, height, data };
    for spec in figures {
        let made = (spec.make)(&context).map_err(|e| format!("figure {}: {e}", spec.id))?;
        let image = made.figure.compose()?;
        let png = args.out.join(format!("figure-{}.png", spec.id));
        write_png(&png, &image)?;
        let txt = args.out.join(format!("figure-{}.txt", spec.id));
        let line = format!("{}\n", made.caption);
        mesh_io::write_atomic(&txt, |w| w.write_all(line.as_bytes()).map_err(|e| mesh_io::IoError::io(&txt, e)))?;
        eprintln!("wrote {} ({}x{})", png.display(), image.width(), image.height());
    }
    Ok(())
}

/// Makes one figure in memory (tests).
#[cfg(test)]
pub fn make(id: &str, context: &Context) -> CliResult<Made> {
    let spec = FIGURES.iter().find(|f| f.id == id).ok_or_else(|| format!("no figure {id}"))?;
    (spec.make)(context)
}

// ---------------------------------------------------------------------------
// Shapes and helpers

const BLACK: DVec3 = DVec3::ZERO;
const RED: DVec3 = DVec3::new(0.85, 0.05, 0.05);
const BLUE: DVec3 = DVec3::new(0.05, 0.2, 0.85);
const GREY: DVec3 = DVec3::new(0.82, 0.82, 0.82);

/// A lumpy sphere like a molecule's surface: the icosphere of `level`
/// pushed out by Gaussian bumps around seven directions and in by three
/// narrow dents, so it has convex caps, concave cups and saddles.
pub fn blob(level: u32) -> CliResult<TriMesh> {
    let mut m = shapes::icosphere(level)?;
    let centres = [
        DVec3::new(1.0, 0.0, 0.2),
        DVec3::new(-0.6, 0.8, 0.1),
        DVec3::new(-0.5, -0.8, 0.3),
        DVec3::new(0.1, 0.2, 1.0),
        DVec3::new(0.3, -0.3, -1.0),
        DVec3::new(0.6, 0.7, -0.4),
        DVec3::new(-0.8, 0.0, -0.6),
    ]
    .map(|c| c.normalize());
    let dents = [DVec3::new(-0.95, -0.2, 0.25), DVec3::new(0.0, -0.75, 0.65), DVec3::new(-0.3, -0.85, -0.45)]
        .map(|c| c.normalize());
    for p in m.positions_mut() {
        let d = p.normalize();
        let bump: f64 = centres.iter().map(|c| (-(d - *c).length_squared() / 0.18).exp()).sum();
        let dent: f64 = dents.iter().map(|c| (-(d - *c).length_squared() / 0.12).exp()).sum();
        *p = d * (0.75 + 0.45 * bump - 0.4 * dent);
    }
    Ok(m)
}

/// A disk with a face-like relief (brow, nose, cheeks), for when the
/// nefertiti mesh is not at hand.
fn relief_disk() -> CliResult<TriMesh> {
    let mut m = shapes::disk(12, 7)?;
    for p in m.positions_mut() {
        let g = |x: f64, y: f64, s: f64| (-((p.x - x).powi(2) + (p.y - y).powi(2)) / s).exp();
        p.z = 0.35 * g(0.0, 0.0, 0.02) + 0.15 * g(0.0, 0.35, 0.08) + 0.12 * (g(0.4, -0.2, 0.05) + g(-0.4, -0.2, 0.05))
            - 0.08 * (g(0.3, 0.2, 0.02) + g(-0.3, 0.2, 0.02))
            + 0.25 * (1.0 - p.x * p.x - p.y * p.y);
    }
    Ok(m)
}

fn ellipsoid() -> CliResult<TriMesh> {
    let mut m = shapes::icosphere(3)?;
    for p in m.positions_mut() {
        *p *= DVec3::new(1.6, 1.0, 0.7);
    }
    Ok(m)
}

/// Mean edge length.
fn mean_edge(mesh: &TriMesh) -> f64 {
    let p = mesh.positions();
    let (sum, n) = mesh.faces().iter().fold((0.0, 0usize), |(s, n), f| {
        let [a, b, c] = f.map(|v| p[v as usize]);
        (s + a.distance(b) + b.distance(c) + c.distance(a), n + 3)
    });
    if n == 0 {
        1.0
    } else {
        sum / n as f64
    }
}

/// Every edge of the mesh once, as segments.
fn edges(mesh: &TriMesh) -> Vec<[DVec3; 2]> {
    let mut e: Vec<(u32, u32)> = mesh
        .faces()
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    e.sort_unstable();
    e.dedup();
    let p = mesh.positions();
    e.into_iter().map(|(a, b)| [p[a as usize], p[b as usize]]).collect()
}

/// A small cross (three short segments) marking a point.
fn marker(p: DVec3, size: f64) -> [[DVec3; 2]; 3] {
    [DVec3::X, DVec3::Y, DVec3::Z].map(|d| [p - size * d, p + size * d])
}

/// The area-weighted mean normal of a mesh.
fn mean_normal(mesh: &TriMesh) -> DVec3 {
    let p = mesh.positions();
    let n: DVec3 = mesh
        .faces()
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| p[v as usize]);
            (b - a).cross(c - a)
        })
        .sum();
    n.try_normalize().unwrap_or(DVec3::Z)
}

/// The mesh turned so that its mean normal points along +z (toward a
/// camera at azimuth 0, elevation 0 with y up), the file's up axis kept as
/// close to +y as the turn allows.
fn facing_camera(mesh: &TriMesh, up: DVec3) -> CliResult<TriMesh> {
    let n = mean_normal(mesh);
    let q1 = DQuat::from_rotation_arc(n, DVec3::Z);
    let u = q1 * up;
    let u = DVec3::new(u.x, u.y, 0.0).try_normalize().unwrap_or(DVec3::Y);
    let q = DQuat::from_rotation_arc(u, DVec3::Y) * q1;
    let mut m = mesh.clone();
    for p in m.positions_mut() {
        *p = q * *p;
    }
    Ok(m)
}

/// Median of the finite values (0 for none).
fn median(v: &[f64]) -> f64 {
    let mut a: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    a.sort_by(f64::total_cmp);
    a.get(a.len() / 2).copied().unwrap_or(0.0)
}

// ---------------------------------------------------------------------------
// The figures

/// Figure 2.4: a face-like disk texture-mapped with a checker under five
/// parameterizations.
fn figure_2_4(cx: &Context) -> CliResult<Made> {
    let src = cx.shared("cgal_nefertiti.off", "relief disk", relief_disk)?;
    let mesh = facing_camera(&src.mesh, src.up)?;
    let view = View::new(0.0, 0.0, DVec3::Y);
    let mut panels = Vec::new();
    let mut scene = Scene::new();
    scene.surface(&mesh, Paint::Plain(mesh_render::scene::SURFACE), Shading::Smooth)?;
    panels.push(Panel::new(cx.render(&scene, &view, false)?, "original"));
    let mut scene = Scene::new();
    scene.surface(&mesh, Paint::Plain(mesh_render::scene::SURFACE), Shading::Flat)?;
    panels.push(Panel::new(cx.render(&scene, &view, false)?, "flat-shaded"));
    let methods: [(ParamMethod, &str); 5] = [
        (ParamMethod::Tutte, "Tutte"),
        (ParamMethod::MeanValue, "Floater"),
        (ParamMethod::Authalic, "authalic"),
        (ParamMethod::Harmonic, "conformal"),
        (ParamMethod::Intrinsic { lambda: 0.5, mu: 0.5 }, "intrinsic"),
    ];
    let mut tutte_uv = None;
    for (method, label) in methods {
        let p = parameterize(&src.mesh, &ParamOptions { method, ..Default::default() })?;
        let mut uv = corner_uvs(&mesh, &p.uv)?;
        normalize_uvs(&mut uv);
        if method == ParamMethod::Tutte {
            tutte_uv = Some(uv.clone());
        }
        let mut scene = Scene::new();
        scene.surface(&mesh, Paint::Texture { uv, texture: Texture::checker(10) }, Shading::Smooth)?;
        panels.push(Panel::new(cx.render(&scene, &view, false)?, label));
    }
    // The Tutte map itself: the mesh drawn in the (u, v) plane.
    if let Some(uv) = tutte_uv {
        let mut d = Drawing::new();
        for tri in &uv {
            d.polygon(tri.to_vec(), DVec3::new(0.86, 0.9, 0.97));
        }
        for tri in &uv {
            for k in 0..3 {
                d.segment(tri[k], tri[(k + 1) % 3], DVec3::splat(0.25), 0.6)?;
            }
        }
        panels.push(Panel::new(d.render(cx.width, cx.height)?, "Tutte (u,v) plane"));
    }
    let title = format!("Figure 2.4: parameterizations of {}", src.name);
    Ok(Made {
        figure: Figure { title, panels, columns: 4 },
        caption: format!(
            "Figure 2.4: {} ({} vertices), original, flat-shaded, and a checker texture mapped through the Tutte, \
             Floater mean-value, authalic, conformal (harmonic) and intrinsic (lambda = mu = 1/2) \
             parameterizations onto a circle (mesh-param), with the Tutte map's (u, v) plane.",
            src.name,
            mesh.vertex_count()
        ),
    })
}

/// The principal-direction panel: max directions red, min directions blue
/// (either or both), on a plain surface.
fn directions_panel(cx: &Context, mesh: &TriMesh, view: &View, max: bool, min: bool) -> CliResult<(Image, f64, f64)> {
    let pc = pointwise_curvature(mesh, &PointwiseOptions::default())?;
    let t = &pc.tensor;
    let half = 0.4 * mean_edge(mesh);
    let p = mesh.positions();
    // Lift the segments a little off the surface, along the normal.
    let lifted: Vec<DVec3> = p.iter().zip(&t.normal).map(|(&x, &n)| x + 0.1 * half * n).collect();
    let mut scene = Scene::new();
    scene.surface(mesh, Paint::Plain(GREY), Shading::Smooth)?;
    if max {
        scene.line_field(&lifted, &t.d1, half, LineStyle::new(RED, 1.2))?;
    }
    if min {
        scene.line_field(&lifted, &t.d2, half, LineStyle::new(BLUE, 1.2))?;
    }
    Ok((cx.render(&scene, view, false)?, median(&t.k1), median(&t.k2)))
}

/// Figure 2.7: principal curvatures and directions on basic shapes.
fn figure_2_7(cx: &Context) -> CliResult<Made> {
    let sphere = shapes::icosphere(2)?;
    let cylinder = shapes::cylinder(0.5, 1.6, 24, 8)?;
    let torus = shapes::torus(1.0, 0.4, 32, 14)?;
    let mut saddle = shapes::grid(2.0, 2.0, 14, 14)?;
    for p in saddle.positions_mut() {
        *p -= DVec3::new(1.0, 1.0, 0.0);
        p.z = 0.5 * (p.x * p.x - p.y * p.y);
    }
    let view = View::new(-60.0, 30.0, DVec3::Z);
    let mut panels = Vec::new();
    let mut parts = Vec::new();
    for (mesh, name) in [(&sphere, "sphere"), (&cylinder, "cylinder"), (&torus, "torus"), (&saddle, "saddle")] {
        let (image, k1, k2) = directions_panel(cx, mesh, &view, true, true)?;
        let label = format!("{name} k1 {} k2 {}", legend::format_value(k1), legend::format_value(k2));
        parts.push(label.clone());
        panels.push(Panel::new(image, label));
    }
    Ok(Made {
        figure: Figure::row("Figure 2.7: principal directions, max red, min blue", panels),
        caption: format!(
            "Figure 2.7: principal curvature directions of basic shapes from the curvature tensor (mesh-curvature, \
             quartic jet fit): maximum curvature direction in red, minimum in blue; median principal curvatures: {}.",
            parts.join("; ")
        ),
    })
}

/// Figure 2.8: minimum and maximum principal directions on a scanned shape.
fn figure_2_8(cx: &Context) -> CliResult<Made> {
    let src = cx.shared("npm_bunny.obj", "ellipsoid", ellipsoid)?;
    let view = View::new(-20.0, 15.0, src.up);
    let (min_image, _, _) = directions_panel(cx, &src.mesh, &view, false, true)?;
    let (max_image, _, _) = directions_panel(cx, &src.mesh, &view, true, false)?;
    let panels = vec![Panel::new(min_image, "minimum directions"), Panel::new(max_image, "maximum directions")];
    Ok(Made {
        figure: Figure::row(format!("Figure 2.8: principal directions on {}", src.name), panels),
        caption: format!(
            "Figure 2.8: principal curvature directions on {} ({} vertices) from the curvature tensor \
             (mesh-curvature): left the minimum curvature directions, right the maximum curvature directions, one \
             short segment per vertex.",
            src.name,
            src.mesh.vertex_count()
        ),
    })
}

/// Figure 2.9: mean and Gaussian curvature, and the convex / concave /
/// saddle map of the chapter's caption.
fn figure_2_9(cx: &Context) -> CliResult<Made> {
    let mesh = blob(5)?;
    let pc = pointwise_curvature(&mesh, &PointwiseOptions::default())?;
    let view = View::new(-50.0, 25.0, DVec3::Z);
    let mut panels = Vec::new();
    for (values, label) in [(&pc.mean, "mean curvature H"), (&pc.gaussian, "Gaussian curvature K")] {
        let scale = ColorScale::symmetric(values);
        let mut scene = Scene::new();
        scene.surface(&mesh, Paint::Vertex(scale.colors(values)), Shading::Smooth)?;
        let mut image = cx.render(&scene, &view, true)?;
        legend::horizontal(&mut image, &scale);
        panels.push(Panel::new(image, label));
    }
    let classes = CurvatureClasses::fit(&pc.mean, &pc.gaussian);
    let mut scene = Scene::new();
    scene.surface(&mesh, Paint::Vertex(classes.colors(&pc.mean, &pc.gaussian)), Shading::Smooth)?;
    let mut image = cx.render(&scene, &view, true)?;
    legend::swatches(&mut image, &CurvatureClasses::swatches());
    panels.push(Panel::new(image, "signs of H and K"));
    Ok(Made {
        figure: Figure::row("Figure 2.9: mean and Gaussian curvature of a molecule-like blob", panels),
        caption: format!(
            "Figure 2.9: pointwise mean and Gaussian curvature (mesh-curvature, from the curvature tensor) of a \
             molecule-like blob ({} vertices), diverging colours; right, red where convex (H > 0, K > 0), blue where \
             concave (H < 0, K > 0), grey at saddles (K < 0), light where |K| is below 2% of its 95th percentile.",
            mesh.vertex_count()
        ),
    })
}

/// The two vertices of a figure's geodesic: the highest along `up` (the
/// tip of an ear of the bunny, where Euclidean and geodesic distance part),
/// and the vertex farthest from it along the surface.
fn endpoints(
    mesh: &TriMesh,
    up: DVec3,
    distance_from: impl Fn(VertexId) -> CliResult<Vec<f64>>,
) -> CliResult<(VertexId, VertexId, Vec<f64>)> {
    let p = mesh.positions();
    let source =
        (0..p.len()).max_by(|&a, &b| p[a].dot(up).total_cmp(&p[b].dot(up))).ok_or("the mesh has no vertices")?;
    let source = VertexId(source as u32);
    let d = distance_from(source)?;
    let target = (0..p.len())
        .filter(|&v| d[v].is_finite())
        .max_by(|&a, &b| d[a].total_cmp(&d[b]))
        .ok_or("no vertex is reachable from the source")?;
    Ok((source, VertexId(target as u32), d))
}

/// A surface coloured by a distance field, with its isolines.
fn distance_panel(
    cx: &Context,
    mesh: &TriMesh,
    view: &View,
    d: &[f64],
    scale: &ColorScale,
    lines: usize,
) -> CliResult<Image> {
    let mut scene = Scene::new();
    let colors: Vec<DVec3> = scale.colors(d).into_iter().map(|c| c.lerp(DVec3::ONE, 0.25)).collect();
    scene.surface(mesh, Paint::Vertex(colors), Shading::Smooth)?;
    let step = (scale.max - scale.min) / (lines + 1) as f64;
    scene.lines(isolines(mesh, d, &Levels::Step(step))?, LineStyle::new(BLACK, 1.0))?;
    let mut image = cx.render(&scene, view, true)?;
    legend::horizontal(&mut image, scale);
    Ok(image)
}

/// Figure 2.10: Euclidean against geodesic distance; the Dijkstra path
/// against the Fast Marching path.
fn figure_2_10(cx: &Context) -> CliResult<Made> {
    let src = cx.shared("npm_bunny.obj", "torus", || Ok(shapes::torus(1.0, 0.35, 64, 24)?))?;
    let mesh = &src.mesh;
    let fmm = FastMarching::new(mesh, &FmmOptions::default())?;
    let (source, target, geodesic) = endpoints(mesh, src.up + 0.3 * DVec3::X, |s| Ok(fmm.distance(&[s])?))?;
    let p = mesh.positions();
    let euclid: Vec<f64> = p.iter().map(|q| q.distance(p[source.idx()])).collect();
    let scale = ColorScale::full(&geodesic);
    let view = View::new(-20.0, 15.0, src.up);
    let euclid_image = distance_panel(cx, mesh, &view, &euclid, &scale, 12)?;
    let geodesic_image = distance_panel(cx, mesh, &view, &geodesic, &scale, 12)?;

    let graph = dijkstra(mesh, &[source], &DijkstraOptions::default())?;
    let edge_path = graph.edge_path(target).ok_or("the target is not reachable along edges")?;
    let edge_points: Vec<DVec3> = edge_path.iter().map(|v| p[v.idx()]).collect();
    let start = SurfacePoint::at_vertex(mesh, target).ok_or("the target vertex has no face")?;
    let traced = trace_path(mesh, &geodesic, &[source], start, &TraceOptions::default())?;
    let size = 1.5 * mean_edge(mesh);
    let mut scene = Scene::new();
    scene.surface(mesh, Paint::Plain(GREY), Shading::Smooth)?;
    scene.polyline(&edge_points, LineStyle::new(BLACK, 3.0))?;
    scene.polyline(&traced.positions, LineStyle::new(RED, 1.5))?;
    scene.lines(
        marker(p[source.idx()], size).into_iter().chain(marker(p[target.idx()], size)),
        LineStyle::new(BLUE, 2.0),
    )?;
    let path_image = cx.render(&scene, &view, false)?;
    let dijkstra_length = graph.distance[target.idx()];
    let panels = vec![
        Panel::new(euclid_image, "Euclidean"),
        Panel::new(geodesic_image, "geodesic (FMM)"),
        Panel::new(path_image, "Dijkstra black, FMM red"),
    ];
    Ok(Made {
        figure: Figure::row(format!("Figure 2.10: distances on {}", src.name), panels),
        caption: format!(
            "Figure 2.10: on {}, left the Euclidean distance and middle the Fast Marching geodesic distance from one \
             vertex (same colours, isolines every 1/13 of the largest geodesic distance); right the shortest path \
             along edges (Dijkstra, black, length {}) against the path traced across triangles down the Fast Marching \
             distance (red, length {}) to the farthest vertex (mesh-geodesic).",
            src.name,
            legend::format_value(dijkstra_length),
            legend::format_value(traced.length)
        ),
    })
}

/// Figure 2.11: Fast Marching wavefronts on a sphere and on the bunny.
fn figure_2_11(cx: &Context) -> CliResult<Made> {
    let sphere = shapes::icosphere(4)?;
    let src = cx.shared("npm_bunny.obj", "torus", || Ok(shapes::torus(1.0, 0.35, 64, 24)?))?;
    let mut panels = Vec::new();
    for (mesh, view, name) in [
        (&sphere, View::new(-60.0, 25.0, DVec3::Z), "sphere".to_owned()),
        (&src.mesh, View::new(-20.0, 15.0, src.up), src.name.clone()),
    ] {
        let fmm = FastMarching::new(mesh, &FmmOptions::default())?;
        // The source: the vertex nearest the camera's upper left.
        let frame = view.frame()?;
        let key = frame.toward + 0.5 * frame.up - 0.5 * frame.right;
        let p = mesh.positions();
        let source = (0..p.len()).max_by(|&a, &b| p[a].dot(key).total_cmp(&p[b].dot(key))).ok_or("empty mesh")?;
        let d = fmm.distance(&[VertexId(source as u32)])?;
        let scale = ColorScale::full(&d);
        panels.push(Panel::new(distance_panel(cx, mesh, &view, &d, &scale, 20)?, name));
    }
    Ok(Made {
        figure: Figure::row("Figure 2.11: Fast Marching wavefronts", panels),
        caption: format!(
            "Figure 2.11: Fast Marching wavefronts (mesh-geodesic) from one vertex, drawn as 20 isolines of the \
             distance at equal spacing, on a sphere (icosphere, {} vertices) and on {}.",
            sphere.vertex_count(),
            src.name
        ),
    })
}

/// Figure 2.12: a multiresolution cascade: the fine mesh, a coarser level
/// and the base mesh of the wavelet analysis.
fn figure_2_12(cx: &Context) -> CliResult<Made> {
    let fine = blob(4)?;
    let mr = Multiresolution::analyze(&fine, &MultiresOptions::default())?;
    let levels = mr.levels();
    let view = View::new(-50.0, 25.0, DVec3::Z);
    let mut panels = Vec::new();
    let picks = [levels, levels.saturating_sub(2), 0];
    for (k, &j) in picks.iter().enumerate() {
        let mesh = mr.level(j)?;
        let mut scene = Scene::new();
        scene.surface(&mesh, Paint::Plain(mesh_render::scene::SURFACE), Shading::Flat)?;
        if j < levels {
            scene.lines(edges(&mesh), LineStyle::new(DVec3::splat(0.2), 1.0))?;
        }
        let label = format!("({}) level {j}, {} faces", ['a', 'b', 'c'][k], mesh.face_count());
        panels.push(Panel::new(cx.render(&scene, &view, false)?, label));
    }
    Ok(Made {
        figure: Figure::row("Figure 2.12: multiresolution analysis", panels),
        caption: format!(
            "Figure 2.12: the Lounsbery multiresolution analysis (mesh-wavelet, midpoint scheme, lifted wavelets) of a \
             blob with subdivision connectivity: (a) the original, level {levels}; (b) the coarser level {}; (c) the \
             base mesh, level 0, each the low-pass output of the analysis filters.",
            levels.saturating_sub(2)
        ),
    })
}

/// Figure 2.2: the same points triangulated arbitrarily (a sweep) and by
/// Delaunay, reached from the sweep by Lawson's edge flips (mesh-delaunay;
/// checked equal to spade's triangulation), with the Voronoi cells.
fn figure_2_2(cx: &Context) -> CliResult<Made> {
    use mesh_delaunay::{check_empty_circumcircles, delaunay, lawson_flips, sweep_triangulation, voronoi};
    let mut rng = mesh_kernel::random::SplitMix64::new(22);
    let points: Vec<DVec2> = (0..40).map(|_| DVec2::new(rng.signed(), 0.8 * rng.signed())).collect();
    let sweep = sweep_triangulation(&points)?;
    let flipped = lawson_flips(&points, &sweep, &Default::default())?;
    let reference = delaunay(&points)?;
    let sorted = |t: &[[u32; 3]]| {
        let mut v: Vec<[u32; 3]> = t.iter().map(|f| rotate_smallest_first(*f)).collect();
        v.sort_unstable();
        v
    };
    if sorted(&flipped.triangles) != sorted(&reference.triangles) {
        return Err("Lawson's flips did not reach spade's Delaunay triangulation".into());
    }
    let check = check_empty_circumcircles(&points, &flipped.triangles, 1e-9)?;
    let cells = voronoi(&reference, &Default::default())?;
    let fill = DVec3::new(0.86, 0.9, 0.97);
    let panel = |triangles: &[[u32; 3]], with_cells: bool| -> CliResult<Image> {
        let mut d = Drawing::new();
        for f in triangles {
            d.polygon(f.iter().map(|&v| points[v as usize]).collect(), fill);
        }
        d.triangle_edges(&points, triangles, BLACK, 1.2)?;
        if with_cells {
            for cell in &cells.cells {
                for k in 0..cell.len() {
                    d.segment(cell[k], cell[(k + 1) % cell.len()], RED, 1.2)?;
                }
            }
        }
        for &p in &points {
            d.point(p, BLACK, 4.0)?;
        }
        Ok(d.render(cx.width, cx.height)?)
    };
    let panels = vec![
        Panel::new(panel(&sweep, false)?, "(a) an arbitrary triangulation".to_owned()),
        Panel::new(panel(&flipped.triangles, false)?, format!("(b) Delaunay after {} flips", flipped.flips)),
        Panel::new(panel(&flipped.triangles, true)?, "(c) with its Voronoi cells".to_owned()),
    ];
    Ok(Made {
        figure: Figure::row("Figure 2.2: Delaunay triangulation and Voronoi diagram", panels),
        caption: format!(
            "Figure 2.2: 40 random points triangulated by a sweep (a), flipped to Delaunay by {} Lawson edge flips \
             (b; equal to spade's Delaunay triangulation, {} empty-circumcircle violations), and the Voronoi cells \
             clipped to a box (c, red) (mesh-delaunay).",
            flipped.flips, check.violations
        ),
    })
}

/// A triangle's corners rotated so that the smallest index comes first (the
/// orientation kept), to compare triangulations as sets.
fn rotate_smallest_first(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

/// Figure 2.13: recursive 4-to-1 splits of one triangle, in the plane.
fn figure_2_13(cx: &Context) -> CliResult<Made> {
    let h = 3f64.sqrt() / 2.0;
    let triangle =
        TriMesh::new(vec![DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0), DVec3::new(0.5, h, 0.0)], vec![[0, 1, 2]])?;
    let mut panels = Vec::new();
    for (k, levels) in [0usize, 1, 2].into_iter().enumerate() {
        let mesh = if levels == 0 {
            triangle.clone()
        } else {
            subdivide(&triangle, &SubdivideOptions { scheme: Scheme::Midpoint, levels })?
        };
        let pts: Vec<DVec2> = mesh.positions().iter().map(|p| DVec2::new(p.x, p.y)).collect();
        let mut d = Drawing::new();
        for f in mesh.faces() {
            d.polygon(f.iter().map(|&v| pts[v as usize]).collect(), DVec3::new(0.86, 0.9, 0.97));
        }
        d.triangle_edges(&pts, mesh.faces(), BLACK, 1.5)?;
        // Vertices: old ones black, the ones the last split added red.
        let old = if levels == 0 { pts.len() } else { triangle_vertices_after(levels - 1) };
        for (i, &q) in pts.iter().enumerate() {
            d.point(q, if i < old { BLACK } else { RED }, 5.0)?;
        }
        let label = match k {
            0 => "(a) initial face".to_owned(),
            1 => "(b) one 4-to-1 split".to_owned(),
            _ => "(c) two 4-to-1 splits".to_owned(),
        };
        panels.push(Panel::new(d.render(cx.width, cx.height)?, label));
    }
    Ok(Made {
        figure: Figure::row("Figure 2.13: 4-to-1 splits", panels),
        caption:
            "Figure 2.13: recursive 4-to-1 splitting of one triangle (mesh-wavelet midpoint subdivision): (a) the \
                  initial face, (b) after one split, (c) after two; the vertices each split adds in red."
                .into(),
    })
}

/// Vertices of one triangle after `levels` 4-to-1 splits: (2^l + 1)(2^l + 2) / 2.
fn triangle_vertices_after(levels: usize) -> usize {
    let n = 1usize << levels.min(20);
    (n + 1) * (n + 2) / 2
}

/// One wavelet function psi^j_i as a scalar per vertex of the finest level
/// (input order): synthesis of the unit coefficient `(level, index)`.
fn wavelet_function(mr: &Multiresolution, level: usize, index: usize) -> CliResult<Vec<f64>> {
    let h = mr.hierarchy();
    let n = h.vertex_count(mr.levels())?;
    let at = h.vertex_count(level)? + index;
    if at >= h.vertex_count(level + 1)? {
        return Err(format!("level {level} has no coefficient {index}").into());
    }
    let mut data = vec![0.0f64; n];
    data[at] = 1.0;
    mr.bank().synthesize(&mut data)?;
    let mut out = vec![0.0; n];
    for (hv, &x) in data.iter().enumerate() {
        let v = h.input_index(hv).ok_or("hierarchy without an input index")?;
        out[v] = x;
    }
    Ok(out)
}

/// Figure 2.14: one wavelet function on a surface.
fn figure_2_14(cx: &Context) -> CliResult<Made> {
    let sphere = shapes::icosphere(5)?;
    let view = View::new(-30.0, 20.0, DVec3::Z);
    let mut panels = Vec::new();
    let (level, index) = (1, 0);
    for (kind, label) in [(WaveletKind::Lazy, "lazy"), (WaveletKind::Lifted, "lifted")] {
        let mr = Multiresolution::analyze(
            &sphere,
            &MultiresOptions { scheme: Scheme::Loop, wavelet: kind, ..Default::default() },
        )?;
        let psi = wavelet_function(&mr, level, index)?;
        let peak = psi.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let peak = if peak > 0.0 { peak } else { 1.0 };
        let mut shown = sphere.clone();
        for (p, &x) in shown.positions_mut().iter_mut().zip(&psi) {
            *p *= 1.0 + 0.35 * x / peak;
        }
        // Look at the coefficient's vertex.
        let at = shown
            .positions()
            .iter()
            .zip(&psi)
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .map_or(DVec3::X, |(p, _)| *p);
        // Azimuth phi + 90 degrees faces the point; 50 degrees less shows the
        // displacement in profile.
        let az = at.y.atan2(at.x).to_degrees() + 40.0;
        let el = (at.z / at.length().max(1e-300)).clamp(-1.0, 1.0).asin().to_degrees();
        let v = View::new(az, el.clamp(-60.0, 60.0) * 0.8 + 10.0, view.up);
        let scale = ColorScale::symmetric(&psi);
        let mut scene = Scene::new();
        scene.surface(&shown, Paint::Vertex(scale.colors(&psi)), Shading::Smooth)?;
        let mut image = cx.render(&scene, &v, true)?;
        legend::horizontal(&mut image, &scale);
        panels.push(Panel::new(image, format!("{label} Loop wavelet")));
    }
    Ok(Made {
        figure: Figure::row("Figure 2.14: a wavelet function on a sphere", panels),
        caption: format!(
            "Figure 2.14: one wavelet function psi of level {level} (mesh-wavelet, Loop scheme; synthesis of a single \
             unit coefficient to the finest level, {} vertices), lazy and lifted, shown as colours and as a \
             displacement of the sphere along its normal.",
            sphere.vertex_count()
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_selections() {
        assert_eq!(parse_size("320x200").unwrap(), (320, 200));
        for bad in ["320", "x", "10x10", "320x99999", "axb"] {
            assert!(matches!(parse_size(bad), Err(FiguresError::BadSize { .. })), "{bad}");
        }
        assert_eq!(select(&[]).unwrap().len(), FIGURES.len());
        assert_eq!(
            select(&["2.9".into(), "2.4".into()]).unwrap().iter().map(|f| f.id).collect::<Vec<_>>(),
            ["2.4", "2.9"]
        );
        assert!(matches!(select(&["2.99".into()]), Err(FiguresError::UnknownFigure { .. })));
    }

    #[test]
    fn a_missing_shared_file_is_a_typed_error() {
        let dir = tempfile::tempdir().unwrap();
        let cx = Context { width: 64, height: 64, data: Some(dir.path().to_path_buf()) };
        let e = make("2.8", &cx).err().unwrap();
        assert!(e.downcast_ref::<FiguresError>().is_some_and(|e| matches!(e, FiguresError::MissingFile { .. })), "{e}");
    }

    /// Every panel of `made` has at least `fraction` of its pixels off white.
    fn assert_panels_drawn(id: &str, made: &Made, fraction: f64) {
        let image = made.figure.compose().unwrap();
        for (k, r) in made.figure.panel_rects().iter().enumerate() {
            let drawn = image.count_differing(*r, DVec3::ONE);
            assert!(
                drawn as f64 >= fraction * (r.width * r.height) as f64,
                "figure {id} panel {k} is nearly blank ({drawn} of {} pixels drawn)",
                r.width * r.height
            );
        }
        assert!(!made.caption.contains('\n') && made.caption.starts_with(&format!("Figure {id}:")));
    }

    #[test]
    fn every_figure_draws_every_panel_with_stand_ins() {
        let cx = Context { width: 96, height: 80, data: None };
        for spec in FIGURES {
            let made = (spec.make)(&cx).unwrap_or_else(|e| panic!("figure {}: {e}", spec.id));
            let image = made.figure.compose().unwrap();
            let cols = made.figure.columns.min(made.figure.panels.len());
            let rows = made.figure.panels.len().div_ceil(cols);
            use mesh_render::figure::{CAPTION_HEIGHT, GAP, TITLE_HEIGHT};
            assert_eq!(image.width(), GAP + cols * (96 + GAP), "figure {}", spec.id);
            assert_eq!(image.height(), TITLE_HEIGHT + rows * (80 + CAPTION_HEIGHT + GAP), "figure {}", spec.id);
            assert_panels_drawn(spec.id, &made, 0.05);
        }
    }

    #[test]
    fn figures_on_the_shared_meshes() {
        let Some(dir) = mesh_testkit::data::shared_data() else { return };
        let cx = Context { width: 120, height: 100, data: Some(dir) };
        for id in ["2.4", "2.8", "2.10", "2.11"] {
            let made = make(id, &cx).unwrap_or_else(|e| panic!("figure {id}: {e}"));
            assert_panels_drawn(id, &made, 0.05);
            assert!(made.caption.contains(".o"), "figure {id} does not name its shared mesh: {}", made.caption);
        }
    }

    #[test]
    fn tutte_checker_cells_are_never_flipped() {
        // On the parameterization itself: every UV triangle of the Tutte map
        // is counter-clockwise, so no cell of the checker is mirrored.
        let mut meshes = vec![relief_disk().unwrap()];
        if let Some(path) = mesh_testkit::data::shared_file("cgal_nefertiti.off") {
            meshes.push(mesh_io::read(&path).unwrap().mesh);
        }
        for mesh in &meshes {
            let p = parameterize(mesh, &ParamOptions { method: ParamMethod::Tutte, ..Default::default() }).unwrap();
            let mut uv = corner_uvs(mesh, &p.uv).unwrap();
            normalize_uvs(&mut uv);
            let flipped = uv.iter().filter(|t| (t[1] - t[0]).perp_dot(t[2] - t[0]) <= 0.0).count();
            assert_eq!(flipped, 0, "{} of {} UV triangles not counter-clockwise", flipped, uv.len());
        }
    }

    #[test]
    fn convex_caps_are_red_and_dents_blue() {
        let mesh = blob(4).unwrap();
        let pc = pointwise_curvature(&mesh, &PointwiseOptions::default()).unwrap();
        let classes = CurvatureClasses::fit(&pc.mean, &pc.gaussian);
        let p = mesh.positions();
        // The outermost vertex is on a bump's cap: convex, red.
        let top = (0..p.len()).max_by(|&a, &b| p[a].length().total_cmp(&p[b].length())).unwrap();
        let c = classes.color(pc.mean[top], pc.gaussian[top]);
        assert!(c.x > 0.6 && c.y < 0.3 && c.z < 0.3, "convex vertex coloured {c}");
        // The vertex nearest a dent's centre direction is at the bottom of a cup: concave, blue.
        let dent = DVec3::new(-0.95, -0.2, 0.25).normalize();
        let bottom =
            (0..p.len()).max_by(|&a, &b| p[a].normalize().dot(dent).total_cmp(&p[b].normalize().dot(dent))).unwrap();
        let c = classes.color(pc.mean[bottom], pc.gaussian[bottom]);
        assert!(c.z > 0.6 && c.x < 0.3, "concave vertex coloured {c}");
    }

    #[test]
    fn the_wavelet_function_is_a_unit_coefficient() {
        // Analysis of the synthesized function gives back the unit coefficient.
        let sphere = shapes::icosphere(3).unwrap();
        let mr = Multiresolution::analyze(&sphere, &MultiresOptions::default()).unwrap();
        let psi = wavelet_function(&mr, 1, 3).unwrap();
        let h = mr.hierarchy();
        let mut data: Vec<f64> = (0..psi.len()).map(|hv| psi[h.input_index(hv).unwrap()]).collect();
        mr.bank().analyze(&mut data).unwrap();
        let at = h.vertex_count(1).unwrap() + 3;
        for (i, x) in data.iter().enumerate() {
            let expected = if i == at { 1.0 } else { 0.0 };
            assert!((x - expected).abs() < 1e-12, "coefficient {i}: {x}");
        }
        assert!(wavelet_function(&mr, 1, 1_000_000).is_err());
    }

    #[test]
    fn vertices_after_splits() {
        assert_eq!(triangle_vertices_after(0), 3);
        assert_eq!(triangle_vertices_after(1), 6);
        assert_eq!(triangle_vertices_after(2), 15);
    }
}
