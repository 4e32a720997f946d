//! Detection of subdivision connectivity: reverse 4-to-1 splitting
//! (after Taubin, "Detecting and reconstructing subdivision connectivity",
//! The Visual Computer 2002).
//!
//! A mesh split once from K^j has its faces in groups of four: a *central*
//! face of three odd vertices and three *corner* faces, each with one even
//! vertex (a vertex of K^j) and two odd ones. An interior odd vertex has
//! valence 6 and a boundary one valence 4, so any other vertex must be even.
//! Starting from a face next to such a vertex (or trying the four possible
//! roles of a seed face when the component is fully regular), the grouping
//! grows face by face: the faces across a central face are its corners, and
//! the face across a corner's even edge is a corner of the next group. Any
//! conflict (a face or vertex given two roles, an odd vertex on two coarse
//! edges, a non-manifold coarse mesh) rejects the hypothesis. Each success
//! yields K^j; the process repeats until it fails, which gives the number of
//! levels J. Cost O(F) per level and hypothesis, at most four hypotheses per
//! connected component.

use mesh_kernel::{MeshError, TriMesh, VertexId};

use crate::error::{Result, WaveletError};
use crate::hierarchy::Hierarchy;
use crate::topology::{manifold_topology, Kind, Topology};

/// Options of [`detect`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DetectOptions {
    /// Stop after reversing this many levels (the base mesh is then the
    /// level reached). Default: as many as the mesh has.
    pub max_levels: usize,
}

impl Default for DetectOptions {
    fn default() -> Self {
        Self { max_levels: 32 }
    }
}

/// Finds the hierarchy K^0 ⊂ ... ⊂ K^J = `mesh` by reversing 4-to-1 splits as
/// often as possible (at most `max_levels`). The hierarchy remembers the
/// input index of every vertex ([`Hierarchy::to_input`]); its finest faces
/// are the input faces, in order.
///
/// Cost O(F) per level.
///
/// # Errors
/// [`WaveletError::InvalidOption`] (`max_levels`) when `max_levels` is 0;
/// [`MeshError::Empty`] for a mesh without faces; [`MeshError::NonManifold`]
/// when the mesh is not an oriented manifold; and
/// [`WaveletError::NoSubdivisionConnectivity`] when not even one split can
/// be reversed (or a vertex is referenced by no face), with the reason.
pub fn detect(mesh: &TriMesh, options: &DetectOptions) -> Result<Hierarchy> {
    if options.max_levels == 0 {
        let reason = "0 levels allowed: at least one 4-to-1 split must be looked for".into();
        return Err(WaveletError::InvalidOption { name: "max_levels", reason });
    }
    if mesh.face_count() == 0 {
        return Err(MeshError::Empty.into());
    }
    let topo = manifold_topology(mesh.vertex_count(), mesh.faces())?;
    if let Some(v) = (0..mesh.vertex_count() as u32).find(|&v| topo.kind(v) == Kind::Isolated) {
        return Err(WaveletError::NoSubdivisionConnectivity {
            reason: format!("vertex {} is referenced by no face", VertexId(v)),
        });
    }
    let mut steps: Vec<Reversal> = Vec::new();
    let mut failure = String::new();
    let mut current = topo;
    while steps.len() < options.max_levels {
        let faces = steps.last().map_or(mesh.faces(), |r| &r.coarse_faces[..]);
        match reverse(&current, faces) {
            Ok((r, coarse)) => {
                steps.push(r);
                current = coarse;
            }
            Err(reason) => {
                failure = reason;
                break;
            }
        }
    }
    if steps.is_empty() {
        return Err(WaveletError::NoSubdivisionConnectivity { reason: failure });
    }
    assemble(mesh, &steps)
}

/// One reversed 4-to-1 split: the coarse mesh and how the fine vertices
/// relate to it.
struct Reversal {
    /// Fine index of each coarse vertex, increasing.
    evens: Vec<u32>,
    /// Coarse index of each fine vertex, `u32::MAX` for odd vertices.
    coarse_of: Vec<u32>,
    /// Parent edge (coarse indices) of each fine vertex; unused for evens.
    parent: Vec<[u32; 2]>,
    /// Faces of the coarse mesh (coarse indices).
    coarse_faces: Vec<[u32; 3]>,
}

const UNSET: u32 = u32::MAX;
const EVEN: u8 = 1;
const ODD: u8 = 2;

/// The grouping of faces into quadruples, grown from seeds.
struct Grouping<'a> {
    topo: &'a Topology<'a>,
    /// Per face: `4 q + k` for corner k of group q, `4 q + 3` for its centre.
    role: Vec<u32>,
    label: Vec<u8>,
    /// Per group: the central face and its three even vertices, the one
    /// across central half-edge k at position k.
    groups: Vec<(u32, [u32; 3])>,
    touched_faces: Vec<u32>,
    touched_vertices: Vec<u32>,
    queue: Vec<u32>,
}

impl<'a> Grouping<'a> {
    fn new(topo: &'a Topology<'a>) -> Self {
        Self {
            topo,
            role: vec![UNSET; topo.face_count()],
            label: vec![0; topo.vertex_count()],
            groups: Vec::new(),
            touched_faces: Vec::new(),
            touched_vertices: Vec::new(),
            queue: Vec::new(),
        }
    }

    fn set_label(&mut self, v: u32, label: u8) -> Result<(), String> {
        match self.label[v as usize] {
            0 => {
                self.label[v as usize] = label;
                self.touched_vertices.push(v);
                Ok(())
            }
            l if l == label => Ok(()),
            _ => Err(format!("vertex v{v} would be both a vertex of the coarse mesh and an edge midpoint")),
        }
    }

    fn set_role(&mut self, f: u32, role: u32) -> Result<(), String> {
        if self.role[f as usize] != UNSET {
            return Err(format!("face f{f} would belong to two groups of four"));
        }
        self.role[f as usize] = role;
        self.touched_faces.push(f);
        Ok(())
    }

    /// Grows the grouping from `seed` taken as a central face. On failure
    /// every assignment of this attempt is undone.
    fn grow(&mut self, seed: u32) -> Result<usize, String> {
        self.touched_faces.clear();
        self.touched_vertices.clear();
        let groups_before = self.groups.len();
        match self.grow_inner(seed) {
            Ok(()) => Ok(self.touched_faces.len()),
            Err(reason) => {
                self.rollback(groups_before);
                Err(reason)
            }
        }
    }

    /// Undoes every assignment since the last call to `grow` started.
    fn rollback(&mut self, groups_before: usize) {
        for &f in &self.touched_faces {
            self.role[f as usize] = UNSET;
        }
        for &v in &self.touched_vertices {
            self.label[v as usize] = 0;
        }
        self.groups.truncate(groups_before);
    }

    fn grow_inner(&mut self, seed: u32) -> Result<(), String> {
        let topo = self.topo;
        self.queue.clear();
        self.queue.push(seed);
        while let Some(t) = self.queue.pop() {
            match self.role[t as usize] {
                UNSET => {}
                r if r % 4 == 3 => continue,
                _ => return Err(format!("face f{t} would be both a corner and a central face")),
            }
            let q = self.groups.len() as u32;
            self.set_role(t, 4 * q + 3)?;
            let mut evens = [0u32; 3];
            for k in 0..3 {
                let h = 3 * t + k;
                self.set_label(topo.origin(h), ODD)?;
                let tw = topo.twin(h).ok_or_else(|| format!("central face f{t} would touch the boundary"))?;
                self.set_role(tw / 3, 4 * q + k)?;
                let e = topo.opposite(tw);
                self.set_label(e, EVEN)?;
                evens[k as usize] = e;
                // The faces across the two edges at the even vertex are corners
                // of neighbouring groups; their central faces are across their
                // edge that avoids the even vertex.
                for g in [Topology::next(tw), Topology::prev(tw)] {
                    if let Some(g2) = topo.twin(g) {
                        let inner = if topo.origin(g2) == e { Topology::next(g2) } else { Topology::prev(g2) };
                        let ct = topo.twin(inner).ok_or_else(|| {
                            format!("corner face f{} would touch the boundary with an inner edge", g2 / 3)
                        })?;
                        if self.role[(ct / 3) as usize] == UNSET {
                            self.queue.push(ct / 3);
                        }
                    }
                }
            }
            self.groups.push((t, evens));
        }
        Ok(())
    }
}

/// `true` for a vertex that cannot be an edge midpoint of a 4-to-1 split
/// (interior valence other than 6, boundary valence other than 4).
fn must_be_even(topo: &Topology<'_>, v: u32) -> bool {
    match topo.kind(v) {
        Kind::Interior => topo.valence(v) != 6,
        Kind::Boundary => topo.valence(v) != 4,
        Kind::Isolated => false,
    }
}

/// Connected component of each face (through shared vertices, which for a
/// manifold is through shared edges) by union-find, and the count. O(F).
fn face_components(topo: &Topology<'_>, faces: &[[u32; 3]]) -> (Vec<u32>, usize) {
    let mut parent: Vec<u32> = (0..topo.vertex_count() as u32).collect();
    fn find(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let p = parent[parent[i as usize] as usize];
            parent[i as usize] = p;
            i = p;
        }
        i
    }
    for &[a, b, c] in faces {
        for (x, y) in [(a, b), (a, c)] {
            let (rx, ry) = (find(&mut parent, x), find(&mut parent, y));
            if rx != ry {
                parent[rx.max(ry) as usize] = rx.min(ry);
            }
        }
    }
    let mut label = vec![UNSET; parent.len()];
    let mut count = 0;
    let comp = faces
        .iter()
        .map(|f| {
            let r = find(&mut parent, f[0]) as usize;
            if label[r] == UNSET {
                label[r] = count;
                count += 1;
            }
            label[r]
        })
        .collect();
    (comp, count as usize)
}

/// Reverses one 4-to-1 split of the manifold mesh `faces` (with topology
/// `topo`), giving the coarse mesh and its topology, or says why not.
fn reverse(topo: &Topology<'_>, faces: &[[u32; 3]]) -> Result<(Reversal, Topology<'static>), String> {
    let nf = faces.len();
    if !nf.is_multiple_of(4) {
        return Err(format!("{nf} faces is not a multiple of 4"));
    }
    let (face_comp, count) = face_components(topo, faces);
    let mut forced = vec![u32::MAX; count];
    let mut comp_faces = vec![0usize; count];
    for &c in &face_comp {
        comp_faces[c as usize] += 1;
    }
    for v in 0..topo.vertex_count() as u32 {
        if must_be_even(topo, v) {
            let c = face_comp[(topo.out(v)[0] / 3) as usize] as usize;
            if forced[c] == u32::MAX {
                forced[c] = v;
            }
        }
    }
    let mut grouping = Grouping::new(topo);
    for f in 0..nf as u32 {
        if grouping.role[f as usize] != UNSET {
            continue;
        }
        let c = face_comp[f as usize] as usize;
        let hypotheses: Vec<u32> = match forced[c] {
            u32::MAX => {
                let mut h = vec![f];
                h.extend((0..3).filter_map(|k| topo.twin(3 * f + k)).map(|t| t / 3));
                h
            }
            v => {
                // v is even: its first face is a corner; the centre is across
                // the edge opposite v.
                let h = topo.out(v)[0];
                match topo.twin(Topology::next(h)) {
                    Some(t) => vec![t / 3],
                    None => return Err(format!("vertex v{v} must be even but its face has a boundary inner edge")),
                }
            }
        };
        let mut last = String::from("no hypothesis");
        let mut ok = false;
        for seed in hypotheses {
            let groups_before = grouping.groups.len();
            match grouping.grow(seed) {
                Ok(count) if count == comp_faces[c] => {
                    ok = true;
                    break;
                }
                Ok(count) => {
                    grouping.rollback(groups_before);
                    last = format!("the groups of four cover {count} of {} faces", comp_faces[c]);
                }
                Err(reason) => last = reason,
            }
        }
        if !ok {
            return Err(last);
        }
    }
    build_reversal(topo, grouping)
}

/// The coarse mesh of a complete grouping, after the global checks.
fn build_reversal(topo: &Topology<'_>, g: Grouping<'_>) -> Result<(Reversal, Topology<'static>), String> {
    let n = topo.vertex_count();
    let mut coarse_of = vec![UNSET; n];
    let mut evens = Vec::new();
    for v in 0..n {
        if g.label[v] == EVEN {
            coarse_of[v] = evens.len() as u32;
            evens.push(v as u32);
        }
    }
    let mut coarse_faces = Vec::with_capacity(g.groups.len());
    for &(_, [b, c, a]) in &g.groups {
        // Central half-edge k runs m_k -> m_{k+1}; the even across it lies
        // between them, so m_0 splits (a, b), m_1 (b, c), m_2 (c, a): the
        // edges 0, 1, 2 of the coarse face (a, b, c).
        let [ca, cb, cc] = [a, b, c].map(|v| coarse_of[v as usize]);
        if ca == cb || cb == cc || cc == ca {
            return Err("a coarse triangle would repeat a vertex".into());
        }
        coarse_faces.push([ca, cb, cc]);
    }
    let coarse =
        Topology::new(evens.len(), &coarse_faces).map_err(|_| "the coarser mesh would not be manifold")?.into_owned();
    let odd = n - evens.len();
    if coarse.edge_count() != odd {
        return Err(format!("{odd} edge midpoints for {} coarse edges", coarse.edge_count()));
    }
    // Each coarse edge gets one midpoint and each midpoint one edge.
    let mut parent = vec![[UNSET; 2]; n];
    let mut edge_odd = vec![UNSET; odd];
    for (f, &(t, _)) in g.groups.iter().enumerate() {
        for (k, e) in coarse.face_edges(f).into_iter().enumerate() {
            let m = topo.origin(3 * t + k as u32);
            match edge_odd[e as usize] {
                UNSET => edge_odd[e as usize] = m,
                x if x == m => continue,
                _ => return Err("two edge midpoints would split the same coarse edge".into()),
            }
            if parent[m as usize][0] != UNSET {
                return Err(format!("vertex v{m} would split two different coarse edges"));
            }
            parent[m as usize] = coarse.edges()[e as usize];
        }
    }
    Ok((Reversal { evens, coarse_of, parent, coarse_faces }, coarse))
}

/// Sorts `(key, value)` pairs by key in O(n + len): counting sort on the
/// first key component (below `n`), then the small buckets by the second.
fn sort_by_edge(items: Vec<([u32; 2], u32)>, n: usize) -> Vec<([u32; 2], u32)> {
    let mut start = vec![0u32; n + 1];
    for (k, _) in &items {
        start[k[0] as usize + 1] += 1;
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut sorted = vec![([0u32; 2], 0u32); items.len()];
    for item in items {
        let slot = &mut start[item.0[0] as usize];
        sorted[*slot as usize] = item;
        *slot += 1;
    }
    // start[v] now ends bucket v; bucket v begins where bucket v - 1 ends.
    let mut begin = 0;
    for &end in &start[..n] {
        let bucket = &mut sorted[begin..end as usize];
        if bucket.len() > 1 {
            bucket.sort_unstable();
        }
        begin = end as usize;
    }
    sorted
}

/// Hierarchical numbering from the reversals (finest first): the numbering
/// [`Hierarchy::from_base`] gives the detected base mesh, odd vertices of
/// each level in the sorted order of their parent edges.
fn assemble(mesh: &TriMesh, steps: &[Reversal]) -> Result<Hierarchy> {
    let levels = steps.len();
    let base = &steps[levels - 1];
    let n0 = base.evens.len();
    let mut counts = vec![n0];
    let mut faces = vec![base.coarse_faces.clone()];
    let mut parents = Vec::with_capacity(levels);
    // hier_to_level[h] = index of hierarchical vertex h in the numbering of the
    // current level's reversal; level_to_hier its inverse.
    let mut hier_to_level: Vec<u32> = (0..n0 as u32).collect();
    let mut level_to_hier: Vec<u32> = hier_to_level.clone();
    for j in 0..levels {
        let r = &steps[levels - 1 - j];
        let fine_n = r.coarse_of.len();
        let mut next: Vec<u32> = hier_to_level.iter().map(|&c| r.evens[c as usize]).collect();
        let odd: Vec<([u32; 2], u32)> = (0..fine_n as u32)
            .filter(|&v| r.coarse_of[v as usize] == UNSET)
            .map(|v| {
                let [a, b] = r.parent[v as usize].map(|c| level_to_hier[c as usize]);
                ([a.min(b), a.max(b)], v)
            })
            .collect();
        let odd = sort_by_edge(odd, hier_to_level.len());
        next.extend(odd.iter().map(|o| o.1));
        parents.push(odd.into_iter().map(|o| o.0).collect());
        let mut inverse = vec![0u32; fine_n];
        for (h, &v) in next.iter().enumerate() {
            inverse[v as usize] = h as u32;
        }
        let fine_faces: &[[u32; 3]] = if j + 1 == levels { mesh.faces() } else { &steps[levels - 2 - j].coarse_faces };
        faces.push(fine_faces.iter().map(|f| f.map(|v| inverse[v as usize])).collect());
        counts.push(fine_n);
        hier_to_level = next;
        level_to_hier = inverse;
    }
    Hierarchy::new(counts, faces, parents, Some(hier_to_level))
}
