//! Tool bar, side panel (parameters, event log, plots), timeline and status bar. Widgets
//! only send [`Command`]s or edit settings.

use super::{Command, ExportKind, Tool, TopoApp};
use crate::contours::BroadPhaseKind;
use crate::evolution::{Modality, Polarity};
use egui_plot::{Legend, Line, Plot, PlotPoints};

pub fn top_bar(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::Panel::top("toolbar").show(ui, |ui| {
        ui.horizontal_wrapped(|ui| {
            if ui.button("Open…").clicked() {
                app.send(Command::OpenDialog);
            }
            let (can_undo, can_redo) = app.can_undo_redo();
            if ui
                .add_enabled(can_undo, egui::Button::new("Undo"))
                .on_hover_text("undo the last change of shapes, parameters or image (Ctrl+Z); a reset run comes back at its frame")
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
                if ui.button("Open session…").clicked() {
                    app.send(Command::SessionDialog(false));
                    ui.close();
                }
            });
            ui.menu_button("Export", |ui| {
                for (label, kind) in [
                    ("SVG…", ExportKind::Svg),
                    ("GeoJSON…", ExportKind::GeoJson),
                    ("Mask PNG…", ExportKind::Mask),
                    ("Measurements CSV…", ExportKind::Csv),
                    ("Label image TIFF…", ExportKind::Labels),
                    ("ImageJ ROIs (Fiji)…", ExportKind::Roi),
                ] {
                    if ui.button(label).clicked() {
                        app.send(Command::ExportDialog(kind));
                        ui.close();
                    }
                }
            });
            ui.separator();
            for (label, tool) in [
                ("Seed", Tool::Seed),
                ("Rectangle", Tool::Rect),
                ("Polygon", Tool::Polygon),
                ("Select", Tool::Select),
                ("Edit", Tool::Edit),
            ] {
                if ui
                    .selectable_label(app.settings.tool == tool, label)
                    .clicked()
                {
                    app.send(Command::SetTool(tool));
                }
            }
            if ui.button("Wrap border").clicked() {
                app.send(Command::WrapBorder(6.0));
            }
            if ui
                .button("Find seeds")
                .on_hover_text("one seed per object, found in the image (distance-transform maxima of the local threshold); move, delete or add seeds before you play")
                .clicked()
            {
                app.send(Command::FindSeeds);
            }
            let selected = app.selected;
            if ui
                .add_enabled(selected.is_some(), egui::Button::new("Delete shape"))
                .clicked()
            {
                if let Some(i) = selected {
                    app.send(Command::DeleteShape(i));
                }
            }
            ui.separator();
            let polarity = app.settings.polarity;
            for (label, p) in [
                ("Dark objects", Polarity::Dark),
                ("Bright objects", Polarity::Bright),
            ] {
                if ui.selectable_label(polarity == p, label).clicked() && polarity != p {
                    app.send(Command::SetPolarity(p));
                }
            }
            let modality = app.settings.modality;
            egui::ComboBox::from_id_salt("modality")
                .selected_text(format!("image: {}", modality.name()))
                .show_ui(ui, |ui| {
                    for m in [
                        Modality::Generic,
                        Modality::Fluorescence,
                        Modality::PhaseContrast,
                        Modality::Brightfield,
                    ] {
                        if ui.selectable_label(modality == m, m.name()).clicked() && modality != m {
                            app.send(Command::SetModality(m));
                        }
                    }
                })
                .response
                .on_hover_text("the kind of image: fluorescence finds dim objects beside bright ones; phase contrast treats the bright halo around cells as background");
            let mode = app.settings.mode;
            for (label, m) in [
                ("Adaptive", crate::evolution::Mode::Adaptive),
                ("Preserve", crate::evolution::Mode::Preserve),
                ("Implicit", crate::evolution::Mode::Implicit),
            ] {
                if ui
                    .selectable_label(mode == m, label)
                    .on_hover_text("engine: adaptive topology; or keep the initial topology (preserve: explicit with a gap; implicit: fast marching with sub-pixel contact lines)")
                    .clicked()
                    && mode != m
                {
                    app.send(Command::SetMode(m));
                }
            }
            let compare = app.settings.compare;
            let name = |m: Option<crate::evolution::Mode>| m.map_or("none", |m| m.name());
            egui::ComboBox::from_id_salt("compare")
                .selected_text(format!("beside: {}", name(compare)))
                .show_ui(ui, |ui| {
                    for m in [
                        None,
                        Some(crate::evolution::Mode::Adaptive),
                        Some(crate::evolution::Mode::Preserve),
                        Some(crate::evolution::Mode::Implicit),
                    ] {
                        if ui.selectable_label(compare == m, name(m)).clicked() && compare != m {
                            app.send(Command::SetCompare(m));
                        }
                    }
                })
                .response
                .on_hover_text("run a second engine side by side on the same image and shapes");
        });
        // Playback on its own row, so its buttons stay put whatever the first row holds.
        ui.horizontal_wrapped(|ui| {
            if app.playing {
                if ui.button("Pause").clicked() {
                    app.send(Command::Pause);
                }
            } else if ui.button("Play").clicked() {
                app.send(Command::Play);
            }
            if ui.button("Step").clicked() {
                app.send(Command::Step(1));
            }
            if ui.button("Step 10").clicked() {
                app.send(Command::Step(10));
            }
            if ui
                .button("Next event")
                .on_hover_text("Step until a topology event (key E)")
                .clicked()
            {
                app.send(Command::StepToEvent);
            }
            if ui.button("Reset").clicked() {
                app.send(Command::Reset);
            }
            ui.add(
                egui::Slider::new(&mut app.settings.speed, 1.0..=240.0)
                    .logarithmic(true)
                    .text("frames/s"),
            );
        });
    });
}

pub fn bottom_bar(app: &mut TopoApp, ui: &mut egui::Ui) {
    egui::Panel::bottom("status").show(ui, |ui| {
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
                    let s = &mut app.settings;
                    let mut changed = false;
                    let w = &mut s.weights;
                    for (value, range, label) in [
                        (&mut w.region, 0.0..=2.0, "region"),
                        (&mut w.balloon, 0.0..=1.0, "balloon"),
                        (&mut w.edge, 0.0..=1.0, "edge"),
                        (&mut w.stretch, 0.0..=1.0, "stretch"),
                        (&mut w.bend, 0.0..=0.5, "bend"),
                        (&mut s.step, 0.1..=1.5, "step (× grid)"),
                    ] {
                        changed |= ui.add(egui::Slider::new(value, range).text(label)).changed();
                    }
                    ui.add(
                        egui::Slider::new(&mut s.min_area, 0.0..=500.0)
                            .text("min area px² (export)"),
                    );
                    // Low never passes high: each slider's range ends at the other.
                    let (lo, hi) = s.contrast;
                    ui.add(egui::Slider::new(&mut s.contrast.0, 0.0..=hi).text("contrast low"))
                        .on_hover_text("display only: the darkest shown value (set per image from its percentiles when it opens)");
                    ui.add(egui::Slider::new(&mut s.contrast.1, lo..=1.0).text("contrast high"))
                        .on_hover_text("display only: the brightest shown value");
                    ui.checkbox(&mut s.show_fill, "Fill regions");
                    if ui.button("Reset parameters").clicked() {
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
                    if changed {
                        app.commands.push(Command::Reset);
                    }
                });
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
