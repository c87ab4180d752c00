//! The status bar: background work (preparing, a folder run), the timeline, the frame's
//! figures, the selected contour's measurements, and the last error or notice.

use crate::app::{Command, Ctx};

/// The bottom panel.
pub(in crate::app) fn bottom_bar(cx: &mut Ctx, ui: &mut egui::Ui) {
    egui::Panel::bottom("status").show(ui, |ui| {
        jobs_ui(cx, ui);
        super::movie::movie_bar(cx, ui);
        if cx.doc.run.is_some() {
            let last = cx.doc.last_frame();
            let mut shown = cx.doc.shown.min(last);
            ui.horizontal(|ui| {
                ui.label("Timeline");
                let w = ui.available_width() - 80.0;
                ui.spacing_mut().slider_width = w.max(100.0);
                if ui
                    .add(egui::Slider::new(&mut shown, 0..=last).text("frame"))
                    .changed()
                {
                    cx.send(Command::SeekFrame(shown));
                }
            });
        }
        ui.horizontal(|ui| figures_ui(cx, ui));
    });
}

/// A run being prepared, a folder being segmented.
fn jobs_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    if cx.jobs.preparing.is_some() {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label("preparing the image (pyramid and local statistics)…")
                .on_hover_text("large images are prepared in the background; Play or Step now and it happens when ready");
        });
    }
    let Some(f) = &cx.jobs.folder else { return };
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
            cx.send(Command::CancelFolder);
        }
    });
}

/// The frame's figures, the selected contour, the error or notice.
fn figures_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let rec = cx.doc.shown_record();
    let (frame, verts, contours, area) = rec.map_or((0, 0, 0, 0.0), |r| {
        (r.index, r.vertices, r.contours, r.area)
    });
    // The contour selected with the Edit tool, measured.
    if let Some(r) = cx
        .view
        .selected_contour
        .and_then(|id| rec.and_then(|rec| rec.rings.iter().find(|r| r.id == id)))
    {
        let a = crate::geometry::signed_area(&r.points).abs();
        let p: f64 = (0..r.points.len())
            .map(|i| r.points[i].dist(r.points[(i + 1) % r.points.len()]))
            .sum();
        // On a frame being corrected, the cell by the track it keeps, as the canvas and
        // the table name it.
        let track = (cx.view.correction_tracks.get(cx.doc))
            .and_then(|t| t.get(&r.id).map(|&(k, _)| k))
            .filter(|_| !r.hole);
        let name = match track {
            Some(k) => format!("track {k}"),
            None => format!("contour {}", r.id),
        };
        ui.label(format!(
            "{name}{}: area {a:.1} px², perimeter {p:.1} px, circularity {:.3}",
            if r.hole { " (hole)" } else { "" },
            4.0 * std::f64::consts::PI * a / (p * p).max(1e-9)
        ));
    }
    let status = cx.status;
    // A movie's frame on screen, then the evolution's frame (which starts again at 0 on
    // each movie frame a hand correction opens).
    let movie = cx.doc.movie.as_ref().map_or(String::new(), |m| {
        format!("  |  movie frame {} of 0–{}", m.frame, m.movie.len() - 1)
    });
    if !movie.is_empty() && rec.is_none() {
        // A tracked frame on screen with no run: its cells are in the Objects table.
        ui.label(format!("{}{movie}", cx.doc.image_name));
    } else {
        let frame = if movie.is_empty() {
            format!("frame {frame}")
        } else {
            format!("evolution frame {frame}")
        };
        ui.label(format!(
            "{}{movie}  |  {frame}  |  {verts} vertices  |  {contours} contours  |  area {area:.0} px²  |  step {:.2} ms  draw {:.2} ms{}",
            cx.doc.image_name,
            status.step_ms,
            status.draw_ms,
            if rec.is_some_and(|r| r.converged) { "  |  converged" } else { "" }
        ));
    }
    if let Some(e) = &status.error {
        ui.colored_label(egui::Color32::from_rgb(255, 90, 90), format!("Error: {e}"));
    } else if let Some(n) = &status.notice {
        ui.label(n);
    }
}
