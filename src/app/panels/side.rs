//! The side panel: parameters, the image, the object table, the event log and plots.

use crate::app::{Command, Ctx, FrameRecord};
use crate::contours::BroadPhaseKind;
use egui_plot::{Legend, Line, Plot, PlotPoints};

/// The right panel.
pub(in crate::app) fn side_panel(cx: &mut Ctx, ui: &mut egui::Ui) {
    egui::Panel::right("side")
        .default_size(330.0)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                ui.collapsing("Parameters", |ui| parameters_ui(cx, ui));
                image_info_ui(cx, ui);
                crate::app::objects::objects_ui(cx, ui);
                egui::CollapsingHeader::new("Event log")
                    .default_open(true)
                    .show(ui, |ui| {
                        super::movie::divisions_ui(cx, ui);
                        event_log_ui(cx, ui);
                    })
                    .header_response
                    .widget_info(|| {
                        egui::WidgetInfo::labeled(egui::Role::Button, true, "Event log")
                    });
                if cx.doc.movie.is_some() {
                    egui::CollapsingHeader::new("Lineage")
                        .default_open(true)
                        .show(ui, |ui| super::movie::lineage_ui(cx, ui));
                }
                egui::CollapsingHeader::new("Plots")
                    .default_open(true)
                    .show(ui, |ui| plots_ui(cx, ui));
            });
        });
}

/// Forces and step, minimum area, contrast, fill, broad phase.
fn parameters_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let s = &cx.doc.settings;
    let (mut w, mut step) = (s.params.weights, s.params.step);
    let mut changed = false;
    for (value, range, label, tip) in [
        (&mut w.region, 0.0..=2.0, "region", "region: how strongly intensity pulls the contour towards the local decision level (object inside, background outside)"),
        (&mut w.balloon, 0.0..=1.0, "balloon", "balloon: a constant push outward where the image says object, so seeds grow through faint interiors"),
        (&mut w.edge, 0.0..=1.0, "edge", "edge: attraction to strong intensity gradients, where boundaries are"),
        (&mut w.stretch, 0.0..=1.0, "stretch", "stretch: pull of each vertex towards its neighbours' midpoint (shorter, tauter contours)"),
        (&mut w.bend, 0.0..=0.5, "bend", "bend: smoothing of that pull (rounder contours, fewer spikes)"),
        (&mut step, 0.1..=1.5, "step (× grid)", "step: the largest move of a vertex per frame, in grid spacings of the pyramid level"),
    ] {
        changed |= ui.add(egui::Slider::new(value, range).text(label)).on_hover_text(tip).changed();
    }
    if changed {
        cx.send(Command::SetForces { weights: w, step });
    }
    let mut min_area = s.params.min_area;
    if ui
        .add(egui::Slider::new(&mut min_area, 0.0..=500.0).text("min area px² (export)"))
        .on_hover_text("regions and holes smaller than this are left out of exports")
        .changed()
    {
        cx.send(Command::SetMinArea(min_area));
    }
    // Low never passes high: each slider's range ends at the other.
    let (mut lo, mut hi) = s.contrast;
    let a = ui
        .add(egui::Slider::new(&mut lo, 0.0..=s.contrast.1).text("contrast low"))
        .on_hover_text("display only: the darkest shown value (set per image from its percentiles when it opens)");
    let b = ui
        .add(egui::Slider::new(&mut hi, s.contrast.0..=1.0).text("contrast high"))
        .on_hover_text("display only: the brightest shown value");
    if a.changed() || b.changed() {
        cx.send(Command::SetContrast((lo, hi)));
    }
    ui.checkbox(&mut cx.view.prefs.show_fill, "Fill regions")
        .on_hover_text("fill the region between contours (holes stay open)");
    if ui
        .button("Reset parameters")
        .on_hover_text("forces, step, minimum area and contrast back to their defaults (undoable; a run goes on with them)")
        .clicked()
    {
        cx.send(Command::ResetParameters);
    }
    let broad = cx.doc.params().broad_phase;
    let mut chosen = None;
    egui::ComboBox::from_label("broad phase")
        .selected_text(broad.name())
        .show_ui(ui, |ui| {
            for k in [BroadPhaseKind::Bins, BroadPhaseKind::Hash] {
                if ui.selectable_label(broad == k, k.name()).clicked() && broad != k {
                    chosen = Some(k);
                }
            }
        })
        .response
        .on_hover_text(
            "crossing search: vertex bins or staggered hashing (same contours, different speed)",
        );
    if let Some(k) = chosen {
        cx.send(Command::SetBroadPhase(k));
    }
}

/// Every topology event of the run, as the evolver logged it; a click shows its frame.
fn event_log_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let Some(run) = &cx.doc.run else {
        ui.label("No topology events yet.");
        return;
    };
    let mut events = run.events().peekable();
    if events.peek().is_none() {
        ui.label("No topology events yet.");
    }
    let shown = cx.doc.shown;
    // A tracked frame open for correction: its run's events are hand edits of that
    // movie frame (the run's own frame 0 is no frame of the movie).
    let correcting = (cx.doc.movie.as_ref()).and_then(|m| m.correcting.map(|(t, _)| t));
    let mut seek = None;
    egui::ScrollArea::vertical()
        .id_salt("log")
        .max_height(220.0)
        .show(ui, |ui| {
            for (frame, e) in events {
                let text = match correcting {
                    Some(t) => format!("movie frame {t}, by hand: {}", e.describe()),
                    None => format!("frame {frame}: {}", e.describe()),
                };
                if ui.selectable_label(shown == frame, text).clicked() {
                    seek = Some(frame);
                }
            }
        });
    if let Some(f) = seek {
        cx.send(Command::SeekFrame(f));
    }
}

/// Area, energy, contours and vertices over the frames.
fn plots_ui(cx: &Ctx, ui: &mut egui::Ui) {
    let Some(run) = &cx.doc.run else {
        ui.label("Plots appear once the evolution runs.");
        return;
    };
    let h = &run.history;
    let series = |f: &dyn Fn(&FrameRecord) -> f64| -> PlotPoints {
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

/// The image: its size, the page of a stack, the pixel size.
fn image_info_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let doc = cx.doc;
    let Some(image) = &doc.image else {
        return;
    };
    egui::CollapsingHeader::new("Image")
        .default_open(doc.stack.pages > 1)
        .show(ui, |ui| {
            ui.label(format!(
                "{}: {} × {} pixels",
                doc.image_name, image.width, image.height
            ));
            if doc.stack.pages > 1 {
                let mut page = doc.stack.page + 1;
                let slider = egui::Slider::new(&mut page, 1..=doc.stack.pages).text("page");
                if ui
                    .add(slider)
                    .on_hover_text(
                        "the page of the stack to segment (shapes stay; the run starts again)",
                    )
                    .changed()
                {
                    cx.send(Command::SetPage(page - 1));
                }
            }
            ui.horizontal(|ui| pixel_size_ui(cx, ui));
        });
}

/// The physical size of a pixel, and its unit.
fn pixel_size_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let known = &cx.doc.stack.pixel;
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
        cx.send(Command::SetPixelSize(pixel));
    }
}
