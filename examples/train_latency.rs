//! The Train tool's stroke-to-map latency (issue 25: the probability map updates within
//! 0.3 s of a stroke), measured through the real `TopoApp::ui` headless (egui_kittest):
//! an image and `scribbles.py`'s strokes of it (0 none, 1 background, 2 object, 3
//! boundary) are read, the Train tool is chosen (the trainer computes the image's
//! features then, and keeps them), the strokes are set and their first map waited for,
//! then strokes are added one at a time — a short
//! segment painted as the canvas paints it, on a pixel the strokes already label — and
//! frames are drawn until each stroke's map is the one on screen.
//!
//! Prints, per stroke, what the user sees: the wall time from the paint to the first
//! frame that drew the map's half-resolution preview and to the frame that drew the
//! full map (the trainer's own request-to-answer figure beside it), and the process's
//! CPU seconds meanwhile (all threads, the frames included); then the medians; then
//! pairs of strokes one frame apart (the second's map; the first is stopped); and the
//! last strokes trained and predicted again outside the app (its cost alone, and
//! whether the map is the app's).
//!
//! `cargo run --release --features gui --example train_latency -- IMAGE STROKES [N]`

use egui_kittest::Harness;
use std::path::Path;
use std::time::{Duration, Instant};
use topocontour::app::{Command, Tool, TopoApp, Training};
use topocontour::geometry::Point;
use topocontour::learn::Strokes;

/// CPU seconds of this process so far (user + system, every thread).
fn cpu_seconds() -> f64 {
    // SAFETY: getrusage writes the struct we pass and nothing else.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// Draws frames until the map of the strokes now painted is on screen; the wall seconds
/// from `t0` to the first frame that drew its preview (or the map, when no preview
/// came first), and to the frame that drew the map.
fn wait_for_map(h: &mut Harness<'_, TopoApp>, t0: Instant) -> (f64, f64) {
    let mut preview = None;
    loop {
        h.step();
        let app = h.state();
        let key = app.doc.train.key(app.doc.image.as_ref().expect("image"));
        let t = t0.elapsed().as_secs_f64();
        if key.is_some_and(|k| app.jobs.trainer.preview_of(k).is_some()) {
            preview.get_or_insert(t);
        }
        if key.is_some_and(|k| app.jobs.trainer.map_of(k).is_some()) {
            return (preview.unwrap_or(t), t);
        }
        assert!(t < 120.0, "no map came");
        std::thread::sleep(Duration::from_millis(1));
    }
}

/// Paints a short segment (as the canvas paints a stroke) at labelled pixel `i`.
fn paint_at(h: &mut Harness<'_, TopoApp>, s: &Strokes, i: usize) {
    let (w, ht) = (s.width, s.height);
    let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
    let seg = [Point::new(x - 2.0, y), Point::new(x + 2.0, y)];
    h.state_mut()
        .doc
        .train
        .paint(seg, 1.5, s.labels[i], (w, ht));
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [image, strokes, rest @ ..] = args.as_slice() else {
        eprintln!("usage: train_latency IMAGE STROKES [N]");
        std::process::exit(2);
    };
    let n: usize = rest.first().and_then(|a| a.parse().ok()).unwrap_or(9);
    let mut app = TopoApp::default();
    app.send(Command::OpenImage(image.into()));
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .build_ui_state(|ui, app: &mut TopoApp| app.ui(ui), app);
    h.step();
    let (w, ht) = {
        let img = h.state().doc.image.as_ref().expect("the image opened");
        (img.width, img.height)
    };
    let s = Strokes::read(Path::new(strokes), w, ht).expect("strokes");
    // The Train tool chosen: the trainer computes the image's features at once.
    let t0 = Instant::now();
    h.state_mut().send(Command::SetTool(Tool::Train));
    while !h
        .state()
        .jobs
        .trainer
        .features_ready(h.state().doc.image.as_ref().expect("image"))
    {
        h.step();
        std::thread::sleep(Duration::from_millis(1));
    }
    println!(
        "features ready {:.3} s after the Train tool was chosen",
        t0.elapsed().as_secs_f64()
    );
    let (c0, t0) = (cpu_seconds(), Instant::now());
    h.state_mut().doc.train = Training::of_strokes(&s);
    let (p, m) = wait_for_map(&mut h, t0);
    println!(
        "{w}x{ht}: first map (training, prediction) preview shown {p:.3} s, map shown {m:.3} s wall, cpu {:.3} s",
        cpu_seconds() - c0
    );
    // Evenly spread labelled pixels: each is where one more stroke goes.
    let labelled: Vec<usize> = (0..w * ht).filter(|&i| s.labels[i] > 0).collect();
    let at = |k: usize, n: usize| labelled[(2 * k + 1) * labelled.len() / (2 * n)];
    let (mut previews, mut walls, mut cpus) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..n {
        let (c0, t0) = (cpu_seconds(), Instant::now());
        paint_at(&mut h, &s, at(k, n));
        let (p, wall) = wait_for_map(&mut h, t0);
        let cpu = cpu_seconds() - c0;
        let ms = h.state().jobs.trainer.latency_ms.unwrap_or(f64::NAN);
        println!(
            "stroke {k} (label {}): preview shown {p:.3} s, map shown {wall:.3} s wall (trainer {:.3} s), cpu {cpu:.3} s",
            s.labels[at(k, n)],
            ms / 1e3
        );
        previews.push(p);
        walls.push(wall);
        cpus.push(cpu);
    }
    println!(
        "median of {n} strokes: preview shown {:.3} s, map shown {:.3} s wall, cpu {:.3} s",
        median(previews),
        median(walls),
        median(cpus)
    );
    // Two strokes one frame apart (the second while the first is trained): the wall
    // time from the second to its map on screen.
    let mut pairs = Vec::new();
    for k in 0..n.min(5) {
        paint_at(&mut h, &s, at(k, 2 * n));
        h.step();
        let t0 = Instant::now();
        paint_at(&mut h, &s, at(k + n, 2 * n));
        pairs.push(wait_for_map(&mut h, t0));
    }
    let (p2, m2): (Vec<f64>, Vec<f64>) = pairs.into_iter().unzip();
    println!(
        "two strokes a frame apart, median of {}: the second's preview shown {:.3} s, map shown {:.3} s",
        p2.len(),
        median(p2),
        median(m2)
    );
    // The last map's classifier again, here: its prediction alone.
    let img = h.state().doc.image.clone().expect("image");
    let taught = &h.state().jobs.trainer.map.as_ref().expect("map").taught;
    let features = topocontour::learn::FeatureSet::default().compute(w, ht, &img.data);
    let strokes = h.state().doc.train.strokes(w, ht).expect("strokes");
    let (c0, t0) = (cpu_seconds(), Instant::now());
    let c = topocontour::learn::Classifier::train(&features, &strokes, &Default::default());
    let (c1, t1) = (cpu_seconds(), Instant::now());
    let p = c.predict(&features);
    println!(
        "alone: train cpu {:.3} s wall {:.3}, predict cpu {:.3} s wall {:.3} s, same map {}, {} nodes",
        c1 - c0,
        (t1 - t0).as_secs_f64(),
        cpu_seconds() - c1,
        t1.elapsed().as_secs_f64(),
        p == taught.probabilities,
        c.forest.nodes.len()
    );
}
