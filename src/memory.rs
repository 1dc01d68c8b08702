//! Peak resident memory of the process, for the `--report` JSON.
//!
//! On Linux it is `VmHWM` of `/proc/self/status` (the high-water mark of the resident set); where
//! that file is missing, on a Unix, `getrusage(RUSAGE_SELF).ru_maxrss` (kilobytes on Linux and the
//! BSDs, bytes on macOS); elsewhere it is not known (`None`). It is the whole process's peak since
//! it started, not only the reconstruction's (reading the input counts; in a library caller,
//! whatever the caller did before counts too).
use serde::Serialize;

/// The peak resident set size and where it was read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct PeakMemory {
    pub bytes: u64,
    /// `"VmHWM"` (Linux `/proc/self/status`) or `"ru_maxrss"` (`getrusage`).
    pub source: &'static str,
}

/// The process's peak resident memory, if the platform tells it.
impl PeakMemory {
    /// The peak in MiB.
    pub fn mib(&self) -> f64 {
        self.bytes as f64 / (1024.0 * 1024.0)
    }
}

pub fn peak_resident() -> Option<PeakMemory> {
    from_proc_status().or_else(from_getrusage)
}

fn from_proc_status() -> Option<PeakMemory> {
    let text = std::fs::read_to_string("/proc/self/status").ok()?;
    parse_vm_hwm(&text).map(|bytes| PeakMemory {
        bytes,
        source: "VmHWM",
    })
}

/// `VmHWM:   123456 kB` → bytes.
fn parse_vm_hwm(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let mut it = line["VmHWM:".len()..].split_whitespace();
    let n: u64 = it.next()?.parse().ok()?;
    match it.next() {
        Some("kB") | None => n.checked_mul(1024),
        Some(_) => None,
    }
}

#[cfg(unix)]
fn from_getrusage() -> Option<PeakMemory> {
    // SAFETY: getrusage writes into the zeroed struct we own; no other memory is touched.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) } != 0 || u.ru_maxrss <= 0 {
        return None;
    }
    let n = u.ru_maxrss as u64;
    let bytes = if cfg!(target_os = "macos") || cfg!(target_os = "ios") {
        n
    } else {
        n.checked_mul(1024)?
    };
    Some(PeakMemory {
        bytes,
        source: "ru_maxrss",
    })
}

#[cfg(not(unix))]
fn from_getrusage() -> Option<PeakMemory> {
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_vm_hwm() {
        let s = "Name:\tx\nVmPeak:\t  20000 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(parse_vm_hwm(s), Some(1234 * 1024));
        assert_eq!(parse_vm_hwm("VmRSS: 5 kB\n"), None);
        assert_eq!(parse_vm_hwm("VmHWM: x kB\n"), None);
    }

    #[test]
    fn the_peak_covers_what_the_process_holds() {
        let held: Vec<u8> = vec![1; 64 << 20];
        let p = peak_resident();
        if cfg!(unix) {
            let p = p.expect("a Unix reports its peak");
            assert!(p.bytes >= 64 << 20, "{p:?}");
            assert!(p.bytes < 1 << 40, "{p:?}");
        }
        assert_eq!(held.iter().map(|&b| b as usize).sum::<usize>(), 64 << 20);
    }
}
