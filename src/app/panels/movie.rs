//! The movie's widgets: the frame slider (apart from the evolution's timeline), Track
//! with its progress and Cancel, the divisions in the event log, and the lineage view
//! (one row per track over the frames, a division a fork from the parent's row to its
//! children's), linked to the canvas: a click selects the track and shows that frame.

use crate::app::{Command, Ctx};
use crate::track::{Lineage, Track};
use egui::{Color32, Pos2, Rect, Sense, Stroke, Vec2};

/// The movie's row in the status bar: frame slider, Track or Cancel with progress, export.
pub(in crate::app) fn movie_bar(cx: &mut Ctx, ui: &mut egui::Ui) {
    let Some(m) = &cx.doc.movie else { return };
    let (frames, shown) = (m.movie.len(), m.frame);
    ui.horizontal(|ui| {
        ui.label("Movie");
        let playing = cx.view.movie_playing;
        let (icon, tip) = if playing {
            ("Pause movie", "pause the movie (Space on a tracked movie)")
        } else {
            ("Play movie", "play the movie's frames, five a second (Space on a tracked movie)")
        };
        if ui.button(icon).on_hover_text(tip).clicked() {
            cx.send(Command::PlayMovie(!playing));
        }
        let mut t = shown;
        let w = ui.available_width() - 450.0;
        ui.spacing_mut().slider_width = w.max(120.0);
        if ui
            .add(egui::Slider::new(&mut t, 0..=frames - 1).text("movie frame"))
            .on_hover_text("the frame of the movie on screen (the evolution's timeline is below)")
            .changed()
        {
            cx.send(Command::SeekMovieFrame(t));
        }
        match &cx.jobs.track {
            Some(job) => {
                ui.add(
                    egui::ProgressBar::new(job.done as f32 / job.total.max(1) as f32)
                        .desired_width(140.0)
                        .text(format!("{} / {} frames", job.done, job.total)),
                );
                if ui
                    .button("Cancel tracking")
                    .on_hover_text("stop after the frame in progress (the frames tracked are kept)")
                    .clicked()
                {
                    cx.send(Command::CancelTrack);
                }
            }
            None => {
                let tip = "track every frame from frame 0 in the background: each frame starts from the contours of the frame before; touching cells never merge, a cell that pinches in two divides (seeds drawn on frame 0, or automatic seeds)";
                let partial = m
                    .tracking
                    .as_ref()
                    .is_some_and(|t| !t.frames.is_empty() && !t.complete);
                if partial
                    && ui
                        .button("Continue tracking")
                        .on_hover_text("track on from the last frame tracked")
                        .clicked()
                {
                    cx.send(Command::ContinueTrack);
                }
                let label = if m.tracking.is_some() {
                    "Track again"
                } else {
                    "Track movie"
                };
                if ui.button(label).on_hover_text(tip).clicked() {
                    cx.send(Command::Track);
                }
            }
        }
        if let Some(tr) = m.tracking.as_ref().filter(|t| !t.corrected.is_empty()) {
            let frames: Vec<String> = tr.corrected.iter().map(usize::to_string).collect();
            let which = if frames.len() == 1 { "frame" } else { "frames" };
            ui.label(format!("corrected by hand: {which} {}", frames.join(", ")))
                .on_hover_text("frames you corrected by hand (Edit or Brush tool on a tracked frame); the frames after each were tracked again from it");
        }
        let tracked = m.tracking.as_ref().is_some_and(|t| !t.frames.is_empty());
        if ui
            .add_enabled(tracked, egui::Button::new("Export CTC…"))
            .on_hover_text("write maskTTT.tif (16-bit track labels) per frame and res_track.txt (L B E P) to a folder: the Cell Tracking Challenge result layout")
            .clicked()
        {
            cx.send(Command::ExportCtcDialog);
        }
    });
}

/// The divisions found by tracking, each a line of the event log; a click shows the
/// frame the daughters start in and selects the parent.
pub(in crate::app) fn divisions_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let Some(tr) = cx.doc.movie.as_ref().and_then(|m| m.tracking.as_ref()) else {
        return;
    };
    let shown = cx.doc.movie.as_ref().map_or(0, |m| m.frame);
    let mut chosen = None;
    ui.label(format!("Divisions ({})", tr.divisions().count()));
    egui::ScrollArea::vertical()
        .id_salt("divisions")
        .max_height(160.0)
        .show(ui, |ui| {
            for d in tr.divisions() {
                let selected = shown == d.frame && cx.view.selected_track == Some(d.parent);
                if ui.selectable_label(selected, d.describe()).clicked() {
                    chosen = Some(*d);
                }
            }
        });
    if let Some(d) = chosen {
        cx.send(Command::SeekMovieFrame(d.frame));
        cx.send(Command::SelectTrack(Some(d.parent)));
    }
}

/// The rows of the lineage view: tracks in depth-first order from each root (by label),
/// so daughters sit beside their parent.
fn rows(tracks: &[Track]) -> Vec<usize> {
    // Per track (by index), its daughters' indices.
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); tracks.len()];
    let mut roots = Vec::new();
    for (i, t) in tracks.iter().enumerate() {
        match index_of(tracks, t.parent) {
            Some(p) => children[p].push(i),
            None => roots.push(i),
        }
    }
    let mut order = Vec::with_capacity(tracks.len());
    let mut stack: Vec<usize> = roots.into_iter().rev().collect();
    while let Some(i) = stack.pop() {
        order.push(i);
        stack.extend(children[i].iter().rev());
    }
    order
}

/// Where track `label` is in `tracks` (by label; a taken-back division leaves gaps).
fn index_of(tracks: &[Track], label: u32) -> Option<usize> {
    tracks.binary_search_by_key(&label, |t| t.label).ok()
}

/// The lineage view: x is the frame, one row per track in its colour; a fork joins a
/// parent to its daughters; the frame on screen is a vertical line. A click selects the
/// track under the pointer and shows that frame.
pub(in crate::app) fn lineage_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let Some(m) = &cx.doc.movie else { return };
    let Some(tr) = m
        .tracking
        .as_ref()
        .filter(|t| !t.lineage.tracks().is_empty())
    else {
        ui.label("Track the movie to see its lineage.");
        return;
    };
    let tracks = tr.lineage.tracks();
    let order = rows(tracks);
    let row_h = (260.0 / order.len() as f32).clamp(2.0, 10.0);
    let size = Vec2::new(ui.available_width(), row_h * order.len() as f32 + 16.0);
    let (response, painter) = ui.allocate_painter(size, Sense::click());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, "Lineage view"));
    let rect = response.rect.shrink2(Vec2::new(4.0, 8.0));
    let frames = m.movie.len().max(2) - 1;
    let layout = Layout {
        rect,
        frames,
        row_h,
    };
    let mut row_of = vec![0usize; tracks.len()];
    for (r, &i) in order.iter().enumerate() {
        row_of[i] = r;
    }
    painter.rect_filled(response.rect, 2.0, Color32::from_gray(24));
    draw_tracks(&painter, &layout, tracks, &row_of, cx.view.selected_track);
    let now = layout.x(m.frame);
    painter.line_segment(
        [Pos2::new(now, rect.min.y), Pos2::new(now, rect.max.y)],
        Stroke::new(1.0, Color32::from_gray(200)),
    );
    // The frame axis: its ends, at the bottom corners.
    let (font, grey) = (egui::FontId::monospace(9.0), Color32::from_gray(150));
    let bottom = response.rect.max.y - 1.0;
    painter.text(
        Pos2::new(rect.min.x, bottom),
        egui::Align2::LEFT_BOTTOM,
        "0",
        font.clone(),
        grey,
    );
    painter.text(
        Pos2::new(rect.max.x, bottom),
        egui::Align2::RIGHT_BOTTOM,
        format!("frame {frames}"),
        font,
        grey,
    );
    // What is under the pointer: the track, when it lived, what it came from and became.
    let hovered = response.hover_pos().map(|p| layout.hit(p, tracks, &order));
    let response = match hovered {
        Some((track, frame)) => response.on_hover_ui_at_pointer(|ui| {
            ui.label(describe_track(&tr.lineage, track, frame));
        }),
        None => response,
    };
    if let Some(p) = response
        .interact_pointer_pos()
        .filter(|_| response.clicked())
    {
        let (track, frame) = layout.hit(p, tracks, &order);
        cx.send(Command::SelectTrack(track));
        cx.send(Command::SeekMovieFrame(frame));
    }
}

/// The lineage view's words for `track` (or none) at `frame`: "track 4, frames 3–9, from
/// 1, divided into 9 and 10".
fn describe_track(lineage: &Lineage, track: Option<u32>, frame: usize) -> String {
    let Some(t) = track.and_then(|k| lineage.get(k)) else {
        return format!("frame {frame}");
    };
    let mut text = format!("track {}, frames {}–{}", t.label, t.first, t.last);
    if t.parent != 0 {
        text.push_str(&format!(", from {}", t.parent));
    }
    let children: Vec<String> = lineage
        .tracks()
        .iter()
        .filter(|c| c.parent == t.label)
        .map(|c| c.label.to_string())
        .collect();
    if !children.is_empty() {
        text.push_str(&format!(", divided into {}", children.join(" and ")));
    }
    text
}

/// Where frames and rows of the lineage view are on screen.
struct Layout {
    rect: Rect,
    frames: usize,
    row_h: f32,
}

impl Layout {
    fn x(&self, frame: usize) -> f32 {
        self.rect.min.x + self.rect.width() * frame as f32 / self.frames as f32
    }
    fn y(&self, row: usize) -> f32 {
        self.rect.min.y + self.row_h * (row as f32 + 0.5)
    }
    /// The track whose row is under `p` (if it lives at that frame) and the frame.
    fn hit(&self, p: Pos2, tracks: &[Track], order: &[usize]) -> (Option<u32>, usize) {
        let f = ((p.x - self.rect.min.x) / self.rect.width() * self.frames as f32).round();
        let frame = (f.max(0.0) as usize).min(self.frames);
        let row = ((p.y - self.rect.min.y) / self.row_h).floor();
        let track = order
            .get(row.max(0.0) as usize)
            .map(|&i| tracks[i])
            .filter(|t| (t.first..=t.last).contains(&frame))
            .map(|t| t.label);
        (track, frame)
    }
}

fn draw_tracks(
    painter: &egui::Painter,
    l: &Layout,
    tracks: &[Track],
    row_of: &[usize],
    selected: Option<u32>,
) {
    let width = (l.row_h * 0.6).clamp(1.5, 4.0);
    for (i, t) in tracks.iter().enumerate() {
        let y = l.y(row_of[i]);
        let colour = crate::app::canvas::ring_color(t.label);
        let (x0, x1) = (l.x(t.first), l.x(t.last).max(l.x(t.first) + 2.0));
        if selected == Some(t.label) {
            painter.line_segment(
                [Pos2::new(x0, y), Pos2::new(x1, y)],
                Stroke::new(width + 3.0, Color32::WHITE),
            );
        }
        painter.line_segment(
            [Pos2::new(x0, y), Pos2::new(x1, y)],
            Stroke::new(width, colour),
        );
        if let Some(p) = index_of(tracks, t.parent) {
            // The fork: from the parent's end down (or up) to this daughter's start.
            let (px, py) = (l.x(tracks[p].last), l.y(row_of[p]));
            painter.line_segment(
                [Pos2::new(px, py), Pos2::new(x0, y)],
                Stroke::new(1.0, Color32::from_gray(190)),
            );
        }
    }
}

/// The question asked before work of the user's is replaced: the corrections of later
/// frames (tracking after a correction again), all of them (tracking again), or
/// everything not saved (closing the window).
pub(in crate::app) fn question_ui(cx: &mut Ctx, ctx: &egui::Context) {
    let Some(q) = cx.view.question.clone() else {
        return;
    };
    let list = |v: &[usize]| {
        v.iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let title = match q {
        super::super::Question::Quit(_) => "Quit without saving?",
        super::super::Question::Open(_) => "Open without saving?",
        _ => "Replace your corrections?",
    };
    egui::Window::new(title)
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, Vec2::ZERO)
        .show(ctx, |ui| match &q {
            super::super::Question::Retrack { frame, later } => {
                ui.label(format!(
                    "Tracking the frames after frame {frame} again replaces your corrections on {} {}.",
                    frames_word(later),
                    list(later)
                ));
                ui.horizontal(|ui| {
                    if ui.button(format!("Track again from frame {frame}")).clicked() {
                        cx.send(Command::Retrack(*frame));
                    }
                    if ui
                        .button("Undo my edit")
                        .on_hover_text("take back the edit of this frame; the later corrections stay")
                        .clicked()
                    {
                        cx.send(Command::CloseQuestion);
                        cx.send(Command::Undo);
                    }
                });
            }
            super::super::Question::TrackAgain(corrected) => {
                ui.label(format!(
                    "Tracking again from frame 0 replaces your corrections on {} {} (Undo brings them back).",
                    frames_word(corrected),
                    list(corrected)
                ));
                ui.horizontal(|ui| {
                    if ui.button("Track again from frame 0").clicked() {
                        cx.send(Command::TrackConfirmed);
                    }
                    if ui.button("Keep my corrections").clicked() {
                        cx.send(Command::CloseQuestion);
                    }
                });
            }
            super::super::Question::Open(what) => {
                ui.label(what);
                ui.horizontal(|ui| {
                    if ui.button("Save session…").clicked() {
                        cx.view.pending_open = None;
                        cx.send(Command::CloseQuestion);
                        cx.send(Command::SessionDialog(true));
                    }
                    if ui.button("Open without saving").clicked() {
                        cx.send(Command::CloseQuestion);
                        if let Some(open) = cx.view.pending_open.take() {
                            cx.view.open_confirmed = true;
                            cx.send(open);
                        }
                    }
                    if ui.button("Cancel").clicked() {
                        cx.view.pending_open = None;
                        cx.send(Command::CloseQuestion);
                    }
                });
            }
            super::super::Question::Quit(what) => {
                ui.label(what);
                ui.horizontal(|ui| {
                    if ui.button("Save session…").clicked() {
                        cx.send(Command::CloseQuestion);
                        cx.send(Command::SessionDialog(true));
                    }
                    if cx.doc.movie.is_some() && ui.button("Export CTC…").clicked() {
                        cx.send(Command::CloseQuestion);
                        cx.send(Command::ExportCtcDialog);
                    }
                    if ui.button("Quit without saving").clicked() {
                        cx.view.quit_confirmed = true;
                        ctx.send_viewport_cmd(egui::ViewportCommand::Close);
                    }
                    if ui.button("Cancel").clicked() {
                        cx.send(Command::CloseQuestion);
                    }
                });
            }
        });
}

/// "frame" or "frames", as many as `frames`.
fn frames_word(frames: &[usize]) -> &'static str {
    if frames.len() == 1 {
        "frame"
    } else {
        "frames"
    }
}
