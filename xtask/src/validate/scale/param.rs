//! Part 4 of the scale checks: a texture atlas of any mesh. On the full
//! Stanford dragon (151 components, genus 46, 108 zero-area faces) and the
//! dirty dragon scan (cleaned into an oriented manifold first), with Tutte,
//! harmonic and LSCM charts: the atlas is built, every face has finite UVs
//! in [0, 1]^2 inside its chart's box, no two chart boxes meet, and no
//! Tutte face is flipped or collapsed (zero-area surface faces included:
//! Tutte's weights ignore geometry); the same for Tutte charts of at most
//! about 5,000 faces split until their mean area distortion is at most 2. The invariants are
//! measured on the corner UVs themselves, not taken from the atlas's own
//! summary.

use std::time::Instant;

use mesh_kernel::clean::CleanOptions;
use mesh_kernel::glam::DVec2;
use mesh_kernel::TriMesh;
use mesh_param::{atlas, Atlas, AtlasOptions, ParamMethod, UvRect};

use super::{ScaleMeshes, Validator};

/// Runs the atlas checks.
pub fn run(v: &mut Validator, meshes: &ScaleMeshes) {
    for (name, mesh) in [("dragon_vrip", meshes.dragon_full()), ("npm_dragon_res3", meshes.dragon_res3())] {
        let mesh = match mesh {
            Ok(m) => m,
            Err(e) => {
                v.skip(format!("{name}: atlas"), e.to_owned());
                continue;
            }
        };
        let cleaned = match manifold(mesh) {
            Ok(m) => m,
            Err(e) => {
                v.error(format!("{name}: cleaned into an oriented manifold"), e);
                continue;
            }
        };
        let mesh = cleaned.as_ref().unwrap_or(mesh);
        for method in [ParamMethod::Tutte, ParamMethod::Harmonic, ParamMethod::Lscm] {
            check_method(v, name, mesh, method, None);
        }
        check_method(v, name, mesh, ParamMethod::Tutte, Some((5000, 2.0)));
    }
}

/// `None` when the mesh is an oriented manifold already, else the cleaned
/// mesh (or why cleaning could not make it one).
fn manifold(mesh: &TriMesh) -> Result<Option<TriMesh>, String> {
    if mesh.manifold_connectivity().is_ok() {
        return Ok(None);
    }
    let options = CleanOptions { manifold: true, ..CleanOptions::default() };
    let (cleaned, _) = mesh.cleaned(&options).map_err(|e| e.to_string())?;
    cleaned.manifold_connectivity().map_err(|e| format!("after cleaning: {e}"))?;
    Ok(Some(cleaned))
}

/// One atlas and its checks; `split` bounds the charts (faces, mean area
/// distortion).
fn check_method(v: &mut Validator, name: &str, mesh: &TriMesh, method: ParamMethod, split: Option<(usize, f64)>) {
    let bound = split.map_or(String::new(), |(n, d)| format!(", charts <= ~{n} faces, area distortion <= {d}"));
    let label = format!("{name} {}{bound}", method.name());
    let options = AtlasOptions {
        method,
        max_chart_faces: split.map(|s| s.0),
        max_area_distortion: split.map(|s| s.1),
        ..AtlasOptions::default()
    };
    let start = Instant::now();
    let a = match atlas(mesh, &options) {
        Ok(a) => a,
        Err(e) => return v.error(format!("{label}: atlas"), e),
    };
    let seconds = start.elapsed().as_secs_f64();
    let s = &a.summary;
    let d = &s.distortion;
    v.holds(
        format!("{label}: atlas"),
        s.charts > 0,
        format!(
            "{seconds:.1} s, {} charts ({} fallback), coverage {:.2}, angle distortion mean {:.3}, area distortion mean {:.3e}",
            s.charts, s.fallback_charts, s.coverage, d.angle_distortion_mean, d.area_distortion_mean
        ),
    );
    let found = Invariants::of(mesh, &a);
    v.equal(format!("{label}: faces with a UV outside [0, 1]^2 or not finite"), found.outside_square as i64, 0);
    v.equal(format!("{label}: faces outside their chart's box"), found.outside_box as i64, 0);
    v.equal(format!("{label}: pairs of chart boxes that meet"), found.meeting_boxes as i64, 0);
    if method == ParamMethod::Tutte {
        v.equal(format!("{label}: flipped faces"), found.flipped as i64, 0);
        v.equal(format!("{label}: collapsed faces (zero-area surface faces included)"), found.collapsed as i64, 0);
    }
}

/// The atlas's invariants, counted from the corner UVs and chart boxes.
struct Invariants {
    outside_square: usize,
    outside_box: usize,
    meeting_boxes: usize,
    flipped: usize,
    collapsed: usize,
}

impl Invariants {
    fn of(mesh: &TriMesh, a: &Atlas) -> Self {
        let unit = UvRect { min: DVec2::ZERO, max: DVec2::ONE };
        let inside = |r: &UvRect, t: &[DVec2; 3]| t.iter().all(|q| q.is_finite() && r.contains(*q));
        let faces = a.corner_uvs.len().min(mesh.face_count());
        let outside_square = mesh.face_count() - (0..faces).filter(|&f| inside(&unit, &a.corner_uvs[f])).count();
        let outside_box = (0..faces)
            .filter(|&f| a.charts.get(a.face_chart[f] as usize).is_none_or(|c| !inside(&c.rect, &a.corner_uvs[f])))
            .count();
        let doubled = |t: &[DVec2; 3]| (t[1] - t[0]).perp_dot(t[2] - t[0]);
        let flipped = a.corner_uvs.iter().filter(|t| doubled(t) < 0.0).count();
        let collapsed = a.corner_uvs.iter().filter(|t| doubled(t) == 0.0).count();
        Self { outside_square, outside_box, meeting_boxes: meeting_pairs(a), flipped, collapsed }
    }
}

/// Pairs of chart boxes that overlap or touch: sweep over boxes sorted by
/// their left side. O(c log c + pairs tested).
fn meeting_pairs(a: &Atlas) -> usize {
    let mut rects: Vec<UvRect> = a.charts.iter().map(|c| c.rect).collect();
    rects.sort_by(|p, q| p.min.x.total_cmp(&q.min.x));
    let mut count = 0;
    for (i, r) in rects.iter().enumerate() {
        count += rects[i + 1..].iter().take_while(|q| q.min.x <= r.max.x).filter(|q| r.meets(q)).count();
    }
    count
}
