//! Shell completions and man pages of `testbed`, generated from the filter registry's command.

#![allow(clippy::expect_used, clippy::unwrap_used)] // test fixtures fail loudly by design

use crate::support::{ok, testbed};

#[test]
fn completions_list_every_registered_filter() {
    let text = String::from_utf8(ok(&["completions", "bash"], b"")).unwrap();
    for filter in testbed::filters::FILTERS {
        assert!(text.contains(filter.name()), "no {}", filter.name());
    }
    assert!(text.contains("--segments"));
    assert_eq!(
        testbed(&["completions", "nope"], b"").status.code(),
        Some(2)
    );
}

#[test]
fn a_man_page_is_written_for_every_filter() {
    let dir = tempfile::tempdir().unwrap();
    let out = testbed(&["man", "--output", dir.path().to_str().unwrap()], b"");
    assert!(out.status.success());
    for filter in testbed::filters::FILTERS {
        let page = dir.path().join(format!("testbed-{}.1", filter.name()));
        let text = std::fs::read_to_string(&page).expect("a page");
        assert!(text.contains(".TH"), "{}", page.display());
    }
}
