//! Two rods side by side under one outline are two cells. The neck rule ([`super::neck`])
//! cuts rods that touch end to end, where the outline narrows; rods lying side by side
//! make a body as long as one rod and twice as wide, with no neck: its shortest chords
//! run across both rods. Automatic seeds read such a pair as one cell when the line
//! between them is faint (a colony's first frame), and sisters that slid alongside each
//! other before their neck was cut stay one outline too; a carried outline is never
//! divided again by the partition of touching cells ([`super::partition`]), which only
//! redraws the line between cells already apart, so the pair went on under one outline,
//! passed on through the movie (a synthetic colony, seed 53: 71 objects covered two
//! cells each; docs/decisions.md, 2026-12-06).
//!
//! The cut follows the concave points of Bai, Sun & Zhou (2009), as the seeds' declumping
//! does for nuclei ([`crate::image::declump`]): where two convex cells meet, the outline
//! dips below its convex hull at each end of the contact; the chord between the two
//! deepest dips is the contact. It is taken only where the frame's cells are rods
//! (their median aspect at least [`super::neck::MIN_LOBE_ASPECT`]), the outline is much
//! wider than they are ([`SIDE_WIDE`]), both dips are deep ([`SIDE_NOTCH`]) and each
//! part is one rod of the frame's width ([`SIDE_PART_WIDE`]) and of about the other's
//! size ([`SIDE_SHARE`]), with a seam between them ([`SIDE_LINE`]).
//!
//! The pieces are not a division: of 22 such cuts that parted two cells on synthetic
//! movies, 21 parted cells of different mothers that one outline had come to cover, so
//! the larger piece goes on as the outline's track and the other starts one of its own.

use super::neck::{elongation, lobes, off_edge, septum, MIN_LOBE_ASPECT};
use crate::geometry::{point_segment_distance, signed_area, Point};
use crate::image::Field;

/// An outline is cut only when its width (the band width of its second moments) is at
/// least this many times the frame's rod width: two rods side by side are about twice
/// as wide as one, a single rod bent or pressed by its neighbours hardly wider.
pub const SIDE_WIDE: f64 = 1.5;

/// Each dip at least this deep below the convex hull, in rod widths: the ends of a
/// contact between two rounded rods; a rod's outline, pressed by neighbours or ragged
/// with noise, dips a pixel or so.
pub const SIDE_NOTCH: f64 = 0.25;

/// Each part at most this many times the frame's rod width: one rod, not a pair cut
/// off a clump.
pub const SIDE_PART_WIDE: f64 = 1.3;

/// The image along the contact must be more background-like than the two cells' cores
/// (a septum share above this, [`super::neck`]; brighter in phase contrast, darker in
/// fluorescence): two cells side by side show at least a faint seam between them, a
/// single cell's outline with two dips (a rod bent by its neighbours) shows its own
/// inside. On 24 side cuts of synthetic movies, the two that cut one cell
/// had −0.05 and −0.04; 19 of the 22 that parted two cells had more than 0.
pub const SIDE_LINE: f64 = 0.0;

/// The smaller part at least this share of the larger's area: two cells read as one
/// are each a cell, while a sliver that a crowded neighbour's outline spilled over, or
/// the flank of a rod pressed out of shape, is not. Of 52 side cuts on 60 synthetic
/// movies (most in colonies growing a cycle in 7–9 frames), 41 started a track that
/// covered at most half of any true cell, 29 of them with shares 0.14–0.49; 10 of the 11
/// that parted two cells had 0.53–0.95 (docs/decisions.md, 2026-12-06).
pub const SIDE_SHARE: f64 = 0.5;

/// The rod width of a frame's outlines `rings`: the lower median of their band widths,
/// or `None` when they are not rods (their median aspect is under
/// [`MIN_LOBE_ASPECT`]) or fewer than two.
pub fn rod_width<'a>(rings: impl IntoIterator<Item = &'a [Point]>) -> Option<f64> {
    let (mut aspects, mut widths): (Vec<f64>, Vec<f64>) = rings
        .into_iter()
        .filter(|r| r.len() >= 3)
        .map(|r| {
            let (a, w, _) = elongation(r);
            (a, w)
        })
        .unzip();
    if widths.len() < 2 {
        return None;
    }
    aspects.sort_by(f64::total_cmp);
    widths.sort_by(f64::total_cmp);
    let lower = |v: &[f64]| v[(v.len() - 1) / 2];
    (lower(&aspects) >= MIN_LOBE_ASPECT).then(|| lower(&widths))
}

/// The two rods of `ring` (region on the left) lying side by side in `image`, cut along
/// their contact, or `None` when it is not such a pair for rods `rod_width` wide.
pub fn side_cut(ring: &[Point], rod_width: f64, image: &Field) -> Option<(Vec<Point>, Vec<Point>)> {
    let n = ring.len();
    if n < 8 || rod_width <= 0.0 || elongation(ring).1 < SIDE_WIDE * rod_width {
        return None;
    }
    let hull = crate::image::patch::convex_hull(ring.to_vec());
    let h = hull.len();
    if h < 3 {
        return None;
    }
    let depth: Vec<f64> = ring
        .iter()
        .map(|&p| {
            (0..h)
                .map(|k| point_segment_distance(p, hull[k], hull[(k + 1) % h]))
                .fold(f64::MAX, f64::min)
        })
        .collect();
    let mut arc = vec![0.0; n + 1];
    for k in 0..n {
        arc[k + 1] = arc[k] + ring[k].dist(ring[(k + 1) % n]);
    }
    let per = arc[n];
    let deepest = |among: &dyn Fn(usize) -> bool| {
        (0..n)
            .filter(|&k| among(k))
            .max_by(|&a, &b| depth[a].total_cmp(&depth[b]))
    };
    let i = deepest(&|_| true)?;
    // The other end of the contact: the deepest dip a fifth of the outline away or more.
    let apart = |k: usize| {
        let a = (arc[k] - arc[i]).abs();
        a.min(per - a) >= 0.2 * per
    };
    let j = deepest(&apart)?;
    if depth[i].min(depth[j]) < SIDE_NOTCH * rod_width {
        return None;
    }
    if !off_edge(ring[i], image) || !off_edge(ring[j], image) {
        return None;
    }
    let (a, b) = lobes(ring, i.min(j), i.max(j))?;
    let (sa, sb) = (signed_area(&a), signed_area(&b));
    let one_rod = |p: &[Point], area: f64| {
        let (aspect, width, _) = elongation(p);
        area > 0.0 && aspect >= MIN_LOBE_ASPECT && width <= SIDE_PART_WIDE * rod_width
    };
    let alike = sa.min(sb) >= SIDE_SHARE * sa.max(sb);
    let seam = || septum(ring, &a, &b, ring[i], ring[j], image) > SIDE_LINE;
    (one_rod(&a, sa) && one_rod(&b, sb) && alike && seam()).then_some((a, b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::winding_number;
    use crate::track::neck::tests::densified;

    /// A capsule from `c0` to `c1` of radius `r`, region on the left, points at most half
    /// a pixel apart.
    fn rod(c0: Point, c1: Point, r: f64) -> Vec<Point> {
        densified(&crate::track::neck::tests::rod(c0, c1, r))
    }

    /// The outline of two rods along x, radius 4.5, one above the other and touching
    /// (centre lines 9 px apart), the lower one shifted right by `shift`: their union
    /// rasterised at a quarter pixel and outlined.
    fn pair(shift: f64) -> Vec<Point> {
        stacked((10.0, 34.0), (10.0 + shift, 34.0 + shift))
    }

    /// [`pair`] with the rods' centre lines running over `top` and `bottom` (x ranges).
    fn stacked(top: (f64, f64), bottom: (f64, f64)) -> Vec<Point> {
        let (top, bottom) = (
            rod(Point::new(top.0, 20.0), Point::new(top.1, 20.0), 4.5),
            rod(Point::new(bottom.0, 29.0), Point::new(bottom.1, 29.0), 4.5),
        );
        let (w, h) = (240, 200);
        let labels: Vec<u32> = (0..w * h)
            .map(|k| {
                let p = Point::new((k % w) as f64 * 0.25 + 0.125, (k / w) as f64 * 0.25 + 0.125);
                u32::from(winding_number(&top, p) != 0 || winding_number(&bottom, p) != 0)
            })
            .collect();
        let ring = crate::image::outline::basin_outline(&labels, 1, 80 * w + 80, w, h)
            .expect("one outline");
        let ring: Vec<Point> = ring.into_iter().map(|p| p * 0.25).collect();
        densified(&ring)
    }

    /// A 64×48 image dark inside `ring`, bright outside, with a faint seam along y = 24.5
    /// (where [`stacked`] rods touch).
    fn seamed(ring: &[Point]) -> Field {
        Field::new(
            64,
            48,
            (0..64 * 48)
                .map(|k| {
                    let p = Point::new((k % 64) as f64 + 0.5, (k / 64) as f64 + 0.5);
                    match (winding_number(ring, p) != 0, (p.y - 24.5).abs() < 1.0) {
                        (false, _) => 1.0,
                        (true, true) => 0.4,
                        (true, false) => 0.0,
                    }
                })
                .collect(),
        )
    }

    #[test]
    fn two_rods_side_by_side_are_cut_along_their_contact_one_rod_is_not() {
        let w = 9.0 * 0.93; // a capsule's band width, a little under its diameter
        let ring = pair(4.0);
        // The cells dark, the background bright, and a faint seam where they touch.
        let img = &seamed(&ring);
        let (a, b) = side_cut(&ring, w, img).expect("a pair side by side");
        let ys = |p: &[Point]| p.iter().map(|q| q.y).sum::<f64>() / p.len() as f64;
        let (ya, yb) = (ys(&a), ys(&b));
        assert!((ya.min(yb) - 20.0).abs() < 1.5 && (ya.max(yb) - 29.0).abs() < 1.5);
        // One rod, straight or with its neighbours' dents, is no pair.
        let one = rod(Point::new(10.0, 20.0), Point::new(40.0, 20.0), 4.5);
        assert!(side_cut(&one, w, img).is_none());
        // Rods end to end are the neck rule's: no wider than one.
        let chain = rod(Point::new(10.0, 20.0), Point::new(60.0, 20.0), 4.5);
        assert!(side_cut(&chain, w, img).is_none());
        // A blob as wide as the pair but round has no two deep dips.
        let blob: Vec<Point> = (0..96)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 96.0;
                Point::new(30.0 + 16.0 * t.cos(), 25.0 + 10.0 * t.sin())
            })
            .collect();
        assert!(side_cut(&blob, w, img).is_none());
        // No seam between them in the image: one cell as far as it shows.
        let flat = Field::new(64, 48, vec![0.5; 64 * 48]);
        assert!(side_cut(&ring, w, &flat).is_none());
    }

    #[test]
    fn a_sliver_beside_a_rod_is_no_cell_of_its_own() {
        let w = 9.0 * 0.93;
        // A shorter rod beside a long one, 0.66 of its area: two cells.
        let two = stacked((10.0, 50.0), (16.0, 40.0));
        assert!(side_cut(&two, w, &seamed(&two)).is_some());
        // A part of 0.41 of its area (a rod itself, aspect 2.3), as a crowded
        // neighbour's outline leaves beside a rod: no cell, and the outline is not cut.
        let stub = stacked((10.0, 50.0), (16.0, 28.0));
        assert!(side_cut(&stub, w, &seamed(&stub)).is_none());
    }

    #[test]
    fn the_rod_width_is_of_rods_only() {
        let rods: Vec<Vec<Point>> = (0..3)
            .map(|k| {
                let y = 20.0 + 12.0 * k as f64;
                rod(Point::new(10.0, y), Point::new(30.0, y), 4.5)
            })
            .collect();
        let w = rod_width(rods.iter().map(|r| r.as_slice())).expect("rods");
        assert!((w - 8.4).abs() < 0.6, "{w}");
        let disks: Vec<Vec<Point>> = (0..3)
            .map(|k| {
                (0..48)
                    .map(|s| {
                        let t = std::f64::consts::TAU * s as f64 / 48.0;
                        Point::new(20.0 * k as f64 + 8.0 * t.cos(), 8.0 * t.sin())
                    })
                    .collect()
            })
            .collect();
        assert!(rod_width(disks.iter().map(|r| r.as_slice())).is_none());
    }
}
