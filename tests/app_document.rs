//! The app as a document: the bugs a new user met (issue 23), each driven headless with
//! egui_kittest through the real `TopoApp::ui`.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;

use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, Tool, TopoApp};
use topocontour::evolution::{Modality, Mode, Polarity, Shape};
use topocontour::{Point, TopologyEvent};

/// Issue 23: Preserve, Find seeds, play to the end, delete a contour with Edit, drag the
/// timeline back, press Right then Space: the deletion survives; Undo and Redo bring it
/// back; a session saved afterwards lists it.
#[test]
fn a_deletion_survives_scrubbing_back_and_stepping() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("blobs_wrap")));
    let mut h = harness(app);
    h.step();
    h.get_by_label("Preserve").click();
    h.step();
    h.get_by_label("Find seeds").click();
    h.step();
    run_to_end(&mut h);
    let end = h.state().doc.shown;
    assert_eq!(contours_now(&h), 4);
    h.get_by_label("Edit").click();
    h.step();
    let ring = h.state().shown_record().unwrap().rings[0].points.clone();
    let c = ring.iter().fold(Point::new(0.0, 0.0), |a, &p| a + p) * (1.0 / ring.len() as f64);
    let at = h.state().screen_from_image(c);
    click_at(&mut h, at);
    assert!(h.state().view.selected_contour.is_some());
    h.key_press(egui::Key::Delete);
    h.step();
    h.step();
    assert_eq!(contours_now(&h), 3, "deleted");
    h.state_mut().send(Command::SeekFrame(end / 2));
    h.step();
    h.key_press(egui::Key::ArrowRight);
    h.step();
    h.key_press(egui::Key::Space);
    h.step();
    for _ in 0..400 {
        if !h.state().view.playing {
            break;
        }
        h.step();
    }
    assert_eq!(contours_now(&h), 3, "the deletion survives");
    h.state_mut().send(Command::Undo);
    h.step();
    assert_eq!(contours_now(&h), 4, "undo takes the deletion back");
    h.state_mut().send(Command::Redo);
    h.step();
    assert_eq!(contours_now(&h), 3, "redo brings it back");
    let path = temp("deleted.session.json");
    h.state_mut().send(Command::SaveSession(path.to_path_buf()));
    h.step();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let edits = json["edits"].as_array().unwrap();
    assert!(edits.iter().any(|e| e["edit"] == "delete"), "{edits:?}");
    let _ = std::fs::remove_file(path);
}

/// Issue 23: the object table shows the areas of the frame as it is after a brush stroke.
#[test]
fn the_object_table_refreshes_after_a_brush_stroke() {
    let mut app = TopoApp::with_sample();
    app.send(Command::Step(60));
    let mut h = harness(app);
    h.step();
    let rec = h.state().shown_record().unwrap().clone();
    let ring = rec.rings.iter().find(|r| !r.hole).unwrap();
    // A small dab just inside the boundary of the first region: one vertex moves out by
    // about a pixel, so its area changes, not its counts.
    let n = ring.points.len() as f64;
    let c = ring.points.iter().fold(Point::new(0.0, 0.0), |a, &p| a + p) * (1.0 / n);
    let v = ring.points[0];
    let inward = (c - v) * (1.0 / c.dist(v));
    let at = v + inward * 1.0;
    h.state_mut().send(Command::Brush {
        from: at,
        to: at,
        radius: 2.0,
        stroke: 1,
    });
    h.step();
    h.step();
    let after = h.state().shown_record().unwrap().clone();
    assert_eq!(
        (after.vertices, after.rings.len()),
        (rec.vertices, rec.rings.len())
    );
    let area = |rec: &topocontour::app::FrameRecord| {
        let rings: Vec<(u32, bool, &[Point])> = rec
            .rings
            .iter()
            .map(|r| (r.id, r.hole, r.points.as_slice()))
            .collect();
        let regions = topocontour::evolution::measure::regions_of_rings(&rings);
        let r = regions.iter().find(|r| r.id.0 == ring.id).unwrap();
        format!("{:.1}", r.area)
    };
    assert_ne!(area(&after), area(&rec), "the dab changed the area");
    h.get_by_label(&area(&after));
}

/// A bright ring (a hole opens in a wrap around it) and the shapes of a wrap.
fn ring_app() -> (TopoApp, Scratch) {
    let img = topocontour::check::ring_image(128, 16.0, 40.0);
    let path = temp("ring.png");
    img.save(&path).unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path.to_path_buf()));
    app.send(Command::SetPolarity(Polarity::Bright));
    app.send(Command::WrapBorder(4.0));
    app.apply();
    (app, path)
}

/// Issue 23: the event log and the E key list every event the headless run lists,
/// holes opened between levels (hole_made) included.
#[test]
fn the_event_log_and_the_e_key_list_every_event_replay_lists() {
    let (app, path) = ring_app();
    let (field, _) = topocontour::io::load_image_page(&path, 0).unwrap();
    let params = topocontour::evolution::Params {
        polarity: Polarity::Bright,
        ..Default::default()
    };
    let mut ev = topocontour::evolution::Evolver::new(&field, &app.doc.shapes, params).unwrap();
    while !ev.is_finished() {
        ev.step();
    }
    let want: Vec<(usize, TopologyEvent)> =
        ev.events().iter().map(|e| (e.frame, e.event)).collect();
    assert!(
        want.iter().any(|(_, e)| e.kind() == "hole_made"),
        "{want:?}"
    );
    let mut h = harness(app);
    h.step();
    // E from the start: it stops at every frame with an event.
    let mut stops = Vec::new();
    for _ in 0..want.len() + 2 {
        h.key_press(egui::Key::E);
        h.step();
        let rec = h.state().shown_record().unwrap();
        if !rec.events.is_empty() {
            stops.push(rec.index);
        }
    }
    let mut frames: Vec<usize> = want.iter().map(|(f, _)| *f).collect();
    frames.dedup();
    assert_eq!(stops, frames);
    run_to_end(&mut h);
    assert_eq!(h.state().doc.events(), want);
    let (f, e) = want.iter().find(|(_, e)| e.kind() == "hole_made").unwrap();
    h.get_by_label(&format!("frame {f}: {}", e.describe()));
    let _ = std::fs::remove_file(path);
}

/// Issue 23: the kind of image, the polarity and the engine are set again for each image
/// opened (nuclei must not open as "phase contrast, bright, preserve" because the last
/// image was).
#[test]
fn settings_reset_for_each_image_opened() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    app.send(Command::SetModality(Modality::PhaseContrast));
    app.send(Command::SetPolarity(Polarity::Bright));
    app.send(Command::SetMode(Mode::Preserve));
    let mut h = harness(app);
    h.step();
    h.state_mut()
        .send(Command::OpenImage(case_image("blobs_wrap")));
    h.step();
    let s = &h.state().doc.settings.params;
    assert_eq!(
        (s.modality, s.polarity, s.mode),
        (Modality::Generic, Polarity::Dark, Mode::Adaptive)
    );
}

/// Issue 23: a hand drag is one undo step even when the vertex leading it is replaced on
/// the way (the remesh joins it to a neighbour, the drag goes on with its successor).
#[test]
fn a_drag_whose_lead_vertex_is_replaced_is_one_undo_step() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    app.send(Command::SetPolarity(Polarity::Bright));
    app.send(Command::AddShape(Shape::Disk {
        center: Point::new(60.0, 64.0),
        radius: 20.0,
    }));
    app.send(Command::SetTool(Tool::Edit));
    app.send(Command::Step(1));
    app.send(Command::SeekFrame(0));
    let mut h = harness(app);
    h.step();
    h.step();
    let set = h
        .state()
        .doc
        .run
        .as_ref()
        .unwrap()
        .evolver
        .contours()
        .clone();
    let v = set
        .vertices()
        .min_by(|&a, &b| {
            set.position(a)
                .dist(Point::new(80.0, 64.0))
                .total_cmp(&set.position(b).dist(Point::new(80.0, 64.0)))
        })
        .unwrap();
    let from = set.position(v);
    // Along the contour, onto the vertices ahead: the remesh joins the lead to them.
    let screen = |h: &Harness<'_, TopoApp>, p: Point| h.state().screen_from_image(p);
    let start = screen(&h, from);
    h.hover_at(start);
    h.step();
    h.drag_at(start);
    h.step();
    for k in 1..=30 {
        let p = screen(&h, Point::new(from.x, from.y - k as f64));
        h.hover_at(p);
        h.step();
    }
    let end = screen(&h, Point::new(from.x, from.y - 30.0));
    h.drop_at(end);
    h.step();
    h.step();
    let edits = h.state().doc.run.as_ref().unwrap().evolver.edits().to_vec();
    let leads: std::collections::BTreeSet<u32> = edits
        .iter()
        .filter_map(|e| match e {
            topocontour::evolution::Edit::Drag { vertex, .. } => Some(*vertex),
            _ => None,
        })
        .collect();
    assert!(
        leads.len() > 1,
        "the lead vertex was replaced on the way: {leads:?}"
    );
    h.state_mut().send(Command::Undo);
    h.step();
    assert!(
        h.state()
            .doc
            .run
            .as_ref()
            .unwrap()
            .evolver
            .edits()
            .is_empty(),
        "one undo takes the whole drag back"
    );
}

/// Issue 23: the brush radius has a control (the README promises one), and [ and ] change
/// it.
#[test]
fn the_brush_radius_has_a_control() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.get_by_label("Brush").click();
    h.step();
    h.step();
    h.get_by_label("brush radius px");
    let r = h.state().view.prefs.brush_radius;
    h.key_press(egui::Key::CloseBracket);
    h.step();
    assert!(h.state().view.prefs.brush_radius > r);
}

/// Issue 23: in adaptive mode, when two seeds' contours merge, the status bar says once how
/// to keep touching objects apart.
#[test]
fn an_adaptive_merge_of_two_seeds_says_how_to_keep_them_apart() {
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(case_image("bridge_merge")));
    app.send(Command::SetPolarity(Polarity::Bright));
    for x in [80.0, 220.0] {
        app.send(Command::AddShape(Shape::Disk {
            center: Point::new(x, 100.0),
            radius: 6.0,
        }));
    }
    let mut h = harness(app);
    h.step();
    run_to_end(&mut h);
    assert_eq!(contours_now(&h), 1);
    let notice = notice(&h);
    assert!(notice.contains("Preserve"), "{notice}");
    h.state_mut().status.notice = None;
    h.state_mut().send(Command::Reset);
    h.step();
    run_to_end(&mut h);
    assert!(h.state().status.notice.is_none(), "said once");
}

/// Issue 23: the idle app does not repaint (no frame loop when nothing moves), even with a
/// contour selected in the object table.
#[test]
fn the_idle_app_requests_no_repaint() {
    let mut app = TopoApp::with_sample();
    app.send(Command::Step(60));
    let mut h = harness(app);
    h.step();
    let id = h.state().shown_record().unwrap().rings[0].id;
    h.state_mut().send(Command::SelectContour(Some(id)));
    for _ in 0..10 {
        h.step();
    }
    assert!(!h.ctx.has_requested_repaint());
}

/// Issue 23: after Find seeds, Apply to folder finds seeds in each image (the seeds of
/// this image would miss every object of a wider one).
#[test]
fn apply_to_folder_finds_seeds_per_image() {
    let dir = temp("folder-seeds");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let blobs = |w: u32, centres: &[f64]| {
        image::GrayImage::from_fn(w, 64, |x, y| {
            let inside = centres
                .iter()
                .any(|&cx| (x as f64 + 0.5 - cx).hypot(y as f64 + 0.5 - 32.0) < 12.0);
            image::Luma([if inside { 40 } else { 210 }])
        })
    };
    blobs(96, &[30.0, 66.0])
        .save(dir.join("a_small.png"))
        .unwrap();
    blobs(256, &[40.0, 200.0])
        .save(dir.join("b_wide.png"))
        .unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(dir.join("a_small.png")));
    app.send(Command::FindSeeds);
    app.send(Command::ApplyToFolder(dir.to_path_buf()));
    let mut h = harness(app);
    h.step();
    let t = std::time::Instant::now();
    while h.state().jobs.folder.is_some() {
        assert!(t.elapsed().as_secs() < 60);
        std::thread::sleep(std::time::Duration::from_millis(20));
        h.step();
    }
    let csv = std::fs::read_to_string(dir.join("topocontour/b_wide.csv")).unwrap();
    let xs: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(5).unwrap().parse().unwrap())
        .collect();
    assert!(
        xs.iter().any(|&x| x > 150.0),
        "an object right of the small image: {xs:?}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
