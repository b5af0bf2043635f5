//! Ctrl+C and SIGTERM: the evaluation is cancelled (between nodes and between the items of a
//! mapped node), and within a second the process has removed its own temporary export files and
//! left with exit code 130, so no partial file stays behind (exports are written to a temporary
//! file and renamed, `cnets_engine::files`). The handler comes from the `ctrlc` crate (SIGINT,
//! SIGTERM and SIGHUP with its `termination` feature).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Duration;

/// Exit code of a cancelled command (128 + SIGINT, as shells report it).
pub const CANCELLED: u8 = 130;

/// How long a cancelled evaluation may take to stop by itself before the process leaves anyway.
const GRACE: Duration = Duration::from_millis(800);

static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// The process's cancel flag, set by Ctrl+C or SIGTERM (give it to `NodeContext::cancel`).
pub fn cancel_flag() -> Arc<AtomicBool> {
    FLAG.get_or_init(|| Arc::new(AtomicBool::new(false)))
        .clone()
}

/// Installs the handler (once; a failure to install leaves the default behaviour).
pub fn install() {
    let flag = cancel_flag();
    let _ = ctrlc::set_handler(move || {
        flag.store(true, Ordering::SeqCst);
        std::thread::sleep(GRACE);
        cnets_engine::files::temp::remove_own();
        crate::errln!("error: cancelled");
        std::process::exit(i32::from(CANCELLED));
    });
}
