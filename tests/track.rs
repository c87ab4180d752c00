//! Tracking on small synthetic movies made here (bright cells on a dark background): a
//! rod that divides, two touching cells that must stay two, a cell entering at the
//! border, a cell leaving. Tracks and parents asserted exactly, as `res_track.txt` lists
//! them (label, first frame, last frame, parent).

use std::sync::Arc;
use topocontour::evolution::{Field, Modality, Params, Polarity, Shape};
use topocontour::geometry::Point;
use topocontour::io::movie::normalise;
use topocontour::track::{TrackSettings, TrackedFrame, Tracker};

const W: usize = 96;
const H: usize = 64;

/// A cell as a capsule: the two ends of its axis and its radius (a disk when they meet).
type Capsule = (Point, Point, f64);

/// A frame with bright capsules (segments `a`–`b` thickened by `r`) on a dark background.
fn frame(capsules: &[Capsule]) -> Field {
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

fn disk(x: f64, y: f64, r: f64) -> Capsule {
    (Point::new(x, y), Point::new(x, y), r)
}

/// Tracks `frames`; returns the CTC track lines.
fn track(frames: &[Field]) -> String {
    track_as(frames, Polarity::Bright, Modality::Generic)
}

/// Tracks `frames` of objects of `polarity` in `modality`.
fn track_as(frames: &[Field], polarity: Polarity, modality: Modality) -> String {
    tracked(frames, polarity, modality).lineage().ctc_text()
}

/// The tracker after tracking `frames` of objects of `polarity` in `modality`.
fn tracked(frames: &[Field], polarity: Polarity, modality: Modality) -> Tracker {
    let params = Params {
        polarity,
        modality,
        ..Params::default()
    };
    let mut tracker = Tracker::new(TrackSettings::new(params), Vec::new());
    for f in frames {
        tracker.step(f).unwrap();
    }
    tracker
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

/// `f` with a line of value `v` and half-width 0.8 from `a` to `b` where it crosses a
/// cell (the bright contact line of phase contrast where two cells meet, here toward the
/// dark background).
fn with_line(mut f: Field, a: Point, b: Point, v: f32) -> Field {
    for y in 0..H {
        for x in 0..W {
            let p = Point::new(x as f64 + 0.5, y as f64 + 0.5);
            let d = b - a;
            let t = ((p - a).dot(d) / d.norm2()).clamp(0.0, 1.0);
            if p.dist(a + d * t) <= 0.8 && f.data[y * W + x] > 0.5 {
                f.data[y * W + x] = v;
            }
        }
    }
    f
}

/// `f` as phase contrast shows it: dark cells on a bright ground.
fn inverted(f: Field) -> Field {
    Field::new(W, H, f.data.iter().map(|v| 1.0 - v).collect())
}

/// `f` blurred by [1 2 1]/4 along x and y (σ ≈ 0.7, a microscope's blur, which
/// fills the notches where two caps meet with background).
fn blurred(f: Field) -> Field {
    let mut d = f.data;
    for _ in 0..1 {
        for (sx, sy) in [(1usize, 0usize), (0, 1)] {
            let src = d.clone();
            for y in 0..H {
                for x in 0..W {
                    let at = |dx: isize, dy: isize| {
                        let xx = (x as isize + dx).clamp(0, W as isize - 1) as usize;
                        let yy = (y as isize + dy).clamp(0, H as isize - 1) as usize;
                        src[yy * W + xx]
                    };
                    let (sx, sy) = (sx as isize, sy as isize);
                    d[y * W + x] = 0.25 * at(-sx, -sy) + 0.5 * at(0, 0) + 0.25 * at(sx, sy);
                }
            }
        }
    }
    Field::new(W, H, d)
}

/// A straight rod growing (frames 0–2), then two sister rods end to end from frame 3
/// whose caps are `overlap` px into each other, with a contact line of value `line`
/// across the neck (cells are 0.85, background 0.15); blurred.
fn sisters(overlap: f64, line: Option<f32>) -> Vec<Field> {
    let mother = |half: f64| {
        (
            Point::new(48.0 - half, 32.0),
            Point::new(48.0 + half, 32.0),
            5.0,
        )
    };
    let mut frames: Vec<Field> = [12.0, 14.0, 16.0]
        .map(|h| blurred(frame(&[mother(h)])))
        .into();
    for grow in [0.0, 1.0, 2.0] {
        let c = 5.0 - overlap / 2.0;
        let l = (
            Point::new(32.0 - grow, 32.0),
            Point::new(48.0 - c, 32.0),
            5.0,
        );
        let r = (
            Point::new(48.0 + c, 32.0),
            Point::new(64.0 + grow, 32.0),
            5.0,
        );
        let f = frame(&[l, r]);
        frames.push(blurred(match line {
            Some(v) => with_line(f, Point::new(48.0, 25.0), Point::new(48.0, 39.0), v),
            None => f,
        }));
    }
    frames
}

#[test]
fn sister_rods_touching_end_to_end_are_two_children() {
    // Phase-contrast bacteria: the daughters stay in contact tip to tip, no background
    // between them, so the contour never pinches; the neck between the caps, where the
    // contact line is only starting to show (a third of the way to the background), is cut.
    assert_eq!(
        track(&sisters(0.0, Some(0.6))),
        "1 0 2 0\n2 3 5 1\n3 3 5 1\n"
    );
}

#[test]
fn sisters_with_a_wide_contact_are_cut_at_their_line_and_a_waist_is_not() {
    // Caps 4 px into each other: a neck of 0.8 widths, as wide as a constricting
    // mother's waist. With the contact line across it, two daughters; without, one cell.
    assert_eq!(
        track(&sisters(4.0, Some(0.15))),
        "1 0 2 0\n2 3 5 1\n3 3 5 1\n"
    );
    assert_eq!(track(&sisters(4.0, None)), "1 0 5 0\n");
}

/// A wide rod (14 px) growing (frames 0–2), then from frame 3 two stubby sisters (each
/// 14 px wide and `length` long at birth, growing a pixel a frame) whose caps meet end to
/// end, with no line between them; blurred.
fn stubby_sisters(length: f64) -> Vec<Field> {
    let r = 7.0;
    let mother = |half: f64| {
        (
            Point::new(48.0 - half, 32.0),
            Point::new(48.0 + half, 32.0),
            r,
        )
    };
    let mut frames: Vec<Field> = [8.0, 9.0, 10.0]
        .map(|h| blurred(frame(&[mother(h)])))
        .into();
    let axis = length - 2.0 * r;
    for grow in [0.0, 1.0, 2.0] {
        let l = (
            Point::new(48.0 - r - axis - grow, 32.0),
            Point::new(48.0 - r, 32.0),
            r,
        );
        let rr = (
            Point::new(48.0 + r, 32.0),
            Point::new(48.0 + r + axis + grow, 32.0),
            r,
        );
        frames.push(blurred(frame(&[l, rr])));
    }
    frames
}

#[test]
fn stubby_sisters_of_a_wide_rod_divide_in_their_first_frame() {
    // Daughters of a wide rod are stubby (aspect under 1.5, as round as a condensing
    // nucleus by that measure alone); of one size, they are rods: cut where their caps meet.
    assert_eq!(track(&stubby_sisters(21.0)), "1 0 2 0\n2 3 5 1\n3 3 5 1\n");
}

#[test]
fn two_cells_that_appear_as_one_and_part_are_not_a_division() {
    // A cell on its own throughout; from frame 2 two more cells, pressed into one blob
    // in their first frame, then apart: two new tracks, no parent.
    let a = disk(20.0, 20.0, 7.0);
    let frames: Vec<Field> = (0..5)
        .map(|t| match t {
            0 | 1 => blurred(frame(&[a])),
            2 => blurred(frame(&[a, disk(52.0, 40.0, 8.0), disk(62.0, 40.0, 8.0)])),
            _ => blurred(frame(&[a, disk(48.0, 40.0, 8.0), disk(68.0, 40.0, 8.0)])),
        })
        .collect();
    assert_eq!(track(&frames), "1 0 4 0\n2 2 4 0\n3 3 4 0\n");
}

/// Upright rods (y 14–38, radius 5) at `xs`, the field moved by (`dx`, `dy`).
fn upright_rods(xs: &[f64], dx: f64, dy: f64) -> Vec<Capsule> {
    xs.iter()
        .map(|&x| {
            (
                Point::new(x + dx, 14.0 + dy),
                Point::new(x + dx, 38.0 + dy),
                5.0,
            )
        })
        .collect()
}

#[test]
fn a_colony_on_a_drifting_stage_keeps_its_tracks() {
    // Four rods side by side 3 px apart; the whole field moves (7, 2) px a frame, so
    // each carried contour would land across its neighbour: it is moved with the field.
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let (dx, dy) = (7.0 * t as f64, 2.0 * t as f64);
            blurred(frame(&upright_rods(&[12.0, 25.0, 38.0, 51.0], dx, dy)))
        })
        .collect();
    assert_eq!(track(&frames), "1 0 4 0\n2 0 4 0\n3 0 4 0\n4 0 4 0\n");
}

#[test]
fn a_colony_carried_further_than_a_stage_drifts_keeps_its_tracks() {
    // Two rods 3 px apart slide 32 px right and 4 px down a frame (a pad sliding under
    // a still camera): their contours are moved with them, not lost each frame.
    let frames: Vec<Field> = (0..3)
        .map(|t| {
            let (dx, dy) = (32.0 * t as f64, 4.0 * t as f64);
            blurred(frame(&upright_rods(&[8.0, 21.0], dx, dy)))
        })
        .collect();
    assert_eq!(track(&frames), "1 0 2 0\n2 0 2 0\n");
}

#[test]
fn a_cell_the_drift_carries_out_of_the_frame_ends_its_track() {
    // Three rods drifting right 7 px a frame, and a cell near the right edge that the
    // drift carries out: its outline is scaled into the frame, then its track ends.
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let dx = 7.0 * t as f64;
            let mut cells = upright_rods(&[12.0, 25.0, 38.0], dx, 0.0);
            cells.push(disk(80.0 + dx, 48.0, 6.0));
            blurred(frame(&cells))
        })
        .collect();
    assert_eq!(track(&frames), "1 0 4 0\n2 0 4 0\n3 0 4 0\n4 0 2 0\n");
}

/// A round nucleus (frames 0–2), then two sister nuclei along x whose outlines are `gap`
/// px apart in frame 3 and part by 2 px a frame on each side; blurred σ ≈ 1.2 (three
/// passes), so the first frame's gap is a dip, not background.
fn sister_nuclei(gap: f64) -> Vec<Field> {
    let blur3 = |f: Field| blurred(blurred(blurred(f)));
    let mut frames: Vec<Field> = [3.0, 4.0, 5.0]
        .map(|h| {
            blur3(frame(&[(
                Point::new(48.0 - h, 32.0),
                Point::new(48.0 + h, 32.0),
                10.0,
            )]))
        })
        .into();
    for k in 0..3 {
        let off = 9.0 + 0.5 * gap + 2.0 * k as f64;
        frames.push(blur3(frame(&[
            disk(48.0 - off, 32.0, 9.0),
            disk(48.0 + off, 32.0, 9.0),
        ])));
    }
    frames
}

#[test]
fn sister_nuclei_a_blurred_gap_apart_divide_in_their_first_frame() {
    // The contour bridges the dim gap (the region model counts it inside) and would
    // only pinch a frame later; the narrow neck with the image half-way to the
    // background along it is cut at once.
    assert_eq!(track(&sister_nuclei(2.5)), "1 0 2 0\n2 3 5 1\n3 3 5 1\n");
}

#[test]
fn a_bent_rod_and_a_kidney_are_not_cut() {
    // A rod bent at a right angle, and a kidney (a thick arc): elongated lobes on either
    // side of the bend, but no neck narrower than the cell and no line along it.
    let bent = |t: f64| {
        let k = Point::new(30.0 + t, 40.0);
        vec![
            (Point::new(12.0 + t, 40.0), k, 6.0),
            (k, Point::new(30.0 + t, 18.0), 6.0),
        ]
    };
    let kidney = |t: f64| {
        let (c, r) = (Point::new(66.0 + t, 50.0), 18.0);
        let at = |k: usize| {
            let a = std::f64::consts::PI * (1.15 + 0.7 * k as f64 / 8.0);
            Point::new(c.x + r * a.cos(), c.y + r * a.sin())
        };
        (0..8).map(|k| (at(k), at(k + 1), 7.0)).collect::<Vec<_>>()
    };
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let mut cells = bent(t as f64);
            cells.extend(kidney(t as f64));
            frame(&cells)
        })
        .collect();
    assert_eq!(track(&frames), "1 0 4 0\n2 0 4 0\n");
}

/// A rod and, far from it, a speck of radius `speck` (a bubble's dark centre, debris).
fn rod_and_speck(speck: f64) -> Vec<Field> {
    (0..3)
        .map(|t| {
            let rod = (
                Point::new(20.0, 20.0 + t as f64),
                Point::new(50.0, 20.0 + t as f64),
                6.0,
            );
            blurred(frame(&[rod, disk(75.0, 48.0, speck)]))
        })
        .collect()
}

#[test]
fn a_speck_in_transmitted_light_is_no_cell_and_in_fluorescence_is_one() {
    // A speck a tenth of the rod's area: debris in phase contrast or bright field (dark
    // objects, the frames inverted), a small nucleus in fluorescence.
    let dark = |fs: Vec<Field>| -> Vec<Field> { fs.into_iter().map(inverted).collect() };
    for m in [Modality::PhaseContrast, Modality::Brightfield] {
        assert_eq!(
            track_as(&dark(rod_and_speck(4.0)), Polarity::Dark, m),
            "1 0 2 0\n"
        );
    }
    let fluo = track_as(
        &rod_and_speck(4.0),
        Polarity::Bright,
        Modality::Fluorescence,
    );
    assert_eq!(fluo, "1 0 2 0\n2 0 2 0\n");
    // A cell of a third of the rod's area is a cell in any light.
    let cell = track_as(
        &dark(rod_and_speck(8.0)),
        Polarity::Dark,
        Modality::PhaseContrast,
    );
    assert_eq!(cell, "1 0 2 0\n2 0 2 0\n");
}

/// A nucleus of radius 10 (frames 0–2), then, in frames 3–4, two small nuclei of radius
/// `r` at `apart` px either side of where it was; and a second nucleus throughout.
fn mitosis(r: f64, apart: f64) -> Vec<Field> {
    let other = disk(84.0, 54.0, 8.0);
    let mut frames: Vec<Field> = (0..3)
        .map(|_| blurred(frame(&[disk(40.0, 34.0, 10.0), other])))
        .collect();
    for k in 0..2 {
        let d = apart + 2.0 * k as f64;
        frames.push(blurred(frame(&[
            disk(40.0 - d, 34.0 + 0.5 * d, r),
            disk(40.0 + d, 34.0 - 0.5 * d, r),
            other,
        ])));
    }
    frames
}

#[test]
fn daughters_pushed_apart_between_two_frames_are_children_of_the_nucleus_that_was_there() {
    // A nucleus divides between frames: its contour finds nothing where it was, and two
    // small nuclei are picked up on either side; they are its daughters.
    let fluo = |fs: &[Field]| track_as(fs, Polarity::Bright, Modality::Fluorescence);
    assert_eq!(
        fluo(&mitosis(6.0, 16.0)),
        "1 0 2 0\n2 0 4 0\n3 3 4 1\n4 3 4 1\n"
    );
    // Far beyond the nucleus's reach they are cells of their own.
    assert_eq!(
        fluo(&mitosis(6.0, 30.0)),
        "1 0 2 0\n2 0 4 0\n3 3 4 0\n4 3 4 0\n"
    );
}

#[test]
fn a_cell_appearing_beside_one_that_kept_its_size_is_no_daughter() {
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let mut cells = vec![disk(40.0, 34.0, 10.0)];
            if t >= 3 {
                cells.push(disk(62.0, 34.0, 6.0));
            }
            blurred(frame(&cells))
        })
        .collect();
    let lines = track_as(&frames, Polarity::Bright, Modality::Fluorescence);
    assert_eq!(lines, "1 0 4 0\n2 3 4 0\n");
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

/// Uniform noise in ±0.15, a value per call, drawn from `seed` (a linear congruential
/// generator: the movies are the same on every machine).
fn uniform_noise(seed: u64) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as f64 / (1u64 << 31) as f64 - 0.5) as f32 * 0.3
    }
}

/// `cells(t)` for `frames` frames, lit unevenly: the upper right corner brighter by up to
/// `ramp` (a broad ramp), with uniform noise (±0.15) drawn from `seed`.
fn on_a_ramp(
    frames: usize,
    ramp: f32,
    seed: u64,
    cells: impl Fn(usize) -> Vec<Capsule>,
) -> Vec<Field> {
    let mut noise = uniform_noise(seed);
    (0..frames)
        .map(|t| {
            let mut f = frame(&cells(t));
            for y in 0..H {
                for x in 0..W {
                    let r =
                        ((x as f32 - 60.0) / 36.0).max(0.0) * ((40.0 - y as f32) / 40.0).max(0.0);
                    f.data[y * W + x] += ramp * r + noise();
                }
            }
            f
        })
        .collect()
}

#[test]
fn a_brighter_corner_of_uneven_light_is_not_a_cell() {
    // Fluorescence lit unevenly: one corner a shade brighter (a broad ramp, noisy), and
    // one nucleus. Seeds on the ramp settle into blobs barely apart from their
    // surroundings; only the nucleus is a cell.
    let frames = on_a_ramp(3, 0.3, 12345, |t| vec![disk(30.0 + t as f64, 32.0, 9.0)]);
    assert_eq!(track(&frames), "1 0 2 0\n");
}

#[test]
fn a_cell_that_fades_on_a_brighter_corner_ends_its_track() {
    // A nucleus on the brighter corner of uneven light goes dark after frame 1: its
    // contour, carried on, settles into a blob of the ramp, which must not live on as
    // the nucleus's track (a carried cell is judged by its separation too).
    let frames = on_a_ramp(6, 0.5, 777, |t| {
        let mut cells = vec![disk(30.0 + t as f64, 32.0, 9.0)];
        if t < 2 {
            cells.push(disk(80.0, 14.0, 8.0));
        }
        cells
    });
    // The fading nucleus's track ends with it (before: "2 0 5 0", a blob to the end).
    // A seed the ramp gave in frame 1, a shade past the new-cell bound there, lives on.
    let lines = track(&frames);
    let lines: Vec<&str> = lines.lines().collect();
    assert_eq!(&lines[..2], ["1 0 5 0", "2 0 1 0"]);
}

/// Two rods lying side by side, turning together about the pair's centre by `step`
/// degrees a frame with a darker seam along their contact, blurred: per frame the image
/// and each rod's capsule.
fn turning_pair(frames: usize, step: f64) -> Vec<(Field, [Capsule; 2])> {
    let c = Point::new(48.0, 32.0);
    (0..frames)
        .map(|t| {
            let a = (step * t as f64).to_radians();
            let (u, n) = (Point::new(a.cos(), a.sin()), Point::new(-a.sin(), a.cos()));
            let rod = |side: f64| {
                (
                    c + n * (4.6 * side) - u * 14.0,
                    c + n * (4.6 * side) + u * 14.0,
                    4.5,
                )
            };
            let rods = [rod(1.0), rod(-1.0)];
            let f = with_line(frame(&rods), c - u * 20.0, c + u * 20.0, 0.3);
            (blurred(f), rods)
        })
        .collect()
}

#[test]
fn the_line_between_rods_side_by_side_turns_with_them() {
    // The contours are held apart where their fronts meet; each frame starts from the
    // last one's, so without dividing them again on the image, the line between them
    // stays at the angle where they first met while the rods turn.
    let movie = turning_pair(9, 6.0);
    let params = Params {
        polarity: Polarity::Bright,
        ..Params::default()
    };
    // One click on each rod (the pair's union has no neck for automatic seeds).
    let clicks = movie[0].1.map(|(a, b, _)| Shape::Disk {
        center: (a + b) * 0.5,
        radius: 3.0,
    });
    let settings = TrackSettings {
        auto_seeds: false,
        ..TrackSettings::new(params)
    };
    let mut tracker = Tracker::new(settings, clicks.into());
    for (f, _) in &movie {
        tracker.step(f).unwrap();
    }
    assert_eq!(tracker.lineage().ctc_text(), "1 0 8 0\n2 0 8 0\n");
    let labels = tracker.labels();
    for rod in movie[8].1 {
        let inside = |i: usize| {
            let p = Point::new((i % W) as f64 + 0.5, (i / W) as f64 + 0.5);
            let (a, b, r) = rod;
            let d = b - a;
            p.dist(a + d * ((p - a).dot(d) / d.norm2()).clamp(0.0, 1.0)) <= r
        };
        let iou = [1u32, 2]
            .map(|l| {
                let both = (0..W * H).filter(|&i| inside(i) && labels[i] == l).count();
                let either = (0..W * H).filter(|&i| inside(i) || labels[i] == l).count();
                both as f64 / either as f64
            })
            .into_iter()
            .fold(0.0, f64::max);
        assert!(iou > 0.75, "{iou}");
    }
}

/// A nucleus (frames 0–2) that parts in frame 3 into two lobes 6 px apart; from frame 4
/// on the lobes are `rejoined` by a bridge 10 px wide (one dumbbell nucleus), or stay
/// apart and part further (two daughters).
fn parting(rejoined: bool) -> Vec<Field> {
    let mut frames: Vec<Field> = [3.0, 4.0, 5.0]
        .map(|h| frame(&[(Point::new(48.0 - h, 32.0), Point::new(48.0 + h, 32.0), 10.0)]))
        .into();
    frames.push(frame(&[disk(37.0, 32.0, 8.0), disk(59.0, 32.0, 8.0)]));
    for k in 0..3 {
        let off = 11.0 + 2.0 * k as f64;
        frames.push(if rejoined {
            frame(&[
                disk(40.0, 32.0, 8.0),
                disk(56.0, 32.0, 8.0),
                (Point::new(40.0, 32.0), Point::new(56.0, 32.0), 5.0),
            ])
        } else {
            frame(&[
                disk(48.0 - off - 2.0, 32.0, 8.0),
                disk(48.0 + off + 2.0, 32.0, 8.0),
            ])
        });
    }
    frames
}

#[test]
fn a_nucleus_that_parts_for_one_frame_did_not_divide() {
    let params = Params {
        polarity: Polarity::Bright,
        ..Params::default()
    };
    let mut tracker = Tracker::new(TrackSettings::new(params), Vec::new());
    let mut seen = Vec::new();
    for f in &parting(true) {
        seen.push(tracker.step(f).unwrap());
    }
    // Frame 3 saw two sisters; frame 4 took them back, and frame 3 revised is the
    // mother in two pieces.
    assert_eq!(seen[3].divisions.len(), 1);
    assert_eq!(seen[4].undone, seen[3].divisions);
    let mut revised = seen[3].clone();
    revised.revise(&seen[4]);
    assert!(revised.divisions.is_empty());
    assert_eq!(
        revised.objects.iter().map(|o| o.track).collect::<Vec<_>>(),
        [1, 1]
    );
    assert_eq!(seen[4].objects.len(), 1);
    assert_eq!(tracker.lineage().ctc_text(), "1 0 6 0\n");
    // Daughters that stay apart divided.
    assert_eq!(track(&parting(false)), "1 0 2 0\n2 3 6 1\n3 3 6 1\n");
}

#[test]
fn two_rods_side_by_side_under_one_outline_are_two_tracks() {
    // A rectangle dragged around two rods lying side by side shrinks onto both as one
    // outline (a faint seam between them, and no neck); a click on each of two single
    // rods beside them shows how wide one rod of this movie is. The outline twice as
    // wide, dipping at both ends of the contact, is two cells from frame 0 on, neither
    // the other's child.
    let params = Params {
        polarity: Polarity::Bright,
        ..Params::default()
    };
    let mut init: Vec<Shape> = [10.0, 86.0]
        .map(|x| Shape::Disk {
            center: Point::new(x, 26.0),
            radius: 3.0,
        })
        .into();
    init.push(Shape::Rect {
        min: Point::new(22.0, 19.0),
        max: Point::new(72.0, 45.0),
    });
    let settings = TrackSettings {
        auto_seeds: false,
        ..TrackSettings::new(params)
    };
    let mut tracker = Tracker::new(settings, init);
    for f in &offset_pair(3) {
        tracker.step(f).unwrap();
    }
    assert_eq!(
        tracker.lineage().ctc_text(),
        "1 0 2 0\n2 0 2 0\n3 0 2 0\n4 0 2 0\n",
        "each rod its own track"
    );
}

/// Two rods side by side, one shifted along the other by a third of its length, a faint
/// seam between them, and two single upright rods beside them; `n` still frames.
fn offset_pair(n: usize) -> Vec<Field> {
    let pair = [
        (Point::new(30.0, 27.4), Point::new(54.0, 27.4), 4.5),
        (Point::new(40.0, 36.6), Point::new(64.0, 36.6), 4.5),
    ];
    let mut cells = upright_rods(&[10.0, 86.0], 0.0, 0.0);
    cells.extend(pair);
    let f = with_line(
        frame(&cells),
        Point::new(30.0, 32.0),
        Point::new(70.0, 32.0),
        0.6,
    );
    vec![blurred(f); n]
}

/// Frames 0–1: a long rod with a waist (two rods `overlap` px into each other, no line),
/// its two halves `half` px long; frames 2–4: the two daughters end to end with a
/// contact line; blurred.
fn waisted_mother(half: f64, overlap: f64) -> Vec<Field> {
    let r = 5.0;
    let pair = |overlap: f64, grow: f64| {
        let c = r - overlap / 2.0;
        [
            (
                Point::new(48.0 - c - half - grow, 32.0),
                Point::new(48.0 - c, 32.0),
                r,
            ),
            (
                Point::new(48.0 + c, 32.0),
                Point::new(48.0 + c + half + grow, 32.0),
                r,
            ),
        ]
    };
    let mut frames: Vec<Field> = [0.0, 1.0].map(|g| blurred(frame(&pair(overlap, g)))).into();
    for grow in [2.0, 3.0, 4.0] {
        let f = frame(&pair(0.0, grow));
        frames.push(blurred(with_line(
            f,
            Point::new(48.0, 25.0),
            Point::new(48.0, 39.0),
            0.6,
        )));
    }
    frames
}

#[test]
fn a_mother_seeded_on_both_sides_of_her_waist_on_frame_0_is_one_cell_that_divides() {
    // Automatic seeds fall on both sides of the waist; evolved again as one outline,
    // the mother has no neck the tracker cuts, so she is one cell until her daughters
    // show their contact line. Without that, two tracks ran from frame 0 and the
    // division was never seen.
    for (half, overlap) in [(12.0, 4.0), (16.0, 3.0), (20.0, 4.0)] {
        assert_eq!(
            track(&waisted_mother(half, overlap)),
            "1 0 1 0\n2 2 4 1\n3 2 4 1\n",
            "halves {half} px, {overlap} px into each other"
        );
    }
    // Daughters already born on frame 0 (their contact line shows) stay two cells.
    let born: Vec<Field> = waisted_mother(16.0, 0.0).split_off(2);
    assert_eq!(track(&born), "1 0 2 0\n2 0 2 0\n");
}

/// A rod growing (frames 0–3) that divides into two sisters a gap apart (frames 4–8),
/// neither growing; from frame 6 the left one shows a band of background 3 px wide
/// across its middle (a paler spot inside a cell, or a septum). Bright on dark.
fn young_sister_with_a_band() -> Vec<Field> {
    let mother = |half: f64| {
        (
            Point::new(48.0 - half, 32.0),
            Point::new(48.0 + half, 32.0),
            5.0,
        )
    };
    let mut frames: Vec<Field> = [14.0, 16.0, 18.0, 20.0]
        .map(|h| blurred(frame(&[mother(h)])))
        .into();
    for t in 4..9 {
        let l = (Point::new(24.0, 32.0), Point::new(41.0, 32.0), 5.0);
        let r = (Point::new(55.0, 32.0), Point::new(72.0, 32.0), 5.0);
        let mut f = frame(&[l, r]);
        if t >= 6 {
            for x in [31.7, 32.5, 33.3] {
                f = with_line(f, Point::new(x, 25.0), Point::new(x, 39.0), 0.15);
            }
        }
        frames.push(blurred(f));
    }
    frames
}

#[test]
fn a_rod_that_has_not_grown_since_its_birth_does_not_divide_again() {
    let movie = young_sister_with_a_band();
    // Fluorescence: the band parts the left sister into two cells.
    assert_eq!(
        track_as(&movie, Polarity::Bright, Modality::Fluorescence),
        "1 0 3 0\n2 4 5 1\n3 4 8 1\n4 6 8 2\n5 6 8 2\n"
    );
    // Phase contrast (dark cells, the frames inverted): a rod divides at about twice
    // its birth size, and this one has not grown; it stays one cell.
    let dark: Vec<Field> = movie.into_iter().map(inverted).collect();
    assert_eq!(
        track_as(&dark, Polarity::Dark, Modality::PhaseContrast),
        "1 0 3 0\n2 4 8 1\n3 4 8 1\n"
    );
}

/// Phase contrast: a dark rod (0.05) from `x0` to `x1` at y = 20, wrapped in a bright halo
/// 4 px wide, on grey ground (0.6) with a dark band of uneven light (0.1, its edge 30 px
/// wide: light changes over tens of pixels) across the lower half; uniform noise (±0.15)
/// from `seed`, the values clipped to [0, 1] as a camera's are and the frame normalised
/// as a movie's.
fn rod_beside_a_band(x0: f64, x1: f64, seed: u64) -> Field {
    let mut noise = uniform_noise(seed);
    let (a, b) = (Point::new(x0, 20.0), Point::new(x1, 20.0));
    let data = (0..W * H)
        .map(|i| {
            let p = Point::new((i % W) as f64 + 0.5, (i / W) as f64 + 0.5);
            let t = ((p.x - a.x) / (b.x - a.x)).clamp(0.0, 1.0);
            let d = p.dist(a + (b - a) * t);
            let band = ((p.y - 30.0) / 30.0).clamp(0.0, 1.0) as f32;
            let v = if d <= 4.0 {
                0.05
            } else if d <= 8.0 {
                0.95
            } else {
                0.6 - 0.5 * band
            };
            (v + noise()).clamp(0.0, 1.0)
        })
        .collect();
    let mut f = Field::new(W, H, data);
    normalise(&mut f);
    f
}

#[test]
fn in_phase_contrast_a_dark_band_of_uneven_light_is_not_a_cell_and_the_rod_beside_it_is() {
    // Seeds settle on the band too, into one wide blob or many small ones; none is
    // wrapped in a halo, and none may start a track or spread over the band, whatever
    // the noise.
    for seed in 0..8 {
        let frames: Vec<Field> = (0..3)
            .map(|t| rod_beside_a_band(20.0 + t as f64, 44.0 + t as f64, 10 * seed + t))
            .collect();
        let tracker = tracked(&frames, Polarity::Dark, Modality::PhaseContrast);
        assert_eq!(tracker.lineage().ctc_text(), "1 0 2 0\n", "noise {seed}");
        // The one track is the rod's (its middle at (34, 20) in the last frame), and
        // nothing covers the band.
        let labels = tracker.labels();
        assert_eq!(labels[20 * W + 34], 1, "noise {seed}");
        assert!(labels[45 * W..].iter().all(|&l| l == 0), "noise {seed}");
    }
}

#[test]
fn in_phase_contrast_rods_pushed_against_their_neighbours_keep_their_tracks() {
    // Four dark rods of different lengths side by side, 1 px apart; the right pair is
    // pushed 7 px right a frame while the left pair stays (a colony growing between
    // them). No one shift fits the field, and a contour left where its rod was lands
    // across the gap and its neighbour; each rod's own shift is followed.
    let ends = [(14.0, 34.0), (18.0, 44.0), (10.0, 28.0), (16.0, 40.0)];
    let frames: Vec<Field> = (0..4)
        .map(|t| {
            let rods: Vec<Capsule> = [20.0, 31.0, 42.0, 53.0]
                .iter()
                .zip(ends)
                .enumerate()
                .map(|(k, (&x, (y0, y1)))| {
                    let x = x + if k >= 2 { 7.0 * t as f64 } else { 0.0 };
                    (Point::new(x, y0), Point::new(x, y1), 5.0)
                })
                .collect();
            inverted(blurred(frame(&rods)))
        })
        .collect();
    assert_eq!(
        track_as(&frames, Polarity::Dark, Modality::PhaseContrast),
        "1 0 3 0\n2 0 3 0\n3 0 3 0\n4 0 3 0\n"
    );
}

#[test]
fn in_phase_contrast_a_rod_does_not_divide_into_a_piece_far_smaller_than_the_colonys_cells() {
    // Eight dark rods side by side; from frame 2 a pale line crosses the fourth a quarter
    // of the way down (a paler spot in a real colony's mottled rod). Its carried outline
    // parts there, into a piece about a quarter of a cell: no division.
    let xs: Vec<f64> = (0..8).map(|k| 8.0 + 11.0 * k as f64).collect();
    let frames: Vec<Field> = (0..5)
        .map(|t| {
            let rods: Vec<Capsule> = xs
                .iter()
                .map(|&x| (Point::new(x, 14.0), Point::new(x, 38.0), 5.0))
                .collect();
            let mut f = frame(&rods);
            if t >= 2 {
                f = with_line(f, Point::new(35.0, 20.0), Point::new(47.0, 20.0), 0.15);
            }
            inverted(blurred(f))
        })
        .collect();
    let text = track_as(&frames, Polarity::Dark, Modality::PhaseContrast);
    let lines: Vec<&str> = text.lines().collect();
    let rods: Vec<String> = (1..=8).map(|k| format!("{k} 0 4 0")).collect();
    assert_eq!(lines[..8], rods, "{text}");
    // The piece let go may be picked up later as a new cell, never as a daughter.
    assert!(lines.iter().all(|l| l.ends_with(" 0")), "{text}");
}

/// Twelve frames with what a tracker must remember across them: a nucleus that stays, a
/// rod that divides into two round daughters pushed apart, a cell entering from the right
/// and one appearing from nothing (each picked up by the new-cell look, which a tracker
/// schedules).
fn eventful() -> Vec<Field> {
    (0..12)
        .map(|t| {
            let tf = t as f64;
            let mut cells = vec![disk(16.0, 14.0, 7.0)];
            if t < 6 {
                let half = 6.0 + tf;
                cells.push((
                    Point::new(48.0 - half, 40.0),
                    Point::new(48.0 + half, 40.0),
                    6.0,
                ));
            } else {
                let apart = 12.0 + 2.0 * (tf - 6.0);
                cells.push(disk(48.0 - apart, 40.0, 7.0));
                cells.push(disk(48.0 + apart, 40.0, 7.0));
            }
            if t >= 4 {
                cells.push(disk(100.0 - 4.0 * (tf - 4.0), 12.0, 8.0));
            }
            if t >= 7 {
                cells.push(disk(60.0, 14.0, 6.0));
            }
            blurred(frame(&cells))
        })
        .collect()
}

/// Settings for bright cells, and a tracker that tracked the first `n` frames of `movie`
/// with those frames.
fn bright_tracked(movie: &[Field], n: usize) -> (TrackSettings, Tracker, Vec<TrackedFrame>) {
    let settings = TrackSettings::new(Params {
        polarity: Polarity::Bright,
        ..Params::default()
    });
    let mut tracker = Tracker::new(settings.clone(), Vec::new());
    let frames = movie[..n]
        .iter()
        .map(|f| tracker.step(f).unwrap())
        .collect();
    (settings, tracker, frames)
}

/// [`eventful`], and [`bright_tracked`] to frame 3.
fn eventful_to_frame_3() -> (Vec<Field>, TrackSettings, Tracker, Vec<TrackedFrame>) {
    let movie = eventful();
    let (settings, tracker, frames) = bright_tracked(&movie, 4);
    (movie, settings, tracker, frames)
}

/// The frames a tracker gives for `movie` from `tracker` on, each as the next revised it,
/// and the lineage at the end.
fn run_on(mut tracker: Tracker, movie: &[Field]) -> (Vec<TrackedFrame>, String) {
    let mut out: Vec<TrackedFrame> = Vec::new();
    for f in movie {
        let frame = tracker.step(f).unwrap();
        if let Some(before) = out.last_mut() {
            before.revise(&frame);
        }
        out.push(frame);
    }
    (out, tracker.lineage().ctc_text())
}

/// A tracker resumed from any frame with what the tracker that tracked it remembered
/// goes on exactly as that tracker did: a hand correction re-tracks the frames after it
/// as the run would have, changed only by what the correction changed. Resumed from the
/// contours alone, it does not (it looks for new cells at once, knows no births).
#[test]
fn a_tracker_resumed_with_its_memory_goes_on_as_the_run_did() {
    let movie = eventful();
    let settings = TrackSettings::new(Params {
        polarity: Polarity::Bright,
        ..Params::default()
    });
    let mut tracker = Tracker::new(settings.clone(), Vec::new());
    let (mut frames, mut memories, mut lineages) = (Vec::new(), Vec::new(), Vec::new());
    for f in &movie {
        let frame = tracker.step(f).unwrap();
        if let Some(before) = frames.last_mut() {
            TrackedFrame::revise(before, &frame);
        }
        frames.push(frame);
        memories.push(tracker.memory());
        lineages.push(tracker.lineage().clone());
    }
    let whole = tracker.lineage().ctc_text();
    assert!(
        whole.lines().count() >= 5,
        "the movie's events were tracked: {whole}"
    );
    let mut forgetful_differs = false;
    for t in 0..movie.len() - 1 {
        // A frame the next revised is not where the run stood after it.
        let next = &frames[t + 1];
        if !(next.earlier.is_empty() && next.undone.is_empty()) {
            continue;
        }
        let resumed = |memory| {
            let mut r = Tracker::resume(
                settings.clone(),
                lineages[t].clone(),
                &frames[t],
                W,
                H,
                memory,
            );
            r.set_previous(movie[t].clone());
            run_on(r, &movie[t + 1..])
        };
        let memory = memories[t].corrected(&frames[t], &frames[t], W, H);
        let (again, lineage) = resumed(Some(memory));
        let differs = again.iter().zip(&frames[t + 1..]).position(|(a, b)| a != b);
        assert_eq!(
            differs, None,
            "resumed after frame {t}: frames differ from this one on"
        );
        assert_eq!(lineage, whole, "resumed after frame {t}");
        let (forgetful, lineage) = resumed(None);
        forgetful_differs |= forgetful != frames[t + 1..] || lineage != whole;
    }
    assert!(
        forgetful_differs,
        "the memory made no difference: the movie tests nothing"
    );
}

/// `tracker` (which tracked `movie` up to `frame`) resumed from `frame` as corrected,
/// with `memory`, and run on the rest of `movie`: the frames after and the lineage.
fn resumed_from(
    settings: &TrackSettings,
    tracker: &Tracker,
    frame: &TrackedFrame,
    memory: topocontour::track::Memory,
    movie: &[Field],
) -> (Vec<TrackedFrame>, String) {
    let t = frame.frame;
    let lineage = tracker.lineage().clone();
    let mut r = Tracker::resume(settings.clone(), lineage, frame, W, H, Some(memory));
    r.set_previous(movie[t].clone());
    run_on(r, &movie[t + 1..])
}

/// A cell deleted by hand stays deleted: the tracker resumed after the correction takes
/// no new cell where it is, though the image still shows it, as it moves on further than
/// its own size, and still finds a cell that appears elsewhere. Resumed with the same
/// memory less the deletion, it finds the cell again at its next look (so the scene
/// tells).
#[test]
fn a_cell_deleted_by_hand_is_not_found_again_and_new_cells_elsewhere_are() {
    let gone = |t: usize| Point::new(84.0 - 2.5 * t as f64, 40.0);
    let movie: Vec<Field> = (0..10)
        .map(|t| {
            let g = gone(t);
            let mut cells = vec![disk(16.0 + t as f64, 20.0, 7.0), disk(g.x, g.y, 5.0)];
            if t >= 6 {
                cells.push(disk(30.0, 50.0, 6.0));
            }
            blurred(frame(&cells))
        })
        .collect();
    let (settings, tracker, frames) = bright_tracked(&movie, 3);
    let near = |o: &topocontour::track::TrackedObject, x: f64, y: f64| {
        o.centroid.dist(Point::new(x, y)) < 5.0
    };
    let old = frames[2].clone();
    assert_eq!(old.objects.len(), 2, "the two cells");
    let mut new = old.clone();
    new.objects.retain(|o| !near(o, gone(2).x, gone(2).y));
    assert_eq!(new.objects.len(), 1);
    let resumed = |memory| resumed_from(&settings, &tracker, &new, memory, &movie).0;
    let memory = tracker.memory();
    let after = resumed(memory.corrected(&old, &new, W, H));
    assert_eq!(memory.corrected(&old, &new, W, H).unwanted().len(), 1);
    for (t, f) in (3..).zip(&after) {
        assert!(
            !f.objects.iter().any(|o| o.centroid.dist(gone(t)) < 8.0),
            "frame {t}: the deleted cell is not found again"
        );
        assert!(f.objects.iter().any(|o| near(o, 16.0 + t as f64, 20.0)));
        assert_eq!(
            f.objects.iter().any(|o| near(o, 30.0, 50.0)),
            t >= 6,
            "frame {t}: the cell appearing elsewhere is found"
        );
        assert_eq!(f.objects.len(), 1 + usize::from(t >= 6), "frame {t}");
    }
    // The same memory, the frame not seen as corrected: the cell comes back.
    let forgetful = resumed(memory.corrected(&new, &new, W, H));
    assert!(
        (3..)
            .zip(&forgetful)
            .any(|(t, f)| f.objects.iter().any(|o| near(o, gone(t).x, gone(t).y))),
        "without the deletion remembered the cell is found again"
    );
}

/// A deleted cell that divides later stays deleted, both its daughters too (the one
/// pushed apart from where the mother was included), and the cells around go on.
#[test]
fn a_deleted_cell_that_divides_stays_deleted_with_its_daughters() {
    let (movie, settings, tracker, frames) = eventful_to_frame_3();
    let (first, _) = run_on(tracker.clone(), &movie[4..]);
    // The rod about (48, 40), dividing at frame 6 into sisters pushed apart.
    let old = frames[3].clone();
    let rod = |o: &topocontour::track::TrackedObject| (o.centroid.y - 40.0).abs() < 6.0;
    assert_eq!(old.objects.iter().filter(|o| rod(o)).count(), 1);
    let mut new = old.clone();
    new.objects.retain(|o| !rod(o));
    let memory = tracker.memory().corrected(&old, &new, W, H);
    let (after, lineage) = resumed_from(&settings, &tracker, &new, memory, &movie);
    for ((t, f), was) in (4..).zip(&after).zip(&first) {
        assert!(
            !f.objects.iter().any(rod),
            "frame {t}: nothing of the deleted rod is found again: {:?}",
            f.objects.iter().map(|o| o.centroid).collect::<Vec<_>>()
        );
        assert!(
            was.objects.iter().any(rod),
            "frame {t}: the first run has it"
        );
        // The cells around as the first run found them.
        let others = |f: &TrackedFrame| {
            let mut c: Vec<_> = f
                .objects
                .iter()
                .filter(|o| !rod(o))
                .map(|o| o.centroid)
                .collect();
            c.sort_by(|a, b| a.x.total_cmp(&b.x));
            c
        };
        let (a, b) = (others(f), others(was));
        assert_eq!(a.len(), b.len(), "frame {t}");
        assert!(
            a.iter().zip(&b).all(|(p, q)| p.dist(*q) < 0.5),
            "frame {t}: {a:?} {b:?}"
        );
    }
    assert_eq!(
        lineage.lines().count(),
        4,
        "two disks and the disk entering: {lineage}"
    );
}

/// After a correction the cells keep their numbers: the frames tracked again number a
/// track begun after the corrected frame as the run they replace did, and a track that
/// run did not have after all of its. Deleting the rod before it divides takes its two
/// daughters away; numbered on, the cell appearing later took a daughter's number.
#[test]
fn cells_tracked_again_after_a_correction_keep_their_numbers() {
    let (movie, settings, tracker, frames) = eventful_to_frame_3();
    let mut on = tracker.clone();
    let first: Vec<Arc<TrackedFrame>> = movie[4..]
        .iter()
        .map(|f| Arc::new(on.step(f).unwrap()))
        .collect();
    let rod = |o: &topocontour::track::TrackedObject| (o.centroid.y - 40.0).abs() < 6.0;
    let old = frames[3].clone();
    let mut new = old.clone();
    new.objects.retain(|o| !rod(o));
    let resumed = |keep: bool| {
        let memory = tracker.memory().corrected(&old, &new, W, H);
        let mut r = Tracker::resume(
            settings.clone(),
            tracker.lineage().clone(),
            &new,
            W,
            H,
            Some(memory),
        );
        if keep {
            r = r.keeping_numbers(first.iter().cloned(), on.lineage());
        }
        r.set_previous(movie[3].clone());
        run_on(r, &movie[4..])
    };
    let numbers = |f: &TrackedFrame| -> Vec<(u32, Point)> {
        f.objects
            .iter()
            .filter(|o| !rod(o))
            .map(|o| (o.track, o.centroid))
            .collect()
    };
    let same_numbers = |after: &[TrackedFrame]| {
        after.iter().zip(&first).all(|(f, was)| {
            numbers(f)
                .iter()
                .all(|&(k, c)| numbers(was).iter().any(|&(l, d)| l == k && c.dist(d) < 0.5))
        })
    };
    let (kept, lineage) = resumed(true);
    assert!(same_numbers(&kept), "{lineage}");
    // The cells found as the first run found them, none of the rod's.
    for (f, was) in kept.iter().zip(&first) {
        assert_eq!(numbers(f).len(), numbers(was).len(), "frame {}", f.frame);
        assert_eq!(f.objects.len(), numbers(f).len(), "frame {}", f.frame);
    }
    assert!(on
        .lineage()
        .tracks()
        .iter()
        .any(|t| t.first >= 6 && t.parent == 0));
    let (renumbered, _) = resumed(false);
    assert!(
        !same_numbers(&renumbered),
        "numbered on, the later cells change numbers"
    );
}

/// Two cells joined by hand stay one cell in the frames after, while they touch: the
/// resumed tracker holds the joined cell together until it grows, as a cell just born.
/// Resumed without remembering the join, the two come apart again at the next frame,
/// as a division.
#[test]
fn cells_joined_by_hand_stay_one_while_they_touch() {
    // Two nuclei 3 px apart, drifting right together.
    let movie: Vec<Field> = (0..7)
        .map(|t| {
            let x = 30.0 + t as f64;
            blurred(frame(&[disk(x, 32.0, 8.0), disk(x + 19.0, 32.0, 8.0)]))
        })
        .collect();
    let (settings, tracker, frames) = bright_tracked(&movie, 3);
    let old = frames[2].clone();
    assert_eq!(old.objects.len(), 2, "two cells found");
    // Joined at frame 2: one outline round both, the left one's track.
    let keep = old.objects.iter().map(|o| o.track).min().unwrap();
    let ring: Vec<Point> = (0..64)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 64.0;
            let cx = if a.cos() >= 0.0 { 51.5 } else { 32.5 };
            Point::new(cx + 9.0 * a.cos(), 32.0 + 9.0 * a.sin())
        })
        .collect();
    let (a2, centroid) = topocontour::geometry::area2_centroid(&ring);
    let mut new = old.clone();
    new.objects = vec![topocontour::track::TrackedObject {
        track: keep,
        ring,
        area: 0.5 * a2.abs(),
        centroid,
    }];
    let resumed = |memory: Option<topocontour::track::Memory>| {
        let mut r = Tracker::resume(
            settings.clone(),
            tracker.lineage().clone(),
            &new,
            W,
            H,
            memory,
        );
        r.set_previous(movie[2].clone());
        run_on(r, &movie[3..])
    };
    let (after, lineage) = resumed(Some(tracker.memory().corrected(&old, &new, W, H)));
    for f in &after {
        let tracks: Vec<u32> = f.objects.iter().map(|o| o.track).collect();
        assert_eq!(tracks, [keep], "frame {}: {lineage}", f.frame);
    }
    // The same memory less the join (the tracker's own, before the correction).
    let (_, forgot) = resumed(Some(tracker.memory()));
    assert!(
        forgot.lines().any(|l| l.ends_with(&format!(" {keep}"))),
        "without the join remembered they divide: {forgot}"
    );
}

/// A deleted nucleus whose daughters are pushed apart between two frames stays deleted:
/// they are taken as its own, as its daughters would have been, not as new cells.
#[test]
fn a_deleted_nucleus_whose_daughters_are_pushed_apart_stays_deleted() {
    let movie = mitosis(6.0, 16.0);
    let settings = TrackSettings::new(Params {
        polarity: Polarity::Bright,
        modality: Modality::Fluorescence,
        ..Params::default()
    });
    let mut tracker = Tracker::new(settings.clone(), Vec::new());
    let mut frames = Vec::new();
    for f in &movie[..2] {
        frames.push(tracker.step(f).unwrap());
    }
    let old = frames[1].clone();
    let nucleus = |o: &topocontour::track::TrackedObject| o.centroid.x < 70.0;
    let mut new = old.clone();
    new.objects.retain(|o| !nucleus(o));
    assert_eq!(new.objects.len(), 1);
    let memory = tracker.memory().corrected(&old, &new, W, H);
    let (after, _) = resumed_from(&settings, &tracker, &new, memory, &movie);
    for (t, f) in (2..).zip(&after) {
        let left: Vec<_> = f.objects.iter().map(|o| o.centroid).collect();
        assert!(
            f.objects.len() == 1 && !nucleus(&f.objects[0]),
            "frame {t}: only the other nucleus: {left:?}"
        );
    }
}
