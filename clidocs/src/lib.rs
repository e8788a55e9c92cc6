//! Shell completions and man pages of a binary's command line, generated from the same
//! `clap::Command` the binary parses with (so they list what the registries list, and cannot
//! drift from `--help`).
//!
//! Each binary offers them as two subcommands, [`completions_command`] and [`man_command`]:
//!
//! ```sh
//! experiments completions bash > ~/.local/share/bash-completion/completions/experiments
//! experiments man --output ~/.local/share/man/man1   # experiments.1, experiments-fit.1, …
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Arg, ArgMatches, Command};
pub use clap_complete::Shell;

/// The name of the completions subcommand.
pub const COMPLETIONS: &str = "completions";
/// The name of the man-page subcommand.
pub const MAN: &str = "man";

/// `completions SHELL`: the completion script of the binary for a shell, on standard output.
pub fn completions_command() -> Command {
    Command::new(COMPLETIONS)
        .about("Print the shell completion script (bash, zsh, fish, elvish, powershell) to standard output")
        .arg(
            Arg::new("shell")
                .required(true)
                .value_parser(clap::value_parser!(Shell))
                .help("The shell"),
        )
}

/// `man --output DIR`: one man page for the binary and one a subcommand, written to `DIR`.
pub fn man_command() -> Command {
    Command::new(MAN)
        .about(
            "Write the man pages (section 1: the command and one page a subcommand) to a directory",
        )
        .arg(
            Arg::new("output")
                .short('o')
                .long("output")
                .required(true)
                .value_parser(clap::value_parser!(PathBuf))
                .help("Directory for the pages (created if absent)"),
        )
}

/// What a documentation subcommand could not do.
#[derive(Debug)]
pub struct DocsError {
    /// The file or stream being written.
    pub path: PathBuf,
    /// Why.
    pub source: std::io::Error,
}

impl std::fmt::Display for DocsError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write {}: {}", self.path.display(), self.source)
    }
}

impl std::error::Error for DocsError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

/// Runs the documentation subcommand `name` with `matches` for the binary's whole `command`;
/// `None` when `name` is neither of them.
pub fn run(
    command: &mut Command,
    name: &str,
    matches: &ArgMatches,
) -> Option<Result<(), DocsError>> {
    match name {
        COMPLETIONS => Some(print_completions(
            command,
            *matches.get_one::<Shell>("shell")?,
        )),
        MAN => Some(man_pages_into(
            command,
            matches.get_one::<PathBuf>("output")?,
        )),
        _ => None,
    }
}

/// Prints the completion script of `command` for `shell` on standard output.
pub fn print_completions(command: &mut Command, shell: Shell) -> Result<(), DocsError> {
    let mut out = Vec::new();
    write_completions(command, shell, &mut out);
    std::io::stdout()
        .lock()
        .write_all(&out)
        .map_err(|source| DocsError {
            path: "<stdout>".into(),
            source,
        })
}

/// Writes the man pages of `command` into `dir` ([`write_man_pages`]) and says on standard
/// error how many.
pub fn man_pages_into(command: &Command, dir: &Path) -> Result<(), DocsError> {
    let written = write_man_pages(command, dir)?;
    let _ = writeln!(
        std::io::stderr(),
        "{} man pages written to {}",
        written.len(),
        dir.display()
    );
    Ok(())
}

/// The completion script of `command` for `shell`.
pub fn write_completions(command: &mut Command, shell: Shell, out: &mut dyn Write) {
    let name = command.get_name().to_string();
    clap_complete::generate(shell, command, name, out);
}

/// Writes `NAME.1` for `command` and `NAME-SUB.1` for each of its subcommands into `dir`;
/// returns the files written.
pub fn write_man_pages(command: &Command, dir: &Path) -> Result<Vec<PathBuf>, DocsError> {
    let err = |path: &Path| {
        let path = path.to_path_buf();
        move |source| DocsError { path, source }
    };
    std::fs::create_dir_all(dir).map_err(err(dir))?;
    let mut command = command.clone();
    command.build();
    let mut written = Vec::new();
    let name = command.get_name().to_string();
    let mut page = |cmd: Command, file: String| -> Result<(), DocsError> {
        let path = dir.join(file);
        let mut bytes = Vec::new();
        clap_mangen::Man::new(cmd)
            .render(&mut bytes)
            .map_err(err(&path))?;
        std::fs::write(&path, bytes).map_err(err(&path))?;
        written.push(path);
        Ok(())
    };
    page(command.clone(), format!("{name}.1"))?;
    // clap's generated `help` subcommand gets no page (the pages are the help).
    for sub in command.get_subcommands().filter(|s| s.get_name() != "help") {
        let sub_name = format!("{name}-{}", sub.get_name());
        page(sub.clone().name(sub_name.clone()), format!("{sub_name}.1"))?;
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)] // test fixtures fail loudly by design
    use super::*;

    fn tool() -> Command {
        Command::new("tool")
            .about("A tool")
            .subcommand(
                Command::new("fit")
                    .about("Fit")
                    .arg(Arg::new("segments").long("segments")),
            )
            .subcommand(completions_command())
            .subcommand(man_command())
    }

    #[test]
    fn completions_name_the_subcommands_and_their_options() {
        let mut out = Vec::new();
        write_completions(&mut tool(), Shell::Bash, &mut out);
        let text = String::from_utf8(out).unwrap();
        assert!(text.contains("_tool()"), "{text}");
        assert!(text.contains("fit"), "{text}");
        assert!(text.contains("--segments"), "{text}");
    }

    #[test]
    fn a_man_page_is_written_for_the_command_and_each_subcommand() {
        let dir = tempfile::tempdir().unwrap();
        let written = write_man_pages(&tool(), dir.path()).unwrap();
        let names: Vec<String> = written
            .iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect();
        assert_eq!(
            names,
            ["tool.1", "tool-fit.1", "tool-completions.1", "tool-man.1"]
        );
        let fit = std::fs::read_to_string(dir.path().join("tool-fit.1")).unwrap();
        assert!(fit.starts_with(".ie"), "{fit}");
        assert!(fit.contains(".TH tool-fit 1"), "{fit}");
        assert!(fit.contains("segments"), "{fit}");
    }
}
