//! Movies in the app, driven headless with egui_kittest (issue 26): the movie's frame
//! slider, Track in the background with its progress and Cancel, the division in the
//! event log and the jump to its frame, the lineage view linked to the canvas, the CTC
//! export, hand corrections of a tracked frame that track the frames after it again.
//! The movies are made here: bright capsules on a dark background, written as a folder
//! of PNG frames.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;
use egui_kittest::kittest::Queryable;
use egui_kittest::Harness;
use topocontour::app::{Command, TopoApp};
use topocontour::evolution::Polarity;
use topocontour::geometry::Point;

type Capsule = (Point, Point, f64);

/// A `w`×`h` 8-bit frame with bright capsules (segments thickened by a radius).
fn frame(w: u32, h: u32, capsules: &[Capsule]) -> image::GrayImage {
    image::GrayImage::from_fn(w, h, |x, y| {
        let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
        let inside = capsules.iter().any(|&(a, b, r)| {
            let d = b - a;
            let t = if d.norm2() > 0.0 {
                ((p - a).dot(d) / d.norm2()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            p.dist(a + d * t) <= r
        });
        image::Luma([if inside { 217 } else { 38 }])
    })
}

/// Writes `frames` as `DIR/fNNN.png`; the folder.
fn movie_folder(name: &str, frames: &[image::GrayImage]) -> Scratch {
    let dir = temp(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (t, f) in frames.iter().enumerate() {
        f.save(dir.join(format!("f{t:03}.png"))).unwrap();
    }
    dir
}

/// A rod that grows for four frames, then two rods drifting apart for four (the rod of
/// tests/track.rs): track 1 divides into 2 and 3 at frame 4.
fn dividing_rod() -> Vec<image::GrayImage> {
    let rod = |a: f64, b: f64| (Point::new(a, 32.0), Point::new(b, 32.0), 6.0);
    let mut frames: Vec<_> = [10.0, 12.0, 14.0, 16.0]
        .map(|h| frame(96, 64, &[rod(48.0 - h, 48.0 + h)]))
        .into();
    for gap in [3.0, 4.0, 5.0, 6.0] {
        let cells = [rod(24.0, 42.0 - gap), rod(54.0 + gap, 72.0)];
        frames.push(frame(96, 64, &cells));
    }
    frames
}

/// A nucleus that parts into two lobes 6 px apart at frame 3 and is one dumbbell again
/// from frame 4 on (tests/track.rs): no division.
fn parting_nucleus() -> Vec<image::GrayImage> {
    let disk = |x: f64, r: f64| (Point::new(x, 32.0), Point::new(x, 32.0), r);
    let mut frames: Vec<_> = [3.0, 4.0, 5.0]
        .map(|h| {
            frame(
                96,
                64,
                &[(Point::new(48.0 - h, 32.0), Point::new(48.0 + h, 32.0), 10.0)],
            )
        })
        .into();
    frames.push(frame(96, 64, &[disk(37.0, 8.0), disk(59.0, 8.0)]));
    for _ in 0..3 {
        let bridge = (Point::new(40.0, 32.0), Point::new(56.0, 32.0), 5.0);
        frames.push(frame(96, 64, &[disk(40.0, 8.0), disk(56.0, 8.0), bridge]));
    }
    frames
}

/// The app on the movie in `dir`, bright objects, drawn once.
fn movie_app(dir: &std::path::Path) -> Harness<'static, TopoApp> {
    let mut app = TopoApp::default();
    app.send(Command::OpenMovie(dir.to_path_buf()));
    app.send(Command::SetPolarity(Polarity::Bright));
    let mut h = harness(app);
    h.step();
    assert_no_error(&h);
    h
}

/// The app on `frames` (written as the movie folder `name`), tracked to the end; the
/// folder goes when the second is dropped.
fn tracked_movie(name: &str, frames: &[image::GrayImage]) -> (Harness<'static, TopoApp>, Scratch) {
    let dir = movie_folder(name, frames);
    let mut h = movie_app(&dir);
    click_label(&mut h, "Track movie");
    wait_for_tracking(&mut h);
    (h, dir)
}

/// Draws frames until tracking has ended (at most a minute).
fn wait_for_tracking(h: &mut Harness<'_, TopoApp>) {
    let start = std::time::Instant::now();
    while h.state().jobs.track.is_some() {
        assert!(start.elapsed().as_secs() < 60, "tracking did not end");
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    h.step();
}

fn movie_frame(h: &Harness<'_, TopoApp>) -> usize {
    h.state().doc.movie.as_ref().expect("a movie").frame
}

#[test]
fn the_movie_slider_shows_frames_and_track_runs_with_cancel() {
    // 150 frames of two cells drifting right: long enough to cancel midway.
    let frames: Vec<_> = (0..150)
        .map(|t| {
            let x = 30.0 + 0.2 * t as f64;
            let cells = [
                (Point::new(x, 40.0), Point::new(x + 10.0, 40.0), 9.0),
                (Point::new(x + 40.0, 80.0), Point::new(x + 40.0, 90.0), 9.0),
            ];
            frame(160, 128, &cells)
        })
        .collect();
    let dir = movie_folder("slider", &frames);
    let mut h = movie_app(&dir);
    assert_eq!(h.state().doc.movie.as_ref().unwrap().movie.len(), 150);
    let first = h.state().doc.image.clone().unwrap();
    h.get_by_role_and_label(egui::accesskit::Role::Slider, "movie frame")
        .set_value_accesskit(120.0);
    h.step();
    h.step();
    assert_eq!(movie_frame(&h), 120);
    let shown = h.state().doc.image.clone().unwrap();
    assert_ne!(
        first.data, shown.data,
        "the slider shows another frame's image"
    );
    assert!(h.state().title().contains("movie frame 120"));
    click_label(&mut h, "Track movie");
    let start = std::time::Instant::now();
    while h.state().jobs.track.as_ref().is_some_and(|j| j.done < 3) {
        assert!(start.elapsed().as_secs() < 60);
        std::thread::sleep(std::time::Duration::from_millis(2));
        h.step();
    }
    // The window draws frames while the thread tracks.
    h.step();
    assert!(h.state().jobs.track.is_some(), "still tracking");
    click_label(&mut h, "Cancel tracking");
    wait_for_tracking(&mut h);
    let tr = h
        .state()
        .doc
        .movie
        .as_ref()
        .unwrap()
        .tracking
        .clone()
        .unwrap();
    assert!(!tr.complete);
    let n = tr.frames.len();
    assert!((3..150).contains(&n), "cancelled midway: {n} frames");
    assert!(notice(&h).contains("(stopped)"), "{}", notice(&h));
    // Each track keeps its label (its colour) across the frames tracked.
    for f in &tr.frames {
        let tracks: Vec<u32> = f.objects.iter().map(|o| o.track).collect();
        assert_eq!(tracks, [1, 2], "frame {}", f.frame);
    }
    // Nothing repaints once tracking has ended.
    for _ in 0..5 {
        h.step();
    }
    assert!(!h.ctx.has_requested_repaint());
    // Continued, it is the tracking that ran on (its stopped tracker, not one rebuilt
    // from the last contours): the same as one never stopped.
    let stopped = tr.stopped.as_ref().expect("the stopped tracker is kept");
    assert_eq!(stopped.next_frame(), n);
    click_label(&mut h, "Continue tracking");
    wait_for_tracking(&mut h);
    let continued = tracking(&h);
    assert!(continued.complete);
    click_label(&mut h, "Track again");
    wait_for_tracking(&mut h);
    let whole = tracking(&h);
    assert_eq!(whole.frames.len(), 150);
    for (a, b) in continued.frames.iter().zip(&whole.frames) {
        assert_eq!(a, b, "frame {}", a.frame);
    }
    assert_eq!(continued.lineage, whole.lineage);
}

#[test]
fn a_division_is_listed_in_the_event_log_and_a_click_shows_its_frame() {
    let (mut h, _movie) = tracked_movie("division", &dividing_rod());
    let tr = h
        .state()
        .doc
        .movie
        .as_ref()
        .unwrap()
        .tracking
        .clone()
        .unwrap();
    assert!(tr.complete);
    assert_eq!(tr.lineage.ctc_text(), "1 0 3 0\n2 4 7 1\n3 4 7 1\n");
    h.state_mut().send(Command::SeekMovieFrame(0));
    h.step();
    assert_eq!(movie_frame(&h), 0);
    h.step(); // laid out for frame 0 (its cell table is shorter than frame 7's)
    click_label(&mut h, "cell 1 divided into 2 and 3 at frame 4");
    assert_eq!(movie_frame(&h), 4);
    assert_eq!(h.state().view.selected_track, Some(1));
    let tracked = h
        .state()
        .doc
        .movie
        .as_ref()
        .unwrap()
        .tracked_frame()
        .unwrap();
    assert_eq!(
        tracked.divisions.len(),
        1,
        "the frame shown is the division's"
    );
}

#[test]
fn keys_and_play_move_through_a_tracked_movie_not_the_evolution() {
    let (mut h, _movie) = tracked_movie("keys", &dividing_rod());
    h.state_mut().send(Command::SeekMovieFrame(0));
    h.step();
    let evolution = h.state().doc.shown;
    h.key_press(egui::Key::ArrowRight);
    h.step();
    assert_eq!(movie_frame(&h), 1);
    h.key_press(egui::Key::E);
    h.step();
    assert_eq!(movie_frame(&h), 4, "the next division's frame");
    assert_eq!(h.state().view.selected_track, Some(1));
    h.key_press(egui::Key::ArrowLeft);
    h.step();
    assert_eq!(movie_frame(&h), 3);
    assert_eq!(h.state().doc.shown, evolution, "the evolution did not step");
    h.key_press(egui::Key::Space);
    h.step();
    assert!(h.state().view.movie_playing && !h.state().view.playing);
    for _ in 0..200 {
        if !h.state().view.movie_playing {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.step();
    }
    assert_eq!(movie_frame(&h), 7, "played to the last frame and stopped");
    assert!(!h.state().view.movie_playing);
    h.step(); // the bar drawn since it stopped
    click_label(&mut h, "Play movie");
    assert!(h.state().view.movie_playing);
    assert!(
        movie_frame(&h) <= 1,
        "at the end, play starts again from frame 0"
    );
    h.step();
    click_label(&mut h, "Pause movie");
    assert!(!h.state().view.movie_playing);
    // Playing stops when another image opens.
    h.step();
    click_label(&mut h, "Play movie");
    assert!(h.state().view.movie_playing);
    h.state_mut()
        .send(Command::OpenImage(case_image("bridge_merge")));
    // The tracking is not saved: asked first.
    h.run_steps(3);
    click_label(&mut h, "Open without saving");
    h.run_steps(2);
    assert!(!h.state().view.movie_playing);
}

#[test]
fn a_division_the_next_frame_takes_back_leaves_the_event_log_and_the_lineage() {
    let (mut h, _movie) = tracked_movie("parting", &parting_nucleus());
    let tr = tracking(&h);
    assert!(tr.complete);
    assert_eq!(tr.lineage.ctc_text(), "1 0 6 0\n");
    assert_eq!(tr.divisions().count(), 0);
    // Frame 3 shows the mother in two pieces, both in her colour and track.
    let tracks: Vec<u32> = tr.frames[3].objects.iter().map(|o| o.track).collect();
    assert_eq!(tracks, [1, 1]);
    h.state_mut().send(Command::SeekMovieFrame(3));
    h.step();
    assert_no_error(&h);
    assert!(h.query_by_label("Divisions (0)").is_some());
}

#[test]
fn the_lineage_view_selects_a_track_and_shows_its_frame() {
    let (mut h, _movie) = tracked_movie("lineage", &dividing_rod());
    // Rows in depth-first order: track 1, then its daughters 2 and 3, 10 px each, in a
    // view inset 4 px across and 8 px down; x runs over frames 0 to 7.
    let r = h.get_by_label("Lineage view").rect();
    let at = |frame: f32, row: f32| {
        egui::pos2(
            r.min.x + 4.0 + (r.width() - 8.0) * frame / 7.0,
            r.min.y + 8.0 + 10.0 * (row + 0.5),
        )
    };
    click_at(&mut h, at(6.0, 2.0));
    assert_eq!(h.state().view.selected_track, Some(3));
    assert_eq!(movie_frame(&h), 6);
    click_at(&mut h, at(1.0, 0.0));
    assert_eq!(h.state().view.selected_track, Some(1));
    assert_eq!(movie_frame(&h), 1);
    // The status bar says which movie frame is on screen.
    h.get_by_label("lineage  |  movie frame 1 of 0–7");
    // Under the pointer, a row says which track it is and what it became.
    h.ctx.all_styles_mut(|s| s.interaction.tooltip_delay = 0.0);
    for (frame, row, says) in [
        (2.0, 0.0, "track 1, frames 0–3, divided into 2 and 3"),
        (5.0, 1.0, "track 2, frames 4–7, from 1"),
    ] {
        // The view moves down as the Objects table above it grows.
        let r = h.get_by_label("Lineage view").rect();
        h.hover_at(egui::pos2(
            r.min.x + 4.0 + (r.width() - 8.0) * frame / 7.0,
            r.min.y + 8.0 + 10.0 * (row + 0.5),
        ));
        for _ in 0..3 {
            h.step();
        }
        h.get_by_label(says);
    }
}

#[test]
fn the_tracking_result_exports_in_the_ctc_layout() {
    let dir = movie_folder("ctc", &dividing_rod());
    let mut h = movie_app(&dir);
    let out = temp("ctc-out");
    let _ = std::fs::remove_dir_all(&out);
    h.state_mut().send(Command::ExportCtc(out.to_path_buf()));
    h.step();
    assert!(h.state().status.error.is_some(), "nothing tracked yet");
    h.state_mut().status.error = None;
    click_label(&mut h, "Track movie");
    wait_for_tracking(&mut h);
    h.state_mut().send(Command::ExportCtc(out.to_path_buf()));
    h.step();
    assert_no_error(&h);
    let res = std::fs::read_to_string(out.join("res_track.txt")).unwrap();
    assert_eq!(res, "1 0 3 0\n2 4 7 1\n3 4 7 1\n");
    let mask = image::open(out.join("mask005.tif")).unwrap().into_luma16();
    let mut labels: Vec<u16> = mask.pixels().map(|p| p.0[0]).collect();
    labels.sort_unstable();
    labels.dedup();
    assert_eq!(labels, [0, 2, 3], "frame 5 holds the two daughters");
    assert!(out.join("mask007.tif").exists());
}

#[test]
fn closing_with_a_tracking_not_exported_asks_first() {
    let (mut h, _movie) = tracked_movie("close", &dividing_rod());
    assert!(!close_window(&mut h));
    h.get_by_label("The tracking of 8 frames is not saved.");
    click_label(&mut h, "Cancel");
    let out = temp("close-ctc");
    let _ = std::fs::remove_dir_all(&out);
    h.state_mut().send(Command::ExportCtc(out.to_path_buf()));
    h.step();
    assert_no_error(&h);
    assert!(close_window(&mut h), "exported");
    click_label(&mut h, "Track again");
    wait_for_tracking(&mut h);
    assert!(!close_window(&mut h), "tracked again since");
    assert_eq!(
        h.get_all_by_label("Export CTC…").count(),
        2,
        "the panel's and the question's"
    );
    click_label(&mut h, "Quit without saving");
    assert!(sent(&h, &egui::ViewportCommand::Close));
    assert!(close_window(&mut h), "not asked twice");
}

#[test]
fn a_tracked_frame_lists_and_exports_its_cells_by_track() {
    let (mut h, _movie) = tracked_movie("table", &dividing_rod());
    h.state_mut().send(Command::SeekMovieFrame(5));
    h.step();
    h.step();
    h.get_by_label("2 cells in movie frame 5");
    let csv = temp("tracks.csv");
    h.state_mut().send(Command::Export(
        topocontour::app::Format::Csv,
        csv.to_path_buf(),
    ));
    h.step();
    assert_no_error(&h);
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows[0], "track,frame,area_px,centroid_x,centroid_y,parent");
    assert_eq!(rows.len(), 1 + 4 + 2 * 4, "every frame's cells: {text}");
    assert!(
        rows[5].starts_with("2,4,") && rows[5].ends_with(",1"),
        "{}",
        rows[5]
    );
    let labels = temp("frame5.labels.tif");
    h.state_mut().send(Command::Export(
        topocontour::app::Format::Labels,
        labels.to_path_buf(),
    ));
    h.step();
    assert_no_error(&h);
    let img = image::open(&labels).unwrap().into_luma16();
    let mut seen: Vec<u16> = img.pixels().map(|p| p.0[0]).collect();
    seen.sort_unstable();
    seen.dedup();
    assert_eq!(seen, [0, 2, 3], "the frame's cells by track");
    // The CSV gives each cell the size it has in the label image.
    let pixels = img.pixels().filter(|p| p.0[0] == 2).count();
    let row = rows.iter().find(|r| r.starts_with("2,5,")).unwrap();
    let area: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
    assert_eq!(area, pixels as f64, "{row}");
    // Open for correction (Edit), the same: by track, not by the run's contour ids.
    click_label(&mut h, "Edit");
    h.step();
    h.step();
    assert!(h.state().doc.run.is_some(), "a correction run on screen");
    let edit = temp("frame5.edit.labels.tif");
    h.state_mut().send(Command::Export(
        topocontour::app::Format::Labels,
        edit.to_path_buf(),
    ));
    h.step();
    assert_no_error(&h);
    let again = image::open(&edit).unwrap().into_luma16();
    assert!(again == img, "the tracked frame's label image, by track");
    click_label(&mut h, "Select");
    h.step();
    let svg = temp("f.svg");
    h.state_mut().send(Command::Export(
        topocontour::app::Format::Svg,
        svg.to_path_buf(),
    ));
    h.step();
    let err = h
        .state()
        .status
        .error
        .as_ref()
        .expect("refused")
        .to_string();
    assert!(err.contains("Measurements CSV"), "{err}");
}

#[test]
fn a_bad_movie_is_refused_with_one_line() {
    let dir = movie_folder("short", &dividing_rod()[..1]);
    let mut app = TopoApp::default();
    app.send(Command::OpenMovie(dir.to_path_buf()));
    let mut h = harness(app);
    h.step();
    let e = h.state().status.error.as_ref().map(|e| e.to_string());
    assert!(
        e.as_deref().is_some_and(|e| e.contains("at least two")),
        "{e:?}"
    );
    assert!(h.state().doc.movie.is_none());
}

fn tracking(h: &Harness<'_, TopoApp>) -> topocontour::app::Tracking {
    h.state()
        .doc
        .movie
        .as_ref()
        .unwrap()
        .tracking
        .clone()
        .unwrap()
}

/// The dividing rod tracked (1 divides into 2 and 3 at frame 4), frame `t` on screen.
fn tracked_rod(name: &str, t: usize) -> (Harness<'static, TopoApp>, Scratch) {
    let (mut h, dir) = tracked_movie(name, &dividing_rod());
    assert_eq!(
        tracking(&h).lineage.ctc_text(),
        "1 0 3 0\n2 4 7 1\n3 4 7 1\n"
    );
    h.state_mut().send(Command::SeekMovieFrame(t));
    h.step();
    assert_eq!(movie_frame(&h), t);
    (h, dir)
}

/// Drags the primary button across the canvas from image point `a` to `b`.
fn drag(h: &mut Harness<'_, TopoApp>, a: Point, b: Point) {
    let (sa, sb) = (
        h.state().screen_from_image(a),
        h.state().screen_from_image(b),
    );
    h.hover_at(sa);
    h.step();
    h.drag_at(sa);
    h.step();
    for k in 1..=12 {
        h.hover_at(sa + (sb - sa) * (k as f32 / 12.0));
        h.step();
    }
    h.drop_at(sb);
    h.step();
    h.step();
}

#[test]
fn a_wrong_split_undone_by_hand_tracks_the_frames_after_it_again() {
    let (mut h, _movie) = tracked_rod("undo-split", 4);
    let before = tracking(&h);
    click_label(&mut h, "Brush");
    h.step();
    assert!(
        h.state().doc.run.is_some(),
        "the Brush tool opens the frame's tracked contours"
    );
    // From inside daughter 2 across the gap into daughter 3: the two become one.
    drag(&mut h, Point::new(38.0, 32.0), Point::new(60.0, 32.0));
    assert_no_error(&h);
    wait_for_tracking(&mut h);
    let tr = tracking(&h);
    assert_ne!(tr.id, before.id, "a new result");
    let f4 = &tr.frames[4];
    let tracks: Vec<u32> = f4.objects.iter().map(|o| o.track).collect();
    assert_eq!(
        tracks,
        [1],
        "one cell at frame 4, the mother's track goes on"
    );
    assert!(f4.divisions.is_empty(), "the division at frame 4 is undone");
    // The edit is logged as one of movie frame 4, not of the correction run's frame 0.
    h.get_by_label_contains("movie frame 4, by hand: ");
    assert!(tr.divisions().all(|d| d.frame > 4));
    assert_eq!(tr.lineage.get(1).unwrap().last, 4);
    assert!(tr.complete, "frames 5 to 7 tracked again");
    assert_eq!(tr.frames.len(), 8);
    assert_eq!(tr.corrected.iter().copied().collect::<Vec<_>>(), [4]);
    // The frames before stay as they were.
    for t in 0..4 {
        assert_eq!(tr.frames[t], before.frames[t], "frame {t}");
    }
    assert!(
        h.get_by_label_contains("corrected by hand: frame 4")
            .rect()
            .width()
            > 0.0
    );
    // Undo brings the tracking before the correction back, division and all.
    h.state_mut().send(Command::Undo);
    h.step();
    wait_for_tracking(&mut h);
    let back = tracking(&h);
    assert_eq!(back.lineage.ctc_text(), before.lineage.ctc_text());
    assert!(back.corrected.is_empty());
    // The status bar tells of the tracking brought back, not of the one undone.
    let notice = h.state().status.notice.clone().unwrap_or_default();
    assert_eq!(
        notice,
        "undone: tracked 8 of 8 frames: 3 tracks, 1 division"
    );
}

#[test]
fn a_tracked_and_corrected_movie_saved_as_a_session_reopens_as_it_was() {
    let (mut h, _movie) = tracked_rod("session", 4);
    click_label(&mut h, "Brush");
    h.step();
    drag(&mut h, Point::new(38.0, 32.0), Point::new(60.0, 32.0));
    wait_for_tracking(&mut h);
    click_label(&mut h, "Select");
    h.state_mut().send(Command::SeekMovieFrame(6));
    h.step();
    let saved = tracking(&h);
    assert_eq!(saved.corrected.iter().copied().collect::<Vec<_>>(), [4]);
    assert!(!close_window(&mut h), "not saved yet");
    click_label(&mut h, "Cancel");
    let path = save_session(&mut h, "movie.session.json");
    assert!(close_window(&mut h), "saved");
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("\"format\":\"topocontour-tracking\""));
    assert!(
        !text.contains("unwanted"),
        "no cell deleted: read as before"
    );
    let mut again = harness(TopoApp::default());
    again
        .state_mut()
        .send(Command::OpenSession(path.to_path_buf()));
    again.step();
    again.step();
    assert_no_error(&again);
    let notice = again.state().status.notice.clone().unwrap_or_default();
    assert!(
        notice.starts_with("session opened: tracked 8 of 8 frames"),
        "{notice}"
    );
    let opened = tracking(&again);
    assert_eq!(opened.frames, saved.frames);
    assert_eq!(opened.lineage, saved.lineage);
    assert_eq!(opened.corrected, saved.corrected);
    assert!(opened.complete);
    assert_eq!(movie_frame(&again), 6, "the frame that was on screen");
    let p = again.state().doc.params();
    assert_eq!(
        p.polarity,
        Polarity::Bright,
        "the document's own parameters"
    );
    assert_ne!(p.mode, topocontour::evolution::Mode::Track);
    again.get_by_label_contains("corrected by hand: frame 4");
    assert!(
        close_window(&mut again),
        "nothing changed since it was opened"
    );
    // A damaged session is one error, nothing opened.
    std::fs::write(
        &path,
        text.replace("\"corrected\":[4]", "\"corrected\":[40]"),
    )
    .unwrap();
    let mut bad = harness(TopoApp::default());
    bad.state_mut()
        .send(Command::OpenSession(path.to_path_buf()));
    bad.step();
    let e = bad.state().status.error.as_ref().map(|e| e.to_string());
    assert!(
        e.as_deref()
            .is_some_and(|e| e.contains("frame 40 corrected but not tracked")),
        "{e:?}"
    );
    assert!(bad.state().doc.movie.is_none());
}

/// With the Edit tool, the cell of the frame on screen at `p` (image pixels) selected
/// with a click and deleted; the tracking once the frames after are tracked again.
fn delete_at(h: &mut Harness<'static, TopoApp>, p: Point) -> topocontour::app::Tracking {
    click_label(h, "Edit");
    h.step();
    let at = h.state().screen_from_image(p);
    click_at(h, at);
    assert!(
        h.state().view.selected_contour.is_some(),
        "a click selects it"
    );
    h.key_press(egui::Key::Delete);
    h.step();
    h.step();
    wait_for_tracking(h);
    tracking(h)
}

#[test]
fn a_cell_deleted_ends_its_track_and_later_corrections_are_asked_about() {
    let (mut h, _movie) = tracked_rod("delete", 6);
    // The daughter on the right.
    let right = tracking(&h).frames[6]
        .objects
        .iter()
        .max_by(|a, b| a.centroid.x.total_cmp(&b.centroid.x))
        .unwrap()
        .track;
    let left = 5 - right;
    let tr = delete_at(&mut h, Point::new(66.0, 32.0));
    assert_eq!(
        tr.lineage.get(right).unwrap().last,
        5,
        "its track ends before frame 6"
    );
    let f6: Vec<u32> = tr.frames[6].objects.iter().map(|o| o.track).collect();
    assert_eq!(f6, [left]);
    assert_eq!(tr.corrected.iter().copied().collect::<Vec<_>>(), [6]);
    // Correcting an earlier frame would track frame 6 again: asked first.
    h.state_mut().send(Command::SeekMovieFrame(5));
    h.step();
    h.step();
    assert_eq!(movie_frame(&h), 5);
    let at = h.state().screen_from_image(Point::new(34.0, 32.0));
    click_at(&mut h, at);
    h.key_press(egui::Key::Delete);
    h.step();
    h.step();
    assert!(
        matches!(
            h.state().view.question,
            Some(topocontour::app::Question::Retrack { frame: 5, .. })
        ),
        "{:?}",
        h.state().view.question
    );
    h.get_by_label_contains("replaces your corrections on frame 6.");
    assert_eq!(
        tracking(&h).frames[6].objects.len(),
        1,
        "nothing replaced yet"
    );
    click_label(&mut h, "Undo my edit");
    h.step();
    assert!(h.state().view.question.is_none());
    let tr = tracking(&h);
    assert_eq!(
        tr.corrected.iter().copied().collect::<Vec<_>>(),
        [6],
        "kept"
    );
    assert_eq!(tr.frames[5].objects.len(), 2, "frame 5 as it was");
    // Tracking again from frame 0 would replace the correction too: asked.
    click_label(&mut h, "Track again");
    h.step();
    assert!(matches!(
        h.state().view.question,
        Some(topocontour::app::Question::TrackAgain(_))
    ));
    click_label(&mut h, "Keep my corrections");
    h.step();
    assert!(h.state().jobs.track.is_none());
    assert_eq!(tracking(&h).corrected.len(), 1);
}

/// Each movie frame shows with its own contrast window, as the first did (a phase-contrast
/// colony's halo grows frame by frame, and frame 0's window showed later frames' ground
/// black); a window the user set stays on every frame.
#[test]
fn each_movie_frame_shows_with_its_own_contrast_unless_the_user_set_one() {
    // A graded grey ground, a speck of a dark cell (under 0.5 % of the frame), and a
    // bright halo growing from nothing to a wide band.
    let frames: Vec<image::GrayImage> = (0..3u32)
        .map(|t| {
            image::GrayImage::from_fn(96, 64, |x, y| {
                let (dx, dy) = (x as f64 - 48.0, y as f64 - 32.0);
                let r = (dx * dx + dy * dy).sqrt();
                image::Luma([if r < 2.5 {
                    30
                } else if r < 3.0 + 8.0 * t as f64 {
                    250
                } else {
                    100 + (x * 40 / 96) as u8
                }])
            })
        })
        .collect();
    let dir = movie_folder("contrast", &frames);
    let mut h = movie_app(&dir);
    let window = |h: &Harness<'_, TopoApp>| h.state().doc.settings.contrast;
    let own = |h: &Harness<'_, TopoApp>| {
        topocontour::app::auto_contrast(h.state().doc.image.as_ref().unwrap())
    };
    assert_eq!(window(&h), own(&h));
    let first = window(&h);
    h.state_mut().send(Command::SeekMovieFrame(2));
    h.step();
    assert_eq!(window(&h), own(&h));
    assert_ne!(window(&h), first, "frame 2's window is its own");
    // The ground shows grey, not black, through it (frame 0's window made it 0).
    let image = h.state().doc.image.clone().unwrap();
    let ground = image.data[60 * image.width + 48];
    let shown = |(lo, hi): (f32, f32)| (ground - lo) / (hi - lo);
    assert!(shown(first) < 0.0, "{ground} {first:?}");
    assert!(shown(window(&h)) > 0.1, "{ground} {:?}", window(&h));
    // A window set by hand stays.
    h.state_mut().send(Command::SetContrast((0.1, 0.9)));
    h.step();
    h.state_mut().send(Command::SeekMovieFrame(1));
    h.step();
    assert_eq!(window(&h), (0.1, 0.9));
}

/// A tracked frame whose cells cover most of it is said with the tracking's summary.
#[test]
fn cells_covering_most_of_a_tracked_frame_are_said() {
    let disk = (Point::new(48.0, 32.0), Point::new(48.0, 32.0), 10.0);
    let wide = (Point::new(20.0, 32.0), Point::new(76.0, 32.0), 31.0);
    let frames = [
        frame(96, 64, &[disk]),
        frame(96, 64, &[disk]),
        frame(96, 64, &[wide]),
    ];
    let (h, _movie) = tracked_movie("crowded", &frames);
    let notice = h.state().status.notice.clone().unwrap_or_default();
    assert!(
        notice.contains("frame 2's cells cover") && notice.contains("check Dark/Bright objects"),
        "{notice}"
    );
}

/// The shapes that started frame 0 are drawn on frame 0 only, once the movie is tracked.
#[test]
fn the_seeds_of_frame_0_are_not_drawn_on_later_tracked_frames() {
    let (mut h, _movie) = tracked_rod("seeds_shown", 0);
    h.state_mut()
        .send(Command::AddShape(topocontour::evolution::Shape::Disk {
            center: Point::new(48.0, 32.0),
            radius: 4.0,
        }));
    h.step();
    assert!(h.state().doc.shapes_shown());
    h.state_mut().send(Command::SeekMovieFrame(5));
    h.step();
    assert!(!h.state().doc.shapes_shown(), "frame 5 is tracked");
    assert_eq!(h.state().doc.shapes.len(), 1, "kept for tracking again");
}

/// Opening a movie over a tracking not saved asks first; Cancel keeps the tracking.
#[test]
fn opening_a_movie_over_a_tracking_not_saved_asks_first() {
    let (mut h, movie) = tracked_rod("open_over", 5);
    let before = tracking(&h);
    h.state_mut().send(Command::OpenMovie(movie.to_path_buf()));
    h.run_steps(3);
    assert!(matches!(
        h.state().view.question,
        Some(topocontour::app::Question::Open(_))
    ));
    h.get_by_label_contains("The tracking of 8 frames is not saved");
    click_label(&mut h, "Cancel");
    h.step();
    assert!(h.state().view.question.is_none());
    assert_eq!(tracking(&h).lineage, before.lineage, "the tracking stays");
    h.state_mut().send(Command::OpenMovie(movie.to_path_buf()));
    h.run_steps(3);
    click_label(&mut h, "Open without saving");
    h.run_steps(2);
    assert!(
        h.state().doc.movie.as_ref().unwrap().tracking.is_none(),
        "opened anew"
    );
}

/// Cells keep their numbers across a correction: the rod deleted before it divides takes
/// its daughters' tracks with it, and the cell appearing later keeps the number the first
/// run gave it (numbered on, it took a daughter's).
#[test]
fn a_correction_leaves_the_numbers_of_later_cells_as_they_were() {
    let rod = |a: f64, b: f64| (Point::new(a, 32.0), Point::new(b, 32.0), 6.0);
    let late = (Point::new(84.0, 52.0), Point::new(84.0, 52.0), 6.0);
    let mut frames: Vec<_> = [10.0, 12.0, 14.0, 16.0]
        .map(|h| frame(96, 64, &[rod(48.0 - h, 48.0 + h)]))
        .into();
    for gap in [3.0, 4.0, 5.0, 6.0] {
        let mut cells = vec![rod(24.0, 42.0 - gap), rod(54.0 + gap, 72.0)];
        if gap >= 4.0 {
            cells.push(late);
        }
        frames.push(frame(96, 64, &cells));
    }
    let (mut h, _movie) = tracked_movie("numbers", &frames);
    let before = tracking(&h);
    let at_late = |f: &topocontour::track::TrackedFrame| {
        (f.objects.iter())
            .find(|o| o.centroid.dist(Point::new(84.0, 52.0)) < 4.0)
            .map(|o| o.track)
    };
    let number = at_late(&before.frames[7]).expect("the first run finds the late cell");
    assert_eq!(
        before.lineage.get(number).map(|t| t.parent),
        Some(0),
        "{}",
        before.lineage.ctc_text()
    );
    assert!(
        number > 3,
        "numbered after the daughters: {}",
        before.lineage.ctc_text()
    );
    h.state_mut().send(Command::SeekMovieFrame(1));
    h.step();
    let tr = delete_at(&mut h, Point::new(48.0, 32.0));
    assert_eq!(tr.divisions().count(), 0, "{}", tr.lineage.ctc_text());
    for t in 5..8 {
        assert_eq!(
            at_late(&tr.frames[t]),
            at_late(&before.frames[t]),
            "frame {t}"
        );
    }
    // Saved and opened again, the numbers stand.
    let path = save_session(&mut h, "numbers.session.json");
    let mut again = harness(TopoApp::default());
    (again.state_mut()).send(Command::OpenSession(path.to_path_buf()));
    again.step();
    again.step();
    assert_no_error(&again);
    assert_eq!(tracking(&again).lineage, tr.lineage);
}

/// A cell deleted by hand changes nothing else: the frames after the correction are
/// tracked again as the first run tracked them (the tracker resumes with what it
/// remembered of the frame), the division of a rod elsewhere included. The deleted cell's
/// track ends, and the speck, still in the image, is not found again as a new cell.
#[test]
fn a_correction_leaves_the_cells_it_did_not_touch_as_they_were() {
    let rod = |a: f64, b: f64| (Point::new(a, 32.0), Point::new(b, 32.0), 6.0);
    let speck = (Point::new(86.0, 9.0), Point::new(86.0, 9.0), 5.0);
    let mut frames: Vec<_> = [10.0, 12.0, 14.0, 16.0]
        .map(|h| frame(96, 64, &[rod(48.0 - h, 48.0 + h), speck]))
        .into();
    for gap in [3.0, 4.0, 5.0, 6.0] {
        let cells = [rod(24.0, 42.0 - gap), rod(54.0 + gap, 72.0), speck];
        frames.push(frame(96, 64, &cells));
    }
    let (mut h, _movie) = tracked_movie("untouched", &frames);
    let before = tracking(&h);
    let far = |f: &topocontour::track::TrackedFrame| {
        f.objects
            .iter()
            .max_by(|a, b| a.centroid.x.total_cmp(&b.centroid.x))
            .map(|o| o.track)
    };
    let gone = far(&before.frames[1]).unwrap();
    h.state_mut().send(Command::SeekMovieFrame(1));
    h.step();
    let tr = delete_at(&mut h, Point::new(86.0, 9.0));
    // The rod the correction did not touch keeps its place and size (the run opened for
    // the correction puts points on its outline's edges): the resumed tracker knows it
    // as the same cell.
    let rod = |f: &topocontour::track::TrackedFrame| {
        let o = f.objects.iter().find(|o| o.track == 1).unwrap();
        (o.area, o.centroid)
    };
    let ((a, c), (a0, c0)) = (rod(&tr.frames[1]), rod(&before.frames[1]));
    assert!(
        (a - a0).abs() < 1e-6 * a0 && c.dist(c0) < 1e-6,
        "{a} {a0} {c:?} {c0:?}"
    );
    assert_eq!(
        tr.lineage.get(gone).unwrap().last,
        0,
        "the deleted cell's track ends"
    );
    let divisions = |t: &topocontour::app::Tracking| {
        t.divisions()
            .map(|d| (d.frame, d.parent, d.children))
            .collect::<Vec<_>>()
    };
    assert_eq!(
        divisions(&tr),
        divisions(&before),
        "the rod divides as it did"
    );
    assert_eq!(divisions(&before)[0].0, 4);
    let near_speck =
        |o: &topocontour::track::TrackedObject| o.centroid.dist(Point::new(86.0, 9.0)) < 6.0;
    for t in 2..8 {
        assert!(
            before.frames[t].objects.iter().any(near_speck),
            "frame {t}: the first run has the speck"
        );
        assert!(
            !tr.frames[t].objects.iter().any(near_speck),
            "frame {t}: the deleted speck is not found again"
        );
        let rods = |f: &topocontour::track::TrackedFrame| {
            let mut cells = (f.objects.iter())
                .filter(|o| !near_speck(o))
                .map(|o| (o.track, o.area, o.centroid))
                .collect::<Vec<_>>();
            cells.sort_by(|a, b| a.2.x.total_cmp(&b.2.x));
            cells
        };
        let (again, was) = (rods(&tr.frames[t]), rods(&before.frames[t]));
        assert_eq!(again.len(), was.len(), "frame {t}");
        for ((k, a, c), (k0, a0, c0)) in again.into_iter().zip(was) {
            assert_eq!(k, k0, "frame {t}: the same track");
            assert!(
                (a - a0).abs() < 0.01 * a0 && c.dist(c0) < 0.2,
                "frame {t}: {a} {a0} {c:?} {c0:?}"
            );
        }
    }
    // Saved and opened again, the tracking still knows where the speck was deleted.
    let path = save_session(&mut h, "untouched.session.json");
    let mut again = harness(TopoApp::default());
    (again.state_mut()).send(Command::OpenSession(path.to_path_buf()));
    again.step();
    again.step();
    assert_no_error(&again);
    let unwanted = |t: &topocontour::app::Tracking| {
        (t.memory.get(&(t.frames.len() - 1))).map_or(Vec::new(), |m| m.unwanted().to_vec())
    };
    assert_eq!(unwanted(&tr).len(), 1);
    assert_eq!(unwanted(&tracking(&again)), unwanted(&tr));
}

/// Dark cells in a bright halo tracked as a generic image: the tracking's summary says
/// they look like phase contrast.
#[test]
fn a_haloed_movie_tracked_as_generic_suggests_phase_contrast() {
    let frames: Vec<image::GrayImage> = (0..3)
        .map(|t| {
            image::GrayImage::from_fn(96, 80, |x, y| {
                let (x, y) = (x as f64 + 0.5, y as f64 + 0.5);
                let d = [(30.0 + t as f64, 30.0), (64.0, 50.0 - t as f64)]
                    .iter()
                    .map(|&(cx, cy)| (x - cx).hypot(y - cy))
                    .fold(f64::INFINITY, f64::min);
                image::Luma([match d {
                    d if d < 9.0 => 30,
                    d if d < 11.0 => 200,
                    _ => 120,
                }])
            })
        })
        .collect();
    let dir = movie_folder("haloed", &frames);
    let mut app = TopoApp::default();
    app.send(Command::OpenMovie(dir.to_path_buf()));
    app.send(Command::SetPolarity(Polarity::Dark));
    let mut h = harness(app);
    h.step();
    click_label(&mut h, "Track movie");
    wait_for_tracking(&mut h);
    let notice = h.state().status.notice.clone().unwrap_or_default();
    assert!(notice.contains("as in phase contrast"), "{notice}");
}

/// A tracked frame opened for correction names its cells by track, on the canvas and in
/// the object table, as the tracked frame did (not by the run's contour ids); a join
/// shows the track the joined cell continues.
#[test]
fn a_frame_being_corrected_shows_its_cells_by_track() {
    let (mut h, _movie) = tracked_rod("by-track", 4);
    click_label(&mut h, "Edit");
    h.step();
    h.step();
    let cells = |h: &Harness<'static, TopoApp>| {
        let mut c: Vec<(u32, Point)> = (h.state().correction_cells())
            .expect("a correction on screen")
            .into_values()
            .collect();
        c.sort_by_key(|v| v.0);
        c.dedup_by_key(|v| v.0);
        c
    };
    let tracked = tracking(&h).frames[4].clone();
    let shown = cells(&h);
    assert_eq!(shown.len(), 2, "{shown:?}");
    for (k, c) in shown {
        let o = tracked.objects.iter().find(|o| o.track == k).unwrap();
        assert!(o.centroid.dist(c) < 0.5, "track {k} where it was tracked");
    }
    h.get_by_label_contains("2 cells in movie frame 4, being corrected");
    // A cell clicked is measured under its track's number.
    let (k, c) = cells(&h)[0];
    let at = h.state().screen_from_image(c);
    click_at(&mut h, at);
    h.step();
    h.get_by_label_contains(&format!("track {k}: area"));
    click_label(&mut h, "Brush");
    h.step();
    drag(&mut h, Point::new(38.0, 32.0), Point::new(60.0, 32.0));
    wait_for_tracking(&mut h);
    let joined = cells(&h);
    assert_eq!(
        joined.iter().map(|v| v.0).collect::<Vec<_>>(),
        [1],
        "the mother goes on"
    );
    h.get_by_label_contains("1 cell in movie frame 4, being corrected");
}

/// On a frame open for correction the arrows still move through the movie, and the
/// frame they reach opens for correction in turn (they once stepped the correction's
/// run, which has no evolution, and said so).
#[test]
fn the_arrows_move_through_frames_being_corrected() {
    let (mut h, _movie) = tracked_rod("arrows", 4);
    click_label(&mut h, "Edit");
    h.step();
    h.step();
    let correcting = |h: &Harness<'static, TopoApp>| {
        (h.state().doc.movie.as_ref()).and_then(|m| m.correcting.map(|c| c.0))
    };
    assert_eq!(correcting(&h), Some(4));
    h.key_press(egui::Key::ArrowRight);
    h.step();
    h.step();
    assert_eq!(movie_frame(&h), 5);
    assert_eq!(
        correcting(&h),
        Some(5),
        "the next frame opens for correction"
    );
    h.key_press(egui::Key::ArrowLeft);
    h.step();
    h.key_press(egui::Key::ArrowLeft);
    h.step();
    h.step();
    assert_eq!(movie_frame(&h), 3);
    assert_eq!(correcting(&h), Some(3));
    assert!(
        tracking(&h).corrected.is_empty(),
        "nothing corrected by moving"
    );
}

/// A frame opened for correction where a rod divided into a short and a long daughter
/// and a cell appeared: each keeps the number it was tracked with (they were numbered
/// again, the larger daughter first, so the preview and a correction there swapped the
/// daughters).
#[test]
fn a_corrected_frame_keeps_the_numbers_of_the_tracks_it_began() {
    let rod = |a: f64, b: f64| (Point::new(a, 32.0), Point::new(b, 32.0), 6.0);
    let disk = |x: f64, y: f64| (Point::new(x, y), Point::new(x, y), 6.0);
    let mut frames: Vec<_> = [10.0, 12.0, 14.0, 16.0]
        .map(|h| frame(96, 64, &[rod(52.0 - h, 52.0 + h)]))
        .into();
    for gap in [3.0, 4.0, 5.0, 6.0] {
        let cells = [
            rod(36.0, 48.0 - gap),
            rod(56.0 + gap, 70.0),
            disk(12.0, 12.0),
        ];
        frames.push(frame(96, 64, &cells));
    }
    let (mut h, _movie) = tracked_movie("numbers", &frames);
    let tr = tracking(&h);
    let t = tr.divisions().next().expect("the rod divides").frame;
    let born: Vec<(u32, u32)> = (tr.lineage.tracks().iter())
        .filter(|k| k.first == t)
        .map(|k| (k.label, k.parent))
        .collect();
    assert_eq!(
        born.len(),
        3,
        "two daughters and a new cell: {}",
        tr.lineage.ctc_text()
    );
    h.state_mut().send(Command::SeekMovieFrame(t));
    h.step();
    click_label(&mut h, "Edit");
    h.step();
    h.step();
    let shown = h
        .state()
        .correction_cells()
        .expect("a correction on screen");
    for o in &tr.frames[t].objects {
        let k = (shown.values())
            .find(|(_, c)| c.dist(o.centroid) < 1.0)
            .map(|v| v.0);
        assert_eq!(k, Some(o.track), "the cell tracked as {}", o.track);
    }
}

/// A movie of bright cells on a dark background opens with Bright objects and says so
/// (tracked as dark objects, a fluorescence movie gave its background); one of dark
/// cells on a lighter ground opens with Dark objects.
#[test]
fn a_movie_opens_with_the_polarity_its_first_frame_shows() {
    let dir = movie_folder("bright-first", &dividing_rod());
    let mut h = harness(TopoApp::default());
    (h.state_mut()).send(Command::OpenMovie(dir.to_path_buf()));
    h.step();
    assert_no_error(&h);
    assert_eq!(h.state().doc.params().polarity, Polarity::Bright);
    let notice = h.state().status.notice.clone().unwrap_or_default();
    assert!(
        notice.contains("bright cells on a dark background, so Bright objects"),
        "{notice}"
    );
    let inverted: Vec<_> = dividing_rod()
        .into_iter()
        .map(|mut f| {
            image::imageops::invert(&mut f);
            f
        })
        .collect();
    let dir = movie_folder("dark-first", &inverted);
    (h.state_mut()).send(Command::OpenMovie(dir.to_path_buf()));
    h.step();
    assert_no_error(&h);
    assert_eq!(h.state().doc.params().polarity, Polarity::Dark);
}
