//! `testbed`: the pipeline's filters as subcommands, built from the registry
//! (`testbed::filters::FILTERS`; see the library's docs and `examples/` at the repository
//! root).
//!
//! ```sh
//! testbed fit --scheme shirman-sequin < data/octa.m | testbed tess -s 8 | testbed mat0 \
//!     | testbed render > octa.png
//! ```

use std::process::ExitCode;

use clap::Command;
use testbed::filters::{self, FILTERS};

/// The command line: one subcommand a registered filter, in the registry's order, then the
/// shell completions and the man pages (`clidocs`).
fn command() -> Command {
    Command::new("testbed")
        .version(env!("CARGO_PKG_VERSION"))
        .about(
            "Filters of the surface-interpolation testbed (Lounsbery et al. 1990), connected by pipes",
        )
        .subcommand_required(true)
        .arg_required_else_help(true)
        .subcommands(FILTERS.iter().map(|f| f.command()))
        .subcommand(clidocs::completions_command())
        .subcommand(clidocs::man_command())
}

fn main() -> ExitCode {
    let mut command = command();
    let matches = command.get_matches_mut();
    if let Some((name, sub)) = matches.subcommand() {
        if let Some(done) = clidocs::run(&mut command, name, sub) {
            return match done {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("testbed {name}: error: {e}");
                    ExitCode::FAILURE
                }
            };
        }
    }
    // clap has required a subcommand, one of the registry's.
    let Some((filter, sub)) = matches
        .subcommand()
        .and_then(|(name, sub)| Some((filters::find(name)?, sub)))
    else {
        let _ = command.print_help();
        return ExitCode::from(2);
    };
    let job = match filter.parse(sub) {
        Ok(job) => job,
        Err(e) => e.format(&mut command).exit(),
    };
    match job() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("testbed {}: error: {e}", filter.name());
            // 2 for a usage error, 1 for a runtime error (docs/conventions.md).
            ExitCode::from(e.exit_code())
        }
    }
}

#[cfg(test)]
mod tests {
    /// clap's own checks of the command built from the registry (names, ids, defaults).
    #[test]
    fn the_command_line_is_consistent() {
        super::command().debug_assert();
    }
}
