//! Mutation fuzzing of the workbench's input path on stable Rust (no coverage instrumentation,
//! no nightly): seed files per target, mutated by a deterministic engine ([`Mutator`]), each
//! input run under `catch_unwind`, panics and slow inputs reported.
//!
//! Targets ([`TARGETS`]): every mesh reader of `meshio` on its own format (`testbed`, `obj`,
//! `ply`, `stl`, `off`), the reader chosen by content (`sniff`), one line of the `curve`
//! command's JSON Lines protocol (`curve-line`), a `sweep` shard file as `merge` reads it
//! (`shard`), and `pipeline`: whatever the readers accept, repaired, estimated and fitted
//! (optimized curves) — the code a user's file reaches.
//!
//! `cargo run --release -p fuzz -- TARGET --runs N [--seed S]` runs one target;
//! `fuzz/tests/smoke.rs` runs twenty thousand inputs of each in the test suite.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use meshio::MeshFormat;
use rng::SplitMix64;

/// One fuzz target: a name, its seed directory under `fuzz/corpus/`, and the function run on
/// each input.
pub struct Target {
    /// Name on the command line.
    pub name: &'static str,
    /// What it exercises.
    pub description: &'static str,
    /// The code under test: true when the input was accepted (read without error), so a run
    /// can say how deep the mutants get; it must never panic.
    pub run: fn(&[u8]) -> bool,
}

fn read_as(format: &dyn MeshFormat, bytes: &[u8]) -> bool {
    format.read(bytes).is_ok()
}

fn pipeline(bytes: &[u8]) -> bool {
    // Inputs that would take long to fit are cut by the readers' limits, not here; the sizes a
    // mutation produces from the seeds stay small.
    let Ok(raw) = meshio::read_bytes(Path::new("input"), bytes) else {
        return false;
    };
    if raw.num_faces() > 2000 {
        return false;
    }
    let Ok(est) = estimate::estimator_by_name(estimate::DEFAULT_ESTIMATOR) else {
        return false;
    };
    let Ok(p) = estimate::prepare(&raw, estimate::EstimateChoice::With(est), false) else {
        return false;
    };
    match curves::method_by_name("optimized", &curves::MethodOptions::default()) {
        Ok(m) => surface::fit(&p.mesh, m.as_ref(), &|_| {
            surface::InteriorParameters::default()
        })
        .is_ok(),
        Err(_) => false,
    }
}

/// A result file as `merge` reads it: the lines parsed, then each checked (identity, measure
/// types and ranges) against task 0 of the default sweep, the committed seed's first task.
fn shard(bytes: &[u8]) -> bool {
    thread_local! {
        static TASK0: serde_json::Value =
            serde_json::from_str(include_str!("../corpus/shard/task-0.jsonl")).unwrap_or_default();
    }
    let Ok(text) = std::str::from_utf8(bytes) else {
        return false;
    };
    let Ok(file) = experiments::shard::read_shard(text, 20) else {
        return false;
    };
    TASK0.with(|task0| {
        file.results
            .iter()
            .enumerate()
            .all(|(i, (_, v))| experiments::shard::check_line(i + 1, v, task0).is_ok())
    })
}

fn curve_line(bytes: &[u8]) -> bool {
    thread_local! {
        static METHODS: Vec<Box<dyn curves::CurveMethod>> = curves::REGISTRY
            .iter()
            .filter_map(|e| curves::method_by_name(e.name, &curves::MethodOptions::default()).ok())
            .collect();
    }
    METHODS.with(
        |methods| match curves::jsonl::answer_line(1, bytes, methods) {
            Some(Ok(a)) => {
                let _ = curves::jsonl::answer_json(&a).to_string();
                true
            }
            _ => false,
        },
    )
}

/// Every target.
pub static TARGETS: &[Target] = &[
    Target {
        name: "testbed",
        description: "meshio's testbed-format reader",
        run: |b| read_as(&meshio::testbed::Testbed, b),
    },
    Target {
        name: "obj",
        description: "meshio's OBJ reader",
        run: |b| read_as(&meshio::obj::Obj, b),
    },
    Target {
        name: "ply",
        description: "meshio's PLY reader",
        run: |b| read_as(&meshio::ply::Ply, b),
    },
    Target {
        name: "stl",
        description: "meshio's STL reader",
        run: |b| read_as(&meshio::stl::Stl, b),
    },
    Target {
        name: "off",
        description: "meshio's OFF reader",
        run: |b| read_as(&meshio::off::Off, b),
    },
    Target {
        name: "sniff",
        description: "the reader chosen by content (meshio::read_bytes with no extension)",
        run: |b| meshio::read_bytes(Path::new("input"), b).is_ok(),
    },
    Target {
        name: "curve-line",
        description: "one line of the curve command's JSON Lines protocol, answered by every construction with its measures",
        run: curve_line,
    },
    Target {
        name: "shard",
        description: "a sweep result file as merge reads it, each line checked against the default sweep's first task",
        run: shard,
    },
    Target {
        name: "pipeline",
        description:
            "read by content, repair, estimate (default estimator), fit with optimized curves",
        run: pipeline,
    },
];

/// The target called `name`.
pub fn target_by_name(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}

/// The seed files of a target: `fuzz/corpus/<dir>/*`, where `pipeline` and `sniff` use every
/// directory.
pub fn seeds(target: &str) -> Vec<Vec<u8>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus");
    let dirs: Vec<PathBuf> = match target {
        "pipeline" | "sniff" => std::fs::read_dir(&root)
            .map(|d| d.filter_map(|e| e.ok().map(|e| e.path())).collect())
            .unwrap_or_default(),
        "curve-line" => vec![root.join("curve")],
        t => vec![root.join(t)],
    };
    let mut files: Vec<PathBuf> = dirs
        .iter()
        .filter_map(|d| std::fs::read_dir(d).ok())
        .flat_map(|d| d.filter_map(|e| e.ok().map(|e| e.path())))
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files.iter().filter_map(|p| std::fs::read(p).ok()).collect()
}

/// A deterministic mutation engine (driven by the workbench's one generator,
/// [`rng::SplitMix64`], so a run is replayed by its seed): bit flips, byte overwrites with
/// interesting values, insertions, deletions, duplicated or spliced chunks, ASCII digits
/// replaced by extreme numbers, truncation.
pub struct Mutator {
    rng: SplitMix64,
}

/// Numbers a parser should survive, spliced into text inputs.
const INTERESTING: &[&str] = &[
    "0",
    "-1",
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "-inf",
    "4294967295",
    "18446744073709551615",
    "9999999999999999999999",
    "-0",
    "0x10",
    "1.5e",
    "[",
    "]",
    "((((((((",
    "{",
    "}",
    ";",
    "\"",
];

impl Mutator {
    /// A mutator from a seed.
    pub fn new(seed: u64) -> Self {
        Mutator {
            rng: SplitMix64::new(seed),
        }
    }

    fn next(&mut self) -> u64 {
        self.rng.next_u64()
    }

    fn below(&mut self, n: usize) -> usize {
        self.rng.below(n)
    }

    /// One to eight mutations of `input`, splicing from `other` sometimes.
    pub fn mutate(&mut self, input: &[u8], other: &[u8]) -> Vec<u8> {
        let mut b = input.to_vec();
        // Mostly one mutation (so most mutants stay close to valid and reach deep code), now and
        // then up to eight.
        let n = if self.below(4) == 0 {
            1 + self.below(8)
        } else {
            1
        };
        for _ in 0..n {
            let len = b.len();
            match self.below(9) {
                0 if len > 0 => {
                    let i = self.below(len);
                    b[i] ^= 1 << self.below(8);
                }
                1 if len > 0 => {
                    let i = self.below(len);
                    b[i] = [0u8, 0xff, 0x7f, 0x80, b'\n', b' ', b'-', b'.'][self.below(8)];
                }
                2 => {
                    let i = self.below(len + 1);
                    b.insert(i, self.next() as u8);
                }
                3 if len > 0 => {
                    let i = self.below(len);
                    let k = 1 + self.below(16.min(len - i));
                    b.drain(i..i + k);
                }
                4 if len > 0 => {
                    let i = self.below(len);
                    let k = 1 + self.below(64.min(len - i));
                    let chunk = b[i..i + k].to_vec();
                    let at = self.below(len + 1);
                    b.splice(at..at, chunk);
                }
                5 if !other.is_empty() => {
                    let i = self.below(other.len());
                    let k = 1 + self.below(64.min(other.len() - i));
                    let at = self.below(len + 1);
                    b.splice(at..at, other[i..i + k].iter().copied());
                }
                6 if len > 0 => {
                    // Replace a run of digits by an interesting token.
                    let i = self.below(len);
                    if let Some(s) = b[i..].iter().position(|c| c.is_ascii_digit()) {
                        let s = i + s;
                        let e = s + b[s..].iter().take_while(|c| c.is_ascii_digit()).count();
                        let tok = INTERESTING[self.below(INTERESTING.len())].as_bytes();
                        b.splice(s..e, tok.iter().copied());
                    }
                }
                7 if len > 0 => {
                    b.truncate(self.below(len));
                }
                _ if len >= 4 => {
                    // Overwrite a little-endian u32 with a boundary value (binary counts).
                    let i = self.below(len - 3);
                    let v: u32 = [0, 1, 3, 0xffff_ffff, 0x8000_0000, 0x7fff_ffff][self.below(6)];
                    b[i..i + 4].copy_from_slice(&v.to_le_bytes());
                }
                _ => {}
            }
        }
        b
    }
}

/// What a run found.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Inputs run.
    pub executions: u64,
    /// Inputs the target accepted (read without error; for `pipeline`, fitted).
    pub accepted: u64,
    /// Inputs that panicked, with the panic message.
    pub panics: Vec<(Vec<u8>, String)>,
    /// The slowest input's time.
    pub slowest: Duration,
    /// Inputs slower than the limit given.
    pub slow: Vec<Vec<u8>>,
}

/// Runs `target` on `runs` mutated inputs from its seeds (and the seeds themselves first).
pub fn fuzz(target: &Target, runs: u64, seed: u64, slow_limit: Duration) -> Outcome {
    let seeds = seeds(target.name);
    let mut m = Mutator::new(seed);
    let mut out = Outcome::default();
    let mut pool: Vec<Vec<u8>> = seeds.clone();
    if pool.is_empty() {
        pool.push(Vec::new());
    }
    for k in 0..runs {
        let input = if (k as usize) < seeds.len() {
            seeds[k as usize].clone()
        } else {
            // Half the parents are seeds, so the pool cannot drift to trivial inputs.
            let a = if m.below(2) == 0 && !seeds.is_empty() {
                &seeds[m.below(seeds.len())]
            } else {
                &pool[m.below(pool.len())]
            };
            let b = &pool[m.below(pool.len())];
            m.mutate(a, b)
        };
        let t = Instant::now();
        let result = catch_unwind(AssertUnwindSafe(|| (target.run)(&input)));
        let dt = t.elapsed();
        out.executions += 1;
        out.accepted += u64::from(matches!(result, Ok(true)));
        if dt > out.slowest {
            out.slowest = dt;
        }
        if dt > slow_limit {
            out.slow.push(input.clone());
        }
        let accepted = matches!(result, Ok(true));
        if let Err(e) = result {
            let msg = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            out.panics.push((input.clone(), msg));
        }
        // Keep accepted mutants as new parents (bounded pool), so mutations compound on inputs
        // that still reach past the parser's first checks.
        if (k as usize) >= seeds.len() && accepted && m.below(4) == 0 {
            if pool.len() < 256 {
                pool.push(input);
            } else {
                let i = m.below(pool.len());
                pool[i] = input;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::Hasher as _;

    /// The mutation stream is pinned: a recorded long run (docs/hostile-input.md) is replayed by
    /// its seed, so the engine's draws ([`rng::SplitMix64`]) must not change. The hash was
    /// taken before the generator moved to the `rng` crate (from a copy here).
    #[test]
    fn mutants_of_a_seed_are_pinned() {
        let input =
            b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nend_header\n0 1 2\n";
        let other = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        let mut m = Mutator::new(7);
        let mut h = meshio::hash::FxHasher::default();
        for _ in 0..2000 {
            let b = m.mutate(input, other);
            h.write_usize(b.len());
            h.write(&b);
        }
        assert_eq!(h.finish(), 0x3bd8_7d44_9c81_29bd);
    }
}
