//! The propagation: a vertex queue drives the window lists of the
//! half-edges (vertex-oriented triangle propagation, Qin, Han, Yu, Yu and
//! Zhang 2016), each list crossing its face as a group.

use std::collections::{BinaryHeap, VecDeque};

use mesh_kernel::glam::DVec2;
use mesh_kernel::{Connectivity, HalfedgeId, VertexId};

use super::layout::Layout;
use super::window::{Window, PRUNE_MARGIN};
use crate::error::{GeodesicError, Result};
use crate::support::HeapEntry;

/// Where a vertex stands in the vertex queue's sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sweep {
    /// Not popped yet.
    Ahead,
    /// Popped: the window lists of its edges are propagated as they fill.
    Inside,
}

/// The state of one propagation.
pub(super) struct Propagation<'a> {
    conn: &'a Connectivity,
    geo: &'a Layout,
    pub distance: Vec<f64>,
    sweep: Vec<Sweep>,
    vertices: BinaryHeap<HeapEntry>,
    /// Per half-edge: the windows that crossed its edge into its face and
    /// wait to cross the face.
    lists: Vec<Vec<Window>>,
    /// Popped pseudo-sources whose distance dropped, to emit again (with
    /// that distance; stale entries are skipped).
    reemit: Vec<HeapEntry>,
    /// Half-edges whose list waits in `fifo`.
    queued: Vec<bool>,
    fifo: VecDeque<u32>,
    /// The list being propagated (its buffer is swapped with the
    /// half-edge's, so that capacity is reused).
    batch: Vec<Window>,
    /// Per half-edge: the shortest distance to the apex C found through it,
    /// and where that path crosses the edge.
    through_apex: Vec<(f64, f64)>,
    created: usize,
    max_windows: usize,
}

impl<'a> Propagation<'a> {
    pub fn new(conn: &'a Connectivity, geo: &'a Layout, max_windows: usize) -> Self {
        let nh = geo.len.len();
        Self {
            conn,
            geo,
            distance: vec![f64::INFINITY; conn.vertex_count()],
            sweep: vec![Sweep::Ahead; conn.vertex_count()],
            vertices: BinaryHeap::new(),
            reemit: Vec::new(),
            lists: vec![Vec::new(); nh],
            queued: vec![false; nh],
            fifo: VecDeque::new(),
            batch: Vec::new(),
            through_apex: vec![(f64::INFINITY, 0.0); nh],
            created: 0,
            max_windows,
        }
    }

    /// Makes `s` a source (distance 0).
    pub fn set_source(&mut self, s: VertexId) {
        if self.distance[s.idx()] > 0.0 {
            self.distance[s.idx()] = 0.0;
            self.vertices.push(HeapEntry { distance: 0.0, vertex: s.0 });
        }
    }

    /// Pops vertices nearest first; each one (Dijkstra-like) relaxes its
    /// edges, emits windows if it is a source or pseudo-source, and sends
    /// the window lists around it across their faces, which keep going
    /// (first in, first out) while they touch a popped vertex.
    ///
    /// # Errors
    /// `GeodesicError::WorkLimit` once more windows than the bound were created.
    pub fn run(&mut self) -> Result<()> {
        while let Some(e) = self.vertices.pop() {
            let v = VertexId(e.vertex);
            if e.distance > self.distance[v.idx()] || self.sweep[v.idx()] == Sweep::Inside {
                continue; // stale
            }
            self.sweep[v.idx()] = Sweep::Inside;
            for h in self.conn.outgoing(v).iter().copied() {
                let d = self.distance[v.idx()] + self.geo.len[h.idx()];
                self.offer(self.conn.dest(h), d);
                let p = h.prev();
                let d = self.distance[v.idx()] + self.geo.len[p.idx()];
                self.offer(self.conn.origin(p), d);
            }
            if e.distance == 0.0 || self.geo.pseudo_source[v.idx()] {
                self.emit_from_vertex(v)?;
            }
            for h in self.conn.outgoing(v).iter().copied() {
                for g in [h, h.prev(), h.next()] {
                    self.enqueue(g);
                    if let Some(t) = self.conn.twin(g) {
                        self.enqueue(t);
                    }
                }
            }
            loop {
                if let Some(e) = self.reemit.pop() {
                    if e.distance == self.distance[e.vertex as usize] {
                        self.emit_from_vertex(VertexId(e.vertex))?;
                    }
                } else if let Some(h) = self.fifo.pop_front() {
                    self.queued[h as usize] = false;
                    self.propagate_list(HalfedgeId(h))?;
                } else {
                    break;
                }
            }
        }
        Ok(())
    }

    /// Queues the list of `h` unless it is empty or queued.
    fn enqueue(&mut self, h: HalfedgeId) {
        if !self.lists[h.idx()].is_empty() && !self.queued[h.idx()] {
            self.queued[h.idx()] = true;
            self.fifo.push_back(h.0);
        }
    }

    /// Lowers the distance of `v` to `d` if smaller: queued if not popped
    /// yet; a popped pseudo-source is queued to emit its windows again.
    fn offer(&mut self, v: VertexId, d: f64) {
        if d < self.distance[v.idx()] {
            self.distance[v.idx()] = d;
            let entry = HeapEntry { distance: d, vertex: v.0 };
            if self.sweep[v.idx()] == Sweep::Ahead {
                self.vertices.push(entry);
            } else if self.geo.pseudo_source[v.idx()] {
                self.reemit.push(entry);
            }
        }
    }

    /// A source or pseudo-source `v` sends one window, from itself at its
    /// distance, across the far edge of each of its faces.
    fn emit_from_vertex(&mut self, v: VertexId) -> Result<()> {
        let d = self.distance[v.idx()];
        for h in self.conn.outgoing(v).iter().copied() {
            // The far edge P -> Q of the face, with v at its apex; seen from
            // the other side (frame Q -> P), v lies below at (len - x, -y).
            let e = h.next();
            let (len, apex) = (self.geo.len[e.idx()], self.geo.apex[e.idx()]);
            self.emit(e, DVec2::new(len - apex.x, -apex.y), d, 0.0, len)?;
        }
        Ok(())
    }

    /// Creates the window `[t0, t1]` with `source`, `sigma` on the twin of
    /// `e` (in the twin's frame: from `dest(e)` at 0 to `origin(e)` at
    /// `len`). Its ends give upper bounds to the edge's vertices; it joins
    /// the twin's list if the edge is interior and the window is neither
    /// empty nor beaten at its ends by the edge's vertices.
    fn emit(&mut self, e: HalfedgeId, source: DVec2, sigma: f64, t0: f64, t1: f64) -> Result<()> {
        let len = self.geo.len[e.idx()];
        let (t0, t1) = (t0.clamp(0.0, len), t1.clamp(0.0, len));
        let w = Window { b0: t0, b1: t1, source, sigma };
        let (d0, d1) = (w.at(t0), w.at(t1));
        self.offer(self.conn.dest(e), d0 + t0);
        self.offer(self.conn.origin(e), d1 + (len - t1));
        let Some(twin) = self.conn.twin(e) else { return Ok(()) };
        if !(t1 > t0) || !(source.y < 0.0) || self.beaten_at_ends(twin, &w) {
            return Ok(());
        }
        self.created += 1;
        if self.created > self.max_windows {
            return Err(GeodesicError::WorkLimit { what: "exact geodesic windows", limit: self.max_windows });
        }
        self.lists[twin.idx()].push(w);
        if self.sweep[self.conn.origin(twin).idx()] == Sweep::Inside
            || self.sweep[self.conn.dest(twin).idx()] == Sweep::Inside
        {
            self.enqueue(twin);
        }
        Ok(())
    }

    /// The vertex filter of Xin and Wang (2009): every point of `w` on
    /// half-edge `h` is reached more shortly along the edge from one of its
    /// end vertices, since `d(A) + |A P| < d_w(P)` at the end P of `w`
    /// farthest from A (and `d_w(x) - x` does not increase along the edge),
    /// or the same from B.
    fn beaten_at_ends(&self, h: HalfedgeId, w: &Window) -> bool {
        let len = self.geo.len[h.idx()];
        let da = self.distance[self.conn.origin(h).idx()];
        let db = self.distance[self.conn.dest(h).idx()];
        da + w.b1 < w.at(w.b1) * (1.0 - PRUNE_MARGIN) || db + (len - w.b0) < w.at(w.b0) * (1.0 - PRUNE_MARGIN)
    }

    /// Sends the list of `h` across its face A B C: trims overlapping
    /// windows against each other (after sorting them along the edge), gives
    /// C the shortest route through any of them, and unfolds each onto A C
    /// and C B. (Filtering the list again by the edge's vertices here, as
    /// VTP does, dropped 0.02% of the windows on the bunny Loop x2: the
    /// filter runs when a window is created.)
    fn propagate_list(&mut self, h: HalfedgeId) -> Result<()> {
        let mut batch = std::mem::take(&mut self.batch);
        std::mem::swap(&mut batch, &mut self.lists[h.idx()]);
        trim_overlaps(&mut batch);
        let c = self.geo.apex[h.idx()];
        let (mut best, mut best_x) = self.through_apex[h.idx()];
        for w in &batch {
            let r = w.apex_route(c);
            if r.distance < best {
                (best, best_x) = (r.distance, r.x);
            }
        }
        self.through_apex[h.idx()] = (best, best_x);
        self.offer(self.conn.opposite_vertex(h), best);
        for w in &batch {
            self.cross_face(h, w, best, best_x)?;
        }
        batch.clear();
        self.batch = batch;
        Ok(())
    }

    /// Carries `w` across the face of `h`: the rays from the source through
    /// the window leave through A C, C B or both (split at C). If a route
    /// through this edge reaches C more shortly (`best`, crossing the edge at
    /// `best_x`), the rays of `w` that cross that route's last segment
    /// (from `(best_x, 0)` to C) are dropped: where they cross, the other
    /// route is shorter, since w's own route to C is longer still ("one
    /// angle, one split", Chen and Han 1990).
    fn cross_face(&mut self, h: HalfedgeId, w: &Window, best: f64, best_x: f64) -> Result<()> {
        let (len, c) = (self.geo.len[h.idx()], self.geo.apex[h.idx()]);
        let route = w.apex_route(c);
        let cut = (best < route.distance * (1.0 - PRUNE_MARGIN)).then_some(best_x);
        let (a, b) = (DVec2::ZERO, DVec2::new(len, 0.0));
        let (ac, cb) = (h.prev(), h.next()); // half-edges C -> A and B -> C
        let xc = route.foot;
        if xc > w.b0 {
            // Rays left of C, through [b0, min(xc, b1)]; beaten right of x*.
            let end = xc.min(w.b1);
            let (end, end_point) = match cut {
                Some(x) if x < end => (x, DVec2::new(x, 0.0)),
                _ if xc < w.b1 => (xc, c),
                _ => (end, DVec2::new(end, 0.0)),
            };
            if end > w.b0 {
                let (t0, t1, s) = w.onto_edge(a, c, self.geo.len[ac.idx()], DVec2::new(w.b0, 0.0), end_point);
                self.emit(ac, s, w.sigma, t0, t1)?;
            }
        }
        if xc < w.b1 {
            // Rays right of C, through [max(xc, b0), b1]; beaten left of x*.
            let start = xc.max(w.b0);
            let (start, start_point) = match cut {
                Some(x) if x > start => (x, DVec2::new(x, 0.0)),
                _ if xc > w.b0 => (xc, c),
                _ => (start, DVec2::new(start, 0.0)),
            };
            if start < w.b1 {
                let (t0, t1, s) = w.onto_edge(c, b, self.geo.len[cb.idx()], start_point, DVec2::new(w.b1, 0.0));
                self.emit(cb, s, w.sigma, t0, t1)?;
            }
        }
        Ok(())
    }
}

/// Sorts the windows of one list along the edge and trims every two that
/// overlap ([`Window::trim_pair`]), dropping those that vanish. O(k log k +
/// overlapping pairs) for k windows.
fn trim_overlaps(batch: &mut Vec<Window>) {
    if batch.len() < 2 {
        return;
    }
    batch.sort_unstable_by(|p, q| p.b0.total_cmp(&q.b0));
    let dead = |w: &Window| w.b0 == f64::INFINITY;
    for i in 0..batch.len() {
        for j in i + 1..batch.len() {
            if dead(&batch[i]) || batch[j].b0 >= batch[i].b1 {
                break;
            }
            if dead(&batch[j]) {
                continue;
            }
            let (head, tail) = batch.split_at_mut(j);
            let (keep_i, keep_j) = Window::trim_pair(&mut head[i], &mut tail[0]);
            for (keep, w) in [(keep_i, &mut head[i]), (keep_j, &mut tail[0])] {
                if !keep {
                    w.b0 = f64::INFINITY;
                }
            }
        }
    }
    batch.retain(|w| !dead(w));
}
