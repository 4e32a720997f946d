//! A minimal OFF / OBJ reader for the shared meshes, so that the tests of a
//! crate below mesh-io do not depend on mesh-io's state.

use std::path::Path;

/// Vertex positions and triangles, before any validation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RawMesh {
    /// Vertex positions, in file order.
    pub positions: Vec<[f64; 3]>,
    /// Triangles (zero-based); polygons are split as fans from their first corner.
    pub faces: Vec<[u32; 3]>,
}

/// Reads an OFF (by extension `.off`) or OBJ file: vertices, and faces as
/// fans; `#` comments, blank lines and repeated spaces allowed; OBJ texture
/// and normal indices (`v/vt/vn`) ignored. O(file size).
///
/// # Errors
/// A message naming the file for an unreadable file, another extension, a
/// truncated OFF, or a token that is not a number or index.
pub fn read_raw(path: &Path) -> Result<RawMesh, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let mesh = match ext.as_deref() {
        Some("off") => parse_off(&text),
        Some("obj") => parse_obj(&text),
        // Parsing another format as OBJ would give an empty mesh, silently.
        _ => Err("read_raw reads .obj and .off only (use mesh-io for other formats)".into()),
    };
    mesh.map_err(|e| format!("{}: {e}", path.display()))
}

/// Every mesh of [`SHARED_MESHES`](crate::data::SHARED_MESHES) read with
/// [`read_raw`], by file name; empty (with the skip or failure of
/// [`shared_data`](crate::shared_data)) when the data is absent.
/// O(total file size).
///
/// # Panics
/// When a listed file is missing or malformed (incomplete data).
pub fn shared_meshes() -> Vec<(&'static str, RawMesh)> {
    let Some(dir) = crate::shared_data() else { return Vec::new() };
    let read = |name: &'static str| read_raw(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
    crate::data::SHARED_MESHES.iter().map(|m| (m.name, read(m.name))).collect()
}

/// Appends the fan triangulation of one polygon.
fn fan(poly: &[u32], faces: &mut Vec<[u32; 3]>) {
    for k in 1..poly.len().saturating_sub(1) {
        faces.push([poly[0], poly[k], poly[k + 1]]);
    }
}

fn parse_off(text: &str) -> Result<RawMesh, String> {
    let mut tokens = text.lines().map(|l| l.split('#').next().unwrap_or("")).flat_map(str::split_whitespace);
    if tokens.next() != Some("OFF") {
        return Err("no OFF header".into());
    }
    let mut next = || tokens.next().ok_or_else(|| "truncated OFF".to_string());
    let count = |t: &str| t.parse::<usize>().map_err(|_| format!("bad count `{t}`"));
    let (nv, nf) = (count(next()?)?, count(next()?)?);
    next()?;
    let mut mesh = RawMesh::default();
    for _ in 0..nv {
        let mut p = [0.0; 3];
        for c in &mut p {
            let t = next()?;
            *c = t.parse().map_err(|_| format!("bad coordinate `{t}`"))?;
        }
        mesh.positions.push(p);
    }
    for _ in 0..nf {
        let k = count(next()?)?;
        let poly = (0..k)
            .map(|_| next().and_then(|t| t.parse::<u32>().map_err(|_| format!("bad index `{t}`"))))
            .collect::<Result<Vec<u32>, String>>()?;
        fan(&poly, &mut mesh.faces);
    }
    Ok(mesh)
}

fn parse_obj(text: &str) -> Result<RawMesh, String> {
    let mut mesh = RawMesh::default();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c = it.take(3).map(str::parse::<f64>).collect::<Result<Vec<f64>, _>>();
                match c.as_deref() {
                    Ok(&[x, y, z]) => mesh.positions.push([x, y, z]),
                    _ => return Err(format!("bad vertex line `{line}`")),
                }
            }
            Some("f") => {
                let index = |t: &str| {
                    let i = t.split('/').next().and_then(|i| i.parse::<u32>().ok());
                    i.and_then(|i| i.checked_sub(1)).ok_or_else(|| format!("bad face index `{t}`"))
                };
                let poly = it.map(index).collect::<Result<Vec<u32>, String>>()?;
                fan(&poly, &mut mesh.faces);
            }
            _ => {}
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygons_become_fans_and_comments_are_skipped() {
        let off = parse_off("OFF # a square\n\n4 1 0\n0 0 0\n1  0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n").unwrap();
        assert_eq!(off.positions.len(), 4);
        assert_eq!(off.faces, vec![[0, 1, 2], [0, 2, 3]]);
        let obj = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n").unwrap();
        assert_eq!(obj, off);
    }

    #[test]
    fn malformed_files_are_errors() {
        assert!(parse_off("OFF\n3 1 0\n0 0 0\n").is_err());
        assert!(parse_off("PLY\n").is_err());
        assert!(parse_obj("f 0 1 2\n").is_err());
        assert!(parse_obj("v 1 x 0\n").is_err());
    }

    #[test]
    fn every_shared_mesh_reads_with_its_counts() {
        let meshes = shared_meshes();
        for (m, (name, raw)) in crate::data::SHARED_MESHES.iter().zip(&meshes) {
            assert_eq!(m.name, *name);
            assert_eq!((raw.positions.len(), raw.faces.len()), (m.vertices, m.faces), "{name}");
        }
    }
}
