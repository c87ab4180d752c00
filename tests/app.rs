//! The desktop app driven headless with egui_kittest: the real `TopoApp::ui`, real
//! clicks on real widgets, assertions on its state.
#![cfg(feature = "gui")]

use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, Format, Tool, TopoApp};
use topocontour::evolution::Shape;

fn harness(app: TopoApp) -> Harness<'static, TopoApp> {
    Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut TopoApp| app.ui(ui), app)
}

fn case_image(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/cases")
        .join(name)
        .join("image.png")
}

/// The app on the bundled sample after `frames` frames of its wrap, drawn once.
fn sample_after(frames: usize) -> Harness<'static, TopoApp> {
    let mut app = TopoApp::with_sample();
    app.send(Command::Step(frames));
    let mut h = harness(app);
    h.step();
    h
}

/// Clicks the canvas at `pos` (press and release on successive frames).
fn click_at(h: &mut Harness<'_, TopoApp>, pos: egui::Pos2) {
    h.hover_at(pos);
    h.step();
    h.drag_at(pos);
    h.step();
    h.drop_at(pos);
    h.step();
    h.step();
}

#[test]
fn starts_with_the_sample_and_a_wrap_rectangle() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    assert!(h.state().doc.image.is_some());
    assert!(matches!(h.state().doc.shapes[..], [Shape::Rect { .. }]));
    h.get_by_label("Canvas");
}

#[test]
fn clicking_on_the_canvas_adds_a_seed() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.get_by_label("Seed").click();
    h.step();
    assert_eq!(h.state().view.prefs.tool, Tool::Seed);
    let canvas = h.get_by_label("Canvas").rect();
    click_at(&mut h, canvas.center());
    // The sample's wrap rectangle makes way for the first seed (it would swallow it).
    let shapes = &h.state().doc.shapes;
    assert_eq!(shapes.len(), 1, "{shapes:?}");
    assert!(matches!(shapes[0], Shape::Disk { radius, .. } if radius == 5.0));
    assert!(h
        .state()
        .status
        .notice
        .as_deref()
        .unwrap()
        .contains("made way"));
    click_at(&mut h, canvas.center() + egui::vec2(40.0, 0.0));
    assert_eq!(h.state().doc.shapes.len(), 2, "later seeds add up");
    h.state_mut().send(Command::Undo);
    h.step();
    h.state_mut().send(Command::Undo);
    h.step();
    assert!(
        matches!(h.state().doc.shapes[..], [Shape::Rect { .. }]),
        "Undo brings the wrap back"
    );
}

#[test]
fn step_advances_exactly_one_frame_and_play_pause_toggle() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.get_by_label("Step").click();
    h.step();
    assert_eq!(h.state().doc.run.as_ref().unwrap().head(), 1);
    assert_eq!(h.state().doc.shown, 1);
    h.get_by_label("Step").click();
    h.step();
    assert_eq!(h.state().doc.shown, 2);
    h.get_by_label("Play").click();
    h.step();
    assert!(h.state().view.playing);
    for _ in 0..5 {
        h.step();
    }
    let after_play = h.state().doc.shown;
    assert!(after_play > 2, "playing advances frames");
    h.get_by_label("Pause").click();
    h.step();
    assert!(!h.state().view.playing);
    let paused = h.state().doc.shown;
    h.step();
    h.step();
    assert_eq!(h.state().doc.shown, paused, "paused stays put");
}

#[test]
fn a_split_appears_in_the_event_log_and_clicking_it_shows_that_frame() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("blobs_wrap")));
    app.send(Command::WrapBorder(8.0));
    app.apply();
    let mut h = harness(app);
    h.step();
    for _ in 0..30 {
        h.get_by_label("Step 10").click();
        h.step();
        if logged(&h, |e| e.kind() == "split") {
            break;
        }
    }
    let (frame, event) = *h
        .state()
        .doc
        .events()
        .iter()
        .find(|(_, e)| e.kind() == "split")
        .expect("a split was logged");
    // Events are named by object: "object 3 split into 3 and 7".
    let text = format!("frame {frame}: {}", event.describe());
    assert!(text.contains("split into"), "{text}");
    h.step(); // draw the log as it is after the last step
    h.get_by_label(&text).click();
    h.step();
    assert_eq!(h.state().doc.shown, frame);
    assert!(h
        .state()
        .shown_record()
        .unwrap()
        .events
        .iter()
        .any(|e| e.kind() == "split"));
}

#[test]
fn export_writes_an_svg_that_parses_and_reset_clears() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    for _ in 0..4 {
        h.get_by_label("Step 10").click();
        h.step();
    }
    let path = temp("app.svg");
    h.state_mut()
        .send(Command::Export(Format::Svg, path.clone()));
    h.step();
    let svg = std::fs::read_to_string(&path).expect("export wrote the file");
    let tree =
        resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).expect("SVG parses");
    assert!(tree.root().children().len() >= 5, "one path per region");
    assert!(h.state().status.error.is_none());
    h.get_by_label("Reset").click();
    h.step();
    assert!(h.state().doc.run.is_none());
    assert!(h.state().doc.events().is_empty());
    assert_eq!(
        h.state().doc.shapes.len(),
        1,
        "reset keeps the initialisation"
    );
}

#[test]
fn errors_show_in_the_app_instead_of_panicking() {
    let mut h = harness(TopoApp::with_sample());
    h.state_mut()
        .send(Command::OpenImage("/nonexistent/image.png".into()));
    h.step();
    let error = |h: &Harness<TopoApp>| h.state().status.error.as_ref().unwrap().to_string();
    assert!(error(&h).contains("cannot read"));
    h.state_mut().send(Command::DeleteShape(0));
    h.step();
    h.get_by_label("Step").click();
    h.step();
    assert!(error(&h).contains("initialisation"));
}

#[test]
fn select_and_delete_a_shape_from_the_canvas() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.get_by_label("Select").click();
    h.step();
    // The wrap rectangle's left edge runs 6 image pixels inside the image's left border.
    let on_edge = h
        .state()
        .screen_from_image(topocontour::Point::new(6.0, 150.0));
    click_at(&mut h, on_edge);
    assert_eq!(h.state().view.selected, Some(0));
    h.get_by_label("Delete shape").click();
    h.step();
    assert!(h.state().doc.shapes.is_empty());
}

#[test]
fn the_engine_choice_keeps_two_touching_seeds_apart() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    app.send(Command::SetPolarity(
        topocontour::evolution::Polarity::Bright,
    ));
    app.send(Command::AddShape(Shape::Disk {
        center: topocontour::Point::new(80.0, 100.0),
        radius: 6.0,
    }));
    app.send(Command::AddShape(Shape::Disk {
        center: topocontour::Point::new(220.0, 100.0),
        radius: 6.0,
    }));
    app.apply();
    let mut h = harness(app);
    h.step();
    h.get_by_label("Preserve").click();
    h.step();
    assert_eq!(
        h.state().doc.settings.params.mode,
        topocontour::evolution::Mode::Preserve
    );
    for _ in 0..40 {
        h.get_by_label("Step 10").click();
        h.step();
    }
    let rec = h.state().shown_record().unwrap();
    assert_eq!(
        rec.contours, 2,
        "preserve keeps the two seeds' contours apart"
    );
    assert!(h.state().doc.events().is_empty());
}

fn now(app: &mut TopoApp, c: Command) {
    app.send(c);
    app.apply();
}

#[test]
fn side_by_side_runs_a_second_engine_on_the_same_shapes() {
    let mut app = TopoApp::default();
    now(&mut app, Command::OpenImage(case_image("bridge_merge")));
    now(&mut app, Command::SetTool(Tool::Seed));
    for x in [80.0, 220.0] {
        now(
            &mut app,
            Command::AddShape(Shape::Disk {
                center: topocontour::Point::new(x, 100.0),
                radius: 6.0,
            }),
        );
    }
    now(
        &mut app,
        Command::SetPolarity(topocontour::evolution::Polarity::Bright),
    );
    let mut h = harness(app);
    h.step();
    h.state_mut().send(Command::SetCompare(Some(
        topocontour::evolution::Mode::Implicit,
    )));
    h.step();
    // Run both to the end: adaptive merges the two seeds, implicit keeps them apart.
    for _ in 0..40 {
        h.state_mut().send(Command::Step(50));
        h.step();
    }
    let s = h.state();
    let a = s.shown_record().expect("main run");
    let b = s.doc.shown_record_b().expect("side-by-side run");
    assert_eq!(a.contours, 1, "adaptive merges through the bridge");
    assert_eq!(b.contours, 2, "implicit keeps the two seeds apart");
    assert!(s.doc.run_b.as_ref().unwrap().evolver.is_converged());
    // Both halves are labelled with their engine.
    h.get_by_label("Canvas");
}

/// "Find seeds" places one editable seed per object (four dark blobs), and playing grows
/// them into four contours.
#[test]
fn find_seeds_places_one_seed_per_object() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("blobs_wrap")));
    let mut h = harness(app);
    h.step();
    h.get_by_label("Find seeds").click();
    h.step();
    h.step();
    let shapes = &h.state().doc.shapes;
    assert_eq!(shapes.len(), 4, "{shapes:?}");
    // Each seed is its object's basin (a polygon), or a disk where the basin is tiny.
    assert!(shapes
        .iter()
        .all(|s| matches!(s, Shape::Disk { .. } | Shape::Polygon(_))));
    h.state_mut().send(Command::Step(400));
    h.step();
    let run = h.state().doc.run.as_ref().expect("a run");
    assert_eq!(run.evolver.contours().contour_count(), 4);
}

/// The E key steps to the next frame with a topology event (the README promises it).
#[test]
fn the_e_key_steps_to_the_next_event() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("blobs_wrap")));
    app.send(Command::WrapBorder(8.0));
    let mut h = harness(app);
    h.step();
    h.key_press(egui::Key::E);
    h.step();
    h.step();
    let app = h.state();
    let run = app.doc.run.as_ref().expect("E started a run");
    assert!(app.doc.shown > 0, "E advanced");
    let rec = app.shown_record().expect("a frame on screen");
    assert!(
        !rec.events.is_empty() || run.evolver.is_finished(),
        "E stopped at frame {} without an event",
        app.doc.shown
    );
    assert!(!app.doc.events().is_empty(), "the event is in the log");
}

/// The app exports a label image and an ImageJ ROI set of the frame on screen.
#[test]
fn export_labels_and_roi_set() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.state_mut().send(Command::Step(60));
    h.step();
    let dir = std::env::temp_dir();
    let (tif, zip) = (
        dir.join(format!("topocontour-app-{}.tif", std::process::id())),
        dir.join(format!("topocontour-app-{}.zip", std::process::id())),
    );
    h.state_mut()
        .send(Command::Export(Format::Labels, tif.clone()));
    h.state_mut()
        .send(Command::Export(Format::Roi, zip.clone()));
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    let labels = image::open(&tif).expect("label image").to_luma16();
    let max = labels.pixels().map(|p| p.0[0]).max().unwrap();
    let archive = zip::ZipArchive::new(std::fs::File::open(&zip).unwrap()).unwrap();
    assert!(max >= 1);
    assert_eq!(archive.len(), max as usize, "one ROI per label");
}

/// A session saved at a frame opens in a fresh app as the same state: image, shapes,
/// parameters, frame and contours.
#[test]
fn session_save_then_open_gives_the_same_state() {
    let mut app = bright_bridge_with_seeds(&[(60.0, 64.0, 6.0)]);
    app.send(Command::WrapBorder(4.0));
    app.send(Command::Step(25));
    let mut h = harness(app);
    h.step();
    let path = save_session(&mut h, "app.session.json");
    let before = h.state();
    let (shapes, settings, shown) = (
        before.doc.shapes.clone(),
        before.doc.settings.clone(),
        before.doc.shown,
    );
    let contours = |a: &TopoApp| {
        let set = evolver(a).contours();
        (set.contour_count(), set.vertex_count(), set.region_area())
    };
    let want = contours(before);
    let mut other = harness(TopoApp::default());
    other.step();
    other.state_mut().send(Command::OpenSession(path));
    other.step();
    let after = other.state();
    assert!(after.status.error.is_none(), "{:?}", after.status.error);
    assert_eq!(after.doc.shapes, shapes);
    assert_eq!(after.doc.settings.params.polarity, settings.params.polarity);
    assert_eq!(after.doc.shown, shown);
    assert_eq!(contours(after), want);
}

/// Undo and redo of adding, moving and deleting a shape, with the keys and the buttons.
#[test]
fn undo_and_redo_shape_edits() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    let mut h = harness(app);
    h.step();
    let disk = Shape::Disk {
        center: topocontour::Point::new(40.0, 40.0),
        radius: 5.0,
    };
    h.state_mut().send(Command::AddShape(disk.clone()));
    h.step();
    // A drag: several moves of one shape are one undo step.
    for _ in 0..5 {
        h.state_mut().send(Command::MoveShape {
            index: 0,
            by: topocontour::Point::new(2.0, 0.0),
        });
        h.step();
    }
    h.state_mut().send(Command::DeleteShape(0));
    h.step();
    assert!(h.state().doc.shapes.is_empty());
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.step();
    h.step();
    let moved = Shape::Disk {
        center: topocontour::Point::new(50.0, 40.0),
        radius: 5.0,
    };
    assert_eq!(h.state().doc.shapes, vec![moved.clone()], "undo the delete");
    h.get_by_label("Undo").click();
    h.step();
    h.step();
    assert_eq!(h.state().doc.shapes, vec![disk], "undo the whole drag");
    h.get_by_label("Undo").click();
    h.step();
    h.step();
    assert!(h.state().doc.shapes.is_empty(), "undo the add");
    h.key_press_modifiers(
        egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
        egui::Key::Z,
    );
    h.step();
    h.step();
    h.get_by_label("Redo").click();
    h.step();
    h.step();
    assert_eq!(h.state().doc.shapes, vec![moved], "redo add and drag");
}

/// A parameter change clears the run on screen; Undo brings it back at its frame.
#[test]
fn undo_brings_back_a_run_a_parameter_change_cleared() {
    let mut h = sample_after(30);
    let frame = h.state().doc.shown;
    assert!(frame > 0 && h.state().doc.run.is_some());
    h.state_mut().send(Command::SetPolarity(
        topocontour::evolution::Polarity::Bright,
    ));
    h.step();
    assert!(h.state().doc.run.is_none());
    h.state_mut().send(Command::Undo);
    h.step();
    let app = h.state();
    assert_eq!(
        app.doc.settings.params.polarity,
        topocontour::evolution::Polarity::Dark
    );
    assert_eq!(app.doc.shown, frame);
    assert!(app.doc.run.is_some(), "the run is back");
}

/// F1 opens the shortcut list, Esc closes it; ← goes one frame back.
#[test]
fn help_and_frame_keys() {
    let mut h = sample_after(5);
    assert!(!h.state().view.show_help);
    h.key_press(egui::Key::F1);
    h.step();
    h.step();
    assert!(h.state().view.show_help);
    h.get_by_label("Keyboard shortcuts");
    h.key_press(egui::Key::Escape);
    h.step();
    assert!(!h.state().view.show_help);
    let shown = h.state().doc.shown;
    h.key_press(egui::Key::ArrowLeft);
    h.step();
    h.step();
    assert_eq!(h.state().doc.shown, shown - 1);
}

/// A 16-bit image whose data fill 12 bits opens with a contrast window around them.
#[test]
fn a_twelve_bit_image_opens_with_its_own_contrast() {
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(64, 48, |x, y| {
        image::Luma([((x * 61 + y * 13) % 4096) as u16])
    });
    let path = temp("app-12bit.tif");
    img.save(&path).unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path));
    let mut h = harness(app);
    h.step();
    let (lo, hi) = h.state().doc.settings.contrast;
    assert!(lo < 0.01 && hi > 0.05 && hi < 0.07, "{lo} {hi}");
}

/// The app on the bridge_merge image, bright objects, with seed disks (x, y, r).
fn bright_bridge_with_seeds(disks: &[(f64, f64, f64)]) -> TopoApp {
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

/// A path in the temporary folder, unique to this test process.
fn temp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("topocontour-{}-{name}", std::process::id()))
}

/// Saves the session of `h` to a temporary file, checking no error showed; its path.
fn save_session(h: &mut Harness<'_, TopoApp>, name: &str) -> std::path::PathBuf {
    let path = temp(name);
    h.state_mut().send(Command::SaveSession(path.clone()));
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    path
}

/// The evolver of the run on screen.
fn evolver(app: &TopoApp) -> &topocontour::evolution::Evolver {
    &app.doc.run.as_ref().expect("a run").evolver
}

/// How many contours the run on screen has now.
fn contour_count(h: &Harness<'_, TopoApp>) -> usize {
    evolver(h.state()).contours().contour_count()
}

/// Whether the event log holds an event that `is` accepts.
fn logged(h: &Harness<'_, TopoApp>, is: impl Fn(&topocontour::TopologyEvent) -> bool) -> bool {
    h.state().doc.events().iter().any(|(_, e)| is(e))
}

/// Drags the contour vertex nearest to `from` to the right in `steps` hand moves of
/// 4 px, one frame drawn after each.
fn drag_right(h: &mut Harness<'_, TopoApp>, from: topocontour::Point, steps: usize) {
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
fn vertex_near(app: &TopoApp, p: topocontour::Point) -> u32 {
    let set = evolver(app).contours();
    set.vertices()
        .min_by(|&a, &b| set.position(a).dist(p).total_cmp(&set.position(b).dist(p)))
        .unwrap()
}

/// Hand edits go through the topology core: dragging a vertex of one contour into
/// another merges them, dragging one through its own contour splits it; both are
/// logged as events, and Undo takes the edit back.
#[test]
fn hand_edits_merge_and_split_exactly() {
    use topocontour::{Point, TopologyEvent};
    let mut app = bright_bridge_with_seeds(&[(40.0, 64.0, 10.0), (75.0, 64.0, 10.0)]);
    app.send(Command::Step(1));
    app.send(Command::SeekFrame(0));
    let mut h = harness(app);
    h.step();
    assert_eq!(contour_count(&h), 2);
    // Merge: drag the right-most vertex of the left disk into the right one, in steps.
    drag_right(&mut h, Point::new(50.0, 64.0), 5);
    assert_eq!(contour_count(&h), 1, "merged");
    assert!(h
        .state()
        .doc
        .events()
        .iter()
        .any(|(f, e)| *f == 0 && matches!(e, TopologyEvent::Merge { .. })));
    h.state_mut().send(Command::Undo);
    h.step();
    assert_eq!(contour_count(&h), 2, "undo takes the whole drag back");

    // Split: a long rectangle, its top middle vertex dragged down through the bottom.
    h.state_mut().send(Command::Reset);
    h.state_mut().send(Command::DeleteShape(1));
    h.state_mut().send(Command::DeleteShape(0));
    h.state_mut().send(Command::AddShape(Shape::Rect {
        min: Point::new(20.0, 50.0),
        max: Point::new(108.0, 70.0),
    }));
    h.state_mut().send(Command::Step(1));
    h.state_mut().send(Command::SeekFrame(0));
    h.step();
    assert_eq!(contour_count(&h), 1);
    let v = vertex_near(h.state(), Point::new(64.0, 50.0));
    let from = evolver(h.state()).contours().position(v);
    h.state_mut().send(Command::HandMove {
        vertex: v,
        to: Point::new(from.x, 80.0),
        stroke: 2,
    });
    h.step();
    assert_eq!(contour_count(&h), 2, "split");
    assert!(logged(&h, |e| matches!(e, TopologyEvent::Split { .. })));
    evolver(h.state()).contours().sanity_check().unwrap();
}

/// A change of forces goes on from the frame on screen: the frames before it stay, the
/// run is not thrown away, and Undo puts the old forces and frames back.
#[test]
fn a_force_change_continues_from_the_frame_on_screen() {
    let mut h = sample_after(20);
    let at = h.state().doc.shown;
    assert_eq!(at, 20);
    let before = h.state().doc.run.as_ref().unwrap().history[at].rings.len();
    let mut weights = h.state().doc.settings.params.weights;
    weights.stretch = 0.6;
    h.state_mut()
        .send(Command::SetForces { weights, step: 0.5 });
    h.state_mut().send(Command::Step(5));
    h.step();
    let app = h.state();
    let run = app.doc.run.as_ref().expect("the run goes on");
    assert_eq!(app.doc.shown, at + 5, "continued from frame {at}");
    assert_eq!(
        run.history[at].rings.len(),
        before,
        "frames up to the change kept"
    );
    assert_eq!(run.evolver.params().weights.stretch, 0.6);
    assert_eq!(run.evolver.params().step, 0.5);
    assert!(matches!(
        run.evolver.edits(),
        [topocontour::evolution::Edit::Forces { frame: 20, .. }]
    ));
    assert!(app
        .status
        .notice
        .as_deref()
        .unwrap_or("")
        .contains("frame 20"));
    h.state_mut().send(Command::Undo);
    h.step();
    let app = h.state();
    assert_eq!(
        app.doc.settings.params.weights.stretch, 0.2,
        "old forces back"
    );
    assert!(evolver(app).edits().is_empty());
    assert_eq!(app.doc.shown, at);
}

/// A session keeps the edits made on the way (a force change and a hand drag, each at
/// its frame): opening it rebuilds the same contours.
#[test]
fn a_session_replays_hand_edits_and_force_changes() {
    use topocontour::Point;
    let mut app = bright_bridge_with_seeds(&[(40.0, 64.0, 10.0), (75.0, 64.0, 10.0)]);
    app.send(Command::Step(3));
    let mut h = harness(app);
    h.step();
    drag_right(&mut h, Point::new(52.0, 64.0), 4);
    let mut weights = h.state().doc.settings.params.weights;
    weights.bend = 0.2;
    h.state_mut().send(Command::SetForces {
        weights,
        step: 0.75,
    });
    h.state_mut().send(Command::Step(4));
    h.step();
    let path = save_session(&mut h, "app-edits.session.json");
    let points = |a: &TopoApp| {
        let set = evolver(a).contours();
        set.contour_ids()
            .map(|id| set.ring_points(id))
            .collect::<Vec<_>>()
    };
    let want = points(h.state());
    assert!(evolver(h.state()).edits().len() >= 2);
    let mut other = harness(TopoApp::default());
    other.step();
    other.state_mut().send(Command::OpenSession(path.clone()));
    other.step();
    assert!(
        other.state().status.error.is_none(),
        "{:?}",
        other.state().status.error
    );
    assert_eq!(other.state().doc.shown, h.state().doc.shown);
    assert_eq!(
        points(other.state()),
        want,
        "same contours, vertex for vertex"
    );
    assert_eq!(other.state().doc.settings.params.weights.bend, 0.2);
    // Headless, the same session gives the same contours.
    let run = topocontour::io::session::Session::read(&path)
        .unwrap()
        .replay(&path, None)
        .unwrap();
    let set = run.ev.contours();
    let headless: Vec<_> = set.contour_ids().map(|id| set.ring_points(id)).collect();
    assert_eq!(headless, want);
    let _ = std::fs::remove_file(path);
}

/// The object table lists the regions of the frame on screen with their measurements; a
/// click on a row selects that contour (highlighted on the canvas), a second click
/// clears the selection.
#[test]
fn the_object_table_is_linked_to_the_canvas() {
    let mut h = sample_after(60);
    h.step();
    let set = evolver(h.state()).contours().clone();
    let regions = topocontour::evolution::regions(&set);
    assert!(regions.len() >= 2, "the sample has several cells");
    // The largest region: the table's first row.
    let id = regions
        .iter()
        .max_by(|a, b| a.area.total_cmp(&b.area))
        .unwrap()
        .id
        .0;
    h.get_by_label("Objects");
    h.get_by_label(&format!("#{id}")).click();
    h.step();
    h.step();
    assert_eq!(h.state().view.selected_contour, Some(id));
    h.get_by_label(&format!("#{id}")).click();
    h.step();
    h.step();
    assert_eq!(h.state().view.selected_contour, None);
}

/// Without a desktop portal a file dialog gives no path: the built-in path field takes
/// a typed one (here: open an image, then export next to it under the image's name).
#[test]
fn the_path_field_stands_in_for_a_file_dialog() {
    use topocontour::app::{PathPrompt, PathPurpose};
    let mut h = harness(TopoApp::default());
    h.step();
    h.state_mut().view.path_prompt = Some(PathPrompt {
        purpose: PathPurpose::OpenImage,
        text: case_image("bridge_merge").display().to_string(),
    });
    h.step();
    h.step();
    h.get_by_label("OK").click();
    h.step();
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    assert_eq!(h.state().doc.image_name, "image.png");
    assert!(h.state().view.path_prompt.is_none());
    assert_eq!(Format::Labels.file_name("image"), "image.labels.tif");
    let out = temp("prompt.svg");
    h.state_mut().send(Command::WrapBorder(4.0));
    h.state_mut().send(Command::Step(2));
    h.step();
    h.state_mut().view.path_prompt = Some(PathPrompt {
        purpose: PathPurpose::Export(Format::Svg),
        text: out.display().to_string(),
    });
    h.step();
    h.step();
    h.get_by_label("OK").click();
    h.step();
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    assert!(std::fs::read_to_string(&out).unwrap().contains("<svg"));
    let _ = std::fs::remove_file(out);
}

/// A TIFF stack opens on page 1 and says it holds more; another page keeps the shapes;
/// the pixel size from the file reaches the CSV export.
#[test]
fn a_tiff_stack_opens_with_its_pages_and_pixel_size() {
    use tiff::encoder::{colortype::Gray8, Rational, TiffEncoder};
    use tiff::tags::ResolutionUnit;
    let path = temp("app-stack.tif");
    {
        let mut enc = TiffEncoder::new(std::fs::File::create(&path).unwrap()).unwrap();
        for k in 0..3u32 {
            let data: Vec<u8> = (0..64 * 64u32)
                .map(|i| if (i % 64) < 20 + 10 * k { 30 } else { 200 })
                .collect();
            let mut img = enc.new_image::<Gray8>(64, 64).unwrap();
            img.resolution(ResolutionUnit::Centimeter, Rational { n: 10_000, d: 1 });
            img.write_data(&data).unwrap();
        }
    }
    let mut h = harness(TopoApp::default());
    h.state_mut().send(Command::OpenImage(path.clone()));
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    assert!(h
        .state()
        .status
        .notice
        .as_deref()
        .unwrap()
        .contains("3 pages"));
    assert_eq!(h.state().doc.stack.pages, 3);
    let pixel = h.state().doc.stack.pixel.clone().expect("resolution read");
    assert_eq!(pixel.unit, "cm");
    assert!((pixel.size - 1e-4).abs() < 1e-12);
    let mean = |a: &TopoApp| a.doc.image.as_ref().unwrap().data.iter().sum::<f32>();
    let first = mean(h.state());
    h.state_mut().send(Command::WrapBorder(2.0));
    h.state_mut().send(Command::SetPage(2));
    h.step();
    assert_eq!(h.state().doc.stack.page, 2);
    assert!(mean(h.state()) < first, "page 3 is darker");
    assert_eq!(h.state().doc.shapes.len(), 1, "shapes stay");
    h.state_mut().send(Command::Step(3));
    let csv = temp("app-stack.csv");
    h.state_mut()
        .send(Command::Export(Format::Csv, csv.clone()));
    h.step();
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(
        text.lines().nth(1).unwrap().contains(",0.0001,\"cm\","),
        "{text}"
    );
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(csv);
}

/// A brush stroke from inside one disc towards the other pushes its boundary out until
/// the two merge (logged as an event); the whole stroke is one undo step.
#[test]
fn a_brush_stroke_merges_and_undoes_as_one_step() {
    use topocontour::{Point, TopologyEvent};
    let mut app = bright_bridge_with_seeds(&[(40.0, 64.0, 10.0), (75.0, 64.0, 10.0)]);
    app.send(Command::SetTool(topocontour::app::Tool::Brush));
    app.send(Command::Step(1));
    app.send(Command::SeekFrame(0));
    let mut h = harness(app);
    h.step();
    assert_eq!(contour_count(&h), 2);
    for k in 0..5 {
        let x = 40.0 + 4.0 * k as f64;
        h.state_mut().send(Command::Brush {
            from: Point::new(x, 64.0),
            to: Point::new(x + 4.0, 64.0),
            radius: 7.0,
            stroke: 1,
        });
        h.step();
    }
    assert_eq!(contour_count(&h), 1, "merged");
    assert!(logged(&h, |e| matches!(e, TopologyEvent::Merge { .. })));
    h.state_mut().send(Command::Undo);
    h.step();
    assert_eq!(contour_count(&h), 2, "one undo takes the whole stroke back");
}

/// "Apply to folder…" segments every image of a folder in the background (the window
/// keeps drawing, a progress bar shows) and writes JSON and CSV per image and
/// summary.csv into the folder's topocontour subfolder.
#[test]
fn apply_to_folder_runs_in_the_background() {
    let dir = temp("app-folder");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (i, case) in ["bridge_merge", "blobs_wrap", "ring_seed"]
        .iter()
        .enumerate()
    {
        std::fs::copy(case_image(case), dir.join(format!("img{i}.png"))).unwrap();
    }
    let mut app = TopoApp::with_sample();
    app.send(Command::ApplyToFolder(dir.clone()));
    let mut h = harness(app);
    h.step();
    assert!(
        h.state().jobs.folder.is_some(),
        "{:?}",
        h.state().status.notice
    );
    h.get_by_label("Cancel");
    let t = std::time::Instant::now();
    while h.state().jobs.folder.is_some() {
        assert!(t.elapsed().as_secs() < 60, "the folder run finishes");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    let notice = h.state().status.notice.clone().unwrap();
    assert!(notice.contains("wrote 3 images"), "{notice}");
    let out = dir.join("topocontour");
    for i in 0..3 {
        let json: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(format!("img{i}.json"))).unwrap(),
        )
        .unwrap();
        assert!(!json["contours"].as_array().unwrap().is_empty());
        assert!(out.join(format!("img{i}.csv")).is_file());
    }
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(summary.lines().count() > 3, "{summary}");
    let _ = std::fs::remove_dir_all(dir);
}

/// A large image is prepared on a background thread: the frame that asked for steps
/// returns at once with the preparation under way, and the steps happen when it is done.
#[test]
fn a_large_image_is_prepared_in_the_background() {
    let (w, h_px) = (1600u32, 1400u32);
    assert!((w * h_px) as usize > topocontour::app::PREPARE_IN_BACKGROUND);
    let img = image::GrayImage::from_fn(w, h_px, |x, y| {
        let (dx, dy) = (x as f64 - 800.0, y as f64 - 700.0);
        image::Luma([if dx.hypot(dy) < 300.0 { 40 } else { 200 }])
    });
    let path = temp("app-large.png");
    img.save(&path).unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path.clone()));
    app.send(Command::WrapBorder(10.0));
    app.send(Command::Step(3));
    let mut h = harness(app);
    h.step();
    assert!(
        h.state().jobs.preparing.is_some(),
        "prepared in the background"
    );
    assert!(h.state().doc.run.is_none());
    let t = std::time::Instant::now();
    while h.state().jobs.preparing.is_some() {
        assert!(t.elapsed().as_secs() < 120, "the preparation finishes");
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    assert!(
        h.state().status.error.is_none(),
        "{:?}",
        h.state().status.error
    );
    assert_eq!(
        h.state().doc.shown,
        3,
        "the steps asked meanwhile were done"
    );
    let _ = std::fs::remove_file(path);
}

/// A wrap over a bright ring finds the ring's hole; unticking "open holes" (one click
/// on the check box) keeps the wrap's region filled, and undo brings the setting back.
#[test]
fn the_open_holes_check_box_decides_whether_a_wrap_finds_a_ring_hole() {
    let img = topocontour::check::ring_image(128, 16.0, 40.0);
    let path = temp("app-ring.png");
    img.save(&path).unwrap();
    let run_holes = |h: &mut Harness<'_, TopoApp>| {
        for _ in 0..40 {
            h.get_by_label("Step 10").click();
            h.step();
        }
        let set = evolver(h.state()).contours();
        set.contour_ids().filter(|&id| set.is_hole(id)).count()
    };
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path));
    app.send(Command::SetPolarity(
        topocontour::evolution::Polarity::Bright,
    ));
    app.send(Command::WrapBorder(4.0));
    app.apply();
    let mut h = harness(app);
    h.step();
    assert!(h.state().doc.settings.params.open_holes);
    assert_eq!(run_holes(&mut h), 1, "the ring's hole opens");
    h.get_by_label("open holes").click();
    h.step();
    assert!(!h.state().doc.settings.params.open_holes);
    assert_eq!(run_holes(&mut h), 0, "no hole without nucleation");
    h.state_mut().send(Command::Undo);
    h.step();
    assert!(h.state().doc.settings.params.open_holes);
}
