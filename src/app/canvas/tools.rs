//! The canvas tools: presses, drags and releases become [`Command`]s; the shape being
//! drawn is previewed.

use super::View;
use crate::app::{Command, Ctx, Tool};
use crate::evolution::Shape;
use crate::geometry::Point;
use egui::{Color32, Pos2, Rect, Stroke};

/// The tools: presses, drags and releases become commands; drawing previews.
pub(super) fn tools_layer(
    cx: &mut Ctx,
    ui: &egui::Ui,
    response: &egui::Response,
    painter: &egui::Painter,
    view: View,
    image: &crate::evolution::Field,
) {
    let tool = cx.view.prefs.tool;
    let zoom = view.zoom;
    let pointer = response.interact_pointer_pos().or(response.hover_pos());
    if response.drag_started_by(egui::PointerButton::Primary) {
        if let Some(p) = pointer {
            press(cx, ui, view, view.to_image(p));
        }
    }
    if tool == Tool::Brush {
        brush(
            cx,
            ui,
            response,
            painter,
            view,
            pointer,
            |from, to, radius, stroke| Command::Brush {
                from,
                to,
                radius,
                stroke,
            },
        );
        return;
    }
    if tool == Tool::Train {
        let label = cx.view.prefs.train_label;
        brush(
            cx,
            ui,
            response,
            painter,
            view,
            pointer,
            |from, to, radius, stroke| Command::Paint {
                from,
                to,
                label,
                radius,
                stroke,
            },
        );
        return;
    }
    let cs = &mut cx.view.canvas;
    if response.dragged_by(egui::PointerButton::Primary) {
        if let (Some(p), Some(_)) = (pointer, cs.drag_from_in_image) {
            cs.drag_to_in_image = Some(view.to_image(p));
            if let (Tool::Edit, Some(vertex)) = (tool, cs.editing) {
                let (to, stroke) = (view.to_image(p), cs.strokes);
                cx.commands.push(Command::HandMove { vertex, to, stroke });
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
            release(cx, response, view, image, a, b);
        }
    }
    let cs = &cx.view.canvas;
    if !cs.polygon.is_empty() {
        let mut pts: Vec<Pos2> = cs.polygon.iter().map(|&p| view.to_screen(p)).collect();
        if let Some(h) = response.hover_pos() {
            pts.push(h);
        }
        painter.add(egui::Shape::line(pts, Stroke::new(1.5, Color32::YELLOW)));
    }
}

/// The shapes a click can reach: none where they are not drawn
/// ([`crate::app::Document::shapes_shown`]).
fn shapes_on_screen(doc: &crate::app::Document) -> &[crate::evolution::Shape] {
    if doc.shapes_shown() {
        &doc.shapes
    } else {
        &[]
    }
}

/// A drag starts at image point `at`: the Select tool grabs the shape there, the Edit
/// tool the contour vertex.
fn press(cx: &mut Ctx, ui: &egui::Ui, view: View, at: Point) {
    let (tool, zoom) = (cx.view.prefs.tool, view.zoom);
    let cs = &mut cx.view.canvas;
    cs.drag_from_in_image = Some(at);
    cs.drag_to_in_image = Some(at);
    if tool == Tool::Select {
        cs.moving = hit_shape(shapes_on_screen(cx.doc), at, 6.0 / zoom as f64);
        let moving = cs.moving;
        cx.commands.push(Command::Select(moving));
    }
    if tool == Tool::Edit {
        // Each drag is one stroke (one undo step), whichever vertex leads it.
        cs.strokes = cs.strokes.wrapping_add(1);
        // The vertex under the press (a drag starts a few pixels later) in the frame on
        // screen.
        let at = ui
            .input(|i| i.pointer.press_origin())
            .map_or(at, |s| view.to_image(s));
        cx.commands.push(Command::GrabVertex {
            at,
            tol: 8.0 / zoom as f64,
        });
    }
}

/// The brush (and the Train tool's, which paints strokes): a press starts a stroke (a
/// dab where it is), a drag moves the disc, each frame's movement one command made by
/// `command(from, to, radius, stroke)`; the disc is drawn under the pointer.
fn brush(
    cx: &mut Ctx,
    ui: &egui::Ui,
    response: &egui::Response,
    painter: &egui::Painter,
    view: View,
    pointer: Option<Pos2>,
    command: impl Fn(Point, Point, f64, u32) -> Command,
) {
    let radius = cx.view.prefs.brush_radius;
    let cs = &mut cx.view.canvas;
    cs.drag_from_in_image = None;
    cs.drag_to_in_image = None;
    let pressed = response.drag_started_by(egui::PointerButton::Primary)
        || response.clicked_by(egui::PointerButton::Primary);
    let dragging = response.dragged_by(egui::PointerButton::Primary);
    if let Some(p) = pointer.map(|s| view.to_image(s)) {
        if pressed && cs.brush_at.is_none() {
            cs.strokes = cs.strokes.wrapping_add(1);
            // The stroke starts where the button went down, not where the drag began.
            let start = ui
                .input(|i| i.pointer.press_origin())
                .map_or(p, |s| view.to_image(s));
            cs.brush_at = Some(start);
            cx.commands.push(command(start, start, radius, cs.strokes));
        }
        if let Some(last) = cs.brush_at.filter(|&l| dragging && l != p) {
            cx.commands.push(command(last, p, radius, cs.strokes));
            cs.brush_at = Some(p);
        }
    }
    if !dragging {
        cs.brush_at = None;
    }
    if let Some(h) = response.hover_pos().or(pointer) {
        painter.circle_stroke(
            h,
            radius as f32 * view.zoom,
            Stroke::new(1.5, Color32::from_rgb(255, 230, 120)),
        );
    }
}

/// A press at `a` released at `b`: what it makes with the current tool.
fn release(
    cx: &mut Ctx,
    response: &egui::Response,
    view: View,
    image: &crate::evolution::Field,
    a: Point,
    b: Point,
) {
    let zoom = view.zoom;
    let cs = &mut cx.view.canvas;
    let inside = |p: Point| {
        p.x >= 0.0 && p.y >= 0.0 && p.x <= image.width as f64 && p.y <= image.height as f64
    };
    let command = match cx.view.prefs.tool {
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
            let id = cx.doc.shown_record().and_then(|r| contour_at(&r.rings, b));
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
                shapes_on_screen(cx.doc),
                b,
                6.0 / zoom as f64,
            ))),
        },
        _ => None,
    };
    cx.commands.extend(command);
}

/// The innermost ring of the frame on screen around `at` (a hole inside a region wins).
fn contour_at(rings: &[crate::app::RingView], at: Point) -> Option<u32> {
    rings
        .iter()
        .filter(|r| crate::geometry::winding_number(&r.points, at) != 0)
        .min_by(|a, b| {
            let area = |r: &crate::app::RingView| crate::geometry::signed_area(&r.points).abs();
            area(a).total_cmp(&area(b))
        })
        .map(|r| r.id)
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
