//! "Apply to folder…": every image of a folder segmented with the shapes and parameters
//! on screen, on a background thread so the window stays responsive, with a progress bar
//! and Cancel in the status bar. Outputs go to a `topocontour` folder inside the input
//! folder: `NAME.json` and `NAME.csv` per image and `summary.csv` (as `topocontour
//! batch` writes them; see [`crate::io::folder`]). When the user placed seeds with Find
//! seeds (or drew no shape), each image gets one seed per object found in it, as `batch
//! --auto-seeds` does: this image's seeds would miss every object of another image.

use super::TopoApp;
use crate::io::folder::{list_images, FolderJob, SUMMARY_HEADER};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

/// A folder being segmented.
pub struct FolderRun {
    /// Images in all.
    pub total: usize,
    /// Images finished (written or failed).
    pub done: Arc<AtomicUsize>,
    cancel: Arc<AtomicBool>,
    /// Where the outputs go.
    pub out: PathBuf,
    handle: Option<std::thread::JoinHandle<FolderResult>>,
}

/// What a folder run did: images written, failures (one line each), cancelled or not.
type FolderResult = (usize, Vec<String>, bool);

impl FolderRun {
    /// Asks the run to stop after the image in progress.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::SeqCst);
    }
}

impl TopoApp {
    /// Starts segmenting every image of `dir` in the background.
    pub(super) fn apply_to_folder(&mut self, dir: &Path) {
        if self.jobs.folder.is_some() {
            self.status
                .notify("a folder is already being segmented".into());
            return;
        }
        let images = match list_images(dir) {
            Ok(i) if !i.is_empty() => i,
            Ok(_) => {
                self.status.notify(format!(
                    "{} holds no PNG, JPEG or TIFF image",
                    dir.display()
                ));
                return;
            }
            Err(e) => {
                self.status
                    .notify(format!("cannot read {}: {e}", dir.display()));
                return;
            }
        };
        let out = dir.join("topocontour");
        if let Err(e) = std::fs::create_dir_all(&out) {
            self.status
                .notify(format!("cannot create {}: {e}", out.display()));
            return;
        }
        let doc = &self.doc;
        // Seeds found in this image fit no other: each image gets its own.
        let shapes = if doc.found_seeds {
            Vec::new()
        } else {
            doc.shapes.clone()
        };
        let job = FolderJob {
            job: crate::job::Job {
                auto_seeds: shapes.is_empty(),
                ..crate::job::Job::new(PathBuf::new(), shapes, doc.params().clone())
            },
            out: out.clone(),
        };
        let done = Arc::new(AtomicUsize::new(0));
        let cancel = Arc::new(AtomicBool::new(false));
        let total = images.len();
        let handle = {
            let (done, cancel) = (done.clone(), cancel.clone());
            std::thread::spawn(move || {
                let (mut rows, mut ok, mut failed) = (String::from(SUMMARY_HEADER), 0, Vec::new());
                for img in &images {
                    if cancel.load(Ordering::SeqCst) {
                        break;
                    }
                    match job.run_one(img) {
                        Ok(lines) => {
                            ok += 1;
                            lines.iter().for_each(|l| rows.push_str(l));
                        }
                        Err(e) => failed.push(format!("{}: {e}", img.display())),
                    }
                    done.fetch_add(1, Ordering::SeqCst);
                }
                if let Err(e) =
                    crate::io::write_atomic(&job.out.join("summary.csv"), rows.as_bytes())
                {
                    failed.push(e.to_string());
                }
                (ok, failed, cancel.load(Ordering::SeqCst))
            })
        };
        self.jobs.folder = Some(FolderRun {
            total,
            done,
            cancel,
            out,
            handle: Some(handle),
        });
        self.status
            .notify(format!("segmenting {total} images of {}", dir.display()));
    }

    /// Collects a finished folder run: what it wrote, in the status bar.
    pub(super) fn poll_folder(&mut self, ctx: &egui::Context) {
        let Some(run) = self.jobs.folder.as_mut() else {
            return;
        };
        if !run.handle.as_ref().is_some_and(|h| h.is_finished()) {
            // Keep the progress bar moving while nothing else repaints.
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
            return;
        }
        let out = run.out.clone();
        let result = run.handle.take().map(|h| h.join());
        self.jobs.folder = None;
        match result {
            Some(Ok((ok, failed, cancelled))) => {
                let mut text = format!("wrote {ok} images and summary.csv to {}", out.display());
                if cancelled {
                    text.push_str(" (cancelled)");
                }
                if let Some(first) = failed.first() {
                    text.push_str(&format!("; {} failed, first: {first}", failed.len()));
                }
                self.status.notify(text);
            }
            _ => self
                .status
                .notify("the folder run stopped unexpectedly".into()),
        }
    }
}
