//! The object table: the regions of the frame on screen with their measurements, linked
//! to the canvas (a click on a row selects the contour there; a contour selected on the
//! canvas is the highlighted row). Rows are measured once per frame recording (the
//! table is drawn every frame; an edit records the frame again).

use super::{Command, Ctx, FrameRecord};
use crate::evolution::measure::{regions_of_rings, Region};
use std::sync::Arc;

/// Measured regions of the last frame recording asked for.
#[derive(Default)]
pub struct ObjectTable {
    stamp: Option<u64>,
    rows: Arc<Vec<Region>>,
    /// The selected contour the table last scrolled to.
    scrolled_to: Option<u32>,
}

impl ObjectTable {
    /// The regions of `rec`, largest first.
    pub fn rows(&mut self, rec: &FrameRecord) -> Arc<Vec<Region>> {
        if self.stamp != Some(rec.stamp) {
            let rings: Vec<(u32, bool, &[crate::geometry::Point])> = rec
                .rings
                .iter()
                .map(|r| (r.id, r.hole, r.points.as_slice()))
                .collect();
            let mut rows = regions_of_rings(&rings);
            rows.sort_by(|a, b| b.area.total_cmp(&a.area));
            self.rows = Arc::new(rows);
            self.stamp = Some(rec.stamp);
        }
        self.rows.clone()
    }

    /// Whether the table should scroll to `selected` (once per new selection: scrolling
    /// every frame would keep the window repainting).
    fn scroll_to(&mut self, selected: Option<u32>) -> bool {
        let new = selected.is_some() && selected != self.scrolled_to;
        self.scrolled_to = selected;
        new
    }
}

/// The table, in a collapsing section.
pub(super) fn objects_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    egui::CollapsingHeader::new("Objects")
        .default_open(true)
        .show(ui, |ui| {
            let Some(rec) = cx.doc.shown_record() else {
                if !tracked_ui(cx, ui) {
                    ui.label("No contours yet: play or step the evolution.");
                }
                return;
            };
            let rows = cx.view.objects.rows(rec);
            let tracks = cx.view.correction_tracks.get(cx.doc);
            let correcting = cx.doc.movie.as_ref().and_then(|m| m.correcting);
            let title = match (&tracks, correcting) {
                (Some(t), Some((f, _))) => {
                    let cells: std::collections::BTreeSet<u32> = t.values().map(|v| v.0).collect();
                    let n = crate::cli::counted(cells.len(), "cell");
                    format!("{n} in movie frame {f}, being corrected")
                }
                _ => format!("{} in frame {}", crate::cli::counted(rows.len(), "object"), rec.index),
            };
            ui.label(title)
                .on_hover_text("regions of the frame on screen: area and perimeter in pixels, circularity 4πA/P² (1 for a disk)");
            let selected = cx.view.selected_contour;
            let scroll = cx.view.objects.scroll_to(selected);
            let mut clicked = None;
            egui::ScrollArea::vertical()
                .id_salt("objects")
                .max_height(220.0)
                .show(ui, |ui| {
                    egui::Grid::new("object table")
                        .striped(true)
                        .num_columns(5)
                        .show(ui, |ui| {
                            clicked = rows_ui(ui, &rows, selected, scroll, tracks.as_deref())
                        });
                });
            if let Some(id) = clicked {
                cx.send(Command::SelectContour(id));
            }
        });
}

/// The header and one row per region; the selection a click asks for. With `tracks`
/// (a tracked frame being corrected) a region is named by the track its cell would
/// keep, as on the canvas; "–" for one too small to be kept.
fn rows_ui(
    ui: &mut egui::Ui,
    rows: &[Region],
    selected: Option<u32>,
    scroll: bool,
    tracks: Option<&super::correct::CellTracks>,
) -> Option<Option<u32>> {
    let first = if tracks.is_some() { "track" } else { "object" };
    for h in [first, "area px²", "perimeter px", "circularity", "holes"] {
        ui.strong(h);
    }
    ui.end_row();
    let mut clicked = None;
    for r in rows {
        let id = r.id.0;
        let on = selected == Some(id);
        let name = match tracks.map(|t| t.get(&id)) {
            None => format!("#{id}"),
            Some(Some((k, _))) => k.to_string(),
            Some(None) => "–".into(),
        };
        let hover = match tracks {
            None => "select this contour on the canvas",
            Some(_) => "select this cell on the canvas: the track it keeps when the correction goes into the tracking (– : smaller than the smallest cell, left out)",
        };
        let cell = ui.selectable_label(on, name).on_hover_text(hover);
        if on && scroll {
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
    clicked
}

/// On a tracked movie frame (no run on screen) the table lists its cells by track, with
/// the parent of each; a click selects the track. Whether there was one.
fn tracked_ui(cx: &mut Ctx, ui: &mut egui::Ui) -> bool {
    let Some(m) = cx.doc.movie.as_ref() else {
        return false;
    };
    let (Some(f), Some(tr)) = (m.tracked_frame(), m.tracking.as_ref()) else {
        return false;
    };
    // A cell seen in two pieces (sisters taken back) is one row per piece, both its track.
    let rings: Vec<(u32, bool, &[crate::geometry::Point])> = f
        .objects
        .iter()
        .enumerate()
        .map(|(k, o)| (k as u32, false, o.ring.as_slice()))
        .collect();
    let rows = regions_of_rings(&rings);
    let cells: std::collections::BTreeSet<u32> = f.objects.iter().map(|o| o.track).collect();
    ui.label(format!(
        "{} in movie frame {}",
        crate::cli::counted(cells.len(), "cell"),
        f.frame
    ))
    .on_hover_text("the tracked cells of the frame on screen: area and perimeter in pixels, circularity 4πA/P² (1 for a disk)");
    let selected = cx.view.selected_track;
    let mut clicked = None;
    egui::ScrollArea::vertical()
        .id_salt("cells")
        .max_height(220.0)
        .show(ui, |ui| {
            egui::Grid::new("cell table")
                .striped(true)
                .num_columns(5)
                .show(ui, |ui| {
                    for h in ["track", "parent", "area px²", "perimeter px", "circularity"] {
                        ui.strong(h);
                    }
                    ui.end_row();
                    for r in &rows {
                        let track = f.objects[r.id.0 as usize].track;
                        let on = selected == Some(track);
                        if ui
                            .selectable_label(on, format!("{track}"))
                            .on_hover_text("select this track (canvas and lineage view)")
                            .clicked()
                        {
                            clicked = Some((!on).then_some(track));
                        }
                        match tr.lineage.get(track).map(|t| t.parent).filter(|&p| p != 0) {
                            Some(p) => ui.label(format!("{p}")),
                            None => ui.label("–"),
                        };
                        ui.label(format!("{:.1}", r.area));
                        ui.label(format!("{:.1}", r.perimeter));
                        ui.label(format!("{:.3}", r.circularity));
                        ui.end_row();
                    }
                });
        });
    if let Some(t) = clicked {
        cx.send(Command::SelectTrack(t));
    }
    true
}
