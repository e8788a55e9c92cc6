//! The patch tessellator of `tess` (and of the one-process benchmark): patches one at a time
//! at `s` segments per edge, exactly as `surface::tessellate` does for the patch alone, with
//! the Bernstein weights of the samples computed once per degree and shared by every patch.

use std::collections::HashMap;

use surface::beztri::SampleWeights;
use surface::BezierTriangle;

use crate::sample::Sample;

/// One patch's tessellation with shared vertices: its samples, and its triangles as indices
/// into them (counter-clockwise, in the order of `surface::tessellate`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct IndexedPatch {
    /// The samples (vertices), each once.
    pub samples: Vec<Sample>,
    /// The triangles: indices into `samples`.
    pub triangles: Vec<[u32; 3]>,
}

impl IndexedPatch {
    /// The triangles with their vertices, appended to `out` after clearing it.
    pub fn expand(&self, out: &mut Vec<[Sample; 3]>) {
        out.clear();
        out.extend(
            self.triangles
                .iter()
                .map(|t| t.map(|i| self.samples[i as usize])),
        );
    }
}

/// Tessellates patches one at a time at `s` segments per edge, exactly as
/// `surface::tessellate` does for the patch alone, with the Bernstein weights of the samples
/// computed once per degree and shared by every patch (`surface::tessellate` computes them
/// per call, which is 90% of its time for one patch). A patch with a singular sample or two
/// boundary samples close enough to be welded goes through `surface::tessellate` itself.
#[derive(Debug)]
pub struct PatchTessellator {
    s: usize,
    tables: HashMap<usize, Vec<SampleWeights>>,
    indexed: IndexedPatch,
}

/// Boundary samples closer than this many weld tolerances (`surface::tessellate`'s
/// `WELD_RELATIVE` times the net's size) send a patch to the general path: a margin of 4
/// keeps the fast path away from the welder's own comparisons.
const WELD_MARGIN: f64 = 4.0;

impl PatchTessellator {
    /// A tessellator at `s ≥ 1` segments per edge.
    pub fn new(s: usize) -> Result<Self, surface::TessError> {
        if s == 0 {
            return Err(surface::TessError::ZeroDensity);
        }
        Ok(PatchTessellator {
            s,
            tables: HashMap::new(),
            indexed: IndexedPatch::default(),
        })
    }

    /// The `s²` triangles of `patch` (fewer where the general path collapses some), appended
    /// to `out` after clearing it: [`PatchTessellator::tessellate_indexed`] with each
    /// triangle's vertices copied out.
    pub fn tessellate(
        &mut self,
        patch: &BezierTriangle,
        out: &mut Vec<[Sample; 3]>,
    ) -> Result<(), surface::TessError> {
        let mut indexed = std::mem::take(&mut self.indexed);
        let result = self.tessellate_indexed(patch, &mut indexed);
        indexed.expand(out);
        self.indexed = indexed;
        result
    }

    /// The tessellation of `patch` with shared vertices: `(s + 1)(s + 2)/2` samples and `s²`
    /// triangles on the fast path; on the general path the welded vertices and triangles of
    /// `surface::tessellate` for the patch alone. `out` is cleared first.
    pub fn tessellate_indexed(
        &mut self,
        patch: &BezierTriangle,
        out: &mut IndexedPatch,
    ) -> Result<(), surface::TessError> {
        out.samples.clear();
        out.triangles.clear();
        let s = self.s;
        let table = self
            .tables
            .entry(patch.degree())
            .or_insert_with(|| SampleWeights::grid(patch.degree(), s));
        for w in table.iter() {
            let Some((d, c)) = patch
                .derivatives_with(w)
                .and_then(|d| surface::beztri::curvature_of(&d).map(|c| (d, c)))
            else {
                return general(patch, s, out);
            };
            out.samples.push(Sample {
                pos: d.p,
                norm: c.normal,
                kg: c.gaussian,
                km: c.mean,
            });
        }
        let local = |i: usize, j: usize| j * (s + 1) - j * j.saturating_sub(1) / 2 + i;
        // Would the welder join two boundary samples?
        let tol = surface::tessellate::WELD_RELATIVE
            * surface::mesh::bounding_size(patch.points()).max(f64::MIN_POSITIVE)
            * WELD_MARGIN;
        let mut boundary = Vec::with_capacity(3 * s);
        for j in 0..=s {
            for i in 0..=s - j {
                if i == 0 || j == 0 || i + j == s {
                    boundary.push(out.samples[local(i, j)].pos);
                }
            }
        }
        for (a, p) in boundary.iter().enumerate() {
            if boundary[a + 1..].iter().any(|q| (p - q).norm() <= tol) {
                return general(patch, s, out);
            }
        }
        // Sample indices fit u32 for any s whose samples fit in memory (and `tess` allows at
        // most MAX_SEGMENTS).
        let at = |i: usize, j: usize| local(i, j) as u32;
        for j in 0..s {
            for i in 0..s - j {
                // Upward triangle: corners towards u, v, w; then the downward one (the order
                // of `surface::tessellate`).
                out.triangles.push([at(i + 1, j), at(i, j + 1), at(i, j)]);
                if i + j + 2 <= s {
                    out.triangles
                        .push([at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
                }
            }
        }
        Ok(())
    }
}

/// `surface::tessellate` on the patch alone.
fn general(
    patch: &BezierTriangle,
    s: usize,
    out: &mut IndexedPatch,
) -> Result<(), surface::TessError> {
    out.samples.clear();
    out.triangles.clear();
    let t = surface::tessellate(std::slice::from_ref(patch), s)?;
    out.samples.extend((0..t.positions.len()).map(|i| Sample {
        pos: t.positions[i],
        norm: t.normals[i],
        kg: t.gaussian[i],
        km: t.mean[i],
    }));
    out.triangles
        .extend(t.faces.iter().map(|f| f.map(|i| i as u32)));
    Ok(())
}

/// The `s²` triangles of one patch at `s` segments per patch edge (`surface::tessellate` on
/// the patch alone, so every vertex carries its own patch's normal and curvature). For many
/// patches use a [`PatchTessellator`], which shares the sample weights.
pub fn tessellate_patch(
    patch: &BezierTriangle,
    s: usize,
) -> Result<Vec<[Sample; 3]>, surface::TessError> {
    let mut indexed = IndexedPatch::default();
    general(patch, s, &mut indexed)?;
    let mut out = Vec::new();
    indexed.expand(&mut out);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use nalgebra::Point3;

    use super::*;

    /// The shared-weights path gives exactly (bit for bit) what `surface::tessellate` gives
    /// for the patch alone, on regular patches and on a degenerate one (a collapsed edge: its
    /// samples are welded and some triangles dropped there, so it takes the general path).
    #[test]
    fn patch_tessellator_equals_surface_tessellate() {
        let quad = BezierTriangle::from_fn(4, |i, j, k| {
            let (u, v) = (i as f64 / 4.0, j as f64 / 4.0);
            Point3::new(
                u,
                v,
                0.3 * u * u - 0.2 * u * v + 0.1 * v * v + 0.05 * k as f64,
            )
        });
        let collapsed = BezierTriangle::from_fn(2, |i, j, _| {
            // Corners (2,0,0) and (0,2,0) coincide: edge w = 0 is a point.
            Point3::new(
                (i * j) as f64 * 0.5,
                (i + j) as f64 * 0.25,
                (i as f64 - 1.0).abs(),
            )
        });
        for s in [1, 3, 8] {
            let mut t = PatchTessellator::new(s).expect("s ≥ 1");
            let mut out = Vec::new();
            for patch in [&quad, &collapsed, &quad] {
                t.tessellate(patch, &mut out).expect("tessellates");
                let expected = tessellate_patch(patch, s).expect("tessellates");
                assert_eq!(out, expected, "s = {s}");
            }
            // Shared vertices: each sample once, s² triangles on the fast path (the quartic),
            // fewer vertices where the general path welds (the collapsed edge).
            let mut indexed = IndexedPatch::default();
            t.tessellate_indexed(&quad, &mut indexed)
                .expect("tessellates");
            assert_eq!(indexed.samples.len(), (s + 1) * (s + 2) / 2);
            assert_eq!(indexed.triangles.len(), s * s);
            t.tessellate_indexed(&collapsed, &mut indexed)
                .expect("tessellates");
            assert!(indexed.samples.len() < (s + 1) * (s + 2) / 2, "s = {s}");
            indexed.expand(&mut out);
            assert_eq!(out, tessellate_patch(&collapsed, s).expect("tessellates"));
        }
        assert!(PatchTessellator::new(0).is_err());
    }
}
