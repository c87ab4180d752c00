//! Measures the app's frame cost with about 20,000 contour vertices: a 1600×1600 image of
//! 400 cells, shrink-wrapped until the contours settle on the cells at full resolution,
//! then the time of one `Step` (evolution + record) and of one UI frame (panels, canvas,
//! filled regions) through the headless egui harness — which builds every shape but does
//! not rasterise them (the GPU does that in the real window).
//!
//! `cargo run --release --example app_frame_time`

use egui_kittest::Harness;
use std::time::Instant;
use topocontour::app::{Command, TopoApp};

fn main() {
    let (w, h) = (1600u32, 1600u32);
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
    // Evolve until the contours sit on the cells at full resolution.
    while harness
        .state()
        .shown_record()
        .is_none_or(|r| r.vertices < 20_000)
    {
        harness.state_mut().send(Command::Step(1));
        harness.step();
        let r = harness.state().shown_record().unwrap();
        if r.index > 2000 || r.converged {
            break;
        }
    }
    let r = harness.state().shown_record().unwrap();
    println!(
        "frame {} with {} vertices in {} contours",
        r.index, r.vertices, r.contours
    );
    let (mut step_ms, mut ui_ms, mut paused_ms) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..20 {
        // One frame of evolution: every vertex moves once (the engine keeps stepping even
        // once converged; the app's Step would stop there).
        let t = Instant::now();
        let f = harness.state_mut().run.as_mut().unwrap().evolver.step();
        step_ms.push(t.elapsed().as_secs_f64() * 1e3);
        assert!(f.vertices >= 20_000);
        // One UI frame while playing (regions outlined), and one paused (filled, cached).
        harness.state_mut().playing = true;
        let t = Instant::now();
        harness.step();
        ui_ms.push(t.elapsed().as_secs_f64() * 1e3);
        harness.state_mut().playing = false;
        let t = Instant::now();
        harness.step();
        paused_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (s, u, p) = (med(&mut step_ms), med(&mut ui_ms), med(&mut paused_ms));
    println!("evolution step median {s:.2} ms; UI frame while playing {u:.2} ms (step + UI {:.2} ms); paused UI frame {p:.2} ms", s + u);
}
