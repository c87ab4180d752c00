//! Undo and redo: an undo step is the [`Document`] as it was before a change.
//!
//! Before a command that changes the document ([`Command::undo_key`]) the document is
//! kept, run included: a parameter change or a reset clears the run on screen, and Undo
//! brings it back at the frame it was on. A gesture sends one command per frame (a shape
//! dragged, a hand drag or brush stroke, a slider): consecutive commands of the same
//! gesture are one step. Playing, stepping, selecting and exporting are not undone.

use super::command::{Command, UndoKey};
use super::Document;

/// Past and undone documents.
#[derive(Default)]
pub struct History {
    past: Vec<Document>,
    future: Vec<Document>,
    /// The gesture the last step belongs to: further commands of it join that step.
    gesture: Option<UndoKey>,
}

/// Steps kept: runs can be large.
const DEPTH: usize = 100;

impl History {
    /// Whether `c` starts a new undo step (a change of the document that does not
    /// continue the last step's gesture); then the caller pushes the document before it.
    pub fn starts_step(&mut self, c: &Command) -> bool {
        let Some(key) = c.undo_key() else {
            return false;
        };
        let gesture = matches!(key, UndoKey::Gesture(_)).then_some(key);
        if gesture.is_some() && self.gesture == gesture {
            return false;
        }
        self.gesture = gesture;
        true
    }

    /// Pushes the document to return to when the step just started is undone.
    pub fn push(&mut self, before: Document) {
        self.past.push(before);
        if self.past.len() > DEPTH {
            self.past.remove(0);
        }
        self.future.clear();
    }

    /// The document to restore for Undo; `now` is kept for Redo.
    pub fn undo(&mut self, now: Document) -> Option<Document> {
        let s = self.past.pop()?;
        self.future.push(now);
        self.gesture = None;
        Some(s)
    }

    /// The document to restore for Redo; `now` is kept for Undo.
    pub fn redo(&mut self, now: Document) -> Option<Document> {
        let s = self.future.pop()?;
        self.past.push(now);
        self.gesture = None;
        Some(s)
    }

    /// Whether there is something to undo / redo.
    pub fn can(&self) -> (bool, bool) {
        (!self.past.is_empty(), !self.future.is_empty())
    }
}
