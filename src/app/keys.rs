//! Keyboard shortcuts and the help window that lists them (F1 or ?).

use super::{Command, TopoApp};
use std::path::PathBuf;

/// Every shortcut, as the help window lists it.
pub const SHORTCUTS: [(&str, &str); 11] = [
    ("Space", "play / pause"),
    ("Right arrow", "step one frame"),
    ("Left arrow", "one frame back"),
    ("E", "step to the next topology event"),
    (
        "Delete",
        "delete the selected shape (or, with Edit, the selected contour)",
    ),
    ("Esc", "cancel the polygon being drawn (or close this help)"),
    ("F", "fit the image to the window"),
    ("Ctrl+Z", "undo"),
    ("Ctrl+Shift+Z, Ctrl+Y", "redo"),
    ("F1, ?", "this help"),
    ("mouse wheel, middle drag", "zoom, pan"),
];

impl TopoApp {
    pub(super) fn keyboard(&mut self, ui: &egui::Ui) {
        if ui.ctx().egui_wants_keyboard_input() {
            return;
        }
        let (space, right, del, event) = ui.input(|i| {
            (
                i.key_pressed(egui::Key::Space),
                i.key_pressed(egui::Key::ArrowRight),
                i.key_pressed(egui::Key::Delete),
                i.key_pressed(egui::Key::E),
            )
        });
        let (left, escape, fit, help) = ui.input(|i| {
            (
                i.key_pressed(egui::Key::ArrowLeft),
                i.key_pressed(egui::Key::Escape),
                i.key_pressed(egui::Key::F),
                i.key_pressed(egui::Key::F1) || i.key_pressed(egui::Key::Questionmark),
            )
        });
        if left && self.shown > 0 {
            self.send(Command::SeekFrame(self.shown - 1));
        }
        if escape {
            if self.show_help {
                self.show_help = false;
            } else {
                self.canvas.cancel_polygon();
            }
        }
        if fit {
            self.canvas.refit();
        }
        if help {
            self.show_help = !self.show_help;
        }
        if event {
            self.send(Command::StepToEvent);
        }
        // Redo first: Ctrl+Shift+Z also matches Ctrl+Z when Shift is ignored.
        let (redo, undo) = ui.input_mut(|i| {
            let redo = i.consume_key(
                egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
                egui::Key::Z,
            ) || i.consume_key(egui::Modifiers::COMMAND, egui::Key::Y);
            (redo, i.consume_key(egui::Modifiers::COMMAND, egui::Key::Z))
        });
        if redo {
            self.send(Command::Redo);
        } else if undo {
            self.send(Command::Undo);
        }
        if space {
            self.send(if self.playing {
                Command::Pause
            } else {
                Command::Play
            });
        }
        if right {
            self.send(Command::Step(1));
        }
        if del {
            if let Some(id) = self.selected_contour {
                self.send(Command::DeleteContour(id));
            } else if let Some(i) = self.selected {
                self.send(Command::DeleteShape(i));
            }
        }
        let dropped: Vec<PathBuf> = ui.input(|i| {
            i.raw
                .dropped_files
                .iter()
                .map(|f| f.path().to_path_buf())
                .filter(|p| !p.as_os_str().is_empty())
                .collect()
        });
        if let Some(p) = dropped.into_iter().next() {
            self.send(Command::OpenImage(p));
        }
    }

    /// The help window, while it is open.
    pub(super) fn help_ui(&mut self, ctx: &egui::Context) {
        let mut open = self.show_help;
        egui::Window::new("Keyboard shortcuts")
            .open(&mut open)
            .collapsible(false)
            .show(ctx, |ui| {
                egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                    for (key, what) in SHORTCUTS {
                        ui.strong(key);
                        ui.label(what);
                        ui.end_row();
                    }
                });
                ui.separator();
                ui.label("Tools: Seed (click, drag sets the radius), Rectangle, Polygon (click the first point to close), Select (drag moves, Delete removes), Edit (drag a contour vertex: merges, splits and holes happen exactly; click a contour to measure it, Delete removes it), Brush (a disc pushes contours: from inside a region the boundary moves out, from outside it moves in). Find seeds places one seed per object; Session > Apply to folder… runs every image of a folder.");
            });
        self.show_help = open;
    }
}
