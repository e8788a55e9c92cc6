//! The triangles of a picture's stream kept for replaying, in bounded memory
//! ([`TriangleStore`]).
//!
//! A picture needs its triangles more than once: the camera is framed on all of them (a
//! bounding box, then a distance over every vertex: `render::Camera::framing_box`), the
//! highlight lines are spaced across their camera-space bounding box, and only then can a
//! pixel be drawn (`render::Canvas`). The store keeps them, in stream order, as render meshes
//! of at most [`CHUNK_TRIANGLES`] triangles — a `Triangle` record's three vertices, a
//! `TriangleMesh`'s as `crate::draw::push_triangle_mesh` lays them out, exactly as the whole
//! picture's mesh held them before — and hands them back chunk by chunk as often as asked
//! ([`TriangleStore::replay`]).
//!
//! Up to a budget ([`STORE_BYTES`]) the chunks stay in memory; past it they go, in order, to a
//! temporary file ([`crate::scratch_file`]: `TMPDIR`, unlinked at once) and are read back one
//! at a time. So the memory is the budget, the chunk being filled and one chunk read back,
//! whatever the stream holds. A chunk is closed before a `TriangleMesh` that would take it
//! past [`CHUNK_TRIANGLES`], so only a record larger than that (held in memory whole anyway,
//! when it was read) makes a larger chunk. A failed write or read of the file (a full disk) is
//! an error naming the file, never a panic.
//!
//! The file holds each chunk exactly: its vertex, normal, colour and face counts (u64), the
//! positions and normals (three f64 each), the colours (three f32) and the faces (three u32
//! chunk-local indices), all little-endian. An index that does not fit a u32 is past every
//! vertex of the chunk (a chunk holds fewer than 2³² vertices), so it is written as
//! `u32::MAX` and read back as an index past the end: skipped by every drawing, as before.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use nalgebra::{Point3, Vector3};
use render::{FrameBox, RenderMesh};

use crate::draw::{push_triangle, push_triangle_mesh};
use crate::error::{FilterError, StreamError};
use crate::record::Vertex;
use crate::scratch_file::{self, ScratchPath};
use crate::triangle_mesh::TriangleMesh;

/// Memory the stored chunks may take before the rest go to a temporary file: the budget of
/// records held by the colouring filters ([`crate::hold::HELD_BYTES`], 64 MiB), about 750 000
/// triangles of `tess --mesh` patches (some 85 bytes a triangle, a vertex shared by about
/// two), so pictures of honest sizes never touch the disk.
pub const STORE_BYTES: usize = crate::hold::HELD_BYTES;

/// Most triangles a chunk is closed at (before a record that would pass it): a chunk unwelded
/// at most about 13 MB, drawn in one go by the canvas (its set-up triangles about 9 MB more).
pub const CHUNK_TRIANGLES: usize = 65_536;

/// Bytes a stored chunk takes in memory: its arrays and their headers.
fn chunk_bytes(m: &RenderMesh) -> usize {
    std::mem::size_of_val(&m.positions[..])
        + std::mem::size_of_val(&m.normals[..])
        + std::mem::size_of_val(&m.colors[..])
        + std::mem::size_of_val(&m.faces[..])
        + std::mem::size_of::<RenderMesh>()
}

/// A stream's triangles, in chunks, in memory up to a budget and in a temporary file beyond
/// (module docs).
pub struct TriangleStore {
    budget: usize,
    dir: PathBuf,
    filter: &'static str,
    mem: Vec<RenderMesh>,
    mem_bytes: usize,
    building: RenderMesh,
    spill: Option<StoreFile>,
    spilled: usize,
    triangles: usize,
    bounds: FrameBox,
}

/// The temporary file of a store.
struct StoreFile {
    file: BufWriter<File>,
    /// One chunk's bytes (reused).
    bytes: Vec<u8>,
    _path: ScratchPath,
}

/// An I/O error of the temporary file, named.
fn store_error(e: std::io::Error) -> FilterError {
    StreamError::io("keeping the picture's triangles in a temporary file", e).into()
}

fn damaged() -> FilterError {
    store_error(std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        "the temporary file does not read back as written",
    ))
}

impl TriangleStore {
    /// An empty store for the filter `filter` (named in the note printed when the file is
    /// opened), keeping up to `budget` bytes of chunks in memory, the rest in a temporary file
    /// in the system's temporary directory (`TMPDIR`).
    pub fn new(budget: usize, filter: &'static str) -> Self {
        Self::in_dir(budget, filter, &std::env::temp_dir())
    }

    /// [`TriangleStore::new`] with the temporary file in `dir`.
    pub fn in_dir(budget: usize, filter: &'static str, dir: &Path) -> Self {
        TriangleStore {
            budget,
            dir: dir.to_path_buf(),
            filter,
            mem: Vec::new(),
            mem_bytes: 0,
            building: RenderMesh::default(),
            spill: None,
            spilled: 0,
            triangles: 0,
            bounds: FrameBox::default(),
        }
    }

    /// Triangles stored (faces, in range or not, as the pictures count them).
    pub fn triangles(&self) -> usize {
        self.triangles
    }

    /// Chunks in the temporary file.
    pub fn spilled(&self) -> usize {
        self.spilled
    }

    /// Memory taken by the chunks kept in memory (the estimate the budget is checked with).
    pub fn memory(&self) -> usize {
        self.mem_bytes
    }

    /// The bounding box of every finite vertex stored so far (the first pass of the camera's
    /// framing, gathered as the chunks close: `render::Camera::framing_box`). Complete after
    /// [`TriangleStore::finish`].
    pub fn bounds(&self) -> &FrameBox {
        &self.bounds
    }

    /// Stores one triangle (`crate::draw::push_triangle`: its normals, the geometric normal
    /// where a vertex has none; its colours, `default_color` where a vertex has none).
    pub fn push_triangle(
        &mut self,
        t: &[Vertex; 3],
        default_color: [f32; 3],
    ) -> Result<(), FilterError> {
        push_triangle(&mut self.building, t, default_color);
        self.triangles += 1;
        if self.building.faces.len() >= CHUNK_TRIANGLES {
            self.close()?;
        }
        Ok(())
    }

    /// Stores a `TriangleMesh` record's triangles (`crate::draw::push_triangle_mesh`), in a
    /// new chunk when they would take the current one past [`CHUNK_TRIANGLES`].
    pub fn push_triangle_mesh(
        &mut self,
        mesh: &TriangleMesh,
        default_color: [f32; 3],
    ) -> Result<(), FilterError> {
        if !self.building.faces.is_empty()
            && self.building.faces.len() + mesh.triangles.len() > CHUNK_TRIANGLES
        {
            self.close()?;
        }
        push_triangle_mesh(&mut self.building, mesh, default_color);
        self.triangles += mesh.triangles.len();
        if self.building.faces.len() >= CHUNK_TRIANGLES {
            self.close()?;
        }
        Ok(())
    }

    /// Closes the chunk being filled (the stream is read): every chunk is then in memory or
    /// in the file, and the file written out.
    pub fn finish(&mut self) -> Result<(), FilterError> {
        self.close()?;
        if let Some(spill) = self.spill.as_mut() {
            spill.file.flush().map_err(store_error)?;
        }
        Ok(())
    }

    /// Keeps the chunk being filled (if it holds anything) in memory or, past the budget and
    /// after the first chunk that went to the file (so the order stays), in the file.
    fn close(&mut self) -> Result<(), FilterError> {
        let m = &mut self.building;
        if m.positions.is_empty() && m.faces.is_empty() {
            return Ok(());
        }
        self.bounds.add(&m.positions);
        let cost = chunk_bytes(m);
        if self.spill.is_none() && self.mem_bytes + cost <= self.budget {
            let mut m = std::mem::take(m);
            m.positions.shrink_to_fit();
            m.normals.shrink_to_fit();
            m.colors.shrink_to_fit();
            m.faces.shrink_to_fit();
            self.mem_bytes += cost;
            self.mem.push(m);
            return Ok(());
        }
        if self.spill.is_none() {
            let (file, path) = scratch_file::create_in(&self.dir, "triangles")?;
            eprintln!(
                "{}: the triangles kept for drawing passed {} MiB; the rest wait in a temporary \
                 file ({}; removed when the filter ends)",
                self.filter,
                self.budget >> 20,
                self.dir.display()
            );
            self.spill = Some(StoreFile {
                file: BufWriter::with_capacity(1 << 16, file),
                bytes: Vec::new(),
                _path: path,
            });
        }
        if let Some(spill) = self.spill.as_mut() {
            spill.bytes.clear();
            encode(&mut spill.bytes, m);
            spill.file.write_all(&spill.bytes).map_err(store_error)?;
            self.spilled += 1;
        }
        // Keep the allocation for the next chunk.
        m.positions.clear();
        m.normals.clear();
        m.colors.clear();
        m.faces.clear();
        Ok(())
    }

    /// Hands every stored chunk to `f`, in the order stored (memory first, then the file,
    /// read back one chunk at a time into one reused mesh); as often as asked. The store must
    /// be finished ([`TriangleStore::finish`]; a chunk still being filled is handed last). An
    /// error of `f` or of the file ends the replay and is returned.
    pub fn replay(
        &mut self,
        f: &mut dyn FnMut(&RenderMesh) -> Result<(), FilterError>,
    ) -> Result<(), FilterError> {
        for m in &self.mem {
            f(m)?;
        }
        if let Some(spill) = self.spill.as_mut() {
            spill.file.flush().map_err(store_error)?;
            let file = spill.file.get_mut();
            file.seek(SeekFrom::Start(0)).map_err(store_error)?;
            let mut reader = BufReader::with_capacity(1 << 16, &mut *file);
            let mut m = RenderMesh::default();
            for _ in 0..self.spilled {
                decode(&mut reader, &mut spill.bytes, &mut m)?;
                f(&m)?;
            }
            drop(reader);
            // Later chunks are appended.
            file.seek(SeekFrom::End(0)).map_err(store_error)?;
        }
        if !self.building.positions.is_empty() || !self.building.faces.is_empty() {
            f(&self.building)?;
        }
        Ok(())
    }
}

fn put_u64(out: &mut Vec<u8>, x: usize) {
    out.extend_from_slice(&(x as u64).to_le_bytes());
}

/// Appends one chunk (the layout of the module docs).
fn encode(out: &mut Vec<u8>, m: &RenderMesh) {
    put_u64(out, m.positions.len());
    put_u64(out, m.normals.len());
    put_u64(out, m.colors.len());
    put_u64(out, m.faces.len());
    for p in &m.positions {
        for x in p.iter() {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    for n in &m.normals {
        for x in n.iter() {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    for c in &m.colors {
        for x in c {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    for f in &m.faces {
        for &i in f {
            out.extend_from_slice(&u32::try_from(i).unwrap_or(u32::MAX).to_le_bytes());
        }
    }
}

/// Bytes of one position or normal, of one colour, of one face in the file.
const VEC_BYTES: usize = 24;
/// See [`VEC_BYTES`].
const COLOR_BYTES: usize = 12;
/// See [`VEC_BYTES`].
const FACE_BYTES: usize = 12;

/// Reads one chunk into `m` (its storage reused), through `bytes`. The file is this
/// process's own, but its counts are checked all the same: a chunk's arrays are at most a
/// record's, far below 2⁴⁰ bytes.
fn decode(r: &mut impl Read, bytes: &mut Vec<u8>, m: &mut RenderMesh) -> Result<(), FilterError> {
    /// More bytes than a chunk can hold: the counts are damaged.
    const MOST: u128 = 1 << 40;
    let mut head = [0u8; 32];
    r.read_exact(&mut head).map_err(store_error)?;
    let count = |k: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&head[8 * k..8 * k + 8]);
        u64::from_le_bytes(b)
    };
    let (np, nn, nc, nf) = (count(0), count(1), count(2), count(3));
    let total = (u128::from(np) + u128::from(nn)) * VEC_BYTES as u128
        + u128::from(nc) * COLOR_BYTES as u128
        + u128::from(nf) * FACE_BYTES as u128;
    if total > MOST {
        return Err(damaged());
    }
    let (np, nn, nc, nf) = (np as usize, nn as usize, nc as usize, nf as usize);
    bytes.resize(total as usize, 0);
    r.read_exact(bytes).map_err(store_error)?;
    let f64_at = |at: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&bytes[at..at + 8]);
        f64::from_le_bytes(b)
    };
    let four = |at: usize| {
        let mut b = [0u8; 4];
        b.copy_from_slice(&bytes[at..at + 4]);
        b
    };
    let vec_at = |at: usize| [f64_at(at), f64_at(at + 8), f64_at(at + 16)];
    m.positions.clear();
    m.positions
        .extend((0..np).map(|i| Point3::from(vec_at(VEC_BYTES * i))));
    let base = VEC_BYTES * np;
    m.normals.clear();
    m.normals
        .extend((0..nn).map(|i| Vector3::from(vec_at(base + VEC_BYTES * i))));
    let base = base + VEC_BYTES * nn;
    m.colors.clear();
    m.colors.extend((0..nc).map(|i| {
        let at = base + COLOR_BYTES * i;
        std::array::from_fn(|k| f32::from_le_bytes(four(at + 4 * k)))
    }));
    let base = base + COLOR_BYTES * nc;
    m.faces.clear();
    m.faces.extend((0..nf).map(|i| {
        let at = base + FACE_BYTES * i;
        std::array::from_fn(|k| match u32::from_le_bytes(four(at + 4 * k)) {
            u32::MAX => usize::MAX,
            x => x as usize,
        })
    }));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Triangle `i` of the test streams: corners that differ from triangle to triangle, some
    /// vertices with normals and colours, some without, one corner not finite now and then.
    fn triangle(i: usize) -> [Vertex; 3] {
        let t = i as f64 * 0.618;
        let at = |k: f64| Point3::new(t.sin() + k, t.cos() * k, 1e-3 * t - k);
        [
            Vertex {
                pos: at(0.0),
                norm: Some(Vector3::new(0.1, t, -1.0)),
                color: Some([0.25, (i % 7) as f32 / 7.0, 1.0]),
                kg: None,
                km: None,
            },
            Vertex {
                pos: if i % 13 == 5 {
                    Point3::new(f64::NAN, 0.0, 1.0)
                } else {
                    at(1.0)
                },
                norm: None,
                color: None,
                kg: None,
                km: None,
            },
            Vertex {
                pos: at(2.5),
                norm: (i % 2 == 0).then(|| Vector3::new(t, 1.0, 0.5)),
                color: None,
                kg: None,
                km: None,
            },
        ]
    }

    /// A TriangleMesh record of `n` triangles over `n + 2` shared vertices (a strip), with
    /// normals and colours.
    fn strip(n: usize, shift: f64) -> TriangleMesh {
        let mut m = TriangleMesh::default();
        for k in 0..n + 2 {
            let x = k as f64 + shift;
            m.pos.push(Point3::new(x, (k % 2) as f64, 0.1 * x));
            m.norm.push(Vector3::new(0.0, 0.1 * x, 1.0));
            m.color.push([0.5, 0.25, (k % 3) as f32 / 3.0]);
        }
        m.triangles = (0..n as u32).map(|k| [k, k + 1, k + 2]).collect();
        m
    }

    /// The stream the tests store: single triangles and strips in turn, some strips larger
    /// than a chunk.
    fn fill(store: &mut TriangleStore, whole: &mut RenderMesh) {
        /// Strip sizes: small ones, one just under a chunk, one over.
        const STRIPS: [usize; 5] = [3, 1000, CHUNK_TRIANGLES - 1, 17, CHUNK_TRIANGLES + 9];
        let colour = render::colors::MATERIAL;
        let mut i = 0;
        for (s, &n) in STRIPS.iter().enumerate() {
            for _ in 0..(s * 9000 + 5) {
                let t = triangle(i);
                store.push_triangle(&t, colour).unwrap();
                push_triangle(whole, &t, colour);
                i += 1;
            }
            let m = strip(n, s as f64);
            store.push_triangle_mesh(&m, colour).unwrap();
            push_triangle_mesh(whole, &m, colour);
        }
        store.finish().unwrap();
    }

    /// Concatenates replayed chunks into one mesh (faces renumbered), as the picture's mesh
    /// was built before.
    fn concatenated(store: &mut TriangleStore) -> (RenderMesh, usize) {
        let mut all = RenderMesh::default();
        let mut chunks = 0;
        store
            .replay(&mut |m| {
                let base = all.positions.len();
                all.positions.extend_from_slice(&m.positions);
                all.normals.extend_from_slice(&m.normals);
                all.colors.extend_from_slice(&m.colors);
                all.faces
                    .extend(m.faces.iter().map(|f| f.map(|i| base + i)));
                chunks += 1;
                assert!(
                    m.faces.len() <= CHUNK_TRIANGLES + 9,
                    "a chunk of {} triangles",
                    m.faces.len()
                );
                Ok(())
            })
            .unwrap();
        (all, chunks)
    }

    /// Bit patterns of a mesh's numbers (NaN compared as bits, which `==` would not).
    fn bits(m: &RenderMesh) -> (Vec<u64>, Vec<u32>, Vec<[usize; 3]>) {
        let v: Vec<u64> = m
            .positions
            .iter()
            .flat_map(|p| p.coords.iter().copied().collect::<Vec<_>>())
            .chain(
                m.normals
                    .iter()
                    .flat_map(|n| n.iter().copied().collect::<Vec<_>>()),
            )
            .map(f64::to_bits)
            .collect();
        let c = m.colors.iter().flatten().map(|x| x.to_bits()).collect();
        (v, c, m.faces.clone())
    }

    #[test]
    fn chunks_come_back_exact_in_memory_and_spilled_and_replay_again() {
        /// A budget of a few small chunks: most of the stream spills.
        const TINY: usize = 200 << 10;
        for budget in [usize::MAX, TINY] {
            let mut store = TriangleStore::new(budget, "test");
            let mut whole = RenderMesh::default();
            fill(&mut store, &mut whole);
            assert_eq!(store.triangles(), whole.faces.len());
            assert!(store.memory() <= budget);
            if budget == TINY {
                assert!(store.spilled() >= 3, "{}", store.spilled());
            } else {
                assert_eq!(store.spilled(), 0);
            }
            for _ in 0..3 {
                let (back, chunks) = concatenated(&mut store);
                assert!(chunks >= 4, "{chunks}");
                assert!(bits(&back) == bits(&whole), "budget {budget}");
            }
            let mut lo_hi = FrameBox::default();
            lo_hi.add(&whole.positions);
            assert_eq!(store.bounds(), &lo_hi);
        }
    }

    #[test]
    fn a_file_that_cannot_be_made_is_a_clear_error_and_a_replay_error_stops_it() {
        let dir = std::env::temp_dir().join(format!("no-such-dir-{}", std::process::id()));
        let mut store = TriangleStore::in_dir(0, "test", &dir);
        let err = store
            .push_triangle_mesh(&strip(CHUNK_TRIANGLES, 0.0), render::colors::MATERIAL)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("creating a temporary file in") && err.contains("no-such-dir"),
            "{err}"
        );
        let dir = tempfile::tempdir().unwrap();
        let mut store = TriangleStore::in_dir(0, "test", dir.path());
        store
            .push_triangle_mesh(&strip(10, 0.0), render::colors::MATERIAL)
            .unwrap();
        store.finish().unwrap();
        assert_eq!(store.spilled(), 1);
        // The file in use has no name in its directory (unlinked at once).
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
        let err = store
            .replay(&mut |_| Err(FilterError::Usage("stop".into())))
            .unwrap_err();
        assert_eq!(err.to_string(), "stop");
        // The file reads back after an interrupted replay.
        assert_eq!(concatenated(&mut store).0.faces.len(), 10);
    }

    #[test]
    fn a_damaged_file_is_an_error_not_a_panic() {
        let mut bytes = Vec::new();
        let mut m = RenderMesh::default();
        encode(&mut bytes, &RenderMesh::default());
        let mut huge = bytes.clone();
        huge[0..8].copy_from_slice(&u64::MAX.to_le_bytes());
        let err = decode(&mut &huge[..], &mut Vec::new(), &mut m).unwrap_err();
        assert!(err.to_string().contains("does not read back"), "{err}");
        let mut m2 = RenderMesh::default();
        push_triangle(&mut m2, &triangle(3), [0.5; 3]);
        let mut one = Vec::new();
        encode(&mut one, &m2);
        let cut = &one[..one.len() - 1];
        let err = decode(&mut &cut[..], &mut Vec::new(), &mut m).unwrap_err();
        assert!(err.to_string().contains("temporary file"), "{err}");
        decode(&mut &one[..], &mut Vec::new(), &mut m).unwrap();
        assert!(bits(&m) == bits(&m2));
    }
}
