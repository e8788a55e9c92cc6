//! Valid ranges of the numeric options and memory estimates made before large allocations, so
//! that a setting the workbench cannot honour is refused with the option, the value and the
//! range, instead of producing silent nonsense or being killed by the system. Every front end
//! (both binaries, the studies) checks with these, so the limits are the same wherever a user
//! comes in.

use std::ops::RangeInclusive;

pub use surface::limits::{
    available_memory, dataset_faces, tessellation_bytes, FIT_BYTES_PER_FACE,
};

use crate::error::JobError;

/// Segments per patch edge of a tessellation (`--segments`): 1 is the patch's
/// corners only; 256 already gives 65 536 triangles per patch.
pub const SAMPLING_RANGE: RangeInclusive<usize> = 1..=256;

/// Samples per boundary of the G1 measure (`g1_samples`, Python's keyword; the command line
/// uses the default, 9): at least the two ends (fewer measures nothing, and a jump would read
/// as 0), at most 1000 (the measure's cost is linear in it: 1000 is about a hundred times the
/// default's, already several fits' worth on a large mesh).
pub const G1_SAMPLES_RANGE: RangeInclusive<usize> = 2..=1000;

/// The process's peak resident memory so far, bytes (`VmHWM` of `/proc/self/status`; `None`
/// where the system does not say).
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Every parameter of `entry`'s scheme must lie in its declared range
/// ([`surface::scheme::ParameterSpec`]): refused as `--name value: outside its valid range`.
pub fn check_scheme_parameters(
    entry: &surface::scheme::SchemeEntry,
    options: &surface::SchemeOptions,
) -> Result<(), JobError> {
    match options.out_of_range(entry) {
        None => Ok(()),
        Some((p, value)) => check_f64(p.name, value, &(p.range.0..=p.range.1), p.range_reason),
    }
}

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

/// Refuses a plan needing `bytes` when that exceeds the share of the available memory
/// ([`surface::limits::check_memory`]: the limit and the estimates are the library's, shared
/// with the testbed).
pub fn check_memory(what: &str, bytes: u128) -> Result<(), JobError> {
    surface::limits::check_memory(what, bytes).map_err(|e| JobError::TooMuchMemory {
        what: e.what,
        needed_bytes: e.needed_bytes,
        budget_bytes: e.budget_bytes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_name_option_value_and_range() {
        use surface::scheme::shirman_sequin::{BETA, C};
        let entry = surface::scheme::entry_by_name("shirman-sequin").expect("registered");
        let with = |p, v| surface::SchemeOptions::default().with(p, v);
        let e = check_scheme_parameters(entry, &with(&BETA, 1e-308)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--beta 1e-308: outside its valid range [0.01, 10] (the interior points move by ~1/β)"
        );
        assert!(check_scheme_parameters(entry, &with(&C, 1.0)).is_ok());
        assert!(check_scheme_parameters(entry, &with(&C, f64::NAN)).is_err());
        let phong = surface::scheme::entry_by_name("phong").expect("registered");
        let alpha = &surface::scheme::phong::ALPHA;
        assert!(check_scheme_parameters(phong, &with(alpha, 1e308)).is_err());
        let e = check_usize("segments", 1000, &SAMPLING_RANGE).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--segments 1000: outside its valid range [1, 256]"
        );
        assert!(check_usize("segments", usize::MAX, &SAMPLING_RANGE).is_err());
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
