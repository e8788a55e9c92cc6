//! `fit | tess -s 8 --kg [--mesh] | kcolor | render` as four processes connected by pipes, in
//! each stream format and with each record kind (`Triangle`, `TriangleMesh`), against the same
//! work in one process (library calls, no records).
//!
//! The mesh: `surface::datasets::ring(nu, nv)` written as OBJ (so `fit` reads, repairs and
//! estimates as for any file). `TESTBED_BENCH_RING=NU,NV` (default `16,16`: 512 faces, 1 536
//! Shirman–Séquin patches, 98 304 triangles in the stream) chooses the size. Each
//! configuration runs `RUNS` times (`TESTBED_BENCH_RUNS`); the median wall time is reported
//! with the bytes per record and per triangle of the tess → kcolor and kcolor → render
//! streams, and each stage's median time run alone from a file to a file (what the pipes
//! overlap).
//!
//! `TESTBED_BENCH_ONLY=binary:mesh,json:triangle,…` runs only the configurations listed and
//! `TESTBED_BENCH_STAGES=0` skips the stages alone and the stream sizes (for the large
//! meshes: the bytes per record do not depend on the mesh's size).
//!
//! The one-process reference is run twice: filling the render mesh with every triangle's own
//! three vertices (what `render` builds from `Triangle` records) and with each patch's
//! vertices shared (what it builds from `TriangleMesh` records); each pipeline is compared
//! with the reference building the same render mesh. The reference runs in a fresh process
//! (this benchmark started again as a child, reading the OBJ file), as every stage of the
//! pipes does; the same run repeated inside the benchmark's own process, where the heap's
//! pages are already mapped from the previous run, is printed beside it (faster by the page
//! faults of a first run).

// A measurement, not an input path: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::io::Write;
use std::process::{Command, Stdio};
use std::time::Instant;

use testbed::binders::{Colouring, DEFAULT_BLOCK};
use testbed::draw::{self, View};
use testbed::filters::KColor;
use testbed::record::Vertex;
use testbed::tessellator::{IndexedPatch, PatchTessellator};

/// Runs per configuration (median reported): enough to steady a 2-core shared machine's noise.
const RUNS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `tess`'s arguments for a record kind.
fn tess_args(mesh: bool) -> Vec<&'static str> {
    let mut a = vec!["tess", "-s", "8", "--kg"];
    if mesh {
        a.push("--mesh");
    }
    a
}

fn piped(bin: &str, obj: &std::path::Path, format: &str, mesh: bool) -> f64 {
    let t = Instant::now();
    let mut fit = Command::new(bin)
        .args([
            "fit",
            "--scheme",
            "shirman-sequin",
            "--format",
            format,
            "--input",
        ])
        .arg(obj)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("fit");
    let mut tess = Command::new(bin)
        .args(tess_args(mesh))
        .stdin(fit.stdout.take().expect("pipe"))
        .stdout(Stdio::piped())
        .spawn()
        .expect("tess");
    let mut kcolor = Command::new(bin)
        .args(["kcolor"])
        .stdin(tess.stdout.take().expect("pipe"))
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("kcolor");
    let out = Command::new(bin)
        .args(["render"])
        .stdin(kcolor.stdout.take().expect("pipe"))
        .output()
        .expect("render");
    for child in [&mut fit, &mut tess, &mut kcolor] {
        assert!(child.wait().expect("waited").success());
    }
    assert!(out.status.success() && out.stdout.len() > 1000);
    t.elapsed().as_secs_f64()
}

/// One stage alone: `args` reading `input`, writing `output`; wall time.
fn stage(bin: &str, args: &[&str], input: &std::path::Path, output: &std::path::Path) -> f64 {
    let t = Instant::now();
    let status = Command::new(bin)
        .args(args)
        .stdin(std::fs::File::open(input).expect("input"))
        .stdout(std::fs::File::create(output).expect("output"))
        .stderr(Stdio::null())
        .status()
        .expect("runs");
    assert!(status.success(), "{args:?}");
    t.elapsed().as_secs_f64()
}

fn in_process(obj_bytes: &[u8], shared: bool) -> f64 {
    let t = Instant::now();
    let raw = meshio::read_bytes(std::path::Path::new("ring.obj"), obj_bytes).expect("read");
    let estimator = estimate::estimator_by_name("hybrid").expect("estimator");
    let input = estimate::prepare(&raw, estimate::EstimateChoice::With(estimator), false)
        .expect("prepared");
    let scheme = surface::scheme_by_name("shirman-sequin", &Default::default()).expect("scheme");
    let method = curves::method_by_name("chord", &Default::default()).expect("method");
    let fitted = surface::fit_scheme(&input.mesh, scheme.as_ref(), method.as_ref()).expect("fit");
    // Straight into the render mesh, the Gaussian curvature beside it (the leanest one-process
    // form of the same work): every triangle's own vertices, or each patch's shared.
    let mut mesh = render::RenderMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        colors: Vec::new(),
        faces: Vec::new(),
    };
    let mut kg: Vec<f64> = Vec::new();
    let mut corners: Vec<f64> = Vec::new();
    let mut tessellator = PatchTessellator::new(8).expect("tessellator");
    let mut samples = Vec::new();
    let mut indexed = IndexedPatch::default();
    for net in fitted.nets() {
        let pts = net.iter().map(|p| input.frame.to_world(p)).collect();
        let patch = surface::BezierTriangle::new(fitted.layout.degree, pts).expect("patch");
        if shared {
            tessellator
                .tessellate_indexed(&patch, &mut indexed)
                .expect("tess");
            let base = mesh.positions.len();
            for s in &indexed.samples {
                mesh.positions.push(s.pos);
                mesh.normals.push(s.norm);
                mesh.colors.push(render::colors::MATERIAL);
                kg.push(s.kg);
            }
            for t in &indexed.triangles {
                mesh.faces.push(t.map(|i| base + i as usize));
                corners.extend(t.map(|i| indexed.samples[i as usize].kg));
            }
            continue;
        }
        tessellator.tessellate(&patch, &mut samples).expect("tess");
        for t in &samples {
            let tri = t.map(|s| Vertex {
                pos: s.pos,
                norm: Some(s.norm),
                kg: Some(s.kg),
                km: None,
                color: None,
            });
            draw::push_triangle(&mut mesh, &tri, render::colors::MATERIAL);
            kg.extend(t.iter().map(|s| s.kg));
        }
    }
    if !shared {
        corners.clone_from(&kg);
    }
    // The range as kcolor's default takes it: from the first block of triangles.
    let mut first: Vec<f64> = corners.iter().take(3 * DEFAULT_BLOCK).copied().collect();
    let range = KColor.default_range(&mut first);
    for (c, k) in mesh.colors.iter_mut().zip(&kg) {
        *c = KColor.color(*k, range);
    }
    let img = draw::draw_mesh(
        &mesh,
        &View {
            view: draw::DEFAULT_VIEW,
            size: draw::DEFAULT_SIZE,
            wire: false,
        },
    )
    .expect("drawn");
    let mut png = Vec::new();
    draw::write_png(&img, &mut png).expect("png");
    assert!(png.len() > 1000);
    t.elapsed().as_secs_f64()
}

/// Set in a child run of this benchmark: one one-process run on the OBJ file named, in a
/// fresh process (`shared` or `own` vertices), its time printed.
const CHILD: &str = "TESTBED_BENCH_ONE_PROCESS";

/// The one-process run in a fresh process (this benchmark run again as a child): cold heap
/// and caches, a process started, as each stage of the pipes has; wall time of the child.
fn in_fresh_process(obj: &std::path::Path, shared: bool) -> f64 {
    let t = Instant::now();
    let out = Command::new(std::env::current_exe().expect("the benchmark"))
        .env(
            CHILD,
            format!(
                "{},{}",
                if shared { "shared" } else { "own" },
                obj.display()
            ),
        )
        .stderr(Stdio::null())
        .output()
        .expect("runs");
    assert!(out.status.success());
    t.elapsed().as_secs_f64()
}

fn main() {
    if let Ok(spec) = std::env::var(CHILD) {
        let (kind, path) = spec.split_once(',').expect("KIND,PATH");
        let bytes = std::fs::read(path).expect("the OBJ file");
        in_process(&bytes, kind == "shared");
        return;
    }
    let bin = env!("CARGO_BIN_EXE_testbed");
    let (nu, nv) = std::env::var("TESTBED_BENCH_RING")
        .ok()
        .and_then(|s| {
            let (a, b) = s.split_once(',')?;
            Some((a.parse().ok()?, b.parse().ok()?))
        })
        .unwrap_or((16usize, 16usize));
    let data = surface::datasets::ring(nu, nv).expect("ring");
    let raw = meshio::RawMesh::from_triangles(
        data.mesh.vertices().iter().map(|v| v.data.p).collect(),
        data.mesh.faces(),
    );
    let obj_bytes = meshio::write_bytes(
        &raw,
        meshio::format_by_name("obj").expect("obj"),
        &meshio::WriteOptions::new(),
    )
    .expect("obj");
    let dir = tempfile::tempdir().expect("dir");
    let obj = dir.path().join("ring.obj");
    std::fs::File::create(&obj)
        .and_then(|mut f| f.write_all(&obj_bytes))
        .expect("written");
    let faces = data.mesh.num_faces();
    println!(
        "ring({nu}, {nv}): {faces} faces, {} triangles in the stream",
        faces * 3 * 64
    );
    let runs = std::env::var("TESTBED_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(RUNS);
    let only = std::env::var("TESTBED_BENCH_ONLY").ok();
    let chosen = |format: &str, mesh: bool| {
        let name = format!("{format}:{}", if mesh { "mesh" } else { "triangle" });
        only.as_deref()
            .is_none_or(|o| o.split(',').any(|c| c.trim() == name))
    };
    let stages = std::env::var("TESTBED_BENCH_STAGES").map_or(true, |s| s != "0");
    let formats = ["json", "dstruct", "binary"];
    let base = [false, true].map(|shared| {
        if !formats.iter().any(|f| chosen(f, shared)) {
            return f64::NAN;
        }
        median((0..runs).map(|_| in_process(&obj_bytes, shared)).collect())
    });
    let warm = base;
    let base = [false, true].map(|shared| {
        if warm[usize::from(shared)].is_nan() {
            return f64::NAN;
        }
        median((0..runs).map(|_| in_fresh_process(&obj, shared)).collect())
    });
    println!(
        "in one process: {:.3} s (every triangle's own vertices), {:.3} s (each patch's shared) \
         in a fresh process (the reference); {:.3} s, {:.3} s repeated inside this one (warm heap)",
        base[0], base[1], warm[0], warm[1]
    );
    let patches = faces * 3;
    let triangles = patches * 64;
    for format in formats {
        for mesh in [false, true] {
            if !chosen(format, mesh) {
                continue;
            }
            let kind = if mesh { "TriangleMesh" } else { "Triangle" };
            let reference = base[usize::from(mesh)];
            let t = median((0..runs).map(|_| piped(bin, &obj, format, mesh)).collect());
            if !stages {
                println!(
                    "pipes, {format:7} {kind:12}: {t:.3} s = {:.2}× one process",
                    t / reference
                );
                continue;
            }
            // Each stage alone, file to file.
            let f = |name: &str| dir.path().join(format!("{name}.{format}.{kind}"));
            let steps: [(&str, Vec<&str>, std::path::PathBuf, std::path::PathBuf); 4] = [
                (
                    "fit",
                    vec!["fit", "--scheme", "shirman-sequin", "--format", format],
                    obj.clone(),
                    f("patches"),
                ),
                ("tess", tess_args(mesh), f("patches"), f("tris")),
                ("kcolor", vec!["kcolor"], f("tris"), f("coloured")),
                ("render", vec!["render"], f("coloured"), f("png")),
            ];
            let mut line = String::from("  stages alone:");
            for (name, args, input, output) in &steps {
                let t = median((0..runs).map(|_| stage(bin, args, input, output)).collect());
                line += &format!(" {name} {t:.3} s");
            }
            let size = |p: std::path::PathBuf| std::fs::metadata(p).expect("written").len() as f64;
            let records = if mesh { patches } else { triangles } as f64;
            let (tris, coloured) = (size(f("tris")), size(f("coloured")));
            println!(
                "pipes, {format:7} {kind:12}: {t:.3} s = {:.2}× one process; patches {:.0} B/record; \
                 tess → kcolor {:.0} B/record, {:.1} B/triangle ({:.1} MB); \
                 kcolor → render {:.0} B/record, {:.1} B/triangle ({:.1} MB)",
                t / reference,
                size(f("patches")) / patches as f64,
                tris / records,
                tris / triangles as f64,
                tris / 1e6,
                coloured / records,
                coloured / triangles as f64,
                coloured / 1e6,
            );
            println!("{line}");
        }
    }
}
