//! Valid ranges of the numeric options and memory estimates made before large allocations, so
//! that a setting the workbench cannot honour is refused with the option, the value and the
//! range, instead of producing silent nonsense or being killed by the system. Every front end
//! (both binaries, the studies) checks with these, so the limits are the same wherever a user
//! comes in.

use std::ops::RangeInclusive;

use crate::error::JobError;

/// β at a corner. Any β > 0 gives a G1 surface, but the interior points move by `~1/β` (the
/// `m = 2` step divides by β): below 0.01 the nets reach 100× the triangle's size and the
/// surface folds; above 10 the first interior points overshoot the triangle tenfold. Appendix A
/// uses 1/3.
pub const BETA_RANGE: RangeInclusive<f64> = 0.01..=10.0;

/// Jensen's c on an edge. `K(t)` is a quadratic in c; at 0.01 or 100 the cross-boundary field
/// already changes by 100× along an edge, beyond which the patch folds over itself. 1 is
/// Chiyokura–Kimura.
pub const C_RANGE: RangeInclusive<f64> = 0.01..=100.0;

/// Segments per patch edge of a tessellation (`--tess`, `--sampling`): 1 is the patch's
/// corners only; 256 already gives 65 536 triangles per patch.
pub const SAMPLING_RANGE: RangeInclusive<usize> = 1..=256;

/// Bytes one tessellation vertex takes (position, normal, K, H, shape tensor: 136 bytes, plus
/// the welding grid's entry), and one output triangle (indices and its patch).
const TESS_BYTES_PER_VERTEX: usize = 160;
const TESS_BYTES_PER_TRIANGLE: usize = 32;

/// Bytes a fitted face takes: mesh and adjacency (~300), three quartic nets (1080), curves and
/// measurement buffers (~600).
pub const FIT_BYTES_PER_FACE: usize = 2000;

/// The share of the available memory a run may plan to use.
const MEMORY_SHARE: f64 = 0.8;

/// The process's peak resident memory so far, bytes (`VmHWM` of `/proc/self/status`; `None`
/// where the system does not say).
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Memory assumed available where the system does not say (`/proc/meminfo` absent).
const FALLBACK_AVAILABLE: u64 = 8 << 30;

/// `--option value` must lie in `range` (`option` without its dashes; `why` says why the range is
/// what it is).
pub fn check_f64(
    option: &'static str,
    value: f64,
    range: &RangeInclusive<f64>,
    why: &'static str,
) -> Result<(), JobError> {
    if range.contains(&value) {
        return Ok(());
    }
    let shown = if value != 0.0 && !(1e-3..1e6).contains(&value.abs()) {
        format!("{value:e}")
    } else {
        format!("{value}")
    };
    Err(JobError::OutOfRange {
        option,
        value: shown,
        range: format!("[{}, {}]", range.start(), range.end()),
        why: Some(why),
    })
}

/// `--option value` must lie in `range` (`option` without its dashes).
pub fn check_usize(
    option: &'static str,
    value: usize,
    range: &RangeInclusive<usize>,
) -> Result<(), JobError> {
    if range.contains(&value) {
        return Ok(());
    }
    Err(JobError::OutOfRange {
        option,
        value: value.to_string(),
        range: format!("[{}, {}]", range.start(), range.end()),
        why: None,
    })
}

/// Memory available to this process, bytes (Linux `MemAvailable`, else a stated assumption).
pub fn available_memory() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| {
            text.lines()
                .find(|l| l.starts_with("MemAvailable:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<u64>().ok())
                .map(|kb| kb * 1024)
        })
        .unwrap_or(FALLBACK_AVAILABLE)
}

/// Refuses a plan needing `bytes` when that exceeds the share of the available memory.
pub fn check_memory(what: &str, bytes: u128) -> Result<(), JobError> {
    let budget = (available_memory() as f64 * MEMORY_SHARE) as u128;
    if bytes <= budget {
        return Ok(());
    }
    Err(JobError::TooMuchMemory {
        what: what.to_string(),
        needed_bytes: bytes,
        budget_bytes: budget,
    })
}

/// Estimated bytes of a tessellation of `patches` patches at `s` segments per edge.
pub fn tessellation_bytes(patches: u128, s: usize) -> u128 {
    let (p, s) = (patches, s as u128);
    p * ((s + 1) * (s + 2) / 2 * TESS_BYTES_PER_VERTEX as u128
        + s * s * TESS_BYTES_PER_TRIANGLE as u128)
}

/// Faces of a named data set at a resolution (before building it), for the memory check.
pub fn dataset_faces(name: &str, resolution: usize) -> u128 {
    let n = resolution as u128;
    match name {
        "ring" => 2 * n * (n / 2).max(3),
        "capsule" => 2 * n * n,
        "sphere" => 8u128.saturating_mul(4u128.saturating_pow(resolution.min(60) as u32)),
        _ => 0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_name_option_value_and_range() {
        let e = check_f64("beta", 1e-308, &BETA_RANGE, "β").unwrap_err();
        assert!(e
            .to_string()
            .contains("--beta 1e-308: outside its valid range [0.01, 10]"));
        assert!(check_f64("c", 1.0, &C_RANGE, "c").is_ok());
        assert!(check_f64("c", f64::NAN, &C_RANGE, "c").is_err());
        let e = check_usize("tess", 1000, &SAMPLING_RANGE).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--tess 1000: outside its valid range [1, 256]"
        );
        assert!(check_usize("tess", usize::MAX, &SAMPLING_RANGE).is_err());
    }

    #[test]
    fn memory_estimates_refuse_the_impossible() {
        assert!(check_memory("x", 1 << 20).is_ok());
        let e = check_memory("a 4096 ring", dataset_faces("ring", 4096) * 10_000).unwrap_err();
        assert!(e.to_string().contains("GB"), "{e}");
        assert_eq!(dataset_faces("ring", 16), 256);
        assert_eq!(tessellation_bytes(1, 1), 3 * 160 + 32);
    }
}
