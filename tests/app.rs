//! The desktop app driven headless with egui_kittest: the real `TopoApp::ui`, real
//! clicks on real widgets, assertions on its state. Seeds, tools, playback, the event
//! log, undo, keys; hand edits in app_edits.rs, files in app_files.rs.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, Tool, TopoApp};
use topocontour::evolution::Shape;

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
    assert!(notice(&h).contains("made way"));
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
    app.send(Command::OpenImage(path.to_path_buf()));
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
