//! The conventions other tools' users expect of our files: sRGB colours in PLY, OBJ and OFF,
//! one all-float PLY layout with MeshLab's `quality` and named curvature, the curvature sign
//! and generator stated in every file, headers libigl and MeshLab read, glTF's custom
//! attributes, extras and up axis; and the `.glb` reader's refusals of hostile files.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

use meshio::{format_by_name, ColorMap, Curvature, MeshFormat, RawMesh, UpAxis, WriteOptions};

fn format(name: &str) -> &'static dyn MeshFormat {
    format_by_name(name).expect(name)
}

/// The diverging map's red end, sRGB (0.706, 0.016, 0.150), as the linear colour a mesh holds.
fn curvature_red() -> [f32; 3] {
    [0.706f32, 0.016, 0.150].map(meshio::srgb::decode)
}

/// The cube with the red, a colour map and a curvature (a sphere's: K = 4, H = 2 exported).
fn coloured_cube() -> RawMesh {
    let mut m = common::cube();
    m.properties.clear();
    m.colors = Some(vec![curvature_red(); 8]);
    m.color_map = Some(ColorMap {
        quantity: "gaussian_curvature".into(),
        map: "diverging".into(),
        min: -4.0,
        max: 4.0,
    });
    m.curvature = Some(Curvature::from_internal(vec![4.0; 8], vec![-2.0; 8]));
    m
}

fn header(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(bytes);
    let end = text.find("end_header").unwrap_or(text.len());
    text[..end].to_string()
}

#[test]
fn ply_is_all_float_with_quality_and_named_curvature_and_says_its_convention() {
    let bytes = format("ply")
        .write(&coloured_cube(), &WriteOptions::new())
        .unwrap();
    let h = header(&bytes);
    // Every vertex property one type: libigl 2.6.3 aborts on byte colours beside floats.
    let props: Vec<&str> = h
        .lines()
        .filter(|l| l.starts_with("property ") && !l.contains("list"))
        .collect();
    assert!(
        props.iter().all(|l| l.starts_with("property float ")),
        "{h}"
    );
    for name in [
        "red",
        "quality",
        "gaussian_curvature",
        "mean_curvature",
        "k1",
        "k2",
    ] {
        assert!(
            h.contains(&format!("property float {name}\n")),
            "{name}: {h}"
        );
    }
    assert!(!h.contains(" gaussian\n") && !h.contains(" mean\n"), "{h}");
    assert!(h.contains("comment generator surface-workbench "), "{h}");
    assert!(h.contains("comment curvature convention: libigl"), "{h}");
    assert!(h.contains("sRGB"), "{h}");
    assert!(
        h.contains("colour map: diverging of gaussian_curvature"),
        "{h}"
    );
    // Read back: the curvature in the exported sign, the colours decoded.
    let back = format("ply").read(&bytes).unwrap();
    let c = back.curvature.expect("curvature read back");
    assert_eq!(c.mean, vec![2.0; 8]);
    assert_eq!(c.gaussian, vec![4.0; 8]);
    assert!(back.properties.is_empty(), "{:?}", back.properties.keys());
}

#[test]
fn the_curvature_red_is_stored_as_its_srgb_values() {
    let m = coloured_cube();
    // OFF: bytes (180, 4, 38), not the linear (116, 0, 5).
    let off = String::from_utf8(format("off").write(&m, &WriteOptions::new()).unwrap()).unwrap();
    assert!(off.starts_with("COFF\n"), "{off}");
    assert!(off.contains("0.0 0.0 0.0 180 4 38\n"), "{off}");
    // OBJ: 0–1 floats of the same sRGB values.
    let obj = String::from_utf8(format("obj").write(&m, &WriteOptions::new()).unwrap()).unwrap();
    let v0 = obj.lines().find(|l| l.starts_with("v ")).unwrap();
    let rgb: Vec<f32> = v0.split(' ').skip(4).map(|t| t.parse().unwrap()).collect();
    assert_eq!(
        rgb.iter()
            .map(|c| (c * 255.0).round() as u8)
            .collect::<Vec<_>>(),
        [180, 4, 38]
    );
    assert!(obj.starts_with("# generator surface-workbench "), "{obj}");
    // glTF stays linear: COLOR_0 holds the linear value.
    let glb = format("glb").write(&m, &WriteOptions::new()).unwrap();
    let back = format("glb").read(&glb).unwrap();
    assert_eq!(back.colors.unwrap()[0], curvature_red());
}

#[test]
fn off_headers_are_ones_libigl_and_meshlab_read() {
    let mut m = coloured_cube();
    for (colours, normals, want) in [
        (true, true, "COFF\n"),
        (true, false, "COFF\n"),
        (false, true, "NOFF\n"),
        (false, false, "OFF\n"),
    ] {
        let mut x = m.clone();
        if !colours {
            x.colors = None;
        }
        if !normals {
            x.normals = None;
        }
        let text = format("off").write(&x, &WriteOptions::new()).unwrap();
        assert!(text.starts_with(want.as_bytes()), "{colours} {normals}");
        assert!(!String::from_utf8_lossy(&text).contains("CNOFF"));
    }
    m.colors = None;
}

/// The JSON chunk of a `.glb`.
fn gltf_json(bytes: &[u8]) -> serde_json::Value {
    let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + n]).unwrap()
}

#[test]
fn gltf_has_curvature_attributes_extras_generator_and_turns_z_up() {
    let m = coloured_cube();
    let bytes = format("glb").write(&m, &WriteOptions::new()).unwrap();
    // (The Khronos validator passes it with no issue: `scripts/readback`, run by the
    // integration tests; the `gltf` crate without its `extras` feature refuses any `_`
    // attribute name, which the specification allows.)
    let doc = gltf_json(&bytes);
    let asset = &doc["asset"];
    assert!(asset["generator"]
        .as_str()
        .unwrap()
        .starts_with("surface-workbench "));
    assert_eq!(asset["extras"]["data_up_axis"], "z");
    assert!(asset["extras"]["curvature_convention"]
        .as_str()
        .unwrap()
        .contains("H = (k1 + k2)/2 > 0"));
    assert_eq!(asset["extras"]["color_map"]["min"], -4.0);
    assert_eq!(asset["extras"]["color_map"]["max"], 4.0);
    let attrs = &doc["meshes"][0]["primitives"][0]["attributes"];
    assert!(attrs["_GAUSSIAN_CURVATURE"].is_u64() && attrs["_MEAN_CURVATURE"].is_u64());
    // The data's z is glTF's y: the accessor's max is the cube's (1, 1, 0) turned.
    let pos = attrs["POSITION"].as_u64().unwrap() as usize;
    assert_eq!(
        doc["accessors"][pos]["min"],
        serde_json::json!([0.0, 0.0, -1.0])
    );
    assert_eq!(
        doc["accessors"][pos]["max"],
        serde_json::json!([1.0, 1.0, 0.0])
    );
    // Read back into the data's frame, with the curvature.
    let back = format("glb").read(&bytes).unwrap();
    assert_eq!(back.positions, m.positions);
    assert_eq!(back.curvature, m.curvature);
    // `--up y`: unchanged.
    let y = format("glb")
        .write(&m, &WriteOptions::new().up(UpAxis::Y))
        .unwrap();
    assert_eq!(gltf_json(&y)["asset"]["extras"]["data_up_axis"], "y");
    assert_eq!(format("glb").read(&y).unwrap().positions, m.positions);
}

#[test]
fn curvature_no_float_holds_is_refused_by_name_and_formats_without_it_ignore_it() {
    let mut m = coloured_cube();
    m.curvature = Some(Curvature::from_internal(
        vec![f64::INFINITY; 8],
        vec![0.0; 8],
    ));
    for f in ["ply", "glb"] {
        let e = format(f)
            .write(&m, &WriteOptions::new())
            .unwrap_err()
            .to_string();
        assert!(e.contains("gaussian curvature of vertex 0"), "{f}: {e}");
    }
    for f in ["obj", "off", "stl", "testbed"] {
        assert!(!format(f).writes_curvature());
        format(f)
            .write(&m, &WriteOptions::new())
            .unwrap_or_else(|e| panic!("{f}: {e}"));
    }
}

// ---------------------------------------------------------------------------------------------
// The `.glb` reader on hostile files.

/// A `.glb` of `json` and `bin`, padded as the specification says.
fn glb(json: &serde_json::Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while b.len() % 4 != 0 {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

/// One triangle: 3 positions, 3 indices; `nodes` and `count` to tamper with.
fn triangle(nodes: serde_json::Value, count: u64) -> (serde_json::Value, Vec<u8>) {
    let mut bin = Vec::new();
    for x in [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        bin.extend_from_slice(&x.to_le_bytes());
    }
    for i in [0u32, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": bin.len()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 12}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3"},
            {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}
        ]
    });
    (json, bin)
}

fn refusal(bytes: &[u8]) -> String {
    match format("glb").read(bytes) {
        Err(e) => e.to_string(),
        Ok(m) => panic!("read, {} vertices: {:?}", m.num_vertices(), m.notes),
    }
}

#[test]
fn a_foreign_glb_reads_and_is_turned_into_z_up() {
    let (json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    let m = format("glb").read(&glb(&json, &bin)).unwrap();
    assert_eq!(m.num_faces(), 1);
    // glTF (0, 1, 0), its up, is the data's (0, 0, 1).
    assert_eq!(m.positions[2].coords.as_slice(), &[0.0, 0.0, 1.0]);
    assert!(common::has_note(&m, "turned from glTF's y up"));
}

#[test]
fn hostile_glb_files_are_refused_with_the_place_and_the_reason() {
    let (json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    let good = glb(&json, &bin);
    // The header and chunks.
    assert!(refusal(&good[..10]).contains("header is cut"));
    let mut long = good.clone();
    long.extend_from_slice(&[0; 4]);
    assert!(refusal(&long).contains("the header says"));
    let mut v1 = good.clone();
    v1[4] = 1;
    assert!(refusal(&v1).contains("only glTF 2"));
    let mut cut = good.clone();
    cut[12] = 0xff;
    assert!(refusal(&cut).contains("the chunk says"));
    // An accessor that claims more than its view: 4 vertices from 36 bytes; 10¹² of them are
    // refused by the memory estimate before any accessor is looked at.
    let (json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 4);
    let e = refusal(&glb(&json, &bin));
    assert!(
        e.contains("accessor 0") && e.contains("the view has 36"),
        "{e}"
    );
    let (json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 1_000_000_000_000);
    let e = refusal(&glb(&json, &bin));
    assert!(e.contains("1000000000000 vertices"), "{e}");
    // A cycle in the nodes.
    let (json, bin) = triangle(serde_json::json!([{"mesh": 0, "children": [0]}]), 3);
    assert!(refusal(&glb(&json, &bin)).contains("reached twice"));
    // A mesh of 3000 vertices instanced by 1000 nodes: 228 MB asked by a 50 kB file, refused
    // by the estimate before anything is read.
    let (mut json, mut bin) = triangle(serde_json::json!([]), 3000);
    let indices = bin.split_off(36);
    bin.resize(36_000, 0);
    bin.extend_from_slice(&indices);
    json["bufferViews"][0]["byteLength"] = serde_json::json!(36_000);
    json["bufferViews"][1]["byteOffset"] = serde_json::json!(36_000);
    json["buffers"][0]["byteLength"] = serde_json::json!(36_012);
    json["nodes"] = (0..1000).map(|_| serde_json::json!({"mesh": 0})).collect();
    json["scenes"][0]["nodes"] = (0..1000).collect();
    let e = refusal(&glb(&json, &bin));
    assert!(
        e.contains("1000 mesh instances") && e.contains("more than 32 times"),
        "{e}"
    );
    json["nodes"] = serde_json::json!([{"mesh": 0}]);
    json["scenes"][0]["nodes"] = serde_json::json!([0]);
    let once = format("glb").read(&glb(&json, &bin)).unwrap();
    assert_eq!(once.num_vertices(), 3000);
    assert!(
        once.notes.iter().all(|n| !n.contains("dropped")),
        "{:?}",
        once.notes
    );
    // Things the reader does not do, said as such.
    let (mut json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    json["extensionsRequired"] = serde_json::json!(["KHR_draco_mesh_compression"]);
    assert!(refusal(&glb(&json, &bin)).contains("KHR_draco_mesh_compression"));
    let (mut json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    json["buffers"][0]["uri"] = serde_json::json!("outside.bin");
    assert!(refusal(&glb(&json, &bin)).contains("not the file's BIN chunk"));
    let (mut json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    json["meshes"][0]["primitives"][0]["mode"] = serde_json::json!(1);
    assert!(refusal(&glb(&json, &bin)).contains("only triangles"));
    let (mut json, bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    json["accessors"][0]["componentType"] = serde_json::json!(5121);
    assert!(refusal(&glb(&json, &bin)).contains("component type 5121"));
    // An index out of range, and JSON that is not a document.
    let (json, mut bin) = triangle(serde_json::json!([{"mesh": 0}]), 3);
    bin[40..44].copy_from_slice(&7u32.to_le_bytes());
    assert!(refusal(&glb(&json, &bin)).contains("index 7 of triangle 0 is out of range"));
    assert!(refusal(&glb(&serde_json::json!([1, 2]), &[])).contains("JSON chunk"));
}

/// The cube's curvature with principal directions: a cylinder about z (κ1 = 2 along the
/// circle, κ2 = 0 along z), d1 = (0, 1, 0) and d2 = (0, 0, 1) at every vertex.
fn cube_with_directions() -> RawMesh {
    let mut m = coloured_cube();
    let d = [nalgebra::Vector3::y(), nalgebra::Vector3::z()];
    m.curvature =
        Some(Curvature::from_exported(vec![0.0; 8], vec![1.0; 8]).with_directions(vec![d; 8]));
    m
}

#[test]
fn ply_writes_and_reads_the_principal_directions_as_libigls_pd1_pd2() {
    let m = cube_with_directions();
    let bytes = format("ply").write(&m, &WriteOptions::new()).unwrap();
    let h = header(&bytes);
    for name in ["pd1x", "pd1y", "pd1z", "pd2x", "pd2y", "pd2z"] {
        assert!(
            h.contains(&format!("property float {name}\n")),
            "{name}: {h}"
        );
    }
    let back = format("ply").read(&bytes).unwrap();
    assert!(back.properties.is_empty(), "{:?}", back.properties.keys());
    let c = back.curvature.expect("curvature read back");
    assert_eq!(c.principal(0), Some([2.0, 0.0]));
    assert_eq!(c.directions, m.curvature.unwrap().directions);
}

#[test]
fn gltf_writes_principal_curvatures_and_directions_turned_to_y_up() {
    let bytes = format("glb")
        .write(&cube_with_directions(), &WriteOptions::new())
        .unwrap();
    let doc = gltf_json(&bytes);
    let attrs = &doc["meshes"][0]["primitives"][0]["attributes"];
    for name in meshio::glb::PRINCIPAL_ATTRIBUTES {
        assert!(attrs[name].is_u64(), "{name}: {attrs}");
        assert!(
            doc["asset"]["extras"]["curvature_attributes"][name].is_string(),
            "{name}"
        );
    }
    let d1 = attrs["_PRINCIPAL_DIRECTION_1"].as_u64().unwrap() as usize;
    assert_eq!(doc["accessors"][d1]["type"], "VEC3");
    // The data's z is glTF's y (and the data's y glTF's −z): d2 = z becomes (0, 1, 0).
    let bin = glb_bin(&bytes);
    let at = |acc: usize| {
        let view = doc["accessors"][acc]["bufferView"].as_u64().unwrap() as usize;
        let off = doc["bufferViews"][view]["byteOffset"].as_u64().unwrap() as usize;
        (0..3)
            .map(|k| f32::from_le_bytes(bin[off + 4 * k..off + 4 * k + 4].try_into().unwrap()))
            .collect::<Vec<f32>>()
    };
    let d2 = attrs["_PRINCIPAL_DIRECTION_2"].as_u64().unwrap() as usize;
    assert_eq!(at(d2), vec![0.0, 1.0, 0.0]);
    let k1 = attrs["_PRINCIPAL_CURVATURE_1"].as_u64().unwrap() as usize;
    assert_eq!(at(k1)[0], 2.0);
    // Our reader takes K and H back (the directions are the writer's extra, not read).
    let back = format("glb").read(&bytes).unwrap();
    assert_eq!(back.curvature.unwrap().principal(0), Some([2.0, 0.0]));
}

/// The binary chunk of a `.glb` (after the JSON chunk and its 8-byte header).
fn glb_bin(bytes: &[u8]) -> &[u8] {
    let n = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    &bytes[20 + n + 8..]
}
