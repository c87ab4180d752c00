//! The built-in path field: where no desktop portal answers a file dialog (a bare X
//! session, a remote desktop), or the user cancelled it, the path can be typed instead.

use super::command::Command;
use super::{Ctx, TopoApp};
use crate::io::export::Format;
use std::path::PathBuf;

/// What a typed path is for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathPurpose {
    /// An image to open.
    OpenImage,
    /// A file to export to.
    Export(Format),
    /// A session file to write.
    SaveSession,
    /// A session file to open.
    OpenSession,
    /// A folder of images to segment.
    ApplyToFolder,
    /// A movie to open (a TIFF or a folder).
    OpenMovie,
    /// A folder for the tracking result.
    ExportCtc,
    /// A classifier file to save (true) or load.
    Classifier(bool),
}

impl PathPurpose {
    /// The window's title.
    fn title(self) -> &'static str {
        match self {
            PathPurpose::OpenImage => "Open image",
            PathPurpose::Export(_) => "Export to",
            PathPurpose::SaveSession => "Save session as",
            PathPurpose::OpenSession => "Open session",
            PathPurpose::ApplyToFolder => "Apply to folder",
            PathPurpose::OpenMovie => "Open movie",
            PathPurpose::ExportCtc => "Export tracks (CTC) to folder",
            PathPurpose::Classifier(true) => "Save classifier as",
            PathPurpose::Classifier(false) => "Load classifier",
        }
    }
    /// The command the path completes.
    fn command(self, path: PathBuf) -> Command {
        match self {
            PathPurpose::OpenImage => Command::OpenImage(path),
            PathPurpose::Export(kind) => Command::Export(kind, path),
            PathPurpose::SaveSession => Command::SaveSession(path),
            PathPurpose::OpenSession => Command::OpenSession(path),
            PathPurpose::ApplyToFolder => Command::ApplyToFolder(path),
            PathPurpose::OpenMovie => Command::OpenMovie(path),
            PathPurpose::ExportCtc => Command::ExportCtc(path),
            PathPurpose::Classifier(true) => Command::SaveClassifier(path),
            PathPurpose::Classifier(false) => Command::LoadClassifier(path),
        }
    }
}

/// An open path field.
#[derive(Clone, Debug)]
pub struct PathPrompt {
    /// What the path is for.
    pub purpose: PathPurpose,
    /// The path typed so far.
    pub text: String,
}

/// The name of `image` without its extension (and without " (sample)").
pub fn stem(image: &str) -> String {
    let name = image.trim_end_matches(" (sample)");
    let stem = crate::io::folder::stem(std::path::Path::new(name));
    if stem.is_empty() {
        "contours".into()
    } else {
        stem
    }
}

impl TopoApp {
    /// Opens the path field for `purpose`, starting from the last folder and `name`.
    pub(super) fn prompt_path(&mut self, purpose: PathPurpose, name: String) {
        let dir = self.view.prefs.last_dir.clone().unwrap_or_default();
        let text = if name.is_empty() && dir.as_os_str().is_empty() {
            String::new()
        } else {
            dir.join(name).display().to_string()
        };
        self.view.path_prompt = Some(PathPrompt { purpose, text });
        self.status
            .notify("no file chosen in a dialog: type the path instead".into());
    }
}

/// The path field's window, while one is open.
pub(super) fn path_prompt_ui(cx: &mut Ctx, ctx: &egui::Context) {
    let Some(prompt) = cx.view.path_prompt.as_mut() else {
        return;
    };
    let (mut done, mut cancel) = (false, false);
    egui::Window::new(prompt.purpose.title())
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
        .show(ctx, |ui| {
            ui.label("Path (absolute, or relative to the folder topocontour started in):");
            let field = ui.add(
                egui::TextEdit::singleline(&mut prompt.text)
                    .desired_width(480.0)
                    .hint_text("/path/to/file"),
            );
            if !field.has_focus() && !field.lost_focus() {
                field.request_focus();
            }
            let enter = ui.input(|i| i.key_pressed(egui::Key::Enter));
            ui.horizontal(|ui| {
                done = ui
                    .button("OK")
                    .on_hover_text("use this path (Enter)")
                    .clicked()
                    || enter;
                cancel = ui.button("Cancel").on_hover_text("close (Esc)").clicked();
            });
        });
    if done && !prompt.text.trim().is_empty() {
        let command = prompt.purpose.command(PathBuf::from(prompt.text.trim()));
        cx.view.path_prompt = None;
        cx.send(command);
    } else if cancel || ctx.input(|i| i.key_pressed(egui::Key::Escape)) {
        cx.view.path_prompt = None;
    }
}
