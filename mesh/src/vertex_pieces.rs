//! Per-vertex passes over the half-edges of a triangle list, split over the threads by vertex
//! range: each thread reads every face and handles the half-edges whose vertex falls in its
//! range, into its own part of the per-vertex array. Every vertex's half-edges are still met in
//! increasing order, so the result is the one a single loop over the half-edges gives; no
//! write is shared, so no locking (and no `unsafe`) is needed.

use rayon::prelude::*;

/// Below this many half-edges a pass runs on one thread (each piece reads every face; splitting
/// a small mesh costs more than it saves).
pub(crate) const PARALLEL_MIN_HALF_EDGES: usize = 1 << 16;

/// How many vertex ranges to cut a pass over `half_edges` half-edges into.
pub(crate) fn pieces(half_edges: usize) -> usize {
    if half_edges < PARALLEL_MIN_HALF_EDGES {
        1
    } else {
        rayon::current_num_threads().clamp(1, 8)
    }
}

/// For every half-edge `h = 3 f + l` of `faces`, in increasing order for each vertex, calls
/// `visit(&mut slots[v], h)` with `v = vertex(faces[f], l)` (for example the corner it leaves,
/// `t[l]`); half-edges whose vertex is not below `slots.len()` are skipped.
pub(crate) fn for_each_half_edge_by_vertex<T: Send>(
    faces: &[[usize; 3]],
    slots: &mut [T],
    vertex: impl Fn(&[usize; 3], usize) -> usize + Sync,
    visit: impl Fn(&mut T, usize) + Sync,
) {
    let span = slots.len().div_ceil(pieces(3 * faces.len())).max(1);
    slots
        .par_chunks_mut(span)
        .enumerate()
        .for_each(|(i, part)| {
            let base = i * span;
            for (f, t) in faces.iter().enumerate() {
                for l in 0..3 {
                    let v = vertex(t, l);
                    if let Some(slot) = v.checked_sub(base).and_then(|k| part.get_mut(k)) {
                        visit(slot, 3 * f + l);
                    }
                }
            }
        });
}
