//! [`EdgeGroups`]: the half-edges of a triangle list grouped by undirected edge, the one sort
//! behind the mesh's adjacency ([`crate::mesh::Mesh`]) and the repair's rules
//! ([`crate::repair`]).
//!
//! Half-edge `h = 3 f + l` runs from corner `l` of face `f` to corner `(l + 1) % 3`; its key is
//! the unordered pair `{min, max}` of those two vertices. The groups come in the order of their
//! keys `(min, max)`, and each group's half-edges in increasing order: exactly the order a full
//! comparison sort of the triples `(min, max, h)` gives, so code that walks the groups in order
//! sees the same sequence whichever way it was computed.
//!
//! # How
//!
//! A counting sort on `min` (a bucket per vertex, the half-edges scattered in increasing `h`),
//! then a small sort of each bucket by `(max, h)` (a bucket holds about a vertex's valence, so
//! this is linear in practice). On large meshes the vertex range is cut into as many pieces as
//! there are threads: each piece counts, scatters and sorts the half-edges whose `min` falls in
//! it, into its own part of the output (the parts are contiguous because buckets are in vertex
//! order), so the pieces run in parallel without sharing a write and give the same array as one
//! piece would. Only half-edge indices are stored (8 bytes each, a third of the former
//! `(min, max, h)` triples); keys are read back from the faces.

use rayon::prelude::*;

use crate::vertex_pieces::{for_each_half_edge_by_vertex, pieces};

/// Half-edges grouped by undirected edge (see the module docs for the order).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct EdgeGroups {
    /// Half-edge indices, group after group.
    order: Vec<usize>,
    /// Where each group starts in `order`, then `order.len()`.
    starts: Vec<usize>,
}

/// The two vertices of half-edge `h`: from, to.
pub(crate) fn ends(faces: &[[usize; 3]], h: usize) -> (usize, usize) {
    let t = &faces[h / 3];
    (t[h % 3], t[(h % 3 + 1) % 3])
}

/// The key of half-edge `h`: its two vertices, smaller first.
pub(crate) fn key(faces: &[[usize; 3]], h: usize) -> (usize, usize) {
    let (a, b) = ends(faces, h);
    (a.min(b), a.max(b))
}

impl EdgeGroups {
    /// Groups the half-edges of `faces` (any vertex indices; faces may repeat a vertex, such a
    /// face's half-edges then share keys like any others).
    pub(crate) fn new(faces: &[[usize; 3]]) -> Self {
        let nh = 3 * faces.len();
        let n = faces
            .par_iter()
            .flat_map_iter(|t| t.iter().copied())
            .max()
            .map_or(0, |m| m + 1);
        // Vertices per piece (at least one, so that `chunks` is well defined): the pieces of
        // `for_each_half_edge_by_vertex`, which counts the bucket sizes.
        let span = n.div_ceil(pieces(nh)).max(1);
        let mut counts = vec![0usize; n];
        for_each_half_edge_by_vertex(
            faces,
            &mut counts,
            |t, l| t[l].min(t[(l + 1) % 3]),
            |c, _| *c += 1,
        );
        // Bucket starts (exclusive prefix sums), in place.
        let mut total = 0;
        for c in counts.iter_mut() {
            let size = *c;
            *c = total;
            total += size;
        }
        let mut next = counts;
        // The output cut where the pieces' vertex ranges start.
        let mut order = vec![0usize; nh];
        let mut parts: Vec<&mut [usize]> = Vec::with_capacity(n.div_ceil(span));
        let mut rest: &mut [usize] = &mut order;
        let mut taken = 0;
        for i in 1..=next.len().div_ceil(span) {
            let end = next.get(i * span).copied().unwrap_or(nh);
            let (part, tail) = rest.split_at_mut(end - taken);
            parts.push(part);
            rest = tail;
            taken = end;
        }
        let starts: Vec<Vec<usize>> = next
            .par_chunks_mut(span)
            .zip(parts.into_par_iter())
            .enumerate()
            .map(|(i, (next, part))| {
                let base = i * span;
                let offset = next.first().copied().unwrap_or(0);
                // Scatter in increasing half-edge order.
                for (f, t) in faces.iter().enumerate() {
                    for l in 0..3 {
                        let lo = t[l].min(t[(l + 1) % 3]);
                        if let Some(slot) = lo.checked_sub(base).and_then(|k| next.get_mut(k)) {
                            part[*slot - offset] = 3 * f + l;
                            *slot += 1;
                        }
                    }
                }
                // Each bucket by (max, h), and the group starts where `max` changes. After the
                // scatter, `next[k]` is the end of bucket k, so the start of bucket k + 1.
                let mut starts = Vec::with_capacity(part.len() / 2 + 1);
                let mut scratch: Vec<(usize, usize)> = Vec::new();
                let mut begin = 0;
                for &end in next.iter() {
                    let end = end - offset;
                    let bucket = &mut part[begin..end];
                    match bucket.len() {
                        0 => {}
                        1 => starts.push(offset + begin),
                        _ => {
                            scratch.clear();
                            scratch.extend(bucket.iter().map(|&h| (key(faces, h).1, h)));
                            scratch.sort_unstable();
                            let mut previous = None;
                            for (j, (slot, &(hi, h))) in
                                bucket.iter_mut().zip(scratch.iter()).enumerate()
                            {
                                *slot = h;
                                if previous != Some(hi) {
                                    starts.push(offset + begin + j);
                                    previous = Some(hi);
                                }
                            }
                        }
                    }
                    begin = end;
                }
                starts
            })
            .collect();
        let mut flat = Vec::with_capacity(starts.iter().map(Vec::len).sum::<usize>() + 1);
        for s in starts {
            flat.extend(s);
        }
        flat.push(nh);
        EdgeGroups {
            order,
            starts: flat,
        }
    }

    /// [`EdgeGroups::iter`] in parallel.
    pub(crate) fn par_iter(&self) -> impl IndexedParallelIterator<Item = &[usize]> + '_ {
        self.starts.par_windows(2).map(|w| &self.order[w[0]..w[1]])
    }

    /// The groups in order, each as its half-edges in increasing order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &[usize]> + '_ {
        self.starts.windows(2).map(|w| &self.order[w[0]..w[1]])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The definition: a full sort of `(min, max, h)`, grouped by `(min, max)`.
    fn by_full_sort(faces: &[[usize; 3]]) -> Vec<Vec<usize>> {
        let mut all: Vec<(usize, usize, usize)> = (0..3 * faces.len())
            .map(|h| {
                let (lo, hi) = key(faces, h);
                (lo, hi, h)
            })
            .collect();
        all.sort_unstable();
        let mut out: Vec<Vec<usize>> = Vec::new();
        for (i, &(lo, hi, h)) in all.iter().enumerate() {
            if i > 0 && (all[i - 1].0, all[i - 1].1) == (lo, hi) {
                if let Some(g) = out.last_mut() {
                    g.push(h);
                }
            } else {
                out.push(vec![h]);
            }
        }
        out
    }

    fn grouped(faces: &[[usize; 3]]) -> Vec<Vec<usize>> {
        EdgeGroups::new(faces)
            .iter()
            .map(<[usize]>::to_vec)
            .collect()
    }

    #[test]
    fn groups_are_those_of_a_full_sort() {
        // Small (one piece) and large (several pieces) random soups, with repeated vertices,
        // non-manifold edges and unused vertex numbers.
        let mut rng = fixtures::SplitMix64::new(7);
        let mut rnd = |n: usize| rng.below(n);
        for (faces, verts) in [(0, 1), (1, 3), (5, 4), (40, 9), (30_000, 900), (40_000, 40)] {
            let tris: Vec<[usize; 3]> = (0..faces)
                .map(|_| [rnd(verts) + 3, rnd(verts) + 3, rnd(verts)])
                .collect();
            let g = EdgeGroups::new(&tris);
            assert_eq!(g.iter().count(), g.par_iter().count());
            assert_eq!(grouped(&tris), by_full_sort(&tris), "{faces} faces");
        }
    }
}
