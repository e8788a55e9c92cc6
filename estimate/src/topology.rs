//! Flat (compressed-row) vertex adjacency built once per mesh, and k-ring neighbourhoods.
//!
//! [`Mesh::faces_around_vertex`] and [`Mesh::vertex_ring`] allocate a `Vec` per call; the
//! estimators visit every vertex (and its rings) and use these flat arrays instead, so that the
//! hot loop allocates nothing.

use mesh::Mesh;

/// Faces around and neighbours of every vertex, in compressed-row form.
///
/// The lists hold `u32` indices (a face or a vertex each): half the memory of `usize`, 28 MB
/// less at 10⁶ faces, held through every estimator's run. Every [`Mesh`] has at most
/// `mesh::MAX_FACES` faces and `mesh::MAX_VERTICES` vertices, so each index is a `u32`.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Topology {
    face_start: Vec<usize>,
    face_list: Vec<u32>,
    nb_start: Vec<usize>,
    nb_list: Vec<u32>,
}

impl Topology {
    /// Builds the adjacency of `mesh` in `O(F)` (plus a sort of each vertex's short neighbour
    /// list).
    pub fn new(mesh: &Mesh) -> Self {
        // (Every face and vertex index of a mesh is below `u32::MAX`: the casts are exact.)
        let nv = mesh.num_vertices();
        let faces = mesh.faces();
        let mut face_start = vec![0usize; nv + 1];
        for f in faces {
            for &v in f {
                face_start[v + 1] += 1;
            }
        }
        for i in 0..nv {
            face_start[i + 1] += face_start[i];
        }
        let mut fill = face_start.clone();
        let mut face_list = vec![0u32; face_start[nv]];
        let mut nb_raw = vec![0u32; 2 * face_start[nv]];
        for (fi, f) in faces.iter().enumerate() {
            for (c, &v) in f.iter().enumerate() {
                let slot = fill[v];
                face_list[slot] = fi as u32;
                nb_raw[2 * slot] = f[(c + 1) % 3] as u32;
                nb_raw[2 * slot + 1] = f[(c + 2) % 3] as u32;
                fill[v] += 1;
            }
        }
        let mut nb_start = vec![0usize; nv + 1];
        let mut nb_list = Vec::with_capacity(face_start[nv] + nv);
        for v in 0..nv {
            let seg = &mut nb_raw[2 * face_start[v]..2 * face_start[v + 1]];
            seg.sort_unstable();
            let mut last = None;
            for &u in seg.iter() {
                if last != Some(u) {
                    nb_list.push(u);
                    last = Some(u);
                }
            }
            nb_start[v + 1] = nb_list.len();
        }
        Topology {
            face_start,
            face_list,
            nb_start,
            nb_list,
        }
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.face_start.len().saturating_sub(1)
    }

    /// The faces using vertex `v` (in face order; empty for an isolated or missing vertex).
    pub fn faces(&self, v: usize) -> &[u32] {
        match (self.face_start.get(v), self.face_start.get(v + 1)) {
            (Some(&a), Some(&b)) => self.face_list.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// The distinct vertices sharing a face with `v` (sorted by index).
    pub fn neighbours(&self, v: usize) -> &[u32] {
        match (self.nb_start.get(v), self.nb_start.get(v + 1)) {
            (Some(&a), Some(&b)) => self.nb_list.get(a..b).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// Collects into `out` the vertex `v` followed by its rings 1, 2, … (breadth first, each
    /// vertex once) until `out` holds at least `min_points` vertices, `max_rings` rings have been
    /// added, `max_points` is reached (the last ring is then cut short) or the component is
    /// exhausted. Returns the number of complete or partial rings added.
    ///
    /// Membership is tested by a linear scan of `out`: neighbourhoods are short (`max_points`),
    /// and a scan needs no per-mesh marker array per thread.
    pub fn rings_into(
        &self,
        v: usize,
        min_points: usize,
        max_rings: usize,
        max_points: usize,
        out: &mut Vec<usize>,
    ) -> usize {
        out.clear();
        if v >= self.num_vertices() {
            return 0;
        }
        out.push(v);
        let mut ring_begin = 0;
        let mut rings = 0;
        while out.len() < min_points && rings < max_rings && out.len() < max_points {
            let ring_end = out.len();
            'ring: for i in ring_begin..ring_end {
                let u = out[i];
                for w in self.neighbours(u).iter().map(|&w| w as usize) {
                    if !out.contains(&w) {
                        out.push(w);
                        if out.len() >= max_points {
                            break 'ring;
                        }
                    }
                }
            }
            if out.len() == ring_end {
                break;
            }
            rings += 1;
            ring_begin = ring_end;
        }
        rings
    }
}

/// Reusable scratch for [`Topology::rings_into_marked`]: one bit per vertex of the mesh, set
/// for the vertices gathered so far, so that a membership test is one load and a mask. It grows
/// to the mesh on first use (`V/8` bytes: 125 kB at 10⁶ vertices, within the second-level
/// cache) and is cleared by walking the gathered vertices, not the whole set.
#[derive(Clone, Debug, Default)]
pub struct RingMarks {
    bits: Vec<u64>,
}

impl RingMarks {
    /// Makes room for vertices `0..num_vertices` (all unmarked, as [`RingMarks::clear`] leaves
    /// them).
    fn begin(&mut self, num_vertices: usize) {
        let words = num_vertices.div_ceil(64);
        if self.bits.len() < words {
            self.bits.resize(words, 0);
        }
    }

    /// Unmarks `items`, which hold every marked vertex.
    fn clear(&mut self, items: &[usize]) {
        for &v in items {
            if let Some(w) = self.bits.get_mut(v / 64) {
                *w = 0;
            }
        }
    }

    /// Marks `v` (below the `num_vertices` of [`RingMarks::begin`]); true when it was not
    /// marked.
    fn insert(&mut self, v: usize) -> bool {
        let bit = 1u64 << (v % 64);
        match self.bits.get_mut(v / 64) {
            Some(w) if *w & bit == 0 => {
                *w |= bit;
                true
            }
            _ => false,
        }
    }
}

impl Topology {
    /// [`Topology::rings_into`] with a reusable marker instead of a linear search of `out`
    /// for each candidate: the same vertices in the same order, in time linear in the
    /// neighbourhood (the estimators' hot loop at three rings).
    pub fn rings_into_marked(
        &self,
        v: usize,
        min_points: usize,
        max_rings: usize,
        max_points: usize,
        out: &mut Vec<usize>,
        marks: &mut RingMarks,
    ) -> usize {
        out.clear();
        if v >= self.num_vertices() {
            return 0;
        }
        marks.begin(self.num_vertices());
        out.push(v);
        marks.insert(v);
        let mut ring_begin = 0;
        let mut rings = 0;
        while out.len() < min_points && rings < max_rings && out.len() < max_points {
            let ring_end = out.len();
            'ring: for i in ring_begin..ring_end {
                let u = out[i];
                for w in self.neighbours(u).iter().map(|&w| w as usize) {
                    if marks.insert(w) {
                        out.push(w);
                        if out.len() >= max_points {
                            break 'ring;
                        }
                    }
                }
            }
            if out.len() == ring_end {
                break;
            }
            rings += 1;
            ring_begin = ring_end;
        }
        marks.clear(out);
        rings
    }

    /// The vertices of `v`'s connected neighbourhood within Euclidean distance `radius` of
    /// `v`'s position in `mesh` (whose topology this is): a breadth-first walk over the edges from `v` that keeps (and walks on
    /// from) only the vertices inside the ball, stopping at `max_points`. `v` comes first. This
    /// is the "sphere" neighbourhood of the fitting literature (Cazals & Pouget 2005, §5.1)
    /// restricted to what is connected to `v` inside the ball, so that a nearby sheet of the
    /// surface (the other side of a thin part) is not gathered. Returns the largest distance
    /// gathered.
    pub fn ball_into(
        &self,
        v: usize,
        mesh: &Mesh,
        radius: f64,
        max_points: usize,
        out: &mut Vec<usize>,
        marks: &mut RingMarks,
    ) -> f64 {
        out.clear();
        let positions = mesh.vertices();
        let Some(origin) = positions.get(v).map(|x| x.data.p) else {
            return 0.0;
        };
        if v >= self.num_vertices() || max_points == 0 {
            return 0.0;
        }
        marks.begin(self.num_vertices());
        out.push(v);
        marks.insert(v);
        let r2 = radius * radius;
        let mut far = 0.0_f64;
        let mut next = 0;
        'walk: while next < out.len() {
            let u = out[next];
            next += 1;
            for w in self.neighbours(u).iter().map(|&w| w as usize) {
                let Some(p) = positions.get(w) else { continue };
                let d2 = (p.data.p - origin).norm_squared();
                if d2 <= r2 && marks.insert(w) {
                    out.push(w);
                    far = far.max(d2);
                    if out.len() >= max_points {
                        break 'walk;
                    }
                }
            }
        }
        marks.clear(out);
        far.sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rings_of_the_octahedron() {
        let data = mesh::datasets::octa().expect("built-in");
        let t = Topology::new(&data.mesh);
        let mut out = Vec::new();
        for v in 0..6 {
            assert_eq!(t.faces(v).len(), 4);
            assert_eq!(t.neighbours(v).len(), 4);
            assert_eq!(t.rings_into(v, 2, 1, 100, &mut out), 1);
            assert_eq!(out.len(), 5);
            assert_eq!(t.rings_into(v, 100, 5, 100, &mut out), 2);
            assert_eq!(out.len(), 6);
        }
        assert!(t.faces(6).is_empty());
        // The marked walk gives the same vertices in the same order.
        let (mut a, mut b, mut marks) = (Vec::new(), Vec::new(), RingMarks::default());
        for v in 0..6 {
            for (min, rings, max) in [(2, 1, 100), (100, 5, 100), (3, 2, 4)] {
                let ra = t.rings_into(v, min, rings, max, &mut a);
                let rb = t.rings_into_marked(v, min, rings, max, &mut b, &mut marks);
                assert_eq!((ra, &a), (rb, &b));
            }
        }
        assert_eq!(t.rings_into(6, 10, 2, 10, &mut out), 0);
        assert!(out.is_empty());
    }

    #[test]
    fn balls_of_the_octahedron() {
        // Unit octahedron: neighbours at √2, the opposite vertex at 2.
        let data = mesh::datasets::octa().expect("built-in");
        let t = Topology::new(&data.mesh);
        let p = &data.mesh;
        let scale = p.vertices()[0].data.p.coords.norm();
        let (mut out, mut marks) = (Vec::new(), RingMarks::default());
        for v in 0..6 {
            let far = t.ball_into(v, p, 0.5 * scale, 100, &mut out, &mut marks);
            assert_eq!((out.as_slice(), far), ([v].as_slice(), 0.0));
            t.ball_into(v, p, 1.5 * scale, 100, &mut out, &mut marks);
            assert_eq!(out.len(), 5);
            t.ball_into(v, p, 2.0 * scale, 100, &mut out, &mut marks);
            assert_eq!(out.len(), 6);
            t.ball_into(v, p, 2.0 * scale, 3, &mut out, &mut marks);
            assert_eq!(out.len(), 3);
        }
    }
}
