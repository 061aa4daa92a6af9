//! The memory the system can still give this process: `MemAvailable` of
//! `/proc/meminfo` (the kernel's estimate of the memory available for new
//! allocations without swapping), read by the memory guard before a model
//! is built ([`crate::memory`]); and [`AddressSpaceLimit`], under which the
//! LDLᵀ's LU fallback allocates ([`crate::linear::fallback`]), so that an
//! allocation past that memory fails instead of the system killing the
//! process. Where `/proc` cannot be read (not Linux, or no such line),
//! `None`, and nothing is refused or limited.

use std::sync::{Mutex, MutexGuard};

/// `MemAvailable` of `/proc/meminfo` in bytes, `None` where it cannot be
/// read.
pub fn available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    mem_available(&text)
}

/// `MemAvailable` (in bytes) of the text of `/proc/meminfo`: a value in
/// `kB` or, without a unit, in bytes.
fn mem_available(meminfo: &str) -> Option<u64> {
    match proc_field(meminfo, "MemAvailable:")? {
        (value, Some("kB")) => value.checked_mul(1024),
        (value, None) => Some(value),
        _ => None,
    }
}

/// The value and unit of the line `name value [unit]` of `/proc` text.
fn proc_field<'t>(text: &'t str, name: &str) -> Option<(u64, Option<&'t str>)> {
    let line = text.lines().find_map(|l| l.strip_prefix(name))?;
    let mut words = line.split_whitespace();
    let value: u64 = words.next()?.parse().ok()?;
    Some((value, words.next()))
}

/// The size of this process's address space (`VmSize` of
/// `/proc/self/status`) in bytes, `None` where it cannot be read.
pub fn address_space() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    kib_field(&text, "VmSize:")
}

/// A field `name value kB` of `/proc` text, in bytes.
fn kib_field(text: &str, name: &str) -> Option<u64> {
    match proc_field(text, name)? {
        (value, Some("kB")) => value.checked_mul(1024),
        _ => None,
    }
}

/// One limit at a time: a second one set while the first is held would be
/// restored out of order.
static LIMITED: Mutex<()> = Mutex::new(());

/// While it lives, this process's address space (`RLIMIT_AS`, soft) is
/// limited to its size when the limit was set plus `extra` bytes, so that
/// an allocation past that fails (`try_reserve`, faer's `OutOfMemory`)
/// instead of succeeding on overcommitted memory that the system then
/// reclaims by killing the process; restored when dropped. A limit already
/// lower is kept. The whole process is limited, every thread: it is held
/// around one allocation-heavy call whose allocations report failure (the
/// LU fallback's numeric factorisation), and at most one is held at a time
/// (later ones wait). Where the size or the limit cannot be read or set
/// (not Linux), it limits nothing.
pub struct AddressSpaceLimit {
    /// The soft limit to restore, `None` when nothing was set.
    previous: Option<u64>,
    _held: MutexGuard<'static, ()>,
}

impl AddressSpaceLimit {
    /// Limits the address space to its present size plus `extra` bytes
    /// (type docs).
    pub fn new(extra: u64) -> AddressSpaceLimit {
        let held = LIMITED.lock().unwrap_or_else(|e| e.into_inner());
        let previous = address_space().and_then(|size| set_soft_limit(size.saturating_add(extra)));
        AddressSpaceLimit {
            previous,
            _held: held,
        }
    }

    /// Whether a limit was set.
    pub fn is_set(&self) -> bool {
        self.previous.is_some()
    }
}

impl Drop for AddressSpaceLimit {
    fn drop(&mut self) {
        if let Some(previous) = self.previous {
            let _ = set_soft(previous);
        }
    }
}

/// Lowers the soft `RLIMIT_AS` to `bytes` (never raising it); the soft
/// limit before, `None` when it was not changed. (`rlim_t` is `u64` on
/// 64-bit Linux, narrower on some other targets: hence the conversions.)
#[cfg(unix)]
#[allow(clippy::useless_conversion)]
fn set_soft_limit(bytes: u64) -> Option<u64> {
    let current = get_limit()?;
    let wanted = libc::rlim_t::try_from(bytes).ok()?;
    if current.rlim_cur != libc::RLIM_INFINITY && current.rlim_cur <= wanted {
        return None;
    }
    set_soft(u64::try_from(wanted).ok()?).ok()?;
    u64::try_from(current.rlim_cur).ok()
}

/// No limit where there is no `setrlimit`.
#[cfg(not(unix))]
fn set_soft_limit(_bytes: u64) -> Option<u64> {
    None
}

/// The present `RLIMIT_AS`.
#[cfg(unix)]
fn get_limit() -> Option<libc::rlimit> {
    let mut current = libc::rlimit {
        rlim_cur: 0,
        rlim_max: 0,
    };
    // SAFETY: getrlimit writes the struct it is given, which lives here.
    (unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut current) } == 0).then_some(current)
}

/// Sets the soft `RLIMIT_AS` (at most the hard one), keeping the hard one.
#[cfg(unix)]
#[allow(clippy::useless_conversion)]
fn set_soft(soft: u64) -> Result<(), ()> {
    let mut limit = get_limit().ok_or(())?;
    limit.rlim_cur = libc::rlim_t::try_from(soft)
        .map_err(|_| ())?
        .min(limit.rlim_max);
    // SAFETY: setrlimit reads a struct that lives here.
    if unsafe { libc::setrlimit(libc::RLIMIT_AS, &limit) } != 0 {
        return Err(());
    }
    Ok(())
}

/// Nothing to restore where there is no `setrlimit`.
#[cfg(not(unix))]
fn set_soft(_soft: u64) -> Result<(), ()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kib_field_is_read_in_bytes() {
        let text = "Name: x\nVmPeak:   200 kB\nVmSize:\t  150 kB\n";
        assert_eq!(kib_field(text, "VmSize:"), Some(150 * 1024));
        assert_eq!(kib_field(text, "VmRSS:"), None);
        assert_eq!(kib_field("VmSize: 5\n", "VmSize:"), None);
    }

    #[test]
    fn mem_available_is_read_in_bytes() {
        let text = "MemTotal:       24000000 kB\nMemFree:  100 kB\nMemAvailable:   22000000 kB\n";
        assert_eq!(mem_available(text), Some(22_000_000 * 1024));
        assert_eq!(mem_available("MemTotal: 5 kB\n"), None);
        assert_eq!(mem_available("MemAvailable: x kB\n"), None);
        assert_eq!(mem_available("MemAvailable: 5 MB\n"), None);
    }
}
