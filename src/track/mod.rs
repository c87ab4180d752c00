//! Tracking cells through a movie: each frame is one evolution that starts from the
//! contours of the frame before, and a cell's division is the exact split event of the
//! topology core (seed 003, §2.4: pseudo-local topology tracking, which names both pieces
//! of a ring that pinched in two), found at the frame and place it happens with no
//! threshold — not a heuristic over contours that another tool drew.
//!
//! Frame by frame:
//! - frame 0 starts from the user's shapes (clicks, strokes, a wrap) and, without any,
//!   from automatic seeds; frame t + 1 starts from frame t's contours, each shrunk a
//!   little ([`carry::shrunk`]) so a cell that moved is still under its contour, and
//!   evolves on frame t + 1 through the whole pyramid (coarse to fine, seed 004 §2.2:
//!   the coarse levels carry a contour over a large move before the fine ones settle it);
//!   when the whole field moved (a drifting stage), the contours are first moved with it
//!   ([`drift`]);
//! - the engine is [`crate::evolution::Mode::Track`]: moves go through the core under
//!   [`crate::topology::TopologyPolicy::TRACKING`], so touching cells never merge, no
//!   hole opens, and a cell that pinches splits;
//! - identity is the contour carried across frames; a contour that vanished (or was
//!   dropped as clutter) ends its track; the pieces of a split are its two children,
//!   whose parent is the track that split (a piece under [`MIN_DAUGHTER_SHARE`] of the
//!   largest is a shred, not a daughter, and is dropped); but a cell picked up new in
//!   the frame before that comes apart was cells found as one, and its pieces go on as
//!   tracks of their own;
//! - cells entering or appearing where no contour is are picked up by automatic seeds
//!   that lie wholly outside every cell of the frame, placed only when it is time: every
//!   [`TrackSettings::seed_every`] frames while some object area is left that no cell
//!   covers, or when that area grew by the smallest cell kept since the last look (the
//!   seeds cost more than the rest of a frame, and most frames have no new cell); the
//!   frame then evolves again with the seeds, its cells starting where they settled;
//! - a frame's image model takes what object looks like from under the contours
//!   carried into it when Otsu's split says otherwise
//!   ([`crate::image::IntensityModel::beside_outlined`]): a few cells in a wide field
//!   are too small a share of the pixels for Otsu, which splits the background's own
//!   unevenness instead;
//! - a seed where a cell was the frame before, on ground that cell's contour has left,
//!   is a daughter that came apart from it (a condensing nucleus pinches one daughter
//!   off dimly, and the contour lets go of it instead of splitting): the mother divided,
//!   into the piece under her contour and that seed's cell;
//! - a cell whose outline has a neck with the image brighter along it ([`neck`]) is cut
//!   there: sister rods touching end to end never pinch apart in the image, so no split
//!   event comes, and the cut is their division (children of the mother, as a split's),
//!   dated a frame earlier when the frame before already showed two cells
//!   (`Tracker::date`);
//!   an outline of two rods side by side, which has no neck, is cut along their contact
//!   ([`side`]) in the same way;
//! - a cell picked up new near where a cell of the frame before was, whose contour
//!   vanished or kept a part of her area, is her daughter (`Tracker::adopt`): a nucleus
//!   that divided between two frames shows as two small cells pushed apart;
//! - in transmitted light a new cell far smaller than the frame's typical cell is a
//!   speck (debris, a bubble's centre) and dropped ([`SPECK_SHARE`]);
//! - a new cell (on frame 0 or picked up later) that does not stand out from the band
//!   around it ([`contrast`]) is dropped: seeds on a gently darker corner of uneven
//!   light settle into such blobs; a carried cell is dropped, ending its track, below
//!   the blobs' own bound (a cell that faded, or a blob that grew from a speck); in
//!   phase contrast a new cell must also be wrapped in its halo (a dark band of uneven
//!   light and the blobs on it are not), and a carried cell that more than doubled in a
//!   frame is judged as a new one.
//!
//! - the cells that touch another are divided again on each frame's image
//!   ([`partition`]: a marker watershed from their cores, so the line between two cells
//!   lies on the seam the image shows, not where their fronts first met); on frame 0,
//!   from automatic seeds only, two touching cells with no seam between them, or whose
//!   union is one round convex body, are one cell its seeds cut in two, and are joined
//!   before any track starts; so are two end to end whose union, evolved again as one
//!   outline, has no neck the tracker cuts (`Tracker::join_rods`: a mother seeded on
//!   both sides of her waist).
//!
//! Memory holds the frame being tracked and the image, contours and labels of the one
//! before.

pub mod carry;
pub mod contrast;
pub mod drift;
pub mod lineage;
pub mod neck;
pub mod partition;
mod resume;
pub mod side;

pub use lineage::{Division, Lineage, Track};
pub use resume::{Memory, DELETED_COVER, SAME_CELL};

use crate::evolution::{find_seeds, EvolveError, Evolver, Field, Mode, Params, Shape};
use crate::geometry::{fill_even_odd, signed_area, Point};
use crate::image::{ImageModel, Modality};
use crate::topology::TopologyEvent;
use carry::{
    claim, drop_shreds, free_object, label_raster, labels_of, majority, ordered, regroup,
    ring_origins, settled, shrunk, uncovered, Origin,
};
use neck::Neck;
use std::collections::{HashMap, HashSet};
use std::sync::Arc;

/// Smallest area of a split's smaller piece, as a share of the larger, for the split to
/// be a division (daughters of a division are of one size; a shred torn off by noise
/// is not).
pub const MIN_DAUGHTER_SHARE: f64 = 0.2;

/// In transmitted light (phase contrast, bright field), the smallest area of a split's
/// smaller piece as a share of the larger: rods divide into sisters of one size (the
/// curated masks of a real E. coli movie: 0.70–0.98 in their first frame), while a
/// carried outline that pinches at a paler spot inside a cell tears off a cap of it. On
/// a real dense colony such pinches were most of 500 splits (median share 0.48) where
/// the synthetic rods showed none; fluorescent daughters keep [`MIN_DAUGHTER_SHARE`], as
/// one may show only partly in its first frame (docs/decisions.md, 2026-12-06, seventh
/// session). Raised from 0.4 when the carried cells were first placed apart
/// ([`drift::cell_shifts`]): on that colony the splits of no reference division then had
/// sisters of 0.50 of each other (median), those at a reference division 0.72 or more
/// (10th percentile; docs/decisions.md, 2026-12-08).
pub const SISTER_SHARE: f64 = 0.55;

/// Smallest area of a daughter that came apart from its mother's contour (see
/// [`carry::claim`]), as a share of the larger: it shows only partly in its first
/// frame (the mother condensed and pinched it off dimly), so a quarter of
/// [`MIN_DAUGHTER_SHARE`]; it is a seed of its own, found where the mother was, not a
/// shred of her contour.
pub const MIN_CLAIMED_SHARE: f64 = 0.05;

/// A division cut at a neck ([`neck`]) is dated a frame earlier when the parent's neck
/// the frame before, left uncut, turned inward at its ends by at least this much
/// (radians, both ends together, plus [`EARLIER_LINE`] × its septum share): two caps
/// just meeting, not a waist. On synthetic phase-contrast bacteria, necks a frame
/// before a cut made at the birth turned 0.34–0.81 (10th–90th percentile), those at a
/// birth the cut came a frame after 0.70–1.10 (docs/decisions.md, 2026-12-06).
pub const EARLIER_TURN: f64 = 0.8;

/// The weight of the septum share beside the turn ([`EARLIER_TURN`]).
pub const EARLIER_LINE: f64 = 0.5;

/// ... and only when the neck had stopped narrowing: at most this much narrower (rod
/// widths) than the frame before. A mother's waist narrows by 0.09–0.23 widths a frame
/// to its last; sisters' contact hardly changes at birth.
pub const EARLIER_NARROWING: f64 = 0.05;

/// The narrowing allowed ([`EARLIER_NARROWING`]) grows by this much per radian the neck
/// bends beyond [`EARLIER_TURN`]: the sharper the notch, the surer it is two caps.
pub const EARLIER_NARROWING_PER_TURN: f64 = 0.15;

/// In transmitted light (phase contrast, bright field), a cell born of a division
/// divides again only once its area or its length grew by this factor since its first
/// frame: a rod divides at about twice its birth size, while the carried outline of a
/// rod a frame or two old pinches at paler spots along it. On a real dense colony, most
/// wrong splits were of mothers that had not grown 1.2 times in area; a real E. coli
/// movie's mothers had grown 1.29–1.75 times (10th–90th percentile) and synthetic rods'
/// 1.6–1.9. The length stands in for the area, which a forming septum eats into
/// (docs/decisions.md, 2026-12-07).
pub const MIN_GROWTH: f64 = 1.3;

/// In transmitted light, a carried cell's pieces (or the lobes of its neck) are a
/// division only when each is at least this share of the frame before's typical cell
/// (the median area, [`TYPICAL_FROM`] cells or more); otherwise they are one cell, and
/// a piece that cannot be joined back to the largest is dropped. Daughters are born at
/// about half a mother, 0.6–1.2 of the median cell. In a real dense colony the carried
/// outline of a mottled rod pinched at its paler spots: 117 of the divisions left both
/// children on one reference cell, 70 of them with the smaller under 0.4 of the median,
/// against 26 of 217 that parted reference sisters; trpL's and synthetic colonies'
/// daughters were 0.59 or more (10th percentile; docs/decisions.md, 2026-12-07, tenth
/// session).
pub const MIN_CHILD_OF_TYPICAL: f64 = 0.4;

/// The fewest cells in the frame before for a typical cell ([`MIN_CHILD_OF_TYPICAL`]):
/// with fewer, one odd cell sets the median.
pub const TYPICAL_FROM: usize = 8;

/// A division's children are measured at birth for [`MIN_GROWTH`] only when their
/// mother had been tracked for at least this many frames: a "division" in the first
/// frames after a cell was found is often cells found as one coming apart, the
/// "children" full-grown cells.
pub const BORN_AFTER: usize = 3;

/// In transmitted light (phase contrast, bright field), a new cell (no track before it)
/// smaller than this share of the frame's typical cell (the area-weighted median: the
/// size of the cell a random cell pixel lies in) is a speck, not a cell, unless it
/// touches the frame's edge (a cell coming into view shows a sliver first). Such light
/// shows debris and the dark centres of bubbles in the optics: 35–120 px against cells
/// of 600 px and more on a real E. coli movie, where a cell at birth has half its
/// mother's area or more. Fluorescence shows only what is labelled, and small nuclei
/// are nuclei (sim_plus_01 has real ones of 125–260 px among 2,000 px ones).
pub const SPECK_SHARE: f64 = 0.15;

/// A cell new in a frame is a daughter of a cell of the frame before whose centroid lies
/// within this many of that cell's radii (of a disk of its area): a nucleus that divided
/// between two frames, its daughters pushed apart (real HeLa nuclei: 20–40 px from a
/// mother of radius 20–25), is two small cells where she was, and her contour either
/// vanished or settled on one of them.
pub const ADOPT_REACH: f64 = 2.5;

/// ... when the mother's contour came through on one of them, only if it kept at most
/// this share of her area (she divided; a cell that stays whole keeps its size).
pub const ADOPT_KEPT: f64 = 0.75;

/// ... and only when the two daughters' areas are within this share of each other.
pub const ADOPT_SHARE: f64 = 0.5;

/// Frame 0's touching pieces are evolved again as one (`Tracker::join_rods`) when
/// their union is a rod at most this many times as wide as either piece: end to end,
/// not side by side (nor a rod beside two cells read as one).
pub const JOIN_ROD_WIDE: f64 = 1.3;

/// ... and joined only when that one outline keeps their area within this share (it did
/// not spread over a neighbour or shrink away).
pub const JOIN_ROD_AREA: f64 = 0.8;

/// ... and, where the one outline has no neck measured at all, when the smaller piece
/// has at least this share of the larger's area: the two halves a rod's seeds cut it
/// into, not a rod and a small cell or stub at its end.
pub const JOIN_NO_NECK_SHARE: f64 = 0.5;

/// A frame after the first evolves through the coarse pyramid levels only when the
/// median half-width (2A/P) of the last frame's cells is at least this many pixels (2.35
/// at half resolution). Synthetic rods 6–7.5 px wide, whose outlines' median is 4.2–4.5
/// over a movie, broke up at the coarse level (TRA 0.87, division F1 0.44 on three
/// movies; at full resolution only, 0.96 and 0.70); rods 8–10 px wide (5.2–5.7 over a
/// movie, 4.7 at the least in a frame) keep it, which carries a moved cell: at full
/// resolution only their division F1 fell from 0.91 to 0.88 (docs/decisions.md,
/// 2026-12-05).
pub const COARSE_MIN_HALF_WIDTH: f64 = 4.7;

/// How tracking runs.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TrackSettings {
    /// The evolution's parameters (the mode is set to [`Mode::Track`]).
    pub params: Params,
    /// How far (pixels) a contour moves in before the next frame starts from it.
    pub shrink: f64,
    /// Place automatic seeds on frame 0 (besides any shapes given).
    pub auto_seeds: bool,
    /// Pick up new cells with automatic seeds on every later frame.
    pub new_cells: bool,
    /// Pyramid levels a frame after the first evolves through (frame 0 uses the full
    /// pyramid of its parameters): 1 is the full resolution only, each more level
    /// carries a contour over a move twice as large. Thin cells use one
    /// ([`COARSE_MIN_HALF_WIDTH`]).
    pub levels: usize,
    /// Look for new cells at least every this many frames while some object area is
    /// left that no cell covers, and on any frame where that area grew since the last
    /// look by the smallest cell kept (`params.min_area`).
    pub seed_every: usize,
}

impl TrackSettings {
    /// The defaults around `params`.
    pub fn new(params: Params) -> Self {
        TrackSettings {
            params: Params {
                mode: Mode::Track,
                ..params
            },
            shrink: 2.0,
            auto_seeds: true,
            new_cells: true,
            levels: 2,
            seed_every: 8,
        }
    }
}

/// One tracked cell in one frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TrackedObject {
    /// Its track.
    pub track: u32,
    /// Its outline (region on the left).
    pub ring: Vec<Point>,
    /// Area, square pixels.
    pub area: f64,
    /// Centroid.
    pub centroid: Point,
}

/// What tracking found in one frame.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TrackedFrame {
    /// The frame (0-based).
    pub frame: usize,
    /// The cells, by track label.
    pub objects: Vec<TrackedObject>,
    /// Divisions whose children start in this frame.
    pub divisions: Vec<Division>,
    /// Divisions of the frame before that this frame took back: sisters that came
    /// apart there and are one cell again here (see [`TrackedFrame::revise`]).
    pub undone: Vec<Division>,
    /// Divisions this frame dated a frame earlier (`Tracker::date`): the frame before
    /// is revised to show the children.
    #[serde(default)]
    pub earlier: Vec<Earlier>,
    /// Frames the evolution ran.
    pub evolution_frames: usize,
}

/// A division the next frame dated into this one ([`TrackedFrame::earlier`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Earlier {
    /// The division, its children starting in the frame revised.
    pub division: Division,
    /// The children's cells in that frame (the lobes of the parent's cell).
    pub cells: [TrackedObject; 2],
}

/// Cells covering more than this share of a frame are most likely its background cut
/// into regions (the wrong polarity, or a phase-contrast movie read as generic): 0.92 of
/// a synthetic nuclei movie's frame 0 tracked as dark, 0.96 of a real E. coli colony's
/// frame 15 tracked as generic, against 0.02–0.23 of a dense colony's frames tracked
/// right.
pub const CROWDED_SHARE: f64 = 0.8;

/// What to say of frame `frame` whose cells cover `covered` of it, naming the settings to
/// `check` (the CLI's flags, the app's controls).
pub fn crowded_note(frame: usize, covered: f64, check: &str) -> String {
    format!(
        "frame {frame}'s cells cover {:.0}% of it: the background is being cut into cells; check {check}",
        100.0 * covered
    )
}

impl TrackedFrame {
    /// The share of a `width`×`height` frame its cells cover (their outlines' areas).
    pub fn covered(&self, width: usize, height: usize) -> f64 {
        let area: f64 = self.objects.iter().map(|o| o.area).sum();
        area / (width * height).max(1) as f64
    }

    /// Its cells as a `width`×`height` raster of track labels (0 outside every cell).
    pub fn label_raster(&self, width: usize, height: usize) -> Vec<u32> {
        let rings: Vec<(u32, &[Point])> = self
            .objects
            .iter()
            .map(|o| (o.track, o.ring.as_slice()))
            .collect();
        label_raster(&rings, width, height)
    }

    /// This frame as `next` revised it: the divisions it took back
    /// ([`TrackedFrame::undone`]) are gone, their children's cells their parent's, one
    /// cell seen in two pieces; the divisions it dated here ([`TrackedFrame::earlier`])
    /// replace their parent's cell by the children's.
    pub fn revise(&mut self, next: &TrackedFrame) {
        for d in &next.undone {
            self.divisions.retain(|x| x != d);
            for o in self.objects.iter_mut() {
                if d.children.contains(&o.track) {
                    o.track = d.parent;
                }
            }
        }
        for e in &next.earlier {
            self.objects.retain(|o| o.track != e.division.parent);
            self.objects.extend(e.cells.iter().cloned());
            self.divisions.push(e.division);
        }
        self.objects.sort_by_key(|o| o.track);
    }
}

/// A frame's label raster (`width` pixels a row) as `next` revised it
/// ([`TrackedFrame::revise`]).
pub fn revise_labels(labels: &mut [u32], width: usize, next: &TrackedFrame) {
    for d in &next.undone {
        for l in labels.iter_mut() {
            if d.children.contains(l) {
                *l = d.parent;
            }
        }
    }
    if next.earlier.is_empty() || width == 0 {
        return;
    }
    let height = labels.len() / width;
    for e in &next.earlier {
        let rings: Vec<(u32, &[Point])> = e
            .cells
            .iter()
            .map(|c| (c.track, c.ring.as_slice()))
            .collect();
        let lobes = label_raster(&rings, width, height);
        let parent = e.division.parent;
        for (k, l) in labels.iter_mut().enumerate().filter(|(_, l)| **l == parent) {
            *l = match lobes[k] {
                0 => {
                    // On the chord between the lobes: the nearer child's.
                    let p = Point::new((k % width) as f64 + 0.5, (k / width) as f64 + 0.5);
                    let [a, b] = &e.cells;
                    if p.dist(a.centroid) <= p.dist(b.centroid) {
                        a.track
                    } else {
                        b.track
                    }
                }
                c => c,
            };
        }
    }
}

/// A cell the user deleted as it was the frame before ([`Tracker::with_new_cells`]):
/// its outline, centroid and area, and the area its pieces kept in this frame.
struct Ghost {
    ring: Vec<Point>,
    centroid: Point,
    area: f64,
    kept: f64,
}

/// What one evolution of a frame gave: per shape, its pieces (largest first); the
/// frames it ran; the image model it read (`None` when nothing was evolved).
type Evolved = (Vec<Vec<TrackedObject>>, usize, Option<Arc<ImageModel>>);

/// A frame's shapes' origins, their pieces, and the frames evolved.
type WithNew = (Vec<Origin>, Vec<Vec<TrackedObject>>, usize);

/// Tracks a movie frame by frame ([`Tracker::step`]).
#[derive(Clone, Debug)]
pub struct Tracker {
    settings: TrackSettings,
    init: Vec<Shape>,
    lineage: Lineage,
    /// The cells of the last frame: track and outline.
    live: Vec<(u32, Vec<Point>)>,
    /// Their label raster.
    labels: Vec<u32>,
    frame: usize,
    /// The frame by which the automatic seeds run again at the latest.
    next_seeding: usize,
    /// Object pixels no cell covered after the last frame that placed seeds, measured
    /// again on the first frame after it ([`Tracker::with_new_cells`]).
    residual: usize,
    /// Whether `residual` is still the look's own measure, not yet the carried cells'.
    look_residual: bool,
    /// The last frame's image on its quantiles ([`drift::on_quantiles`]), to tell how
    /// far the field moved.
    previous: Option<Field>,
    /// The last frame's divisions whose daughters were born apart ([`partition::meet`]):
    /// taken back when the two are one cell again in this frame ([`partition::rejoined`]).
    apart: Vec<Division>,
    /// The necks of the last frame's cells that were not cut, by track, each with the
    /// neck's [`Neck::narrow`] the frame before ([`Tracker::date`]).
    necks: HashMap<u32, (Neck, Option<f64>)>,
    /// The size each track born of a division had in its first frame ([`MIN_GROWTH`]);
    /// a tracker resumed after a correction knows those of the cells it left as they
    /// were ([`Memory::corrected`]).
    born: HashMap<u32, Size>,
    /// Cells the user joined others into ([`Memory::corrected`]): they hold together
    /// until grown, as a cell just born in transmitted light does, in any light.
    joined: HashSet<u32>,
    /// The outlines of cells the user deleted ([`Memory::corrected`]), evolved every
    /// frame as the cells are: no new cell is taken where they lie.
    unwanted: Vec<Vec<Point>>,
    /// The run a correction replaced, whose numbers the tracks begun after it keep
    /// ([`Tracker::keeping_numbers`]).
    numbers: Option<resume::Numbers>,
}

impl Tracker {
    /// A tracker starting frame 0 from `init` (and automatic seeds, if the settings say so).
    pub fn new(settings: TrackSettings, init: Vec<Shape>) -> Self {
        Tracker {
            settings,
            init,
            lineage: Lineage::default(),
            live: Vec::new(),
            labels: Vec::new(),
            frame: 0,
            next_seeding: 0,
            residual: 0,
            look_residual: true,
            previous: None,
            apart: Vec::new(),
            necks: HashMap::new(),
            born: HashMap::new(),
            joined: HashSet::new(),
            unwanted: Vec::new(),
            numbers: None,
        }
    }

    /// The image of the frame tracked last, when the tracker did not see it itself (a
    /// tracker [`Tracker::resume`]d after a correction): the next frame then follows
    /// the field's drift from it as a tracker that ran on would.
    pub fn set_previous(&mut self, image: Field) {
        self.previous = Some(drift::on_quantiles(&image));
    }

    /// The frame the next [`Tracker::step`] tracks (0-based).
    pub fn next_frame(&self) -> usize {
        self.frame
    }

    /// The tracks so far.
    pub fn lineage(&self) -> &Lineage {
        &self.lineage
    }

    /// The label raster of the last frame tracked (track labels, 0 outside).
    pub fn labels(&self) -> &[u32] {
        &self.labels
    }

    /// Tracks the next frame.
    pub fn step(&mut self, image: &Field) -> Result<TrackedFrame, EvolveError> {
        let t = self.frame;
        let (w, h) = (image.width, image.height);
        if self.labels.len() != w * h {
            self.labels = vec![0; w * h];
        }
        // How far the field moved since the last frame (a drifting stage), and each cell
        // against it: rods in a colony push each other about every frame, so in
        // transmitted light each cell's own shift is searched every frame
        // ([`drift::CELL_FROM`]).
        let mut shift = Point::new(0.0, 0.0);
        let scaled = drift::on_quantiles(image);
        if let Some(before) = self.previous.take() {
            let s = drift::field_shift(&before, &scaled, &self.labels);
            let own = if self.transmitted() || s.0.abs().max(s.1.abs()) >= drift::CELL_FROM {
                drift::cell_shifts(&before, &scaled, &self.labels, s)
            } else {
                HashMap::new()
            };
            if s != (0, 0) || !own.is_empty() {
                self.follow(s, &own, w, h);
                shift = Point::new(s.0 as f64, s.1 as f64);
            }
        }
        let mut shapes: Vec<Shape> = Vec::new();
        let mut origins: Vec<Origin> = Vec::new();
        for (track, ring) in &self.live {
            shapes.push(shrunk(ring, self.settings.shrink));
            origins.push(Origin::Carried(*track));
        }
        let automatic = t == 0 && self.init.is_empty();
        if t == 0 {
            for s in std::mem::take(&mut self.init) {
                shapes.push(s);
                origins.push(Origin::New);
            }
            if self.settings.auto_seeds || shapes.is_empty() {
                let p = &self.settings.params;
                let seeds = ordered(find_seeds(image, p.polarity, p.modality));
                origins.extend(seeds.iter().map(|_| Origin::New));
                shapes.extend(seeds);
            }
        }
        // Where the user deleted cells evolves with the cells, as cells would (it follows
        // the cell it was, divides with it, keeps its neighbours off it), then is taken
        // out: no seed is placed there ([`Tracker::with_new_cells`]), nothing is output.
        let cells = shapes.len();
        for ring in &self.unwanted {
            shapes.push(shrunk(ring, self.settings.shrink));
        }
        let mut evolved = self.evolve(image, &shapes)?;
        let before = self.unwanted.clone();
        let mut ghosts_before = Vec::new();
        if let Some(ghosts) = self.take_ghosts(&mut evolved.0, cells) {
            for (ring, pieces) in before.iter().zip(&ghosts) {
                let (a2, c) = crate::geometry::area2_centroid(ring);
                let kept: f64 = pieces.iter().map(|o| o.area).sum();
                ghosts_before.push(Ghost {
                    ring: ring.clone(),
                    centroid: c,
                    area: 0.5 * a2.abs(),
                    kept,
                });
            }
        }
        let model = evolved.2.clone();
        let (origins, mut pieces, evolution_frames) = if t > 0 && self.settings.new_cells {
            self.with_new_cells(image, origins, evolved, &ghosts_before)?
        } else {
            if t == 0 {
                self.residual = self.leftover(&evolved, w, h);
                self.next_seeding = self.settings.seed_every.max(1);
            }
            (origins, evolved.0, evolved.1)
        };
        let mut frame = TrackedFrame {
            frame: t,
            objects: Vec::new(),
            divisions: Vec::new(),
            undone: Vec::new(),
            earlier: Vec::new(),
            evolution_frames,
        };
        let joined = match model.as_deref() {
            Some(m) if automatic => {
                let mut joined = partition::join_pieces(&mut pieces, m, partition::Join::Any);
                joined.extend(self.join_rods(image, &mut pieces, m));
                joined
            }
            // New cells: the pieces that seeds on the ground no contour covers cut one
            // rod into are joined, as on frame 0.
            Some(m) if t > 0 => join_new(&origins, &mut pieces, m),
            _ => Vec::new(),
        };
        let groups = claim(&origins, pieces);
        let mut groups = self.without_faint(groups, image);
        // The user's own shapes on frame 0 are never specks.
        if self.transmitted() && (t > 0 || automatic) {
            groups = without_specks(groups, w, h);
        }
        if t > 0 {
            self.adopt(&mut groups, w, h);
        }
        let rods = side::rod_width(
            groups
                .iter()
                .flat_map(|(_, g)| g.iter().map(|o| o.ring.as_slice())),
        );
        // Cells found alongside another under one outline ([`side`]): tracks of their own.
        let mut alongside: Vec<TrackedObject> = Vec::new();
        // The necks measured in this frame, and the tracks whose one outline was cut at a
        // neck into two ([`Tracker::date`]).
        let mut necks: HashMap<u32, (Neck, Option<f64>)> = HashMap::new();
        let mut neck_cut: Vec<u32> = Vec::new();
        // The frame before's typical cell, in transmitted light ([`MIN_CHILD_OF_TYPICAL`]).
        let typical = self.typical_area().filter(|_| self.transmitted());
        for (owner, mut group) in groups {
            // A rod that has not grown since its birth does not divide again: its pieces
            // are one cell, and no neck of it is cut. Nor does a carried rod come apart
            // into a piece far smaller than the colony's cells ([`MIN_CHILD_OF_TYPICAL`]).
            let typical = typical.filter(|_| owner.is_some());
            let small = group.len() > 1 && under(typical, group.iter().map(|o| o.area));
            let unripe = small || owner.is_some_and(|k| self.unripe(k, &group));
            if unripe && group.len() > 1 {
                if let Some(m) = model.as_deref() {
                    group = as_one(group, m);
                }
            }
            if small && group.len() > 1 {
                // The pieces that could not be joined again are no cell of their own.
                group.sort_by(|x, y| y.area.total_cmp(&x.area));
                group.truncate(1);
            }
            let single = group.len() == 1;
            // Sisters touching end to end never pinch apart in the image: cut at necks.
            let mut cut: Vec<TrackedObject> = Vec::with_capacity(group.len());
            for o in group {
                // Joined cells (frame 0's, new ones') were judged one cell
                // ([`partition::join_pieces`]).
                if joined.contains(&o.ring) {
                    cut.push(o);
                    continue;
                }
                let neck = match neck::cut_or_measure(&o.ring, image) {
                    Ok(_) if unripe => None,
                    Ok(rings) if under(typical, rings.iter().map(|r| signed_area(r).abs())) => None,
                    Ok(rings) => {
                        if let (Some(track), true, 2) = (owner, single, rings.len()) {
                            neck_cut.push(track);
                        }
                        cut.extend(rings.into_iter().map(object));
                        continue;
                    }
                    Err(neck) => neck,
                };
                if let Some((a, b)) = rods.and_then(|w| side::side_cut(&o.ring, w, image)) {
                    // Rods side by side have no neck: two cells read as one, the larger
                    // going on as the outline's cell ([`side`]).
                    let (a, b) = (object(a), object(b));
                    let (keep, other) = if a.area >= b.area { (a, b) } else { (b, a) };
                    cut.push(keep);
                    alongside.push(other);
                    continue;
                }
                if let (Some(track), Some(neck), true) = (owner, neck, single) {
                    let before = self.necks.get(&track).map(|(k, _)| k.narrow);
                    necks.insert(track, (neck, before));
                }
                cut.push(o);
            }
            cut.sort_by(|x, y| y.area.total_cmp(&x.area));
            self.settle(owner, cut, &mut frame);
        }
        self.settle(None, alongside, &mut frame);
        frame.objects.sort_by_key(|o| o.track);
        let raster = |objects: &[TrackedObject]| {
            let rings: Vec<(u32, &[Point])> = objects
                .iter()
                .map(|o| (o.track, o.ring.as_slice()))
                .collect();
            label_raster(&rings, w, h)
        };
        self.labels = raster(&frame.objects);
        if let Some(m) = model.as_deref() {
            if partition::divide_again(&mut frame.objects, &self.labels, m) {
                self.labels = raster(&frame.objects);
            }
            if self.rejoin(&mut frame, m) {
                self.labels = raster(&frame.objects);
            }
        }
        self.date(&mut frame, &neck_cut, shift);
        // The neck is of the evolved outline, before the line between touching cells
        // moved onto the image's seam ([`partition::divide_again`]): that outline follows
        // pixel edges, whose steps read as turns. The cell it revises keeps the outline's
        // lobes; its pixels in the frame's labels are parted by them
        // ([`revise_labels`]).
        self.necks = necks;
        self.apart = frame
            .divisions
            .iter()
            .filter(|d| !partition::meet(&self.labels, w, h, d.children))
            .copied()
            .collect();
        self.live = frame
            .objects
            .iter()
            .map(|o| (o.track, o.ring.clone()))
            .collect();
        let live: HashSet<u32> = self.live.iter().map(|(k, _)| *k).collect();
        self.born.retain(|k, _| live.contains(k));
        self.previous = Some(scaled);
        self.frame += 1;
        Ok(frame)
    }

    /// Moves the last frame's cells (outlines and labels) by the field's shift `s`, a
    /// cell in `own` by its own shift beyond it too ([`drift::cell_shifts`]). An outline
    /// carried partly out of the `w`×`h` frame is scaled about its centre until it fits
    /// (a similarity keeps it simple; the evolution then fills what shows of the cell);
    /// one whose centre left the frame ends its track, as a cell that left it.
    fn follow(&mut self, s: (i32, i32), own: &HashMap<u32, (i32, i32)>, w: usize, h: usize) {
        let shift = |track: u32| {
            let e = own.get(&track).copied().unwrap_or((0, 0));
            (s.0 + e.0, s.1 + e.1)
        };
        let (lo, hi) = (
            Point::new(0.5, 0.5),
            Point::new(w as f64 - 0.5, h as f64 - 0.5),
        );
        let inside = |p: Point| (lo.x..=hi.x).contains(&p.x) && (lo.y..=hi.y).contains(&p.y);
        self.live.retain_mut(|(track, ring)| {
            let (dx, dy) = shift(*track);
            let d = Point::new(dx as f64, dy as f64);
            let c = crate::geometry::area2_centroid(ring).1 + d;
            if !inside(c) {
                return false;
            }
            let mut f: f64 = 1.0;
            for p in ring.iter_mut() {
                *p = *p + d;
                for (v, c, lo, hi) in [(p.x, c.x, lo.x, hi.x), (p.y, c.y, lo.y, hi.y)] {
                    if v < lo {
                        f = f.min((c - lo) / (c - v));
                    } else if v > hi {
                        f = f.min((hi - c) / (v - c));
                    }
                }
            }
            if f < 1.0 {
                ring.iter_mut().for_each(|p| *p = c + (*p - c) * f);
            }
            true
        });
        let mut moved = vec![0u32; w * h];
        for (i, &l) in self.labels.iter().enumerate() {
            let (dx, dy) = shift(l);
            let (x, y) = ((i % w) as i32 + dx, (i / w) as i32 + dy);
            if l != 0 && (0..w as i32).contains(&x) && (0..h as i32).contains(&y) {
                moved[y as usize * w + x as usize] = l;
            }
        }
        self.labels = moved;
        let d = Point::new(s.0 as f64, s.1 as f64);
        self.unwanted.retain_mut(|ring| {
            ring.iter_mut().for_each(|p| *p = *p + d);
            inside(crate::geometry::area2_centroid(ring).1)
        });
    }

    /// A frame's evolution `evolved` from the cells before (`origins`), run again with
    /// automatic seeds where no cell is when it is time to look for new cells: every
    /// [`TrackSettings::seed_every`] frames if any object area is left that no cell
    /// covers, when that area grew by the smallest cell kept since the first frame after
    /// the last look, or when no cell is left. Returns the origins, the pieces per origin
    /// and the frames evolved.
    ///
    /// A seed mostly where a cell the user deleted was the frame before
    /// (`ghosts_before`), or near one whose contour vanished or shrank as a dividing
    /// cell's does ([`ADOPT_REACH`], [`ADOPT_KEPT`], as [`Tracker::adopt`] takes
    /// daughters pushed apart), is the deleted cell's own and evolves as deleted too.
    fn with_new_cells(
        &mut self,
        image: &Field,
        origins: Vec<Origin>,
        evolved: Evolved,
        ghosts_before: &[Ghost],
    ) -> Result<WithNew, EvolveError> {
        let (t, w, h) = (self.frame, image.width, image.height);
        let found = self.covered(&evolved.0, w, h);
        let free = evolved.2.as_deref().map(|m| free_object(m, &found));
        let grown =
            free.is_none_or(|f| f as f64 > self.residual as f64 + self.settings.params.min_area);
        // The periodic look only where some object is left uncovered: where none is, a
        // seed could only evolve on background, and the look costs more than the frame.
        let due = t >= self.next_seeding && free != Some(0);
        if !(grown || due) {
            // A look's evolution leaves another uncovered area than the carried cells'
            // (a dense real colony: 19,000 px against 7,000 the frame after), so growth
            // is counted from the first frame after the look: cells whose contours went
            // elsewhere were otherwise found again only at the next periodic look.
            if let (Some(f), true) = (free, self.look_residual) {
                self.residual = f;
                self.look_residual = false;
            }
            return Ok((origins, evolved.0, evolved.1));
        }
        self.next_seeding = t + self.settings.seed_every.max(1);
        self.look_residual = true;
        let mut seeds = self.new_seeds(image, &found);
        let mut ghost_seeds = Vec::new();
        if !ghosts_before.is_empty() {
            let rings: Vec<(u32, &[Point])> = (ghosts_before.iter())
                .map(|g| (1, g.ring.as_slice()))
                .collect();
            let before = label_raster(&rings, w, h);
            let ghost = |s: &Shape| {
                majority(s, &before, w, h) == 1
                    || ghosts_before.iter().any(|g| {
                        let reach = ADOPT_REACH * (g.area / std::f64::consts::PI).sqrt();
                        g.kept <= ADOPT_KEPT * g.area && s.center().dist(g.centroid) <= reach
                    })
            };
            (ghost_seeds, seeds) = seeds.into_iter().partition(|(s, _)| ghost(s));
        }
        if seeds.is_empty() && ghost_seeds.is_empty() {
            self.residual = free.unwrap_or(0);
            return Ok((origins, evolved.0, evolved.1));
        }
        // Again with the seeds, the cells starting where they settled, so a seed on
        // ground a cell's contour left is not inside that cell's start.
        let (mut shapes, mut all) = settled(&origins, &evolved.0);
        for (s, o) in seeds {
            shapes.push(s);
            all.push(o);
        }
        // Where the user deleted cells evolves again with them too: without it, a
        // neighbour's contour grew over a deleted nucleus and took it as a daughter.
        let cells = shapes.len();
        shapes.extend(self.unwanted.iter().map(|r| Shape::Polygon(r.clone())));
        shapes.extend(ghost_seeds.into_iter().map(|(s, _)| s));
        let mut again = self.evolve(image, &shapes)?;
        self.take_ghosts(&mut again.0, cells);
        self.residual = self.leftover(&again, w, h);
        let (all, pieces) = regroup(all, again.0, self.shred_share());
        Ok((all, pieces, evolved.1 + again.1))
    }

    /// The pieces of the shapes from `cells` on (where the user deleted cells), taken out
    /// of `pieces`; their outlines are where the deleted cells now lie. None when there
    /// were none.
    fn take_ghosts(
        &mut self,
        pieces: &mut Vec<Vec<TrackedObject>>,
        cells: usize,
    ) -> Option<Vec<Vec<TrackedObject>>> {
        if pieces.len() <= cells {
            return None;
        }
        let ghosts = pieces.split_off(cells);
        self.unwanted = ghosts.iter().flatten().map(|o| o.ring.clone()).collect();
        Some(ghosts)
    }

    /// Object pixels an evolution left uncovered ([`free_object`]), where the user
    /// deleted cells counting as covered.
    fn leftover(&self, evolved: &Evolved, w: usize, h: usize) -> usize {
        (evolved.2.as_deref()).map_or(0, |m| free_object(m, &self.covered(&evolved.0, w, h)))
    }

    /// The label raster of `pieces` on a `w`×`h` frame, where the user deleted cells
    /// counting as covered: no seed is taken there, and its area calls for no look.
    fn covered(&self, pieces: &[Vec<TrackedObject>], w: usize, h: usize) -> Vec<u32> {
        let mut found = labels_of(pieces, w, h);
        for ring in &self.unwanted {
            fill_even_odd(std::slice::from_ref(ring), w, h, |i| {
                if found[i] == 0 {
                    found[i] = u32::MAX;
                }
            });
        }
        found
    }

    /// The frame's automatic seeds that no cell of this frame (`found`) covers, each with
    /// where it came from: a daughter of the track whose cell covered most of it the
    /// frame before, else new. New tracks are numbered left to right.
    fn new_seeds(&self, image: &Field, found: &[u32]) -> Vec<(Shape, Origin)> {
        let (w, h) = (image.width, image.height);
        let p = &self.settings.params;
        ordered(find_seeds(image, p.polarity, p.modality))
            .into_iter()
            .filter(|s| uncovered(s, found, w, h))
            .map(|s| {
                let o = match majority(&s, &self.labels, w, h) {
                    0 => Origin::New,
                    x => Origin::Daughter(x),
                };
                (s, o)
            })
            .collect()
    }

    /// Evolves from `shapes`; returns, per shape, the pieces it ended as (largest first)
    /// and the frames the evolution ran.
    fn evolve(&self, image: &Field, shapes: &[Shape]) -> Result<Evolved, EvolveError> {
        let mut pieces: Vec<Vec<TrackedObject>> = vec![Vec::new(); shapes.len()];
        if shapes.is_empty() {
            return Ok((pieces, 0, None));
        }
        let mut params = self.settings.params.clone();
        if self.frame > 0 {
            // The carried contours say what a cell looks like in this frame.
            params.outline_hints = true;
            let side = image.width.min(image.height);
            // Levels the frame is too small for are not made (the pyramid's least side).
            params.coarsest_side = (side >> self.levels().saturating_sub(1)).max(8);
        }
        let mut ev = match Evolver::new(image, shapes, params) {
            Ok(ev) => ev,
            Err(EvolveError::EmptyInit) => return Ok((pieces, 0, None)),
            Err(e) => return Err(e),
        };
        let mut origin: std::collections::HashMap<u32, usize> =
            ring_origins(ev.contours(), shapes).into_iter().collect();
        ev.run();
        ev.filter_clutter();
        for e in ev.events() {
            if let TopologyEvent::Split { from, new } = e.event {
                if let Some(&i) = origin.get(&from.0) {
                    origin.insert(new.0, i);
                }
            }
        }
        let set = ev.contours();
        for r in crate::evolution::regions(set) {
            if let Some(&i) = origin.get(&r.id.0) {
                pieces[i].push(TrackedObject {
                    track: 0,
                    ring: set.ring_points(r.id),
                    area: r.area,
                    centroid: r.centroid,
                });
            }
        }
        let share = self.shred_share();
        pieces.iter_mut().for_each(|g| drop_shreds(g, share));
        Ok((pieces, ev.frames(), Some(ev.image().clone())))
    }

    /// The least share of a split's smaller piece that makes it a daughter, not a shred
    /// ([`SISTER_SHARE`] in transmitted light, else [`MIN_DAUGHTER_SHARE`]).
    fn shred_share(&self) -> f64 {
        if self.transmitted() {
            SISTER_SHARE
        } else {
            MIN_DAUGHTER_SHARE
        }
    }

    /// Whether the movie is in transmitted light (phase contrast, bright field).
    fn transmitted(&self) -> bool {
        matches!(
            self.settings.params.modality,
            Modality::PhaseContrast | Modality::Brightfield
        )
    }

    /// The pyramid levels the next frame evolves through: the settings', or the full
    /// resolution only for thin cells ([`COARSE_MIN_HALF_WIDTH`]).
    fn levels(&self) -> usize {
        if !self.live.is_empty() && half_width(&self.live) < COARSE_MIN_HALF_WIDTH {
            1
        } else {
            self.settings.levels.max(1)
        }
    }

    /// `groups` without the cells that do not stand out from their surroundings
    /// ([`contrast`]): new cells below [`contrast::MIN_SEPARATION`], carried ones below
    /// [`contrast::MIN_CARRIED_SEPARATION`], and in phase contrast new cells without a
    /// halo of [`contrast::MIN_HALO`] ([`contrast::standing_out`]); a carried cell more
    /// than [`contrast::SPREAD`] times its last area is judged as a new one.
    fn without_faint(
        &self,
        groups: Vec<(Option<u32>, Vec<TrackedObject>)>,
        image: &Field,
    ) -> Vec<(Option<u32>, Vec<TrackedObject>)> {
        let polarity = self.settings.params.polarity;
        let phase = self.settings.params.modality == Modality::PhaseContrast;
        let before: HashMap<u32, f64> = self
            .live
            .iter()
            .map(|(k, ring)| (*k, signed_area(ring).abs()))
            .collect();
        let objects: Vec<(&[Point], contrast::Need)> = groups
            .iter()
            .flat_map(|(owner, g)| {
                let area: f64 = g.iter().map(|o| o.area).sum();
                // A carried cell that spread far over its last outline is judged as new.
                let spread = owner
                    .and_then(|k| before.get(&k))
                    .is_some_and(|&a| area > contrast::SPREAD * a);
                let need = match owner {
                    Some(_) if !spread => contrast::Need {
                        separation: contrast::MIN_CARRIED_SEPARATION,
                        halo: None,
                    },
                    _ => contrast::Need {
                        separation: contrast::MIN_SEPARATION,
                        halo: phase.then_some(contrast::MIN_HALO),
                    },
                };
                g.iter().map(move |o| (o.ring.as_slice(), need))
            })
            .collect();
        let keep = contrast::standing_out(&objects, image, polarity);
        let mut k = 0usize;
        groups
            .into_iter()
            .map(|(owner, group)| {
                let group = group
                    .into_iter()
                    .filter(|_| {
                        k += 1;
                        keep[k - 1]
                    })
                    .collect();
                (owner, group)
            })
            .collect()
    }

    /// Whether track `track`, in pieces at frame `t`, is cells found as one rather than a
    /// cell that divided: it was picked up new (after frame 0, from no division) in the
    /// frame before. A cell divides a cell cycle after it is born, and one that came into
    /// view is seldom caught in the very frame before it divides, while two cells that
    /// appear touching are first taken for one (sim_plus_01, frame 53: docs/decisions.md,
    /// 2026-12-05).
    fn found_as_one(&self, track: u32, t: usize) -> bool {
        self.lineage
            .get(track)
            .is_some_and(|k| k.parent == 0 && k.first > 0 && k.first + 1 == t)
    }

    /// Whether the children `parent` has at frame `birth` are measured at birth
    /// ([`BORN_AFTER`]): a mother seen a frame or two may have been cells found as one.
    fn measured_at_birth(&self, parent: u32, birth: usize) -> bool {
        self.lineage
            .get(parent)
            .is_some_and(|p| p.first + BORN_AFTER <= birth)
    }

    /// The median area of the frame before's cells, when there were at least
    /// [`TYPICAL_FROM`] of them.
    fn typical_area(&self) -> Option<f64> {
        let mut areas: Vec<f64> = self
            .live
            .iter()
            .map(|(_, r)| signed_area(r).abs())
            .collect();
        if areas.len() < TYPICAL_FROM {
            return None;
        }
        crate::image::hints::median(&mut areas)
    }

    /// Whether `track`, seen as the cells of `group` in this frame, is a rod born of a
    /// division that has not yet grown by [`MIN_GROWTH`] (transmitted light only), or a
    /// cell the user joined others into that has not (in any light).
    fn unripe(&self, track: u32, group: &[TrackedObject]) -> bool {
        (self.transmitted() || self.joined.contains(&track))
            && self.born.get(&track).is_some_and(|b| {
                let now = Size::of(group);
                now.area < MIN_GROWTH * b.area && now.length < MIN_GROWTH * b.length
            })
    }

    /// Frame 0's touching pieces that are one rod its seeds cut in two, joined; returns
    /// the joined outlines. Each pair of touching pieces (each piece in one pair, the
    /// longest contacts first) whose union is a rod no wider than [`JOIN_ROD_WIDE`] of
    /// either piece is evolved again on frame 0 as one outline, with every other piece
    /// beside it; when what comes out is one outline
    /// whose neck is not cut ([`neck::cut_or_measure`]) and bends gently
    /// ([`neck::SMOOTH_TURN`]), the pair is that one cell (two touching disks, meeting
    /// at a sharp notch, stay two). So is one with no neck at all when its pieces are
    /// of one size ([`JOIN_NO_NECK_SHARE`], a rod's two halves) and it keeps off the
    /// frame's edge (where a neck is not measured). A later
    /// frame asks the same of every cell: a mother a frame or two before her division,
    /// her waist seeded on both sides, was two tracks from frame 0 and her division was
    /// never seen.
    fn join_rods(
        &self,
        image: &Field,
        pieces: &mut [Vec<TrackedObject>],
        model: &ImageModel,
    ) -> Vec<Vec<Point>> {
        let (w, h) = (image.width, image.height);
        let flat: Vec<&TrackedObject> = pieces.iter().flatten().collect();
        let labels = labels_of(pieces, w, h);
        // A piece's width: across its length when it is a rod; a stub's (half a
        // mother cut across) its longer extent, which is the rod's width.
        let width = |p: &[Point]| {
            let (aspect, across, _) = neck::elongation(p);
            if aspect >= neck::MIN_LOBE_ASPECT {
                across
            } else {
                across * aspect
            }
        };
        // Judged on the pieces before pairing: a half that touches a neighbour along a
        // longer edge than its other half still pairs with its other half.
        let ring = |l: u32| flat[l as usize - 1].ring.as_slice();
        let ring_area = |l: u32| flat[l as usize - 1].area;
        let pairs = partition::touching_pairs(&labels, model, |a, b| {
            let (aspect, across, _) = neck::elongation_of(&[ring(a), ring(b)]);
            aspect >= neck::MIN_LOBE_ASPECT
                && across <= JOIN_ROD_WIDE * width(ring(a)).min(width(ring(b)))
        });
        if pairs.is_empty() {
            return Vec::new();
        }
        let paired: HashSet<u32> = pairs.iter().flat_map(|((a, b), _)| [*a, *b]).collect();
        let mut shapes: Vec<Shape> = pairs
            .iter()
            .map(|(_, r)| Shape::Polygon(r.clone()))
            .collect();
        shapes.extend(
            (1..=flat.len() as u32)
                .filter(|l| !paired.contains(l))
                .map(|l| Shape::Polygon(ring(l).to_vec())),
        );
        // Joining refines frame 0; an evolution that fails leaves the pieces as they are.
        let Ok((evolved, _, _)) = self.evolve(image, &shapes) else {
            return Vec::new();
        };
        // Per pair joined, its first piece's new outline; its second piece goes.
        let mut one: HashMap<u32, Vec<Point>> = HashMap::new();
        let mut gone: HashSet<u32> = HashSet::new();
        for (((a, b), union), got) in pairs.iter().zip(&evolved) {
            let [r] = got.as_slice() else {
                continue;
            };
            let area = crate::geometry::signed_area(union);
            if (r.area - area).abs() > (1.0 - JOIN_ROD_AREA) * area {
                continue;
            }
            // One rod: its neck is measured, not cut, and bends gently (a waist, or a
            // chord across a straight rod); two touching disks meet at a sharp notch:
            // two nuclei, whatever the neck rule says of round lobes. No neck measured
            // is a rod too when the pieces were its two halves and it is off the edge:
            // its shortest chord ran near a cap and left a lobe under a daughter's
            // share. A small piece at a rod's end, or a pair cut by the frame's edge,
            // has no neck measured either, and is not judged so.
            let one_rod = match neck::cut_or_measure(&r.ring, image) {
                Err(Some(k)) => k.turn < neck::SMOOTH_TURN,
                Err(None) => {
                    let (sa, sb) = (ring_area(*a), ring_area(*b));
                    sa.min(sb) >= JOIN_NO_NECK_SHARE * sa.max(sb)
                        && r.ring.iter().all(|&p| neck::off_edge(p, image))
                }
                Ok(_) => false,
            };
            if one_rod {
                one.insert(*a, r.ring.clone());
                gone.insert(*b);
            }
        }
        let mut k = 0u32;
        let mut joined = Vec::new();
        for g in pieces.iter_mut() {
            g.retain_mut(|o| {
                k += 1;
                if let Some(ring) = one.remove(&k) {
                    joined.push(ring.clone());
                    *o = object(ring);
                }
                !gone.contains(&k)
            });
            g.sort_by(|a, b| b.area.total_cmp(&a.area));
        }
        joined
    }

    /// Dates the divisions of `frame` cut at a neck (the parents `cut`) a frame earlier
    /// when the parent's outline in the frame before was already two cells: its neck,
    /// left uncut there, parted it into rods, bent at its ends or showed a line
    /// ([`EARLIER_TURN`]) and had stopped narrowing ([`EARLIER_NARROWING`],
    /// [`EARLIER_NARROWING_PER_TURN`]). One frame's outline cannot tell a mother's last
    /// waist from two caps just meeting (their necks are equally wide); the cut that
    /// follows says a division came, and the frames around it say which frame it came
    /// in. The frame before is revised by [`TrackedFrame::revise`]: the parent's cell
    /// there becomes the two lobes of its neck, each the child it is nearer to (the
    /// lobes moved by `shift`, the field's drift since). A parent seen for one frame
    /// only keeps its division where it is. A tracker resumed after a correction has no
    /// necks of the corrected frame ([`Memory::corrected`]), and never revises it.
    fn date(&mut self, frame: &mut TrackedFrame, cut: &[u32], shift: Point) {
        let t = frame.frame;
        for d in frame.divisions.clone() {
            if !cut.contains(&d.parent) {
                continue;
            }
            let Some((neck, before)) = self.necks.get(&d.parent) else {
                continue;
            };
            let bends = neck.turn + EARLIER_LINE * neck.line;
            let narrowing = EARLIER_NARROWING + EARLIER_NARROWING_PER_TURN * (bends - EARLIER_TURN);
            let two = neck.rods()
                && bends >= EARLIER_TURN
                && before.is_none_or(|n| n - neck.narrow <= narrowing);
            // A cell picked up new two frames ago would be cells found as one in the
            // frame before ([`Tracker::found_as_one`]), not a division.
            let seen = self.lineage.get(d.parent).is_some_and(|p| p.first + 2 <= t)
                && !self.found_as_one(d.parent, t - 1);
            if !(two && seen) {
                continue;
            }
            let child = |l: u32| frame.objects.iter().find(|o| o.track == l);
            let (Some(c0), Some(c1)) = (child(d.children[0]), child(d.children[1])) else {
                continue;
            };
            let (a, b) = (object(neck.lobes.0.clone()), object(neck.lobes.1.clone()));
            // The lobes lie where the frame before had them: moved with the field.
            let far = |x: &TrackedObject, c: &TrackedObject| (x.centroid + shift).dist(c.centroid);
            let (a, b) = if far(&a, c0) + far(&b, c1) <= far(&a, c1) + far(&b, c0) {
                (a, b)
            } else {
                (b, a)
            };
            // The lobes are the children a frame younger: each near its own.
            if far(&a, c0).max(far(&b, c1)) > neck.width {
                continue;
            }
            if self.measured_at_birth(d.parent, t - 1) {
                self.born.insert(d.children[0], Size::of([&a]));
                self.born.insert(d.children[1], Size::of([&b]));
            } else {
                self.born.remove(&d.children[0]);
                self.born.remove(&d.children[1]);
            }
            let earlier = Division { frame: t - 1, ..d };
            self.lineage.redate(&earlier);
            frame.divisions.retain(|x| *x != d);
            frame.earlier.push(Earlier {
                division: earlier,
                cells: [
                    TrackedObject {
                        track: d.children[0],
                        ..a
                    },
                    TrackedObject {
                        track: d.children[1],
                        ..b
                    },
                ],
            });
        }
    }

    /// Takes back the last frame's divisions whose daughters came apart there and are
    /// one cell again in `frame` ([`partition::rejoined`]): a nucleus that parts for a
    /// frame, its two lobes a gap apart, and closes again the next was never two cells
    /// (sim_plus_01, frame 38: `docs/decisions.md`, 2026-12-05). The parent goes on as
    /// the union of the two; the frame before is revised by
    /// [`TrackedFrame::revise`]. Whether any was.
    fn rejoin(&mut self, frame: &mut TrackedFrame, model: &ImageModel) -> bool {
        let mut any = false;
        for d in std::mem::take(&mut self.apart) {
            let [a, b] = d.children;
            let here = |l: u32| frame.objects.iter().filter(|o| o.track == l).count() == 1;
            if !(here(a) && here(b)) {
                continue;
            }
            let Some(ring) = partition::rejoined(&self.labels, a, b, model) else {
                continue;
            };
            frame.objects.retain(|o| o.track != a && o.track != b);
            frame.objects.push(TrackedObject {
                track: d.parent,
                ..object(ring)
            });
            self.lineage.undo(&d, frame.frame);
            frame.undone.push(d);
            any = true;
        }
        frame.objects.sort_by_key(|o| o.track);
        any
    }

    /// Moves new cells of `groups` (no owner) that are daughters of a cell of the frame
    /// before into that cell's group ([`ADOPT_REACH`]): two of them when her contour
    /// vanished, one beside the piece her contour kept when it kept under
    /// [`ADOPT_KEPT`] of her area. Daughters are within [`ADOPT_SHARE`] of each other's
    /// area, each no larger than she was, and off the `w`×`h` frame's edge (a cell coming
    /// into view is new). The nearest mother is served first.
    fn adopt(&self, groups: &mut Vec<(Option<u32>, Vec<TrackedObject>)>, w: usize, h: usize) {
        let before: HashMap<u32, (f64, Point)> = self
            .live
            .iter()
            .map(|(k, r)| {
                let (a2, c) = crate::geometry::area2_centroid(r);
                (*k, (0.5 * a2.abs(), c))
            })
            .collect();
        // A cell whose contour vanished has no group left (the evolution again with new
        // seeds starts from the pieces there are): an empty one.
        let owned: HashSet<u32> = groups.iter().filter_map(|(o, _)| *o).collect();
        for (k, _) in &self.live {
            if !owned.contains(k) {
                groups.push((Some(*k), Vec::new()));
            }
        }
        // The new cells: (group, index in it).
        let mut free: Vec<(usize, usize)> = groups
            .iter()
            .enumerate()
            .filter(|(_, (owner, _))| owner.is_none())
            .flat_map(|(g, (_, objs))| {
                objs.iter()
                    .enumerate()
                    .filter(|(_, o)| !at_edge(o, w, h))
                    .map(move |(i, _)| (g, i))
            })
            .collect();
        let mut moves: Vec<((usize, usize), usize)> = Vec::new();
        // Mothers by their distance to the nearest new cell.
        let mut mothers: Vec<(f64, usize)> = groups
            .iter()
            .enumerate()
            .filter_map(|(g, (owner, objs))| {
                let (area, c) = *before.get(&(*owner)?)?;
                (objs.len() <= 1).then_some(())?;
                let near = free
                    .iter()
                    .map(|&(fg, i)| groups[fg].1[i].centroid.dist(c))
                    .fold(f64::INFINITY, f64::min);
                let reach = ADOPT_REACH * (area / std::f64::consts::PI).sqrt();
                (near <= reach).then_some((near, g))
            })
            .collect();
        mothers.sort_by(|a, b| a.0.total_cmp(&b.0));
        let alike = |a: f64, b: f64| a.min(b) >= ADOPT_SHARE * a.max(b);
        for (_, g) in mothers {
            let Some((area, c)) = groups[g].0.and_then(|k| before.get(&k).copied()) else {
                continue;
            };
            let reach = ADOPT_REACH * (area / std::f64::consts::PI).sqrt();
            let mut near: Vec<(f64, usize)> = free
                .iter()
                .enumerate()
                .map(|(k, &(fg, i))| (groups[fg].1[i].centroid.dist(c), k))
                .filter(|&(d, k)| {
                    let (fg, i) = free[k];
                    d <= reach && groups[fg].1[i].area <= area
                })
                .collect();
            near.sort_by(|a, b| a.0.total_cmp(&b.0));
            let of = |k: usize| groups[free[k].0].1[free[k].1].area;
            let taken: Vec<usize> = match groups[g].1.first() {
                Some(kept) if kept.area <= ADOPT_KEPT * area => near
                    .iter()
                    .map(|&(_, k)| k)
                    .find(|&k| alike(of(k), kept.area))
                    .into_iter()
                    .collect(),
                Some(_) => Vec::new(),
                None => match near.as_slice() {
                    [(_, a), (_, b), ..] if alike(of(*a), of(*b)) => vec![*a, *b],
                    _ => Vec::new(),
                },
            };
            for &k in &taken {
                moves.push((free[k], g));
            }
            let mut taken = taken;
            taken.sort_unstable_by(|a, b| b.cmp(a));
            for k in taken {
                free.remove(k);
            }
        }
        // Out of their groups from the back, so the indices left stay true.
        moves.sort_by_key(|m| std::cmp::Reverse(m.0));
        for ((fg, i), g) in moves {
            let o = groups[fg].1.remove(i);
            groups[g].1.push(o);
        }
        for (_, objs) in groups.iter_mut() {
            objs.sort_by(|a, b| b.area.total_cmp(&a.area));
        }
    }

    /// Gives the pieces of one shape their tracks: the same track for one piece of a
    /// tracked cell, two children for two or more (the two largest; any further piece
    /// starts a track of its own), new tracks for the pieces of a new seed.
    fn settle(&mut self, owner: Option<u32>, group: Vec<TrackedObject>, frame: &mut TrackedFrame) {
        let t = frame.frame;
        let mut labels: Vec<u32> = Vec::with_capacity(group.len());
        match (owner, group.len()) {
            (_, 0) => {}
            (Some(track), 1) => {
                self.lineage.extend(track, t);
                labels.push(track);
            }
            (Some(track), _) if self.found_as_one(track, t) => {
                self.lineage.extend(track, t);
                labels.push(track);
                labels.extend(group[1..].iter().map(|o| self.begin(t, 0, o)));
            }
            (Some(parent), _) => {
                let children = [
                    self.begin(t, parent, &group[0]),
                    self.begin(t, parent, &group[1]),
                ];
                if self.measured_at_birth(parent, t) {
                    for (o, c) in group.iter().zip(children) {
                        self.born.insert(c, Size::of([o]));
                    }
                }
                let mut sorted = children;
                sorted.sort_unstable();
                frame.divisions.push(Division {
                    frame: t,
                    parent,
                    children: sorted,
                });
                labels.extend(children);
                labels.extend(group[2..].iter().map(|o| self.begin(t, 0, o)));
            }
            (None, _) => labels.extend(group.iter().map(|o| self.begin(t, 0, o))),
        }
        for (mut o, label) in group.into_iter().zip(labels) {
            o.track = label;
            frame.objects.push(o);
        }
    }

    /// A new track at frame `t` for `cell`, of `parent` (0: none): numbered as the run a
    /// correction replaced numbered the same cell ([`Tracker::keeping_numbers`]), else
    /// the next label.
    fn begin(&mut self, t: usize, parent: u32, cell: &TrackedObject) -> u32 {
        match self
            .numbers
            .as_mut()
            .and_then(|n| n.number(t, parent, cell))
        {
            Some(label) if self.lineage.get(label).is_none() => {
                self.lineage.start_at(label, t, parent)
            }
            _ => self.lineage.start(t, parent),
        }
    }
}

/// Whether any of `areas` is under [`MIN_CHILD_OF_TYPICAL`] of the `typical` cell (never
/// when there is none).
fn under(typical: Option<f64>, mut areas: impl Iterator<Item = f64>) -> bool {
    typical.is_some_and(|a| areas.any(|x| x < MIN_CHILD_OF_TYPICAL * a))
}

/// The pieces of one cell as one outline: each joined to the largest across the gap
/// where they meet ([`partition::united`]); a piece that does not meet it stays apart.
fn as_one(mut pieces: Vec<TrackedObject>, model: &ImageModel) -> Vec<TrackedObject> {
    let (w, h) = model.size();
    pieces.sort_by(|a, b| b.area.total_cmp(&a.area));
    let rest = pieces.split_off(1.min(pieces.len()));
    let Some(mut one) = pieces.pop() else {
        return rest;
    };
    let mut out = vec![];
    for p in rest {
        let labels = label_raster(&[(1, one.ring.as_slice()), (2, p.ring.as_slice())], w, h);
        match partition::united(&labels, 1, 2, model) {
            Some(ring) => one = object(ring),
            None => out.push(p),
        }
    }
    out.insert(0, one);
    out
}

/// How large a cell is, for telling whether it grew ([`MIN_GROWTH`]).
#[derive(Clone, Copy, Debug)]
struct Size {
    area: f64,
    /// The extent of its outline's points along their principal axis: a rod's length
    /// holds while a forming septum eats into its area.
    length: f64,
}

impl Size {
    /// The size of the cell seen as `pieces` (one, or the pieces it came apart in).
    fn of<'a>(pieces: impl IntoIterator<Item = &'a TrackedObject>) -> Size {
        let pieces: Vec<&TrackedObject> = pieces.into_iter().collect();
        let rings: Vec<&[Point]> = pieces.iter().map(|o| o.ring.as_slice()).collect();
        Size {
            area: pieces.iter().map(|o| o.area).sum(),
            length: length(&rings),
        }
    }
}

/// The extent of the points of `rings` along the principal axis of the region they
/// cover ([`neck::elongation_of`]).
fn length(rings: &[&[Point]]) -> f64 {
    let (_, _, axis) = neck::elongation_of(rings);
    let (lo, hi) = rings
        .iter()
        .flat_map(|r| r.iter())
        .map(|p| p.x * axis.x + p.y * axis.y)
        .fold((f64::MAX, f64::MIN), |(lo, hi), s| (lo.min(s), hi.max(s)));
    (hi - lo).max(0.0)
}

/// A cell of outline `ring` (region on the left), not yet given its track.
pub(crate) fn object(ring: Vec<Point>) -> TrackedObject {
    let (a2, centroid) = crate::geometry::area2_centroid(&ring);
    TrackedObject {
        track: 0,
        area: 0.5 * a2,
        centroid,
        ring,
    }
}

/// The median half-width 2A/P (area over perimeter: a disk's radius, about half a long
/// rod's width) of the cells `live`; 0 without any.
fn half_width(live: &[(u32, Vec<Point>)]) -> f64 {
    let mut hw: Vec<f64> = live
        .iter()
        .map(|(_, r)| {
            let p: f64 = (0..r.len()).map(|k| r[k].dist(r[(k + 1) % r.len()])).sum();
            2.0 * crate::geometry::signed_area(r).abs() / p.max(1e-9)
        })
        .collect();
    hw.sort_by(f64::total_cmp);
    hw.get(hw.len() / 2).copied().unwrap_or(0.0)
}

/// Whether `o` touches the edge of a `w`×`h` frame (a cell coming into view).
fn at_edge(o: &TrackedObject, w: usize, h: usize) -> bool {
    let (w, h) = (w as f64, h as f64);
    o.ring
        .iter()
        .any(|p| p.x < 1.5 || p.y < 1.5 || p.x > w - 1.5 || p.y > h - 1.5)
}

/// `groups` without their new cells that are specks ([`SPECK_SHARE`]) away from the
/// `w`×`h` frame's edge.
fn without_specks(
    groups: Vec<(Option<u32>, Vec<TrackedObject>)>,
    w: usize,
    h: usize,
) -> Vec<(Option<u32>, Vec<TrackedObject>)> {
    let mut areas: Vec<f64> = groups
        .iter()
        .flat_map(|(_, g)| g.iter().map(|o| o.area))
        .collect();
    areas.sort_by(f64::total_cmp);
    let total: f64 = areas.iter().sum();
    let mut sum = 0.0;
    let typical = areas
        .iter()
        .find(|&&a| {
            sum += a;
            2.0 * sum >= total
        })
        .copied()
        .unwrap_or(0.0);
    groups
        .into_iter()
        .map(|(owner, mut g)| {
            if owner.is_none() {
                g.retain(|o| o.area >= SPECK_SHARE * typical || at_edge(o, w, h));
            }
            (owner, g)
        })
        .collect()
}

/// The pieces of `pieces` grown from new seeds (`origins` [`Origin::New`]) joined where
/// they are one straight rod ([`partition::Join::Rods`]); carried cells and daughters
/// are left as they are. Returns the joined outlines.
fn join_new(
    origins: &[Origin],
    pieces: &mut [Vec<TrackedObject>],
    model: &ImageModel,
) -> Vec<Vec<Point>> {
    let new: Vec<usize> = (0..pieces.len())
        .filter(|&i| matches!(origins.get(i), Some(Origin::New)))
        .collect();
    if new.iter().map(|&i| pieces[i].len()).sum::<usize>() < 2 {
        return Vec::new();
    }
    let mut some: Vec<Vec<TrackedObject>> = new
        .iter()
        .map(|&i| std::mem::take(&mut pieces[i]))
        .collect();
    let joined = partition::join_pieces(&mut some, model, partition::Join::Rods);
    for (&i, g) in new.iter().zip(some) {
        pieces[i] = g;
    }
    joined
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn new_pieces_of_one_rod_are_joined_and_a_carried_cell_beside_them_is_left_alone() {
        // A bright rod 60 × 12 px on a dark ground, in three pieces: the left one a
        // carried cell's, the middle and right ones grown from two new seeds.
        let (w, h) = (100, 50);
        let data = (0..w * h)
            .map(|i| match (i % w, i / w) {
                (20..80, 20..32) => 1.0,
                _ => 0.2,
            })
            .collect();
        let params = crate::image::model::ModelParams::seeds(
            crate::image::Polarity::Bright,
            Modality::Fluorescence,
        );
        let model = ImageModel::prepare(&Field::new(w, h, data), &params, &[]);
        let piece = |x0: f64, x1: f64| {
            vec![object(vec![
                Point::new(x0, 20.5),
                Point::new(x1, 20.5),
                Point::new(x1, 31.5),
                Point::new(x0, 31.5),
            ])]
        };
        let mut pieces = vec![piece(20.5, 39.9), piece(40.1, 59.9), piece(60.1, 79.5)];
        let left = pieces[0].clone();
        let origins = [Origin::Carried(7), Origin::New, Origin::New];
        let joined = join_new(&origins, &mut pieces, &model);
        assert_eq!(joined.len(), 1);
        assert_eq!(pieces[0], left);
        assert_eq!(pieces[1].len(), 1);
        assert_eq!(pieces[1][0].ring, joined[0]);
        assert!(pieces[1][0].area > 420.0, "{}", pieces[1][0].area);
        assert!(pieces[2].is_empty());
    }

    /// A rod along x from `x0` to `x1` at y = 20, `width` across, as a ring.
    fn rod(x0: f64, x1: f64, width: f64) -> Vec<Point> {
        tapered(x0, 0.5 * width, x1, 0.5 * width)
    }

    /// A rod along x at y = 20 with caps of radius `r0` at `x0` and `r1` at `x1`.
    fn tapered(x0: f64, r0: f64, x1: f64, r1: f64) -> Vec<Point> {
        let mut ring = Vec::new();
        for k in 0..=16 {
            let a = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
            ring.push(Point::new(x1 + r1 * a.cos(), 20.0 + r1 * a.sin()));
        }
        for k in 0..=16 {
            let a = std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * k as f64 / 16.0;
            ring.push(Point::new(x0 + r0 * a.cos(), 20.0 + r0 * a.sin()));
        }
        ring
    }

    /// A tracker whose track 1 was seen on frames `first..=1` and divided at frame 2 into
    /// 2 (on the right) and 3 (on the left), its outline on frame 1 having measured
    /// `neck` after one `before` wide; and that frame 2.
    fn divided(first: usize, neck: Neck, before: Option<f64>) -> (Tracker, TrackedFrame) {
        let mut t = Tracker::new(TrackSettings::new(Params::default()), Vec::new());
        let parent = t.lineage.start(first, 0);
        t.lineage.extend(parent, 1);
        let children = [t.lineage.start(2, parent), t.lineage.start(2, parent)];
        t.necks.insert(parent, (neck, before));
        let frame = TrackedFrame {
            frame: 2,
            objects: vec![
                TrackedObject {
                    track: children[0],
                    ..object(rod(26.5, 38.5, 8.0))
                },
                TrackedObject {
                    track: children[1],
                    ..object(rod(9.5, 21.5, 8.0))
                },
            ],
            divisions: vec![Division {
                frame: 2,
                parent,
                children,
            }],
            undone: Vec::new(),
            earlier: Vec::new(),
            evolution_frames: 1,
        };
        (t, frame)
    }

    /// A neck of two rods meeting end to end at x = 24, as measured.
    fn caps(turn: f64, line: f64) -> Neck {
        Neck {
            narrow: 0.6,
            width: 8.0,
            line,
            turn,
            aspect: 2.0,
            share: 1.0,
            lobes: (rod(10.0, 20.0, 8.0), rod(28.0, 38.0, 8.0)),
        }
    }

    #[test]
    fn a_division_is_dated_where_the_neck_first_showed_two_cells() {
        let (mut t, mut frame) = divided(0, caps(0.9, 0.1), Some(0.62));
        t.date(&mut frame, &[1], Point::new(0.0, 0.0));
        assert!(frame.divisions.is_empty());
        let e = &frame.earlier[0];
        assert_eq!(
            e.division,
            Division {
                frame: 1,
                parent: 1,
                children: [2, 3]
            }
        );
        // Each lobe goes to the child it is nearer to.
        assert_eq!(e.cells[0].track, 2);
        assert!(e.cells[0].centroid.x > 30.0 && e.cells[1].centroid.x < 18.0);
        let l = |k| *t.lineage.get(k).unwrap();
        assert_eq!((l(1).first, l(1).last), (0, 0));
        assert_eq!((l(2).first, l(3).first), (1, 1));

        // The frame before, revised: the parent's cell is the two children's.
        let whole = object(rod(10.0, 38.0, 8.0));
        let mut before = TrackedFrame {
            frame: 1,
            objects: vec![TrackedObject {
                track: 1,
                ..whole.clone()
            }],
            divisions: Vec::new(),
            undone: Vec::new(),
            earlier: Vec::new(),
            evolution_frames: 1,
        };
        let (w, h) = (48, 40);
        let mut labels = label_raster(&[(1, whole.ring.as_slice())], w, h);
        before.revise(&frame);
        revise_labels(&mut labels, w, &frame);
        let tracks: Vec<u32> = before.objects.iter().map(|o| o.track).collect();
        assert_eq!(tracks, [2, 3]);
        assert_eq!(before.divisions, [e.division]);
        assert!(!labels.contains(&1));
        assert_eq!((labels[20 * w + 35], labels[20 * w + 13]), (2, 3));
        assert_eq!(labels[20 * w + 45], 0);

        // On a drifting stage the lobes are matched where the field moved them.
        let (mut t, mut frame) = divided(0, caps(0.9, 0.1), Some(0.62));
        for o in frame.objects.iter_mut() {
            o.centroid.x += 9.0;
        }
        let kept = frame.clone();
        t.date(&mut frame, &[1], Point::new(0.0, 0.0));
        assert_eq!(frame, kept, "9 px away, more than a width: not the lobes");
        t.date(&mut frame, &[1], Point::new(9.0, 0.0));
        assert_eq!(frame.earlier.len(), 1);
    }

    #[test]
    fn a_straight_rod_its_seeds_cut_in_two_on_frame_0_is_joined() {
        // A dark rod tapering from 12 px wide to 8: evolved again as one, its shortest
        // chord is near the thin end, where the lobe left is too small for a daughter,
        // so it has no neck at all; it is one cell.
        let (w, h) = (96usize, 48usize);
        let ring = tapered(16.0, 6.0, 72.0, 4.0);
        let data = (0..w * h)
            .map(|k| {
                let p = Point::new((k % w) as f64 + 0.5, (k / w) as f64 + 0.5);
                if crate::geometry::winding_number(&ring, p) != 0 {
                    0.2
                } else {
                    0.8
                }
            })
            .collect();
        let image = Field::new(w, h, data);
        let params = Params {
            polarity: crate::evolution::Polarity::Dark,
            ..Params::default()
        };
        let tracker = Tracker::new(TrackSettings::new(params), Vec::new());
        let half = |x0: f64, x1: f64| {
            Shape::Polygon(vec![
                Point::new(x0, 18.0),
                Point::new(x0, 22.0),
                Point::new(x1, 22.0),
                Point::new(x1, 18.0),
            ])
        };
        let (mut pieces, _, model) = tracker
            .evolve(&image, &[half(16.0, 42.0), half(46.0, 72.0)])
            .unwrap();
        assert_eq!(pieces.iter().flatten().count(), 2, "the seeds' two pieces");
        let joined = tracker.join_rods(&image, &mut pieces, model.as_deref().unwrap());
        assert_eq!(joined.len(), 1);
        assert_eq!(pieces.iter().flatten().count(), 1);
        let k = neck::measure(&joined[0], &image);
        assert!(k.is_none(), "the one outline has no neck: {k:?}");
    }

    #[test]
    fn a_waist_still_narrowing_or_bending_gently_keeps_its_division_where_it_was_cut() {
        for (first, neck, before) in [
            // The waist narrowed by 0.1 widths since the frame before: a constricting mother.
            (0, caps(0.9, 0.1), Some(0.7)),
            // It bends gently with hardly a line.
            (0, caps(0.6, 0.2), None),
            // The parent was seen on one frame only: it keeps it.
            (1, caps(1.2, 0.3), None),
        ] {
            let (mut t, mut frame) = divided(first, neck, before);
            let kept = frame.clone();
            t.date(&mut frame, &[1], Point::new(0.0, 0.0));
            assert_eq!(frame, kept);
            assert_eq!(t.lineage.get(2).unwrap().first, 2);
        }
        // A division that was not a cut at a neck (the contour split by itself).
        let (mut t, mut frame) = divided(0, caps(1.2, 0.3), None);
        let kept = frame.clone();
        t.date(&mut frame, &[], Point::new(0.0, 0.0));
        assert_eq!(frame, kept);
    }

    #[test]
    fn thin_cells_skip_the_coarse_levels() {
        let mut t = Tracker::new(TrackSettings::new(Params::default()), Vec::new());
        assert_eq!(t.levels(), 2, "no cells yet");
        // Rods 5 px wide (2A/P 4.0) are thin, 9 px wide (6.7) are not.
        t.live = (0..5).map(|k| (k, rod(10.0, 22.0, 5.0))).collect();
        assert!(half_width(&t.live) < COARSE_MIN_HALF_WIDTH);
        assert_eq!(t.levels(), 1);
        t.live = (0..5).map(|k| (k, rod(10.0, 24.0, 9.0))).collect();
        assert_eq!(t.levels(), 2);
    }
}
