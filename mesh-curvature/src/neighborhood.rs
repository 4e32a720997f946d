//! Vertex neighbourhoods: k-rings and geodesic-like balls, gathered by
//! breadth-first search over the mesh edges.

use glam::DVec3;
use mesh_kernel::TriMesh;

use crate::error::{CurvatureError, Result};

/// Which vertices around a vertex an estimator averages or fits over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Neighborhood {
    /// The k-ring: vertices at most `k` edges away (`Rings(1)` is the vertex
    /// and its neighbours). `k` must be at least 1.
    Rings(u32),
    /// A geodesic ball: the vertices within Euclidean distance `radius` of the
    /// centre that are connected to it through such vertices (the connected
    /// part of the surface inside the ball, so a nearby sheet that is far
    /// along the surface is not picked up). `radius` must be positive.
    Ball(f64),
}

impl Default for Neighborhood {
    fn default() -> Self {
        Self::Rings(1)
    }
}

impl Neighborhood {
    /// The same neighbourhood on the mesh divided by `unit` (a ball's radius
    /// is a length).
    pub(crate) fn in_unit(self, unit: f64) -> Self {
        match self {
            Self::Ball(r) => Self::Ball(r / unit),
            rings => rings,
        }
    }

    /// Checks the parameter.
    ///
    /// # Errors
    /// `CurvatureError::InvalidOption` (`rings`) for 0 rings, (`radius`) for a radius that is not finite and
    /// positive.
    pub fn validate(self) -> Result<Self> {
        match self {
            Self::Rings(0) => Err(CurvatureError::InvalidOption { name: "rings", reason: "must be at least 1".into() }),
            Self::Ball(r) if !(r > 0.0 && r.is_finite()) => Err(CurvatureError::InvalidOption {
                name: "radius",
                reason: format!("must be positive and finite, got {r}"),
            }),
            _ => Ok(self),
        }
    }
}

/// Vertex adjacency in compressed rows, from the mesh edges. O(V + E).
#[derive(Debug, Clone)]
pub(crate) struct Adjacency {
    offsets: Vec<u32>,
    targets: Vec<u32>,
}

impl Adjacency {
    pub fn new(mesh: &TriMesh) -> Self {
        let edges = mesh.connectivity().edges();
        let n = mesh.vertex_count();
        let mut offsets = vec![0u32; n + 1];
        for [a, b] in edges {
            offsets[a.idx() + 1] += 1;
            offsets[b.idx() + 1] += 1;
        }
        for i in 0..n {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut targets = vec![0u32; offsets[n] as usize];
        for [a, b] in edges {
            targets[fill[a.idx()] as usize] = b.0;
            fill[a.idx()] += 1;
            targets[fill[b.idx()] as usize] = a.0;
            fill[b.idx()] += 1;
        }
        Self { offsets, targets }
    }

    #[inline]
    pub fn neighbors(&self, v: usize) -> &[u32] {
        &self.targets[self.offsets[v] as usize..self.offsets[v + 1] as usize]
    }
}

/// Reusable breadth-first search state (one per worker thread).
#[derive(Debug, Clone, Default)]
pub(crate) struct Gatherer {
    stamp: Vec<u32>,
    current: u32,
    /// The gathered vertices, centre first, in breadth-first order.
    pub vertices: Vec<u32>,
    /// The ring (edge distance) of each gathered vertex.
    pub rings: Vec<u32>,
}

impl Gatherer {
    /// Gathers the neighbourhood of `centre` into `self.vertices`. Each vertex
    /// is visited at most once, so the cost is bounded by the size of the
    /// neighbourhood and its edges.
    pub fn gather(&mut self, adj: &Adjacency, positions: &[DVec3], centre: usize, nbh: Neighborhood) {
        if self.stamp.len() != positions.len() {
            self.stamp = vec![0; positions.len()];
            self.current = 0;
        }
        self.current = self.current.wrapping_add(1);
        if self.current == 0 {
            self.stamp.fill(0);
            self.current = 1;
        }
        let mark = self.current;
        self.vertices.clear();
        self.rings.clear();
        self.vertices.push(centre as u32);
        self.rings.push(0);
        self.stamp[centre] = mark;
        let c = positions[centre];
        let (max_ring, radius2) = match nbh {
            Neighborhood::Rings(k) => (k, f64::INFINITY),
            Neighborhood::Ball(r) => (u32::MAX, r * r),
        };
        let mut head = 0;
        while head < self.vertices.len() {
            let (v, ring) = (self.vertices[head] as usize, self.rings[head]);
            head += 1;
            if ring >= max_ring {
                continue;
            }
            for &w in adj.neighbors(v) {
                let wi = w as usize;
                if self.stamp[wi] == mark {
                    continue;
                }
                self.stamp[wi] = mark;
                if positions[wi].distance_squared(c) <= radius2 {
                    self.vertices.push(w);
                    self.rings.push(ring + 1);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_kernel::shapes;

    #[test]
    fn rings_of_a_regular_grid() {
        let m = shapes::torus(2.0, 0.5, 32, 16).unwrap();
        let adj = Adjacency::new(&m);
        let mut g = Gatherer::default();
        for (k, count) in [(1, 7), (2, 19), (3, 37)] {
            g.gather(&adj, m.positions(), 40, Neighborhood::Rings(k));
            assert_eq!(g.vertices.len(), count);
        }
        // A ball smaller than every edge holds only the centre.
        g.gather(&adj, m.positions(), 40, Neighborhood::Ball(1e-3));
        assert_eq!(g.vertices, vec![40]);
    }

    #[test]
    fn bad_options_are_errors() {
        assert!(Neighborhood::Rings(0).validate().is_err());
        assert!(Neighborhood::Ball(f64::NAN).validate().is_err());
        assert!(Neighborhood::Ball(-1.0).validate().is_err());
        assert!(Neighborhood::Ball(0.5).validate().is_ok());
    }
}
