//! mesh-wavelet operations, named as in peer_bench.py where they match
//! (`loop_subdivision_1`, `upsample_1`). The filter-bank operations run on
//! the input split twice by the midpoint scheme, which always has
//! subdivision connectivity: `wavelet_detect_2` (reverse 4-to-1 splitting),
//! `wavelet_bank_2` (lifted midpoint filter bank setup), `wavelet_analysis_2`
//! and `wavelet_synthesis_2` (the in-place lifting steps).

use std::path::Path;
use std::sync::{Arc, OnceLock};

use mesh_io::MeshData;
use mesh_kernel::glam::DVec3;
use mesh_kernel::TriMesh;
use mesh_wavelet::{detect, subdivide, FilterBank, Scheme, SubdivideOptions, WaveletKind};

use super::{fresh, Operation};

/// The semi-regular input of the filter-bank operations and what they
/// start from, built on first use (the untimed warm-up run).
struct Setup {
    fine: TriMesh,
    hierarchy: mesh_wavelet::Hierarchy,
    bank: FilterBank,
    /// The fine positions in the hierarchy's order.
    data: Vec<DVec3>,
    /// `data` analyzed.
    coefficients: Vec<DVec3>,
}

/// [`Setup`] shared by the operations, made once.
type Prepared = Arc<OnceLock<Result<Setup, String>>>;

fn prepared<'b>(cell: &'b Prepared, mesh: &TriMesh) -> crate::Result<&'b Setup> {
    let made = cell.get_or_init(|| {
        let run = || -> Result<Setup, mesh_wavelet::WaveletError> {
            let fine = subdivide(mesh, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 2 })?;
            let hierarchy = detect(&fine, &Default::default())?;
            let bank = FilterBank::new(&hierarchy, Scheme::Midpoint, WaveletKind::Lifted)?;
            let data: Vec<DVec3> =
                (0..fine.vertex_count()).map(|v| fine.positions()[hierarchy.input_index(v).unwrap_or(v)]).collect();
            let mut coefficients = data.clone();
            bank.analyze(&mut coefficients)?;
            Ok(Setup { fine, hierarchy, bank, data, coefficients })
        };
        run().map_err(|e| e.to_string())
    });
    made.as_ref().map_err(|e| e.clone().into())
}

/// The subdivision and filter-bank operations.
pub fn operations<'a>(_path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let mut ops = vec![
        Operation::on_fresh("loop_subdivision_1", mesh, |m| {
            Ok(subdivide(&m, &SubdivideOptions { scheme: Scheme::Loop, levels: 1 })?)
        }),
        Operation::on_fresh("upsample_1", mesh, |m| {
            Ok(subdivide(&m, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 1 })?)
        }),
        Operation::on_fresh("butterfly_subdivision_1", mesh, |m| {
            Ok(subdivide(&m, &SubdivideOptions { scheme: Scheme::Butterfly, levels: 1 })?)
        }),
    ];
    let shared = Prepared::default();
    let (f, hb, b, w) = (shared.clone(), shared.clone(), shared.clone(), shared);
    ops.push(Operation::after(
        "wavelet_detect_2",
        move || prepared(&f, mesh).map(|p| fresh(&p.fine)),
        |fine| Ok(detect(&fine?, &Default::default())?),
    ));
    ops.push(Operation::new("wavelet_bank_2", move || {
        Ok(FilterBank::new(&prepared(&hb, mesh)?.hierarchy, Scheme::Midpoint, WaveletKind::Lifted)?)
    }));
    ops.push(Operation::new("wavelet_analysis_2", move || {
        let p = prepared(&b, mesh)?;
        let mut x = p.data.clone();
        p.bank.analyze(&mut x)?;
        Ok(x)
    }));
    ops.push(Operation::new("wavelet_synthesis_2", move || {
        let p = prepared(&w, mesh)?;
        let mut x = p.coefficients.clone();
        p.bank.synthesize(&mut x)?;
        Ok(x)
    }));
    ops
}
