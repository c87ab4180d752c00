//! Tool bar, side panel (parameters, event log, plots), timeline and status bar. Widgets
//! only send [`Command`]s or edit settings.

use super::{Command, ExportKind, Tool, TopoApp};
use crate::contours::BroadPhaseKind;
use crate::evolution::{Modality, Polarity};
use egui_plot::{Legend, Line, Plot, PlotPoints};

/// The tool bar: files, tools, the image and engine, then playback on its own row.
pub fn top_bar(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            files_ui(app, ui);
            ui.separator();
            tools_ui(app, ui);
            ui.separator();
            image_ui(app, ui);
            engine_ui(app, ui);
        });
        // Playback on its own row, so its buttons stay put whatever the first row holds.
        ui.horizontal_wrapped(|ui| playback_ui(app, ui));
    });
}

/// A button with a tooltip that sends `command` when clicked.
fn command_button(app: &mut TopoApp, ui: &mut egui::Ui, label: &str, tip: &str, command: Command) {
    if ui.button(label).on_hover_text(tip).clicked() {
        app.send(command);
    }
}

/// Open, undo and redo, the Session and Export menus.
fn files_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    command_button(
        app,
        ui,
        "Open…",
        "open a PNG, JPEG or TIFF image (8 or 16 bit)",
        Command::OpenDialog,
    );
    let (can_undo, can_redo) = app.can_undo_redo();
    if ui
        .add_enabled(can_undo, egui::Button::new("Undo"))
        .on_hover_text("undo the last change of shapes, parameters, image or contours (Ctrl+Z); a reset run comes back at its frame")
        .clicked()
    {
        app.send(Command::Undo);
    }
    if ui
        .add_enabled(can_redo, egui::Button::new("Redo"))
        .on_hover_text("redo what Undo undid (Ctrl+Shift+Z or Ctrl+Y)")
        .clicked()
    {
        app.send(Command::Redo);
    }
    ui.menu_button("Session", |ui| {
        if ui
            .button("Save session…")
            .on_hover_text("the image, shapes, parameters and frame, to reopen here or replay headless (topocontour replay)")
            .clicked()
        {
            app.send(Command::SessionDialog(true));
            ui.close();
        }
        if ui
            .button("Open session…")
            .on_hover_text("reopen a saved session: its image, shapes and parameters, run to its frame")
            .clicked()
        {
            app.send(Command::SessionDialog(false));
            ui.close();
        }
        ui.separator();
        if ui
            .button("Apply to folder…")
            .on_hover_text("segment every image of a folder with these shapes (or found seeds) and parameters; JSON and CSV per image and summary.csv go to its topocontour subfolder")
            .clicked()
        {
            app.send(Command::ApplyToFolderDialog);
            ui.close();
        }
    })
    .response
    .on_hover_text("save or reopen the whole state of a segmentation; apply it to a folder");
    ui.menu_button("Export", |ui| {
        for (label, kind, tip) in [
            ("SVG…", ExportKind::Svg, "the contours as vector graphics"),
            (
                "GeoJSON…",
                ExportKind::GeoJson,
                "objects with measurements, as QuPath imports them",
            ),
            (
                "Mask PNG…",
                ExportKind::Mask,
                "white inside the region, black outside",
            ),
            (
                "Measurements CSV…",
                ExportKind::Csv,
                "one row per object: area, perimeter, circularity, centroid",
            ),
            (
                "Label image TIFF…",
                ExportKind::Labels,
                "16-bit: one label per object, holes 0",
            ),
            (
                "ImageJ ROIs (Fiji)…",
                ExportKind::Roi,
                "a ROI set for Fiji's ROI Manager; holes as composite ROIs",
            ),
        ] {
            if ui.button(label).on_hover_text(tip).clicked() {
                app.send(Command::ExportDialog(kind));
                ui.close();
            }
        }
    })
    .response
    .on_hover_text("write the frame on screen (small regions dropped)");
}

/// The canvas tools and the shape commands.
fn tools_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    for (label, tool, tip) in [
        ("Seed", Tool::Seed, "click inside an object for a seed; drag to set its radius"),
        ("Rectangle", Tool::Rect, "drag a rectangle that shrinks onto what it holds"),
        ("Polygon", Tool::Polygon, "click corners; double-click or click the first corner to close"),
        ("Select", Tool::Select, "select, drag or delete seeds and shapes"),
        ("Edit", Tool::Edit, "drag a contour by hand (merges, splits and holes happen exactly); click to select a contour, Delete removes it"),
        ("Brush", Tool::Brush, "push contours with a disc: from inside a region its boundary moves out, from outside it moves in; merges, splits and holes happen exactly"),
    ] {
        if ui
            .selectable_label(app.settings.tool == tool, label)
            .on_hover_text(tip)
            .clicked()
        {
            app.send(Command::SetTool(tool));
        }
    }
    command_button(
        app,
        ui,
        "Wrap border",
        "a rectangle 6 pixels inside the border: shrink-wraps every object",
        Command::WrapBorder(6.0),
    );
    command_button(app, ui, "Find seeds", "one seed per object, found in the image (distance-transform maxima of the local threshold); move, delete or add seeds before you play", Command::FindSeeds);
    let selected = app.selected;
    if ui
        .add_enabled(selected.is_some(), egui::Button::new("Delete shape"))
        .on_hover_text("delete the selected seed or shape (Delete)")
        .clicked()
    {
        if let Some(i) = selected {
            app.send(Command::DeleteShape(i));
        }
    }
}

/// What the image shows: object polarity and the kind of image.
fn image_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    let polarity = [
        ("Dark objects", Polarity::Dark),
        ("Bright objects", Polarity::Bright),
    ];
    let tip =
        "whether the objects are darker or brighter than the background (fluorescence: bright)";
    if let Some(p) = choice_row(ui, app.settings.polarity, &polarity, tip) {
        app.send(Command::SetPolarity(p));
    }
    let modality = app.settings.modality;
    let kinds = [
        Modality::Generic,
        Modality::Fluorescence,
        Modality::PhaseContrast,
        Modality::Brightfield,
    ];
    let text = format!("image: {}", modality.name());
    let tip = "the kind of image: fluorescence finds dim objects beside bright ones; phase contrast treats the bright halo around cells as background";
    if let Some(m) = choice_combo(ui, "modality", text, modality, &kinds, Modality::name, tip) {
        app.send(Command::SetModality(m));
    }
}

/// The engine, and a second one side by side.
fn engine_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    use crate::evolution::Mode;
    let modes = [
        ("Adaptive", Mode::Adaptive),
        ("Preserve", Mode::Preserve),
        ("Implicit", Mode::Implicit),
    ];
    let tip = "engine: adaptive topology; or keep the initial topology (preserve: explicit with a gap; implicit: fast marching with sub-pixel contact lines)";
    if let Some(m) = choice_row(ui, app.settings.mode, &modes, tip) {
        app.send(Command::SetMode(m));
    }
    let compare = app.settings.compare;
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
        app.send(Command::SetCompare(m));
    }
    let mut open = app.settings.open_holes;
    let tip = "adaptive engine: open a hole where a region covers clear background, as a level set would (a wrap finds a ring's hole and parts touching cells); off: holes come only from fronts that meet";
    if ui
        .add_enabled(
            app.settings.mode == Mode::Adaptive,
            egui::Checkbox::new(&mut open, "open holes"),
        )
        .on_hover_text(tip)
        .clicked()
    {
        app.send(Command::SetOpenHoles(open));
    }
}

/// A row of selectable labels, one per option; the option clicked, if it is not `current`.
fn choice_row<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    current: T,
    options: &[(&str, T)],
    tip: &str,
) -> Option<T> {
    let mut chosen = None;
    for &(label, option) in options {
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
fn playback_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    if app.playing {
        command_button(app, ui, "Pause", "pause playback (Space)", Command::Pause);
    } else {
        command_button(
            app,
            ui,
            "Play",
            "evolve frame after frame until the contours settle (Space)",
            Command::Play,
        );
    }
    command_button(
        app,
        ui,
        "Step",
        "one frame: every vertex moves once (Right arrow)",
        Command::Step(1),
    );
    command_button(app, ui, "Step 10", "ten frames", Command::Step(10));
    command_button(
        app,
        ui,
        "Next event",
        "Step until a topology event (key E)",
        Command::StepToEvent,
    );
    command_button(
        app,
        ui,
        "Reset",
        "back to the initialisation (undoable)",
        Command::Reset,
    );
    ui.add(
        egui::Slider::new(&mut app.settings.speed, 1.0..=240.0)
            .logarithmic(true)
            .text("frames/s"),
    )
    .on_hover_text("playback speed");
}

pub fn bottom_bar(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::Panel::bottom("status").show(ui, |ui| {
        if app.preparing.is_some() {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label("preparing the image (pyramid and local statistics)…")
                    .on_hover_text("large images are prepared in the background; Play or Step now and it happens when ready");
            });
        }
        if let Some(f) = &app.folder {
            let done = f.done.load(std::sync::atomic::Ordering::SeqCst);
            let (total, out) = (f.total, f.out.display().to_string());
            ui.horizontal(|ui| {
                ui.add(
                    egui::ProgressBar::new(done as f32 / total.max(1) as f32)
                        .desired_width(320.0)
                        .text(format!("{done} / {total} images")),
                )
                .on_hover_text(format!("outputs go to {out}"));
                if ui
                    .button("Cancel")
                    .on_hover_text("stop after the image in progress (what is done is kept)")
                    .clicked()
                {
                    app.send(Command::CancelFolder);
                }
            });
        }
        if let Some(run) = &app.run {
            let last = (run.history.len() - 1)
                .max(app.run_b.as_ref().map_or(0, |b| b.history.len() - 1));
            let mut shown = app.shown.min(last);
            ui.horizontal(|ui| {
                ui.label("Timeline");
                let w = ui.available_width() - 80.0;
                ui.spacing_mut().slider_width = w.max(100.0);
                if ui.add(egui::Slider::new(&mut shown, 0..=last).text("frame")).changed() {
                    app.send(Command::SeekFrame(shown));
                }
            });
        }
        ui.horizontal(|ui| {
            let rec = app.shown_record();
            let (frame, verts, contours, area) = rec.map_or((0, 0, 0, 0.0), |r| (r.index, r.vertices, r.contours, r.area));
            // The contour selected with the Edit tool, measured.
            if let Some(r) = app
                .selected_contour
                .and_then(|id| rec.and_then(|rec| rec.rings.iter().find(|r| r.id == id)))
            {
                let a = crate::geometry::signed_area(&r.points).abs();
                let p: f64 = (0..r.points.len())
                    .map(|i| r.points[i].dist(r.points[(i + 1) % r.points.len()]))
                    .sum();
                ui.label(format!(
                    "contour {}{}: area {a:.1} px², perimeter {p:.1} px, circularity {:.3}",
                    r.id,
                    if r.hole { " (hole)" } else { "" },
                    4.0 * std::f64::consts::PI * a / (p * p).max(1e-9)
                ));
            }
            ui.label(format!(
                "{}  |  frame {frame}  |  {verts} vertices  |  {contours} contours  |  area {area:.0} px²  |  step {:.2} ms  draw {:.2} ms{}",
                app.image_name,
                app.step_ms,
                app.draw_ms,
                if rec.is_some_and(|r| r.converged) { "  |  converged" } else { "" }
            ));
            if let Some(e) = &app.error {
                ui.colored_label(egui::Color32::from_rgb(255, 90, 90), format!("Error: {e}"));
            } else if let Some(n) = &app.notice {
                ui.label(n);
            }
        });
    });
}

pub fn side_panel(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::Panel::right("side")
        .default_size(330.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.collapsing("Parameters", |ui| {
                    let (mut w, mut step) = (app.settings.weights, app.settings.step);
                    let mut changed = false;
                    for (value, range, label, tip) in [
                        (&mut w.region, 0.0..=2.0, "region", "region: how strongly intensity pulls the contour towards the local decision level (object inside, background outside)"),
                        (&mut w.balloon, 0.0..=1.0, "balloon", "balloon: a constant push outward where the image says object, so seeds grow through faint interiors"),
                        (&mut w.edge, 0.0..=1.0, "edge", "edge: attraction to strong intensity gradients, where boundaries are"),
                        (&mut w.stretch, 0.0..=1.0, "stretch", "stretch: pull of each vertex towards its neighbours' midpoint (shorter, tauter contours)"),
                        (&mut w.bend, 0.0..=0.5, "bend", "bend: smoothing of that pull (rounder contours, fewer spikes)"),
                        (&mut step, 0.1..=1.5, "step (× grid)", "step: the largest move of a vertex per frame, in grid spacings of the pyramid level"),
                    ] {
                        changed |= ui
                            .add(egui::Slider::new(value, range).text(label))
                            .on_hover_text(tip)
                            .changed();
                    }
                    if changed {
                        app.commands.push(Command::SetForces { weights: w, step });
                    }
                    let s = &mut app.settings;
                    ui.add(
                        egui::Slider::new(&mut s.min_area, 0.0..=500.0)
                            .text("min area px² (export)"),
                    )
                    .on_hover_text("regions and holes smaller than this are left out of exports");
                    // Low never passes high: each slider's range ends at the other.
                    let (lo, hi) = s.contrast;
                    ui.add(egui::Slider::new(&mut s.contrast.0, 0.0..=hi).text("contrast low"))
                        .on_hover_text("display only: the darkest shown value (set per image from its percentiles when it opens)");
                    ui.add(egui::Slider::new(&mut s.contrast.1, lo..=1.0).text("contrast high"))
                        .on_hover_text("display only: the brightest shown value");
                    ui.checkbox(&mut s.show_fill, "Fill regions")
                        .on_hover_text("fill the region between contours (holes stay open)");
                    if ui
                        .button("Reset parameters")
                        .on_hover_text("forces, step, minimum area and contrast back to their defaults (undoable; a run goes on with them)")
                        .clicked()
                    {
                        app.commands.push(Command::ResetParameters);
                    }
                    let broad = app.settings.broad_phase;
                    egui::ComboBox::from_label("broad phase")
                        .selected_text(broad.name())
                        .show_ui(ui, |ui| {
                            for k in [BroadPhaseKind::Bins, BroadPhaseKind::Hash] {
                                if ui.selectable_label(broad == k, k.name()).clicked() && broad != k
                                {
                                    app.commands.push(Command::SetBroadPhase(k));
                                }
                            }
                        })
                        .response
                        .on_hover_text(
                            "crossing search: vertex bins or staggered hashing (same contours, different speed)",
                        );
                });
                image_info_ui(app, ui);
                objects_ui(app, ui);
                egui::CollapsingHeader::new("Event log")
                    .default_open(true)
                    .show(ui, |ui| {
                        if app.log.is_empty() {
                            ui.label("No topology events yet.");
                        }
                        let mut seek = None;
                        egui::ScrollArea::vertical()
                            .id_salt("log")
                            .max_height(220.0)
                            .show(ui, |ui| {
                                for (frame, e) in &app.log {
                                    let text = format!("frame {frame}: {}", e.describe());
                                    if ui.selectable_label(app.shown == *frame, text).clicked() {
                                        seek = Some(*frame);
                                    }
                                }
                            });
                        if let Some(f) = seek {
                            app.send(Command::SeekFrame(f));
                        }
                    })
                    .header_response
                    .widget_info(|| {
                        egui::WidgetInfo::labeled(egui::Role::Button, true, "Event log")
                    });
                egui::CollapsingHeader::new("Plots")
                    .default_open(true)
                    .show(ui, |ui| plots_ui(app, ui));
            });
        });
}

fn plots_ui(app: &TopoApp, ui: &mut egui::Ui) {
    let Some(run) = &app.run else {
        ui.label("Plots appear once the evolution runs.");
        return;
    };
    let h = &run.history;
    let series = |f: &dyn Fn(&super::FrameRecord) -> f64| -> PlotPoints {
        h.iter().map(|r| [r.index as f64, f(r)]).collect()
    };
    let area_max = h.iter().map(|r| r.area).fold(1.0, f64::max);
    let energy_max = h.iter().map(|r| r.energy).fold(1.0, f64::max);
    Plot::new("area")
        .height(120.0)
        .legend(Legend::default())
        .show(ui, |p| {
            p.line(Line::new(
                "area (normalised)",
                series(&|r| r.area / area_max),
            ));
            p.line(Line::new(
                "energy (normalised)",
                series(&|r| r.energy / energy_max),
            ));
        });
    Plot::new("counts")
        .height(120.0)
        .legend(Legend::default())
        .show(ui, |p| {
            p.line(Line::new("contours", series(&|r| r.contours as f64)));
            p.line(Line::new(
                "vertices / 100",
                series(&|r| r.vertices as f64 / 100.0),
            ));
        });
}

/// The object table of the frame on screen: one row per region (outer ring with its
/// holes), linked to the canvas — a click on a row selects the contour there, a contour
/// selected on the canvas (Edit tool) is the highlighted row.
fn objects_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Objects")
        .default_open(true)
        .show(ui, |ui| {
            let shown = app.shown;
            let Some(rec) = app
                .run
                .as_ref()
                .and_then(|r| r.history.get(shown.min(r.history.len() - 1)))
            else {
                ui.label("No contours yet: play or step the evolution.");
                return;
            };
            let rows = app.objects.rows(rec);
            ui.label(format!("{} objects in frame {}", rows.len(), rec.index))
                .on_hover_text("regions of the frame on screen: area and perimeter in pixels, circularity 4πA/P² (1 for a disk)");
            let selected = app.selected_contour;
            let mut clicked = None;
            egui::ScrollArea::vertical()
                .id_salt("objects")
                .max_height(220.0)
                .show(ui, |ui| {
                    egui::Grid::new("object table")
                        .striped(true)
                        .num_columns(5)
                        .show(ui, |ui| {
                            for h in ["object", "area px²", "perimeter px", "circularity", "holes"] {
                                ui.strong(h);
                            }
                            ui.end_row();
                            for r in rows.iter() {
                                let id = r.id.0;
                                let on = selected == Some(id);
                                let cell = ui
                                    .selectable_label(on, format!("#{id}"))
                                    .on_hover_text("select this contour on the canvas");
                                if on {
                                    cell.scroll_to_me(None);
                                }
                                if cell.clicked() {
                                    clicked = Some(if on { None } else { Some(id) });
                                }
                                ui.label(format!("{:.1}", r.area));
                                ui.label(format!("{:.1}", r.perimeter));
                                ui.label(format!("{:.3}", r.circularity));
                                ui.label(format!("{}", r.holes.len()));
                                ui.end_row();
                            }
                        });
                });
            if let Some(id) = clicked {
                app.send(Command::SelectContour(id));
            }
        });
}

/// The image: its size, the page of a stack, the pixel size.
fn image_info_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    let Some(image) = app.image.clone() else {
        return;
    };
    egui::CollapsingHeader::new("Image")
        .default_open(app.stack.pages > 1)
        .show(ui, |ui| {
            ui.label(format!(
                "{}: {} × {} pixels",
                app.image_name, image.width, image.height
            ));
            if app.stack.pages > 1 {
                let mut page = app.stack.page + 1;
                let slider = egui::Slider::new(&mut page, 1..=app.stack.pages).text("page");
                if ui
                    .add(slider)
                    .on_hover_text("the page of the stack to segment (shapes stay; the run starts again)")
                    .changed()
                {
                    app.send(Command::SetPage(page - 1));
                }
            }
            ui.horizontal(|ui| {
                let known = app.stack.pixel.clone();
                let mut size = known.as_ref().map_or(0.0, |p| p.size);
                let mut unit = known.as_ref().map_or("µm".to_string(), |p| p.unit.clone());
                let a = ui
                    .add(
                        egui::DragValue::new(&mut size)
                            .range(0.0..=1e6)
                            .speed(0.001)
                            .max_decimals(4)
                            .prefix("pixel size "),
                    )
                    .on_hover_text("side of a pixel (0: unknown); read from the TIFF when it records one; exports add calibrated area and perimeter");
                let b = ui.add(egui::TextEdit::singleline(&mut unit).desired_width(40.0));
                if a.changed() || b.changed() {
                    let pixel = (size > 0.0).then_some(crate::io::PixelSize { size, unit });
                    app.send(Command::SetPixelSize(pixel));
                }
            });
        });
}
