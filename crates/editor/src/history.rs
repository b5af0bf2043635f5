//! Undo / redo by whole-graph snapshots.
//!
//! A [`Graph`] clone is cheap (values share their payloads behind `Arc`), so each step stores the
//! complete document as it was before the edit: undo restores it exactly (same canonical file
//! text), whatever the edit was. Continuous gestures — a slider drag, moving nodes — carry an
//! [`EditKey`]; consecutive edits with the same key are merged into one step until the gesture
//! ends ([`History::end_gesture`], called when the pointer is released).

use cnets_engine::Graph;
use cnets_engine::file::GraphMeta;

use crate::document::Level;

/// Most steps kept; older ones are dropped.
pub const MAX_STEPS: usize = 200;

/// A document state.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// The graph being edited (the document's, or a cluster's subgraph opened in place).
    pub graph: Graph,
    /// Its metadata.
    pub meta: GraphMeta,
    /// The clusters opened in place, outermost first (empty at the document's own graph): undo
    /// and redo also restore where the designer was.
    pub stack: Vec<Level>,
}

/// Identifies a continuous gesture whose edits merge into one undo step.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum EditKey {
    /// Editing one input's literal value (node id, input name).
    Value(String, String),
    /// Moving nodes on the canvas.
    Move,
    /// Dragging a graph mapper's handles (node id).
    Mapper(String),
    /// Editing a field of the optimization setup (which one).
    Optimization(String),
}

/// The undo and redo stacks.
#[derive(Default)]
pub struct History {
    undo: Vec<Snapshot>,
    redo: Vec<Snapshot>,
    /// Key of the gesture in progress, whose first state is already on the undo stack.
    gesture: Option<EditKey>,
}

impl History {
    /// Records the state before an edit. With the key of the gesture in progress, nothing is
    /// recorded (the step already holds the state before the gesture). Clears the redo stack.
    pub fn record(&mut self, before: Snapshot, key: Option<EditKey>) {
        self.redo.clear();
        if key.is_some() && key == self.gesture {
            return;
        }
        self.gesture = key;
        self.undo.push(before);
        if self.undo.len() > MAX_STEPS {
            self.undo.remove(0);
        }
    }

    /// Whether a gesture is in progress (its edits are not committed yet: the pointer is still
    /// held, or a text field is being typed in).
    pub fn in_gesture(&self) -> bool {
        self.gesture.is_some()
    }

    /// Ends the gesture in progress: the next edit starts a new step.
    pub fn end_gesture(&mut self) {
        self.gesture = None;
    }

    /// Pops the last step, pushing `current` for redo.
    pub fn undo(&mut self, current: Snapshot) -> Option<Snapshot> {
        let s = self.undo.pop()?;
        self.redo.push(current);
        self.gesture = None;
        Some(s)
    }

    /// Pops the last undone step, pushing `current` for undo.
    pub fn redo(&mut self, current: Snapshot) -> Option<Snapshot> {
        let s = self.redo.pop()?;
        self.undo.push(current);
        self.gesture = None;
        Some(s)
    }

    /// Whether there is a step to undo.
    pub fn can_undo(&self) -> bool {
        !self.undo.is_empty()
    }

    /// Whether there is a step to redo.
    pub fn can_redo(&self) -> bool {
        !self.redo.is_empty()
    }

    /// Number of undo steps.
    pub fn undo_len(&self) -> usize {
        self.undo.len()
    }

    /// Forgets everything (a new document was opened).
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn snap() -> Snapshot {
        Snapshot {
            graph: Graph::new(Arc::new(cnets_engine::Registry::new())),
            meta: GraphMeta::default(),
            stack: Vec::new(),
        }
    }

    #[test]
    fn a_gesture_is_one_step() {
        let mut h = History::default();
        let key = Some(EditKey::Value("n".into(), "value".into()));
        h.record(snap(), key.clone());
        h.record(snap(), key.clone());
        h.record(snap(), key.clone());
        assert_eq!(h.undo_len(), 1);
        h.end_gesture();
        h.record(snap(), key);
        assert_eq!(h.undo_len(), 2);
        h.record(snap(), None);
        h.record(snap(), None);
        assert_eq!(h.undo_len(), 4);
    }

    #[test]
    fn undo_redo_move_between_stacks() {
        let mut h = History::default();
        h.record(snap(), None);
        assert!(h.can_undo() && !h.can_redo());
        assert!(h.undo(snap()).is_some());
        assert!(!h.can_undo() && h.can_redo());
        assert!(h.redo(snap()).is_some());
        assert!(h.undo(snap()).is_some());
        h.record(snap(), None);
        assert!(!h.can_redo(), "a new edit clears redo");
    }
}
