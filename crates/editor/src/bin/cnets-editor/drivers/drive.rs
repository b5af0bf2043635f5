//! `--drive-drag`: a slider drag made of real egui pointer events in the real window (the recovery
//! test kills the process right after it), and the values it prints.

use cnets_editor::app::EditorApp;

/// The values of every `param.number` slider, one `node.value = x` a line (full precision).
pub fn slider_values(app: &EditorApp) -> String {
    let mut lines: Vec<String> = app
        .doc()
        .graph
        .nodes()
        .filter(|(_, n)| n.def.id == "param.number")
        .map(|(_, n)| {
            let v = n.value_of("value").and_then(cnets_engine::Value::as_f64);
            format!("{}.value = {v:?}", n.id)
        })
        .collect();
    lines.sort();
    lines.join("\n")
}

/// `--drive-drag`: a slider drag made of real egui pointer events, injected into the window's
/// raw input (the same path a mouse takes after winit).
pub struct Drive {
    frames: u32,
    /// Where the press happens and how far the drag goes (screen points), once the slider is
    /// drawn.
    from: Option<egui::Pos2>,
    to: egui::Pos2,
    step: u32,
    node: String,
    /// The dragged slider's value before the drag.
    was: Option<f64>,
    /// The values were printed.
    pub reported: bool,
    /// Frames in a row with the evaluation done and its picture drawn.
    settled_frames: u32,
    /// When the release was reported; taken when the autosave of the released values is.
    released_at: Option<std::time::Instant>,
}

/// Moves between the press and the release.
const DRIVE_MOVES: u32 = 12;

impl Drive {
    /// A drive that has not found its slider yet.
    pub fn new() -> Self {
        Drive {
            frames: 0,
            from: None,
            to: egui::Pos2::ZERO,
            step: 0,
            node: String::new(),
            was: None,
            reported: false,
            settled_frames: 0,
            released_at: None,
        }
    }

    /// Finds the slider once the canvas has been framed: the first results in and drawn for a
    /// few frames (they resize the nodes and reframe the canvas; a busy machine may take many
    /// frames to get there).
    pub fn locate(&mut self, app: &EditorApp) {
        if self.from.is_some() {
            return;
        }
        self.frames += 1;
        let settled =
            !app.busy() && app.viewport().handed_version() >= app.viewport().scene_version();
        self.settled_frames = if settled { self.settled_frames + 1 } else { 0 };
        if self.frames < 30 || self.settled_frames < 4 {
            return;
        }
        let Some(id) = first_slider(app) else {
            return;
        };
        if let Some(r) = app.canvas().editor_screen_rect(&id, "value") {
            // On the rail: from a quarter of the way to 85 % (the rail is the left part of the
            // editor; the value box follows it).
            let rail = r.width().min(110.0 * app.canvas().zoom());
            let y = r.center().y;
            self.from = Some(egui::pos2(r.left() + rail * 0.25, y));
            self.to = egui::pos2(r.left() + rail * 0.85, y);
            self.was = app
                .doc()
                .graph
                .node(&id)
                .and_then(|n| n.value_of("value"))
                .and_then(cnets_engine::Value::as_f64);
            self.node = id;
        }
    }

    pub fn inject(&mut self, raw: &mut egui::RawInput) {
        let Some(from) = self.from else {
            return;
        };
        let press = |pos, pressed| egui::Event::PointerButton {
            pos,
            button: egui::PointerButton::Primary,
            pressed,
            modifiers: egui::Modifiers::NONE,
        };
        let t = self.step as f32 / DRIVE_MOVES as f32;
        let at = from + (self.to - from) * t.min(1.0);
        match self.step {
            0 => {
                raw.events.push(egui::Event::PointerMoved(from));
                raw.events.push(press(from, true));
            }
            s if s <= DRIVE_MOVES => raw.events.push(egui::Event::PointerMoved(at)),
            s if s == DRIVE_MOVES + 1 => raw.events.push(press(self.to, false)),
            _ => return,
        }
        self.step += 1;
    }

    /// Whether it still needs frames: until the released values are autosaved.
    pub fn needs_frames(&self) -> bool {
        !self.reported || self.released_at.is_some()
    }

    /// After the release frame: prints what the window shows; then, once autosave has written
    /// the released values, how long after the release (the test kills the process then).
    pub fn report(&mut self, app: &EditorApp) {
        if let Some(at) = self.released_at
            && app.autosaved()
        {
            self.released_at = None;
            println!(
                "drive-drag: autosaved {} ms after the release",
                at.elapsed().as_millis()
            );
            use std::io::Write as _;
            let _ = std::io::stdout().flush();
        }
        if self.reported || self.step <= DRIVE_MOVES + 1 {
            return;
        }
        self.reported = true;
        self.released_at = Some(std::time::Instant::now());
        println!(
            "drive-drag: released {} pid {}",
            self.node,
            std::process::id()
        );
        println!("{}.value was {:?}", self.node, self.was);
        println!("{}", slider_values(app));
        println!("drive-drag: end");
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
    }
}

/// The id of the graph's first number slider (what the drag measurements move).
pub fn first_slider(app: &EditorApp) -> Option<String> {
    app.doc()
        .graph
        .nodes()
        .find(|(_, n)| n.def.id == "param.number")
        .map(|(_, n)| n.id.clone())
}
