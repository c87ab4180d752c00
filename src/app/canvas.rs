//! The canvas: the image with its contrast window, the contours of the frame on screen
//! (each ring in its colour, regions filled with holes left open), the user's shapes,
//! and the motion regions that caused topology events, flashed. Pan with the right or
//! middle button (or the primary button with the Select tool on empty space), zoom with
//! the wheel.

use super::{fill, Command, Tool, TopoApp};
use crate::evolution::Shape;
use crate::geometry::Point;
use egui::{Color32, Pos2, Rect, Sense, Stroke, Vec2};

/// View and gesture state.
#[derive(Default)]
pub struct CanvasState {
    /// Screen position of image pixel (0, 0), relative to the canvas's top-left.
    offset: Vec2,
    /// Screen points per image pixel; 0 until fitted.
    zoom: f32,
    /// Image size and side-by-side state the view was fitted for.
    fitted_for: (usize, usize, bool),
    drag_from_in_image: Option<Point>,
    drag_to_in_image: Option<Point>,
    polygon: Vec<Point>,
    moving: Option<usize>,
    /// The contour vertex the Edit tool drags.
    editing: Option<u32>,
    /// The canvas rectangle on screen last frame.
    rect: Option<Rect>,
    fill_cache: Option<(usize, usize, fill::FillMesh)>,
}

/// The innermost ring of the frame on screen around `at` (a hole inside a region wins).
fn contour_at(rings: &[super::RingView], at: Point) -> Option<u32> {
    rings
        .iter()
        .filter(|r| crate::geometry::winding_number(&r.points, at) != 0)
        .min_by(|a, b| {
            let area = |r: &super::RingView| crate::geometry::signed_area(&r.points).abs();
            area(a).total_cmp(&area(b))
        })
        .map(|r| r.id)
}

impl CanvasState {
    /// After a hand edit: the vertex that now leads the drag (none: it is over).
    pub fn set_drag_lead(&mut self, lead: Option<u32>) {
        self.editing = lead;
    }

    /// Drops the polygon being drawn.
    pub fn cancel_polygon(&mut self) {
        self.polygon.clear();
    }

    /// Fits the image to the canvas again on the next frame.
    pub fn refit(&mut self) {
        self.zoom = 0.0;
    }
}

/// Above this many vertices regions are filled only while playback is paused.
const FILL_WHILE_PLAYING_MAX_VERTICES: usize = 5000;

fn ring_color(id: u32) -> Color32 {
    // Golden-angle hues: neighbouring ids get distant colours.
    let h = (id as f32 * 0.618_034) % 1.0;
    egui::ecolor::Hsva::new(h, 0.85, 0.95, 1.0).into()
}

pub fn canvas_ui(app: &mut TopoApp, ui: &mut egui::Ui) {
    let (response, full_painter) =
        ui.allocate_painter(ui.available_size(), Sense::click_and_drag());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, "Canvas"));
    // Side by side: the main engine on the left half, the second on the right, both with
    // the same view; shapes can be drawn in either half.
    let split = app.run_b.is_some() || app.settings.compare.is_some();
    let full = response.rect;
    let (rect, right) = if split {
        let (l, r) = full.split_left_right_at_fraction(0.5);
        (l, Some(r.shrink2(Vec2::new(1.0, 0.0))))
    } else {
        (full, None)
    };
    let painter = full_painter.with_clip_rect(rect);
    let Some(image) = app.image.clone() else {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Open an image (or drop one here)",
            egui::FontId::proportional(18.0),
            Color32::GRAY,
        );
        return;
    };
    let cs = &mut app.canvas;
    if cs.zoom == 0.0 || cs.fitted_for != (image.width, image.height, split) {
        let z = (rect.width() / image.width as f32)
            .min(rect.height() / image.height as f32)
            .max(0.05);
        cs.zoom = z;
        cs.offset = (rect.size() - Vec2::new(image.width as f32, image.height as f32) * z) * 0.5;
        cs.fitted_for = (image.width, image.height, split);
    }
    let (zoom, offset) = (cs.zoom, cs.offset);
    cs.rect = Some(rect);
    let screen_from_image =
        move |p: Point| rect.min + offset + Vec2::new(p.x as f32, p.y as f32) * zoom;
    let image_from_screen = move |s: Pos2| {
        let origin = match right {
            Some(r) if r.contains(s) => r.min,
            _ => rect.min,
        };
        let v = (s - origin - offset) / zoom;
        Point::new(v.x as f64, v.y as f64)
    };

    // Zoom about the pointer; pan with secondary/middle drag.
    if let Some(hover) = response.hover_pos() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            let anchor = image_from_screen(hover);
            let nz = (zoom * (scroll * 0.002).exp()).clamp(0.05, 64.0);
            cs.zoom = nz;
            cs.offset = hover - rect.min - Vec2::new(anchor.x as f32, anchor.y as f32) * nz;
        }
    }
    if response.dragged_by(egui::PointerButton::Secondary)
        || response.dragged_by(egui::PointerButton::Middle)
    {
        cs.offset += response.drag_delta();
    }

    // The image, through the contrast window.
    if app.texture.is_none() || app.texture_contrast != app.settings.contrast {
        let (lo, hi) = app.settings.contrast;
        let span = (hi - lo).max(1e-3);
        let pixels: Vec<Color32> = image
            .data
            .iter()
            .map(|&v| Color32::from_gray((((v - lo) / span).clamp(0.0, 1.0) * 255.0) as u8))
            .collect();
        let img = egui::ColorImage::new([image.width, image.height], pixels);
        app.texture = Some(
            ui.ctx()
                .load_texture("image", img, egui::TextureOptions::NEAREST),
        );
        app.texture_contrast = app.settings.contrast;
    }
    let img_rect = Rect::from_min_max(
        screen_from_image(Point::new(0.0, 0.0)),
        screen_from_image(Point::new(image.width as f64, image.height as f64)),
    );
    if let Some(t) = &app.texture {
        painter.image(
            t.id(),
            img_rect,
            Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)),
            Color32::WHITE,
        );
    }

    // The second engine's half: the same image and view, its contours.
    if let (Some(r), Some(t)) = (right, &app.texture) {
        let p2 = full_painter.with_clip_rect(r);
        let shift = r.min - rect.min;
        p2.image(
            t.id(),
            img_rect.translate(shift),
            Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)),
            Color32::WHITE,
        );
        if let Some(rec) = app.shown_record_b() {
            for ring in &rec.rings {
                let mut pts: Vec<Pos2> = ring
                    .points
                    .iter()
                    .map(|&p| screen_from_image(p) + shift)
                    .collect();
                pts.push(pts[0]);
                p2.add(egui::Shape::line(
                    pts,
                    Stroke::new(if ring.hole { 1.5 } else { 2.0 }, ring_color(ring.id)),
                ));
            }
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
        let count = |rec: Option<&super::FrameRecord>| {
            rec.map_or(String::new(), |r| format!(" — {} contours", r.contours))
        };
        label(
            &p2,
            r,
            format!(
                "{}{}",
                app.settings.compare.map_or("", |m| m.name()),
                count(app.shown_record_b())
            ),
        );
        label(
            &painter,
            rect,
            format!("{}{}", app.settings.mode.name(), count(app.shown_record())),
        );
        full_painter.line_segment(
            [
                Pos2::new(r.min.x - 1.0, r.min.y),
                Pos2::new(r.min.x - 1.0, r.max.y),
            ],
            Stroke::new(2.0, Color32::DARK_GRAY),
        );
    }

    // Contours of the frame on screen.
    let cs = &mut app.canvas;
    let shown_a = app
        .run
        .as_ref()
        .and_then(|r| r.history.get(app.shown.min(r.history.len() - 1)));
    if let Some(rec) = shown_a {
        // Filling triangulates every ring; for large sets it waits until playback pauses
        // so that playing stays fluid.
        let small = rec.vertices <= FILL_WHILE_PLAYING_MAX_VERTICES;
        if app.settings.show_fill && (small || !app.playing) {
            let key = (rec.index, rec.vertices);
            let stale = cs
                .fill_cache
                .as_ref()
                .is_none_or(|(i, v, _)| (*i, *v) != key);
            if stale {
                cs.fill_cache = Some((key.0, key.1, fill::FillMesh::of(&rec.rings)));
            }
            if let Some((_, _, m)) = &cs.fill_cache {
                painter.add(m.to_mesh(
                    &screen_from_image,
                    Color32::from_rgba_unmultiplied(255, 170, 60, 60),
                ));
            }
        }
        for r in &rec.rings {
            let mut pts: Vec<Pos2> = r.points.iter().map(|&p| screen_from_image(p)).collect();
            pts.push(pts[0]);
            let c = ring_color(r.id);
            painter.add(egui::Shape::line(
                pts,
                Stroke::new(if r.hole { 1.5 } else { 2.0 }, c),
            ));
        }
        // Flash the motion regions of this frame's events (and the few before it).
        let run = app.run.as_ref().expect("record exists");
        for back in 0..6usize {
            let Some(old) = app.shown.checked_sub(back).and_then(|i| run.history.get(i)) else {
                break;
            };
            let alpha = 255 - back as u8 * 40;
            for q in &old.motions {
                let pts: Vec<Pos2> = q.iter().map(|&p| screen_from_image(p)).collect();
                painter.add(egui::Shape::closed_line(
                    pts,
                    Stroke::new(2.5, Color32::from_rgba_unmultiplied(255, 40, 200, alpha)),
                ));
                painter.circle_stroke(
                    screen_from_image(q[3]),
                    10.0 - back as f32,
                    Stroke::new(2.0, Color32::from_rgba_unmultiplied(255, 40, 200, alpha)),
                );
            }
        }
    }

    // The user's shapes, while they are what is on screen (frame 0).
    let shapes_visible = app.shown == 0;
    for (i, s) in app.shapes.iter().enumerate().filter(|_| shapes_visible) {
        let sel = app.selected == Some(i);
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
                painter.circle_stroke(screen_from_image(*center), *radius as f32 * zoom, stroke);
                painter.circle_filled(screen_from_image(*center), 2.0, stroke.color);
            }
            Shape::Rect { min, max } => {
                painter.rect_stroke(
                    Rect::from_min_max(screen_from_image(*min), screen_from_image(*max)),
                    0.0,
                    stroke,
                    egui::StrokeKind::Middle,
                );
            }
            Shape::Polygon(p) => {
                painter.add(egui::Shape::closed_line(
                    p.iter().map(|&q| screen_from_image(q)).collect(),
                    stroke,
                ));
            }
        }
    }

    // Tools.
    let tool = app.settings.tool;
    let pointer = response.interact_pointer_pos().or(response.hover_pos());
    let primary_down = response.drag_started_by(egui::PointerButton::Primary);
    if primary_down {
        if let Some(p) = pointer {
            let at = image_from_screen(p);
            cs.drag_from_in_image = Some(at);
            cs.drag_to_in_image = Some(at);
            if tool == Tool::Select {
                cs.moving = hit_shape(&app.shapes, at, 6.0 / zoom as f64);
                app.commands.push(Command::Select(cs.moving));
            }
            if tool == Tool::Edit {
                // The vertex under the press (a drag starts a few pixels later) in the
                // frame on screen; the run is put back at that frame, so later frames
                // start from the edit.
                let at = ui
                    .input(|i| i.pointer.press_origin())
                    .map_or(at, image_from_screen);
                let shown = app.shown;
                cs.editing = app.run.as_mut().and_then(|run| {
                    run.rewind(shown.min(run.history.len() - 1));
                    run.evolver.vertex_near(at, 8.0 / zoom as f64)
                });
            }
        }
    }
    if response.dragged_by(egui::PointerButton::Primary) {
        if let (Some(p), Some(_)) = (pointer, cs.drag_from_in_image) {
            cs.drag_to_in_image = Some(image_from_screen(p));
            if let (Tool::Edit, Some(v)) = (tool, cs.editing) {
                let to = image_from_screen(p);
                app.commands.push(Command::HandMove { vertex: v, to });
            }
        }
    }
    if let (Some(a), Some(b)) = (cs.drag_from_in_image, cs.drag_to_in_image) {
        match tool {
            Tool::Seed => {
                painter.circle_stroke(
                    screen_from_image(a),
                    (a.dist(b) as f32 * zoom).max(2.0),
                    Stroke::new(1.5, Color32::YELLOW),
                );
            }
            Tool::Rect => {
                painter.rect_stroke(
                    Rect::from_two_pos(screen_from_image(a), screen_from_image(b)),
                    0.0,
                    Stroke::new(1.5, Color32::YELLOW),
                    egui::StrokeKind::Middle,
                );
            }
            _ => {}
        }
    }
    let released = response.drag_stopped_by(egui::PointerButton::Primary) || response.clicked();
    if released {
        let end = pointer.map(image_from_screen);
        let start = cs.drag_from_in_image.take().or(end);
        let stop = cs.drag_to_in_image.take().or(end);
        if let (Some(a), Some(b)) = (start, stop) {
            let inside = |p: Point| {
                p.x >= 0.0 && p.y >= 0.0 && p.x <= image.width as f64 && p.y <= image.height as f64
            };
            match tool {
                Tool::Seed if inside(a) => {
                    // A click makes a seed of default radius; a drag sets the radius.
                    let r = if a.dist(b) < 2.0 { 5.0 } else { a.dist(b) };
                    app.commands.push(Command::AddShape(Shape::Disk {
                        center: a,
                        radius: r,
                    }));
                }
                Tool::Rect if a.dist(b) >= 3.0 => {
                    let min = Point::new(a.x.min(b.x).max(0.0), a.y.min(b.y).max(0.0));
                    let max = Point::new(
                        a.x.max(b.x).min(image.width as f64),
                        a.y.max(b.y).min(image.height as f64),
                    );
                    app.commands
                        .push(Command::AddShape(Shape::Rect { min, max }));
                }
                Tool::Polygon if inside(b) => {
                    let close =
                        cs.polygon.len() >= 3 && (b.dist(cs.polygon[0]) * zoom as f64) < 8.0;
                    if close || response.double_clicked() {
                        if cs.polygon.len() >= 3 {
                            app.commands
                                .push(Command::AddShape(Shape::Polygon(std::mem::take(
                                    &mut cs.polygon,
                                ))));
                        }
                    } else {
                        cs.polygon.push(b);
                    }
                }
                // A click (no vertex dragged) selects the contour under it.
                Tool::Edit if cs.editing.take().is_none() || a.dist(b) == 0.0 => {
                    let shown = app.shown;
                    let id = app
                        .run
                        .as_ref()
                        .and_then(|r| r.history.get(shown.min(r.history.len() - 1)))
                        .and_then(|r| contour_at(&r.rings, b));
                    app.commands.push(Command::SelectContour(id));
                }
                Tool::Select => match cs.moving.take() {
                    Some(i) if a.dist(b) > 0.0 => app.commands.push(Command::MoveShape {
                        index: i,
                        by: b - a,
                    }),
                    Some(_) => {}
                    // A plain click (no drag began): select what is under it.
                    None => app.commands.push(Command::Select(hit_shape(
                        &app.shapes,
                        b,
                        6.0 / zoom as f64,
                    ))),
                },
                _ => {}
            }
        }
    }
    if !cs.polygon.is_empty() {
        let mut pts: Vec<Pos2> = cs.polygon.iter().map(|&p| screen_from_image(p)).collect();
        if let Some(h) = response.hover_pos() {
            pts.push(h);
        }
        painter.add(egui::Shape::line(pts, Stroke::new(1.5, Color32::YELLOW)));
    }
}

impl CanvasState {
    /// Where image point `p` is on screen (as of the last frame drawn).
    pub fn screen_from_image(&self, p: Point) -> Pos2 {
        self.rect.map_or(Pos2::ZERO, |r| r.min)
            + self.offset
            + Vec2::new(p.x as f32, p.y as f32) * self.zoom
    }
}

/// The shape under `at` (within `tol` image pixels of its outline or centre).
fn hit_shape(shapes: &[Shape], at: Point, tol: f64) -> Option<usize> {
    shapes.iter().enumerate().rev().find_map(|(i, s)| {
        let hit = match s {
            Shape::Disk { center, radius } => at.dist(*center) <= radius + tol,
            Shape::Rect { min, max } => {
                let near_x = at.x >= min.x - tol && at.x <= max.x + tol;
                let near_y = at.y >= min.y - tol && at.y <= max.y + tol;
                let on_edge = (at.x - min.x).abs() < tol
                    || (at.x - max.x).abs() < tol
                    || (at.y - min.y).abs() < tol
                    || (at.y - max.y).abs() < tol;
                near_x && near_y && on_edge
            }
            Shape::Polygon(p) => crate::geometry::winding_number(p, at) != 0,
        };
        hit.then_some(i)
    })
}
