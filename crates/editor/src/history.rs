//! Undo / redo by whole-state snapshots, generic over the snapshot type `S`.
//!
//! The document's snapshot (`crate::document::Snapshot`) is cheap to clone (a graph's values
//! share their payloads behind `Arc`), so each step stores the complete state as it was before
//! the edit: undo restores it exactly, whatever the edit was. Continuous gestures — a slider drag, moving nodes — carry an
//! [`EditKey`]; consecutive edits with the same key are merged into one step until the gesture
//! ends ([`History::end_gesture`], called when the pointer is released).

/// Most steps kept; older ones are dropped.
pub const MAX_STEPS: usize = 200;

/// Identifies a continuous gesture whose edits merge into one undo step.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum EditKey {
    /// Editing one input's literal value (node id, input name).
    Value(String, String),
    /// Moving nodes on the canvas.
    Move,
    /// Dragging a graph mapper's handles (node id).
    Mapper(String),
    /// Moving point handles in the 3D view.
    Points,
    /// Dragging a cone-net's vertex (the Drag net tool): the inputs its solves change.
    NetDrag,
    /// Editing a field of the optimization setup (which one).
    Optimization(String),
}

/// The undo and redo stacks of snapshots `S`.
pub struct History<S> {
    undo: Vec<S>,
    redo: Vec<S>,
    /// Key of the gesture in progress, whose first state is already on the undo stack.
    gesture: Option<EditKey>,
}

impl<S> Default for History<S> {
    fn default() -> Self {
        Self {
            undo: Vec::new(),
            redo: Vec::new(),
            gesture: None,
        }
    }
}

impl<S> History<S> {
    /// Records the state before an edit. With the key of the gesture in progress, nothing is
    /// recorded (the step already holds the state before the gesture). Clears the redo stack.
    pub fn record(&mut self, before: S, key: Option<EditKey>) {
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
    pub fn undo(&mut self, current: S) -> Option<S> {
        let s = self.undo.pop()?;
        self.redo.push(current);
        self.gesture = None;
        Some(s)
    }

    /// Pops the last undone step, pushing `current` for undo.
    pub fn redo(&mut self, current: S) -> Option<S> {
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

    fn snap() -> u32 {
        7
    }

    #[test]
    fn a_gesture_is_one_step() {
        let mut h = History::<u32>::default();
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
    fn undo_and_redo_hand_back_the_recorded_states() {
        let mut h = History::<u32>::default();
        h.record(1, None);
        h.record(2, None);
        assert!(h.can_undo() && !h.can_redo());
        assert_eq!(h.undo(3), Some(2));
        assert_eq!(h.undo(2), Some(1));
        assert_eq!(h.undo(1), None);
        assert!(!h.can_undo() && h.can_redo());
        assert_eq!(h.redo(1), Some(2));
        h.record(2, None);
        assert!(!h.can_redo(), "a new edit clears redo");
    }

    #[test]
    fn the_oldest_steps_are_dropped_past_the_limit() {
        let mut h = History::<usize>::default();
        for k in 0..MAX_STEPS + 5 {
            h.record(k, None);
        }
        assert_eq!(h.undo_len(), MAX_STEPS);
        let mut last = None;
        while let Some(s) = h.undo(0) {
            last = Some(s);
        }
        assert_eq!(last, Some(5), "the first five states are gone");
    }
}
