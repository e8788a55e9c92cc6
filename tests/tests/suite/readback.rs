//! Our mesh files as other tools read them: `scripts/readback/readback.py` reads the fit's
//! tessellation of the sphere, as PLY (binary, text, double), OBJ, OFF and glTF binary, with
//! trimesh, Python's meshio, libigl and pymeshlab (and the Khronos glTF validator where it is
//! installed), and checks counts, positions, sRGB colour bytes, `quality` and curvature values
//! and the sign of H (> 0 on a sphere with outward normals) against what we wrote.
//!
//! It runs when a Python with those readers is found: `READBACK_PYTHON`, or the repository's
//! `.venv-readback/bin/python` (which `.ci/run` makes). Otherwise it prints why it is skipped
//! and passes; `READBACK_REQUIRED=1` makes a missing Python a failure (CI sets it).

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use std::path::{Path, PathBuf};
use std::process::Command;

use fitjob::{FitOptions, InputOptions, Source};
use meshio::{MeshFormat, RawMesh, UpAxis, WriteOptions};
use serde_json::{json, Value};

/// Vertices of each file whose values the script compares one by one.
const SAMPLE: usize = 40;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The Python to run the script with, or why there is none.
fn python() -> Result<PathBuf, String> {
    if let Some(p) = std::env::var_os("READBACK_PYTHON") {
        return Ok(PathBuf::from(p));
    }
    let venv = repo().join(".venv-readback/bin/python");
    if venv.exists() {
        return Ok(venv);
    }
    Err(format!(
        "no READBACK_PYTHON and no {} (.ci/run makes it: python3 -m venv .venv-readback && .venv-readback/bin/pip install -r scripts/readback/requirements.txt)",
        venv.display()
    ))
}

/// What a reader should see in `file`: the mesh as our reader reads it back (positions in the
/// file's own frame: glTF's y up for the .glb), colours as the bytes a viewer shows (sRGB for
/// PLY/OBJ/OFF, linear × 255 for glTF's linear COLOR_0), the curvature in the exported sign.
fn expectation(file: &str, back: &RawMesh, gltf: bool) -> Value {
    let n = SAMPLE.min(back.num_vertices());
    let positions: Vec<[f64; 3]> = back.positions[..n]
        .iter()
        .map(|p| {
            let q = [p.x, p.y, p.z];
            if gltf {
                UpAxis::Z.to_gltf(q)
            } else {
                q
            }
        })
        .collect();
    let colours = back.colors.as_ref().map(|cs| {
        cs[..n]
            .iter()
            .map(|c| {
                c.map(|x| {
                    if gltf {
                        (x.clamp(0.0, 1.0) * 255.0).round() as u8
                    } else {
                        meshio::srgb::encode_byte(x)
                    }
                })
            })
            .collect::<Vec<_>>()
    });
    let c = back.curvature.as_ref();
    json!({
        "file": file,
        "vertices": back.num_vertices(),
        "faces": back.num_faces(),
        "positions": positions,
        "colour_bytes": colours,
        "gaussian": c.map(|c| c.gaussian[..n].to_vec()),
        "mean": c.map(|c| c.mean[..n].to_vec()),
        "mean_positive": c.map(|c| c.mean.iter().all(|&h| h > 0.0)),
    })
}

#[test]
fn other_tools_read_our_meshes_as_we_wrote_them() {
    let python = match python() {
        Ok(p) => p,
        Err(why) => {
            assert!(
                std::env::var_os("READBACK_REQUIRED").is_none(),
                "READBACK_REQUIRED is set: {why}"
            );
            println!("readback: skipped: {why}");
            return;
        }
    };
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    // The fit's own mesh output, every format that has colours.
    for ext in ["ply", "obj", "off", "glb"] {
        let name = format!("sphere.{ext}");
        let path = dir.path().join(&name);
        fitjob::run(
            FitOptions {
                input: InputOptions {
                    source: Source::DataSet {
                        name: "sphere".into(),
                        resolution: None,
                    },
                    ..InputOptions::default()
                },
                mesh_out: Some(path.clone()),
                ..FitOptions::default()
            },
            &mut |_| {},
        )
        .unwrap();
        let back = meshio::read_file(&path).unwrap();
        files.push(expectation(&name, &back, ext == "glb"));
        // The PLY's other variants, from the same mesh.
        if ext == "ply" {
            for (variant, options) in [
                ("sphere-ascii.ply", WriteOptions::new().ascii()),
                ("sphere-double.ply", WriteOptions::new().double_precision()),
            ] {
                let bytes = meshio::ply::Ply.write(&back, &options).unwrap();
                std::fs::write(dir.path().join(variant), bytes).unwrap();
                files.push(expectation(variant, &back, false));
            }
        }
    }
    let spec = json!({"sample": SAMPLE, "files": files});
    std::fs::write(dir.path().join("expect.json"), spec.to_string()).unwrap();
    let out = Command::new(&python)
        .arg(repo().join("scripts/readback/readback.py"))
        .arg(dir.path())
        .output()
        .unwrap_or_else(|e| panic!("running {}: {e}", python.display()));
    let text = String::from_utf8_lossy(&out.stdout);
    println!("{text}");
    assert!(
        out.status.success(),
        "readback failed:\n{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
