//! Progress on long work, shown as users of command-line tools expect: a bar (work with a known
//! count) or a spinner (a stage of unknown length) on standard error, **only** when standard
//! error is a terminal and only once the work has run for [`DELAY`]; silent in files, CI logs
//! and tests, and on work that ends sooner. In a pipeline only the last stage shows progress
//! (a program whose standard output is a pipe stays silent): the stages share one terminal
//! line, and the last one's count is the pipeline's. `NO_PROGRESS` set to anything but `0` or the
//! empty string turns it off on a terminal too.
//!
//! Lines a front end prints while a bar is up go through [`Progress::say`], which lifts the
//! bar, prints the line and puts the bar back (printing around it would tear the bar's line).
//!
//! ```
//! let p = progress::Progress::bar("sweep", 20);
//! for _ in 0..20 {
//!     p.inc(1);
//! }
//! p.finish();
//! ```

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long work runs before its progress appears: work shorter than this shows nothing (the
/// "couple of seconds" under which a bar is only flicker).
pub const DELAY: Duration = Duration::from_millis(1500);

/// How often a shown spinner turns and a bar redraws (ten times a second: smooth, and no
/// measurable cost).
const TICK: Duration = Duration::from_millis(100);

/// Whether progress may be drawn at all: standard error is a terminal, standard output is not
/// a pipe into a further stage, and `NO_PROGRESS` does not turn it off.
pub fn enabled() -> bool {
    let off = std::env::var_os("NO_PROGRESS").is_some_and(|v| !v.is_empty() && v != "0");
    !off && std::io::stderr().is_terminal() && !stdout_is_pipe()
}

/// Whether standard output is a pipe (a FIFO), as it is in every stage of a pipeline but the
/// last.
fn stdout_is_pipe() -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        std::fs::metadata("/dev/stdout").is_ok_and(|m| m.file_type().is_fifo())
    }
    #[cfg(not(unix))]
    {
        false
    }
}

/// A bar or spinner that appears after [`DELAY`] on a terminal and stays hidden otherwise. It
/// is removed when finished or dropped.
pub struct Progress {
    bar: ProgressBar,
    done: Arc<AtomicBool>,
    ticker: Option<JoinHandle<()>>,
}

impl Progress {
    /// A bar for `total` units of work, labelled `label` (`sweep`, `estimation`).
    pub fn bar(label: &str, total: u64) -> Progress {
        let style = ProgressStyle::with_template(
            "{prefix} [{bar:32}] {pos}/{len} {msg} ({elapsed}, about {eta} left)",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
        Progress::start(ProgressBar::new(total).with_style(style), label)
    }

    /// A spinner for a stage whose length is not known, labelled `label`; [`Progress::stage`]
    /// names the stage.
    pub fn spinner(label: &str) -> Progress {
        let style = ProgressStyle::with_template("{prefix} {spinner} {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        Progress::start(ProgressBar::new_spinner().with_style(style), label)
    }

    /// Hidden until [`DELAY`] has passed, then drawn and ticked by a background thread until
    /// finished (never drawn when [`enabled`] is false: no thread is started).
    fn start(bar: ProgressBar, label: &str) -> Progress {
        bar.set_draw_target(ProgressDrawTarget::hidden());
        bar.set_prefix(label.to_string());
        let done = Arc::new(AtomicBool::new(false));
        let ticker = enabled().then(|| {
            let (bar, done) = (bar.clone(), Arc::clone(&done));
            std::thread::spawn(move || {
                let mut waited = Duration::ZERO;
                while !done.load(Ordering::Relaxed) {
                    std::thread::sleep(TICK);
                    waited += TICK;
                    if waited >= DELAY && bar.is_hidden() && !done.load(Ordering::Relaxed) {
                        bar.set_draw_target(ProgressDrawTarget::stderr());
                    }
                    bar.tick();
                }
            })
        });
        Progress { bar, done, ticker }
    }

    /// Whether the bar is drawn now (false before [`DELAY`] and wherever [`enabled`] is false).
    pub fn is_shown(&self) -> bool {
        !self.bar.is_hidden()
    }

    /// Advances a bar by `n` units.
    pub fn inc(&self, n: u64) {
        self.bar.inc(n);
    }

    /// Names what is being done now (a stage, a task).
    pub fn stage(&self, what: &str) {
        self.bar.set_message(what.to_string());
    }

    /// Names what is being done now, built only when the bar can be shown (for messages
    /// updated in a hot loop: no formatting where nothing is drawn).
    pub fn stage_with(&self, what: impl FnOnce() -> String) {
        if self.ticker.is_some() {
            self.bar.set_message(what());
        }
    }

    /// Prints `line` on standard error above the bar (or plainly, when no bar is shown).
    pub fn say(&self, line: &str) {
        self.bar.suspend(|| {
            use std::io::Write as _;
            let _ = writeln!(std::io::stderr(), "{line}");
        });
    }

    /// Runs `f` with the bar lifted (for output that is not one line).
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        self.bar.suspend(f)
    }

    /// Removes the bar from the terminal.
    pub fn finish(mut self) {
        self.stop();
    }

    fn stop(&mut self) {
        self.done.store(true, Ordering::Relaxed);
        if let Some(t) = self.ticker.take() {
            let _ = t.join();
        }
        self.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.stop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Under `cargo test` standard error is captured (not a terminal): nothing is ever drawn,
    /// and no ticker thread runs.
    #[test]
    fn progress_is_silent_off_a_terminal() {
        if std::io::stderr().is_terminal() {
            return; // run by hand on a terminal: the check below does not apply
        }
        assert!(!enabled());
        let p = Progress::bar("test", 3);
        assert!(p.ticker.is_none());
        p.inc(3);
        std::thread::sleep(TICK);
        assert!(!p.is_shown());
        p.finish();
    }

    /// The bar counts what it is given, shown or not.
    #[test]
    fn a_bar_counts_its_units() {
        let p = Progress::bar("test", 10);
        p.inc(4);
        p.inc(3);
        assert_eq!(p.bar.position(), 7);
        assert_eq!(p.bar.length(), Some(10));
    }
}
