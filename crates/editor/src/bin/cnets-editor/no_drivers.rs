//! The release build's stand-in for the test kit (`drivers/`, feature `drivers`): no option is a
//! driver's, and nothing runs.

use std::time::Instant;

use cnets_editor::app::EditorApp;

/// No driver options (the release build has none).
pub const HELP: &str = "";

/// No drivers asked for.
#[derive(Default)]
pub struct DriverArgs {}

impl DriverArgs {
    /// Never takes an option.
    pub fn take(
        &mut self,
        _arg: &str,
        _rest: &mut dyn Iterator<Item = String>,
    ) -> anyhow::Result<bool> {
        Ok(false)
    }

    /// No driver runs.
    pub fn any(&self) -> bool {
        false
    }

    /// No driver injects the pointer.
    pub fn injects_pointer(&self) -> bool {
        false
    }

    /// Nothing to start.
    pub fn start(self, _launched: Instant) -> Drivers {
        Drivers
    }
}

/// No drivers running.
pub struct Drivers;

impl Drivers {
    /// Nothing before the frame.
    pub fn before_frame(&mut self, _app: &mut EditorApp) {}

    /// Nothing after the frame.
    pub fn after_frame(&mut self, _app: &mut EditorApp, _ctx: &egui::Context, _ui_ms: f64) {}

    /// The X server's pointer is kept.
    pub fn filter_input(&self, _raw_input: &mut egui::RawInput) {}

    /// Nothing injected.
    pub fn inject(
        &mut self,
        _app: &EditorApp,
        _ctx: &egui::Context,
        _raw_input: &mut egui::RawInput,
    ) {
    }
}
