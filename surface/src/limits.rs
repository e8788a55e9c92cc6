//! Memory estimates made before large allocations, shared by the workbench's binaries
//! (`experiments`, `testbed`), so that a setting the machine cannot honour is refused with the
//! options responsible and the figures, instead of the process being killed by the system or
//! aborting on a failed allocation.
//!
//! **The limit**: a run may plan to use [`MEMORY_SHARE`] of the memory the system reports
//! available (`MemAvailable` of `/proc/meminfo`; [`FALLBACK_AVAILABLE`] where it does not say).
//! The estimates are per stored element, from the sizes of the structures that hold them:
//! [`tessellation_bytes`] for a tessellation, [`sample_weights_bytes`] for the evaluation
//! weights a tessellator keeps per sample, [`FIT_BYTES_PER_FACE`] per fitted face,
//! [`dataset_faces`] for a named data set before it is built.

/// Bytes one tessellation vertex takes (position, normal, K, H, shape tensor: 136 bytes, plus
/// the welding grid's entry), and one output triangle (indices and its patch).
const TESS_BYTES_PER_VERTEX: usize = 160;
const TESS_BYTES_PER_TRIANGLE: usize = 32;

/// Bytes a fitted face takes: mesh and adjacency (~300), three quartic nets (1080), curves and
/// measurement buffers (~600).
pub const FIT_BYTES_PER_FACE: usize = 2000;

/// The share of the available memory a run may plan to use: the rest is left to the system,
/// the page cache and what the estimates do not count (the output's buffers, the allocator's
/// slack).
pub const MEMORY_SHARE: f64 = 0.8;

/// Memory assumed available where the system does not say (`/proc/meminfo` absent).
pub const FALLBACK_AVAILABLE: u64 = 8 << 30;

/// Memory available to this process, bytes: the system's (Linux `MemAvailable`, else
/// [`FALLBACK_AVAILABLE`]), and no more than the room left under the process's address-space
/// limit (`ulimit -v`, [`address_space_room`]), which a failed allocation would otherwise turn
/// into an abort.
pub fn available_memory() -> u64 {
    let system = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| meminfo_field(&text, "MemAvailable:"))
        .unwrap_or(FALLBACK_AVAILABLE);
    system.min(address_space_room().unwrap_or(u64::MAX))
}

/// The field `name` (`MemAvailable:`, `VmSize:`) of a `/proc` status text in kB, as bytes.
fn meminfo_field(text: &str, name: &str) -> Option<u64> {
    text.lines()
        .find(|l| l.starts_with(name))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|kb| kb.parse::<u64>().ok())
        .map(|kb| kb.saturating_mul(1024))
}

/// The soft limit of `Max address space` in a `/proc/self/limits` text, bytes; `None` when
/// unlimited or not said.
fn address_space_limit(limits: &str) -> Option<u64> {
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// Bytes this process may still map under its address-space limit (`RLIMIT_AS`, `ulimit -v`):
/// the limit less the address space already mapped (`VmSize`); `None` without a limit (or
/// where `/proc` does not say). Address space, not resident memory, is what the limit counts:
/// a reservation the allocator has not touched counts too.
pub fn address_space_room() -> Option<u64> {
    let limit = address_space_limit(&std::fs::read_to_string("/proc/self/limits").ok()?)?;
    let used = std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|text| meminfo_field(&text, "VmSize:"))
        .unwrap_or(0);
    Some(limit.saturating_sub(used))
}

/// A plan would need more memory than the run may use ([`check_memory`]).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{what} would need about {:.1} GB, more than this machine has available ({:.1} GB): choose a smaller setting", *needed_bytes as f64 / 1e9, *budget_bytes as f64 / 1e9)]
pub struct TooMuchMemory {
    /// The options responsible (`--resolution 4096 --segments 4`).
    pub what: String,
    /// Estimated need, bytes.
    pub needed_bytes: u128,
    /// What the run may use, bytes.
    pub budget_bytes: u128,
}

/// Refuses a plan needing `bytes` when that exceeds [`MEMORY_SHARE`] of the available memory;
/// `what` names the options responsible, for the message.
pub fn check_memory(what: &str, bytes: u128) -> Result<(), TooMuchMemory> {
    check_memory_within(what, bytes, available_memory())
}

/// [`check_memory`] against `available` bytes instead of what the system says.
pub fn check_memory_within(what: &str, bytes: u128, available: u64) -> Result<(), TooMuchMemory> {
    let budget = (available as f64 * MEMORY_SHARE) as u128;
    if bytes <= budget {
        return Ok(());
    }
    Err(TooMuchMemory {
        what: what.to_string(),
        needed_bytes: bytes,
        budget_bytes: budget,
    })
}

/// Samples of one patch at `s` segments per edge, `(s + 1)(s + 2)/2`, saturating.
fn grid_samples(s: u128) -> u128 {
    (s + 1).saturating_mul(s + 2) / 2
}

/// Estimated bytes of a tessellation of `patches` patches at `s` segments per edge (no
/// overflow: saturates at `u128::MAX`).
pub fn tessellation_bytes(patches: u128, s: usize) -> u128 {
    let (p, s) = (patches, s as u128);
    let per_patch = grid_samples(s)
        .saturating_mul(TESS_BYTES_PER_VERTEX as u128)
        .saturating_add(
            s.saturating_mul(s)
                .saturating_mul(TESS_BYTES_PER_TRIANGLE as u128),
        );
    p.saturating_mul(per_patch)
}

/// Bytes of the evaluation weights of one sample of a patch with `points` stored points
/// ([`crate::beztri::SampleWeights`]: its 72-byte header, six weights per control point, and
/// inside the patch every control point again with its weights in the list of non-zero ones:
/// 48 + 56 bytes per point). A tessellator keeps one per sample of the patch grid.
const WEIGHT_HEADER_BYTES: u128 = 72;
const WEIGHT_BYTES_PER_POINT: u128 = 48 + 56;

/// Estimated bytes of the table of evaluation weights a tessellator keeps for patches of
/// `points` stored points (a quartic net: 15) at `s` segments per edge: one entry per sample,
/// `(s + 1)(s + 2)/2` of them, shared by every patch of the layout. Negligible for a mesh of
/// many patches, but at large `s` on few patches it outweighs the tessellation (quartic at
/// `s = 1024`: 0.86 GB against 0.12 GB).
pub fn sample_weights_bytes(points: usize, s: usize) -> u128 {
    grid_samples(s as u128)
        .saturating_mul(WEIGHT_HEADER_BYTES + WEIGHT_BYTES_PER_POINT * points as u128)
}

/// Faces of a named data set at a resolution (before building it), for the memory check;
/// 0 for a name without a resolution. An upper bound for the capsule (`2n²`; it has `1.5n²`:
/// 384 faces at `n = 16`).
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
    fn estimates_and_refusals() {
        assert_eq!(tessellation_bytes(1, 1), 3 * 160 + 32);
        assert_eq!(tessellation_bytes(2, 8), 2 * (45 * 160 + 64 * 32));
        assert_eq!(tessellation_bytes(u128::MAX, usize::MAX), u128::MAX);
        assert_eq!(sample_weights_bytes(15, 1), 3 * (72 + 15 * 104));
        assert_eq!(dataset_faces("ring", 16), 256);
        assert_eq!(dataset_faces("capsule", 16), 512);
        assert!(check_memory_within("x", 800, 1000).is_ok());
        let e = check_memory_within("--sample 100000", 801, 1000).unwrap_err();
        assert_eq!(e.budget_bytes, 800);
        assert_eq!(
            e.to_string(),
            "--sample 100000 would need about 0.0 GB, more than this machine has available (0.0 GB): choose a smaller setting"
        );
    }

    #[test]
    fn the_address_space_limit_is_read_from_proc_limits() {
        let limits = "Limit                     Soft Limit           Hard Limit           Units     \n\
                      Max cpu time              unlimited            unlimited            seconds   \n\
                      Max address space         2147483648           unlimited            bytes     \n";
        assert_eq!(address_space_limit(limits), Some(2 << 30));
        let unlimited =
            "Max address space         unlimited            unlimited            bytes\n";
        assert_eq!(address_space_limit(unlimited), None);
        assert_eq!(
            address_space_limit("Max open files 1024 1024 files\n"),
            None
        );
        let status = "Name:\ttestbed\nVmPeak:\t  20000 kB\nVmSize:\t   10240 kB\n";
        assert_eq!(meminfo_field(status, "VmSize:"), Some(10240 * 1024));
        assert_eq!(meminfo_field(status, "MemAvailable:"), None);
    }

    #[test]
    fn available_memory_is_within_the_room_under_the_address_space_limit() {
        // Whatever this test process's limit is: never more than the room it leaves.
        if let Some(room) = address_space_room() {
            assert!(available_memory() <= room);
        }
        assert!(available_memory() > 0);
    }
}
