//! Writes a mesh as OFF and its distance fields from vertex 0 (one value per
//! line) for every method, so that external tools can compare them, e.g.
//! `scripts/compare_exact.py` against exact polyhedral geodesics.
//!
//! `cargo run --release -p mesh-geodesic --example export_fields -- OUT_DIR [--no-exact] [MESH.off|obj|strip ...]`
//! (without meshes: the unit icosphere level 5, a flat disk, a torus, a cube;
//! `strip` is the flat 1500 x 2 strip of unit squares; `--no-exact` skips the
//! exact method, for meshes too large for it).

use std::io::Write;
use std::path::{Path, PathBuf};

use mesh_geodesic::{dijkstra, exact_distance, heat_distance, FastMarching, FmmOptions, FmmUpdate, HeatOptions};
use mesh_kernel::{shapes, TriMesh, VertexId};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// A minimal OFF / OBJ reader (triangles and fan-triangulated polygons).
fn read(path: &Path) -> Res<TriMesh> {
    let text = std::fs::read_to_string(path)?;
    let (mut positions, mut faces) = (Vec::new(), Vec::new());
    let fan = |idx: &[u32], faces: &mut Vec<[u32; 3]>| {
        for k in 1..idx.len().saturating_sub(1) {
            faces.push([idx[0], idx[k], idx[k + 1]]);
        }
    };
    if path.extension().is_some_and(|e| e == "off") {
        let mut tokens = text.lines().map(|l| l.split('#').next().unwrap_or("")).flat_map(str::split_whitespace);
        tokens.next();
        let mut num = || -> Res<f64> { Ok(tokens.next().ok_or("truncated OFF")?.parse::<f64>()?) };
        let (nv, nf, _) = (num()? as usize, num()? as usize, num()?);
        for _ in 0..nv {
            positions.push(mesh_kernel::glam::DVec3::new(num()?, num()?, num()?));
        }
        for _ in 0..nf {
            let k = num()? as usize;
            let idx = (0..k).map(|_| num().map(|x| x as u32)).collect::<Res<Vec<u32>>>()?;
            fan(&idx, &mut faces);
        }
    } else {
        for line in text.lines() {
            let mut it = line.split_whitespace();
            match it.next() {
                Some("v") => {
                    let c = it.take(3).map(|t| t.parse::<f64>()).collect::<Result<Vec<f64>, _>>()?;
                    positions.push(mesh_kernel::glam::DVec3::new(c[0], c[1], c[2]));
                }
                Some("f") => {
                    let idx = it
                        .map(|t| t.split('/').next().unwrap_or("").parse::<u32>().map(|i| i - 1))
                        .collect::<Result<Vec<u32>, _>>()?;
                    fan(&idx, &mut faces);
                }
                _ => {}
            }
        }
    }
    Ok(TriMesh::new(positions, faces)?)
}

fn write_field(path: PathBuf, d: &[f64]) -> Res<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
    for x in d {
        writeln!(f, "{x:.17}")?;
    }
    Ok(())
}

fn export(dir: &Path, name: &str, m: &TriMesh, exact: bool) -> Res<()> {
    let mut f = std::io::BufWriter::new(std::fs::File::create(dir.join(format!("{name}.off")))?);
    writeln!(f, "OFF\n{} {} 0", m.vertex_count(), m.face_count())?;
    for p in m.positions() {
        writeln!(f, "{:.17} {:.17} {:.17}", p.x, p.y, p.z)?;
    }
    for t in m.faces() {
        writeln!(f, "3 {} {} {}", t[0], t[1], t[2])?;
    }
    let s = [VertexId(0)];
    for update in [FmmUpdate::CurvedFront, FmmUpdate::PointSource, FmmUpdate::PlaneWave] {
        let d = FastMarching::new(m, &FmmOptions { update, ..Default::default() })?.distance(&s)?;
        write_field(dir.join(format!("{name}.fmm-{update:?}.txt")), &d)?;
    }
    write_field(dir.join(format!("{name}.heat.txt")), &heat_distance(m, &s, &HeatOptions::default())?)?;
    write_field(dir.join(format!("{name}.dijkstra.txt")), &dijkstra(m, &s, &Default::default())?.distance)?;
    if !exact {
        return Ok(());
    }
    let start = std::time::Instant::now();
    match exact_distance(m, &s, &Default::default()) {
        Ok(d) => {
            println!("{name}: exact {} vertices in {:.1} ms", m.vertex_count(), start.elapsed().as_secs_f64() * 1e3);
            write_field(dir.join(format!("{name}.exact.txt")), &d)?;
        }
        Err(e) => println!("{name}: exact: {e}"),
    }
    Ok(())
}

fn main() -> Res<()> {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(args.next().ok_or("usage: export_fields OUT_DIR [MESH ...]")?);
    std::fs::create_dir_all(&dir)?;
    let mut args: Vec<String> = args.collect();
    let exact = !args.iter().any(|a| a == "--no-exact");
    args.retain(|a| a != "--no-exact");
    if args.is_empty() {
        export(&dir, "icosphere5", &shapes::icosphere(5)?, exact)?;
        export(&dir, "disk30", &shapes::disk(30, 3)?, exact)?;
        export(&dir, "torus", &shapes::torus(2.0, 0.5, 120, 30)?, exact)?;
        export(&dir, "cube20", &shapes::cube(20)?, exact)?;
    }
    for a in args {
        if a == "strip" {
            export(&dir, "strip1500x2", &shapes::grid(1500.0, 2.0, 1500, 2)?, exact)?;
            continue;
        }
        let f = PathBuf::from(a);
        let name = f.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        export(&dir, &name, &read(&f)?, exact)?;
    }
    Ok(())
}
