//! Sister rods that touch end to end are two cells: phase-contrast bacteria divide by a
//! septum, and the daughters stay in contact tip to tip with no background between them,
//! so the contour never pinches and the split event never comes (the tracking policy
//! keeps it whole). Both the outline and the image show the division: the outline has a
//! neck (at birth two caps meet; before, the mother's waist narrows to about half her
//! width), and the image along the neck turns from the cell's own dark to a brighter
//! line (the caps' notches blurred together, then the contact line). Neither alone
//! times it: a mother's last waist is as narrow as some necks at birth, and the line is
//! faint at birth. What does tell them apart is how the outline bends at the neck's
//! ends: two caps meeting make a sharp notch, a waist narrows smoothly. So the cut is
//! the shortest chord between two ring points far apart along the ring, taken when both
//! lobes it leaves are rods and the chord is narrower than [`NARROW`] of the rods' width,
//! widened by the septum share (how background-like the image is along the chord, 0
//! inside a cell, 1 outside; [`SEPTUM_WIDENS`]) and by how sharply the outline turns
//! inward at the chord's ends ([`NOTCH_WIDENS`]): caps meeting at half the width are cut,
//! a mother's waist as narrow is not, a full-width contact needs a full line and sharp
//! corners (rods side by side that turned apart). A neck of [`SMOOTH_NECK`] widths or
//! more that bends less than [`SMOOTH_TURN`] is a mother's last waist and is not cut
//! unless a clear line runs along it (on rods at least [`SMOOTH_MIN_WIDTH`] wide). A neck wider than [`WIDE_NECK`] of
//! the width needs a line whatever its corners: in a crowded colony neighbours press
//! notches into a rod's outline. A straight or bent single rod, a kidney and an ellipse
//! have no such neck and no line along it.
//!
//! A lobe is a rod when it is elongated ([`MIN_LOBE_ASPECT`]), or stubby
//! ([`MIN_STUB_ASPECT`]) with its sister of one size: a wide rod's daughters are born
//! stubby, and a cap cut off a long rod's end is small beside the rest.
//!
//! Round lobes (a dividing nucleus) are cut only where the lobes are of one size
//! ([`ROUND_SHARE`]) and either the neck is much narrower than the lobes
//! ([`ROUND_NARROW`]) with the image along it half-way to the background or more
//! ([`ROUND_GAP`]) — sister nuclei start a thin blurred gap apart, which the region model
//! still counts as inside, so the contour splits by itself only a frame or two after the
//! division — or the outline turns sharply inward at both ends of a narrow neck
//! ([`ROUND_NOTCH_TURN`]): the nearly round sister caps of a wide rod, dark where they
//! meet. A condensing mother has no neck, and an unequal hourglass is left to pinch by
//! itself.
//!
//! A taught run (issue 25) cuts its final objects the same way, but reads the septum
//! from the classifier's P(boundary) and lets it choose the chord
//! ([`neck_cut_along`], [`cut_set_at_necks`]): in a dense colony rods merged end to end
//! touch over their full width, so the outline has no neck and the shortest chord is
//! any cross-section of a rod, while the boundary class marks the contact. Measured on
//! two simulated stroke sets, docs/decisions.md (2026-12-02): the tracker's own rule on
//! the final objects lowered mean SEG with every septum image tried (raw intensity,
//! P(object), P(background), P(boundary)); the chord chosen by P(boundary) raised it.
//!
//! The cut is Icy's "opposite points come close" heuristic (de Chaumont et al. 2012,
//! Active Contours plugin) made selective by the image; the pieces are reported as a
//! division like a split of the topology core.

use crate::contours::{ContourId, ContourSet};
use crate::geometry::{
    area2_centroid, segment_intersection, signed_area, winding_number, Point, SegmentIntersection,
};
use crate::image::Field;
use crate::track::MIN_DAUGHTER_SHARE;
use std::collections::{HashMap, HashSet};

/// The widest neck cut with no line along it and an outline that does not bend at its
/// ends, as a share of the thinner rod's width (a mother's last waist is about 0.55):
/// a neck is told by its notch and its line, hardly by its width alone. Fitted on
/// synthetic phase-contrast movies (seeds 1–12, checked on 13–24 and on noisier, blurred
/// and thinner renderings): see docs/decisions.md.
pub const NARROW: f64 = 0.1;

/// How much wider (in rod widths) a cut neck may be per unit of septum share along it.
pub const SEPTUM_WIDENS: f64 = 0.6;

/// How much wider (in rod widths) a cut neck may be per radian the outline turns inward
/// at its two ends (`notch_turn`): two caps just meeting turn it by about 1.6 rad
/// together, a constricting mother's smooth waist by about 0.6.
pub const NOTCH_WIDENS: f64 = 0.475;

/// A neck wider than this share of the thinner rod's width is cut only with a line
/// along it ([`WIDE_NECK_LINE`]), however sharply the outline turns at its ends: sisters
/// at birth meet over 0.37–0.63 of their width (10th to 90th percentile), while a rod
/// whose crowded neighbours press notches into its outline showed necks of 0.77–0.96
/// widths with hardly any line (docs/decisions.md, 2026-12-05).
pub const WIDE_NECK: f64 = 0.7;

/// The least septum share along a neck wider than [`WIDE_NECK`] for a cut.
pub const WIDE_NECK_LINE: f64 = 0.3;

/// A neck at least this wide (a share of the thinner rod's width) whose outline turns
/// less than [`SMOOTH_TURN`] at its ends is a mother's last waist, not two caps, and is
/// not cut (unless a clear line runs along it, [`SMOOTH_LINE`]). The widening by the
/// line and the turn alone cut such waists a frame early: on 24 synthetic movies the
/// cuts a frame before the birth turned 0.76–1.14 rad at 0.50–0.62 widths, those at the
/// birth 1.16–2.13 (10th to 90th percentile); docs/decisions.md, 2026-12-06.
pub const SMOOTH_NECK: f64 = 0.4;

/// The least turn (radians, both ends of the neck together) of a neck at least
/// [`SMOOTH_NECK`] wide for a cut.
pub const SMOOTH_TURN: f64 = 1.0;

/// A neck along which the image is at least this background-like (septum share) is cut
/// however gently it bends: a septum line that shows is the division, whatever the
/// outline does. No waist the bound above refused on the synthetic movies had one over
/// 0.46.
pub const SMOOTH_LINE: f64 = 0.5;

/// The bound on a gentle neck ([`SMOOTH_NECK`]) holds only where the lobes are at least
/// this wide (pixels, their band width on the evolved outline, which comes out narrower
/// than the rod as drawn: synthetic rods drawn 6–7.5 px wide measured 4.8–6.2 at their
/// cuts, median 5.4; rods drawn 8–10 px, 6.0–8.0, median 6.9). The turn is measured over
/// an arc of a quarter width, which on thinner rods spans little more than a pixel, so
/// two caps meeting turn as little as a waist (at necks of 0.4 widths or more, 28% of
/// the thin rods' cuts at birth turned under 1 rad, against 2% on the wider ones).
pub const SMOOTH_MIN_WIDTH: f64 = 5.5;

/// Each lobe at least this elongated (major over minor axis of its second moments): a
/// rod. A nucleus pinches into round lobes, and the contour splits it by itself when
/// the daughters part; cutting it at a neck would be early.
pub const MIN_LOBE_ASPECT: f64 = 1.5;

/// A lobe at least this elongated but under [`MIN_LOBE_ASPECT`] is a stubby rod when
/// the two lobes are of one size ([`ROUND_SHARE`]): the daughters of a wide rod (11–14
/// px wide at birth, aspect 1.3–1.5) are stubby, while a cap cut off a long rod's end is
/// small beside the rest. Under the round rule, their birth waited for the sisters to
/// slide apart (2–3 frames late on synthetic wide rods): docs/decisions.md, 2026-12-05.
pub const MIN_STUB_ASPECT: f64 = 1.3;

/// Round lobes (either below [`MIN_LOBE_ASPECT`]): the widest neck cut, as a share of the
/// thinner lobe's width. Sister nuclei in their first frame are a thin blurred gap apart
/// that the contour still bridges (a dip, not background, so the region model keeps it
/// inside); their neck was 0.03–0.31 widths on synthetic nuclei (seeds 1, 2).
pub const ROUND_NARROW: f64 = 0.4;

/// Round lobes: the least septum share along the neck: the gap is half-way to the
/// background or more (0.50–0.76 at births on seeds 1, 2), a nucleus's texture is not.
pub const ROUND_GAP: f64 = 0.4;

/// Round lobes with no gap between them are cut where the outline turns inward by at
/// least this much (radians, both ends of the neck together) and the neck is narrower
/// than [`ROUND_NOTCH_NARROW`] of the thinner lobe: the sister caps of a wide rod meet
/// at a sharp notch from their first frame, dark between them (the contact line forms
/// later), and are nearly round. The round necks tried on one such movie turned 2.6–3.5
/// rad at 0.19–0.43 widths; a nucleus splits at a gap first ([`ROUND_GAP`]). Under the gap rule alone the
/// synthetic rods 13–17 px wide divided 1–3 frames late (division F1 0.48–0.78); the
/// turn chosen between 1.6 and 2.2, where F1 is flat (docs/decisions.md, 2026-12-06).
pub const ROUND_NOTCH_TURN: f64 = 2.0;

/// Round lobes meeting at a notch: the widest neck cut ([`ROUND_NOTCH_TURN`]), as a
/// share of the thinner lobe's width.
pub const ROUND_NOTCH_NARROW: f64 = 0.5;

/// Round lobes: the smaller lobe's least area, as a share of the larger: sisters are of
/// one size (0.86–1.0 at births); an unequal hourglass (sim_plus's mother a frame before
/// its division, 0.73, neck 0.21 widths, septum 0.60) is left to split by itself.
pub const ROUND_SHARE: f64 = 0.8;

/// Rods: the smaller lobe's least area, as a share of the larger. A rod divides in
/// the middle (the curated masks of a real E. coli movie: sisters 0.70–0.98 of each
/// other in their first frame), while in a dense colony a neighbour's end pressed into
/// a rod's side makes a notch a fifth to a half along it. On a real dense colony
/// (divbac26) the divisions at the reference's frame had sisters of 0.72 or more (10th
/// percentile), those of no reference division 0.50 (median). Requiring half here and
/// sisters of [`crate::track::SISTER_SHARE`] took TRA / CHOTA / division F1 there from
/// 0.901 / 0.736 / 0.358 to 0.907 / 0.765 / 0.406, and HeLa's division F1 from 0.623 to
/// 0.640 (docs/decisions.md, 2026-12-08).
pub const ROD_SHARE: f64 = 0.5;

/// How far (pixels) a neck's ends must be from the frame's edge.
pub const EDGE_MARGIN: f64 = 3.0;

/// Whether `p` is at least [`EDGE_MARGIN`] from the edge of `image`: a cell cut off by
/// the frame's edge is not measured across it (its outline runs along the edge, and the
/// band outside is not in the image).
pub(crate) fn off_edge(p: Point, image: &Field) -> bool {
    let (w, h) = (image.width as f64, image.height as f64);
    p.x.min(p.y).min(w - p.x).min(h - p.y) >= EDGE_MARGIN
}

/// The most pieces one outline is cut into in one frame.
pub const MAX_PIECES: usize = 16;

/// `ring` cut at its necks until none is left (a chain of touching rods is cut at each
/// contact), at most [`MAX_PIECES`] pieces, largest first; `None` when it has no neck.
/// With `line`, each cut is [`neck_cut_along`] it.
pub fn cut_at_necks(
    ring: &[Point],
    image: &Field,
    line: Option<&Field>,
) -> Option<Vec<Vec<Point>>> {
    let (a, b) = neck_cut_along(ring, image, line)?;
    Some(cut_further(a, b, image, line))
}

/// [`cut_at_necks`] with no septum field; an outline that is not cut gives its neck as
/// measured instead (`None` when it has none), which the tracker keeps to date a
/// division it cuts in a later frame ([`crate::track::Tracker`]).
pub fn cut_or_measure(ring: &[Point], image: &Field) -> Result<Vec<Vec<Point>>, Option<Neck>> {
    match measure(ring, image) {
        Some(k) if k.cut() => {
            let (a, b) = k.lobes;
            Ok(cut_further(a, b, image, None))
        }
        other => Err(other),
    }
}

/// Lobes `a` and `b` of a cut outline cut again at their own necks until none is left,
/// largest first.
fn cut_further(
    a: Vec<Point>,
    b: Vec<Point>,
    image: &Field,
    line: Option<&Field>,
) -> Vec<Vec<Point>> {
    let (mut done, mut todo) = (Vec::new(), vec![a, b]);
    while let Some(r) = todo.pop() {
        match (done.len() + todo.len() + 1 < MAX_PIECES)
            .then(|| neck_cut_along(&r, image, line))
            .flatten()
        {
            Some((a, b)) => todo.extend([a, b]),
            None => done.push(r),
        }
    }
    done.sort_by(|a, b| signed_area(b).total_cmp(&signed_area(a)));
    done
}

/// How far apart (pixels) the pieces [`cut_set_at_necks`] puts back are held: rings of
/// one set must not touch, and the pieces of a cut share their chord.
pub const PIECE_GAP: f64 = 0.5;

/// Every outer ring of `set` with no hole cut at the septa `line` shows (a taught run's
/// P(boundary): [`cut_at_necks`] with the chord chosen and judged by it), the pieces put
/// back [`PIECE_GAP`] apart along each chord (the chord split into edges no longer than
/// the set's bound). A ring whose pieces the set refuses (they would touch another
/// ring) stays whole. Returns the number of cuts made.
pub fn cut_set_at_necks(set: &mut ContourSet, line: &Field) -> usize {
    let parents = set.parents();
    let holed: HashSet<ContourId> = parents.iter().filter_map(|&(_, p)| p).collect();
    let outers: Vec<ContourId> = parents
        .iter()
        .filter(|&&(id, p)| p.is_none() && !holed.contains(&id) && !set.is_hole(id))
        .map(|&(id, _)| id)
        .collect();
    let bound = set.max_edge();
    let mut cuts = 0;
    for id in outers {
        let ring = set.ring_points(id);
        let n = ring.len();
        // Only a ring the set would take again: it is put back if a piece is refused.
        if (0..n).any(|k| ring[k].dist(ring[(k + 1) % n]) > bound) {
            continue;
        }
        let Some(pieces) = cut_at_necks(&ring, line, Some(line)) else {
            continue;
        };
        let pieces: Vec<Vec<Point>> = pieces.iter().map(|p| parted(p, &ring, bound)).collect();
        set.remove_ring(id);
        let mut added = Vec::new();
        for p in &pieces {
            match set.add_ring(p) {
                Ok(k) => added.push(k),
                Err(_) => break,
            }
        }
        if added.len() == pieces.len() {
            cuts += pieces.len() - 1;
        } else {
            for k in added {
                set.remove_ring(k);
            }
            // It was in the set, its edges within the bound: the set takes it again.
            let _ = set.add_ring(&ring);
        }
    }
    cuts
}

/// `piece` (a lobe of `ring`, made of `ring`'s points) with each chord's ends (a chord:
/// an edge that is not one of `ring`'s) slid half of [`PIECE_GAP`] back along the
/// piece's outline, and the chord split into edges of at most `bound`.
fn parted(piece: &[Point], ring: &[Point], bound: f64) -> Vec<Point> {
    let key = |p: Point| (p.x.to_bits(), p.y.to_bits());
    let n = ring.len();
    let at: HashMap<(u64, u64), usize> =
        ring.iter().enumerate().map(|(k, &p)| (key(p), k)).collect();
    let m = piece.len();
    let chord = |k: usize| {
        let (a, b) = (at[&key(piece[k])], at[&key(piece[(k + 1) % m])]);
        b != (a + 1) % n
    };
    // Each chord end slides back along the piece's own outline edge next to it: it stays
    // on the outline the set held apart from every other ring.
    let mut moved = piece.to_vec();
    let slide = |from: Point, toward: Point| {
        let len = from.dist(toward);
        from + (toward - from) * ((0.5 * PIECE_GAP).min(0.3 * len) / len.max(1e-9))
    };
    for k in (0..m).filter(|&k| chord(k)) {
        let (before, after) = ((k + m - 1) % m, (k + 1) % m);
        if !chord(before) {
            moved[k] = slide(piece[k], piece[before]);
        }
        if !chord(after) {
            moved[after] = slide(piece[after], piece[(k + 2) % m]);
        }
    }
    let mut out = Vec::with_capacity(m);
    for k in 0..m {
        out.push(moved[k]);
        let (p, q) = (moved[k], moved[(k + 1) % m]);
        if chord(k) {
            let parts = (p.dist(q) / (0.9 * bound)).ceil().max(1.0) as usize;
            out.extend((1..parts).map(|s| p + (q - p) * (s as f64 / parts as f64)));
        }
    }
    out
}

/// The two lobes of `ring` (region on the left) cut at its neck, each a ring with the
/// region on the left, or `None` when it has none.
pub fn neck_cut(ring: &[Point], image: &Field) -> Option<(Vec<Point>, Vec<Point>)> {
    neck_cut_along(ring, image, None)
}

/// [`neck_cut`], or with `line` (a field high along a septum: a taught run's
/// P(boundary)) a cut that field chooses and judges: the chord is the shortest once its
/// length is discounted by [`LINE_PULL`] × `line`'s mean along its middle half (among
/// chords inside the ring that leave lobes of a daughter's share), and it is cut when
/// both lobes are rods of at least [`LINE_LOBE_ASPECT`], `line` rises by
/// [`LINE_CONTRAST`] from the lobes' cores to the chord, and the chord is at most
/// [`LINE_WIDE`] widths. Rods touching end to end over their full width have no neck
/// the outline shows; the classifier's boundary band across the contact does.
pub fn neck_cut_along(
    ring: &[Point],
    image: &Field,
    line: Option<&Field>,
) -> Option<(Vec<Point>, Vec<Point>)> {
    let Some(f) = line else {
        return measure(ring, image).filter(Neck::cut).map(|k| k.lobes);
    };
    let (i, j) = shortest_chord(ring, line)?;
    let (a, b) = daughters(ring, i, j, image)?;
    let (la, lb) = (elongation(&a), elongation(&b));
    let width = la.1.min(lb.1);
    let contrast = along(f, ring[i], ring[j]) - 0.5 * (core_mean(f, &a) + core_mean(f, &b));
    let ok = la.0.min(lb.0) >= LINE_LOBE_ASPECT
        && contrast >= LINE_CONTRAST
        && ring[i].dist(ring[j]) < LINE_WIDE * width;
    ok.then_some((a, b))
}

/// The neck of `ring` as measured ([`Neck`]), whether or not it is cut; `None` when it
/// has no chord leaving two lobes of a daughter's share off the frame's edge.
pub fn measure(ring: &[Point], image: &Field) -> Option<Neck> {
    let (i, j) = shortest_chord(ring, None)?;
    let (a, b) = daughters(ring, i, j, image)?;
    let (la, lb) = (elongation(&a), elongation(&b));
    let width = la.1.min(lb.1);
    let (aa, ab) = (signed_area(&a), signed_area(&b));
    Some(Neck {
        narrow: ring[i].dist(ring[j]) / width.max(1e-9),
        width,
        line: septum(ring, &a, &b, ring[i], ring[j], image),
        turn: notch_turn(ring, i, width) + notch_turn(ring, j, width),
        aspect: la.0.min(lb.0),
        share: aa.min(ab) / aa.max(ab),
        lobes: (a, b),
    })
}

/// The lobes of `ring` at the chord `i`–`j` when its ends are off the frame's edge and
/// both lobes are of a daughter's share ([`MIN_DAUGHTER_SHARE`]).
fn daughters(
    ring: &[Point],
    i: usize,
    j: usize,
    image: &Field,
) -> Option<(Vec<Point>, Vec<Point>)> {
    if !off_edge(ring[i], image) || !off_edge(ring[j], image) {
        return None;
    }
    let (a, b) = lobes(ring, i, j)?;
    let (aa, ab) = (signed_area(&a), signed_area(&b));
    (aa > 0.0 && ab > 0.0 && aa.min(ab) >= MIN_DAUGHTER_SHARE * aa.max(ab)).then_some((a, b))
}

/// The shortest chord of `ring` whose ends are at least a fifth of the perimeter apart
/// both ways, its length discounted by a septum `line` ([`neck_cut_along`]).
fn shortest_chord(ring: &[Point], line: Option<&Field>) -> Option<(usize, usize)> {
    let n = ring.len();
    if n < 8 {
        return None;
    }
    let mut arc = vec![0.0; n + 1];
    for i in 0..n {
        arc[i + 1] = arc[i] + ring[i].dist(ring[(i + 1) % n]);
    }
    let per = arc[n];
    // Prefix sums of the edges' cross products: any lobe's area in O(1).
    let mut cross = vec![0.0; n];
    for i in 1..n {
        cross[i] = cross[i - 1] + ring[i - 1].cross(ring[i]);
    }
    let total = signed_area(ring);
    // The shortest chord whose ends are at least a fifth of the perimeter apart both ways.
    let mut best: Option<(f64, usize, usize)> = None;
    for i in 0..n {
        for j in i + 1..n {
            let a = arc[j] - arc[i];
            if a.min(per - a) < 0.2 * per {
                continue;
            }
            let d = ring[i].dist(ring[j]);
            let score = match line {
                Some(f) if best.is_none_or(|b| d * (1.0 - LINE_PULL) < b.0) => {
                    // Only chords that leave two lobes of the sizes a cut needs and run
                    // inside: a chord along the rim (where the boundary class also
                    // fires) would win and then be refused.
                    let lobe = 0.5 * (cross[j] - cross[i] + ring[j].cross(ring[i]));
                    let rest = total - lobe;
                    let mid = (ring[i] + ring[j]) * 0.5;
                    if lobe.min(rest) < MIN_DAUGHTER_SHARE * lobe.max(rest)
                        || winding_number(ring, mid) == 0
                    {
                        continue;
                    }
                    d * (1.0 - LINE_PULL * along(f, ring[i], ring[j]).clamp(0.0, 1.0))
                }
                Some(_) => continue,
                None => d,
            };
            if best.is_none_or(|b| score < b.0) {
                best = Some((score, i, j));
            }
        }
    }
    best.map(|(_, i, j)| (i, j))
}

/// An outline's shortest chord between points a fifth of its perimeter apart, when the
/// two lobes it leaves are of a daughter's share ([`measure`]), as measured.
#[derive(Clone, Debug, PartialEq)]
pub struct Neck {
    /// The chord's length over the thinner lobe's width.
    pub narrow: f64,
    /// The thinner lobe's width, pixels.
    pub width: f64,
    /// How background-like the image is along the chord: 0 as dark as the lobes' cores,
    /// 1 as the band just outside the outline.
    pub line: f64,
    /// How far the outline turns inward at the chord's two ends together, radians.
    pub turn: f64,
    /// The less elongated lobe's aspect.
    pub aspect: f64,
    /// The smaller lobe's area over the larger's.
    pub share: f64,
    /// The two lobes, each made of the outline's points.
    pub lobes: (Vec<Point>, Vec<Point>),
}

impl Neck {
    /// Whether both lobes are rods ([`MIN_LOBE_ASPECT`], [`MIN_STUB_ASPECT`]).
    pub fn rods(&self) -> bool {
        self.aspect >= MIN_LOBE_ASPECT
            || (self.aspect >= MIN_STUB_ASPECT && self.share >= ROUND_SHARE)
    }

    /// Whether the outline is two cells here ([`neck_cut`]'s rule).
    pub fn cut(&self) -> bool {
        let (d, line, turn) = (self.narrow, self.line, self.turn);
        if !self.rods() {
            // Round lobes: sister nuclei a thin gap apart that the contour still bridges.
            let gap = d < ROUND_NARROW && line >= ROUND_GAP;
            let caps = d < ROUND_NOTCH_NARROW && turn >= ROUND_NOTCH_TURN;
            return (gap || caps) && self.share >= ROUND_SHARE;
        }
        // A mother's last waist: wide, bending gently, no clear line (on rods wide enough
        // for the turn to be measured).
        let waist = d >= SMOOTH_NECK
            && turn < SMOOTH_TURN
            && line < SMOOTH_LINE
            && self.width >= SMOOTH_MIN_WIDTH;
        d < NARROW + SEPTUM_WIDENS * line + NOTCH_WIDENS * turn
            && (d <= WIDE_NECK || line >= WIDE_NECK_LINE)
            && !waist
            && self.share >= ROD_SHARE
    }
}

/// The two lobes of `ring` on either side of the chord from `ring[i]` to `ring[j]`
/// (`i < j`), each made of `ring`'s points, when the chord runs inside the ring (not
/// across a bay outside it) and crosses none of its edges (both lobes are simple).
pub(crate) fn lobes(ring: &[Point], i: usize, j: usize) -> Option<(Vec<Point>, Vec<Point>)> {
    let n = ring.len();
    if winding_number(ring, (ring[i] + ring[j]) * 0.5) == 0 {
        return None;
    }
    let crosses = (0..n).any(|k| {
        let l = (k + 1) % n;
        ![i, j].contains(&k)
            && ![i, j].contains(&l)
            && !matches!(
                segment_intersection(ring[i], ring[j], ring[k], ring[l]),
                SegmentIntersection::None
            )
    });
    if crosses {
        return None;
    }
    let a: Vec<Point> = ring[i..=j].to_vec();
    let b: Vec<Point> = ring[j..].iter().chain(&ring[..=i]).copied().collect();
    Some((a, b))
}

/// How far the outline turns inward (radians, ≥ 0) at `ring[k]`: the angle between the
/// chords to the ring points an arc of a quarter `width` before and after it.
fn notch_turn(ring: &[Point], k: usize, width: f64) -> f64 {
    let n = ring.len();
    let reach = 0.25 * width;
    let walk = |step: usize| {
        let (mut s, mut c) = (0.0, k);
        while s < reach {
            let next = (c + step) % n;
            s += ring[c].dist(ring[next]);
            c = next;
            if c == k {
                break;
            }
        }
        ring[c]
    };
    let (t1, t2) = (ring[k] - walk(n - 1), walk(1) - ring[k]);
    (-t1.cross(t2).atan2(t1.x * t2.x + t1.y * t2.y)).max(0.0)
}

/// How much a chord's length is discounted at most for a septum along it
/// ([`neck_cut_along`]).
pub const LINE_PULL: f64 = 0.9;

/// `f`'s mean along the middle of lobe `l`'s major axis (±2 px about its centroid).
fn core_mean(f: &Field, l: &[Point]) -> f64 {
    let c = area2_centroid(l).1;
    let axis = elongation(l).2;
    (-2..=2)
        .map(|k| f.sample(c + axis * (k as f64)))
        .sum::<f64>()
        / 5.0
}

/// Along a septum field ([`neck_cut_along`]): each lobe at least this elongated.
pub const LINE_LOBE_ASPECT: f64 = 2.0;
/// Along a septum field: the least rise of the field from the lobes' cores to the chord.
pub const LINE_CONTRAST: f64 = 0.45;
/// Along a septum field: the widest chord cut, as a share of the thinner lobe's width.
pub const LINE_WIDE: f64 = 1.25;

/// `f`'s mean along the middle half of the chord `p`–`q`.
fn along(f: &Field, p: Point, q: Point) -> f64 {
    (0..=8)
        .map(|k| f.sample(p + (q - p) * (0.25 + 0.5 * k as f64 / 8.0)))
        .sum::<f64>()
        / 9.0
}

/// How background-like the image is along the middle half of the chord `p`–`q`: 0 as
/// dark as the lobes' cores, 1 as the band just outside the outline (a septum line or
/// the gap between two touching caps; a constricting waist is still the cell's own).
pub(crate) fn septum(
    ring: &[Point],
    a: &[Point],
    b: &[Point],
    p: Point,
    q: Point,
    image: &Field,
) -> f64 {
    let mean = |pts: &mut dyn Iterator<Item = Point>| {
        let (mut s, mut n) = (0.0, 0usize);
        for x in pts {
            s += image.sample(x);
            n += 1;
        }
        s / n.max(1) as f64
    };
    let inside = 0.5 * (core_mean(image, a) + core_mean(image, b));
    let n = ring.len();
    let (w, h) = (image.width as f64, image.height as f64);
    let outside = mean(
        &mut (0..n)
            .map(|k| {
                let t = ring[(k + 1) % n] - ring[(k + n - 1) % n];
                let out = Point::new(t.y, -t.x) * (1.0 / t.norm().max(1e-9));
                ring[k] + out * 3.0
            })
            .filter(|p| p.x >= 0.0 && p.y >= 0.0 && p.x < w && p.y < h),
    );
    let chord = along(image, p, q);
    let span = outside - inside;
    if span.abs() < 1e-9 {
        return 0.0;
    }
    (chord - inside) / span
}

/// The aspect (major over minor axis) of polygon `p`'s second moments, its width across
/// the major axis (a band's, √(12 × minor moment / area)) and that axis (unit).
pub(crate) fn elongation(p: &[Point]) -> (f64, f64, Point) {
    elongation_of(&[p])
}

/// [`elongation`] of the region that disjoint polygons `parts` cover together.
pub(crate) fn elongation_of(parts: &[&[Point]]) -> (f64, f64, Point) {
    let (mut a2, mut at) = (0.0, Point::new(0.0, 0.0));
    for p in parts {
        let (k, c) = area2_centroid(p);
        a2 += k;
        at = at + c * k;
    }
    if a2.abs() < 1e-9 {
        return (1.0, 0.0, Point::new(1.0, 0.0));
    }
    let c = at * (1.0 / a2);
    // Second moments about the common centroid (each polygon's formula holds about any
    // point, so the parts' sums add).
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in parts {
        let n = p.len();
        for i in 0..n {
            let (u, v) = (p[i] - c, p[(i + 1) % n] - c);
            let k = u.cross(v);
            sxx += k * (u.y * u.y + u.y * v.y + v.y * v.y);
            syy += k * (u.x * u.x + u.x * v.x + v.x * v.x);
            sxy += k * (u.x * v.y + 2.0 * u.x * u.y + 2.0 * v.x * v.y + v.x * u.y);
        }
    }
    // Ixx = ∫y², Iyy = ∫x², Ixy = ∫xy.
    let (ixx, iyy, ixy) = (sxx / 12.0, syy / 12.0, sxy / 24.0);
    let (mx, my, mxy) = (iyy, ixx, ixy); // ∫x², ∫y², ∫xy
    let tr = 0.5 * (mx + my);
    let disc = (0.25 * (mx - my) * (mx - my) + mxy * mxy).sqrt();
    let (l1, l2) = (tr + disc, (tr - disc).max(1e-12));
    let ang = 0.5 * (2.0 * mxy).atan2(mx - my);
    let area = 0.5 * a2;
    (
        (l1 / l2).sqrt(),
        (12.0 * l2 / area.abs()).sqrt(),
        Point::new(ang.cos(), ang.sin()),
    )
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A capsule (rod) from `c0` to `c1` of radius `r`, region on the left.
    pub(crate) fn rod(c0: Point, c1: Point, r: f64) -> Vec<Point> {
        let ang = (c1.y - c0.y).atan2(c1.x - c0.x);
        let mut pts = Vec::new();
        for (c, a0) in [
            (c1, ang - std::f64::consts::FRAC_PI_2),
            (c0, ang + std::f64::consts::FRAC_PI_2),
        ] {
            for k in 0..=16 {
                let a = a0 + std::f64::consts::PI * k as f64 / 16.0;
                pts.push(Point::new(c.x + r * a.cos(), c.y + r * a.sin()));
            }
        }
        pts
    }

    #[test]
    fn a_straight_rod_a_disk_and_an_ellipse_are_not_cut() {
        let img = flat();
        let straight = rod(Point::new(10.0, 10.0), Point::new(40.0, 10.0), 4.5);
        assert!(neck_cut(&straight, &img).is_none());
        let disk: Vec<Point> = (0..64)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 64.0;
                Point::new(50.0 + 20.0 * a.cos(), 50.0 + 12.0 * a.sin())
            })
            .collect();
        assert!(neck_cut(&disk, &img).is_none());
    }

    #[test]
    fn two_rods_end_to_end_and_two_round_caps_are_cut_at_their_neck_an_hourglass_is_not() {
        // Two rods of radius 4.5 whose caps overlap by 0.5 px: a neck of about 3, a third
        // of their width (on a flat image, no line along it: the outline alone).
        let img = flat();
        let a = rod(Point::new(10.0, 20.0), Point::new(22.5, 20.0), 4.5);
        let b = rod(Point::new(31.5, 20.0), Point::new(44.0, 20.0), 4.5);
        let ring = union_of(&a, &b);
        let (p, q) = neck_cut(&ring, &img).expect("a neck");
        let (cp, cq) = (centre(&p), centre(&q));
        let (lo, hi) = (cp.x.min(cq.x), cp.x.max(cq.x));
        assert!(
            (lo - 16.0).abs() < 3.0 && (hi - 38.0).abs() < 3.0,
            "{cp:?} {cq:?}"
        );
        let disk = |cx: f64, r: f64| -> Vec<Point> {
            (0..48)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / 48.0;
                    Point::new(cx + r * t.cos(), 20.0 + r * t.sin())
                })
                .collect()
        };
        // Two disks of one size on a neck as narrow, dark between them: the nearly round
        // sister caps of a wide rod, cut at their notch.
        let (p, q) =
            neck_cut(&union_of(&disk(20.0, 10.0), &disk(39.5, 10.0)), &img).expect("sister caps");
        let (cp, cq) = (centre(&p), centre(&q));
        assert!((cp.x.min(cq.x) - 20.0).abs() < 2.0 && (cp.x.max(cq.x) - 39.5).abs() < 2.0);
        // Disks of unequal size on a narrow neck (an hourglass, left to pinch by itself),
        // and disks overlapping into a wide waist: not cut.
        assert!(neck_cut(&union_of(&disk(20.0, 10.0), &disk(36.5, 7.0)), &img).is_none());
        assert!(neck_cut(&union_of(&disk(20.0, 10.0), &disk(34.0, 10.0)), &img).is_none());
    }

    #[test]
    fn a_wide_neck_with_sharp_corners_needs_a_line() {
        // A rod 9 px wide with a sharp notch 0.9 px deep pressed into each side at x = 27
        // (as crowded neighbours press into a rod): a neck of 0.8 widths whose outline
        // turns sharply at its ends. On a flat image, no line: not cut; with the image
        // background-like along it: cut.
        let (top, bottom) = (15.5, 24.5);
        let notch = |y: f64, inward: f64| {
            [(26.1, y), (27.0, y + inward), (27.9, y)].map(|(x, y)| Point::new(x, y))
        };
        let mut corners = vec![Point::new(10.0, bottom)];
        corners.extend(notch(bottom, -0.9));
        corners.push(Point::new(44.0, bottom));
        for k in 1..16 {
            let a = std::f64::consts::FRAC_PI_2 - std::f64::consts::PI * k as f64 / 16.0;
            corners.push(Point::new(44.0 + 4.5 * a.cos(), 20.0 + 4.5 * a.sin()));
        }
        corners.push(Point::new(44.0, top));
        corners.extend(notch(top, 0.9).into_iter().rev());
        corners.push(Point::new(10.0, top));
        for k in 1..16 {
            let a = -std::f64::consts::FRAC_PI_2 - std::f64::consts::PI * k as f64 / 16.0;
            corners.push(Point::new(10.0 + 4.5 * a.cos(), 20.0 + 4.5 * a.sin()));
        }
        let ring = densified(&corners);
        assert!(neck_cut(&ring, &flat()).is_none());
        // The cell at 1, the background and a line across the neck (x 26–27) at 0.
        let lined = Field::new(
            64,
            40,
            (0..64 * 40)
                .map(|i| {
                    let p = Point::new((i % 64) as f64 + 0.5, (i / 64) as f64 + 0.5);
                    let cell = winding_number(&ring, p) != 0 && !(26..28).contains(&(i % 64));
                    if cell {
                        1.0
                    } else {
                        0.0
                    }
                })
                .collect(),
        );
        assert!(neck_cut(&ring, &lined).is_some());
    }

    #[test]
    fn a_mothers_gentle_waist_is_not_cut_and_a_deep_one_is() {
        // A rod of width 9 whose waist narrows smoothly (a Gaussian over 0.45 widths, as a
        // constricting mother): at 0.55 of the width the outline bends gently, unlike two
        // caps meeting at the same width; pinched to 0.3 it is cut by its narrowness alone.
        let img = flat();
        let waist = |pinch: f64| waist(4.5, pinch);
        assert!(neck_cut(&waist(0.45), &img).is_none());
        let (p, q) = neck_cut(&waist(0.7), &img).expect("a deep waist is a neck");
        let (cp, cq) = (centre(&p), centre(&q));
        assert!((cp.x.min(cq.x) - 21.0).abs() < 4.0 && (cp.x.max(cq.x) - 39.0).abs() < 4.0);
        // Two caps meeting as wide as that gentle waist: the outline turns sharply at the
        // neck's ends, so it is cut.
        let a = rod(Point::new(10.0, 20.0), Point::new(22.5, 20.0), 4.5);
        let b = rod(Point::new(30.3, 20.0), Point::new(42.8, 20.0), 4.5);
        let ring = union_of(&a, &b);
        let neck = ring
            .iter()
            .filter(|p| (p.x - 26.4).abs() < 0.8)
            .map(|p| (p.y - 20.0).abs());
        assert!(
            neck.fold(f64::MAX, f64::min) > 2.0,
            "the caps meet over half the width"
        );
        assert!(neck_cut(&ring, &img).is_some());
    }

    #[test]
    fn a_notch_a_third_along_a_rod_is_no_division() {
        // The same caps meeting as above, the one rod over twice the other's length: a
        // neighbour's end pressed into a rod's side, not sisters (ROD_SHARE).
        let img = flat();
        let sisters = union_of(
            &rod(Point::new(10.0, 20.0), Point::new(22.5, 20.0), 4.5),
            &rod(Point::new(30.3, 20.0), Point::new(42.8, 20.0), 4.5),
        );
        assert!(neck_cut(&sisters, &img).is_some());
        let unequal = union_of(
            &rod(Point::new(16.0, 20.0), Point::new(22.5, 20.0), 4.5),
            &rod(Point::new(30.3, 20.0), Point::new(56.0, 20.0), 4.5),
        );
        let neck = measure(&unequal, &img).expect("a neck");
        assert!(neck.share < ROD_SHARE && neck.rods(), "{neck:?}");
        assert!(neck_cut(&unequal, &img).is_none());
        assert!(Neck { share: 0.9, ..neck }.cut());
    }

    #[test]
    fn two_halves_of_a_rod_measure_as_the_rod() {
        let p = |x: f64, y: f64| Point::new(x, y);
        // A 40×8 box along a diagonal, and its two halves.
        let (c, u, v) = (p(50.0, 50.0), p(0.6, 0.8), p(-0.8, 0.6));
        let at = |a: f64, b: f64| c + u * a + v * b;
        let whole = [
            at(-20.0, -4.0),
            at(20.0, -4.0),
            at(20.0, 4.0),
            at(-20.0, 4.0),
        ];
        let left = [at(-20.0, -4.0), at(0.0, -4.0), at(0.0, 4.0), at(-20.0, 4.0)];
        let right = [at(0.0, -4.0), at(20.0, -4.0), at(20.0, 4.0), at(0.0, 4.0)];
        let (a, w, axis) = elongation(&whole);
        let (a2, w2, axis2) = elongation_of(&[&left, &right]);
        assert!((a - 5.0).abs() < 1e-9 && (w - 8.0).abs() < 1e-9);
        assert!((a2 - a).abs() < 1e-9 && (w2 - w).abs() < 1e-9);
        assert!(axis.cross(axis2).abs() < 1e-9 && axis.cross(u).abs() < 1e-9);
        // Side by side instead: as wide as long.
        let beside = [at(-20.0, 4.0), at(0.0, 4.0), at(0.0, 12.0), at(-20.0, 12.0)];
        let (a3, w3, _) = elongation_of(&[&left, &beside]);
        assert!((a3 - 20.0 / 16.0).abs() < 1e-9 && (w3 - 16.0).abs() < 1e-9);
    }

    #[test]
    fn a_gentle_waist_is_cut_only_with_a_clear_line_unless_the_rod_is_thin() {
        // The waist of a rod 9 px wide narrowed to 0.6 of it, smoothly, with a faint line
        // along it (septum share 0.45): the mother's last frame, not cut. The same with a
        // clear line (0.8) is cut, and so is the faint one on a rod 5 px wide, whose
        // outline is too coarse for its turn to tell a waist from two caps.
        let lined = |ring: &[Point], share: f64| {
            Field::new(
                64,
                64,
                (0..64 * 64)
                    .map(|i| {
                        let p = Point::new((i % 64) as f64 + 0.5, (i / 64) as f64 + 0.5);
                        match (winding_number(ring, p) != 0, (29..31).contains(&(i % 64))) {
                            (false, _) => 0.0,
                            (true, false) => 1.0,
                            (true, true) => 1.0 - share as f32,
                        }
                    })
                    .collect(),
            )
        };
        let wide = waist(4.5, 0.4);
        assert!(neck_cut(&wide, &lined(&wide, 0.45)).is_none());
        assert!(neck_cut(&wide, &lined(&wide, 0.8)).is_some());
        let thin = waist(2.5, 0.4);
        let (p, q) = neck_cut(&thin, &lined(&thin, 0.45)).expect("a thin rod's waist");
        let (cp, cq) = (centre(&p), centre(&q));
        assert!(cp.x.min(cq.x) < 30.0 && cp.x.max(cq.x) > 30.0);
    }

    /// A rod of radius `r` along y = 30 from x = 12 to 48 whose waist at x = 30 narrows
    /// smoothly by `pinch` of its width (a Gaussian over 0.45 widths, as a constricting
    /// mother's), region on the left.
    fn waist(r: f64, pinch: f64) -> Vec<Point> {
        let (x0, x1, y) = (12.0, 48.0, 30.0);
        let half = |x: f64| {
            let u = (x - 0.5 * (x0 + x1)) / (0.45 * 2.0 * r);
            r * (1.0 - pinch * (-u * u).exp())
        };
        let mut pts = Vec::new();
        for k in 0..=72 {
            let x = x0 + (x1 - x0) * k as f64 / 72.0;
            pts.push(Point::new(x, y - half(x)));
        }
        for k in 1..16 {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
            pts.push(Point::new(x1 + r * a.cos(), y + r * a.sin()));
        }
        for k in 0..=72 {
            let x = x1 - (x1 - x0) * k as f64 / 72.0;
            pts.push(Point::new(x, y + half(x)));
        }
        for k in 1..16 {
            let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
            pts.push(Point::new(x0 + r * a.cos(), y + r * a.sin()));
        }
        if signed_area(&pts) < 0.0 {
            pts.reverse();
        }
        pts
    }

    /// The outline of the union of two convex rings overlapping a little along x (the
    /// left one's points right of the overlap's middle dropped, and the right one's left
    /// of it), region on the left.
    fn union_of(a: &[Point], b: &[Point]) -> Vec<Point> {
        let mid = 0.5
            * (a.iter().map(|p| p.x).fold(f64::MIN, f64::max)
                + b.iter().map(|p| p.x).fold(f64::MAX, f64::min));
        let keep = |r: &[Point], left: bool| -> Vec<Point> {
            let n = r.len();
            // Start just after the dropped run so the kept points are one arc.
            let s = (0..n)
                .find(|&k| (r[k].x > mid) == left && (r[(k + 1) % n].x > mid) != left)
                .map_or(0, |k| k + 1);
            (0..n)
                .map(|k| r[(s + k) % n])
                .filter(|p| (p.x > mid) != left)
                .collect()
        };
        let mut ring = keep(a, true);
        ring.extend(keep(b, false));
        if crate::geometry::signed_area(&ring) < 0.0 {
            ring.reverse();
        }
        ring
    }

    /// The ring through `corners` with vertices every half pixel or closer, as evolved
    /// outlines have, region on the left.
    pub(crate) fn densified(corners: &[Point]) -> Vec<Point> {
        let mut ring = Vec::new();
        for (k, &p) in corners.iter().enumerate() {
            let q = corners[(k + 1) % corners.len()];
            let steps = (p.dist(q) / 0.5).ceil().max(1.0) as usize;
            ring.extend((0..steps).map(|s| p + (q - p) * (s as f64 / steps as f64)));
        }
        if signed_area(&ring) < 0.0 {
            ring.reverse();
        }
        ring
    }

    /// A flat 64² image: no line anywhere, so only the outline decides.
    fn flat() -> Field {
        Field::new(64, 64, vec![0.5; 64 * 64])
    }

    fn centre(p: &[Point]) -> Point {
        p.iter().fold(Point::default(), |s, &q| s + q) * (1.0 / p.len() as f64)
    }
}
