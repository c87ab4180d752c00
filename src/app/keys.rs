//! Keyboard shortcuts and the help window that lists them (F1 or ?).

use super::{Command, Ctx};
use std::path::PathBuf;

/// Every shortcut, as the help window lists it.
pub const SHORTCUTS: [(&str, &str); 15] = [
    ("Space", "play / pause"),
    ("Right arrow", "step one frame"),
    ("Left arrow", "one frame back"),
    ("E", "step to the next topology event"),
    (
        "on a tracked movie",
        "Space plays its frames, the arrows move a frame (one being corrected too), E goes to the next division",
    ),
    ("[ and ]", "brush smaller / larger"),
    (
        "1, 2, 3, 0",
        "Train tool: paint background, object, boundary; erase",
    ),
    ("P", "show or hide the probability map"),
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

/// The shortcuts of this frame, as commands (and view changes).
pub(super) fn keyboard(cx: &mut Ctx, ui: &egui::Ui) {
    if ui.ctx().egui_wants_keyboard_input() {
        return;
    }
    frame_keys(cx, ui);
    edit_keys(cx, ui);
    train_keys(cx, ui);
    let dropped: Vec<PathBuf> = ui.input(|i| {
        i.raw
            .dropped_files
            .iter()
            .map(|f| f.path().to_path_buf())
            .filter(|p| !p.as_os_str().is_empty())
            .collect()
    });
    if let Some(p) = dropped.into_iter().next() {
        cx.send(Command::OpenImage(p));
    }
}

/// Playback, stepping, the view and help.
fn frame_keys(cx: &mut Ctx, ui: &egui::Ui) {
    let (space, right, event) = ui.input(|i| {
        (
            i.key_pressed(egui::Key::Space),
            i.key_pressed(egui::Key::ArrowRight),
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
    frame_view_keys(cx, escape, fit, help);
    if movie_keys(cx, left, right, space, event) {
        return;
    }
    let shown = cx.doc.shown;
    if left && shown > 0 {
        cx.send(Command::SeekFrame(shown - 1));
    }
    if event {
        cx.send(Command::StepToEvent);
    }
    if space {
        cx.send(if cx.view.playing {
            Command::Pause
        } else {
            Command::Play
        });
    }
    if right {
        cx.send(Command::Step(1));
    }
}

/// On a tracked movie the frame keys move through the movie, not the evolution: ←/→ a
/// frame, Space plays or pauses it, E the next division. So too on a frame open for
/// correction (its run is the tracked contours, with no evolution to step): the next
/// frame opens for correction in turn, as the slider does. Whether they did.
fn movie_keys(cx: &mut Ctx, left: bool, right: bool, space: bool, event: bool) -> bool {
    let Some(m) = cx.doc.movie.as_ref() else {
        return false;
    };
    let Some(tr) = m.tracking.as_ref() else {
        return false;
    };
    let t = m.frame;
    let next = tr
        .divisions()
        .find(|d| d.frame > t)
        .map(|d| (d.frame, d.parent));
    if left && t > 0 {
        cx.send(Command::SeekMovieFrame(t - 1));
    }
    if right {
        cx.send(Command::SeekMovieFrame(t + 1));
    }
    if space {
        cx.send(Command::PlayMovie(!cx.view.movie_playing));
    }
    if let Some((frame, parent)) = next.filter(|_| event) {
        cx.send(Command::SeekMovieFrame(frame));
        cx.send(Command::SelectTrack(Some(parent)));
    }
    true
}

/// Escape, fit and help: the same on a still and a movie.
fn frame_view_keys(cx: &mut Ctx, escape: bool, fit: bool, help: bool) {
    if escape {
        if cx.view.show_help {
            cx.view.show_help = false;
        } else {
            cx.view.canvas.cancel_polygon();
        }
    }
    if fit {
        cx.view.canvas.refit();
    }
    if help {
        cx.view.show_help = !cx.view.show_help;
    }
}

/// Undo, redo, delete and the brush size.
fn edit_keys(cx: &mut Ctx, ui: &egui::Ui) {
    // Redo first: Ctrl+Shift+Z also matches Ctrl+Z when Shift is ignored.
    let (redo, undo) = ui.input_mut(|i| {
        let redo = i.consume_key(
            egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
            egui::Key::Z,
        ) || i.consume_key(egui::Modifiers::COMMAND, egui::Key::Y);
        (redo, i.consume_key(egui::Modifiers::COMMAND, egui::Key::Z))
    });
    if redo {
        cx.send(Command::Redo);
    } else if undo {
        cx.send(Command::Undo);
    }
    let (del, smaller, larger) = ui.input(|i| {
        (
            i.key_pressed(egui::Key::Delete),
            i.key_pressed(egui::Key::OpenBracket),
            i.key_pressed(egui::Key::CloseBracket),
        )
    });
    if del {
        if let Some(id) = cx.view.selected_contour {
            cx.send(Command::DeleteContour(id));
        } else if let Some(i) = cx.view.selected.filter(|_| cx.doc.shapes_shown()) {
            cx.send(Command::DeleteShape(i));
        }
    }
    let r = &mut cx.view.prefs.brush_radius;
    if smaller || larger {
        let factor: f64 = if larger { 1.25 } else { 0.8 };
        *r = (*r * factor).clamp(*super::BRUSH_RADIUS.start(), *super::BRUSH_RADIUS.end());
    }
}

/// The Train tool's labels (1–3, 0 erases) and the probability map's switch.
fn train_keys(cx: &mut Ctx, ui: &egui::Ui) {
    use egui::Key;
    let keys = [
        (Key::Num0, 0),
        (Key::Num1, 1),
        (Key::Num2, 2),
        (Key::Num3, 3),
    ];
    let label = ui.input(|i| {
        keys.iter()
            .find(|(k, _)| i.key_pressed(*k))
            .map(|&(_, l)| l)
    });
    if let Some(l) = label.filter(|_| cx.view.prefs.tool == super::Tool::Train) {
        cx.send(Command::SetTrainLabel(l));
    }
    if ui.input(|i| i.key_pressed(Key::P)) {
        cx.send(Command::ShowProbabilities(
            !cx.view.prefs.show_probabilities,
        ));
    }
}

/// The help window, while it is open.
pub(super) fn help_ui(cx: &mut Ctx, ctx: &egui::Context) {
    let mut open = cx.view.show_help;
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
                ui.label("Tools: Seed (click, drag sets the radius), Rectangle, Polygon (click the first point to close), Select (drag moves, Delete removes), Edit (drag a contour vertex: merges, splits and holes happen exactly; click a contour to measure it, Delete removes it), Brush (a disc pushes contours: from inside a region the boundary moves out, from outside it moves in; its radius is set beside the tools, or with [ and ]). Find seeds places one seed per object; Session > Apply to folder… runs every image of a folder.");
            });
    cx.view.show_help = open;
}
