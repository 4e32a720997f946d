//! mesh-geodesic operations from vertex 0, named as in peer_bench.py where
//! they match (`dijkstra`, which builds its edge graph in the call, and
//! `dijkstra_query` on a prepared `DijkstraGraph`, like scipy's prebuilt
//! CSR graph; `heat_precompute` / `heat_solve` next to the
//! `_igl` and `_pp3d` figures; `exact_geodesic` next to
//! `exact_geodesic_pygeodesic`).

use std::path::Path;
use std::sync::{Arc, OnceLock};

use mesh_geodesic::{
    dijkstra, exact_distance, farthest_point_sampling, DijkstraGraph, DijkstraOptions, ExactOptions, FastMarching,
    FmmOptions, HeatGeodesics, HeatOptions, SamplingMetric, SamplingOptions,
};
use mesh_io::MeshData;
use mesh_kernel::VertexId;

use super::Operation;

/// The geodesic operations on the (connectivity-cached) mesh.
pub fn operations<'a>(_path: &'a Path, data: &'a MeshData) -> Vec<Operation<'a>> {
    let mesh = &data.mesh;
    let _ = mesh.connectivity();
    let source = [VertexId(0)];
    // Prepared on first use (the untimed warm-up run of `time`).
    let (heat, fmm, graph) = (OnceLock::new(), Arc::new(OnceLock::new()), OnceLock::new());
    let fmm_for_sources = Arc::clone(&fmm);
    vec![
        Operation::new("dijkstra", move || Ok(dijkstra(mesh, &source, &DijkstraOptions::default())?)),
        Operation::new("dijkstra_query", move || {
            Ok(graph.get_or_init(|| DijkstraGraph::new(mesh)).shortest_paths(&source, &DijkstraOptions::default())?)
        }),
        Operation::new("fmm", move || Ok(FastMarching::new(mesh, &FmmOptions::default())?.distance(&source)?)),
        Operation::new("fmm_march", move || {
            match fmm.get_or_init(|| FastMarching::new(mesh, &FmmOptions::default())) {
                Ok(f) => Ok(f.distance(&source)?),
                Err(e) => Err(e.clone().into()),
            }
        }),
        // Eight single-source fields, as for a distance matrix (the marches
        // split between threads).
        Operation::new("fmm_sources_8", move || {
            let sources: Vec<VertexId> = (0..8).map(|i| VertexId::new(i * (mesh.vertex_count() / 8))).collect();
            match fmm_for_sources.get_or_init(|| FastMarching::new(mesh, &FmmOptions::default())) {
                Ok(f) => Ok(f.distances(&sources)?),
                Err(e) => Err(e.clone().into()),
            }
        }),
        // A thousand farthest-point samples on each metric (on a mesh of
        // fewer vertices, until the radius reaches 0).
        Operation::new("fps_1000", move || Ok(farthest_point_sampling(mesh, 1000, &SamplingOptions::default())?)),
        Operation::new("fps_dijkstra_1000", move || {
            let options = SamplingOptions { metric: SamplingMetric::Dijkstra, ..SamplingOptions::default() };
            Ok(farthest_point_sampling(mesh, 1000, &options)?)
        }),
        Operation::new("heat_precompute", move || Ok(HeatGeodesics::new(mesh, &HeatOptions::default())?)),
        Operation::new("heat_solve", move || {
            match heat.get_or_init(|| HeatGeodesics::new(mesh, &HeatOptions::default())) {
                Ok(h) => Ok(h.distance(&source)?),
                Err(e) => Err(e.clone().into()),
            }
        }),
        Operation::new("exact_geodesic", move || Ok(exact_distance(mesh, &source, &ExactOptions::default())?)),
    ]
}
