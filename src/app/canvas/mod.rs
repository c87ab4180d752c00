//! The canvas: the image with its contrast window, the contours of the frame on screen
//! (each ring in its colour, regions filled with holes left open), the user's shapes,
//! and the motion regions that caused topology events, flashed. Pan with the right or
//! middle button (or the primary button with the Select tool on empty space), zoom with
//! the wheel.

mod layers;
mod tools;
mod train;

pub(in crate::app) use train::label_color;

use layers::{
    compare_layer, contours_layer, image_layer, motion_layer, shapes_layer, tracks_layer,
};
use tools::tools_layer;

use super::{fill, Ctx};
use crate::geometry::Point;
use egui::{Color32, Pos2, Rect, Sense, Vec2};

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
    /// Where the brush was last frame during a stroke.
    brush_at: Option<Point>,
    /// The number of the last stroke (a hand drag or brush stroke): each is one undo step.
    strokes: u32,
    /// The canvas rectangle on screen last frame.
    rect: Option<Rect>,
    /// The fill of the frame recording with this stamp.
    fill_cache: Option<(u64, fill::FillMesh)>,
    /// The probability map and strokes as textures.
    train_textures: train::TrainTextures,
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

impl CanvasState {
    /// Where image point `p` is on screen (as of the last frame drawn).
    pub fn screen_from_image(&self, p: Point) -> Pos2 {
        self.rect.map_or(Pos2::ZERO, |r| r.min)
            + self.offset
            + Vec2::new(p.x as f32, p.y as f32) * self.zoom
    }
}

/// Above this many vertices regions are filled only while playback is paused.
const FILL_WHILE_PLAYING_MAX_VERTICES: usize = 5000;

pub(in crate::app) fn ring_color(id: u32) -> Color32 {
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
pub(super) fn canvas_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    let (response, full_painter) =
        ui.allocate_painter(ui.available_size(), Sense::click_and_drag());
    response.widget_info(|| egui::WidgetInfo::labeled(egui::Role::Canvas, true, "Canvas"));
    // Side by side: the main engine on the left half, the second on the right, both with
    // the same view; shapes can be drawn in either half.
    let split = cx.doc.run_b.is_some() || cx.doc.settings.compare.is_some();
    let full = response.rect;
    let (rect, right) = if split {
        let (l, r) = full.split_left_right_at_fraction(0.5);
        (l, Some(r.shrink2(Vec2::new(1.0, 0.0))))
    } else {
        (full, None)
    };
    let painter = full_painter.with_clip_rect(rect);
    let Some(image) = cx.doc.image.clone() else {
        painter.text(
            rect.center(),
            egui::Align2::CENTER_CENTER,
            "Open an image (or drop one here)",
            egui::FontId::proportional(18.0),
            Color32::GRAY,
        );
        return;
    };
    let view = navigate(
        &mut cx.view.canvas,
        ui,
        &response,
        rect,
        right,
        &image,
        split,
    );
    image_layer(cx, ui, &painter, view, &image);
    train::train_layer(cx, ui, &painter, view, &image);
    if let Some(r) = right {
        compare_layer(cx, &full_painter, &painter, view, r);
    }
    if cx.doc.run.is_none() {
        // A tracked movie frame shows its tracks until a run of its own starts.
        tracks_layer(cx, &painter, view);
    }
    contours_layer(cx, &painter, view);
    motion_layer(cx, &painter, view);
    if cx.doc.shown == 0 {
        // The user's shapes, while they are what is on screen (frame 0).
        shapes_layer(cx, &painter, view);
    }
    tools_layer(cx, ui, &response, &painter, view, &image);
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
