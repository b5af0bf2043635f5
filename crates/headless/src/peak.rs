//! The process's peak resident memory, for `--timing` (Linux: `VmHWM` of `/proc/self/status`).

/// The most resident memory this process has used so far, in bytes; `None` where the system does
/// not say.
pub fn peak_memory() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line
        .trim_start_matches("VmHWM:")
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_peak_grows_with_a_touched_allocation() {
        let Some(before) = super::peak_memory() else {
            return; // not Linux
        };
        let block = vec![1u8; 64 << 20];
        let after = super::peak_memory().unwrap();
        assert!(
            after >= before.max(64 << 20),
            "{before} → {after} ({})",
            block[12345]
        );
    }
}
