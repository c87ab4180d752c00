//! The Train tool's commands and what ties the probability map to the run: a stroke
//! asks the background trainer for a new map ([`super::train::Trainer`]); a run started
//! while strokes (or a loaded classifier) teach reads the map as its image
//! ([`crate::learn::guide::Guide`], as a taught [`crate::job::Job`] does); when a newer
//! map comes, the run on screen starts again on it (and plays on if it was playing).

use super::train::{teach_now, Key, Source};
use super::{AppError, Command, TopoApp};
use crate::learn::guide::{self, Guide};
use crate::learn::Taught;
use std::path::Path;

impl TopoApp {
    /// The Train tool's commands.
    pub(super) fn train_command(&mut self, c: Command) {
        match c {
            Command::Paint {
                from,
                to,
                label,
                radius,
                ..
            } => {
                let Some(img) = &self.doc.image else { return };
                let size = (img.width, img.height);
                self.doc.train.paint([from, to], radius, label, size);
            }
            Command::SetTrainLabel(l) => self.view.prefs.train_label = l.min(3),
            Command::ShowProbabilities(on) => self.view.prefs.show_probabilities = on,
            Command::ClearStrokes => self.doc.train.clear(),
            Command::SaveClassifier(p) => match self.save_classifier(&p) {
                Ok(()) => self.status.notify(format!("wrote {}", p.display())),
                Err(e) => self.status.error = Some(e),
            },
            Command::LoadClassifier(p) => match crate::io::classifier::read(&p) {
                Ok(c) => {
                    self.doc.train.loaded = Some(std::sync::Arc::new(c));
                    self.doc.train.revision = super::train::next_revision();
                    self.status.notify(format!(
                        "loaded {}: it applies while no strokes are painted",
                        p.display()
                    ));
                }
                Err(e) => self.status.error = Some(AppError::Teach(e.to_string())),
            },
            Command::ClassifierDialog(save) => self.classifier_dialog(save),
            _ => unreachable!("not a train command: {c:?}"),
        }
    }

    /// The key of the map that teaches now (none: nothing teaches).
    pub(super) fn map_key(&self) -> Option<Key> {
        self.doc.train.key(self.doc.image.as_ref()?)
    }

    /// Asks for the map of the strokes on screen, once per revision and image.
    pub(super) fn request_map(&mut self) {
        let Some(key) = self.map_key() else {
            // The Train tool on an image and nothing to train yet: its features now.
            if self.view.prefs.tool == super::Tool::Train {
                if let Some(image) = self.doc.image.clone() {
                    self.jobs.trainer.warm(image, self.view.egui_ctx.clone());
                }
            }
            return;
        };
        if self.jobs.trainer.asked(key) {
            return;
        }
        let Some(image) = self.doc.image.clone() else {
            return;
        };
        let Some(source) = self.doc.train.source(image.width, image.height) else {
            return;
        };
        let (name, wake) = (self.doc.image_name.clone(), self.view.egui_ctx.clone());
        self.jobs.trainer.request(key, image, name, source, wake);
    }

    /// Takes a map the trainer sent; a run taught by an older map starts again on it.
    pub(super) fn poll_map(&mut self) {
        let key = self.map_key();
        let (came, error) = self.jobs.trainer.poll(key);
        if let Some(e) = error {
            self.status.error = Some(AppError::Teach(e));
        }
        let stale = self.doc.run.is_some() && self.doc.taught != key;
        if came && stale && key.is_some() {
            let playing = self.view.playing;
            self.reset_run();
            self.status.notice =
                Some("the probability map changed: the run starts again on it".into());
            if playing {
                self.apply_now(Command::Play);
            }
        }
    }

    /// The map that teaches now: the trainer's, or computed here when it has not come
    /// yet (a run asked for at once). Errors go to the status bar.
    fn taught_now(&mut self) -> Option<(Key, Taught)> {
        let key = self.map_key()?;
        if let Some(m) = self.jobs.trainer.map_of(key) {
            return Some((key, m.taught.clone()));
        }
        let image = self.doc.image.clone()?;
        let source = self.doc.train.source(image.width, image.height)?;
        match teach_now(&image, &self.doc.image_name, source) {
            Ok(t) => {
                self.jobs.trainer.accept(key, t.clone());
                Some((key, t))
            }
            Err(e) => {
                self.status.error = Some(AppError::Teach(e));
                None
            }
        }
    }

    /// The guide a run starting now reads (none: the run reads the image), remembered
    /// as what taught the run.
    pub(super) fn guide_for_run(&mut self) -> Option<Guide> {
        let taught = self.taught_now();
        self.doc.taught = taught.as_ref().map(|(k, _)| *k);
        let (_, t) = taught?;
        let s = &mut self.doc.settings;
        if !s.mode_chosen {
            // As the command line: a taught run keeps the classifier's objects apart.
            s.params.mode = crate::evolution::Mode::default_for(true);
            s.mode_chosen = true;
            self.status.notify(format!(
                "taught run: engine {} keeps touching cells apart (choose Adaptive to let them merge)",
                s.params.mode.name()
            ));
        }
        Some(Guide::new(t.probabilities, self.doc.params()))
    }

    /// The seeds of the map that teaches now: the connected interiors of its object
    /// class (none: nothing teaches).
    pub(super) fn taught_seeds(&mut self) -> Option<Vec<crate::evolution::Shape>> {
        self.taught_now()
            .map(|(_, t)| guide::seeds(&t.probabilities))
    }

    /// What a session records of the teaching: the strokes, or the loaded classifier.
    pub(super) fn session_teaching(&self) -> Option<Source> {
        let img = self.doc.image.as_ref()?;
        self.doc.train.source(img.width, img.height)
    }

    /// Chooses a classifier file in a dialog (or the path field), then saves or loads.
    fn classifier_dialog(&mut self, save: bool) {
        let d = self.dialog().add_filter("classifiers", &["json"]);
        let name = format!(
            "{}.classifier.json",
            super::path_prompt::stem(&self.doc.image_name)
        );
        let chosen = if save {
            d.set_file_name(&name).save_file()
        } else {
            d.pick_file()
        };
        let purpose = super::PathPurpose::Classifier(save);
        match (chosen, save) {
            (Some(p), true) => self.apply_now(Command::SaveClassifier(p)),
            (Some(p), false) => self.apply_now(Command::LoadClassifier(p)),
            (None, true) => self.prompt_path(purpose, name),
            (None, false) => self.prompt_path(purpose, String::new()),
        }
    }

    fn save_classifier(&mut self, path: &Path) -> Result<(), AppError> {
        let Some((_, t)) = self.taught_now() else {
            return Err(AppError::Teach(
                "no classifier yet: paint object (2) and background (1) or boundary (3) strokes with the Train tool".into(),
            ));
        };
        let bytes = crate::io::classifier::to_bytes(&t.classifier);
        crate::io::OutputFiles::prepare(self.doc.image_path.as_deref(), &[path])?
            .commit(vec![bytes])?;
        Ok(())
    }
}
