//! The tool bar (files, tools, the image and engine, playback), the side panel
//! ([`side`]) and the status bar ([`status`]). Widgets read the document and send
//! [`Command`]s; only view preferences (speed, fill, brush radius) are set in place.

mod movie;
mod side;
mod status;
mod train;

pub(super) use movie::question_ui;
pub(super) use side::side_panel;
pub(super) use status::bottom_bar;

use super::{Command, Ctx, Format, Tool};
use crate::evolution::{Modality, Mode, Polarity};

/// The tool bar: files, tools, the image and engine, then playback on its own row.
pub(super) fn top_bar(cx: &mut Ctx, ui: &mut egui::Ui) {
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            files_ui(cx, ui);
            ui.separator();
            tools_ui(cx, ui);
            ui.separator();
            image_ui(cx, ui);
            engine_ui(cx, ui);
        });
        if cx.view.prefs.tool == Tool::Train {
            ui.horizontal_wrapped(|ui| train::train_ui(cx, ui));
        }
        // Playback on its own row, so its buttons stay put whatever the first row holds.
        ui.horizontal_wrapped(|ui| playback_ui(cx, ui));
    });
}

/// A button with a tooltip that sends `command` when clicked.
fn command_button(cx: &mut Ctx, ui: &mut egui::Ui, label: &str, tip: &str, command: Command) {
    if ui.button(label).on_hover_text(tip).clicked() {
        cx.send(command);
    }
}

/// A menu entry with a tooltip that sends `command` and closes the menu.
fn menu_entry(cx: &mut Ctx, ui: &mut egui::Ui, label: &str, tip: &str, command: Command) {
    menu_entry_if(cx, ui, true, label, tip, command);
}

/// A menu entry that can be chosen only when `enabled` (greyed out otherwise).
fn menu_entry_if(
    cx: &mut Ctx,
    ui: &mut egui::Ui,
    enabled: bool,
    label: &str,
    tip: &str,
    command: Command,
) {
    if ui
        .add_enabled(enabled, egui::Button::new(label))
        .on_hover_text(tip)
        .clicked()
    {
        cx.send(command);
        ui.close();
    }
}

/// Open, undo and redo, the Session and Export menus.
fn files_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    command_button(
        cx,
        ui,
        "Open…",
        "open a PNG, JPEG or TIFF image (8 or 16 bit)",
        Command::OpenDialog,
    );
    let (can_undo, can_redo) = cx.can_undo_redo;
    if ui
        .add_enabled(can_undo, egui::Button::new("Undo"))
        .on_hover_text("undo the last change of shapes, parameters, image or contours (Ctrl+Z); a reset run comes back at its frame")
        .clicked()
    {
        cx.send(Command::Undo);
    }
    if ui
        .add_enabled(can_redo, egui::Button::new("Redo"))
        .on_hover_text("redo what Undo undid (Ctrl+Shift+Z or Ctrl+Y)")
        .clicked()
    {
        cx.send(Command::Redo);
    }
    ui.menu_button("Session", |ui| {
        menu_entry(cx, ui, "Save session…", "the image, shapes, parameters, your edits and the frame, to reopen here or replay headless (topocontour replay); of a movie: its tracking and your corrections, to reopen here", Command::SessionDialog(true));
        menu_entry(cx, ui, "Open session…", "reopen a saved session: its image, shapes, parameters and edits, run to its frame; or a movie's tracking as it was saved", Command::SessionDialog(false));
        ui.separator();
        menu_entry(cx, ui, "Apply to folder…", "segment every image of a folder with these shapes (after Find seeds: seeds found in each image) and parameters; JSON and CSV per image and summary.csv go to its topocontour subfolder", Command::ApplyToFolderDialog);
    })
    .response
    .on_hover_text("save or reopen the whole state of a segmentation; apply it to a folder");
    ui.menu_button("Movie", |ui| {
        menu_entry(
            cx,
            ui,
            "Open movie (TIFF)…",
            "a multi-page TIFF, one page per time point (8 or 16 bit)",
            Command::OpenMovieDialog(false),
        );
        menu_entry(
            cx,
            ui,
            "Open movie folder…",
            "a folder of images, frames in natural name order (frame_2 before frame_10)",
            Command::OpenMovieDialog(true),
        );
        ui.separator();
        let tracked = cx
            .doc
            .movie
            .as_ref()
            .and_then(|m| m.tracking.as_ref())
            .is_some_and(|t| !t.frames.is_empty());
        menu_entry_if(
            cx,
            ui,
            tracked,
            "Export tracks (CTC)…",
            "maskTTT.tif per frame and res_track.txt, the Cell Tracking Challenge result layout",
            Command::ExportCtcDialog,
        );
    })
    .response
    .on_hover_text(
        "track cells through a time-lapse: divisions are the contours' exact split events",
    );
    ui.menu_button("Export", |ui| {
        for (label, kind, tip) in [
            ("SVG…", Format::Svg, "the contours as vector graphics"),
            (
                "GeoJSON…",
                Format::Geojson,
                "objects with measurements, as QuPath imports them",
            ),
            (
                "Mask PNG…",
                Format::Mask,
                "white inside the region, black outside",
            ),
            (
                "Measurements CSV…",
                Format::Csv,
                "one row per object: area, perimeter, circularity, centroid",
            ),
            (
                "Label image TIFF…",
                Format::Labels,
                "16-bit: one label per object, numbered as the ids of the CSV, GeoJSON and ROIs; holes 0 (a .png name writes PNG)",
            ),
            (
                "ImageJ ROIs (Fiji)…",
                Format::Roi,
                "a ROI set for Fiji's ROI Manager; holes as composite ROIs",
            ),
            ("Overlay PNG…", Format::Overlay, "the image with the contours drawn"),
            (
                "Contours JSON…",
                Format::Json,
                "contours and topology events, as topocontour segment writes them",
            ),
        ] {
            menu_entry(cx, ui, label, tip, Command::ExportDialog(kind));
        }
    })
    .response
    .on_hover_text("write the frame on screen (small regions dropped)");
}

/// The canvas tools, the brush radius and the shape commands.
fn tools_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let tool = cx.view.prefs.tool;
    for (label, t, tip) in [
        ("Seed", Tool::Seed, "click inside an object for a seed; drag to set its radius"),
        ("Rectangle", Tool::Rect, "drag a rectangle that shrinks onto what it holds"),
        ("Polygon", Tool::Polygon, "click corners; double-click or click the first corner to close"),
        ("Select", Tool::Select, "select, drag or delete seeds and shapes"),
        ("Edit", Tool::Edit, "drag a contour by hand (merges, splits and holes happen exactly); click to select a contour, Delete removes it"),
        ("Brush", Tool::Brush, "push contours with a disc: from inside a region its boundary moves out, from outside it moves in; merges, splits and holes happen exactly"),
        ("Train", Tool::Train, "paint strokes of background, object and boundary (keys 1–3): a pixel classifier learns them and the contours read its probability map"),
    ] {
        if ui.selectable_label(tool == t, label).on_hover_text(tip).clicked() {
            cx.send(Command::SetTool(t));
        }
    }
    if matches!(tool, Tool::Brush | Tool::Train) {
        let r = &mut cx.view.prefs.brush_radius;
        ui.add(
            egui::DragValue::new(r)
                .range(super::BRUSH_RADIUS)
                .speed(0.2)
                .max_decimals(1)
                .prefix("brush radius ")
                .suffix(" px"),
        )
        .on_hover_text("the brush disc's radius in image pixels (keys [ and ])");
    }
    command_button(
        cx,
        ui,
        "Wrap border",
        "a rectangle 6 pixels inside the border: shrink-wraps every object",
        Command::WrapBorder(6.0),
    );
    command_button(cx, ui, "Find seeds", "one seed per object, found in the image (distance-transform maxima of the local threshold); move, delete or add seeds before you play", Command::FindSeeds);
    let selected = cx.view.selected;
    if ui
        .add_enabled(selected.is_some(), egui::Button::new("Delete shape"))
        .on_hover_text("delete the selected seed or shape (Delete)")
        .clicked()
    {
        if let Some(i) = selected {
            cx.send(Command::DeleteShape(i));
        }
    }
}

/// What the image shows: object polarity and the kind of image.
fn image_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let p = cx.doc.params();
    let polarity = [
        (
            "Dark objects",
            Polarity::Dark,
            "objects darker than the background (stained cells in brightfield, phase contrast)",
        ),
        (
            "Bright objects",
            Polarity::Bright,
            "objects brighter than the background (fluorescence)",
        ),
    ];
    if let Some(p) = choice_row(ui, p.polarity, &polarity) {
        cx.send(Command::SetPolarity(p));
    }
    let modality = p.modality;
    let kinds = [
        Modality::Generic,
        Modality::Fluorescence,
        Modality::PhaseContrast,
        Modality::Brightfield,
    ];
    let text = format!("image: {}", modality.name());
    let tip = "the kind of image (set again for each image opened): fluorescence finds dim objects beside bright ones; phase contrast treats the bright halo around cells as background";
    if let Some(m) = choice_combo(ui, "modality", text, modality, &kinds, Modality::name, tip) {
        cx.send(Command::SetModality(m));
    }
}

/// The engine, in what it does for touching objects, and a second one side by side.
fn engine_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let p = cx.doc.params();
    let modes = [
        ("Adaptive", Mode::Adaptive, "touching objects may merge into one, one may split in two, holes open and close: for a wrap around many objects, or when you do not know how many there are"),
        ("Preserve", Mode::Preserve, "each seed stays one object: touching objects stay apart (a thin gap between them), nothing splits or merges — for seeds placed on touching cells"),
        ("Track", Mode::Track, "one object per seed, may divide: touching objects never merge and no hole opens, but an object that pinches in two splits (the engine tracking uses)"),
        ("Implicit", Mode::Implicit, "each seed stays one object, as Preserve, computed on a grid: touching objects share a boundary line with no gap"),
    ];
    if let Some(m) = choice_row(ui, p.mode, &modes) {
        cx.send(Command::SetMode(m));
    }
    let compare = cx.doc.settings.compare;
    let name = |m: Option<Mode>| m.map_or("none", |m| m.name());
    let beside = [
        None,
        Some(Mode::Adaptive),
        Some(Mode::Preserve),
        Some(Mode::Implicit),
    ];
    let text = format!("beside: {}", name(compare));
    let tip = "run a second engine side by side on the same image and shapes";
    if let Some(m) = choice_combo(ui, "compare", text, compare, &beside, name, tip) {
        cx.send(Command::SetCompare(m));
    }
    let mut open = p.open_holes;
    let tip = "adaptive engine: open a hole where a region covers clear background, as a level set would (a wrap finds a ring's hole and parts touching cells); off: holes come only from fronts that meet";
    if ui
        .add_enabled(
            p.mode == Mode::Adaptive,
            egui::Checkbox::new(&mut open, "open holes"),
        )
        .on_hover_text(tip)
        .clicked()
    {
        cx.send(Command::SetOpenHoles(open));
    }
}

/// A row of selectable labels, one per option with its tip; the option clicked, if it is
/// not `current`.
fn choice_row<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    current: T,
    options: &[(&str, T, &str)],
) -> Option<T> {
    let mut chosen = None;
    for &(label, option, tip) in options {
        if ui
            .selectable_label(current == option, label)
            .on_hover_text(tip)
            .clicked()
            && current != option
        {
            chosen = Some(option);
        }
    }
    chosen
}

/// A combo box showing `text` with one entry per option, named by `name`; the option
/// chosen, if it is not `current`.
fn choice_combo<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    id: &str,
    text: String,
    current: T,
    options: &[T],
    name: impl Fn(T) -> &'static str,
    tip: &str,
) -> Option<T> {
    let mut chosen = None;
    egui::ComboBox::from_id_salt(id)
        .selected_text(text)
        .show_ui(ui, |ui| {
            for &option in options {
                if ui
                    .selectable_label(current == option, name(option))
                    .clicked()
                    && current != option
                {
                    chosen = Some(option);
                }
            }
        })
        .response
        .on_hover_text(tip);
    chosen
}

/// Play or pause, step, next event, reset and the playback speed.
fn playback_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    if cx.view.playing {
        command_button(cx, ui, "Pause", "pause playback (Space)", Command::Pause);
    } else {
        command_button(
            cx,
            ui,
            "Play",
            "evolve frame after frame until the contours settle (Space)",
            Command::Play,
        );
    }
    command_button(
        cx,
        ui,
        "Step",
        "one frame: every vertex moves once (Right arrow)",
        Command::Step(1),
    );
    command_button(cx, ui, "Step 10", "ten frames", Command::Step(10));
    command_button(
        cx,
        ui,
        "Next event",
        "Step until a topology event (key E)",
        Command::StepToEvent,
    );
    command_button(
        cx,
        ui,
        "Reset",
        "back to the initialisation (undoable)",
        Command::Reset,
    );
    ui.add(
        egui::Slider::new(&mut cx.view.prefs.speed, 1.0..=240.0)
            .logarithmic(true)
            .text("frames/s"),
    )
    .on_hover_text("playback speed");
}
