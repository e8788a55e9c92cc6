//! `cargo run --release -p fuzz -- TARGET [--runs N] [--seed S] [--slow-ms MS]`: mutation
//! fuzzing of one target (`all` for every one); panicking and slow inputs are written to
//! `fuzz/crashes/<target>-<n>` and the exit status is 1 when there were any.

use std::process::ExitCode;
use std::time::{Duration, Instant};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(name) = args.first() else {
        eprintln!(
            "usage: fuzz TARGET [--runs N] [--seed S] [--slow-ms MS]; targets: all, {}",
            fuzz::TARGETS
                .iter()
                .map(|t| t.name)
                .collect::<Vec<_>>()
                .join(", ")
        );
        return ExitCode::from(2);
    };
    let opt = |flag: &str, default: u64| -> u64 {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (runs, seed, slow) = (
        opt("--runs", 100_000),
        opt("--seed", 1),
        opt("--slow-ms", 1000),
    );
    let targets: Vec<&fuzz::Target> = if name == "all" {
        fuzz::TARGETS.iter().collect()
    } else {
        match fuzz::target_by_name(name) {
            Some(t) => vec![t],
            None => {
                eprintln!("unknown target `{name}`");
                return ExitCode::from(2);
            }
        }
    };
    // Panics are expected to be caught and reported, not printed as they happen.
    std::panic::set_hook(Box::new(|_| {}));
    let mut bad = 0;
    for t in targets {
        let t0 = Instant::now();
        let out = fuzz::fuzz(t, runs, seed, Duration::from_millis(slow));
        let secs = t0.elapsed().as_secs_f64();
        println!(
            "{:<9} {} executions ({} accepted) in {:.1} s ({:.0}/s), {} panics, {} slower than {} ms (slowest {:.1} ms)",
            t.name,
            out.executions,
            out.accepted,
            secs,
            out.executions as f64 / secs.max(1e-9),
            out.panics.len(),
            out.slow.len(),
            slow,
            out.slowest.as_secs_f64() * 1e3
        );
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("crashes");
        for (k, (input, msg)) in out.panics.iter().enumerate().take(20) {
            let _ = std::fs::create_dir_all(&dir);
            let path = dir.join(format!("{}-{k}", t.name));
            let _ = std::fs::write(&path, input);
            println!("  panic: {msg} → {}", path.display());
        }
        for (k, input) in out.slow.iter().enumerate().take(20) {
            let _ = std::fs::create_dir_all(&dir);
            let _ = std::fs::write(dir.join(format!("{}-slow-{k}", t.name)), input);
        }
        bad += out.panics.len() + out.slow.len();
    }
    if bad > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}
