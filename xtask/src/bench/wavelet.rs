//! mesh-wavelet operations, named as in peer_bench.py where they match
//! (`loop_subdivision_1`, `upsample_1`). The filter-bank operations run on
//! the input split twice by the midpoint scheme, which always has
//! subdivision connectivity: `wavelet_detect_2` (reverse 4-to-1 splitting),
//! `wavelet_bank_2` (lifted midpoint filter bank setup), `wavelet_analysis_2`
//! and `wavelet_synthesis_2` (the in-place lifting steps).

use std::path::Path;
use std::sync::Arc;

use mesh_io::MeshData;
use mesh_kernel::glam::DVec3;
use mesh_kernel::TriMesh;
use mesh_wavelet::{detect, subdivide, FilterBank, Scheme, SubdivideOptions, WaveletKind};

use super::Operation;

/// A copy of the mesh without its cached connectivity.
fn fresh(mesh: &TriMesh) -> TriMesh {
    // Positions and faces were validated when the mesh was built.
    TriMesh::new(mesh.positions().to_vec(), mesh.faces().to_vec()).expect("copy of a valid mesh")
}

/// The subdivision and filter-bank operations.
pub fn operations<'a>(_path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let mut ops = vec![
        Operation::new("loop_subdivision_1", move || {
            Ok(subdivide(&fresh(mesh), &SubdivideOptions { scheme: Scheme::Loop, levels: 1 })?)
        }),
        Operation::new("upsample_1", move || {
            Ok(subdivide(&fresh(mesh), &SubdivideOptions { scheme: Scheme::Midpoint, levels: 1 })?)
        }),
        Operation::new("butterfly_subdivision_1", move || {
            Ok(subdivide(&fresh(mesh), &SubdivideOptions { scheme: Scheme::Butterfly, levels: 1 })?)
        }),
    ];
    // The semi-regular input of the filter-bank operations, built once.
    let prepared = subdivide(mesh, &SubdivideOptions { scheme: Scheme::Midpoint, levels: 2 }).and_then(|fine| {
        let h = Arc::new(detect(&fine, &Default::default())?);
        let bank = Arc::new(FilterBank::new(&h, Scheme::Midpoint, WaveletKind::Lifted)?);
        Ok((Arc::new(fine), h, bank))
    });
    match prepared {
        Ok((fine, h, bank)) => {
            let data: Arc<Vec<DVec3>> =
                Arc::new((0..fine.vertex_count()).map(|v| fine.positions()[h.input_index(v).unwrap_or(v)]).collect());
            let mut coefficients = data.to_vec();
            let analyzed = bank.analyze(&mut coefficients).map(|()| Arc::new(coefficients));
            let (f, hb, b, d) = (fine.clone(), h.clone(), bank.clone(), data.clone());
            ops.push(Operation::new("wavelet_detect_2", move || Ok(detect(&fresh(&f), &Default::default())?)));
            ops.push(Operation::new("wavelet_bank_2", move || {
                Ok(FilterBank::new(&hb, Scheme::Midpoint, WaveletKind::Lifted)?)
            }));
            ops.push(Operation::new("wavelet_analysis_2", move || {
                let mut x = d.to_vec();
                b.analyze(&mut x)?;
                Ok(x)
            }));
            match analyzed {
                Ok(w) => ops.push(Operation::new("wavelet_synthesis_2", move || {
                    let mut x = w.to_vec();
                    bank.synthesize(&mut x)?;
                    Ok(x)
                })),
                Err(e) => {
                    let msg = e.to_string();
                    ops.push(Operation::new("wavelet_synthesis_2", move || -> crate::Result<()> {
                        Err(msg.clone().into())
                    }))
                }
            }
        }
        Err(e) => {
            let msg = e.to_string();
            for name in ["wavelet_detect_2", "wavelet_bank_2", "wavelet_analysis_2", "wavelet_synthesis_2"] {
                let msg = msg.clone();
                ops.push(Operation::new(name, move || -> crate::Result<()> { Err(msg.clone().into()) }));
            }
        }
    }
    ops
}
