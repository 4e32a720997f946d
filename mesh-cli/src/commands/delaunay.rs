//! `mesh delaunay`: the Delaunay triangulation of planar points (chapter
//! section 2.2.2, Figure 2.2), Lawson's flips from an arbitrary
//! triangulation, the Voronoi cells, and constrained refinement of a
//! polygon with holes.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use mesh_delaunay::{
    check_empty_circumcircles, delaunay, lawson_flips, refine_polygon, sweep_triangulation, voronoi, LawsonOptions,
    PolygonDomain, RefineOptions, VoronoiOptions,
};
use mesh_kernel::glam::{DVec2, DVec3};
use mesh_kernel::random::SplitMix64;
use mesh_kernel::TriMesh;
use serde::Serialize;

use crate::input::read_mesh;
use crate::output::{check_output, print_json, write_mesh, CliResult, SaveArgs};

/// The largest plain-text point or polygon file read (bytes), and the
/// longest line.
const MAX_TEXT_BYTES: u64 = 1 << 32;
const MAX_LINE_BYTES: u64 = 4096;
/// The most points `--random` makes (2^26; 1 GiB of points).
const MAX_RANDOM: usize = 1 << 26;

/// Arguments of `mesh delaunay`.
#[derive(Debug, clap::Args)]
#[command(mut_arg("json", |a| a.help("Print a JSON summary on standard output")))]
#[command(mut_arg("force", |a| a.help("Allow an output to be the input file")))]
pub struct Args {
    /// Points: a mesh file (its vertices' x and y are used) or a text file
    /// (.txt, .xy, .csv) of "x y" lines ('#' starts a comment).
    #[arg(value_name = "FILE", conflicts_with_all = ["random", "polygon"])]
    pub(crate) input: Option<PathBuf>,
    /// N random points, uniform in [-1, 1]^2, instead of a file.
    #[arg(long, value_name = "N", conflicts_with = "polygon")]
    random: Option<usize>,
    /// Seed of --random.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Triangulate by Lawson's flips from a sweep triangulation (an
    /// arbitrary one) instead of spade's Delaunay, and print the flip count.
    #[arg(long)]
    flips: bool,
    /// Write the Voronoi cells (clipped to the points' bounding box plus 10%)
    /// as closed OBJ polylines to this file.
    #[arg(long, value_name = "FILE")]
    voronoi: Option<PathBuf>,
    /// Refine a polygon with holes instead: a text file of loops of "x y"
    /// lines separated by blank lines, the outer loop first.
    #[arg(long, value_name = "FILE")]
    pub(crate) polygon: Option<PathBuf>,
    /// Smallest angle of the refined triangles, in degrees (with --polygon).
    #[arg(long, default_value_t = 25.0, requires = "polygon")]
    min_angle: f64,
    /// Largest area of the refined triangles (with --polygon).
    #[arg(long, requires = "polygon")]
    max_area: Option<f64>,
    /// Output mesh (.obj, .ply, ...; z = 0).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    #[command(flatten)]
    save: SaveArgs,
}

impl Args {
    /// The input file, if any.
    pub fn input_file(&self) -> Option<&Path> {
        self.input.as_deref().or(self.polygon.as_deref())
    }

    /// The library options this command line set.
    pub fn given(&self) -> Vec<(&'static str, String)> {
        use crate::errors::flag;
        let mut given = vec![("min_angle", flag("--min-angle", self.min_angle))];
        if let Some(a) = self.max_area {
            given.push(("max_area", flag("--max-area", a)));
        }
        given
    }
}

/// The JSON summary.
#[derive(Debug, Default, Serialize)]
struct Summary {
    input: String,
    points: usize,
    duplicates: Option<usize>,
    vertices: usize,
    triangles: usize,
    /// Flips from the sweep triangulation (with --flips).
    flips: Option<usize>,
    /// Triangles of the sweep triangulation whose circumcircle held a point.
    sweep_violations: Option<usize>,
    /// Triangles of the result whose circumcircle holds a point (0).
    violations: usize,
    voronoi_cells: Option<usize>,
    min_angle_degrees: f64,
    max_triangle_area: f64,
    /// With --polygon: false when the refinement stopped at its vertex bound.
    complete: Option<bool>,
}

/// Runs `mesh delaunay`.
pub fn run(args: &Args) -> CliResult<()> {
    let input = args.input_file();
    for out in [&args.out, &args.voronoi].into_iter().flatten() {
        check_output(out, input, args.save.force)?;
    }
    if args.polygon.is_some() && args.voronoi.is_some() {
        return Err("--voronoi needs points (FILE or --random), not --polygon".into());
    }
    let (points, triangles, mut summary) = match &args.polygon {
        Some(path) => {
            let domain = read_polygon(path)?;
            let options = RefineOptions { min_angle: args.min_angle, max_area: args.max_area, ..Default::default() };
            let m = refine_polygon(&domain, &options)?;
            let summary = Summary {
                input: path.display().to_string(),
                points: m.input_vertices,
                duplicates: None,
                vertices: m.points.len(),
                triangles: m.triangles.len(),
                complete: Some(m.complete),
                ..Summary::default()
            };
            if !m.complete {
                eprintln!(
                    "mesh: warning: the refinement stopped at its vertex bound; the bounds may not hold everywhere"
                );
            }
            (m.points, m.triangles, summary)
        }
        None => {
            let (name, points) = match (&args.input, args.random) {
                (Some(path), _) => (path.display().to_string(), read_points(path)?),
                (None, Some(n)) if n > MAX_RANDOM => {
                    return Err(format!("--random {n}: at most {MAX_RANDOM} random points").into());
                }
                (None, Some(n)) => (format!("random:{n}:seed {}", args.seed), random_points(n, args.seed)),
                (None, None) => return Err("give a points FILE, --random N, or --polygon FILE".into()),
            };
            let d = delaunay(&points)?;
            let mut summary = Summary {
                input: name,
                points: points.len(),
                duplicates: Some(d.duplicates),
                vertices: points.len() - d.duplicates,
                triangles: d.triangles.len(),
                ..Summary::default()
            };
            let triangles = if args.flips {
                let sweep = sweep_triangulation(&points)?;
                summary.sweep_violations = Some(check_empty_circumcircles(&points, &sweep, 1e-9)?.violations);
                let f = lawson_flips(&points, &sweep, &LawsonOptions::default())?;
                summary.flips = Some(f.flips);
                if !args.save.json {
                    println!("{} Lawson flips from the sweep triangulation", f.flips);
                }
                f.triangles
            } else {
                d.triangles.clone()
            };
            if let Some(path) = &args.voronoi {
                let v = voronoi(&d, &VoronoiOptions::default())?;
                let cells: Vec<Vec<DVec3>> = v
                    .cells
                    .iter()
                    .filter(|c| !c.is_empty())
                    .map(|c| c.iter().chain(c.first()).map(|p| p.extend(0.0)).collect())
                    .collect();
                summary.voronoi_cells = Some(cells.len());
                mesh_io::write_polylines(path, &cells).map_err(crate::errors::io)?;
                eprintln!("wrote {} ({} Voronoi cells)", path.display(), cells.len());
            }
            (points, triangles, summary)
        }
    };
    summary.violations = check_empty_circumcircles(&points, &triangles, 1e-9)?.violations;
    let (mut smallest, mut largest) = (180.0f64, 0.0f64);
    for t in &triangles {
        let [a, b, c] = t.map(|v| points[v as usize]);
        largest = largest.max(0.5 * (b - a).perp_dot(c - a));
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b)] {
            smallest = smallest.min((q - p).angle_to(r - p).abs().to_degrees());
        }
    }
    (summary.min_angle_degrees, summary.max_triangle_area) = (smallest, largest);
    if let Some(out) = &args.out {
        let mesh = TriMesh::new(points.iter().map(|p| p.extend(0.0)).collect(), triangles)?;
        write_mesh(out, &mesh, &args.save.write.options(Default::default()))?;
        eprintln!("wrote {} ({} vertices, {} triangles)", out.display(), mesh.vertex_count(), mesh.face_count());
    }
    if args.save.json {
        print_json(&summary)?;
    } else {
        eprintln!(
            "{}: {} triangles, smallest angle {:.2} degrees, {} circumcircles holding a point",
            summary.input, summary.triangles, summary.min_angle_degrees, summary.violations
        );
    }
    Ok(())
}

fn random_points(n: usize, seed: u64) -> Vec<DVec2> {
    let mut rng = SplitMix64::new(seed);
    (0..n).map(|_| DVec2::new(rng.signed(), rng.signed())).collect()
}

/// Whether a file is read as text points rather than as a mesh.
fn is_text(path: &Path) -> bool {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    matches!(ext.as_deref(), Some("txt" | "xy" | "csv"))
}

/// The points of a text file or of a mesh file's vertices.
fn read_points(path: &Path) -> CliResult<Vec<DVec2>> {
    if is_text(path) {
        let loops = read_text_loops(path)?;
        return Ok(loops.into_iter().flatten().collect());
    }
    let data = read_mesh(path)?;
    Ok(data.mesh.positions().iter().map(|p| p.truncate()).collect())
}

/// A polygon with holes from a text file of loops.
fn read_polygon(path: &Path) -> CliResult<PolygonDomain> {
    let mut loops = read_text_loops(path)?.into_iter();
    let outer = loops.next().ok_or_else(|| format!("{}: no polygon loop in the file", path.display()))?;
    Ok(PolygonDomain { outer, holes: loops.collect() })
}

/// Groups of "x y" lines separated by blank lines; '#' starts a comment;
/// "x,y" and "x y z" (z ignored) are accepted. Bounded: at most 4 GiB and
/// 4096 bytes a line.
fn read_text_loops(path: &Path) -> CliResult<Vec<Vec<DVec2>>> {
    let file = std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let size = file.metadata().map(|m| m.len()).unwrap_or(0);
    if size > MAX_TEXT_BYTES {
        return Err(format!(
            "{}: {size} bytes, more than the {MAX_TEXT_BYTES} a text point file may have",
            path.display()
        )
        .into());
    }
    let mut reader = BufReader::new(file.take(MAX_TEXT_BYTES));
    let mut loops: Vec<Vec<DVec2>> = vec![Vec::new()];
    let mut line = String::new();
    for number in 1.. {
        line.clear();
        let n = (&mut reader)
            .take(MAX_LINE_BYTES + 1)
            .read_line(&mut line)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        if n == 0 {
            break;
        }
        if n as u64 > MAX_LINE_BYTES {
            return Err(format!("{}:{number}: a line longer than {MAX_LINE_BYTES} bytes", path.display()).into());
        }
        let text = line.split('#').next().unwrap_or("").trim();
        if text.is_empty() {
            if loops.last().is_some_and(|l| !l.is_empty()) && line.split('#').count() == 1 {
                loops.push(Vec::new());
            }
            continue;
        }
        let fields: Vec<&str> = text.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).collect();
        let parse = |s: &str| s.parse::<f64>().ok().filter(|x| x.is_finite());
        match fields[..] {
            [x, y] | [x, y, _] => match (parse(x), parse(y)) {
                (Some(x), Some(y)) => {
                    if let Some(l) = loops.last_mut() {
                        l.push(DVec2::new(x, y));
                    }
                }
                _ => return Err(format!("{}:{number}: not two finite numbers: {text:?}", path.display()).into()),
            },
            _ => return Err(format!("{}:{number}: expected \"x y\", found {text:?}", path.display()).into()),
        }
    }
    loops.retain(|l| !l.is_empty());
    Ok(loops)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_loops_are_split_at_blank_lines() {
        let dir = std::env::temp_dir().join(format!("mesh-delaunay-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("loops.txt");
        std::fs::write(&path, "# a square\n0 0\n1,0\n1 1 5\n0 1\n\n\n0.2 0.2\n0.4 0.2\n0.3 0.4\n").expect("write");
        let loops = read_text_loops(&path).expect("valid");
        assert_eq!(loops.iter().map(Vec::len).collect::<Vec<_>>(), vec![4, 3]);
        assert_eq!(loops[0][2], DVec2::new(1.0, 1.0));
        std::fs::write(&path, "0 0\n1 nan\n").expect("write");
        assert!(read_text_loops(&path).is_err());
        std::fs::write(&path, "0 0 0 0\n").expect("write");
        assert!(read_text_loops(&path).is_err());
        std::fs::write(&path, format!("0 {}\n", "1".repeat(5000))).expect("write");
        assert!(read_text_loops(&path).unwrap_err().to_string().contains("longer"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
