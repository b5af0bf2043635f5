//! `--drive-script NAME [--drive-out DIR]`: plays a scripted design session in the real window —
//! pointer moves, presses, drags, wheel turns and keys injected into the window's raw input (the
//! path a mouse takes after winit) — printing what the editor then holds (`script: key = value`
//! lines) and saving screenshots into DIR. The window tests (`tests/it/window.rs`) run the scripts of
//! [`super::scenarios`] under Xvfb and check the lines.
//!
//! Targets are computed from the editor's state of the previous frame (where the 3D view draws a
//! world point, where the canvas draws a pin), so a script says "drag this handle three grid steps
//! right", not screen coordinates.

use std::path::PathBuf;

use cnets_editor::app::EditorApp;
use egui::{Event, Key, Modifiers, PointerButton, Pos2, RawInput};

/// A screen position computed from the editor's state (`None`: not there yet — the step waits).
pub type Target = Box<dyn Fn(&EditorApp, &egui::Context) -> Option<Pos2>>;

/// One step of a script.
pub enum Step {
    /// Wait this many frames.
    Wait(u32),
    /// Wait until the evaluation is done and the picture drawn.
    Settle,
    /// Press and release a key (with modifiers).
    Key(Key, Modifiers),
    /// Type text (a palette search).
    Text(String),
    /// Move the pointer.
    Move(Target),
    /// Click a button (with modifiers held).
    Click(Target, PointerButton, Modifiers),
    /// Drag with a button from one target to another in several moves (modifiers held).
    Drag(Target, Target, PointerButton, Modifiers),
    /// Press on a target and move by a step each frame until the check holds, then release (a
    /// drag value dragged to a value).
    DragUntil(Target, egui::Vec2, Box<dyn Fn(&EditorApp) -> bool>),
    /// Turn the wheel over a target (points; positive away from you) until the check holds.
    WheelUntil(Target, f32, Box<dyn Fn(&EditorApp) -> bool>),
    /// Print `script: key = value`.
    Print(&'static str, Box<dyn Fn(&EditorApp) -> String>),
    /// Save a screenshot as `DIR/NAME.png`.
    Shot(&'static str),
    /// Print `script: end` and quit (without the unsaved-changes question).
    Quit,
}

/// Moves of a scripted drag between press and release.
const DRAG_MOVES: u32 = 8;
/// How long a step may wait for its target or for the evaluation before the script fails (wall
/// clock: frames come fast in an idle window and slowly on a busy machine).
const PATIENCE: std::time::Duration = std::time::Duration::from_secs(180);

/// A script being played.
pub struct Script {
    steps: Vec<Step>,
    at: usize,
    /// Frames spent in the current step.
    phase: u32,
    /// The last injected pointer position.
    pointer: Pos2,
    /// The modifier keys held, as last told to egui.
    modifiers: Modifiers,
    /// Where a drag started and ends (fixed at its press).
    drag: Option<(Pos2, Pos2)>,
    out: PathBuf,
    shot_requested: bool,
    started: std::time::Instant,
    /// When the current step began.
    step_started: std::time::Instant,
    settled_frames: u32,
    /// Frames since a drag-until's check held (its release goes out in the first).
    released: u32,
}

fn say(key: &str, value: &str) {
    use std::io::Write as _;
    println!("script: {key} = {value}");
    let _ = std::io::stdout().flush();
}

impl Script {
    /// A script of `steps`, saving screenshots into `out`.
    pub fn new(steps: Vec<Step>, out: PathBuf) -> Self {
        Script {
            steps,
            at: 0,
            phase: 0,
            pointer: Pos2::new(1.0, 1.0),
            modifiers: Modifiers::NONE,
            drag: None,
            out,
            shot_requested: false,
            started: std::time::Instant::now(),
            step_started: std::time::Instant::now(),
            settled_frames: 0,
            released: 0,
        }
    }

    fn next(&mut self) {
        self.at += 1;
        self.phase = 0;
        self.drag = None;
        self.step_started = std::time::Instant::now();
    }

    fn fail(&self, why: &str) -> ! {
        say("failed", &format!("step {}: {why}", self.at));
        std::process::exit(3);
    }

    /// Before a frame: the events of the current step.
    pub fn inject(&mut self, app: &EditorApp, ctx: &egui::Context, raw: &mut RawInput) {
        let Some(step) = self.steps.get(self.at) else {
            return;
        };
        let button = |pos, button, pressed, modifiers| Event::PointerButton {
            pos,
            button,
            pressed,
            modifiers,
        };
        let phase = self.phase;
        // The modifier keys this step holds (none unless it says).
        let held = match step {
            Step::Key(_, m) | Step::Click(_, _, m) | Step::Drag(_, _, _, m) => *m,
            _ => Modifiers::NONE,
        };
        if held != self.modifiers {
            raw.events.push(Event::ModifiersChanged(held));
            self.modifiers = held;
        }
        match step {
            Step::Key(key, modifiers) => {
                let pressed = phase == 0;
                raw.events.push(Event::Key {
                    key: *key,
                    physical_key: None,
                    pressed,
                    repeat: false,
                    modifiers: *modifiers,
                });
            }
            Step::Text(text) if phase == 0 => raw.events.push(Event::Text(text.clone())),
            Step::Move(target) => {
                if let Some(p) = target(app, ctx) {
                    self.pointer = p;
                    raw.events.push(Event::PointerMoved(p));
                }
            }
            Step::Click(target, which, modifiers) => match phase {
                0 => {
                    if let Some(p) = target(app, ctx) {
                        self.pointer = p;
                        self.drag = Some((p, p));
                        raw.events.push(Event::PointerMoved(p));
                    }
                }
                1 => {
                    // The target may have moved in the frame since (a result arrived and the
                    // layout changed): press where it is now.
                    if let Some(p) = target(app, ctx)
                        && p != self.pointer
                    {
                        self.pointer = p;
                        raw.events.push(Event::PointerMoved(p));
                    }
                    raw.events
                        .push(button(self.pointer, *which, true, *modifiers))
                }
                2 => raw
                    .events
                    .push(button(self.pointer, *which, false, *modifiers)),
                _ => {}
            },
            Step::Drag(from, to, which, modifiers) => {
                if phase == 0 {
                    if let (Some(a), Some(b)) = (from(app, ctx), to(app, ctx)) {
                        self.drag = Some((a, b));
                        self.pointer = a;
                        raw.events.push(Event::PointerMoved(a));
                    }
                    return;
                }
                let Some((a, b)) = self.drag else { return };
                match phase {
                    1 => raw.events.push(button(a, *which, true, *modifiers)),
                    k if k <= 1 + DRAG_MOVES => {
                        let t = (k - 1) as f32 / DRAG_MOVES as f32;
                        self.pointer = a + (b - a) * t;
                        raw.events.push(Event::PointerMoved(self.pointer));
                    }
                    k if k == 2 + DRAG_MOVES => {
                        raw.events.push(button(b, *which, false, *modifiers))
                    }
                    _ => {}
                }
            }
            Step::DragUntil(target, by, done) => match phase {
                0 => {
                    if let Some(p) = target(app, ctx) {
                        self.pointer = p;
                        self.drag = Some((p, p));
                        raw.events.push(Event::PointerMoved(p));
                    }
                }
                1 => raw.events.push(button(
                    self.pointer,
                    PointerButton::Primary,
                    true,
                    Modifiers::NONE,
                )),
                _ if done(app) => raw.events.push(button(
                    self.pointer,
                    PointerButton::Primary,
                    false,
                    Modifiers::NONE,
                )),
                _ => {
                    self.pointer += *by;
                    raw.events.push(Event::PointerMoved(self.pointer));
                }
            },
            Step::WheelUntil(_, _, done) if done(app) => {
                // Done: end the wheel gesture, so egui drops the turn it still holds back (it
                // spreads large turns over later frames) instead of zooming on.
                raw.events.push(Event::MouseWheel {
                    unit: egui::MouseWheelUnit::Point,
                    delta: egui::Vec2::ZERO,
                    phase: egui::TouchPhase::End,
                    modifiers: Modifiers::NONE,
                });
            }
            Step::WheelUntil(target, points, _) => {
                if let Some(p) = target(app, ctx) {
                    self.pointer = p;
                    raw.events.push(Event::PointerMoved(p));
                    raw.events.push(Event::MouseWheel {
                        unit: egui::MouseWheelUnit::Point,
                        delta: egui::vec2(0.0, *points),
                        phase: egui::TouchPhase::Move,
                        modifiers: Modifiers::NONE,
                    });
                }
            }
            _ => {}
        }
    }

    /// After a frame: advances the script, prints, takes screenshots. Returns whether it ended.
    pub fn after_frame(&mut self, app: &mut EditorApp, ctx: &egui::Context) -> bool {
        ctx.request_repaint();
        cnets_editor::probe::enable(ctx);
        let Some(step) = self.steps.get(self.at) else {
            return true;
        };
        self.phase += 1;
        let phase = self.phase;
        if self.step_started.elapsed() > PATIENCE {
            self.fail(&format!("timed out after {phase} frames"));
        }
        match step {
            Step::Wait(n) => {
                if phase >= *n {
                    self.next();
                }
            }
            Step::Settle => {
                let idle = !app.busy()
                    && app.viewport().handed_version() >= app.viewport().scene_version();
                self.settled_frames = if idle { self.settled_frames + 1 } else { 0 };
                if self.settled_frames >= 4 {
                    self.settled_frames = 0;
                    self.next();
                }
            }
            Step::Key(..) => {
                if phase >= 2 {
                    self.next();
                }
            }
            Step::Text(_) => self.next(),
            Step::Move(target) => {
                if target(app, ctx).is_some() && phase >= 2 {
                    self.next();
                }
            }
            Step::Click(..) => {
                if phase == 1 && self.drag.is_none() {
                    self.phase = 0; // wait for the target (no move was sent)
                } else if phase >= 4 {
                    self.next();
                }
            }
            Step::Drag(..) => {
                if phase == 1 && self.drag.is_none() {
                    self.phase = 0; // wait for the targets
                } else if phase >= 4 + DRAG_MOVES {
                    self.next();
                }
            }
            Step::WheelUntil(_, _, done) => {
                // The frame after the check held sent the gesture's end.
                if done(app) {
                    self.released += 1;
                    if self.released >= 2 {
                        self.released = 0;
                        self.next();
                    }
                } else {
                    self.released = 0;
                }
            }
            Step::DragUntil(_, _, done) => {
                if phase == 1 && self.drag.is_none() {
                    self.phase = 0; // wait for the target
                } else if phase > 2 && done(app) {
                    // The release was injected before this frame.
                    self.released += 1;
                    if self.released >= 2 {
                        self.released = 0;
                        self.next();
                    }
                }
            }
            Step::Print(key, value) => {
                say(key, &value(app));
                self.next();
            }
            Step::Shot(name) => {
                let image = ctx.input(|i| {
                    i.events.iter().find_map(|e| match e {
                        Event::Screenshot { image, .. } => Some(image.clone()),
                        _ => None,
                    })
                });
                if let Some(image) = image {
                    let [w, h] = image.size;
                    let png = cnets_render::Image {
                        width: w as u32,
                        height: h as u32,
                        pixels: image.pixels.iter().flat_map(|c| c.to_array()).collect(),
                    };
                    let path = self.out.join(format!("{name}.png"));
                    if let Err(e) = png.save_png(&path) {
                        self.fail(&format!("cannot save {}: {e}", path.display()));
                    }
                    say(&format!("shot {name}"), &path.display().to_string());
                    self.shot_requested = false;
                    self.next();
                } else if !self.shot_requested && app.viewport().framing().render_scale >= 1.0 {
                    ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(
                        egui::UserData::default(),
                    ));
                    self.shot_requested = true;
                }
            }
            Step::Quit => {
                say(
                    "seconds",
                    &format!("{:.2}", self.started.elapsed().as_secs_f64()),
                );
                println!("script: end");
                app.quit_now();
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                self.next();
                return true;
            }
        }
        false
    }
}
