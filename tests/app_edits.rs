//! The app's hand edits, brush strokes and force changes, and sessions that keep them,
//! driven headless with egui_kittest.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;
use topocontour::app::{Command, TopoApp};
use topocontour::evolution::Shape;

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
    other
        .state_mut()
        .send(Command::OpenSession(path.to_path_buf()));
    other.step();
    assert_no_error(&other);
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
    other
        .state_mut()
        .send(Command::OpenSession(path.to_path_buf()));
    other.step();
    let after = other.state();
    assert!(after.status.error.is_none(), "{:?}", after.status.error);
    assert_eq!(after.doc.shapes, shapes);
    assert_eq!(after.doc.settings.params.polarity, settings.params.polarity);
    assert_eq!(after.doc.shown, shown);
    assert_eq!(contours(after), want);
}
