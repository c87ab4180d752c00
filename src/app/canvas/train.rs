//! The Train tool's layers: the probability map (object green, boundary red,
//! background blue, blended by probability) and the strokes painted, each a texture
//! made again only when its map or its strokes change.

use super::View;
use crate::app::Ctx;
use crate::evolution::Field;
use crate::learn::{BACKGROUND, BOUNDARY, OBJECT};
use egui::{Color32, Pos2, Rect};

/// The colour of stroke label `l` (0: none).
pub(in crate::app) fn label_color(l: u8) -> Color32 {
    match l {
        BACKGROUND => Color32::from_rgb(60, 110, 255),
        OBJECT => Color32::from_rgb(40, 220, 70),
        BOUNDARY => Color32::from_rgb(255, 50, 50),
        _ => Color32::TRANSPARENT,
    }
}

/// The textures of the map and the strokes, with what they were made from.
#[derive(Default)]
pub struct TrainTextures {
    /// The map's key, whether it is the preview, and its texture.
    map: Option<((crate::app::train::Key, bool), egui::TextureHandle)>,
    strokes: Option<(u64, egui::TextureHandle)>,
}

/// The probability map (when shown) and, with the Train tool, the strokes.
pub(super) fn train_layer(
    cx: &mut Ctx,
    ui: &egui::Ui,
    painter: &egui::Painter,
    view: View,
    image: &std::sync::Arc<Field>,
) {
    let rect = Rect::from_min_max(
        view.to_screen(crate::geometry::Point::new(0.0, 0.0)),
        view.to_screen(crate::geometry::Point::new(
            image.width as f64,
            image.height as f64,
        )),
    );
    let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
    let here = std::sync::Arc::as_ptr(image) as usize;
    // The preview of the strokes now painted until their map comes; else the newest
    // map of this image (while a newer one is trained).
    let key = cx.doc.train.key(image);
    let preview = key.and_then(|k| cx.jobs.trainer.preview_of(k).map(|p| (k, p)));
    let map = cx
        .jobs
        .trainer
        .map
        .as_ref()
        .filter(|m| m.key.1 == here && key.is_some());
    let shown = match (preview, map) {
        (Some((k, p)), _) => Some(((k, true), &**p)),
        (None, Some(m)) => Some(((m.key, false), &m.taught.probabilities)),
        (None, None) => None,
    };
    let tex = &mut cx.view.canvas.train_textures;
    if let Some((what, p)) = shown.filter(|_| cx.view.prefs.show_probabilities) {
        if tex.map.as_ref().is_none_or(|(k, _)| *k != what) {
            let (o, d, b) = (p.of(OBJECT), p.of(BOUNDARY), p.of(BACKGROUND));
            let px = |k: usize| {
                let c = |v: f32| (v.clamp(0.0, 1.0) * 255.0) as u8;
                Color32::from_rgba_unmultiplied(c(d[k]), c(o[k]), c(b[k]), 120)
            };
            let pixels = (0..p.width * p.height).map(px).collect();
            let img = egui::ColorImage::new([p.width, p.height], pixels);
            let h = ui
                .ctx()
                .load_texture("probabilities", img, egui::TextureOptions::NEAREST);
            tex.map = Some((what, h));
        }
        if let Some(((_, half), h)) = &tex.map {
            // A preview's pixel (x, y) is the image's (2x, 2y): its texels are 2×2
            // pixels, and its last ones overhang an odd side by half a texel.
            let r = if *half {
                let (pw, ph) = (
                    image.width.div_ceil(2) as f32 * 2.0 / image.width as f32,
                    image.height.div_ceil(2) as f32 * 2.0 / image.height as f32,
                );
                Rect::from_min_size(rect.min, egui::vec2(rect.width() * pw, rect.height() * ph))
            } else {
                rect
            };
            painter.image(h.id(), r, uv, Color32::WHITE);
        }
    }
    let train = &cx.doc.train;
    if cx.view.prefs.tool != crate::app::Tool::Train
        || !train.painted()
        || train.labels.len() != image.width * image.height
    {
        return;
    }
    if tex
        .strokes
        .as_ref()
        .is_none_or(|(r, _)| *r != train.revision)
    {
        let pixels = train
            .labels
            .iter()
            .map(|&l| label_color(l).gamma_multiply(0.85))
            .collect();
        let img = egui::ColorImage::new([image.width, image.height], pixels);
        let h = ui
            .ctx()
            .load_texture("strokes", img, egui::TextureOptions::NEAREST);
        tex.strokes = Some((train.revision, h));
    }
    if let Some((_, h)) = &tex.strokes {
        painter.image(h.id(), rect, uv, Color32::WHITE);
    }
}
