//! The Train tool's row: the legend of the three labels (keys 1–3, and 0 to erase) in
//! their overlay colours, the probability map's switch, Clear, Save and Load classifier,
//! and what the background trainer is doing.

use crate::app::{Command, Ctx};
use crate::learn::{BACKGROUND, BOUNDARY, OBJECT};

/// The labels as the legend lists them.
const LABELS: [(u8, &str, &str); 4] = [
    (BACKGROUND, "1 background", "paint background (key 1): blue in the map"),
    (OBJECT, "2 object", "paint object interiors (key 2): green in the map"),
    (BOUNDARY, "3 boundary", "paint the boundary between touching objects (key 3): red in the map; it is what keeps touching cells apart"),
    (0, "0 erase", "erase strokes (key 0)"),
];

/// The Train tool's row of the tool bar.
pub(in crate::app) fn train_ui(cx: &mut Ctx, ui: &mut egui::Ui) {
    ui.label("Train:");
    let current = cx.view.prefs.train_label;
    for (label, name, tip) in LABELS {
        let (rect, _) = ui.allocate_exact_size(egui::vec2(12.0, 12.0), egui::Sense::hover());
        let colour = crate::app::canvas::label_color(label);
        ui.painter().rect_filled(rect, 2.0, colour);
        if label == 0 {
            ui.painter().rect_stroke(
                rect,
                2.0,
                (1.0, egui::Color32::GRAY),
                egui::StrokeKind::Inside,
            );
        }
        if ui
            .selectable_label(current == label, name)
            .on_hover_text(tip)
            .clicked()
        {
            cx.send(Command::SetTrainLabel(label));
        }
    }
    let mut show = cx.view.prefs.show_probabilities;
    if ui
        .checkbox(&mut show, "probability map (P)")
        .on_hover_text("the classifier's probabilities over the image: object green, boundary red, background blue")
        .changed()
    {
        cx.send(Command::ShowProbabilities(show));
    }
    let painted = cx.doc.train.painted();
    if ui
        .add_enabled(painted, egui::Button::new("Clear strokes"))
        .on_hover_text("wipe every stroke (undoable)")
        .clicked()
    {
        cx.send(Command::ClearStrokes);
    }
    let tip = "write the classifier trained on these strokes, to apply it to other images (Load classifier, or topocontour segment/batch --classifier)";
    if ui.button("Save classifier…").on_hover_text(tip).clicked() {
        cx.send(Command::ClassifierDialog(true));
    }
    let tip = "read a classifier file: it applies while no strokes are painted, and stays when another image opens";
    if ui.button("Load classifier…").on_hover_text(tip).clicked() {
        cx.send(Command::ClassifierDialog(false));
    }
    state_ui(cx, ui);
}

/// What the trainer is doing, or what the strokes still need.
fn state_ui(cx: &Ctx, ui: &mut egui::Ui) {
    let trainer = &cx.jobs.trainer;
    let train = &cx.doc.train;
    if !train.trainable() && train.loaded.is_none() {
        ui.label("paint object (2) and background (1) or boundary (3) to train");
    } else if trainer.busy() {
        ui.spinner();
        let preview = cx
            .doc
            .image
            .as_ref()
            .and_then(|i| train.key(i))
            .is_some_and(|k| trainer.preview_of(k).is_some());
        if preview {
            ui.label("preview (½ resolution), full map…")
                .on_hover_text("the new classifier's probabilities at every other pixel; the full map replaces it, and the contours read only that");
        } else {
            ui.label("training…");
        }
    } else if let Some(ms) = trainer.latency_ms {
        let preview = trainer
            .preview_ms
            .map(|p| format!("preview in {p:.0} ms, "))
            .unwrap_or_default();
        ui.label(format!("{preview}map updated in {ms:.0} ms"))
            .on_hover_text(
            "from the stroke to the map on screen (features of the image, training, prediction)",
        );
    } else if train.loaded.is_some() && !train.trainable() {
        ui.label("the loaded classifier applies");
    }
}
