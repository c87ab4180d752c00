//! The one place the document changes: [`TopoApp::apply_now`] keeps an undo step when the
//! command starts one ([`super::history`]), then hands it to its [`Group`]'s handler.
//! The shape and parameter handlers are here; hand edits, playback and files have their
//! own modules.

use super::command::Group;
use super::{auto_contrast, Command, Settings, TopoApp};
use crate::evolution::{find_seeds, ForceWeights, Shape};
use crate::geometry::Point;

impl TopoApp {
    /// Applies one command.
    pub(super) fn apply_now(&mut self, c: Command) {
        match &c {
            Command::OpenImage(p) | Command::OpenSession(p) | Command::OpenMovie(p) => {
                if !std::mem::take(&mut self.view.open_confirmed) {
                    if let Some(what) = self.own_unsaved_work() {
                        self.view.pending_open = Some(c.clone());
                        self.view.question = Some(super::Question::Open(what));
                        return;
                    }
                }
                let name = p.file_name().map_or_else(
                    || p.display().to_string(),
                    |n| n.to_string_lossy().into_owned(),
                );
                self.open_file(c, name);
            }
            _ => {
                if self.history.starts_step(&c) {
                    self.history.push(self.doc.clone());
                    self.unsaved = true;
                }
                self.unsaved |= matches!(
                    c,
                    Command::Undo
                        | Command::Redo
                        | Command::Track
                        | Command::TrackConfirmed
                        | Command::ContinueTrack
                        | Command::Retrack(_)
                );
                self.dispatch(c);
            }
        }
    }

    /// Opens a file (`c`, named `name`): an undo step when it opened, nothing changed when
    /// it did not (a session whose image opened but whose job failed included). The file's
    /// document has nothing to save; work not saved before it stays in Undo, and the
    /// document says so ([`super::Document::replaced`]), carried through Undo and Redo.
    fn open_file(&mut self, c: Command, name: String) {
        let (before, unsaved) = (self.doc.clone(), self.unsaved);
        let had_work = self.unsaved_work().is_some();
        // An earlier error goes (a success clears it anyway), so one now is this one's.
        self.status.error = None;
        self.history.starts_step(&c);
        self.dispatch(c);
        if self.status.error.is_some() {
            self.doc = before;
            self.unsaved = unsaved;
            return;
        }
        self.history.push(before);
        self.unsaved = false;
        self.doc.replaced = had_work.then_some(name);
    }

    /// Hands one command to its group's handler.
    fn dispatch(&mut self, c: Command) {
        match c.group() {
            Group::Hand => self.hand_edit(c),
            Group::History => self.undo_redo(c),
            Group::Shapes => self.edit_shapes(c),
            Group::Playback => self.playback(c),
            Group::Parameters => self.set_parameter(c),
            Group::Files => self.files(c),
            Group::Movie => self.movie_command(c),
            Group::Train => self.train_command(c),
        }
    }

    /// The user's shapes (the initialisation): a change drops the runs.
    fn edit_shapes(&mut self, c: Command) {
        let doc = &mut self.doc;
        match c {
            Command::AddShape(s) => {
                // The sample's wrap would swallow a seed clicked inside it: it makes way
                // (Undo brings it back).
                if doc.sample_wrap && matches!(s, Shape::Disk { .. }) {
                    doc.shapes.clear();
                    self.status.notify(
                        "the sample's wrap rectangle made way for your seed (Undo brings it back)"
                            .into(),
                    );
                }
                doc.sample_wrap = false;
                doc.shapes.push(s);
                self.view.selected = Some(doc.shapes.len() - 1);
            }
            Command::MoveShape { index, by } => {
                let Some(s) = doc.shapes.get_mut(index) else {
                    return;
                };
                *s = moved(s, by);
            }
            Command::DeleteShape(i) => {
                if i >= doc.shapes.len() {
                    return;
                }
                doc.shapes.remove(i);
                self.view.selected = None;
            }
            Command::Select(i) => {
                self.view.selected = i;
                return;
            }
            Command::WrapBorder(m) => {
                let Some(img) = &doc.image else { return };
                let (w, h) = (img.width as f64, img.height as f64);
                let m = m.min(0.25 * w.min(h));
                doc.shapes.push(Shape::Rect {
                    min: Point::new(m, m),
                    max: Point::new(w - m, h - m),
                });
            }
            Command::FindSeeds => {
                let Some(img) = &doc.image else { return };
                let p = &doc.settings.params;
                let (img, p) = (img.clone(), (p.polarity, p.modality));
                let found = match self.taught_seeds() {
                    Some(seeds) => seeds,
                    None => find_seeds(&img, p.0, p.1),
                };
                let doc = &mut self.doc;
                self.status
                    .notify(format!("found {} objects: seeds placed", found.len()));
                doc.shapes.extend(found);
                doc.found_seeds = true;
            }
            _ => unreachable!("not a shapes command: {c:?}"),
        }
        self.reset_run();
    }

    /// New forces for the runs on screen: each goes on from the frame shown (later frames
    /// are computed again; the change is one of the run's edits, saved with a session).
    fn set_forces(&mut self, weights: ForceWeights, step: f64) {
        let p = &mut self.doc.settings.params;
        (p.weights, p.step) = (weights, step);
        let shown = self.doc.shown;
        let mut failed = None;
        for run in [self.doc.run.as_mut(), self.doc.run_b.as_mut()]
            .into_iter()
            .flatten()
        {
            let at = shown.min(run.last());
            run.edit_at(at, |ev| failed = ev.set_forces(weights, step).err());
        }
        if let Some(e) = failed {
            self.status.error = Some(e.into());
        } else if self.doc.run.is_some() {
            self.status.notify(format!(
                "forces changed at frame {shown}: the run goes on from here with them"
            ));
        }
    }

    /// The tool and the parameters of the run.
    fn set_parameter(&mut self, c: Command) {
        let s = &mut self.doc.settings;
        match c {
            Command::SetTool(t) => self.view.prefs.tool = t,
            Command::SetModality(_)
            | Command::SetOpenHoles(_)
            | Command::SetPolarity(_)
            | Command::SetMode(_)
            | Command::SetCompare(_)
            | Command::SetBroadPhase(_) => {
                match c {
                    Command::SetModality(m) => s.params.modality = m,
                    Command::SetOpenHoles(on) => s.params.open_holes = on,
                    Command::SetPolarity(p) => s.params.polarity = p,
                    Command::SetMode(mode) => {
                        s.params.mode = mode;
                        s.mode_chosen = true;
                    }
                    Command::SetCompare(mode) => s.compare = mode,
                    Command::SetBroadPhase(kind) => s.params.broad_phase = kind,
                    _ => unreachable!(),
                }
                // A parameter the run was started with: it starts again.
                self.reset_run();
            }
            Command::SetForces { weights, step } => self.set_forces(weights, step),
            Command::SetMinArea(a) => s.params.min_area = a,
            Command::SetContrast(window) => s.contrast = window,
            Command::SetPixelSize(p) => self.doc.stack.pixel = p,
            Command::SetPage(n) => self.set_page(n),
            Command::ResetParameters => {
                let d = Settings::default();
                if let Some(img) = &self.doc.image {
                    s.contrast = auto_contrast(img);
                }
                s.params.min_area = d.params.min_area;
                self.set_forces(d.params.weights, d.params.step);
            }
            _ => unreachable!("not a parameter command: {c:?}"),
        }
    }

    /// Shows page `n` of the image's file: the shapes and settings stay, the run starts
    /// again.
    pub(super) fn set_page(&mut self, n: usize) {
        let Some(path) = self.doc.image_path.clone() else {
            return;
        };
        match crate::io::load_image_page(&path, n) {
            Ok((f, _)) => {
                self.doc.image = Some(std::sync::Arc::new(f));
                self.doc.stack.page = n;
                self.reset_run();
            }
            Err(e) => self.status.error = Some(e.into()),
        }
    }
}

/// `s` moved by `by`.
fn moved(s: &Shape, by: Point) -> Shape {
    match s.clone() {
        Shape::Disk { center, radius } => Shape::Disk {
            center: center + by,
            radius,
        },
        Shape::Rect { min, max } => Shape::Rect {
            min: min + by,
            max: max + by,
        },
        Shape::Polygon(p) => Shape::Polygon(p.into_iter().map(|q| q + by).collect()),
    }
}
