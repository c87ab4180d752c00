//! The Train tool driven headless with egui_kittest (issue 25): its labels (keys 1–3,
//! the legend, the brush size), a stroke painted on the canvas updating the probability
//! map in the background, Undo of a stroke, the run on the map, strokes through a saved
//! and reopened session, Save and Load classifier. The image is made here: two bright
//! disks on a dark, textured background.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, Tool, TopoApp};
use topocontour::geometry::Point;
use topocontour::learn::{BACKGROUND, OBJECT};

/// A 128×128 image: disks of radius 20 at (40, 64) and (90, 64), written once per name.
fn disks_png(name: &str) -> Scratch {
    let img = image::GrayImage::from_fn(128, 128, |x, y| {
        let d = |cx: f64, cy: f64| {
            ((x as f64 + 0.5 - cx).powi(2) + (y as f64 + 0.5 - cy).powi(2)).sqrt()
        };
        let inside = d(40.0, 64.0) < 20.0 || d(90.0, 64.0) < 20.0;
        let texture = ((x * 7 + y * 13) % 9) as u8;
        image::Luma([if inside { 190 + texture } else { 50 + texture }])
    });
    let path = temp(name);
    img.save(&path).unwrap();
    path
}

/// The app on the disks with the Train tool chosen, drawn once.
fn train_app(name: &str) -> (Harness<'static, TopoApp>, Scratch) {
    let path = disks_png(name);
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path.to_path_buf()));
    app.send(Command::SetPolarity(
        topocontour::evolution::Polarity::Bright,
    ));
    let mut h = harness(app);
    h.step();
    click_label(&mut h, "Train");
    h.step();
    assert_eq!(h.state().view.prefs.tool, Tool::Train);
    (h, path)
}

/// Drags across the canvas from image point `a` to `b` (a stroke of the tool on).
fn stroke(h: &mut Harness<'_, TopoApp>, a: Point, b: Point) {
    let (sa, sb) = (
        h.state().screen_from_image(a),
        h.state().screen_from_image(b),
    );
    h.hover_at(sa);
    h.step();
    h.drag_at(sa);
    h.step();
    for k in 1..=6 {
        h.hover_at(sa + (sb - sa) * (k as f32 / 6.0));
        h.step();
    }
    h.drop_at(sb);
    h.step();
    h.step();
}

/// An object stroke in the left disk and a background stroke along the top.
fn paint_both(h: &mut Harness<'_, TopoApp>) {
    h.key_press(egui::Key::Num2);
    h.step();
    stroke(h, Point::new(34.0, 64.0), Point::new(46.0, 64.0));
    h.key_press(egui::Key::Num1);
    h.step();
    stroke(h, Point::new(10.0, 10.0), Point::new(118.0, 10.0));
}

/// Draws frames until the map of the strokes on screen has come (at most a minute).
fn wait_for_map(h: &mut Harness<'_, TopoApp>) {
    let start = std::time::Instant::now();
    loop {
        let app = h.state();
        let key = app.doc.train.key(app.doc.image.as_ref().unwrap());
        if key.is_some() && app.jobs.trainer.map_of(key.unwrap()).is_some() {
            break;
        }
        assert!(start.elapsed().as_secs() < 60, "no map came");
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    h.step();
}

/// P(label) at pixel (x, y) of the map on screen.
fn prob(h: &Harness<'_, TopoApp>, label: u8, x: usize, y: usize) -> f32 {
    let p = &h
        .state()
        .jobs
        .trainer
        .map
        .as_ref()
        .unwrap()
        .taught
        .probabilities;
    p.of(label)[y * p.width + x]
}

#[test]
fn the_train_tool_has_keys_a_legend_and_a_brush_size() {
    let (mut h, _image) = train_app("keys.png");
    for label in [
        "1 background",
        "2 object",
        "3 boundary",
        "0 erase",
        "probability map (P)",
    ] {
        h.get_by_label(label);
    }
    h.key_press(egui::Key::Num3);
    h.step();
    assert_eq!(h.state().view.prefs.train_label, 3);
    h.key_press(egui::Key::Num1);
    h.step();
    assert_eq!(h.state().view.prefs.train_label, BACKGROUND);
    click_label(&mut h, "2 object");
    assert_eq!(h.state().view.prefs.train_label, OBJECT);
    let r = h.state().view.prefs.brush_radius;
    h.get_by_label_contains("brush radius");
    h.key_press(egui::Key::CloseBracket);
    h.step();
    assert!(
        h.state().view.prefs.brush_radius > r,
        "] makes the brush larger"
    );
    assert!(h.get_by_label_contains("paint object (2)").rect().width() > 0.0);
    h.key_press(egui::Key::P);
    h.step();
    assert!(!h.state().view.prefs.show_probabilities, "P hides the map");
}

#[test]
fn the_train_tool_computes_the_features_before_the_first_stroke() {
    let (mut h, _image) = train_app("warm.png");
    assert!(!h.state().doc.train.painted(), "no stroke yet");
    let start = std::time::Instant::now();
    loop {
        let app = h.state();
        if app
            .jobs
            .trainer
            .features_ready(app.doc.image.as_ref().unwrap())
        {
            break;
        }
        assert!(start.elapsed().as_secs() < 60, "no features came");
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    // The first map then reads those features: it still comes, and is right.
    paint_both(&mut h);
    wait_for_map(&mut h);
    assert!(prob(&h, OBJECT, 90, 64) > 0.5);
}

#[test]
fn a_stroke_updates_the_probability_map_in_the_background() {
    let (mut h, _image) = train_app("stroke.png");
    paint_both(&mut h);
    let train = &h.state().doc.train;
    assert!(train.trainable(), "object and background painted");
    let w = 128;
    assert_eq!(train.labels[64 * w + 40], OBJECT);
    assert_eq!(train.labels[10 * w + 60], BACKGROUND);
    wait_for_map(&mut h);
    // The other disk, never painted, is object; the far corner background.
    assert!(
        prob(&h, OBJECT, 90, 64) > 0.5,
        "{}",
        prob(&h, OBJECT, 90, 64)
    );
    assert!(prob(&h, BACKGROUND, 120, 120) > 0.5);
    // The map came from the background thread (only its answers are timed).
    assert!(h.state().jobs.trainer.latency_ms.is_some());
    // Two strokes in quick succession: the map that stays is the latest's.
    stroke(&mut h, Point::new(88.0, 60.0), Point::new(92.0, 68.0));
    stroke(&mut h, Point::new(120.0, 100.0), Point::new(120.0, 120.0));
    wait_for_map(&mut h);
    let app = h.state();
    assert_eq!(
        app.jobs.trainer.map.as_ref().unwrap().key.0,
        app.doc.train.revision
    );
}

#[test]
fn undo_removes_a_stroke() {
    let (mut h, _image) = train_app("undo.png");
    paint_both(&mut h);
    let before = h.state().doc.train.labels.clone();
    h.key_press(egui::Key::Num2);
    h.step();
    stroke(&mut h, Point::new(84.0, 64.0), Point::new(96.0, 64.0));
    assert_eq!(h.state().doc.train.labels[64 * 128 + 90], OBJECT);
    h.state_mut().send(Command::Undo);
    h.step();
    assert_eq!(
        h.state().doc.train.labels,
        before,
        "one stroke, one undo step"
    );
    h.state_mut().send(Command::Undo);
    h.step();
    h.state_mut().send(Command::Undo);
    h.step();
    assert!(!h.state().doc.train.painted());
    h.state_mut().send(Command::Redo);
    h.step();
    assert!(h.state().doc.train.painted());
}

#[test]
fn the_run_reads_the_map_and_starts_again_on_a_new_one() {
    let (mut h, _image) = train_app("run.png");
    paint_both(&mut h);
    wait_for_map(&mut h);
    h.state_mut().send(Command::FindSeeds);
    h.step();
    assert_eq!(
        h.state().doc.shapes.len(),
        2,
        "one seed per disk, from the map"
    );
    run_to_end(&mut h);
    assert!(h.state().doc.taught.is_some(), "the run reads the map");
    assert_eq!(contours_now(&h), 2);
    stroke(&mut h, Point::new(118.0, 100.0), Point::new(118.0, 120.0));
    wait_for_map(&mut h);
    let app = h.state();
    assert!(
        app.doc.run.is_none() || app.doc.shown == 0,
        "the run started again"
    );
}

#[test]
fn strokes_survive_saving_and_opening_a_session() {
    let (mut h, _image) = train_app("session.png");
    paint_both(&mut h);
    h.state_mut().send(Command::FindSeeds);
    h.state_mut().send(Command::Step(20));
    h.step();
    let labels = h.state().doc.train.labels.clone();
    let rings = h.state().shown_record().unwrap().rings.clone();
    let path = save_session(&mut h, "strokes.session.json");
    let mut h2 = harness(TopoApp::default());
    h2.state_mut()
        .send(Command::OpenSession(path.to_path_buf()));
    h2.step();
    assert_no_error(&h2);
    assert_eq!(h2.state().doc.train.labels, labels);
    assert!(h2.state().doc.taught.is_some());
    let again = &h2.state().shown_record().unwrap().rings;
    let pts = |r: &[topocontour::app::RingView]| -> Vec<Vec<Point>> {
        r.iter().map(|r| r.points.clone()).collect()
    };
    assert_eq!(pts(again), pts(&rings), "the same run, frame for frame");
}

#[test]
fn a_classifier_saves_and_loads_onto_another_image() {
    let (mut h, _image) = train_app("classifier.png");
    paint_both(&mut h);
    let file = temp("disks.classifier.json");
    h.state_mut()
        .send(Command::SaveClassifier(file.to_path_buf()));
    h.step();
    assert_no_error(&h);
    let (mut h2, _image2) = train_app("classifier2.png");
    h2.state_mut()
        .send(Command::LoadClassifier(file.to_path_buf()));
    h2.step();
    assert_no_error(&h2);
    assert!(h2.state().doc.train.loaded.is_some());
    wait_for_map(&mut h2);
    assert!(prob(&h2, OBJECT, 90, 64) > 0.5);
}

/// A taught run takes the command line's engine (track) until the user chooses one, and
/// a wrap gives way to the map's objects as a taught job's does: one contour per disk.
#[test]
fn a_taught_wrap_runs_as_the_command_line_runs_it() {
    use topocontour::evolution::Mode;
    let (mut h, _image) = train_app("wrap.png");
    paint_both(&mut h);
    wait_for_map(&mut h);
    h.state_mut().send(Command::WrapBorder(4.0));
    h.step();
    run_to_end(&mut h);
    assert_eq!(h.state().doc.params().mode, Mode::Track);
    assert_eq!(contours_now(&h), 2);
    assert!(
        !logged(&h, |e| matches!(
            e,
            topocontour::TopologyEvent::Split { .. }
        )),
        "the wrap gave way to the two disks: nothing had to split"
    );
    // The user's choice stands.
    h.state_mut().send(Command::SetMode(Mode::Adaptive));
    h.step();
    run_to_end(&mut h);
    assert_eq!(h.state().doc.params().mode, Mode::Adaptive);
    assert_eq!(contours_now(&h), 2);
}
