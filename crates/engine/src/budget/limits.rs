//! The memory the process really has: the smallest of the machine's memory, its cgroup's limit
//! (v2 `memory.max` of its group and every parent, v1 `memory.limit_in_bytes`) and its `RLIMIT_AS`
//! and `RLIMIT_DATA`. A container, a batch job or `ulimit -v` gives less than the machine has; a
//! default budget of half the machine would then run into the limit and abort.

use std::path::Path;

/// Limits at or above this many bytes mean "no limit" (cgroup v1 writes 2⁶³ rounded to a page).
const UNLIMITED: u64 = 1 << 62;

/// The smallest memory limit the process runs under, in bytes (`None` when none can be read).
pub fn process_memory_limit() -> Option<u64> {
    [
        machine_memory(),
        cgroup_limit(Path::new("/proc/self/cgroup"), Path::new("/sys/fs/cgroup")),
    ]
    .into_iter()
    .flatten()
    .chain(resource_limits())
    .min()
}

/// The smallest *hard* limit the process runs under, in bytes: its cgroup's limit and its
/// `RLIMIT_AS` / `RLIMIT_DATA`, past which an allocation fails and a Rust process aborts (`None`
/// when none is set). The machine's memory is not one: past it the system swaps or overcommits.
pub fn hard_memory_limit() -> Option<u64> {
    cgroup_limit(Path::new("/proc/self/cgroup"), Path::new("/sys/fs/cgroup"))
        .into_iter()
        .chain(resource_limits())
        .min()
}

/// The machine's physical memory in bytes (Linux: `MemTotal` of `/proc/meminfo`).
pub fn machine_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    parse_meminfo(&text)
}

/// `MemTotal` of a `/proc/meminfo` text, in bytes.
pub fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// A cgroup limit file's value (`max`, or a number of bytes); `None` for no limit.
pub fn parse_limit(text: &str) -> Option<u64> {
    let n: u64 = text.trim().parse().ok()?;
    (n < UNLIMITED).then_some(n)
}

/// The smallest memory limit of the cgroups named in `proc_cgroup` (the text of
/// `/proc/self/cgroup`), looked up under the cgroup mount `root`: v2 (`0::/path`) `memory.max` of
/// the group and each parent; v1 (`N:memory:/path`) `memory/…/memory.limit_in_bytes`, the group's
/// and the mount's own (inside a container the path is often the host's).
pub fn cgroup_limit(proc_cgroup: &Path, root: &Path) -> Option<u64> {
    let text = std::fs::read_to_string(proc_cgroup).ok()?;
    let read = |p: &Path| {
        std::fs::read_to_string(p)
            .ok()
            .and_then(|t| parse_limit(&t))
    };
    let mut limits = Vec::new();
    for line in text.lines() {
        let mut fields = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) =
            (fields.next(), fields.next(), fields.next())
        else {
            continue;
        };
        let path = path.trim_start_matches('/');
        if id == "0" && controllers.is_empty() {
            // v2: the group and every parent up to the mount.
            let mut dir = root.join(path);
            loop {
                limits.extend(read(&dir.join("memory.max")));
                if dir == root || !dir.pop() {
                    break;
                }
            }
        } else if controllers.split(',').any(|c| c == "memory") {
            let mount = root.join("memory");
            limits.extend(read(&mount.join(path).join("memory.limit_in_bytes")));
            limits.extend(read(&mount.join("memory.limit_in_bytes")));
        }
    }
    limits.into_iter().min()
}

/// The soft `RLIMIT_AS` and `RLIMIT_DATA` that are set, in bytes.
#[cfg(unix)]
fn resource_limits() -> Vec<u64> {
    use rustix::process::{Resource, getrlimit};
    [Resource::As, Resource::Data]
        .into_iter()
        .filter_map(|r| getrlimit(r).current)
        .filter(|&n| n < UNLIMITED)
        .collect()
}

#[cfg(not(unix))]
fn resource_limits() -> Vec<u64> {
    Vec::new()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limit_files_read_max_and_huge_values_as_no_limit() {
        assert_eq!(parse_limit("max\n"), None);
        assert_eq!(parse_limit("9223372036854771712\n"), None);
        assert_eq!(parse_limit("2147483648\n"), Some(2_147_483_648));
        assert_eq!(
            parse_meminfo("MemTotal:       24000000 kB\nMemFree: 1 kB\n"),
            Some(24_576_000_000)
        );
    }

    #[test]
    fn cgroup_limits_are_the_smallest_of_the_group_and_its_parents() {
        let root = std::env::temp_dir().join(format!("cnets-cgroup-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&root);
        let group = root.join("batch/job7");
        std::fs::create_dir_all(&group).unwrap();
        std::fs::write(root.join("batch/memory.max"), "3000000000\n").unwrap();
        std::fs::write(group.join("memory.max"), "max\n").unwrap();
        let proc = root.join("cgroup");
        std::fs::write(&proc, "0::/batch/job7\n").unwrap();
        assert_eq!(cgroup_limit(&proc, &root), Some(3_000_000_000));
        // v1: the group's limit, and the mount's own.
        let v1 = root.join("memory/docker/abc");
        std::fs::create_dir_all(&v1).unwrap();
        std::fs::write(v1.join("memory.limit_in_bytes"), "1000000000\n").unwrap();
        std::fs::write(
            root.join("memory/memory.limit_in_bytes"),
            "9223372036854771712\n",
        )
        .unwrap();
        std::fs::write(&proc, "4:memory:/docker/abc\n1:cpu:/\n").unwrap();
        assert_eq!(cgroup_limit(&proc, &root), Some(1_000_000_000));
        std::fs::write(&proc, "4:memory:/elsewhere\n").unwrap();
        assert_eq!(cgroup_limit(&proc, &root), None);
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn the_process_limit_is_at_most_the_machine() {
        let limit = process_memory_limit().expect("Linux reports its memory");
        assert!(limit <= machine_memory().unwrap());
    }
}
