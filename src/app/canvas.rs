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
    /// The contour vertex a drag with the Edit tool moves (none: the drag is over).
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

/// This frame's mapping between image pixels and the screen: the main half `rect`, the
/// second engine's half `right` (side by side), both with the same zoom and offset.
#[derive(Clone, Copy)]
struct View {
    rect: Rect,
    right: Option<Rect>,
    zoom: f32,
    offset: Vec2,
}

impl View {
    /// Where image point `p` is in the main half.
    fn to_screen(self, p: Point) -> Pos2 {
        self.rect.min + self.offset + Vec2::new(p.x as f32, p.y as f32) * self.zoom
    }
    /// The image point under screen point `s`, in whichever half it is.
    fn to_image(self, s: Pos2) -> Point {
        let origin = match self.right {
            Some(r) if r.contains(s) => r.min,
            _ => self.rect.min,
        };
        let v = (s - origin - self.offset) / self.zoom;
        Point::new(v.x as f64, v.y as f64)
    }
}

/// The canvas, drawn in layers: image, second engine's half, contours with their fill,
/// motion flashes, the user's shapes, then the tools (input and their previews).
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
    let view = navigate(&mut app.canvas, ui, &response, rect, right, &image, split);
    image_layer(app, ui, &painter, view, &image);
    if let Some(r) = right {
        compare_layer(app, &full_painter, &painter, view, r);
    }
    contours_layer(app, &painter, view);
    motion_layer(app, &painter, view);
    if app.shown == 0 {
        // The user's shapes, while they are what is on screen (frame 0).
        shapes_layer(app, &painter, view);
    }
    tools_layer(app, ui, &response, &painter, view, &image);
}

/// Fits the image on first show, then zooms about the pointer (wheel) and pans
/// (secondary or middle drag) for the next frame; returns this frame's view.
fn navigate(
    cs: &mut CanvasState,
    ui: &egui::Ui,
    response: &egui::Response,
    rect: Rect,
    right: Option<Rect>,
    image: &crate::evolution::Field,
    split: bool,
) -> View {
    if cs.zoom == 0.0 || cs.fitted_for != (image.width, image.height, split) {
        let z = (rect.width() / image.width as f32)
            .min(rect.height() / image.height as f32)
            .max(0.05);
        cs.zoom = z;
        cs.offset = (rect.size() - Vec2::new(image.width as f32, image.height as f32) * z) * 0.5;
        cs.fitted_for = (image.width, image.height, split);
    }
    cs.rect = Some(rect);
    let view = View {
        rect,
        right,
        zoom: cs.zoom,
        offset: cs.offset,
    };
    if let Some(hover) = response.hover_pos() {
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if scroll != 0.0 {
            let anchor = view.to_image(hover);
            let nz = (view.zoom * (scroll * 0.002).exp()).clamp(0.05, 64.0);
            cs.zoom = nz;
            cs.offset = hover - rect.min - Vec2::new(anchor.x as f32, anchor.y as f32) * nz;
        }
    }
    if response.dragged_by(egui::PointerButton::Secondary)
        || response.dragged_by(egui::PointerButton::Middle)
    {
        cs.offset += response.drag_delta();
    }
    view
}

/// The image through the contrast window (the texture is rebuilt when the window moves).
fn image_layer(
    app: &mut TopoApp,
    ui: &egui::Ui,
    painter: &egui::Painter,
    view: View,
    image: &crate::evolution::Field,
) {
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
    if let Some(t) = &app.texture {
        painter.image(t.id(), image_rect(view, image), UV, Color32::WHITE);
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

/// Draws rings as closed lines (holes thinner), each in its colour, shifted by `shift`.
fn draw_rings(painter: &egui::Painter, view: View, rings: &[super::RingView], shift: Vec2) {
    for ring in rings {
        let mut pts: Vec<Pos2> = ring
            .points
            .iter()
            .map(|&p| view.to_screen(p) + shift)
            .collect();
        pts.push(pts[0]);
        painter.add(egui::Shape::line(
            pts,
            Stroke::new(if ring.hole { 1.5 } else { 2.0 }, ring_color(ring.id)),
        ));
    }
}

/// The second engine's half: the same image and view, its contours, both halves labelled.
fn compare_layer(
    app: &TopoApp,
    full_painter: &egui::Painter,
    painter: &egui::Painter,
    view: View,
    r: Rect,
) {
    let (Some(t), Some(image)) = (&app.texture, &app.image) else {
        return;
    };
    let p2 = full_painter.with_clip_rect(r);
    let shift = r.min - view.rect.min;
    p2.image(
        t.id(),
        image_rect(view, image).translate(shift),
        UV,
        Color32::WHITE,
    );
    if let Some(rec) = app.shown_record_b() {
        draw_rings(&p2, view, &rec.rings, shift);
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
    let compare = app.settings.compare.map_or("", |m| m.name());
    label(&p2, r, format!("{compare}{}", count(app.shown_record_b())));
    let mode = app.settings.mode.name();
    label(
        painter,
        view.rect,
        format!("{mode}{}", count(app.shown_record())),
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
fn contours_layer(app: &mut TopoApp, painter: &egui::Painter, view: View) {
    let Some(rec) = app
        .run
        .as_ref()
        .and_then(|r| r.history.get(app.shown.min(r.history.len() - 1)))
    else {
        return;
    };
    // Filling triangulates every ring; for large sets it waits until playback pauses so
    // that playing stays fluid.
    let small = rec.vertices <= FILL_WHILE_PLAYING_MAX_VERTICES;
    if app.settings.show_fill && (small || !app.playing) {
        let cs = &mut app.canvas;
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
                &|p| view.to_screen(p),
                Color32::from_rgba_unmultiplied(255, 170, 60, 60),
            ));
        }
    }
    draw_rings(painter, view, &rec.rings, Vec2::ZERO);
}

/// Flashes the motion regions of this frame's events and of the few frames before it.
fn motion_layer(app: &TopoApp, painter: &egui::Painter, view: View) {
    let Some(run) = app.run.as_ref() else { return };
    for back in 0..6usize {
        let Some(old) = app.shown.checked_sub(back).and_then(|i| run.history.get(i)) else {
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

/// The user's shapes, the selected one highlighted.
fn shapes_layer(app: &TopoApp, painter: &egui::Painter, view: View) {
    for (i, s) in app.shapes.iter().enumerate() {
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
                let c = view.to_screen(*center);
                painter.circle_stroke(c, *radius as f32 * view.zoom, stroke);
                painter.circle_filled(c, 2.0, stroke.color);
            }
            Shape::Rect { min, max } => {
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

/// The tools: presses, drags and releases become commands; drawing previews.
fn tools_layer(
    app: &mut TopoApp,
    ui: &egui::Ui,
    response: &egui::Response,
    painter: &egui::Painter,
    view: View,
    image: &crate::evolution::Field,
) {
    let tool = app.settings.tool;
    let zoom = view.zoom;
    let cs = &mut app.canvas;
    let pointer = response.interact_pointer_pos().or(response.hover_pos());
    if response.drag_started_by(egui::PointerButton::Primary) {
        if let Some(p) = pointer {
            let at = view.to_image(p);
            cs.drag_from_in_image = Some(at);
            cs.drag_to_in_image = Some(at);
            if tool == Tool::Select {
                cs.moving = hit_shape(&app.shapes, at, 6.0 / zoom as f64);
                app.commands.push(Command::Select(cs.moving));
            }
            if tool == Tool::Edit {
                // The vertex under the press (a drag starts a few pixels later) in the
                // frame on screen.
                let at = ui
                    .input(|i| i.pointer.press_origin())
                    .map_or(at, |s| view.to_image(s));
                app.commands.push(Command::GrabVertex {
                    at,
                    tol: 8.0 / zoom as f64,
                });
            }
        }
    }
    if response.dragged_by(egui::PointerButton::Primary) {
        if let (Some(p), Some(_)) = (pointer, cs.drag_from_in_image) {
            cs.drag_to_in_image = Some(view.to_image(p));
            if let (Tool::Edit, Some(v)) = (tool, cs.editing) {
                let to = view.to_image(p);
                app.commands.push(Command::HandMove { vertex: v, to });
            }
        }
    }
    if let (Some(a), Some(b)) = (cs.drag_from_in_image, cs.drag_to_in_image) {
        let yellow = Stroke::new(1.5, Color32::YELLOW);
        match tool {
            Tool::Seed => {
                let r = (a.dist(b) as f32 * zoom).max(2.0);
                painter.circle_stroke(view.to_screen(a), r, yellow);
            }
            Tool::Rect => {
                painter.rect_stroke(
                    Rect::from_two_pos(view.to_screen(a), view.to_screen(b)),
                    0.0,
                    yellow,
                    egui::StrokeKind::Middle,
                );
            }
            _ => {}
        }
    }
    if response.drag_stopped_by(egui::PointerButton::Primary) || response.clicked() {
        let end = pointer.map(|s| view.to_image(s));
        let start = cs.drag_from_in_image.take().or(end);
        let stop = cs.drag_to_in_image.take().or(end);
        if let (Some(a), Some(b)) = (start, stop) {
            release(app, response, view, image, a, b);
        }
    }
    let cs = &app.canvas;
    if !cs.polygon.is_empty() {
        let mut pts: Vec<Pos2> = cs.polygon.iter().map(|&p| view.to_screen(p)).collect();
        if let Some(h) = response.hover_pos() {
            pts.push(h);
        }
        painter.add(egui::Shape::line(pts, Stroke::new(1.5, Color32::YELLOW)));
    }
}

/// A press at `a` released at `b`: what it makes with the current tool.
fn release(
    app: &mut TopoApp,
    response: &egui::Response,
    view: View,
    image: &crate::evolution::Field,
    a: Point,
    b: Point,
) {
    let zoom = view.zoom;
    let cs = &mut app.canvas;
    let inside = |p: Point| {
        p.x >= 0.0 && p.y >= 0.0 && p.x <= image.width as f64 && p.y <= image.height as f64
    };
    let command = match app.settings.tool {
        Tool::Seed if inside(a) => {
            // A click makes a seed of default radius; a drag sets the radius.
            let r = if a.dist(b) < 2.0 { 5.0 } else { a.dist(b) };
            Some(Command::AddShape(Shape::Disk {
                center: a,
                radius: r,
            }))
        }
        Tool::Rect if a.dist(b) >= 3.0 => {
            let min = Point::new(a.x.min(b.x).max(0.0), a.y.min(b.y).max(0.0));
            let max = Point::new(
                a.x.max(b.x).min(image.width as f64),
                a.y.max(b.y).min(image.height as f64),
            );
            Some(Command::AddShape(Shape::Rect { min, max }))
        }
        Tool::Polygon if inside(b) => {
            let close = cs.polygon.len() >= 3 && (b.dist(cs.polygon[0]) * zoom as f64) < 8.0;
            if !(close || response.double_clicked()) {
                cs.polygon.push(b);
                None
            } else if cs.polygon.len() >= 3 {
                Some(Command::AddShape(Shape::Polygon(std::mem::take(
                    &mut cs.polygon,
                ))))
            } else {
                None
            }
        }
        // A click (no vertex dragged) selects the contour under it.
        Tool::Edit if cs.editing.take().is_none() || a.dist(b) == 0.0 => {
            let id = app.shown_record().and_then(|r| contour_at(&r.rings, b));
            Some(Command::SelectContour(id))
        }
        Tool::Select => match cs.moving.take() {
            Some(i) if a.dist(b) > 0.0 => Some(Command::MoveShape {
                index: i,
                by: b - a,
            }),
            Some(_) => None,
            // A plain click (no drag began): select what is under it.
            None => Some(Command::Select(hit_shape(
                &app.shapes,
                b,
                6.0 / zoom as f64,
            ))),
        },
        _ => None,
    };
    app.commands.extend(command);
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
