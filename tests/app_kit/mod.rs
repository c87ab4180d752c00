//! What the app's kittest files share: the harness around the real `TopoApp::ui`, the
//! test images, and small steps (a click on the canvas, a hand drag, a saved session).
#![allow(dead_code)] // each test file uses some of these

use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, TopoApp};
use topocontour::evolution::Shape;

pub fn harness(app: TopoApp) -> Harness<'static, TopoApp> {
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut TopoApp| app.ui(ui), app)
}

pub fn case_image(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/cases")
        .join(name)
        .join("image.png")
}

/// The app on the bundled sample after `frames` frames of its wrap, drawn once.
pub fn sample_after(frames: usize) -> Harness<'static, TopoApp> {
    let mut app = TopoApp::with_sample();
    app.send(Command::Step(frames));
    let mut h = harness(app);
    h.step();
    h
}

/// Clicks the canvas at `pos` (press and release on successive frames).
pub fn click_at(h: &mut Harness<'_, TopoApp>, pos: egui::Pos2) {
    h.hover_at(pos);
    h.step();
    h.drag_at(pos);
    h.step();
    h.drop_at(pos);
    h.step();
    h.step();
}

pub fn now(app: &mut TopoApp, c: Command) {
    app.send(c);
    app.apply();
}

/// The app on the bridge_merge image, bright objects, with seed disks (x, y, r).
pub fn bright_bridge_with_seeds(disks: &[(f64, f64, f64)]) -> TopoApp {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    app.send(Command::SetPolarity(
        topocontour::evolution::Polarity::Bright,
    ));
    for &(x, y, r) in disks {
        app.send(Command::AddShape(Shape::Disk {
            center: topocontour::Point::new(x, y),
            radius: r,
        }));
    }
    app
}

#[path = "../common/scratch.rs"]
mod scratch;
pub use scratch::Scratch;

/// The path `name` in a fresh temporary folder, removed when the guard is dropped.
pub fn temp(name: &str) -> Scratch {
    Scratch::file(name)
}

/// Saves the session of `h` to a temporary file, checking no error showed; its path.
pub fn save_session(h: &mut Harness<'_, TopoApp>, name: &str) -> Scratch {
    let path = temp(name);
    h.state_mut().send(Command::SaveSession(path.to_path_buf()));
    h.step();
    assert_no_error(h);
    path
}

/// The evolver of the run on screen.
pub fn evolver(app: &TopoApp) -> &topocontour::evolution::Evolver {
    &app.doc.run.as_ref().expect("a run").evolver
}

/// How many contours the run on screen has now.
pub fn contour_count(h: &Harness<'_, TopoApp>) -> usize {
    evolver(h.state()).contours().contour_count()
}

/// Whether the event log holds an event that `is` accepts.
pub fn logged(h: &Harness<'_, TopoApp>, is: impl Fn(&topocontour::TopologyEvent) -> bool) -> bool {
    h.state().doc.events().iter().any(|(_, e)| is(e))
}

/// Drags the contour vertex nearest to `from` to the right in `steps` hand moves of
/// 4 px, one frame drawn after each.
pub fn drag_right(h: &mut Harness<'_, TopoApp>, from: topocontour::Point, steps: usize) {
    let v = vertex_near(h.state(), from);
    for k in 1..=steps {
        h.state_mut().send(Command::HandMove {
            vertex: v,
            to: topocontour::Point::new(from.x + 4.0 * k as f64, from.y),
            stroke: 1,
        });
        h.step();
    }
}

/// The vertex of the run's contours nearest to `p`.
pub fn vertex_near(app: &TopoApp, p: topocontour::Point) -> u32 {
    let set = evolver(app).contours();
    set.vertices()
        .min_by(|&a, &b| set.position(a).dist(p).total_cmp(&set.position(b).dist(p)))
        .unwrap()
}

/// The notice in the status bar (empty if none).
pub fn notice(h: &Harness<'_, TopoApp>) -> String {
    h.state().status.notice.clone().unwrap_or_default()
}

/// The number of contours in the frame on screen.
pub fn contours_now(h: &Harness<'_, TopoApp>) -> usize {
    h.state().shown_record().unwrap().contours
}

/// Steps in chunks until the run on screen has finished.
pub fn run_to_end(h: &mut Harness<'_, TopoApp>) {
    for _ in 0..100 {
        h.state_mut().send(Command::Step(50));
        h.step();
        if h.state().doc.run.as_ref().unwrap().evolver.is_finished() {
            break;
        }
    }
    h.step();
}

/// Clicks the widget labelled `label`, then draws a frame.
pub fn click_label(h: &mut Harness<'_, TopoApp>, label: &str) {
    h.get_by_label(label).click();
    h.step();
}

/// Asserts the status bar shows no error.
pub fn assert_no_error(h: &Harness<'_, TopoApp>) {
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
}

/// Types `text` into the path field for `purpose` and presses OK.
pub fn type_path(
    h: &mut Harness<'_, TopoApp>,
    purpose: topocontour::app::PathPurpose,
    text: String,
) {
    h.state_mut().view.path_prompt = Some(topocontour::app::PathPrompt { purpose, text });
    h.step();
    h.step();
    h.get_by_label("OK").click();
    h.step();
    h.step();
}

/// Asks the window to close as the title bar's close button does; whether it closes
/// (the app did not cancel it).
pub fn close_window(h: &mut Harness<'_, TopoApp>) -> bool {
    h.input_mut()
        .viewports
        .entry(egui::ViewportId::ROOT)
        .or_default()
        .events
        .push(egui::ViewportEvent::Close);
    h.step();
    let closes = !sent(h, &egui::ViewportCommand::CancelClose);
    h.step(); // a window shows from its second frame
    closes
}

/// Whether the last frame sent `command` to the window.
pub fn sent(h: &Harness<'_, TopoApp>, command: &egui::ViewportCommand) -> bool {
    h.output().viewport_output[&egui::ViewportId::ROOT]
        .commands
        .contains(command)
}
