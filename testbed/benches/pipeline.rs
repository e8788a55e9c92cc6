//! `fit | tess -s 8 --kg | kcolor | render` as four processes connected by pipes, in each
//! stream format, against the same work in one process (library calls, no records).
//!
//! The mesh: `surface::datasets::ring(nu, nv)` written as OBJ (so `fit` reads, repairs and
//! estimates as for any file). `TESTBED_BENCH_RING=NU,NV` (default `16,16`: 512 faces, 1 536
//! Shirman–Séquin patches, 98 304 triangles in the stream) chooses the size. Each
//! configuration runs `RUNS` times (`TESTBED_BENCH_RUNS`); the median wall time is reported
//! with the bytes per record of the tess → kcolor stream, and each stage's median time run
//! alone from a file to a file (what the pipes overlap).

// A measurement, not an input path: a failed step should stop it loudly.
#![allow(clippy::expect_used)]

use std::io::Write;
use std::process::{Command, Stdio};
use std::time::Instant;

use testbed::draw::{self, View};
use testbed::filters::{Colouring, KColor, PatchTessellator};
use testbed::record::Vertex;

/// Runs per configuration (median reported): enough to steady a 2-core shared machine's noise.
const RUNS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn piped(bin: &str, obj: &std::path::Path, format: &str) -> f64 {
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
        .args(["tess", "-s", "8", "--kg"])
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

fn in_process(obj_bytes: &[u8]) -> f64 {
    let t = Instant::now();
    let input =
        testbed::fit::prepare_bytes(std::path::Path::new("ring.obj"), obj_bytes, "hybrid", false)
            .expect("prepared");
    let scheme = surface::scheme_by_name("shirman-sequin", &Default::default()).expect("scheme");
    let method = curves::method_by_name("chord", &Default::default()).expect("method");
    let fitted = surface::fit_scheme(&input.mesh, scheme.as_ref(), method.as_ref()).expect("fit");
    // Straight into the render mesh, the Gaussian curvature beside it (the leanest one-process
    // form of the same work).
    let mut mesh = render::RenderMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        colors: Vec::new(),
        faces: Vec::new(),
    };
    let mut kg: Vec<f64> = Vec::new();
    let mut tessellator = PatchTessellator::new(8).expect("tessellator");
    let mut samples = Vec::new();
    for net in fitted.nets() {
        let pts = net.iter().map(|p| input.frame.to_world(p)).collect();
        let patch = surface::BezierTriangle::new(fitted.layout.degree, pts).expect("patch");
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
    // The range as kcolor's default takes it: from the first block of triangles.
    let mut first: Vec<f64> = kg
        .iter()
        .take(3 * testbed::filters::DEFAULT_BLOCK)
        .copied()
        .collect();
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

fn main() {
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
    let base = median((0..runs).map(|_| in_process(&obj_bytes)).collect());
    println!("in one process: {base:.3} s");
    for format in ["json", "dstruct", "binary"] {
        let t = median((0..runs).map(|_| piped(bin, &obj, format)).collect());
        // Bytes per record of the tess → kcolor stream.
        let fit = Command::new(bin)
            .args([
                "fit",
                "--scheme",
                "shirman-sequin",
                "--format",
                format,
                "--input",
            ])
            .arg(&obj)
            .stderr(Stdio::null())
            .output()
            .expect("fit");
        let mut tess = Command::new(bin)
            .args(["tess", "-s", "8", "--kg"])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("tess");
        let mut stdin = tess.stdin.take().expect("stdin");
        let patches = fit.stdout.clone();
        let feeder = std::thread::spawn(move || stdin.write_all(&patches));
        let tris = tess.wait_with_output().expect("tess").stdout;
        let _ = feeder.join();
        let n = faces * 3 * 64;
        println!(
            "pipes, {format:7}: {t:.3} s = {:.2}× one process; patches {:.0} B/record, triangles {:.0} B/record ({:.1} MB)",
            t / base,
            fit.stdout.len() as f64 / (faces * 3) as f64,
            tris.len() as f64 / n as f64,
            tris.len() as f64 / 1e6
        );
        // Each stage alone, file to file.
        let f = |name: &str| dir.path().join(format!("{name}.{format}"));
        let steps: [(&str, Vec<&str>, std::path::PathBuf, std::path::PathBuf); 4] = [
            (
                "fit",
                vec!["fit", "--scheme", "shirman-sequin", "--format", format],
                obj.clone(),
                f("patches"),
            ),
            (
                "tess",
                vec!["tess", "-s", "8", "--kg"],
                f("patches"),
                f("tris"),
            ),
            ("kcolor", vec!["kcolor"], f("tris"), f("coloured")),
            ("render", vec!["render"], f("coloured"), f("png")),
        ];
        let mut line = format!("  stages alone, {format:7}:");
        for (name, args, input, output) in &steps {
            let t = median((0..runs).map(|_| stage(bin, args, input, output)).collect());
            line += &format!(" {name} {t:.3} s");
        }
        println!("{line}");
    }
}
