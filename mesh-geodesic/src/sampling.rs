//! Geodesic sampling: farthest-point sampling and geodesic Voronoi regions
//! (the chapter's geodesic Delaunay / Voronoi tools of section 2.6).
//!
//! Farthest-point sampling (Eldar, Lindenbaum, Porat and Zeevi 1997; Moenning
//! and Dodgson 2003 on surfaces) adds, one at a time, the vertex farthest
//! from all samples so far. The distance to the sample set is kept up to
//! date incrementally: each new sample's front only travels where it is
//! closer than the samples already placed (on a surface, about V / k
//! vertices for the k-th sample), and the next farthest vertex comes from
//! a tournament tree updated at those vertices (O(log V) each) instead of
//! a scan of all V.

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
    let mut front = Front::new(mesh, count, options)?;
    // Fields in the front's own vertex numbering.
    let (mut distance, mut region) = (vec![f64::INFINITY; n], vec![u32::MAX; n]);
    let mut tree = Farthest::new(&front.to_internal(&usable), &distance);
    let (mut seeds, mut radii) = (Vec::with_capacity(count), Vec::with_capacity(count));
    let mut lowered = Vec::new();
    let mut next = Some(start);
    while let Some(seed) = next {
        let label = seeds.len() as u32;
        seeds.push(seed);
        lowered.clear();
        front.add(seed, label, &mut distance, &mut region, &mut lowered);
        tree.lowered(&lowered, &distance);
        // The farthest usable vertex; unreached components first.
        let farthest = tree.vertex();
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
    fn new(mesh: &TriMesh, count: usize, options: &SamplingOptions) -> Result<Self> {
        let n = mesh.vertex_count();
        Ok(match options.metric {
            SamplingMetric::FastMarching => Front::Fmm(FastMarching::new(mesh, &options.fmm)?, March::new(n)),
            SamplingMetric::Dijkstra => {
                Front::Dijkstra(EdgeGraph::new(mesh, robust_lengths(mesh), None), Search::unreached(n, count))
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
    /// where `seed` is closer, appending those vertices to `lowered`.
    fn add(&mut self, seed: VertexId, label: u32, distance: &mut [f64], region: &mut [u32], lowered: &mut Vec<u32>) {
        let seeds = [(seed, label)];
        match self {
            Front::Fmm(fmm, march) => march.run(fmm, &seeds, f64::INFINITY, distance, region, |v| lowered.push(v)),
            Front::Dijkstra(graph, search) => {
                search.propagate(graph, &seeds, f64::INFINITY, |v| lowered.push(v));
                for &v in lowered.iter() {
                    let i = v as usize;
                    (distance[i], region[i]) = (search.distance(i), search.label(i));
                }
            }
        }
    }
}

/// The farthest usable vertex as distances fall: a tournament tree over the
/// vertices whose every node holds the winner of its two children (the
/// larger distance; on a tie the smaller index, which is the left child's),
/// so that a lowered distance costs O(log V) and the question O(1).
struct Farthest {
    /// Leaves from `leaves`: vertex `v` at `leaves + v`, `NONE` where the
    /// vertex is not usable or does not exist; the root at 1.
    winner: Vec<u32>,
    leaves: usize,
}

const NONE: u32 = u32::MAX;

impl Farthest {
    fn new(usable: &[bool], distance: &[f64]) -> Self {
        let leaves = usable.len().next_power_of_two();
        let mut winner = vec![NONE; 2 * leaves];
        for (v, _) in usable.iter().enumerate().filter(|(_, u)| **u) {
            winner[leaves + v] = v as u32;
        }
        let mut tree = Self { winner, leaves };
        tree.replay_all(distance);
        tree
    }

    /// Replays every match, bottom up. O(V).
    fn replay_all(&mut self, distance: &[f64]) {
        for node in (1..self.leaves).rev() {
            self.winner[node] = self.match_of(node, distance);
        }
    }

    /// Brings the tree up to date after the distances of `vertices` fell:
    /// their paths to the root, or every match when that is less work (the
    /// first sample lowers every vertex it reaches).
    fn lowered(&mut self, vertices: &[u32], distance: &[f64]) {
        let depth = self.leaves.trailing_zeros() as usize;
        if vertices.len() * depth > self.leaves {
            self.replay_all(distance);
        } else {
            for &v in vertices {
                self.update(v, distance);
            }
        }
    }

    /// The winner between the two children of `node`.
    #[inline]
    fn match_of(&self, node: usize, distance: &[f64]) -> u32 {
        match (self.winner[2 * node], self.winner[2 * node + 1]) {
            (NONE, b) => b,
            (a, NONE) => a,
            (a, b) if distance[b as usize] > distance[a as usize] => b,
            (a, _) => a,
        }
    }

    /// Replays the matches above vertex `v`, whose distance changed.
    fn update(&mut self, v: u32, distance: &[f64]) {
        let mut node = (self.leaves + v as usize) / 2;
        while node >= 1 {
            self.winner[node] = self.match_of(node, distance);
            node /= 2;
        }
    }

    /// The usable vertex farthest from the samples, if any.
    fn vertex(&self) -> Option<usize> {
        let v = self.winner[1];
        (v != NONE).then_some(v as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::Farthest;
    use mesh_kernel::random::SplitMix64;

    /// After random decreases (ties and infinities included), the tree names
    /// the vertex a scan finds: the largest distance among the usable
    /// vertices, the smallest index on a tie.
    #[test]
    fn the_tree_agrees_with_a_scan() {
        let mut rng = SplitMix64::new(7);
        for n in [1, 2, 3, 37, 64, 1000] {
            let usable: Vec<bool> = (0..n).map(|v| v == 0 || !rng.one_in(5)).collect();
            let mut distance = vec![f64::INFINITY; n];
            let mut tree = Farthest::new(&usable, &distance);
            for step in 0..3 * n {
                let v = rng.below(n);
                // Coarse values, so that ties happen.
                distance[v] = distance[v].min((rng.below(8) * 8 + 8 - step * 8 / (3 * n)) as f64);
                if step % 2 == 0 {
                    tree.update(v as u32, &distance);
                } else {
                    // Either a path or, for the smallest trees, every match.
                    tree.lowered(&[v as u32], &distance);
                }
                let scan =
                    (0..n).filter(|&v| usable[v]).max_by(|&a, &b| distance[a].total_cmp(&distance[b]).then(b.cmp(&a)));
                assert_eq!(tree.vertex(), scan, "n = {n}, step {step}");
            }
        }
        let none = Farthest::new(&[false, false, false], &[1.0; 3]);
        assert_eq!(none.vertex(), None);
    }
}
