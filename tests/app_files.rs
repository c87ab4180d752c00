//! The app's files: exports, images and stacks, the path field, folders and large
//! images prepared in the background, driven headless with egui_kittest.
#![cfg(feature = "gui")]

mod app_kit;

use app_kit::*;
use egui_kittest::kittest::Queryable;
use topocontour::app::{Command, Format, Question, TopoApp};

#[test]
fn closing_with_work_not_saved_asks_first() {
    let mut h = sample_after(0);
    assert!(
        close_window(&mut h),
        "the sample as it opened: nothing to lose"
    );
    let mut h = harness(bright_bridge_with_seeds(&[]));
    h.step();
    assert!(close_window(&mut h), "an image opened: nothing to lose");
    let seed = |h: &mut egui_kittest::Harness<'_, TopoApp>, x| {
        h.state_mut()
            .send(Command::AddShape(topocontour::evolution::Shape::Disk {
                center: topocontour::Point::new(x, 40.0),
                radius: 5.0,
            }));
        h.step();
    };
    seed(&mut h, 40.0);
    assert!(!close_window(&mut h), "a seed clicked: asked");
    h.get_by_label_contains("not saved as a session");
    h.get_by_label("Save session…");
    click_label(&mut h, "Cancel");
    assert!(h.state().view.question.is_none());
    save_session(&mut h, "close.json");
    assert!(close_window(&mut h), "saved");
    seed(&mut h, 60.0);
    assert!(!close_window(&mut h), "changed after the save");
    click_label(&mut h, "Quit without saving");
    assert!(sent(&h, &egui::ViewportCommand::Close));
    assert!(close_window(&mut h), "not asked twice");
}

/// Sends `open` and answers "Open without saving" when it asks.
fn open_over(h: &mut egui_kittest::Harness<'_, TopoApp>, open: Command) {
    h.state_mut().send(open);
    // Applied at the next frame; its question shows from the one after.
    h.run_steps(3);
    if matches!(h.state().view.question, Some(Question::Open(_))) {
        click_label(h, "Open without saving");
        h.step();
        h.step();
    }
}

#[test]
fn opening_over_work_not_saved_asks_first_and_the_work_waits_in_undo() {
    let mut h = harness(bright_bridge_with_seeds(&[(40.0, 40.0, 5.0)]));
    h.step();
    let work =
        |h: &egui_kittest::Harness<'_, TopoApp>| h.state().unsaved_work().unwrap_or_default();
    // Another image asked to open over the seed: asked first; Cancel keeps the seed.
    h.state_mut()
        .send(Command::OpenImage(case_image("blobs_wrap")));
    h.run_steps(3);
    assert!(
        matches!(h.state().view.question, Some(Question::Open(_))),
        "asked before opening"
    );
    h.get_by_label_contains("not saved as a session");
    click_label(&mut h, "Cancel");
    h.step();
    assert!(h.state().view.question.is_none());
    assert_eq!(h.state().doc.shapes.len(), 1, "the seed stays");
    // Opened without saving: the image has nothing to save, the seed is in Undo, and
    // closing says so.
    open_over(&mut h, Command::OpenImage(case_image("blobs_wrap")));
    assert_no_error(&h);
    assert!(h.state().doc.shapes.is_empty(), "the image opened");
    assert!(!close_window(&mut h), "the seed waits in Undo: asked");
    h.get_by_label_contains("before you opened image.png");
    assert!(!work(&h).contains("as a session"), "{}", work(&h));
    click_label(&mut h, "Cancel");
    // Undo: the seed is on screen again, and the question is about it.
    h.state_mut().send(Command::Undo);
    h.step();
    assert_eq!(h.state().doc.shapes.len(), 1);
    assert!(work(&h).contains("not saved as a session"), "{}", work(&h));
    assert!(!work(&h).contains("before you opened"), "{}", work(&h));
    // A session saved, a seed added, the session opened again over it: the same.
    let path = save_session(&mut h, "reopen.json");
    h.state_mut()
        .send(Command::AddShape(topocontour::evolution::Shape::Disk {
            center: topocontour::Point::new(60.0, 40.0),
            radius: 5.0,
        }));
    h.step();
    open_over(&mut h, Command::OpenSession(path.to_path_buf()));
    assert_no_error(&h);
    assert_eq!(h.state().doc.shapes.len(), 1, "the session's one seed");
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let replaced =
        format!("Your work before you opened {name} is not saved (Undo brings it back).");
    assert_eq!(work(&h), replaced);
    // A seed on the opened session, then Undo: the work before it is still only in Undo.
    seed_at(&mut h, 20.0);
    h.state_mut().send(Command::Undo);
    h.step();
    assert!(work(&h).ends_with(&replaced), "{}", work(&h));
    // A file that does not open changes nothing.
    open_over(&mut h, Command::OpenImage("/nonexistent/x.png".into()));
    assert!(h.state().status.error.is_some());
    assert_eq!(h.state().doc.shapes.len(), 1);
    assert!(work(&h).ends_with(&replaced), "{}", work(&h));
    // Nothing unsaved: an opened file asks nothing, nor does a failed open.
    let mut h = harness(bright_bridge_with_seeds(&[]));
    h.step();
    h.state_mut().send(Command::OpenSession(path.to_path_buf()));
    h.step();
    h.state_mut()
        .send(Command::OpenImage("/nonexistent/x.png".into()));
    h.step();
    assert!(close_window(&mut h), "nothing to lose: not asked");
    // A session whose image changed on disk opens its image, then fails: the document
    // before it stays on screen, seeds and all.
    let image = temp("changing.png");
    std::fs::copy(case_image("bridge_merge"), &image).unwrap();
    let mut h = harness(TopoApp::default());
    h.state_mut().send(Command::OpenImage(image.to_path_buf()));
    h.step();
    seed_at(&mut h, 40.0);
    let session = save_session(&mut h, "changing.json");
    seed_at(&mut h, 60.0);
    std::fs::copy(case_image("blobs_wrap"), &image).unwrap();
    open_over(&mut h, Command::OpenSession(session.to_path_buf()));
    assert!(h.state().status.error.is_some(), "the image changed");
    assert_eq!(h.state().doc.shapes.len(), 2);
    assert!(work(&h).contains("not saved as a session"), "{}", work(&h));
}

/// A session named on the command line (`topocontour FILE.json`) opens as a session.
#[test]
fn a_session_given_on_the_command_line_opens_as_one() {
    let mut h = harness(TopoApp::default());
    h.state_mut()
        .send(Command::OpenImage(case_image("bridge_merge")));
    h.step();
    seed_at(&mut h, 40.0);
    let path = save_session(&mut h, "argument.session.json");
    let app = TopoApp::new(None, Some(path.to_path_buf()));
    assert!(app.status.error.is_none(), "{:?}", app.status.error);
    assert_eq!(app.doc.shapes.len(), 1, "the session's seed");
}

/// Adds a seed disk at (`x`, 40).
fn seed_at(h: &mut egui_kittest::Harness<'_, TopoApp>, x: f64) {
    h.state_mut()
        .send(Command::AddShape(topocontour::evolution::Shape::Disk {
            center: topocontour::Point::new(x, 40.0),
            radius: 5.0,
        }));
    h.step();
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
        .send(Command::Export(Format::Svg, path.to_path_buf()));
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

/// The app exports a label image and an ImageJ ROI set of the frame on screen.
#[test]
fn export_labels_and_roi_set() {
    let mut h = harness(TopoApp::with_sample());
    h.step();
    h.state_mut().send(Command::Step(60));
    h.step();
    let (tif, zip) = (temp("labels.tif"), temp("rois.zip"));
    h.state_mut()
        .send(Command::Export(Format::Labels, tif.to_path_buf()));
    h.state_mut()
        .send(Command::Export(Format::Roi, zip.to_path_buf()));
    h.step();
    assert_no_error(&h);
    let labels = image::open(&tif).expect("label image").to_luma16();
    let max = labels.pixels().map(|p| p.0[0]).max().unwrap();
    let archive = zip::ZipArchive::new(std::fs::File::open(&zip).unwrap()).unwrap();
    assert!(max >= 1);
    assert_eq!(archive.len(), max as usize, "one ROI per label");
}

/// A 16-bit image whose data fill 12 bits is read stretched to fill [0, 1]
/// (`io::movie::widen_narrow`), and opens with a contrast window around it.
#[test]
fn a_twelve_bit_image_opens_with_its_own_contrast() {
    let img = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(64, 48, |x, y| {
        image::Luma([((x * 61 + y * 13) % 4096) as u16])
    });
    let path = temp("app-12bit.tif");
    img.save(&path).unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path.to_path_buf()));
    let mut h = harness(app);
    h.step();
    let (lo, hi) = h.state().doc.settings.contrast;
    assert!(lo < 0.01 && hi > 0.95, "{lo} {hi}");
}

/// Without a desktop portal a file dialog gives no path: the built-in path field takes
/// a typed one (here: open an image, then export next to it under the image's name).
#[test]
fn the_path_field_stands_in_for_a_file_dialog() {
    use topocontour::app::PathPurpose;
    let mut h = harness(TopoApp::default());
    h.step();
    type_path(
        &mut h,
        PathPurpose::OpenImage,
        case_image("bridge_merge").display().to_string(),
    );
    assert_no_error(&h);
    assert_eq!(h.state().doc.image_name, "image.png");
    assert!(h.state().view.path_prompt.is_none());
    assert_eq!(Format::Labels.file_name("image"), "image.labels.tif");
    let out = temp("prompt.svg");
    h.state_mut().send(Command::WrapBorder(4.0));
    h.state_mut().send(Command::Step(2));
    h.step();
    type_path(
        &mut h,
        PathPurpose::Export(Format::Svg),
        out.display().to_string(),
    );
    assert_no_error(&h);
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
    h.state_mut().send(Command::OpenImage(path.to_path_buf()));
    h.step();
    assert_no_error(&h);
    assert!(notice(&h).contains("3 pages"));
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
        .send(Command::Export(Format::Csv, csv.to_path_buf()));
    h.step();
    assert_no_error(&h);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(
        text.lines().nth(1).unwrap().contains(",0.0001,\"cm\","),
        "{text}"
    );
    let _ = std::fs::remove_file(path);
    let _ = std::fs::remove_file(csv);
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
    app.send(Command::ApplyToFolder(dir.to_path_buf()));
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
    app.send(Command::OpenImage(path.to_path_buf()));
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
    assert_no_error(&h);
    assert_eq!(
        h.state().doc.shown,
        3,
        "the steps asked meanwhile were done"
    );
    let _ = std::fs::remove_file(path);
}
