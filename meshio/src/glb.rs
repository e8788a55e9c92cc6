//! glTF 2.0 binary (`.glb`), write only.
//!
//! One scene with one node holding one mesh of one primitive (mode 4, triangles; polygons are
//! fan-triangulated around their first corner), with the attributes:
//!
//! * `POSITION`: `f32` `VEC3`, with the accessor `min`/`max` the specification requires;
//! * `NORMAL`: `f32` `VEC3`, normalized, only when the mesh has normals (a zero normal on a
//!   vertex used by a face is an error; unused vertices with a zero normal get `+z`);
//! * `COLOR_0`: `f32` `VEC3`, only when the mesh has colours. Float RGB rather than normalized
//!   `u8` RGBA: [`RawMesh::colors`] already is linear `f32` RGB, which is what glTF's `COLOR_0`
//!   means, so it is stored without quantization and without inventing an alpha; the 8 extra
//!   bytes per vertex do not matter next to positions and normals;
//! * indices: `u32` `SCALAR`.
//!
//! Buffer views are 4-byte aligned; the JSON chunk is padded with spaces and the BIN chunk with
//! zeros to a multiple of 4, as the specification requires. Positions are stored as `f32`
//! (glTF has no `f64` attributes). Shapes, names and other properties are not written. glTF
//! needs at least one triangle: an empty mesh is an error.

use serde_json::json;

use crate::error::{ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::RawMesh;
use crate::util::{fan, fan_count, validate_for_write};

const NAME: &str = "glb";

/// The `generator` string in the written `asset`.
pub const GENERATOR: &str = concat!("meshio ", env!("CARGO_PKG_VERSION"));

/// The glTF 2.0 binary format (`.glb`), write only.
#[derive(Clone, Copy, Debug, Default)]
pub struct Glb;

impl MeshFormat for Glb {
    fn name(&self) -> &'static str {
        NAME
    }

    fn extensions(&self) -> &'static [&'static str] {
        &["glb"]
    }

    fn sniff(&self, bytes: &[u8]) -> bool {
        bytes.starts_with(b"glTF")
    }

    fn can_read(&self) -> bool {
        false
    }

    fn read(&self, _: &[u8]) -> Result<RawMesh, ReadError> {
        Err(ReadError::header(
            NAME,
            "reading glTF binary is not supported (meshio writes .glb only)",
        ))
    }

    fn write(&self, mesh: &RawMesh, _: &WriteOptions) -> Result<Vec<u8>, WriteError> {
        write_glb(mesh)
    }
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

fn push_f32s(bin: &mut Vec<u8>, xs: impl IntoIterator<Item = f32>) {
    for x in xs {
        bin.extend_from_slice(&x.to_le_bytes());
    }
}

fn write_glb(mesh: &RawMesh) -> Result<Vec<u8>, WriteError> {
    validate_for_write(mesh, NAME)?;
    let n = mesh.positions.len();
    let ntri = fan_count(mesh);
    if ntri == 0 {
        return Err(WriteError::invalid(
            NAME,
            "glTF needs at least one triangle",
        ));
    }
    if u32::try_from(n).is_err() || u32::try_from(3 * ntri).is_err() {
        return Err(WriteError::invalid(
            NAME,
            "too many vertices or triangles for u32 indices",
        ));
    }
    let mut used = vec![false; n];
    for &i in mesh.polygons.iter().flatten() {
        if let Some(u) = used.get_mut(i) {
            *u = true;
        }
    }
    let vec3_bytes = 12 * n;
    let mut bin = Vec::with_capacity(vec3_bytes * 3 + 12 * ntri);
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut attributes = serde_json::Map::new();

    // POSITION
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in &mesh.positions {
        let v = [p.x as f32, p.y as f32, p.z as f32];
        for k in 0..3 {
            min[k] = min[k].min(v[k]);
            max[k] = max[k].max(v[k]);
        }
        push_f32s(&mut bin, v);
    }
    if !min.iter().chain(&max).all(|x| x.is_finite()) {
        return Err(WriteError::invalid(NAME, "a position does not fit an f32"));
    }
    let mut add = |bin_start: usize, bin_end: usize, target: u32, acc: serde_json::Value| {
        views.push(json!({
            "buffer": 0,
            "byteOffset": bin_start,
            "byteLength": bin_end - bin_start,
            "target": target,
        }));
        let mut acc = acc;
        acc["bufferView"] = json!(views.len() - 1);
        accessors.push(acc);
        accessors.len() - 1
    };
    let pos = add(
        0,
        bin.len(),
        ARRAY_BUFFER,
        json!({
            "componentType": FLOAT, "count": n, "type": "VEC3",
            "min": min, "max": max,
        }),
    );
    attributes.insert("POSITION".into(), json!(pos));

    if let Some(normals) = &mesh.normals {
        let start = bin.len();
        for (i, nv) in normals.iter().enumerate() {
            let unit = match nv.try_normalize(0.0) {
                Some(u) => u,
                None if !used.get(i).copied().unwrap_or(false) => nalgebra::Vector3::z(),
                None => {
                    return Err(WriteError::invalid(
                        NAME,
                        format!("vertex {i} has a zero normal"),
                    ))
                }
            };
            push_f32s(&mut bin, [unit.x as f32, unit.y as f32, unit.z as f32]);
        }
        let a = add(
            start,
            bin.len(),
            ARRAY_BUFFER,
            json!({
                "componentType": FLOAT, "count": n, "type": "VEC3",
            }),
        );
        attributes.insert("NORMAL".into(), json!(a));
    }
    if let Some(colors) = &mesh.colors {
        let start = bin.len();
        for c in colors {
            push_f32s(&mut bin, c.map(|x| x.clamp(0.0, 1.0)));
        }
        let a = add(
            start,
            bin.len(),
            ARRAY_BUFFER,
            json!({
                "componentType": FLOAT, "count": n, "type": "VEC3",
            }),
        );
        attributes.insert("COLOR_0".into(), json!(a));
    }
    let start = bin.len();
    for t in mesh.polygons.iter().flat_map(fan) {
        for i in t {
            bin.extend_from_slice(&(i as u32).to_le_bytes());
        }
    }
    let indices = add(
        start,
        bin.len(),
        ELEMENT_ARRAY_BUFFER,
        json!({
            "componentType": UNSIGNED_INT, "count": 3 * ntri, "type": "SCALAR",
        }),
    );
    // Every view is a multiple of 4 bytes long, so all offsets are 4-byte aligned.
    let doc = json!({
        "asset": { "version": "2.0", "generator": GENERATOR },
        "scene": 0,
        "scenes": [ { "nodes": [0] } ],
        "nodes": [ { "mesh": 0 } ],
        "meshes": [ { "primitives": [ {
            "attributes": attributes,
            "indices": indices,
            "mode": 4,
        } ] } ],
        "buffers": [ { "byteLength": bin.len() } ],
        "bufferViews": views,
        "accessors": accessors,
    });
    let mut json_bytes =
        serde_json::to_vec(&doc).map_err(|e| WriteError::invalid(NAME, format!("JSON: {e}")))?;
    while json_bytes.len() % 4 != 0 {
        json_bytes.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
    let total32 = u32::try_from(total)
        .map_err(|_| WriteError::invalid(NAME, "the file would exceed 4 GiB"))?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
}
