//! `fit --html` and `view`: one self-contained page that names no network resource, carries
//! the surface's modes (the distance one only with a true surface), and refuses what it cannot
//! draw. The pages themselves are opened in headless Chromium by the viewer's tests.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::common;

/// What an offline page must not hold: a reference a browser would fetch (a script or style
/// source, a link, an import or a CSS url). Plain URLs in strings are fine (three.js names the
/// XHTML namespace `http://www.w3.org/1999/xhtml`, which nothing fetches).
const NETWORK: [&str; 7] = [
    "src=\"http",
    "src=\"//",
    "href=\"http",
    "from 'http",
    "from \"http",
    "url(http",
    "import(\"http",
];

#[test]
fn fit_writes_an_offline_page_with_the_surface_and_its_truth() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("octa.html");
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--curves",
            "optimized",
            "--html",
            page.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("page:"), "{err}");
    let html = std::fs::read_to_string(&page).unwrap();
    for bad in NETWORK {
        assert!(!html.contains(bad), "the page references {bad}");
    }
    assert!(html.contains("octa — shirman-sequin"));
    // The data set's truth gives the distance mode; the octahedron's patches their nets.
    assert!(html.contains("\"distance\""), "no distance data");
    assert!(html.contains("\"nets\""), "no control nets");
    // The same fit's numbers with and without the page (the page holds the fit whole).
    let (code, _, plain) = common::run(&["fit", "--data", "octa", "--curves", "optimized"], "");
    assert_eq!(code, 0);
    let g1 = |s: &str| {
        s.lines()
            .find(|l| l.contains("G1 defect"))
            .map(str::to_string)
    };
    assert_eq!(g1(&err), g1(&plain));
}

#[test]
fn html_is_refused_for_a_subdivision_scheme_and_view_reads_what_fit_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("loop.html");
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--scheme",
            "loop",
            "--html",
            page.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("subdivision"), "{err}");
    assert!(!page.exists());
    let patches = dir.path().join("octa.jsonl");
    let mesh = dir.path().join("octa.ply");
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--output",
            patches.to_str().unwrap(),
            "--mesh-output",
            mesh.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let view = dir.path().join("view.html");
    let (code, _, err) = common::run(
        &[
            "view",
            patches.to_str().unwrap(),
            mesh.to_str().unwrap(),
            "-o",
            view.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let html = std::fs::read_to_string(&view).unwrap();
    assert!(html.contains("octa.jsonl") && html.contains("octa.ply"));
    let (code, _, err) = common::run(&["view", "/no/such.ply", "-o", view.to_str().unwrap()], "");
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("/no/such.ply"), "{err}");
    // A density outside `fit --segments`'s range is a usage error (issue 43: 4096 aborted on
    // the memory it asked for), and the page is not written over.
    let before = std::fs::read(&view).unwrap();
    for density in ["0", "4096"] {
        let (code, _, err) = common::run(
            &[
                "view",
                patches.to_str().unwrap(),
                "--density",
                density,
                "-o",
                view.to_str().unwrap(),
            ],
            "",
        );
        assert_eq!(code, 2, "{density}: {err}");
        assert!(err.contains("--density"), "{err}");
        assert_eq!(std::fs::read(&view).unwrap(), before);
    }
}

/// A directory stands for its meshes and patch files, sorted by name: a patch `.jsonl` is
/// shown, a `.jsonl` of other records (a sweep's results) and pictures are named as skipped,
/// and a directory with nothing to show is refused by name.
#[test]
fn view_of_a_result_directory_shows_its_meshes_and_patches_and_names_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (code, _, err) = common::run(
        &[
            "fit",
            "--data",
            "octa",
            "--output",
            d.join("b-patches.jsonl").to_str().unwrap(),
            "--mesh-output",
            d.join("a-octa.ply").to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    std::fs::write(d.join("results.jsonl"), "{\"task\":\"ring/chord\"}\n").unwrap();
    std::fs::write(d.join("report.md"), "# report\n").unwrap();
    let page = tempfile::tempdir().unwrap();
    let view = page.path().join("dir.html");
    let (code, _, err) = common::run(
        &["view", d.to_str().unwrap(), "-o", view.to_str().unwrap()],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("skipped 2 files") && err.contains("report.md, results.jsonl"),
        "{err}"
    );
    let html = std::fs::read_to_string(&view).unwrap();
    let (a, b) = (
        html.find("a-octa.ply").unwrap(),
        html.find("b-patches.jsonl").unwrap(),
    );
    assert!(a < b, "views out of name order");
    assert!(!html.contains("results.jsonl"));
    let empty = tempfile::tempdir().unwrap();
    std::fs::write(empty.path().join("notes.txt"), "x").unwrap();
    let (code, _, err) = common::run(
        &[
            "view",
            empty.path().to_str().unwrap(),
            "-o",
            view.to_str().unwrap(),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("holds no mesh or patch file"), "{err}");
}
