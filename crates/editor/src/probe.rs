//! Where named controls were drawn, for scripts that drive the real window with pointer events
//! (`cnets-editor --drive-script`): menus, dialog buttons and palette entries record their screen
//! rectangles under their label — only while a script has switched recording on (a flag in
//! egui's memory), so a designer's editor records nothing. Behind the `probes` cargo feature (on
//! by default, for the binary's scripts and the window tests; the web build turns it off, and
//! then recording does nothing and no rectangle is found).

use egui::{Context, Id, Rect};

fn flag() -> Id {
    Id::new("cnets-probe-on")
}

fn key(label: &str) -> Id {
    Id::new(("cnets-probe", label))
}

/// Switches recording on (scripts only).
pub fn enable(ctx: &Context) {
    ctx.data_mut(|d| d.insert_temp(flag(), true));
}

/// Records where the control `label` was drawn this frame (when recording is on).
#[cfg(not(feature = "probes"))]
pub fn record(_ctx: &Context, _label: &str, _rect: Rect) {}

/// Records where the control `label` was drawn this frame (when recording is on).
#[cfg(feature = "probes")]
pub fn record(ctx: &Context, label: &str, rect: Rect) {
    if ctx.data(|d| d.get_temp::<bool>(flag())).unwrap_or(false) {
        let pass = ctx.cumulative_pass_nr();
        ctx.data_mut(|d| d.insert_temp(key(label), (rect, pass)));
    }
}

/// Where the control `label` was drawn in the last frame (`None` when it was not drawn then: a
/// closed menu's entries are gone).
pub fn rect(ctx: &Context, label: &str) -> Option<Rect> {
    let pass = ctx.cumulative_pass_nr();
    ctx.data(|d| d.get_temp::<(Rect, u64)>(key(label)))
        .filter(|(_, at)| at + 1 >= pass)
        .map(|(r, _)| r)
}
