//! The software Vulkan driver (Mesa) complains on stderr when `XDG_RUNTIME_DIR` is missing. Commands
//! that render run themselves again with a private runtime folder set, so a newcomer never sees that
//! noise (setting the variable in-process would need `unsafe`, which the workspace denies).

use std::process::{Command, ExitCode};

/// When `XDG_RUNTIME_DIR` is unset, re-runs this program with a fresh mode-700 folder as
/// `XDG_RUNTIME_DIR` and returns its exit code; `None` when the variable is already set (or the
/// re-run could not be started, in which case the caller just goes on).
pub fn rerun_with_runtime_dir() -> Option<ExitCode> {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|v| !v.is_empty()) {
        return None;
    }
    let dir = std::env::temp_dir().join(format!("cnets-runtime-{}", std::process::id()));
    std::fs::create_dir_all(&dir).ok()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o700)).ok()?;
    }
    let exe = std::env::current_exe().ok()?;
    let status = Command::new(exe)
        .args(std::env::args_os().skip(1))
        .env("XDG_RUNTIME_DIR", &dir)
        .status();
    let _ = std::fs::remove_dir_all(&dir);
    let code = status.ok()?.code().unwrap_or(1);
    Some(ExitCode::from(u8::try_from(code).unwrap_or(1)))
}
