//! Opens the app in a state worth a screenshot, for the README's figures (the window is
//! the real app's; screenshots/train_movie.sh takes them under Xvfb):
//!
//! - `app_shot train IMAGE STROKES.png map|contours`: the Train tool with the strokes of
//!   a label image (0 none, 1 background, 2 object, 3 boundary — the format of
//!   `segment --train`) painted, and either the probability map over the image, or the
//!   contours the taught run produced from the map's seeds;
//! - `app_shot movie MOVIE`: the movie tracked, then the first division's frame shown
//!   with its mother selected in the lineage view;
//! - `app_shot correct MOVIE`: the same frame opened for correction (the Edit tool).

use topocontour::app::{Command, Tool, TopoApp, Training};
use topocontour::evolution::Modality;

struct Shot {
    app: TopoApp,
    /// Track (from the window: its thread wakes the window), then jump to the first
    /// division once tracking has ended.
    jump: bool,
    /// Then open the frame for correction.
    edit: bool,
    asked: bool,
    drawn: bool,
}

impl eframe::App for Shot {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        // After the first frame drawn, when the app knows its window.
        if self.jump && !self.asked && self.drawn {
            self.app.send(Command::Track);
            self.asked = true;
        }
        self.drawn = true;
        let done = self.app.jobs.track.is_none();
        let first = self
            .app
            .doc
            .movie
            .as_ref()
            .and_then(|m| m.tracking.as_ref())
            .filter(|t| t.complete)
            .and_then(|t| t.divisions().next().copied());
        if let (true, true, true, Some(d)) = (self.jump, self.asked, done, first) {
            self.app.send(Command::SeekMovieFrame(d.frame));
            self.app.send(Command::SelectTrack(Some(d.parent)));
            if self.edit {
                self.app.send(Command::SetTool(Tool::Edit));
            }
            self.jump = false;
        }
        self.app.ui(ui);
    }
}

fn fail(why: String) -> ! {
    eprintln!("app_shot: {why}");
    std::process::exit(2)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut app = TopoApp::default();
    let (mut jump, mut edit) = (false, false);
    match args.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        ["train", image, strokes, what] => {
            app.send(Command::OpenImage(image.into()));
            app.send(Command::SetModality(Modality::PhaseContrast));
            app.apply();
            let img = app
                .doc
                .image
                .clone()
                .unwrap_or_else(|| fail(format!("{image}: not opened")));
            let labels = image::open(strokes)
                .unwrap_or_else(|e| fail(format!("{strokes}: {e}")))
                .into_luma8();
            let s = topocontour::learn::Strokes::new(img.width, img.height, labels.into_raw())
                .unwrap_or_else(|e| fail(format!("{strokes}: {e}")));
            app.doc.train = Training::of_strokes(&s);
            if what == "contours" {
                app.send(Command::SetMode(topocontour::evolution::Mode::Preserve));
                app.send(Command::FindSeeds);
                app.send(Command::SetTool(Tool::Select));
                app.send(Command::ShowProbabilities(false));
                app.apply();
                for _ in 0..400 {
                    app.send(Command::Step(20));
                    app.apply();
                    if app.doc.run.as_ref().is_none_or(|r| r.evolver.is_finished()) {
                        break;
                    }
                }
            } else {
                app.send(Command::SetTool(Tool::Train));
                app.apply();
            }
        }
        [kind @ ("movie" | "correct"), movie] => {
            edit = kind == "correct";
            app.send(Command::OpenMovie(movie.into()));
            app.send(Command::SetPolarity(
                topocontour::evolution::Polarity::Bright,
            ));
            app.apply();
            jump = true;
        }
        _ => fail(
            "usage: app_shot train IMAGE STROKES.png map|contours | app_shot movie|correct MOVIE"
                .into(),
        ),
    }
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1280.0, 820.0]),
        ..Default::default()
    };
    let r = eframe::run_native(
        "topocontour",
        options,
        Box::new(move |_| {
            Ok(Box::new(Shot {
                app,
                jump,
                edit,
                asked: false,
                drawn: false,
            }))
        }),
    );
    if let Err(e) = r {
        fail(e.to_string());
    }
}
