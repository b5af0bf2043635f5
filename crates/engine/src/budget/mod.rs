//! The memory budget of an evaluation.
//!
//! A graph is a file people share; a few numbers in it (a 10⁷-point series wired into both inputs
//! of `list.table`, two 100 000-point polylines into a construction) can ask for hundreds of
//! gigabytes. Allocation failure aborts a Rust process, so nothing may get that far: every node that
//! can blow up computes the size its outputs will need *before* allocating and checks it against the
//! budget carried by its [`NodeContext`](crate::NodeContext) ([`NodeContext::reserve`]
//! (crate::NodeContext::reserve)), and the evaluator checks the total size of the values it keeps
//! after every node run (`eval::Evaluator`). Both fail with [`BudgetError`]:
//! `needs 240 GB, the limit is 12 GB`.
//!
//! The default limit is half the memory the process really has: the smallest of the machine's
//! memory, its cgroup's limit and its `RLIMIT_AS` / `RLIMIT_DATA` ([`MemoryBudget::machine_default`],
//! [`limits`]); front ends set another with `cnets run/eval --max-memory SIZE` ([`parse_size`]).
//!
//! Values are not all a process allocates: readers, writers and input conversion allocate on the
//! way. A front end that counts the process's allocations ([`allocated`]: the `cnets` binary wraps
//! its allocator in the `cap` crate's counter) registers that count, and the checks then count
//! what is allocated, not only the values held: [`NodeContext::reserve`](crate::NodeContext::reserve)
//! and [`NodeContext::check_memory`](crate::NodeContext::check_memory), which readers, mapped nodes
//! and writers call where their work is split (records, items, rows).

pub mod allocated;
pub mod guard;
pub mod limits;

pub use allocated::{allocated, set_allocated_probe};
pub use guard::Guard;

use std::sync::OnceLock;

/// The memory an evaluation may use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MemoryBudget {
    /// The most bytes the values of one evaluation may take (live values plus a new allocation).
    pub limit: u64,
}

impl Default for MemoryBudget {
    fn default() -> Self {
        Self::machine_default()
    }
}

impl MemoryBudget {
    /// A budget of `limit` bytes.
    pub fn new(limit: u64) -> Self {
        Self { limit }
    }

    /// Half the memory the process really has ([`limits::process_memory_limit`]: the machine,
    /// the cgroup, `RLIMIT_AS`, `RLIMIT_DATA`; 4 GB when none can be read).
    pub fn machine_default() -> Self {
        static DEFAULT: OnceLock<u64> = OnceLock::new();
        Self::new(
            *DEFAULT
                .get_or_init(|| limits::process_memory_limit().map_or(4_000_000_000, |m| m / 2)),
        )
    }

    /// The budget a user asked for (`--max-memory`, Python's `max_memory`), clamped to the
    /// default's bound — half the process's hard limit ([`limits::hard_memory_limit`]) — when it
    /// asks for more: values are not all a process allocates, and past the hard limit an
    /// allocation aborts the process. The machine's memory alone does not clamp (a user may mean
    /// to use most of it).
    pub fn requested(limit: u64) -> Requested {
        Self::requested_under(limit, limits::hard_memory_limit())
    }

    /// [`MemoryBudget::requested`] under a given hard limit (`None`: none).
    pub fn requested_under(limit: u64, hard_limit: Option<u64>) -> Requested {
        match hard_limit.map(|hard| (hard, hard / 2)) {
            Some((hard, bound)) if limit > bound => Requested {
                budget: Self::new(bound),
                warning: Some(format!(
                    "the memory budget asked for ({}) is more than this process can use safely: \
                     it may address {} (ulimit -v or its cgroup), so the budget is {}, half of it, \
                     as the default is",
                    format_bytes(limit),
                    format_bytes(hard),
                    format_bytes(bound)
                )),
            },
            _ => Requested {
                budget: Self::new(limit),
                warning: None,
            },
        }
    }

    /// Checks that `needed` more bytes fit beside `in_use` bytes already live.
    pub fn check(&self, needed: u64, in_use: u64, what: &str) -> Result<(), BudgetError> {
        if needed.saturating_add(in_use) <= self.limit {
            return Ok(());
        }
        Err(BudgetError::TooLarge {
            what: what.to_string(),
            needed,
            in_use,
            limit: self.limit,
        })
    }
}

/// A budget asked for, as granted ([`MemoryBudget::requested`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Requested {
    /// The budget granted.
    pub budget: MemoryBudget,
    /// Why it is less than asked (both figures named), when it is.
    pub warning: Option<String>,
}

/// A request over the memory budget.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum BudgetError {
    /// `needed` bytes do not fit beside `in_use` bytes under `limit`.
    #[error("{what} needs {}, the limit is {}{}", format_bytes(*.needed), format_bytes(*.limit), in_use_note(*.in_use))]
    TooLarge {
        /// What would be allocated (e.g. "a table of 10000000 × 10000000 numbers").
        what: String,
        /// Bytes it needs.
        needed: u64,
        /// Bytes already taken by live values.
        in_use: u64,
        /// The budget.
        limit: u64,
    },
    /// The process has allocated more than the budget while doing `what`.
    #[error("{what} took {}, the limit is {}", format_bytes(*.allocated), format_bytes(*.limit))]
    Exceeded {
        /// What was being done (e.g. "reading 'big.obj'").
        what: String,
        /// Bytes the process had allocated.
        allocated: u64,
        /// The budget.
        limit: u64,
    },
}

fn in_use_note(in_use: u64) -> String {
    if in_use == 0 {
        String::new()
    } else {
        format!(" ({} already held by other values)", format_bytes(in_use))
    }
}

/// Bytes in decimal units for messages: `240 GB`, `12 GB`, `1.5 MB`, `512 bytes`.
pub fn format_bytes(bytes: u64) -> String {
    const UNITS: [(&str, f64); 5] = [
        ("PB", 1e15),
        ("TB", 1e12),
        ("GB", 1e9),
        ("MB", 1e6),
        ("kB", 1e3),
    ];
    let b = bytes as f64;
    for (unit, size) in UNITS {
        if b >= size {
            let x = b / size;
            return if x >= 10.0 || (x - x.round()).abs() < 0.05 {
                format!("{:.0} {unit}", x.round())
            } else {
                format!("{x:.1} {unit}")
            };
        }
    }
    format!("{bytes} bytes")
}

/// Parses a size: a number of bytes, optionally with a unit — `k`/`kB`, `M`/`MB`, `G`/`GB`, `T`/`TB`
/// (decimal) or `KiB`, `MiB`, `GiB`, `TiB` (binary); case-insensitive, e.g. `12G`, `512MB`, `1.5GiB`.
pub fn parse_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let x: f64 = number
        .parse()
        .map_err(|_| format!("'{text}' is not a size (e.g. 12G, 512MB, 1000000)"))?;
    let scale: f64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "m" | "mb" => 1e6,
        "g" | "gb" => 1e9,
        "t" | "tb" => 1e12,
        "kib" => 1024.0,
        "mib" => 1024.0 * 1024.0,
        "gib" => 1024.0 * 1024.0 * 1024.0,
        "tib" => 1024.0 * 1024.0 * 1024.0 * 1024.0,
        other => {
            return Err(format!(
                "unknown size unit '{other}' in '{text}' (use k, M, G, T or KiB, MiB, GiB, TiB)"
            ));
        }
    };
    let bytes = x * scale;
    if !bytes.is_finite() || bytes < 1.0 || bytes > u64::MAX as f64 {
        return Err(format!("'{text}' is not a usable size (at least 1 byte)"));
    }
    Ok(bytes as u64)
}

/// Bytes of `count` items of `item_bytes` each, saturating (a count of 10¹⁴ never wraps around).
pub fn bytes_of(count: u128, item_bytes: usize) -> u64 {
    u64::try_from(count.saturating_mul(item_bytes as u128)).unwrap_or(u64::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_requested_budget_over_half_the_hard_limit_is_clamped_with_both_figures() {
        // `--max-memory 6G` under `ulimit -v 8000000` (8 192 000 000 bytes).
        let r = MemoryBudget::requested_under(6_000_000_000, Some(8_192_000_000));
        assert_eq!(r.budget.limit, 4_096_000_000);
        let w = r.warning.expect("a warning");
        assert!(
            w.contains("6 GB") && w.contains("8.2 GB") && w.contains("4.1 GB"),
            "{w}"
        );
        // Within the bound, or with no hard limit: granted as asked, no warning.
        let r = MemoryBudget::requested_under(4_000_000_000, Some(8_192_000_000));
        assert_eq!((r.budget.limit, r.warning), (4_000_000_000, None));
        let r = MemoryBudget::requested_under(20_000_000_000, None);
        assert_eq!((r.budget.limit, r.warning), (20_000_000_000, None));
    }

    #[test]
    fn sizes_parse_in_decimal_and_binary_units() {
        assert_eq!(parse_size("12G").unwrap(), 12_000_000_000);
        assert_eq!(parse_size("512MB").unwrap(), 512_000_000);
        assert_eq!(parse_size("1.5GiB").unwrap(), 1_610_612_736);
        assert_eq!(parse_size("1000").unwrap(), 1000);
        assert_eq!(parse_size(" 64 kb ").unwrap(), 64_000);
        assert!(parse_size("12X").is_err());
        assert!(parse_size("").is_err());
        assert!(parse_size("0").is_err());
        assert!(parse_size("-5G").is_err());
    }

    #[test]
    fn bytes_read_as_the_issue_writes_them() {
        assert_eq!(format_bytes(240_000_000_000), "240 GB");
        assert_eq!(format_bytes(12_000_000_000), "12 GB");
        assert_eq!(format_bytes(1_500_000), "1.5 MB");
        assert_eq!(format_bytes(512), "512 bytes");
    }

    #[test]
    fn the_check_counts_what_is_already_live() {
        let b = MemoryBudget::new(1000);
        assert!(b.check(1000, 0, "x").is_ok());
        let e = b.check(600, 500, "a list of 600 bytes").unwrap_err();
        assert_eq!(
            e.to_string(),
            "a list of 600 bytes needs 600 bytes, the limit is 1 kB (500 bytes already held by other values)"
        );
        assert!(b.check(u64::MAX, u64::MAX, "x").is_err());
        assert!(MemoryBudget::machine_default().limit >= 1_000_000);
    }
}
