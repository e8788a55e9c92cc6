//! The registry of filters (`testbed::filters::FILTERS`): the command line is built from it,
//! `testbed --help` lists it in order with its summaries, and the README's table of filters is
//! rendered from it.
#![allow(clippy::expect_used, clippy::unwrap_used)] // tests: a failed step should stop loudly

use std::collections::HashSet;
use std::process::Command;

use testbed::filters::{self, FILTERS};

/// The markers around the README's table of filters.
const BEGIN: &str = "<!-- filters:begin -->";
const END: &str = "<!-- filters:end -->";

/// The README holds exactly the table rendered from the registry between its markers; when
/// a filter is added or its summary changes, the failure prints the table to paste there.
#[test]
fn readme_table_of_filters_is_the_registrys() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/README.md");
    let readme = std::fs::read_to_string(path).expect("README.md");
    let expected = filters::markdown_table();
    let (Some(begin), Some(end)) = (readme.find(BEGIN), readme.find(END)) else {
        panic!("{path}: no `{BEGIN}` … `{END}` markers; put them around this table:\n\n{expected}");
    };
    assert!(begin < end, "{path}: `{END}` before `{BEGIN}`");
    assert_eq!(
        readme.matches(BEGIN).count() + readme.matches(END).count(),
        2,
        "{path}: one pair of markers"
    );
    let found = readme[begin + BEGIN.len()..end].trim_matches('\n');
    assert!(
        found == expected.trim_end(),
        "{path}: the table of filters is not the registry's (testbed/src/filters/mod.rs); \
         paste this between `{BEGIN}` and `{END}`:\n\n{expected}"
    );
}

/// Names are unique and kebab-case, summaries one line without a final period (clap's
/// style), and every filter's command passes clap's own checks with the stream options.
#[test]
fn every_registered_filter_is_well_formed() {
    let mut names = HashSet::new();
    for f in FILTERS {
        let name = f.name();
        assert!(names.insert(name), "{name} registered twice");
        assert!(
            !name.is_empty()
                && name
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'),
            "{name}: a subcommand name"
        );
        let summary = f.summary();
        assert!(
            !summary.is_empty() && !summary.contains('\n') && !summary.ends_with('.'),
            "{name}: summary {summary:?}"
        );
        let command = f.command();
        command.clone().debug_assert();
        assert_eq!(command.get_name(), name);
        assert_eq!(
            command.get_about().map(|a| a.to_string()).as_deref(),
            Some(summary)
        );
        for option in ["input", "output", "format", "keep_going"] {
            assert!(
                command.get_arguments().any(|a| a.get_id() == option),
                "{name}: no --{option}"
            );
        }
        assert_eq!(
            filters::find(name).map(|g| g.name()),
            Some(name),
            "{name}: found by name"
        );
    }
    assert!(filters::find("no-such-filter").is_none());
}

/// A filter's options and the stream options come back from its matches.
#[test]
fn a_filter_parses_its_own_matches() {
    let tess = filters::find("tess").expect("tess is registered");
    let matches = tess
        .command()
        .try_get_matches_from(["tess", "-s", "3", "--kg", "--format", "binary"])
        .expect("tess's options");
    assert!(tess.parse(&matches).is_ok());
    let refused = tess
        .command()
        .try_get_matches_from(["tess", "--no-such-option"]);
    assert!(refused.is_err());
}

/// `testbed --help` lists the filters in registry order, each with its summary, then clap's
/// `help`.
#[test]
fn help_lists_the_registry_in_order() {
    let out = Command::new(env!("CARGO_BIN_EXE_testbed"))
        .arg("--help")
        .output()
        .expect("runs");
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).expect("utf-8");
    let listed: Vec<(String, String)> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .map(|l| {
            let (name, summary) = l.trim().split_once(' ').expect("name and summary");
            (name.to_string(), summary.trim().to_string())
        })
        .collect();
    let mut expected: Vec<(String, String)> = FILTERS
        .iter()
        .map(|f| (f.name().to_string(), f.summary().to_string()))
        .collect();
    // The documentation subcommands after the filters (`clidocs`), then clap's own help.
    for docs in [clidocs::completions_command(), clidocs::man_command()] {
        let about = docs.get_about().map(|a| a.to_string()).unwrap_or_default();
        expected.push((docs.get_name().to_string(), about));
    }
    expected.push((
        "help".into(),
        "Print this message or the help of the given subcommand(s)".into(),
    ));
    assert_eq!(listed, expected, "{help}");
}
