//! Geodesic sampling: farthest-point sampling and geodesic Voronoi regions
//! (the chapter's geodesic Delaunay / Voronoi tools of section 2.6).
//!
//! Farthest-point sampling (Eldar, Lindenbaum, Porat and Zeevi 1997; Moenning
//! and Dodgson 2003 on surfaces) adds, one at a time, the vertex farthest
//! from all samples so far. The distance to the sample set is kept up to
//! date incrementally: each new sample's front only travels where it is
//! closer than the samples already placed (on a surface, about V / k
//! vertices for the k-th sample), plus an O(V) scan for the next farthest
//! vertex.

use mesh_kernel::{TriMesh, VertexId, VertexKind};

use crate::dijkstra::{robust_lengths, Search};
use crate::edge_graph::EdgeGraph;
use crate::error::{GeodesicError, Result};
use crate::fmm::{FastMarching, FmmOptions, March};
use crate::support::validate_sources;

/// The distance used for sampling and Voronoi regions.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum SamplingMetric {
    /// Fast Marching geodesic distance ([`crate::FastMarching`]).
    #[default]
    FastMarching,
    /// Edge-graph distance ([`crate::dijkstra()`]): faster, an upper bound.
    Dijkstra,
}

impl SamplingMetric {
    /// Every metric; their [`name`](Self::name)s are what
    /// [`FromStr`](std::str::FromStr) accepts and
    /// [`Display`](std::fmt::Display) writes.
    pub const ALL: [Self; 2] = [Self::FastMarching, Self::Dijkstra];

    /// The name used on the command line: `fmm`, `dijkstra`.
    pub fn name(self) -> &'static str {
        match self {
            Self::FastMarching => "fmm",
            Self::Dijkstra => "dijkstra",
        }
    }
}

mesh_kernel::named_choice!(SamplingMetric, "metric", GeodesicError);

/// Options of [`farthest_point_sampling`] and [`geodesic_voronoi`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SamplingOptions {
    /// The distance. Default [`SamplingMetric::FastMarching`].
    pub metric: SamplingMetric,
    /// The first sample; `None` picks the first vertex used by a face.
    pub start: Option<VertexId>,
    /// Options of the Fast Marching metric.
    pub fmm: FmmOptions,
}

/// Samples with their geodesic Voronoi regions.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GeodesicVoronoi {
    /// The seed vertices, in the order they were given or chosen.
    pub seeds: Vec<VertexId>,
    /// Distance of every vertex to its nearest seed (`+infinity` where no
    /// seed is reachable, e.g. isolated vertices).
    pub distance: Vec<f64>,
    /// Index in `seeds` of every vertex's nearest seed (`u32::MAX` where
    /// unreached).
    pub region: Vec<u32>,
    /// For farthest-point sampling, the covering radius (largest distance
    /// to the samples) after each sample was added; empty otherwise.
    pub radii: Vec<f64>,
}

/// Geodesic Voronoi regions of `seeds`: every vertex labelled with its
/// nearest seed. Cost one multi-source Fast Marching (or Dijkstra),
/// O(V log V).
///
/// ```
/// use mesh_kernel::{shapes, VertexId};
/// use mesh_geodesic::{geodesic_voronoi, SamplingOptions};
///
/// let sphere = shapes::icosphere(3)?;
/// let cells = geodesic_voronoi(&sphere, &[VertexId(0), VertexId(3)], &SamplingOptions::default())?;
/// assert_eq!((cells.region[0], cells.region[3]), (0, 1));
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::NoSources` / `GeodesicError::SourceOutOfRange` for bad seeds; the errors of the chosen
/// metric (Fast Marching or Dijkstra).
pub fn geodesic_voronoi(mesh: &TriMesh, seeds: &[VertexId], options: &SamplingOptions) -> Result<GeodesicVoronoi> {
    validate_sources(mesh, seeds)?;
    let (distance, region) = match options.metric {
        SamplingMetric::FastMarching => FastMarching::new(mesh, &options.fmm)?.distance_and_labels(seeds)?,
        SamplingMetric::Dijkstra => {
            let tree = crate::dijkstra(mesh, seeds, &Default::default())?;
            (tree.distance, tree.source_index)
        }
    };
    Ok(GeodesicVoronoi { seeds: seeds.to_vec(), distance, region, radii: Vec::new() })
}

/// Farthest-point sampling of `count` vertices: starting from
/// [`SamplingOptions::start`], repeatedly adds the vertex farthest from the
/// samples so far (vertices of components without a sample count as
/// infinitely far, so every component is sampled before any is refined;
/// isolated vertices are never chosen). Stops early when every vertex is a
/// sample. Returns the samples with their Voronoi regions (from one final
/// multi-source march) and the covering radius after each step. Cost: the
/// incremental marches (about O(V log V log count) in all), O(V) per sample
/// to find the next one, and the final march.
///
/// ```
/// use mesh_kernel::shapes;
/// use mesh_geodesic::{farthest_point_sampling, SamplingOptions};
///
/// let sphere = shapes::icosphere(3)?;
/// let fps = farthest_point_sampling(&sphere, 6, &SamplingOptions::default())?;
/// assert_eq!(fps.seeds.len(), 6);
/// // Each new sample shrinks the covering radius (or keeps it).
/// assert!(fps.radii.windows(2).all(|w| w[1] <= w[0]));
/// # Ok::<(), mesh_geodesic::GeodesicError>(())
/// ```
///
/// # Errors
/// `GeodesicError::InvalidOption` (`count`) for a count of 0; `GeodesicError::SourceOutOfRange` for a first
/// sample that is not a vertex; `GeodesicError::Mesh` (`MeshError::Empty`) when no vertex is usable; the
/// errors of the chosen metric.
pub fn farthest_point_sampling(mesh: &TriMesh, count: usize, options: &SamplingOptions) -> Result<GeodesicVoronoi> {
    if count == 0 {
        return Err(GeodesicError::InvalidOption { name: "count", reason: "at least one sample is needed".into() });
    }
    let conn = mesh.connectivity();
    let usable: Vec<bool> = conn.vertex_kinds().iter().map(|k| *k != VertexKind::Isolated).collect();
    let start = match options.start {
        Some(s) => {
            validate_sources(mesh, &[s])?;
            s
        }
        None => VertexId::new(usable.iter().position(|u| *u).ok_or(mesh_kernel::MeshError::Empty)?),
    };
    let n = mesh.vertex_count();
    let mut front = Front::new(mesh, options)?;
    // Fields in the front's own vertex numbering.
    let (mut distance, mut region) = (vec![f64::INFINITY; n], vec![u32::MAX; n]);
    let usable = front.to_internal(&usable);
    let (mut seeds, mut radii) = (Vec::with_capacity(count), Vec::with_capacity(count));
    let mut next = Some(start);
    while let Some(seed) = next {
        let label = seeds.len() as u32;
        seeds.push(seed);
        front.add(seed, label, &mut distance, &mut region);
        // The farthest usable vertex; unreached components first.
        let farthest =
            (0..n).filter(|&v| usable[v]).max_by(|&a, &b| distance[a].total_cmp(&distance[b]).then(b.cmp(&a)));
        let radius = farthest.map_or(0.0, |v| distance[v] * front.unit());
        radii.push(radius);
        next = match farthest {
            Some(v) if seeds.len() < count && radius > 0.0 => Some(front.vertex_at(v)),
            _ => None,
        };
    }
    let (distance, region) = match &front {
        // The pruned fronts only approximate the multi-source march near the
        // region borders: return the fresh field and regions of the samples.
        Front::Fmm(fmm, _) => fmm.distance_and_labels(&seeds)?,
        Front::Dijkstra(..) => (distance, region),
    };
    Ok(GeodesicVoronoi { seeds, distance, region, radii })
}

/// Incremental front propagation for either metric.
enum Front {
    Fmm(FastMarching, March),
    /// The edge graph (built once for all samples) and the search's state.
    Dijkstra(EdgeGraph, Search),
}

impl Front {
    fn new(mesh: &TriMesh, options: &SamplingOptions) -> Result<Self> {
        let n = mesh.vertex_count();
        Ok(match options.metric {
            SamplingMetric::FastMarching => Front::Fmm(FastMarching::new(mesh, &options.fmm)?, March::new(n)),
            SamplingMetric::Dijkstra => {
                Front::Dijkstra(EdgeGraph::new(mesh, robust_lengths(mesh), None), Search::unreached(n))
            }
        })
    }

    /// A per-vertex mask in the front's numbering.
    fn to_internal(&self, mask: &[bool]) -> Vec<bool> {
        match self {
            Front::Fmm(fmm, _) => (0..mask.len()).map(|i| mask[fmm.vertex_at(i).idx()]).collect(),
            Front::Dijkstra(..) => mask.to_vec(),
        }
    }

    /// What the front's distances are multiplied by to be in the mesh's unit.
    fn unit(&self) -> f64 {
        match self {
            Front::Fmm(fmm, _) => fmm.unit,
            Front::Dijkstra(..) => 1.0,
        }
    }

    /// The mesh vertex at an index of the front's numbering.
    fn vertex_at(&self, i: usize) -> VertexId {
        match self {
            Front::Fmm(fmm, _) => fmm.vertex_at(i),
            Front::Dijkstra(..) => VertexId::new(i),
        }
    }

    /// Lowers `distance` and relabels `region` (in the front's numbering)
    /// where `seed` is closer.
    fn add(&mut self, seed: VertexId, label: u32, distance: &mut [f64], region: &mut [u32]) {
        match self {
            Front::Fmm(fmm, march) => march.run(fmm, &[(seed, label)], f64::INFINITY, distance, region),
            Front::Dijkstra(graph, search) => {
                search.propagate(graph, &[(seed, label)], f64::INFINITY);
                for (i, (d, r)) in distance.iter_mut().zip(region.iter_mut()).enumerate() {
                    (*d, *r) = (search.distance(i), search.label(i));
                }
            }
        }
    }
}
