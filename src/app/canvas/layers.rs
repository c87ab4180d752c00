//! The drawn layers of the canvas, bottom to top: image, second engine's half, contours
//! with their fill, motion flashes, the user's shapes.

use super::{fill, ring_color, View, FILL_WHILE_PLAYING_MAX_VERTICES};
use crate::app::view::Texture;
use crate::app::Ctx;
use crate::evolution::Shape;
use crate::geometry::Point;
use egui::{Color32, Pos2, Rect, Stroke, Vec2};

/// The image through the contrast window (the texture is rebuilt when the window moves).
pub(super) fn image_layer(
    cx: &mut Ctx,
    ui: &egui::Ui,
    painter: &egui::Painter,
    view: View,
    image: &std::sync::Arc<crate::evolution::Field>,
) {
    let of = (
        std::sync::Arc::as_ptr(image) as usize,
        cx.doc.settings.contrast,
    );
    if cx.view.texture.as_ref().is_none_or(|t| t.of != of) {
        let (lo, hi) = of.1;
        let span = (hi - lo).max(1e-3);
        let pixels: Vec<Color32> = image
            .data
            .iter()
            .map(|&v| Color32::from_gray((((v - lo) / span).clamp(0.0, 1.0) * 255.0) as u8))
            .collect();
        let img = egui::ColorImage::new([image.width, image.height], pixels);
        let handle = ui
            .ctx()
            .load_texture("image", img, egui::TextureOptions::NEAREST);
        cx.view.texture = Some(Texture { handle, of });
    }
    if let Some(t) = &cx.view.texture {
        painter.image(t.handle.id(), image_rect(view, image), UV, Color32::WHITE);
    }
}

/// The whole texture.
const UV: Rect = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));

/// Where the image lies in the main half.
fn image_rect(view: View, image: &crate::evolution::Field) -> Rect {
    Rect::from_min_max(
        view.to_screen(Point::new(0.0, 0.0)),
        view.to_screen(Point::new(image.width as f64, image.height as f64)),
    )
}

/// Draws rings as closed lines (holes thinner), each in its colour, shifted by `shift`;
/// with `tracks` (a correction on screen), each cell in its track's colour, numbered.
fn draw_rings(
    painter: &egui::Painter,
    view: View,
    rings: &[crate::app::RingView],
    shift: Vec2,
    tracks: Option<&crate::app::correct::CellTracks>,
) {
    let font = egui::FontId::proportional(12.0);
    for ring in rings {
        let mut pts: Vec<Pos2> = ring
            .points
            .iter()
            .map(|&p| view.to_screen(p) + shift)
            .collect();
        pts.push(pts[0]);
        let track = tracks.and_then(|t| t.get(&ring.id));
        let colour = ring_color(track.map_or(ring.id, |t| t.0));
        painter.add(egui::Shape::line(
            pts,
            Stroke::new(if ring.hole { 1.5 } else { 2.0 }, colour),
        ));
        if let (Some(&(k, c)), false) = (track, ring.hole) {
            track_number(painter, view.to_screen(c) + shift, k, &font, colour);
        }
    }
}

/// A track's number at `at` in its colour, on a dark plate: read over bright nuclei as
/// over dark rods (drawn bare, a yellow number vanished on a bright nucleus).
fn track_number(
    painter: &egui::Painter,
    at: Pos2,
    track: u32,
    font: &egui::FontId,
    colour: Color32,
) {
    let galley = painter.layout_no_wrap(track.to_string(), font.clone(), colour);
    let rect = Rect::from_center_size(at, galley.size()).expand2(Vec2::new(2.0, 0.0));
    painter.rect_filled(rect, 3.0, Color32::from_black_alpha(160));
    painter.galley(rect.min + Vec2::new(2.0, 0.0), galley, colour);
}

/// The second engine's half: the same image and view, its contours, both halves labelled.
pub(super) fn compare_layer(
    cx: &Ctx,
    full_painter: &egui::Painter,
    painter: &egui::Painter,
    view: View,
    r: Rect,
) {
    let (Some(t), Some(image)) = (&cx.view.texture, &cx.doc.image) else {
        return;
    };
    let p2 = full_painter.with_clip_rect(r);
    let shift = r.min - view.rect.min;
    p2.image(
        t.handle.id(),
        image_rect(view, image).translate(shift),
        UV,
        Color32::WHITE,
    );
    if let Some(rec) = cx.doc.shown_record_b() {
        draw_rings(&p2, view, &rec.rings, shift, None);
    }
    let label = |p: &egui::Painter, at: Rect, text: String| {
        p.text(
            at.min + Vec2::new(8.0, 6.0),
            egui::Align2::LEFT_TOP,
            text,
            egui::FontId::proportional(15.0),
            Color32::from_rgb(255, 230, 120),
        );
    };
    let count = |rec: Option<&crate::app::FrameRecord>| {
        rec.map_or(String::new(), |r| format!(" — {} contours", r.contours))
    };
    let compare = cx.doc.settings.compare.map_or("", |m| m.name());
    label(
        &p2,
        r,
        format!("{compare}{}", count(cx.doc.shown_record_b())),
    );
    let mode = cx.doc.params().mode.name();
    label(
        painter,
        view.rect,
        format!("{mode}{}", count(cx.doc.shown_record())),
    );
    full_painter.line_segment(
        [
            Pos2::new(r.min.x - 1.0, r.min.y),
            Pos2::new(r.min.x - 1.0, r.max.y),
        ],
        Stroke::new(2.0, Color32::DARK_GRAY),
    );
}

/// The contours of the frame on screen, their region filled (holes open).
pub(super) fn contours_layer(cx: &mut Ctx, painter: &egui::Painter, view: View) {
    let Some(rec) = cx.doc.shown_record() else {
        return;
    };
    // Filling triangulates every ring; for large sets it waits until playback pauses so
    // that playing stays fluid.
    let small = rec.vertices <= FILL_WHILE_PLAYING_MAX_VERTICES;
    if cx.view.prefs.show_fill && (small || !cx.view.playing) {
        let cs = &mut cx.view.canvas;
        if cs.fill_cache.as_ref().is_none_or(|(s, _)| *s != rec.stamp) {
            cs.fill_cache = Some((rec.stamp, fill::FillMesh::of(&rec.rings)));
        }
        if let Some((_, m)) = &cs.fill_cache {
            painter.add(m.to_mesh(
                &|p| view.to_screen(p),
                Color32::from_rgba_unmultiplied(255, 170, 60, 60),
            ));
        }
    }
    // The selected contour (Edit tool or object table) under a white halo.
    if let Some(r) = cx
        .view
        .selected_contour
        .and_then(|id| rec.rings.iter().find(|r| r.id == id))
    {
        let mut pts: Vec<Pos2> = r.points.iter().map(|&p| view.to_screen(p)).collect();
        pts.push(pts[0]);
        painter.add(egui::Shape::line(pts, Stroke::new(5.0, Color32::WHITE)));
    }
    let tracks = cx.view.correction_tracks.get(cx.doc);
    draw_rings(painter, view, &rec.rings, Vec2::ZERO, tracks.as_deref());
}

/// Flashes the motion regions of this frame's events and of the few frames before it.
pub(super) fn motion_layer(cx: &Ctx, painter: &egui::Painter, view: View) {
    let Some(run) = cx.doc.run.as_ref() else {
        return;
    };
    for back in 0..6usize {
        let Some(old) = cx
            .doc
            .shown
            .checked_sub(back)
            .and_then(|i| run.history.get(i))
        else {
            break;
        };
        let color = Color32::from_rgba_unmultiplied(255, 40, 200, 255 - back as u8 * 40);
        for m in &old.motions {
            let (corners, k) = m.loop_points();
            let pts: Vec<Pos2> = corners[..k].iter().map(|&p| view.to_screen(p)).collect();
            painter.add(egui::Shape::closed_line(pts, Stroke::new(2.5, color)));
            painter.circle_stroke(
                view.to_screen(m.q.unwrap_or(m.o)),
                10.0 - back as f32,
                Stroke::new(2.0, color),
            );
        }
    }
}

/// The user's shapes, the selected one highlighted, when on screen
/// ([`crate::app::Document::shapes_shown`]).
pub(super) fn shapes_layer(cx: &Ctx, painter: &egui::Painter, view: View) {
    if !cx.doc.shapes_shown() {
        return;
    }
    for (i, s) in cx.doc.shapes.iter().enumerate() {
        let sel = cx.view.selected == Some(i);
        let stroke = Stroke::new(
            if sel { 2.5 } else { 1.5 },
            if sel {
                Color32::YELLOW
            } else {
                Color32::from_rgb(80, 200, 255)
            },
        );
        match s {
            Shape::Disk { center, radius } => {
                let c = view.to_screen(*center);
                painter.circle_stroke(c, *radius as f32 * view.zoom, stroke);
                painter.circle_filled(c, 2.0, stroke.color);
            }
            Shape::Rect { min, max } => {
                if cx.doc.sample_wrap {
                    painter.text(
                        view.to_screen(*min) + Vec2::new(6.0, 4.0),
                        egui::Align2::LEFT_TOP,
                        "wrap: shrinks onto every cell when you press Play; a seed you click replaces it",
                        egui::FontId::proportional(14.0),
                        Color32::from_rgb(80, 200, 255),
                    );
                }
                painter.rect_stroke(
                    Rect::from_min_max(view.to_screen(*min), view.to_screen(*max)),
                    0.0,
                    stroke,
                    egui::StrokeKind::Middle,
                );
            }
            Shape::Polygon(p) => {
                painter.add(egui::Shape::closed_line(
                    p.iter().map(|&q| view.to_screen(q)).collect(),
                    stroke,
                ));
            }
        }
    }
}

/// A frame with at most this many divisions says each in words beside its ring.
const SAID_DIVISIONS: usize = 3;

/// The tracks of the movie frame on screen, each outline in its track's colour (the same
/// in every frame) with its label; the daughters of a division in this frame ringed (and
/// the division said in words, on a busy frame only the selected track's), the selected
/// track under a white halo.
pub(super) fn tracks_layer(cx: &Ctx, painter: &egui::Painter, view: View) {
    let Some(frame) = cx.doc.movie.as_ref().and_then(|m| m.tracked_frame()) else {
        return;
    };
    let font = egui::FontId::proportional(12.0);
    for o in &frame.objects {
        let mut pts: Vec<Pos2> = o.ring.iter().map(|&p| view.to_screen(p)).collect();
        pts.push(pts[0]);
        let colour = ring_color(o.track);
        if cx.view.selected_track == Some(o.track) {
            painter.add(egui::Shape::line(
                pts.clone(),
                Stroke::new(5.0, Color32::WHITE),
            ));
        }
        painter.add(egui::Shape::line(pts, Stroke::new(2.0, colour)));
        track_number(painter, view.to_screen(o.centroid), o.track, &font, colour);
    }
    let magenta = Stroke::new(2.5, Color32::from_rgb(255, 40, 200));
    // A busy frame's sentences covered the colony: then only the selected track's
    // division is said (the event log lists them all).
    let say_all = frame.divisions.len() <= SAID_DIVISIONS;
    for d in &frame.divisions {
        let at: Vec<Point> = frame
            .objects
            .iter()
            .filter(|o| d.children.contains(&o.track))
            .map(|o| o.centroid)
            .collect();
        if let [a, b] = at[..] {
            let c = (a + b) * 0.5;
            let r = (a.dist(b) * 0.5 + 18.0) as f32 * view.zoom;
            painter.circle_stroke(view.to_screen(c), r, magenta);
            let selected = cx
                .view
                .selected_track
                .is_some_and(|k| k == d.parent || d.children.contains(&k));
            if !(say_all || selected) {
                continue;
            }
            painter.text(
                view.to_screen(c) + Vec2::new(0.0, -r - 8.0),
                egui::Align2::CENTER_BOTTOM,
                d.describe(),
                egui::FontId::proportional(13.0),
                magenta.color,
            );
        }
    }
}
