//! Hand edits of the frame on screen, through the engine (its topology core makes every
//! merge, split and hole exactly), and Undo/Redo of the document.

use super::{Command, TopoApp};
use crate::contours::ContourId;
use crate::evolution::Evolver;

impl TopoApp {
    /// Makes `change` on the main run at the frame on screen; says when edits made at
    /// later frames wait to be made again.
    fn edit_run(&mut self, change: impl FnOnce(&mut Evolver)) {
        if !self.ensure_run() {
            return;
        }
        let run = self.doc.run.as_mut().expect("ensured");
        let at = self.doc.shown.min(run.last());
        let later = run.history.len() - 1 - at;
        run.edit_at(at, change);
        self.doc.shown = at;
        let waiting = run.waiting_edits();
        if later > 0 && waiting > 0 {
            self.status.notify(format!(
                "edited frame {at}: the {later} frames after it are computed again as you play, and your {waiting} later edits are made again at their frames"
            ));
        }
    }

    /// Hand edits of the frame on screen.
    pub(super) fn hand_edit(&mut self, c: Command) {
        // On a tracked movie frame the edits correct its tracked contours.
        self.begin_correction();
        match c {
            Command::HandMove { vertex, to, .. } => {
                let mut lead = None;
                self.edit_run(|ev| lead = ev.hand_drag(vertex, to).1);
                // The drag goes on with the vertex that leads now.
                self.view.canvas.set_drag_lead(lead);
            }
            Command::Brush {
                from, to, radius, ..
            } => self.edit_run(|ev| {
                ev.brush(from, to, radius);
            }),
            Command::GrabVertex { at, tol } => {
                let shown = self.doc.shown;
                let grabbed = self
                    .doc
                    .run
                    .as_ref()
                    .and_then(|run| run.evolver_at(shown).vertex_near(at, tol));
                self.view.canvas.set_drag_lead(grabbed);
            }
            Command::DeleteContour(id) => {
                self.edit_run(|ev| ev.delete_contour(ContourId(id)));
                self.view.selected_contour = None;
            }
            Command::SelectContour(id) => self.view.selected_contour = id,
            _ => unreachable!("not a hand edit command: {c:?}"),
        }
    }

    /// Undo and redo: the document as it was, and what the view holds of it made to fit.
    pub(super) fn undo_redo(&mut self, c: Command) {
        let now = self.doc.clone();
        let back = match c {
            Command::Undo => self.history.undo(now),
            Command::Redo => self.history.redo(now),
            _ => unreachable!("not an undo or redo command: {c:?}"),
        };
        let Some(doc) = back else {
            let what = if c == Command::Undo { "undo" } else { "redo" };
            self.status.notify(format!("nothing to {what}"));
            return;
        };
        self.doc = doc;
        self.jobs.preparing = None;
        let view = &mut self.view;
        view.playing = false;
        view.selected = view.selected.filter(|&i| i < self.doc.shapes.len());
        view.selected_contour = None;
        view.question = None;
        // What the status bar said was of the document before (tracking taken up again
        // says so after).
        let what = if c == Command::Undo {
            "undone"
        } else {
            "redone"
        };
        let tracked = (self.doc.movie.as_ref()).is_some_and(|m| m.tracking.is_some());
        self.status.notify(if tracked {
            format!("{what}: {}", self.tracking_summary(0, 0))
        } else {
            what.to_string()
        });
        self.after_undo_tracking();
    }
}
