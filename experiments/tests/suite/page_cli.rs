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
}
