//! Data per face corner: one normal and one shape tensor per **sector** of a vertex (the faces
//! of its fan between two creases, [`crate::features`]), so that a crease keeps both of its
//! tangent planes instead of one averaged normal.
//!
//! # Slots
//!
//! Every face corner `(f, c)` (corner index `3 f + c`) belongs to one **slot**: the sector of its
//! vertex that face `f` lies in. Two corners at the same vertex share a slot exactly when their
//! faces are joined around the vertex through edges that are not creases. The slots are the
//! classes of the relation "corner `(f, c)` ~ the corner of the same vertex in the face across a
//! smooth edge at it", closed transitively (a union–find over the `3F` corners, `O(F α(F))`,
//! [`Sectors::new`]). So a vertex with no crease, or with one (a dart: the crease fades into the
//! fan, which stays connected round the other side), has one slot; a vertex on a crease line
//! two; a corner of `k` creases `k`; a boundary vertex with `c` creases `c + 1`.
//!
//! A crease edge whose two faces share a slot at both ends (a crease between two darts: the fan
//! is connected round both ends) carries no per-sector data, and is treated as smooth
//! ([`Sectors::is_crease`] is false for it; [`Sectors::demoted`] counts these).
//!
//! Slots are numbered by their first corner in corner order, so the numbering depends only on
//! the faces and the creases.
//!
//! # The split mesh
//!
//! [`Sectors::split_mesh`] gives the mesh with one vertex per slot and the same faces (face `f`
//! of the split mesh uses the slots of `f`'s corners): the mesh cut open along its creases. Any
//! per-vertex computation run on it is per sector, with neighbourhoods that never cross a crease;
//! that is how every estimator estimates per sector ([`Sectors::set_slot_data`] takes the
//! result back).

use nalgebra::{Matrix3, Vector3};

use rayon::prelude::*;

use crate::disjoint::DisjointSets;
use crate::mesh::{Mesh, MeshError, Vertex, NO_TWIN};
use crate::vertex::VertexData;

/// The sectors of a mesh and their data (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct Sectors {
    /// Per corner `3 f + c`: its slot.
    corner_slot: Vec<usize>,
    /// Per slot: its vertex.
    slot_vertex: Vec<usize>,
    /// Per slot: unit normal.
    normals: Vec<Vector3<f64>>,
    /// Per slot: shape tensor (`S n = 0`).
    shapes: Vec<Matrix3<f64>>,
    /// Per slot: whether the shape tensor is known.
    curvature_known: Vec<bool>,
    /// Per edge: the two faces have different slots at one end at least.
    crease: Vec<bool>,
    /// Crease edges asked for whose faces share both slots (between two darts).
    demoted: usize,
}

/// Why sectors could not be attached to a mesh.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SectorError {
    /// The crease flags are not one per edge.
    #[error("{given} crease flags for a mesh of {edges} edges")]
    CreaseCount {
        /// Flags given.
        given: usize,
        /// Edges of the mesh.
        edges: usize,
    },
    /// Sectors made for another mesh.
    #[error("sectors of {corners} corners for a mesh of {faces} faces")]
    Mismatch {
        /// Corners the sectors have.
        corners: usize,
        /// Faces of the mesh.
        faces: usize,
    },
    /// Data for the slots of the wrong length.
    #[error("{given} values for {slots} slots")]
    SlotCount {
        /// Values given.
        given: usize,
        /// Slots.
        slots: usize,
    },
    /// The split mesh did not validate (a bug: cutting a valid mesh along edges keeps it valid).
    #[error("the mesh cut along its creases is invalid: {0}")]
    Split(MeshError),
}

impl Sectors {
    /// The slots of `mesh` cut at the edges flagged in `crease` (one flag per edge, in
    /// `mesh.edges()` order), each slot's data initialized from its vertex.
    pub fn new(mesh: &Mesh, crease: &[bool]) -> Result<Sectors, SectorError> {
        let edges = mesh.edges();
        if crease.len() != edges.len() {
            return Err(SectorError::CreaseCount {
                given: crease.len(),
                edges: edges.len(),
            });
        }
        let faces = mesh.faces();
        let mut sets = DisjointSets::new(3 * faces.len());
        // The corner of face `f` at vertex `v`.
        let corner_at = |f: usize, v: usize| -> Option<usize> {
            faces[f].iter().position(|&x| x == v).map(|c| 3 * f + c)
        };
        for (e, edge) in edges.clone().enumerate() {
            let Some((g, _)) = edge.second else { continue };
            if crease[e] {
                continue;
            }
            let (f, _) = edge.first;
            for &v in &edge.vertices {
                if let (Some(a), Some(b)) = (corner_at(f, v), corner_at(g, v)) {
                    sets.union(a, b);
                }
            }
        }
        let mut corner_slot = vec![usize::MAX; 3 * faces.len()];
        let mut slot_vertex = Vec::new();
        for c in 0..corner_slot.len() {
            let r = sets.find(c);
            if corner_slot[r] == usize::MAX {
                corner_slot[r] = slot_vertex.len();
                slot_vertex.push(faces[r / 3][r % 3]);
            }
            corner_slot[c] = corner_slot[r];
        }
        let slot_of = |f: usize, v: usize| corner_at(f, v).map(|c| corner_slot[c]);
        let mut demoted = 0;
        let effective: Vec<bool> = edges
            .zip(crease)
            .map(|(edge, &asked)| {
                let Some((g, _)) = edge.second else {
                    return false;
                };
                if !asked {
                    return false;
                }
                let (f, _) = edge.first;
                let split = edge
                    .vertices
                    .iter()
                    .any(|&v| slot_of(f, v) != slot_of(g, v));
                if !split {
                    demoted += 1;
                }
                split
            })
            .collect();
        let verts = mesh.vertices();
        Ok(Sectors {
            normals: slot_vertex.iter().map(|&v| verts[v].data.n).collect(),
            shapes: slot_vertex.iter().map(|&v| verts[v].data.shape).collect(),
            curvature_known: slot_vertex
                .iter()
                .map(|&v| verts[v].curvature_known)
                .collect(),
            corner_slot,
            slot_vertex,
            crease: effective,
            demoted,
        })
    }

    /// Number of slots (at least the number of used vertices).
    pub fn num_slots(&self) -> usize {
        self.slot_vertex.len()
    }

    /// The slot of corner `c` of face `f` (`None` past the end).
    pub fn slot(&self, f: usize, c: usize) -> Option<usize> {
        self.corner_slot.get(3 * f + c).copied()
    }

    /// The vertex of slot `s`.
    pub fn slot_vertex(&self, s: usize) -> Option<usize> {
        self.slot_vertex.get(s).copied()
    }

    /// Every slot's vertex, in slot order.
    pub fn slot_vertices(&self) -> &[usize] {
        &self.slot_vertex
    }

    /// The normal of slot `s`.
    pub fn normal(&self, s: usize) -> Option<&Vector3<f64>> {
        self.normals.get(s)
    }

    /// The shape tensor of slot `s`.
    pub fn shape(&self, s: usize) -> Option<&Matrix3<f64>> {
        self.shapes.get(s)
    }

    /// Whether slot `s`'s shape tensor is known.
    pub fn curvature_known(&self, s: usize) -> bool {
        self.curvature_known.get(s).copied().unwrap_or(false)
    }

    /// True when edge `e` separates two sectors at one end at least (module docs).
    pub fn is_crease(&self, e: usize) -> bool {
        self.crease.get(e).copied().unwrap_or(false)
    }

    /// Per edge: [`Sectors::is_crease`].
    pub fn creases(&self) -> &[bool] {
        &self.crease
    }

    /// The number of crease edges (effective ones).
    pub fn num_creases(&self) -> usize {
        self.crease.iter().filter(|&&c| c).count()
    }

    /// Crease edges asked for that separate no sectors (between two darts): treated as smooth.
    pub fn demoted(&self) -> usize {
        self.demoted
    }

    /// The number of slots of each vertex (0 for an isolated vertex).
    pub fn slots_per_vertex(&self, num_vertices: usize) -> Vec<usize> {
        let mut out = vec![0; num_vertices];
        for &v in &self.slot_vertex {
            if let Some(n) = out.get_mut(v) {
                *n += 1;
            }
        }
        out
    }

    /// The mesh cut open along the creases: one vertex per slot (its vertex's data, with the
    /// slot's normal and shape tensor), the same faces in the same order (module docs).
    pub fn split_mesh(&self, mesh: &Mesh) -> Result<Mesh, SectorError> {
        self.check(mesh)?;
        let verts = mesh.vertices();
        let vertices: Vec<Vertex> = (0..self.num_slots())
            .map(|s| {
                let v = &verts[self.slot_vertex[s]];
                let mut slot =
                    Vertex::new(VertexData::new(v.data.p, self.normals[s], self.shapes[s]));
                slot.curvature_known = self.curvature_known[s];
                slot
            })
            .collect();
        let faces: Vec<[usize; 3]> = (0..mesh.num_faces())
            .map(|f| std::array::from_fn(|c| self.corner_slot[3 * f + c]))
            .collect();
        // The same twins but across the creases: cutting a valid mesh along edges leaves every
        // face valid and every fan one fan, so the split mesh needs no validation beyond its
        // vertex data ([`Mesh::from_twins`]; debug builds check the rest).
        let twin: Vec<usize> = (0..mesh.num_half_edges())
            .into_par_iter()
            .map(|h| {
                let e = mesh.edge_of_half_edge(h);
                match mesh.twin_of(h) {
                    Some(t) if !self.crease.get(e).copied().unwrap_or(false) => t,
                    _ => NO_TWIN,
                }
            })
            .collect();
        Mesh::from_twins(vertices, faces, twin).map_err(SectorError::Split)
    }

    /// Sets every slot's normal and shape tensor (one each per slot, e.g. an estimate on
    /// [`Sectors::split_mesh`]), marking the curvature known.
    pub fn set_slot_data(
        &mut self,
        normals: Vec<Vector3<f64>>,
        shapes: Vec<Matrix3<f64>>,
    ) -> Result<(), SectorError> {
        for given in [normals.len(), shapes.len()] {
            if given != self.num_slots() {
                return Err(SectorError::SlotCount {
                    given,
                    slots: self.num_slots(),
                });
            }
        }
        self.normals = normals;
        self.shapes = shapes;
        self.curvature_known = vec![true; self.num_slots()];
        Ok(())
    }

    /// Sets slot `s`'s normal and shape tensor.
    pub fn set_slot(&mut self, s: usize, n: Vector3<f64>, shape: Matrix3<f64>, known: bool) {
        if s < self.num_slots() {
            self.normals[s] = n;
            self.shapes[s] = shape;
            self.curvature_known[s] = known;
        }
    }

    /// Checks that these sectors were made for `mesh` (same corner and edge counts).
    pub fn check(&self, mesh: &Mesh) -> Result<(), SectorError> {
        if self.corner_slot.len() != 3 * mesh.num_faces() || self.crease.len() != mesh.num_edges() {
            return Err(SectorError::Mismatch {
                corners: self.corner_slot.len(),
                faces: mesh.num_faces(),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used)] // test fixtures fail loudly by design
    use super::*;
    use nalgebra::Point3;

    fn v(x: f64, y: f64, z: f64) -> Vertex {
        Vertex::without_curvature(Point3::new(x, y, z), Vector3::z())
    }

    /// Two squares folded along the y axis (x = 0): faces 0, 1 in z = 0 (x ≥ 0), faces 2, 3 in
    /// x = 0 (z ≥ 0). The fold edge is 0–3 (from (0,0,0) to (0,1,0)).
    fn folded() -> Mesh {
        let verts = vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(0.0, 1.0, 1.0),
        ];
        Mesh::new(verts, vec![[0, 1, 2], [0, 2, 3], [0, 3, 5], [0, 5, 4]]).unwrap()
    }

    fn crease_at(mesh: &Mesh, a: usize, b: usize) -> Vec<bool> {
        let e = mesh.find_edge(a, b).unwrap();
        (0..mesh.num_edges()).map(|i| i == e).collect()
    }

    #[test]
    fn a_crease_line_across_an_open_strip_splits_its_vertices_in_two() {
        let m = folded();
        let s = Sectors::new(&m, &crease_at(&m, 0, 3)).unwrap();
        // Vertices 0 and 3 lie on the crease (boundary vertices with one crease: two slots).
        assert_eq!(s.slots_per_vertex(6), vec![2, 1, 1, 2, 1, 1]);
        assert_eq!(s.num_creases(), 1);
        assert_eq!(s.demoted(), 0);
        // Faces 0, 1 share the slot of vertex 0; face 2 has the other.
        assert_eq!(s.slot(0, 0), s.slot(1, 0));
        assert_ne!(s.slot(1, 0), s.slot(2, 0));
        let split = s.split_mesh(&m).unwrap();
        assert_eq!(split.num_vertices(), 8);
        assert_eq!(split.num_faces(), 4);
        // Cut open: the fold edge became two boundary edges.
        assert_eq!(split.boundary_edges().len(), m.boundary_edges().len() + 2);
    }

    #[test]
    fn a_crease_between_two_darts_is_demoted() {
        // A closed fan around vertex 0 (a hexagon), crease on one spoke 0–1: vertex 0 is a dart
        // (one crease), and vertex 1 is a boundary vertex whose fan is two faces joined across
        // that spoke only... so the crease splits vertex 1 but not vertex 0.
        let mut verts = vec![v(0.0, 0.0, 0.0)];
        for k in 0..6 {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_3;
            verts.push(v(a.cos(), a.sin(), 0.0));
        }
        let faces: Vec<[usize; 3]> = (0..6).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        let m = Mesh::new(verts, faces).unwrap();
        let s = Sectors::new(&m, &crease_at(&m, 0, 1)).unwrap();
        assert_eq!(s.slots_per_vertex(7)[0], 1, "a dart keeps one sector");
        assert_eq!(s.slots_per_vertex(7)[1], 2, "the boundary end is cut");
        assert!(s.is_crease(m.find_edge(0, 1).unwrap()));
        // Two spokes: the hub has two sectors; now a crease whose both ends keep one slot.
        let inner = {
            // A closed octahedron: every vertex has a closed fan; one crease edge between two
            // darts separates nothing.
            let p = [
                v(1.0, 0.0, 0.0),
                v(-1.0, 0.0, 0.0),
                v(0.0, 1.0, 0.0),
                v(0.0, -1.0, 0.0),
                v(0.0, 0.0, 1.0),
                v(0.0, 0.0, -1.0),
            ];
            let f = vec![
                [0, 2, 4],
                [2, 1, 4],
                [1, 3, 4],
                [3, 0, 4],
                [2, 0, 5],
                [1, 2, 5],
                [3, 1, 5],
                [0, 3, 5],
            ];
            Mesh::new(p.to_vec(), f).unwrap()
        };
        let s = Sectors::new(&inner, &crease_at(&inner, 0, 4)).unwrap();
        assert_eq!(s.num_creases(), 0);
        assert_eq!(s.demoted(), 1);
        assert_eq!(s.num_slots(), 6);
    }

    #[test]
    fn no_creases_give_one_slot_per_vertex_and_the_same_mesh() {
        let m = folded();
        let s = Sectors::new(&m, &vec![false; m.num_edges()]).unwrap();
        assert_eq!(s.num_slots(), 6);
        let split = s.split_mesh(&m).unwrap();
        assert_eq!(split.num_edges(), m.num_edges());
        assert!(Sectors::new(&m, &[true]).is_err());
    }
}
