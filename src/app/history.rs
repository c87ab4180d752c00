//! Undo and redo of the user's actions.
//!
//! Before an action that changes the document (shapes, parameters, the image, a reset)
//! the document is snapshotted, run included: a parameter change or a reset clears the
//! run on screen, and Undo brings it back at the frame it was on. A drag sends one
//! `MoveShape` per frame; consecutive moves of the same shape are one step. Playing,
//! stepping, selecting and exporting are not document changes and are not undone.

use super::{Command, Run, Settings};
use crate::evolution::Shape;
use crate::topology::TopologyEvent;
use std::sync::Arc;

/// The state an undo step restores.
#[derive(Clone)]
pub struct Snapshot {
    pub image: Option<Arc<crate::evolution::Field>>,
    pub image_name: String,
    pub image_path: Option<std::path::PathBuf>,
    pub stack: super::ImageStack,
    pub sample_wrap: bool,
    pub shapes: Vec<Shape>,
    pub selected: Option<usize>,
    pub settings: Settings,
    pub run: Option<Run>,
    pub run_b: Option<Run>,
    pub shown: usize,
    pub log: Vec<(usize, TopologyEvent)>,
}

/// Past and undone snapshots.
#[derive(Default)]
pub struct History {
    past: Vec<Snapshot>,
    future: Vec<Snapshot>,
    /// What the last undo step dragged (a shape, or a contour vertex when true): further
    /// moves of it join that step.
    moving: Option<(u8, usize)>,
}

/// Steps kept: runs can be large.
const DEPTH: usize = 100;

impl History {
    /// Whether `c` changes the document (and so gets an undo step).
    pub fn records(c: &Command) -> bool {
        matches!(
            c,
            Command::OpenImage(_)
                | Command::OpenSession(_)
                | Command::AddShape(_)
                | Command::MoveShape { .. }
                | Command::DeleteShape(_)
                | Command::WrapBorder(_)
                | Command::FindSeeds
                | Command::SetPolarity(_)
                | Command::SetModality(_)
                | Command::SetOpenHoles(_)
                | Command::SetMode(_)
                | Command::SetBroadPhase(_)
                | Command::SetCompare(_)
                | Command::Reset
                | Command::ResetParameters
                | Command::SetPage(_)
                | Command::SetPixelSize(_)
                | Command::SetForces { .. }
                | Command::HandMove { .. }
                | Command::Brush { .. }
                | Command::DeleteContour(_)
        )
    }

    /// Whether `c` starts a new undo step (a change of the document that does not
    /// continue the last step's drag); then the caller pushes the state before it.
    pub fn starts_step(&mut self, c: &Command) -> bool {
        if !Self::records(c) {
            return false;
        }
        // A drag (of a shape, or of a contour vertex) is one step.
        let dragging = match c {
            Command::MoveShape { index, .. } => Some((0, *index)),
            Command::HandMove { vertex, .. } => Some((1, *vertex as usize)),
            // A slider drag is one step too.
            Command::SetForces { .. } => Some((2, 0)),
            Command::SetPixelSize(_) => Some((3, 0)),
            // A brush stroke (one press) is one step.
            Command::Brush { stroke, .. } => Some((4, *stroke as usize)),
            _ => None,
        };
        if dragging.is_some() && self.moving == dragging {
            return false;
        }
        self.moving = dragging;
        true
    }

    /// Pushes the state to return to when the step just started is undone.
    pub fn push(&mut self, before: Snapshot) {
        self.past.push(before);
        if self.past.len() > DEPTH {
            self.past.remove(0);
        }
        self.future.clear();
    }

    /// The state to restore for Undo; `now` is kept for Redo.
    pub fn undo(&mut self, now: Snapshot) -> Option<Snapshot> {
        let s = self.past.pop()?;
        self.future.push(now);
        self.moving = None;
        Some(s)
    }

    /// The state to restore for Redo; `now` is kept for Undo.
    pub fn redo(&mut self, now: Snapshot) -> Option<Snapshot> {
        let s = self.future.pop()?;
        self.past.push(now);
        self.moving = None;
        Some(s)
    }

    /// Whether there is something to undo / redo.
    pub fn can(&self) -> (bool, bool) {
        (!self.past.is_empty(), !self.future.is_empty())
    }
}
