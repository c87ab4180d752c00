//! Measures the app's frame cost with about 20,000 contour vertices: a 1600×1600 image of
//! 400 cells, shrink-wrapped until the contours settle on the cells at full resolution,
//! then the time of one `Step` (evolution + record) and of one UI frame (panels, canvas,
//! filled regions) through the headless egui harness — which builds every shape but does
//! not rasterise them (the GPU does that in the real window).
//!
//! `cargo run --release --example app_frame_time [SIDE]`: SIDE (default 1600, 400 cells,
//! about 31,000 vertices) sets the image side; 1280 gives 256 cells, about 20,000 vertices.

use egui_kittest::Harness;
use std::time::Instant;
use topocontour::app::{Command, TopoApp};

fn main() {
    let side: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(1600);
    let (w, h) = (side, side);
    let mut img = image::GrayImage::new(w, h);
    for (x, y, p) in img.enumerate_pixels_mut() {
        let (cx, cy) = ((x % 80) as f64 - 40.0 + 0.5, (y % 80) as f64 - 40.0 + 0.5);
        let inside = cx * cx + cy * cy < 26.0 * 26.0;
        let noise = ((x * 7919 + y * 104_729) % 23) as f64 - 11.0;
        p.0[0] = ((if inside { 70.0 } else { 180.0 }) + noise) as u8;
    }
    let path = std::env::temp_dir().join("topocontour-frame-time.png");
    img.save(&path).unwrap();
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(path));
    app.send(Command::WrapBorder(4.0));
    app.apply();
    let mut harness = Harness::builder()
        .with_size(egui::vec2(1400.0, 900.0))
        .build_ui_state(|ui, app: &mut TopoApp| app.ui(ui), app);
    harness.step();
    // Evolve until the contours are at full resolution (at least 1/2 vertex per pixel of
    // perimeter: 50 per cell and more).
    let cells = (side / 80) as usize * (side / 80) as usize;
    let wanted = 50 * cells;
    while harness
        .state()
        .shown_record()
        .is_none_or(|r| r.vertices < wanted)
    {
        harness.state_mut().send(Command::Step(1));
        harness.step();
        if harness.state().shown_record().unwrap().index > 3000 {
            panic!("never reached {wanted} vertices");
        }
    }
    let r = harness.state().shown_record().unwrap();
    println!(
        "frame {} with {} vertices in {} contours",
        r.index, r.vertices, r.contours
    );
    // Play at one evolution frame per UI frame: each harness step is then exactly one
    // frame step plus drawing (outlines; filling waits for a pause at this size).
    harness.state_mut().view.prefs.speed = 1.0;
    harness.state_mut().view.playing = true;
    let mut frame_ms = Vec::new();
    let mut parts = Vec::new();
    let mut sizes = Vec::new();
    for _ in 0..30 {
        let before = harness.state().doc.shown;
        let t = Instant::now();
        harness.step();
        let ms = t.elapsed().as_secs_f64() * 1e3;
        if harness.state().doc.shown != before + 1 {
            break; // converged: nothing was stepped
        }
        frame_ms.push(ms);
        parts.push((
            harness.state().status.step_ms,
            harness.state().status.draw_ms,
        ));
        sizes.push(harness.state().shown_record().unwrap().vertices);
    }
    assert!(frame_ms.len() >= 3, "measured while evolving");
    frame_ms.sort_by(f64::total_cmp);
    println!(
        "{} frames at {}..{} vertices: step + draw median {:.2} ms, max {:.2} ms",
        frame_ms.len(),
        sizes.iter().min().unwrap(),
        sizes.iter().max().unwrap(),
        frame_ms[frame_ms.len() / 2],
        frame_ms[frame_ms.len() - 1]
    );
    parts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let steps = parts[parts.len() / 2].0;
    parts.sort_by(|a, b| a.1.total_cmp(&b.1));
    println!(
        "of which: evolution step (with recording) median {steps:.2} ms, canvas {:.2} ms",
        parts[parts.len() / 2].1
    );
    // Paused: the regions get filled (spade triangulation), once per frame shown.
    harness.state_mut().view.playing = false;
    let t = Instant::now();
    harness.step();
    println!(
        "first paused frame (triangulating the fill) {:.2} ms",
        t.elapsed().as_secs_f64() * 1e3
    );
    let t = Instant::now();
    harness.step();
    println!(
        "next paused frame (fill cached) {:.2} ms",
        t.elapsed().as_secs_f64() * 1e3
    );
}
