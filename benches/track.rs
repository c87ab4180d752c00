//! Tracking speed (issue 26: ≤ 30 ms CPU per 512² frame for a 60-cell colony): a
//! deterministic 512×512 movie of 60 bright cells (radius 9–12 px) on a noisy background,
//! each drifting a pixel or two per frame, tracked frame by frame with the defaults
//! (`Tracker::step`, the same path as `topocontour track`). Prints the CPU time per frame
//! after the first, mean and median (the first frame places automatic seeds over the
//! whole image; later ones start from the contours before; from frame 13 on, cells
//! touch), the tracks found, and, once after all runs, the peak resident memory (the
//! runs are alike, so it is one run's).
//!
//! `cargo bench --bench track` (`-- FRAMES` for another length, default 20; `-- --runs N`
//! tracks the movie N times, default 3, and prints each run and the quietest).

use topocontour::evolution::{Field, Params, Polarity};
use topocontour::geometry::Point;
use topocontour::track::{TrackSettings, Tracker};

const SIDE: usize = 512;

/// Frame `t`: 60 cells on a 10 × 6 grid, each on its own slow drift.
fn frame(t: usize) -> Field {
    let mut data = vec![0f32; SIDE * SIDE];
    for (idx, v) in data.iter_mut().enumerate() {
        let (x, y) = (idx % SIDE, idx / SIDE);
        let h = (x as u64 * 73_856_093) ^ (y as u64 * 19_349_663) ^ (t as u64 * 83_492_791);
        *v = 0.2 + ((h % 1000) as f32 / 1000.0 - 0.5) * 0.1;
    }
    for k in 0..60usize {
        let (i, j) = (k % 10, k / 10);
        let a = k as f64 * 2.399;
        let c = Point::new(
            26.0 + 51.0 * i as f64 + 1.2 * t as f64 * a.cos(),
            43.0 + 85.0 * j as f64 + 1.2 * t as f64 * a.sin(),
        );
        let r = 9.0 + 3.0 * (k as f64 * 0.618_034).fract();
        let (x0, x1) = (
            (c.x - r - 1.0).max(0.0) as usize,
            ((c.x + r + 1.0) as usize).min(SIDE - 1),
        );
        let (y0, y1) = (
            (c.y - r - 1.0).max(0.0) as usize,
            ((c.y + r + 1.0) as usize).min(SIDE - 1),
        );
        for y in y0..=y1 {
            for x in x0..=x1 {
                if Point::new(x as f64 + 0.5, y as f64 + 0.5).dist(c) <= r {
                    data[y * SIDE + x] += 0.5;
                }
            }
        }
    }
    Field::new(SIDE, SIDE, data)
}

/// CPU seconds of this process so far (user + system), from the kernel's per-process
/// clock: nanosecond resolution, where getrusage may count whole scheduler ticks.
fn cpu_seconds() -> f64 {
    // SAFETY: clock_gettime only writes the struct it is given.
    let mut t: libc::timespec = unsafe { std::mem::zeroed() };
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// Peak resident memory of this program, MiB: `VmHWM` of /proc/self/status. Not
/// getrusage's `ru_maxrss`, which keeps across exec the high-water mark of the process
/// that started us (under `cargo bench`, cargo's own ~90 MiB).
fn peak_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// One tracking of the `frames`-frame movie: frame 0's CPU seconds, each later frame's,
/// the cells of the last frame, the tracks.
fn run(frames: usize) -> (f64, Vec<f64>, usize, usize) {
    let params = Params {
        polarity: Polarity::Bright,
        ..Params::default()
    };
    let mut tracker = Tracker::new(TrackSettings::new(params), Vec::new());
    let (mut first, mut rest, mut cells) = (0.0, Vec::new(), 0);
    for t in 0..frames {
        let image = frame(t);
        let before = cpu_seconds();
        let f = tracker.step(&image).expect("tracking a frame");
        let spent = cpu_seconds() - before;
        if t == 0 {
            first = spent;
        } else {
            rest.push(spent);
        }
        cells = f.objects.len();
    }
    (first, rest, cells, tracker.lineage().tracks().len())
}

fn main() {
    // `-- FRAMES` and `--runs N`; cargo's own `--bench` is passed along and ignored.
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = args
        .iter()
        .position(|a| a == "--runs")
        .map(|i| {
            args.get(i + 1)
                .and_then(|v| v.parse().ok())
                .expect("--runs takes a whole number of runs")
        })
        .unwrap_or(3)
        .max(1);
    let frames: usize = args
        .iter()
        .enumerate()
        .filter(|(i, _)| *i == 0 || args[i - 1] != "--runs")
        .find_map(|(_, a)| a.parse().ok())
        .unwrap_or(20);
    // The same movie tracked `runs` times: a shared machine's speed swings between
    // runs (by half on the VMs this was measured on), and the quietest run is the
    // nearest to the code's own cost; every run is printed beside it.
    let mut means = Vec::new();
    for k in 1..=runs {
        let (first, mut rest, cells, tracks) = run(frames);
        // The mean is the figure: it counts the frames where cells touch and where new
        // cells are looked for. The median, a typical frame, shows what those add.
        let mean = rest.iter().sum::<f64>() / rest.len().max(1) as f64;
        rest.sort_by(f64::total_cmp);
        let median = rest.get(rest.len() / 2).copied().unwrap_or(0.0);
        println!(
            "track 512x512, 60 cells, {frames} frames, run {k} of {runs}: frame 0 {:.1} ms CPU, later frames {:.1} ms CPU each (median {:.1}); {} cells in the last frame, {} tracks",
            first * 1e3,
            mean * 1e3,
            median * 1e3,
            cells,
            tracks,
        );
        means.push(mean);
    }
    let (best, worst) = means
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(b, w), &m| (b.min(m), w.max(m)));
    println!(
        "later frames: {:.1} ms CPU each in the quietest of {runs} runs ({:.1} in the slowest); peak RSS {}",
        best * 1e3,
        worst * 1e3,
        peak_mib().map_or("unknown".into(), |m| format!("{m:.0} MiB"))
    );
}
