//! Shared by the viewer's integration tests: closed-form torus and sphere views, and a headless
//! Chromium that opens a page at a hash and returns the page's status and a screenshot.

#![allow(dead_code)] // each test file uses a part
#![allow(clippy::expect_used)] // test fixtures fail loudly by design

use std::f32::consts::TAU;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use viewer::{wireframe, Segment, TriangleMesh, View};

/// A Chromium run taking longer than this has hung (a page here draws in well under 5 s).
pub const CHROMIUM_TIMEOUT: Duration = Duration::from_secs(120);

/// The flags that give headless Chromium WebGL without a GPU on this machine (SwiftShader
/// through ANGLE; `--use-gl=swiftshader` gives no WebGL context at all here), and keep it off
/// the closed network (machine notes: without them it retries connections at every start).
pub const CHROMIUM_FLAGS: &[&str] = &[
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--hide-scrollbars",
    "--force-device-scale-factor=1",
];

/// A torus about the z axis (tube radius `r` < ring radius `big_r`) on an `nu × nv` grid, with
/// its exact normals and curvatures in the exported convention (`H > 0` on a sphere with
/// outward normals): `k1 = 1/r` across the tube, `k2 = cos v / (R + r cos v)` along the ring,
/// `K = k1 k2` (positive outside, negative inside), `H = (k1 + k2)/2`. Every `patch`-th grid
/// line is drawn as a "patch boundary", and the grid coarsened `patch` times is the data mesh.
pub fn torus(title: &str, nu: usize, nv: usize, big_r: f32, r: f32, patch: usize) -> View {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let (mut k, mut h, mut k1, mut k2) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let point = |u: f32, v: f32| {
        let rho = big_r + r * v.cos();
        [rho * u.cos(), rho * u.sin(), r * v.sin()]
    };
    for i in 0..nu {
        for j in 0..nv {
            let (u, v) = (TAU * i as f32 / nu as f32, TAU * j as f32 / nv as f32);
            positions.push(point(u, v));
            normals.push([v.cos() * u.cos(), v.cos() * u.sin(), v.sin()]);
            let (a, b) = (1.0 / r, v.cos() / (big_r + r * v.cos()));
            k1.push(a);
            k2.push(b);
            k.push(a * b);
            h.push(0.5 * (a + b));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + (j % nv)) as u32;
    let grid = |nu: usize, nv: usize, step: usize| {
        let mut t = Vec::new();
        for i in (0..nu).step_by(step) {
            for j in (0..nv).step_by(step) {
                let (a, b, c, d) = (
                    id(i, j),
                    id(i + step, j),
                    id(i + step, j + step),
                    id(i, j + step),
                );
                t.push([a, b, c]);
                t.push([a, c, d]);
            }
        }
        t
    };
    let indices = grid(nu, nv, 1);
    let mut boundaries: Vec<Segment> = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let p = positions[id(i, j) as usize];
            if i % patch == 0 {
                boundaries.push([p, positions[id(i, j + 1) as usize]]);
            }
            if j % patch == 0 {
                boundaries.push([p, positions[id(i + 1, j) as usize]]);
            }
        }
    }
    let data_mesh = wireframe(&positions, &grid(nu, nv, patch));
    View {
        title: title.into(),
        mesh: TriangleMesh {
            positions,
            normals,
            indices,
        },
        scalars: vec![
            ("K".into(), k),
            ("H".into(), h),
            ("k1".into(), k1),
            ("k2".into(), k2),
        ],
        boundaries: Some(boundaries),
        data_mesh: Some(data_mesh),
        ..View::default()
    }
}

/// A unit sphere on a latitude–longitude grid (poles as vertex rings of zero radius are
/// avoided by starting half a step off them), `K = H = k1 = k2 = 1`, and a made-up distance
/// `|sin 3u sin 2v| / 100` to show the distance mode.
pub fn sphere(title: &str, nu: usize, nv: usize) -> View {
    let mut positions = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let u = TAU * i as f32 / nu as f32;
            let v = std::f32::consts::PI * (j as f32 + 0.5) / nv as f32;
            positions.push([v.sin() * u.cos(), v.sin() * u.sin(), v.cos()]);
        }
    }
    let distance = (0..nu * nv)
        .map(|n| {
            let (i, j) = (n / nv, n % nv);
            let u = TAU * i as f32 / nu as f32;
            let v = std::f32::consts::PI * (j as f32 + 0.5) / nv as f32;
            ((3.0 * u).sin() * (2.0 * v).sin()).abs() / 100.0
        })
        .collect();
    let id = |i: usize, j: usize| ((i % nu) * nv + j) as u32;
    let mut indices = Vec::new();
    for i in 0..nu {
        for j in 0..nv - 1 {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            indices.push([a, c, b]);
            indices.push([a, d, c]);
        }
    }
    let n = positions.len();
    View {
        title: title.into(),
        mesh: TriangleMesh {
            normals: positions.clone(),
            positions,
            indices,
        },
        scalars: ["K", "H", "k1", "k2"]
            .iter()
            .map(|s| (s.to_string(), vec![1.0; n]))
            .collect(),
        distance: Some(distance),
        ..View::default()
    }
}

/// Where Chromium is: `$VIEWER_CHROMIUM` when set (and then only there, so that pointing it
/// at nothing tries the skip), else `/usr/bin/chromium` or `chromium` on the `PATH`.
pub fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("VIEWER_CHROMIUM") {
        let p = PathBuf::from(p);
        return p.exists().then_some(p);
    }
    let fixed = PathBuf::from("/usr/bin/chromium");
    if fixed.exists() {
        return Some(fixed);
    }
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("chromium"))
            .find(|p| p.exists())
    })
}

/// Chromium, or `None` after printing why the test is skipped; with `VIEWER_REQUIRE_BROWSER=1`
/// a missing browser fails the test instead.
pub fn browser_or_skip(test: &str) -> Option<PathBuf> {
    let found = chromium();
    if found.is_none() {
        let why = match std::env::var_os("VIEWER_CHROMIUM") {
            Some(p) => format!(
                "no Chromium: $VIEWER_CHROMIUM = {} does not exist",
                p.to_string_lossy()
            ),
            None => "no Chromium: /usr/bin/chromium is missing, $VIEWER_CHROMIUM is unset and \
                     `chromium` is not on the PATH (Debian: apt-get install -y chromium)"
                .to_string(),
        };
        if std::env::var("VIEWER_REQUIRE_BROWSER").as_deref() == Ok("1") {
            panic!("{test}: VIEWER_REQUIRE_BROWSER=1 but {why}");
        }
        eprintln!("SKIPPED {test}: {why}");
    }
    found
}

/// One Chromium run at a time: two at once on two cores only make each slower and a timeout
/// likelier.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

/// A screenshot as RGB rows, and the page's status after drawing.
pub struct Shot {
    /// `ready:<mode>` or `error:<message>` (the page's `#status`), or what stood in its place.
    pub status: String,
    /// Pixels across.
    pub width: usize,
    /// Pixels down.
    pub height: usize,
    /// RGB, row by row from the top.
    pub rgb: Vec<u8>,
}

impl Shot {
    /// The pixel at column `x`, row `y`.
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        let k = 3 * (y * self.width + x);
        [self.rgb[k], self.rgb[k + 1], self.rgb[k + 2]]
    }
}

/// Runs Chromium on `page#hash` with the given arguments, returning standard output.
fn run(browser: &Path, args: &[String]) -> String {
    let user_dir = tempfile::tempdir().expect("a temporary profile directory");
    let mut child = Command::new(browser)
        .args(CHROMIUM_FLAGS)
        .arg(format!("--user-data-dir={}", user_dir.path().display()))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {}: {e}", browser.display()));
    // Standard output (a dumped DOM holds the whole page) is read while the browser runs: a
    // full pipe would stop it.
    let mut stdout = child.stdout.take();
    let reader = std::thread::spawn(move || {
        use std::io::Read as _;
        let mut out = String::new();
        if let Some(s) = stdout.as_mut() {
            let _ = s.read_to_string(&mut out);
        }
        out
    });
    let start = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(_)) => break,
            Ok(None) if start.elapsed() > CHROMIUM_TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                panic!("chromium {args:?} did not finish in {CHROMIUM_TIMEOUT:?}");
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(50)),
            Err(e) => panic!("waiting for chromium: {e}"),
        }
    }
    reader.join().unwrap_or_default()
}

/// The page at `hash` (without `#`), `width × height`: its status (from `--dump-dom`) and a
/// screenshot (a second run: one state a run). With `$VIEWER_SCREENSHOTS` set, the PNG is kept
/// there as `<name>.png` to look at.
pub fn shoot(browser: &Path, page: &Path, hash: &str, size: (usize, usize), name: &str) -> Shot {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let url = format!("file://{}#{hash}", page.display());
    let window = format!("--window-size={},{}", size.0, size.1);
    let dom = run(browser, &[window.clone(), "--dump-dom".into(), url.clone()]);
    let status = dom
        .split("id=\"status\">")
        .nth(1)
        .and_then(|s| s.split('<').next())
        .unwrap_or("no status in the DOM")
        .to_string();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let png = dir.path().join("shot.png");
    run(
        browser,
        &[window, format!("--screenshot={}", png.display()), url],
    );
    if let Some(keep) = std::env::var_os("VIEWER_SCREENSHOTS") {
        let _ = std::fs::create_dir_all(&keep);
        let _ = std::fs::copy(&png, Path::new(&keep).join(format!("{name}.png")));
    }
    let file = std::fs::File::open(&png).unwrap_or_else(|e| panic!("no screenshot {name}: {e}"));
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().expect("a PNG screenshot");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("a PNG frame");
    let channels = info.color_type.samples();
    let rgb = buf[..info.buffer_size()]
        .chunks(channels)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    Shot {
        status,
        width: info.width as usize,
        height: info.height as usize,
        rgb,
    }
}
