//! glTF 2.0 binary (`.glb`): written and read.
//!
//! # Writing
//!
//! One scene with one node holding one mesh of one primitive (mode 4, triangles; polygons are
//! fan-triangulated around their first corner), with the attributes:
//!
//! * `POSITION`: `f32` `VEC3`, with the accessor `min`/`max` the specification requires;
//! * `NORMAL`: `f32` `VEC3`, normalized, only when the mesh has normals (a zero normal on a
//!   vertex used by a face is an error; unused vertices with a zero normal get `+y`);
//! * `COLOR_0`: `f32` `VEC3`, only when the mesh has colours. Float RGB rather than normalized
//!   `u8` RGBA: [`RawMesh::colors`] already is linear `f32` RGB, which is what glTF's `COLOR_0`
//!   means (no sRGB encoding here, unlike PLY, OBJ and OFF), so it is stored without
//!   quantization and without inventing an alpha;
//! * `_GAUSSIAN_CURVATURE`, `_MEAN_CURVATURE`: `f32` `SCALAR`, when the mesh has
//!   [`RawMesh::curvature`] (the exported convention: `H > 0` on a sphere with outward normals;
//!   application-specific attribute names start with `_`, as the specification asks), each
//!   value checked to fit an `f32`;
//! * indices: `u32` `SCALAR`.
//!
//! **Up axis.** glTF is `y` up; the workbench's data are `z` up. With [`UpAxis::Z`] (the
//! default) positions and normals are turned by [`UpAxis::to_gltf`], `(x, y, z) ↦ (x, z, −y)`,
//! so that a viewer shows the data upright; with [`UpAxis::Y`] they are written as they are.
//!
//! `asset.generator` is [`crate::convention::GENERATOR`]; `asset.extras` records what a reader
//! cannot tell from the attributes: `data_up_axis` (`"z"` or `"y"`) and `gltf_from_data` (the
//! turn applied), the `curvature_convention` and the curvature attributes' meaning when there
//! is curvature or colours by it, and the `color_map` (quantity, map, `min`, `max`, encoding
//! `linear`) when the colours show one.
//!
//! Buffer views are 4-byte aligned; the JSON chunk is padded with spaces and the BIN chunk with
//! zeros to a multiple of 4, as the specification requires. Positions are stored as `f32`
//! (glTF has no `f64` attributes). Shapes, names and other properties are not written. glTF
//! needs at least one triangle: an empty mesh is an error.
//!
//! # Reading
//!
//! The 12-byte header (magic `glTF`, version 2, the total length, which must be the file's),
//! then the `JSON` chunk and an optional `BIN` chunk (other chunks are skipped). The document's
//! default scene (or scene 0; every mesh once when there are no scenes) is walked from its
//! root nodes; each node's transform (`matrix`, or `translation`/`rotation`/`scale`) is
//! composed with its parents', and every primitive of every mesh a node holds becomes
//! triangles of one [`RawMesh`] (a transform with a negative determinant reverses the winding,
//! as the specification says). Attributes read: `POSITION` (required, `FLOAT` `VEC3`), `NORMAL`
//! (`FLOAT` `VEC3`, turned with the inverse transpose), `COLOR_0` (`FLOAT`, or normalized
//! `UNSIGNED_BYTE`/`UNSIGNED_SHORT`, `VEC3` or `VEC4`; alpha dropped with a note; linear, as the
//! specification says) and the writer's `_GAUSSIAN_CURVATURE`/`_MEAN_CURVATURE`; normals,
//! colours and curvature are kept only when every primitive has them (else dropped with a
//! note), curvature only when no node scales. Positions and normals are turned back from
//! glTF's `y` up into the data's `z` up ([`UpAxis::from_gltf`]) unless `asset.extras` says the
//! data were `y` up (`data_up_axis: "y"`), so that writing and reading give the mesh back.
//!
//! Refused, with the accessor, buffer view, node, mesh or primitive at fault: a header or chunk
//! that does not fit the file, JSON that does not parse or lacks what is needed, a required
//! extension (`extensionsRequired`: Draco, quantization, …), a buffer other than the `BIN`
//! chunk (`uri`s are not followed), sparse accessors and accessors without a buffer view, a
//! component type or element type an attribute cannot have, a stride smaller than an element,
//! an accessor or view that reaches past its view or buffer, primitives that are not triangles
//! (mode 4), an index count not a multiple of 3, an index out of range, non-finite numbers,
//! a node reached twice (a cycle or a shared child: glTF nodes form trees), and a scene that
//! instances its meshes so often that the mesh read would exceed [`MAX_EXPANSION`] times the
//! file's size. Every accessor is checked against the bytes it reads before anything is
//! allocated from its count.

use std::collections::BTreeMap;

use nalgebra::{Matrix3, Matrix4, Point3, Quaternion, UnitQuaternion, Vector3};
use serde::Deserialize;
use serde_json::json;

use crate::convention::{Curvature, UpAxis, CURVATURE_CONVENTION, GENERATOR};
use crate::error::{Location, ReadError, WriteError};
use crate::format::{MeshFormat, WriteOptions};
use crate::raw::{Polygons, RawMesh};
use crate::util::{check_f32_values, fan, fan_count, validate_for_write};

const NAME: &str = "glb";

/// The attribute name of the Gaussian curvature (application-specific: starts with `_`).
pub const GAUSSIAN_ATTRIBUTE: &str = "_GAUSSIAN_CURVATURE";

/// The attribute name of the mean curvature (exported convention: `H > 0` on a sphere).
pub const MEAN_ATTRIBUTE: &str = "_MEAN_CURVATURE";

/// The attribute names of the principal curvatures `κ1 ≥ κ2` (scalars) and their unit
/// directions (`VEC3`, turned to glTF's up axis like the normals), written when the mesh's
/// curvature has directions.
pub const PRINCIPAL_ATTRIBUTES: [&str; 4] = [
    "_PRINCIPAL_CURVATURE_1",
    "_PRINCIPAL_CURVATURE_2",
    "_PRINCIPAL_DIRECTION_1",
    "_PRINCIPAL_DIRECTION_2",
];

/// The mesh a `.glb` is read into may take at most this many times the file's bytes. A mesh
/// used once takes about 3 times its bytes in a [`RawMesh`] (`f64` positions from `f32`,
/// `usize` indices and offsets from `u32`); a scene that instances a mesh from many nodes
/// multiplies that, and a few bytes of nodes could otherwise ask for any amount of memory.
pub const MAX_EXPANSION: u64 = 32;

/// Bytes a [`RawMesh`] takes a vertex with every attribute (position, normal, colour,
/// curvature) and a triangle (three `usize` indices and an offset), for the estimate.
const RAW_VERTEX_BYTES: u64 = 24 + 24 + 12 + 16;
const RAW_TRIANGLE_BYTES: u64 = 4 * 8;

/// The glTF 2.0 binary format (`.glb`).
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

    fn writes_curvature(&self) -> bool {
        true
    }

    fn read(&self, bytes: &[u8]) -> Result<RawMesh, ReadError> {
        read_glb(bytes)
    }

    fn size_hint(&self, mesh: &RawMesh, _: &WriteOptions) -> usize {
        // Positions and normals as 12 bytes a vertex, 12 bytes a triangle of indices, and the
        // JSON.
        4096 + 24 * mesh.positions.len() + 12 * crate::util::fan_count(mesh)
    }

    fn write_to(
        &self,
        mesh: &RawMesh,
        options: &WriteOptions,
        out: &mut dyn std::io::Write,
    ) -> Result<(), WriteError> {
        write_glb(mesh, options.up, out)
    }
}

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const UNSIGNED_BYTE: u32 = 5121;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;
const FLOAT: u32 = 5126;

fn push_f32s(sink: &mut crate::util::Sink<'_>, xs: impl IntoIterator<Item = f32>) {
    for x in xs {
        sink.f32(x);
    }
}

/// What `asset.extras` records (module docs).
fn extras(mesh: &RawMesh, up: UpAxis) -> serde_json::Value {
    let mut e = serde_json::Map::new();
    e.insert("data_up_axis".into(), json!(up.name()));
    e.insert(
        "gltf_from_data".into(),
        json!(match up {
            UpAxis::Z => "(x, y, z) -> (x, z, -y): the data's z is glTF's y",
            UpAxis::Y => "unchanged: the data's y is up",
        }),
    );
    let by_curvature = mesh
        .color_map
        .as_ref()
        .is_some_and(|m| m.quantity.contains("curvature"));
    if mesh.curvature.is_some() || by_curvature {
        e.insert("curvature_convention".into(), json!(CURVATURE_CONVENTION));
    }
    if mesh.curvature.is_some() {
        e.insert(
            "curvature_attributes".into(),
            json!({
                GAUSSIAN_ATTRIBUTE: "Gaussian curvature K = k1 k2",
                MEAN_ATTRIBUTE: "mean curvature H = (k1 + k2)/2, > 0 on a sphere with outward normals",
                PRINCIPAL_ATTRIBUTES[0]: "principal curvature k1 >= k2 (written with the directions)",
                PRINCIPAL_ATTRIBUTES[1]: "principal curvature k2",
                PRINCIPAL_ATTRIBUTES[2]: "unit principal direction of k1",
                PRINCIPAL_ATTRIBUTES[3]: "unit principal direction of k2 = normal x d1",
            }),
        );
    }
    if let (Some(m), Some(_)) = (&mesh.color_map, &mesh.colors) {
        e.insert(
            "color_map".into(),
            json!({
                "quantity": m.quantity,
                "map": m.map,
                "min": m.min,
                "max": m.max,
                "encoding": "linear (COLOR_0)",
            }),
        );
    }
    serde_json::Value::Object(e)
}

/// The glTF binary of `mesh` in two passes: the first makes every check and the bounds of the
/// positions, and lays out the buffer (each view's length follows from the counts: 12 bytes a
/// vertex for a `VEC3` of `f32`, 4 for a `SCALAR`, 12 a triangle for the `u32` indices); the
/// JSON chunk is then written, and the BIN chunk streamed view by view in the same order.
fn write_glb(mesh: &RawMesh, up: UpAxis, out: &mut dyn std::io::Write) -> Result<(), WriteError> {
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
    if let Some(c) = &mesh.curvature {
        check_f32_values(NAME, "gaussian curvature", c.gaussian.iter().copied())?;
        check_f32_values(NAME, "mean curvature", c.mean.iter().copied())?;
    }
    let mut used = vec![false; n];
    for &i in mesh.polygons.iter().flatten() {
        if let Some(u) = used.get_mut(i) {
            *u = true;
        }
    }
    let gltf_position = |p: &Point3<f64>| up.to_gltf([p.x, p.y, p.z]).map(|x| x as f32);
    let mut min = [f32::INFINITY; 3];
    let mut max = [f32::NEG_INFINITY; 3];
    for p in &mesh.positions {
        let v = gltf_position(p);
        for k in 0..3 {
            min[k] = min[k].min(v[k]);
            max[k] = max[k].max(v[k]);
        }
    }
    if !min.iter().chain(&max).all(|x| x.is_finite()) {
        return Err(WriteError::invalid(NAME, "a position does not fit an f32"));
    }
    // A zero normal is refused where a face uses the vertex, and written as glTF's up elsewhere.
    let gltf_normal = |i: usize, nv: &Vector3<f64>| match nv.try_normalize(0.0) {
        Some(u) => Some(up.to_gltf([u.x, u.y, u.z]).map(|x| x as f32)),
        None if !used.get(i).copied().unwrap_or(false) => Some([0.0, 1.0, 0.0]),
        None => None,
    };
    if let Some(normals) = &mesh.normals {
        if let Some(i) = normals
            .iter()
            .enumerate()
            .position(|(i, nv)| gltf_normal(i, nv).is_none())
        {
            return Err(WriteError::invalid(
                NAME,
                format!("vertex {i} has a zero normal"),
            ));
        }
    }
    let curvature = mesh.curvature.as_ref();
    let directions = curvature.and_then(|c| c.directions.as_ref().map(|ds| (c, ds)));
    if let Some((c, ds)) = directions {
        check_f32_values(
            NAME,
            "principal curvature k1",
            (0..n).map(|i| c.principal(i).map_or(f64::NAN, |k| k[0])),
        )?;
        check_f32_values(
            NAME,
            "principal curvature k2",
            (0..n).map(|i| c.principal(i).map_or(f64::NAN, |k| k[1])),
        )?;
        for j in 0..2 {
            for d in ds {
                let v = up.to_gltf([d[j].x, d[j].y, d[j].z]);
                if !v.iter().all(|x| x.is_finite()) {
                    return Err(WriteError::invalid(
                        NAME,
                        "a principal direction is not finite",
                    ));
                }
            }
        }
    }

    // The layout: views back to back in the order they are streamed below.
    let (vec3_bytes, scalar_bytes) = (12 * n, 4 * n);
    let mut bin_len = 0usize;
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut attributes = serde_json::Map::new();
    let mut add = |byte_length: usize, target: u32, acc: serde_json::Value| {
        views.push(json!({
            "buffer": 0,
            "byteOffset": bin_len,
            "byteLength": byte_length,
            "target": target,
        }));
        bin_len += byte_length;
        let mut acc = acc;
        acc["bufferView"] = json!(views.len() - 1);
        accessors.push(acc);
        accessors.len() - 1
    };
    let vec3 = json!({ "componentType": FLOAT, "count": n, "type": "VEC3" });
    let scalar = json!({ "componentType": FLOAT, "count": n, "type": "SCALAR" });
    let pos = add(
        vec3_bytes,
        ARRAY_BUFFER,
        json!({
            "componentType": FLOAT, "count": n, "type": "VEC3",
            "min": min, "max": max,
        }),
    );
    attributes.insert("POSITION".into(), json!(pos));
    if mesh.normals.is_some() {
        let a = add(vec3_bytes, ARRAY_BUFFER, vec3.clone());
        attributes.insert("NORMAL".into(), json!(a));
    }
    if mesh.colors.is_some() {
        let a = add(vec3_bytes, ARRAY_BUFFER, vec3.clone());
        attributes.insert("COLOR_0".into(), json!(a));
    }
    if curvature.is_some() {
        for name in [GAUSSIAN_ATTRIBUTE, MEAN_ATTRIBUTE] {
            let a = add(scalar_bytes, ARRAY_BUFFER, scalar.clone());
            attributes.insert(name.into(), json!(a));
        }
        if directions.is_some() {
            for name in &PRINCIPAL_ATTRIBUTES[..2] {
                let a = add(scalar_bytes, ARRAY_BUFFER, scalar.clone());
                attributes.insert((*name).into(), json!(a));
            }
            for name in &PRINCIPAL_ATTRIBUTES[2..4] {
                let a = add(vec3_bytes, ARRAY_BUFFER, vec3.clone());
                attributes.insert((*name).into(), json!(a));
            }
        }
    }
    let indices = add(
        12 * ntri,
        ELEMENT_ARRAY_BUFFER,
        json!({
            "componentType": UNSIGNED_INT, "count": 3 * ntri, "type": "SCALAR",
        }),
    );
    // Every view is a multiple of 4 bytes long, so all offsets are 4-byte aligned.
    let doc = json!({
        "asset": { "version": "2.0", "generator": GENERATOR, "extras": extras(mesh, up) },
        "scene": 0,
        "scenes": [ { "nodes": [0] } ],
        "nodes": [ { "mesh": 0 } ],
        "meshes": [ { "primitives": [ {
            "attributes": attributes,
            "indices": indices,
            "mode": 4,
        } ] } ],
        "buffers": [ { "byteLength": bin_len } ],
        "bufferViews": views,
        "accessors": accessors,
    });
    let mut json_bytes =
        serde_json::to_vec(&doc).map_err(|e| WriteError::invalid(NAME, format!("JSON: {e}")))?;
    while json_bytes.len() % 4 != 0 {
        json_bytes.push(b' ');
    }
    let bin_padding = (4 - bin_len % 4) % 4;
    let total = 12 + 8 + json_bytes.len() + 8 + bin_len + bin_padding;
    let total32 = u32::try_from(total)
        .map_err(|_| WriteError::invalid(NAME, "the file would exceed 4 GiB"))?;

    // Every check is done: from here on, bytes go out.
    let mut s = crate::util::Sink::new(out);
    s.put(b"glTF");
    s.u32(2);
    s.u32(total32);
    s.u32(json_bytes.len() as u32);
    s.put(b"JSON");
    s.put(&json_bytes);
    s.u32((bin_len + bin_padding) as u32);
    s.put(b"BIN\0");
    for p in &mesh.positions {
        s.f32x3(gltf_position(p));
    }
    if let Some(normals) = &mesh.normals {
        for (i, nv) in normals.iter().enumerate() {
            s.f32x3(gltf_normal(i, nv).unwrap_or([0.0; 3]));
        }
    }
    if let Some(colors) = &mesh.colors {
        for c in colors {
            s.f32x3(c.map(|x| x.clamp(0.0, 1.0)));
        }
    }
    if let Some(c) = curvature {
        for values in [&c.gaussian, &c.mean] {
            push_f32s(&mut s, values.iter().map(|&x| x as f32));
        }
    }
    if let Some((c, ds)) = directions {
        for j in 0..2 {
            push_f32s(
                &mut s,
                (0..n).map(|i| c.principal(i).map_or(f64::NAN, |k| k[j]) as f32),
            );
        }
        for j in 0..2 {
            for d in ds {
                let v = up.to_gltf([d[j].x, d[j].y, d[j].z]);
                s.f32x3(v.map(|x| x as f32));
            }
        }
    }
    for t in mesh.polygons.iter().flat_map(fan) {
        s.u32x3(t.map(|i| i as u32));
    }
    s.put(&[0; 3][..bin_padding]);
    s.finish(NAME)
}

// ---------------------------------------------------------------------------------------------
// Reading

#[derive(Deserialize)]
struct Doc {
    asset: Asset,
    #[serde(default)]
    scene: Option<usize>,
    #[serde(default)]
    scenes: Vec<Scene>,
    #[serde(default)]
    nodes: Vec<Node>,
    #[serde(default)]
    meshes: Vec<GltfMesh>,
    #[serde(default)]
    accessors: Vec<Accessor>,
    #[serde(default, rename = "bufferViews")]
    buffer_views: Vec<BufferView>,
    #[serde(default)]
    buffers: Vec<Buffer>,
    #[serde(default, rename = "extensionsRequired")]
    extensions_required: Vec<String>,
}

#[derive(Deserialize)]
struct Asset {
    version: String,
    #[serde(default)]
    extras: Option<serde_json::Value>,
}

#[derive(Deserialize)]
struct Scene {
    #[serde(default)]
    nodes: Vec<usize>,
}

#[derive(Deserialize)]
struct Node {
    #[serde(default)]
    children: Vec<usize>,
    #[serde(default)]
    mesh: Option<usize>,
    #[serde(default)]
    matrix: Option<[f64; 16]>,
    #[serde(default)]
    translation: Option<[f64; 3]>,
    #[serde(default)]
    rotation: Option<[f64; 4]>,
    #[serde(default)]
    scale: Option<[f64; 3]>,
}

#[derive(Deserialize)]
struct GltfMesh {
    #[serde(default)]
    primitives: Vec<Primitive>,
}

#[derive(Deserialize)]
struct Primitive {
    attributes: BTreeMap<String, usize>,
    #[serde(default)]
    indices: Option<usize>,
    #[serde(default)]
    mode: Option<u32>,
}

#[derive(Deserialize)]
struct Accessor {
    #[serde(default, rename = "bufferView")]
    buffer_view: Option<usize>,
    #[serde(default, rename = "byteOffset")]
    byte_offset: u64,
    #[serde(rename = "componentType")]
    component_type: u32,
    #[serde(default)]
    normalized: bool,
    count: u64,
    #[serde(rename = "type")]
    kind: String,
    #[serde(default)]
    sparse: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize)]
struct BufferView {
    buffer: usize,
    #[serde(default, rename = "byteOffset")]
    byte_offset: u64,
    #[serde(rename = "byteLength")]
    byte_length: u64,
    #[serde(default, rename = "byteStride")]
    byte_stride: Option<u64>,
}

#[derive(Deserialize)]
struct Buffer {
    #[serde(rename = "byteLength")]
    byte_length: u64,
    #[serde(default)]
    uri: Option<String>,
}

fn at(element: &str, index: usize, message: impl Into<String>) -> ReadError {
    ReadError::element(NAME, element, index, message)
}

fn le_u32(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// The JSON and BIN chunks.
fn chunks(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), ReadError> {
    let header = |m: String| ReadError::header(NAME, m);
    if !bytes.starts_with(b"glTF") {
        return Err(header("a glTF binary file starts with `glTF`".into()));
    }
    let version = le_u32(bytes, 4).ok_or_else(|| header("the 12-byte header is cut".into()))?;
    if version != 2 {
        return Err(header(format!("version {version}; only glTF 2 is read")));
    }
    let length = le_u32(bytes, 8).ok_or_else(|| header("the 12-byte header is cut".into()))?;
    if length as usize != bytes.len() {
        return Err(header(format!(
            "the header says {length} bytes, the file has {}",
            bytes.len()
        )));
    }
    let mut pos = 12usize;
    let mut json = None;
    let mut bin = None;
    while pos < bytes.len() {
        let (Some(len), Some(kind)) = (le_u32(bytes, pos), bytes.get(pos + 4..pos + 8)) else {
            return Err(ReadError::new(
                NAME,
                Location::Byte(pos as u64),
                "a chunk header (8 bytes) is cut",
            ));
        };
        let start = pos + 8;
        let end = start
            .checked_add(len as usize)
            .filter(|&e| e <= bytes.len())
            .ok_or_else(|| {
                ReadError::new(
                    NAME,
                    Location::Byte(pos as u64),
                    format!(
                        "the chunk says {len} bytes, {} are left",
                        bytes.len() - start
                    ),
                )
            })?;
        let data = bytes.get(start..end).unwrap_or(&[]);
        match kind {
            b"JSON" if json.is_none() && pos == 12 => json = Some(data),
            b"BIN\0" if bin.is_none() && json.is_some() => bin = Some(data),
            _ if pos == 12 => {
                return Err(ReadError::new(
                    NAME,
                    Location::Byte(12),
                    "the first chunk must be the JSON chunk",
                ))
            }
            _ => {}
        }
        // Chunks are 4-byte aligned; a last chunk without padding ends the file.
        pos = end.saturating_add(3) & !3;
    }
    let json = json.ok_or_else(|| header("no JSON chunk".into()))?;
    Ok((json, bin))
}

/// A node's local transform (column-major `matrix`, or `T · R · S`).
fn local_transform(node: &Node, index: usize) -> Result<Matrix4<f64>, ReadError> {
    let bad = |what: &str| {
        at(
            "node",
            index,
            format!("{what} has a number that is not finite"),
        )
    };
    if let Some(m) = &node.matrix {
        if !m.iter().all(|x| x.is_finite()) {
            return Err(bad("matrix"));
        }
        return Ok(Matrix4::from_column_slice(m));
    }
    let t = node.translation.unwrap_or([0.0; 3]);
    let r = node.rotation.unwrap_or([0.0, 0.0, 0.0, 1.0]);
    let s = node.scale.unwrap_or([1.0; 3]);
    if !t.iter().chain(&r).chain(&s).all(|x| x.is_finite()) {
        return Err(bad("translation, rotation or scale"));
    }
    let q = UnitQuaternion::from_quaternion(Quaternion::new(r[3], r[0], r[1], r[2]));
    let rs = q.to_rotation_matrix().matrix() * Matrix3::from_diagonal(&Vector3::from(s));
    let mut m = Matrix4::identity();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(&rs);
    m.fixed_view_mut::<3, 1>(0, 3).copy_from(&Vector3::from(t));
    Ok(m)
}

/// Every `(mesh, world transform)` the scene shows, in walking order.
fn instances(doc: &Doc) -> Result<Vec<(usize, Matrix4<f64>)>, ReadError> {
    if doc.scenes.is_empty() {
        return Ok((0..doc.meshes.len())
            .map(|m| (m, Matrix4::identity()))
            .collect());
    }
    let s = doc.scene.unwrap_or(0);
    let scene = doc
        .scenes
        .get(s)
        .ok_or_else(|| ReadError::header(NAME, format!("scene {s} does not exist")))?;
    let mut seen = vec![false; doc.nodes.len()];
    let mut out = Vec::new();
    let mut stack: Vec<(usize, Matrix4<f64>)> = scene
        .nodes
        .iter()
        .rev()
        .map(|&n| (n, Matrix4::identity()))
        .collect();
    while let Some((n, parent)) = stack.pop() {
        let node = doc.nodes.get(n).ok_or_else(|| {
            at(
                "node",
                n,
                format!("does not exist ({} nodes)", doc.nodes.len()),
            )
        })?;
        match seen.get_mut(n) {
            Some(s) if *s => {
                return Err(at(
                    "node",
                    n,
                    "is reached twice (a cycle or a shared child: glTF nodes form trees)",
                ))
            }
            Some(s) => *s = true,
            None => {}
        }
        let world = parent * local_transform(node, n)?;
        if let Some(m) = node.mesh {
            if m >= doc.meshes.len() {
                return Err(at(
                    "node",
                    n,
                    format!("mesh {m} does not exist ({} meshes)", doc.meshes.len()),
                ));
            }
            out.push((m, world));
        }
        for &c in node.children.iter().rev() {
            stack.push((c, world));
        }
    }
    Ok(out)
}

/// One accessor, checked against its view and the BIN chunk: the bytes, the element stride
/// and size, the count.
struct View<'a> {
    data: &'a [u8],
    stride: usize,
    count: usize,
    component_type: u32,
    components: usize,
}

impl View<'_> {
    fn component(&self, i: usize, k: usize) -> f64 {
        let size = component_size(self.component_type);
        let at = i * self.stride + k * size;
        let b = self.data.get(at..at + size).unwrap_or(&[]);
        match (self.component_type, b) {
            (FLOAT, [a, b, c, d]) => f64::from(f32::from_le_bytes([*a, *b, *c, *d])),
            (UNSIGNED_INT, [a, b, c, d]) => f64::from(u32::from_le_bytes([*a, *b, *c, *d])),
            (UNSIGNED_SHORT, [a, b]) => f64::from(u16::from_le_bytes([*a, *b])),
            (UNSIGNED_BYTE, [a]) => f64::from(*a),
            _ => 0.0,
        }
    }
}

fn component_size(t: u32) -> usize {
    match t {
        UNSIGNED_BYTE => 1,
        UNSIGNED_SHORT => 2,
        _ => 4,
    }
}

fn components(kind: &str) -> Option<usize> {
    Some(match kind {
        "SCALAR" => 1,
        "VEC2" => 2,
        "VEC3" => 3,
        "VEC4" => 4,
        _ => return None,
    })
}

/// Accessor `a` read as `what` (an attribute name, `indices`), with the component types and
/// element types it may have.
fn accessor<'a>(
    doc: &Doc,
    bin: &'a [u8],
    a: usize,
    what: &str,
    types: &[u32],
    kinds: &[&str],
) -> Result<View<'a>, ReadError> {
    let err = |m: String| at("accessor", a, format!("({what}) {m}"));
    let acc = doc.accessors.get(a).ok_or_else(|| {
        err(format!(
            "does not exist ({} accessors)",
            doc.accessors.len()
        ))
    })?;
    if acc.sparse.is_some() {
        return Err(err("is sparse; sparse accessors are not read".into()));
    }
    if !types.contains(&acc.component_type) {
        return Err(err(format!(
            "component type {} is not one {what} may have ({types:?})",
            acc.component_type
        )));
    }
    if !kinds.contains(&acc.kind.as_str()) {
        return Err(err(format!(
            "type {} is not one {what} may have ({})",
            acc.kind,
            kinds.join(", ")
        )));
    }
    let comps = components(&acc.kind).unwrap_or(1);
    let elem = comps * component_size(acc.component_type);
    let v = acc
        .buffer_view
        .ok_or_else(|| err("has no buffer view (zero-filled accessors are not read)".into()))?;
    let view = doc.buffer_views.get(v).ok_or_else(|| {
        err(format!(
            "buffer view {v} does not exist ({} views)",
            doc.buffer_views.len()
        ))
    })?;
    let verr = |m: String| at("bufferView", v, m);
    let buffer = doc.buffers.get(view.buffer).ok_or_else(|| {
        verr(format!(
            "buffer {} does not exist ({} buffers)",
            view.buffer,
            doc.buffers.len()
        ))
    })?;
    if view.buffer != 0 || buffer.uri.is_some() {
        return Err(verr(format!(
            "buffer {} is not the file's BIN chunk (external and data URIs are not read)",
            view.buffer
        )));
    }
    let view_end = view
        .byte_offset
        .checked_add(view.byte_length)
        .filter(|&e| e <= bin.len() as u64 && e <= buffer.byte_length.max(bin.len() as u64))
        .ok_or_else(|| {
            verr(format!(
                "bytes {} to {} reach past the BIN chunk ({} bytes)",
                view.byte_offset,
                view.byte_offset.saturating_add(view.byte_length),
                bin.len()
            ))
        })?;
    let stride = match view.byte_stride {
        None => elem as u64,
        Some(s) if s >= elem as u64 && s <= 252 => s,
        Some(s) => {
            return Err(verr(format!(
                "byte stride {s} is outside {elem} (the element's size) to 252"
            )))
        }
    };
    let need = match acc.count {
        0 => 0,
        c => (c - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(elem as u64))
            .and_then(|x| x.checked_add(acc.byte_offset))
            .unwrap_or(u64::MAX),
    };
    if need > view.byte_length {
        return Err(err(format!(
            "{} elements of {elem} bytes every {stride} from byte {} need {need} bytes; the view has {}",
            acc.count, acc.byte_offset, view.byte_length
        )));
    }
    let start = (view.byte_offset + acc.byte_offset) as usize;
    let data = bin.get(start..view_end as usize).unwrap_or(&[]);
    Ok(View {
        data,
        stride: stride as usize,
        count: acc.count as usize,
        component_type: acc.component_type,
        components: comps,
    })
}

fn read_glb(bytes: &[u8]) -> Result<RawMesh, ReadError> {
    let (json, bin) = chunks(bytes)?;
    let doc: Doc = serde_json::from_slice(json)
        .map_err(|e| ReadError::header(NAME, format!("the JSON chunk: {e}")))?;
    if !doc.asset.version.starts_with("2.") {
        return Err(ReadError::header(
            NAME,
            format!("asset version {}; only glTF 2 is read", doc.asset.version),
        ));
    }
    if let Some(e) = doc.extensions_required.first() {
        return Err(ReadError::header(
            NAME,
            format!("the file requires extension {e}, which is not read"),
        ));
    }
    let up = match doc
        .asset
        .extras
        .as_ref()
        .and_then(|e| e.get("data_up_axis"))
        .and_then(|v| v.as_str())
    {
        Some("y") => UpAxis::Y,
        _ => UpAxis::Z,
    };
    let bin = bin.unwrap_or(&[]);
    let insts = instances(&doc)?;
    // The estimate: every instance's vertices and triangles, before anything is read.
    let mut vertices: u64 = 0;
    let mut triangles: u64 = 0;
    for &(m, _) in &insts {
        for p in doc
            .meshes
            .get(m)
            .map(|m| m.primitives.as_slice())
            .unwrap_or(&[])
        {
            let count = |a: Option<usize>| {
                a.and_then(|a| doc.accessors.get(a))
                    .map_or(0, |acc| acc.count)
            };
            let nv = count(p.attributes.get("POSITION").copied());
            vertices = vertices.saturating_add(nv);
            let ni = if p.indices.is_some() {
                count(p.indices)
            } else {
                nv
            };
            triangles = triangles.saturating_add(ni / 3);
        }
    }
    let estimate = vertices
        .saturating_mul(RAW_VERTEX_BYTES)
        .saturating_add(triangles.saturating_mul(RAW_TRIANGLE_BYTES));
    let allowed = MAX_EXPANSION.saturating_mul(bytes.len() as u64);
    if estimate > allowed {
        return Err(ReadError::header(
            NAME,
            format!(
                "the scene shows {vertices} vertices and {triangles} triangles ({} mesh instances): the mesh read would take about {estimate} bytes, more than {MAX_EXPANSION} times the file's {} bytes",
                insts.len(),
                bytes.len()
            ),
        ));
    }
    let mut mesh = RawMesh::default();
    // Each per-vertex attribute is collected while every primitive so far has it; `missing`
    // counts the primitives without it (then it is dropped, with a note if some had it).
    let mut normals: Option<Vec<Vector3<f64>>> = Some(Vec::new());
    let mut colors: Option<Vec<[f32; 3]>> = Some(Vec::new());
    let mut curvature: Option<Curvature> = Some(Curvature::default());
    let (mut with_n, mut with_c, mut with_k) = (0usize, 0usize, 0usize);
    let mut alpha = false;
    let mut scaled = false;
    let mut dropped: Vec<&str> = Vec::new();
    let mut polys = Polygons::new();
    let mut prims = 0usize;
    for (m, world) in &insts {
        let gm = doc
            .meshes
            .get(*m)
            .map(|g| g.primitives.as_slice())
            .unwrap_or(&[]);
        let lin = world.fixed_view::<3, 3>(0, 0).into_owned();
        let flip = lin.determinant() < 0.0;
        let normal_matrix = lin.try_inverse().map(|i| i.transpose()).ok_or_else(|| {
            ReadError::header(NAME, format!("mesh {m} is placed by a singular transform"))
        })?;
        let rigid = (lin.transpose() * lin - Matrix3::identity()).amax() < RIGID_TOLERANCE;
        scaled |= !rigid;
        for (pi, p) in gm.iter().enumerate() {
            prims += 1;
            let perr = |msg: String| {
                ReadError::new(
                    NAME,
                    Location::Element {
                        element: format!("mesh {m} primitive"),
                        index: pi,
                        property: None,
                    },
                    msg,
                )
            };
            let mode = p.mode.unwrap_or(4);
            if mode != 4 {
                return Err(perr(format!(
                    "mode {mode}; only triangles (mode 4) are read"
                )));
            }
            let Some(&pa) = p.attributes.get("POSITION") else {
                return Err(perr("has no POSITION".into()));
            };
            let pos = accessor(&doc, bin, pa, "POSITION", &[FLOAT], &["VEC3"])?;
            let base = mesh.positions.len();
            for i in 0..pos.count {
                let v = Vector3::new(
                    pos.component(i, 0),
                    pos.component(i, 1),
                    pos.component(i, 2),
                );
                if !v.iter().all(|x| x.is_finite()) {
                    return Err(at(
                        "accessor",
                        pa,
                        format!("(POSITION) element {i} is not finite"),
                    ));
                }
                let w = world.transform_point(&Point3::from(v));
                mesh.positions
                    .push(Point3::from(up.from_gltf([w.x, w.y, w.z])));
            }
            // NORMAL
            match (p.attributes.get("NORMAL"), normals.as_mut()) {
                (Some(&na), Some(ns)) => {
                    with_n += 1;
                    let nv = accessor(&doc, bin, na, "NORMAL", &[FLOAT], &["VEC3"])?;
                    if nv.count != pos.count {
                        return Err(at(
                            "accessor",
                            na,
                            format!(
                                "(NORMAL) has {} elements for {} positions",
                                nv.count, pos.count
                            ),
                        ));
                    }
                    for i in 0..nv.count {
                        let v = Vector3::new(
                            nv.component(i, 0),
                            nv.component(i, 1),
                            nv.component(i, 2),
                        );
                        if !v.iter().all(|x| x.is_finite()) {
                            return Err(at(
                                "accessor",
                                na,
                                format!("(NORMAL) element {i} is not finite"),
                            ));
                        }
                        let t = normal_matrix * v;
                        let t = t.try_normalize(0.0).unwrap_or(t);
                        ns.push(Vector3::from(up.from_gltf([t.x, t.y, t.z])));
                    }
                }
                (None, Some(_)) => normals = None,
                (Some(_), None) => with_n += 1,
                _ => {}
            }
            // COLOR_0
            match (p.attributes.get("COLOR_0"), colors.as_mut()) {
                (Some(&ca), Some(cs)) => {
                    with_c += 1;
                    let cv = accessor(
                        &doc,
                        bin,
                        ca,
                        "COLOR_0",
                        &[FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT],
                        &["VEC3", "VEC4"],
                    )?;
                    let normalized = doc.accessors.get(ca).is_some_and(|a| a.normalized);
                    let scale = match cv.component_type {
                        UNSIGNED_BYTE if normalized => 255.0,
                        UNSIGNED_SHORT if normalized => 65535.0,
                        FLOAT => 1.0,
                        t => {
                            return Err(at(
                                "accessor",
                                ca,
                                format!("(COLOR_0) component type {t} must be normalized"),
                            ))
                        }
                    };
                    if cv.count != pos.count {
                        return Err(at(
                            "accessor",
                            ca,
                            format!(
                                "(COLOR_0) has {} elements for {} positions",
                                cv.count, pos.count
                            ),
                        ));
                    }
                    alpha |= cv.components == 4;
                    for i in 0..cv.count {
                        let c = [0, 1, 2].map(|k| cv.component(i, k) / scale);
                        if !c.iter().all(|x| x.is_finite()) {
                            return Err(at(
                                "accessor",
                                ca,
                                format!("(COLOR_0) element {i} is not finite"),
                            ));
                        }
                        cs.push(c.map(|x| x as f32));
                    }
                }
                (None, Some(_)) => colors = None,
                (Some(_), None) => with_c += 1,
                _ => {}
            }
            // Curvature
            match (
                p.attributes.get(GAUSSIAN_ATTRIBUTE),
                p.attributes.get(MEAN_ATTRIBUTE),
                curvature.as_mut(),
            ) {
                (Some(&ka), Some(&ha), Some(c)) => {
                    with_k += 1;
                    for (a, name, out) in [
                        (ka, GAUSSIAN_ATTRIBUTE, &mut c.gaussian),
                        (ha, MEAN_ATTRIBUTE, &mut c.mean),
                    ] {
                        let v = accessor(&doc, bin, a, name, &[FLOAT], &["SCALAR"])?;
                        if v.count != pos.count {
                            return Err(at(
                                "accessor",
                                a,
                                format!(
                                    "({name}) has {} elements for {} positions",
                                    v.count, pos.count
                                ),
                            ));
                        }
                        for i in 0..v.count {
                            let x = v.component(i, 0);
                            if !x.is_finite() {
                                return Err(at(
                                    "accessor",
                                    a,
                                    format!("({name}) element {i} is not finite"),
                                ));
                            }
                            out.push(x);
                        }
                    }
                }
                (Some(_), Some(_), None) => with_k += 1,
                (_, _, Some(_)) => curvature = None,
                _ => {}
            }
            // Triangles
            let nv = pos.count;
            let push = |polys: &mut Polygons, t: [usize; 3]| {
                let t = t.map(|i| base + i);
                if flip {
                    polys.push(&[t[0], t[2], t[1]]);
                } else {
                    polys.push(&t);
                }
            };
            match p.indices {
                Some(ia) => {
                    let iv = accessor(
                        &doc,
                        bin,
                        ia,
                        "indices",
                        &[UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT],
                        &["SCALAR"],
                    )?;
                    if iv.count % 3 != 0 {
                        return Err(at(
                            "accessor",
                            ia,
                            format!("(indices) count {} is not a multiple of 3", iv.count),
                        ));
                    }
                    for t in 0..iv.count / 3 {
                        let mut tri = [0usize; 3];
                        for (k, c) in tri.iter_mut().enumerate() {
                            let i = iv.component(3 * t + k, 0) as usize;
                            if i >= nv {
                                return Err(at("accessor", ia, format!("(indices) index {i} of triangle {t} is out of range ({nv} vertices)")));
                            }
                            *c = i;
                        }
                        push(&mut polys, tri);
                    }
                }
                None => {
                    if nv % 3 != 0 {
                        return Err(perr(format!(
                            "has no indices and {nv} positions, not a multiple of 3"
                        )));
                    }
                    for t in 0..nv / 3 {
                        push(&mut polys, [3 * t, 3 * t + 1, 3 * t + 2]);
                    }
                }
            }
        }
    }
    if prims == 0 {
        mesh.notes.push("the scene shows no mesh primitives".into());
    }
    if scaled && curvature.as_ref().is_some_and(|c| !c.is_empty()) {
        curvature = None;
        mesh.notes
            .push("curvature dropped: a node scales its mesh".into());
    }
    for (with, what) in [
        (with_n, "normals"),
        (with_c, "colours"),
        (with_k, "curvature"),
    ] {
        if with > 0 && with < prims {
            dropped.push(what);
        }
    }
    if !dropped.is_empty() {
        mesh.notes.push(format!(
            "{} dropped: some primitives have them and some do not",
            dropped.join(", ")
        ));
    }
    if alpha {
        mesh.notes
            .push("the alpha of the vertex colours dropped".into());
    }
    if up == UpAxis::Z && prims > 0 {
        mesh.notes
            .push("turned from glTF's y up into z up: (x, y, z) = glTF (x, -z, y)".into());
    }
    let nonempty = !mesh.positions.is_empty();
    mesh.normals = normals.filter(|_| nonempty && with_n == prims);
    mesh.colors = colors.filter(|_| nonempty && with_c == prims);
    mesh.curvature = curvature.filter(|_| nonempty && with_k == prims);
    mesh.polygons = polys;
    Ok(mesh)
}

/// A node transform whose linear part `L` has `‖LᵀL − I‖∞` below this is rigid (a rotation, or
/// a reflection): single-precision matrices written by other tools are orthonormal to about
/// 1e-7, and a scale a user means differs from 1 by far more.
const RIGID_TOLERANCE: f64 = 1e-5;
