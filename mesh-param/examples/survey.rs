//! Runs every method on a mesh file (OFF) and prints the distortion summary:
//! `cargo run -p mesh-param --release --example survey -- FILE.off`.

use glam::DVec3;
use mesh_kernel::TriMesh;
use mesh_param::{parameterize_cut, ParamMethod, ParamOptions};

fn read_off(path: &str) -> Result<TriMesh, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(path)?;
    let mut t = text.lines().filter(|l| !l.starts_with('#')).flat_map(|l| l.split_whitespace()).skip(1);
    let mut num = || -> Result<f64, Box<dyn std::error::Error>> { Ok(t.next().ok_or("truncated")?.parse()?) };
    let (nv, nf, _) = (num()? as usize, num()? as usize, num()?);
    let mut p = Vec::with_capacity(nv);
    for _ in 0..nv {
        p.push(DVec3::new(num()?, num()?, num()?));
    }
    let mut f = Vec::with_capacity(nf);
    for _ in 0..nf {
        let k = num()? as usize;
        let c: Vec<u32> = (0..k).map(|_| num().map(|x| x as u32)).collect::<Result<_, _>>()?;
        for i in 1..k.saturating_sub(1) {
            f.push([c[0], c[i], c[i + 1]]);
        }
    }
    Ok(TriMesh::new(p, f)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).ok_or("usage: survey FILE.off")?;
    let mesh = read_off(&path)?;
    println!("{path}: {} vertices, {} faces", mesh.vertex_count(), mesh.face_count());
    println!(
        "{:<11} {:>7} {:>7} {:>9} {:>9} {:>8} {:>8} {:>5} {:>5} {:>9}",
        "method", "seam", "ms", "angle", "angle max", "area", "area max", "flip", "bij", "E_D/A"
    );
    for method in ParamMethod::ALL {
        let name = method.name();
        let t = std::time::Instant::now();
        match parameterize_cut(&mesh, &ParamOptions { method, ..Default::default() }) {
            Ok(p) => {
                let s = p.param.report.summary;
                println!(
                    "{name:<11} {:>7} {:>7.1} {:>9.4} {:>9.2} {:>8.4} {:>8.2} {:>5} {:>5} {:>9.5}",
                    p.cut.seam.len(),
                    t.elapsed().as_secs_f64() * 1e3,
                    s.angle_distortion_mean,
                    s.angle_distortion_max,
                    s.area_distortion_mean,
                    s.area_distortion_max,
                    s.flipped_faces + s.collapsed_faces,
                    s.bijective,
                    s.dirichlet_area_ratio
                );
            }
            Err(e) => println!("{name:<11} error: {e}"),
        }
    }
    Ok(())
}
