//! Tracking on small synthetic movies made here (bright cells on a dark background): a
//! rod that divides, two touching cells that must stay two, a cell entering at the
//! border, a cell leaving. Tracks and parents asserted exactly, as `res_track.txt` lists
//! them (label, first frame, last frame, parent).

use topocontour::evolution::{Field, Params, Polarity};
use topocontour::geometry::Point;
use topocontour::track::{TrackSettings, Tracker};

const W: usize = 96;
const H: usize = 64;

/// A frame with bright capsules (segments `a`–`b` thickened by `r`) on a dark background.
fn frame(capsules: &[(Point, Point, f64)]) -> Field {
    let mut data = vec![0.15f32; W * H];
    for y in 0..H {
        for x in 0..W {
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
            if inside {
                data[y * W + x] = 0.85;
            }
        }
    }
    Field::new(W, H, data)
}

fn disk(x: f64, y: f64, r: f64) -> (Point, Point, f64) {
    (Point::new(x, y), Point::new(x, y), r)
}

/// Tracks `frames`; returns the CTC track lines.
fn track(frames: &[Field]) -> String {
    let params = Params {
        polarity: Polarity::Bright,
        ..Params::default()
    };
    let mut tracker = Tracker::new(TrackSettings::new(params), Vec::new());
    for f in frames {
        tracker.step(f).unwrap();
    }
    tracker.lineage().ctc_text()
}

#[test]
fn a_dividing_rod_gives_two_children_of_its_track() {
    let rod = |half: f64| {
        (
            Point::new(48.0 - half, 32.0),
            Point::new(48.0 + half, 32.0),
            6.0,
        )
    };
    let mut frames: Vec<Field> = [10.0, 12.0, 14.0, 16.0].map(|h| frame(&[rod(h)])).into();
    // Divided: two rods with a gap between them, drifting apart.
    for gap in [3.0, 4.0, 5.0, 6.0] {
        let l = (
            Point::new(48.0 - 24.0, 32.0),
            Point::new(48.0 - gap - 6.0, 32.0),
            6.0,
        );
        let r = (
            Point::new(48.0 + gap + 6.0, 32.0),
            Point::new(48.0 + 24.0, 32.0),
            6.0,
        );
        frames.push(frame(&[l, r]));
    }
    assert_eq!(track(&frames), "1 0 3 0\n2 4 7 1\n3 4 7 1\n");
}

#[test]
fn two_touching_cells_stay_two() {
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let s = t as f64;
            frame(&[disk(36.0 + s, 32.0, 11.0), disk(57.0 + s, 32.0, 11.0)])
        })
        .collect();
    assert_eq!(track(&frames), "1 0 4 0\n2 0 4 0\n");
}

#[test]
fn a_cell_entering_at_the_border_starts_a_track() {
    let frames: Vec<Field> = (0..6)
        .map(|t| {
            let mut cells = vec![disk(60.0, 32.0, 10.0)];
            if t >= 2 {
                // Enters from the left edge: half of it visible at frame 2.
                cells.push(disk(-10.0 + 5.0 * t as f64, 28.0, 10.0));
            }
            frame(&cells)
        })
        .collect();
    assert_eq!(track(&frames), "1 0 5 0\n2 2 5 0\n");
}

#[test]
fn a_cell_leaving_ends_its_track() {
    let frames: Vec<Field> = (0..6)
        .map(|t| {
            let mut cells = vec![disk(30.0, 32.0, 10.0)];
            if t < 3 {
                // Leaves across the right edge: gone from frame 3.
                cells.push(disk(70.0 + 8.0 * t as f64, 32.0, 10.0));
            }
            frame(&cells)
        })
        .collect();
    assert_eq!(track(&frames), "1 0 5 0\n2 0 2 0\n");
}
