//! [`ImageModel`]: everything an engine reads of the image, prepared once per run.
//!
//! One chain turns an image into what the forces see: the kind of image
//! ([`super::modality`]: phase contrast has its halo clipped), the Gaussian pyramid of
//! seed 004 §2 ([`super::field`]; no deeper than the objects stay resolved,
//! [`COARSE_HALF_WIDTH`]), the two-class intensity model learnt from Otsu's
//! split and the medians under the user's shapes ([`super::intensity`],
//! [`super::hints`]), and per pyramid level the local decision level of the region term
//! ([`super::local`]). The evolver, the automatic seeds and every later model kind start
//! from [`ImageModel::prepare`], so they cannot disagree on it.
//!
//! The explicit engines read the model through [`LevelView`] only: [`LevelView::probe`]
//! says what the image says at a point (the region score, the edge-stopping factor, the
//! edge attraction) and [`LevelView::pixel_score`] the region score of one pixel; the
//! implicit engine reads the full-resolution field and its two-class model
//! ([`ImageModel::fine`], [`ImageModel::global`]). A new kind of model (a pixel
//! classifier's probabilities, say: the field P(object) − P(background) with its level
//! at 0, a boundary probability for the edge stop) is a new [`ModelKind`] whose probes
//! this module answers; the engines stay as they are.

use super::field::{Field, Level, Pyramid};
use super::hints::hints;
use super::intensity::{IntensityModel, Polarity};
use super::local::{decision_field, Decision, LevelRule};
use super::modality::{for_modality, Modality};
use super::scale::{half_width, object_scale};
use super::stored::Stored;
use crate::geometry::Point;
use crate::shape::Shape;
use std::sync::OnceLock;

/// Most levels of the pyramid.
pub const PYRAMID_LEVELS: usize = 4;

/// Half-width (2A/P) the objects keep at the coarsest level, pixels at least: a coarser
/// level is dropped. Objects narrower than a coarse pixel average away there, and a
/// contour on them dies before the finer levels see them (a 512² grid of dots of radius
/// 5 gave no object at all from four levels). Seed 004 §2 leaves the depth open; the
/// object scale decides it. Two pixels cost tracking's noisy movies divisions (the
/// coarse levels smooth the first moves); one keeps them (docs/decisions.md, 2026-12-05).
pub const COARSE_HALF_WIDTH: f64 = 1.0;

/// Levels whose coarsest still shows objects of half-width `hw` at [`COARSE_HALF_WIDTH`].
fn resolvable_levels(hw: f64) -> usize {
    1 + (hw / COARSE_HALF_WIDTH).max(1.0).log2().floor() as usize
}

/// How far a coarse level's object area (the pixels on the object side of the global
/// decision level) may drift from the full resolution's, as a factor either way, for the
/// level to be kept.
pub const LEVEL_AREA_DRIFT: f64 = 1.5;

/// Levels, from the finest, on which the global decision level still finds about the
/// object area it finds at full resolution ([`LEVEL_AREA_DRIFT`]). Objects close
/// together average into one grey on a level too coarse for the gaps between them,
/// whatever their own width: a 512² grid of dots of radius 4 twelve pixels apart read
/// as no object at all at quarter resolution, and a wrap shrank over all 1,849 to one.
fn faithful_levels(pyramid: &Pyramid, global: &IntensityModel) -> usize {
    let share = |f: &Field| {
        let object = f.data.iter().filter(|&&v| global.score(v as f64) > 0.0);
        object.count() as f64 / f.data.len().max(1) as f64
    };
    let fine = share(&pyramid.levels[0].image);
    if fine == 0.0 {
        return pyramid.levels.len();
    }
    let kept = pyramid.levels[1..].iter().take_while(|l| {
        let drift = share(&l.image) / fine;
        (1.0 / LEVEL_AREA_DRIFT..=LEVEL_AREA_DRIFT).contains(&drift)
    });
    1 + kept.count()
}

/// What [`ImageModel::prepare`] is told (the image's part of an evolution's `Params`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ModelParams {
    /// Whether objects are darker or brighter than the background.
    pub polarity: Polarity,
    /// The kind of image.
    pub modality: Modality,
    /// Compare with a local decision level instead of the global one.
    pub local: bool,
    /// Radius of the local statistics, full-resolution pixels; `None`: the object scale
    /// ([`super::scale::object_scale`]).
    pub local_radius: Option<f64>,
    /// Coarsest pyramid level's short side, pixels (`usize::MAX`: level 0 only).
    pub coarsest_side: usize,
    /// The shapes' polygons outline objects ([`super::hints`]).
    pub outline_hints: bool,
}

impl ModelParams {
    /// What the automatic seeds read: local levels at the object scale, on level 0 only.
    pub fn seeds(polarity: Polarity, modality: Modality) -> Self {
        ModelParams {
            polarity,
            modality,
            local: true,
            local_radius: None,
            coarsest_side: usize::MAX,
            outline_hints: false,
        }
    }
}

/// Which model decides object against background.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelKind {
    /// Two intensity classes: the image (as its kind is seen) against the global model's
    /// midpoint or the local decision levels.
    Intensity,
}

/// What an engine reads of the image (see the module doc).
#[derive(Clone, Debug)]
pub struct ImageModel {
    kind: ModelKind,
    /// What it was prepared with.
    params: ModelParams,
    /// The pyramid of the image the forces see.
    pyramid: Pyramid,
    /// The two-class model on pyramid level 0.
    global: IntensityModel,
    /// Per pyramid level, the local decision level, made when first read (empty: the
    /// global model decides).
    decision: Vec<OnceLock<Decision>>,
    /// How the decision levels are made (`None` without local levels).
    rule: Option<LevelRule>,
    /// Radius of the local statistics, full-resolution pixels (`None` without them).
    radius: Option<f64>,
    width: usize,
    height: usize,
}

impl ImageModel {
    /// Prepares `image` as `params` say; `shapes` (the user's initialisation, possibly
    /// none) give the hints of [`super::hints`]: the object and background medians, and
    /// in phase contrast the background level the halo is clipped to.
    pub fn prepare(image: &Field, params: &ModelParams, shapes: &[Shape]) -> Self {
        let model = Self::finish(Self::pyramid(image, params, shapes), params, shapes);
        // Every level now, while the caller prepares (the app: in the background).
        for l in 0..model.levels() {
            model.decision(l);
        }
        model
    }

    /// [`ImageModel::prepare`], keeping the image compactly ([`Stored`]): it is packed as
    /// soon as its pyramid is built, before the decision levels are, so the floats and
    /// the full model are never held at once; and each level's decision level is made
    /// when the run first reads it, coarsest first, so a run that frees the coarse
    /// levels on reaching full resolution never holds every level's at once
    /// (docs/decisions.md, 2026-12-02). The values are the same either way.
    pub fn prepare_keeping(image: Field, params: &ModelParams, shapes: &[Shape]) -> (Self, Stored) {
        let pyramid = Self::pyramid(&image, params, shapes);
        let kept = Stored::new(image);
        (Self::finish(pyramid, params, shapes), kept)
    }

    /// The pyramid of the image as its kind is seen.
    fn pyramid(image: &Field, params: &ModelParams, shapes: &[Shape]) -> Pyramid {
        // Phase contrast: the halo reads as background, clipped to the level of the band a
        // wrap shows.
        let band = (params.modality == Modality::PhaseContrast)
            .then(|| hints(image, shapes, false).background)
            .flatten();
        let seen = for_modality(image, params.polarity, params.modality, band);
        Pyramid::new(&seen, params.coarsest_side, PYRAMID_LEVELS)
    }

    /// The model over `pyramid`: the two-class model and the decision levels.
    fn finish(mut pyramid: Pyramid, params: &ModelParams, shapes: &[Shape]) -> Self {
        let fine = &pyramid.levels[0].image;
        let (width, height) = (fine.width, fine.height);
        let hint = hints(fine, shapes, params.outline_hints);
        let mut global = IntensityModel::learn(fine, params.polarity, hint.object, hint.background);
        if let Some(o) = hint.outlined {
            global = global.beside_outlined(o);
        }
        let hw = half_width(fine, &global);
        pyramid.levels.truncate(resolvable_levels(hw));
        pyramid.levels.truncate(faithful_levels(&pyramid, &global));
        let fine = &pyramid.levels[0].image;
        let (radius, rule, decision) = if params.local {
            let radius = params.local_radius.unwrap_or_else(|| object_scale(hw));
            let rule = LevelRule::new(fine, &global, params.modality);
            let cells = pyramid.levels.iter().map(|_| OnceLock::new()).collect();
            (Some(radius), Some(rule), cells)
        } else {
            (None, None, Vec::new())
        };
        ImageModel {
            kind: ModelKind::Intensity,
            params: *params,
            pyramid,
            global,
            decision,
            rule,
            radius,
            width,
            height,
        }
    }

    /// The kind of model.
    pub fn kind(&self) -> ModelKind {
        self.kind
    }
    /// What it was prepared with.
    pub fn params(&self) -> &ModelParams {
        &self.params
    }
    /// The image's width and height in pixels.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }
    /// Number of pyramid levels (level 0: full resolution).
    pub fn levels(&self) -> usize {
        self.pyramid.levels.len()
    }
    /// The coarsest pyramid level.
    pub fn coarsest(&self) -> usize {
        self.levels() - 1
    }
    /// A model of no pixels: a stand-in while an engine's model is changed in place.
    pub(crate) fn empty() -> Self {
        ImageModel {
            kind: ModelKind::Intensity,
            params: ModelParams::seeds(Polarity::Dark, Modality::Generic),
            pyramid: Pyramid { levels: Vec::new() },
            global: IntensityModel {
                object: 0.0,
                background: 1.0,
            },
            decision: Vec::new(),
            rule: None,
            radius: None,
            width: 0,
            height: 0,
        }
    }

    /// Frees every level but full resolution's (pyramid and decision levels): for a run
    /// that has reached level 0, which it never leaves ([`crate::evolution::Evolver::free_coarse_levels`]).
    pub fn drop_coarse(&mut self) {
        self.pyramid.levels.truncate(1);
        self.pyramid.levels.shrink_to_fit();
        self.decision.truncate(1);
        self.decision.shrink_to_fit();
    }
    /// The same model over another image of the same size, seen as this one's was: its
    /// pyramid and local levels are made anew, its two-class model is this one's, so
    /// the decision level stays where it was (a taught run's last stage,
    /// [`crate::image::edges`]).
    pub fn over(&self, image: &Field) -> Self {
        let mut model = Self::finish(Self::pyramid(image, &self.params, &[]), &self.params, &[]);
        model.global = self.global;
        model
    }

    /// The image the forces see, at full resolution (pyramid level 0).
    pub fn fine(&self) -> &Field {
        &self.pyramid.levels[0].image
    }
    /// The two-class model learnt on [`ImageModel::fine`].
    pub fn global(&self) -> IntensityModel {
        self.global
    }
    /// Radius of the local statistics in full-resolution pixels (`None`: no local levels).
    pub fn radius(&self) -> Option<f64> {
        self.radius
    }
    /// The local decision level of pyramid level `level` (`None`: the global model
    /// decides there).
    pub fn decision(&self, level: usize) -> Option<&Decision> {
        let (cell, rule, radius) = (self.decision.get(level)?, self.rule?, self.radius?);
        Some(cell.get_or_init(|| {
            let r = (radius / Pyramid::scale(level)).round().max(1.0) as usize;
            decision_field(&self.pyramid.levels[level].image, r, &self.global, &rule)
        }))
    }
    /// What the forces read on pyramid level `level`.
    pub fn level(&self, level: usize) -> LevelView<'_> {
        LevelView {
            level: &self.pyramid.levels[level],
            decision: self.decision(level),
            global: &self.global,
        }
    }
}

/// One pyramid level of an [`ImageModel`], as the forces read it.
#[derive(Clone, Copy, Debug)]
pub struct LevelView<'a> {
    level: &'a Level,
    decision: Option<&'a Decision>,
    global: &'a IntensityModel,
}

/// What the image says at one point of a level ([`LevelView::probe`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probe {
    /// The region score, in units of half the contrast: +1 at the object's level, 0 at
    /// the decision level, −1 at the background's (not clamped).
    pub score: f64,
    /// Edge stopping, in (0, 1]: 1 on flat image, towards 0 on a strong edge.
    pub stop: f64,
    /// Edge attraction along the normal, in [−1, 1]: positive when the gradient
    /// magnitude grows ahead.
    pub edge: f64,
}

impl LevelView<'_> {
    /// The level's image.
    pub fn image(&self) -> &Field {
        &self.level.image
    }

    /// What the image says at `x` (level coordinates) for a contour with outward unit
    /// normal `n`. The edge stop is 1 / (1 + 16 (|∇I| / c)²) with c the (local)
    /// contrast; the edge attraction compares the gradient magnitude half a pixel ahead
    /// and behind (halos and texture make wider differences chatter).
    #[inline]
    pub fn probe(&self, x: Point, n: Point) -> Probe {
        let t = self.level.sample(x);
        // The score in units of half the contrast, and the contrast: local or global.
        let (score, contrast) = match self.decision {
            Some(d) => {
                let half = d.half.sample(x).max(1e-6);
                ((t.value - d.level.sample(x)) * d.sign / half, 2.0 * half)
            }
            None => (
                self.global.score(t.value),
                (self.global.object - self.global.background)
                    .abs()
                    .max(1e-6),
            ),
        };
        let gmag = t.gradient.norm() / contrast;
        let stop = 1.0 / (1.0 + 16.0 * gmag * gmag);
        let ahead = self.level.gmag(x + n * 0.5);
        let behind = self.level.gmag(x - n * 0.5);
        let edge = (2.0 * (ahead - behind) / contrast).clamp(-1.0, 1.0);
        Probe { score, stop, edge }
    }

    /// The region score of pixel `i` of the level (as [`Probe::score`]).
    #[inline]
    pub fn pixel_score(&self, i: usize) -> f64 {
        let v = self.level.image.data[i] as f64;
        match self.decision {
            Some(d) => (v - d.level.data[i] as f64) * d.sign / (d.half.data[i] as f64).max(1e-6),
            None => self.global.score(v),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bright disks of two brightnesses on a noisy dark ground.
    fn disks(w: usize, h: usize) -> Field {
        let data = (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                let noise = ((i * 2_654_435_761) % 97) as f32 / 97.0 - 0.5;
                let near = |cx: f64, cy: f64| (x - cx).hypot(y - cy) < 12.0;
                let v = if near(30.0, 30.0) {
                    0.8
                } else if near(80.0, 50.0) {
                    0.45
                } else {
                    0.1
                };
                v + 0.04 * noise
            })
            .collect();
        Field::new(w, h, data)
    }

    fn run_params(polarity: Polarity, modality: Modality) -> ModelParams {
        ModelParams {
            coarsest_side: 16,
            ..ModelParams::seeds(polarity, modality)
        }
    }

    /// An `n`² grid of dark dots (0.15 on 0.8), one per `pitch`-px cell, of radius `r`
    /// around the cell's point `c2 / 2` (twice the offset, to centre on a pixel corner).
    fn dot_grid(n: usize, pitch: usize, c2: i64, r: i64) -> Field {
        let data = (0..n * n).map(|i| {
            let (x, y) = (((i % n) % pitch) as i64, ((i / n) % pitch) as i64);
            let d2 = (2 * x - c2).pow(2) + (2 * y - c2).pow(2);
            if d2 <= 4 * r * r {
                0.15
            } else {
                0.8
            }
        });
        Field::new(n, n, data.collect())
    }

    /// Pyramid levels of a dark-object model of `image`, 64 px at the coarsest at most.
    fn dark_levels(image: &Field) -> usize {
        let params = ModelParams {
            coarsest_side: 64,
            ..ModelParams::seeds(Polarity::Dark, Modality::Generic)
        };
        ImageModel::prepare(image, &params, &[]).levels()
    }

    /// The regions a default run for dark objects finds on `image` from `shape`.
    fn dark_regions(image: &Field, shape: Shape) -> Vec<crate::contours::measure::Region> {
        let run = crate::evolution::Params {
            polarity: Polarity::Dark,
            ..Default::default()
        };
        let mut ev = crate::evolution::Evolver::new(image, &[shape], run).unwrap();
        ev.run();
        ev.filter_clutter();
        crate::contours::measure::regions(ev.contours())
    }

    /// The pyramid stops where the objects would average away: dots of radius 5 every
    /// 16 px keep three levels (they vanished at the fourth, 1/8 scale, and a seed
    /// clicked on one died there), large disks all four; a seed on a dot finds it.
    #[test]
    fn the_pyramid_is_no_deeper_than_the_objects_stay_resolved() {
        let dots = dot_grid(512, 16, 16, 5);
        assert_eq!(dark_levels(&dots), 3);
        let big = disks(512, 512);
        let params = ModelParams {
            coarsest_side: 64,
            ..ModelParams::seeds(Polarity::Bright, Modality::Generic)
        };
        assert_eq!(ImageModel::prepare(&big, &params, &[]).levels(), 4);
        let seed = Shape::Disk {
            center: Point::new(40.5, 40.5),
            radius: 3.0,
        };
        let found = dark_regions(&dots, seed);
        assert_eq!(found.len(), 1, "the dot is found");
        assert!((found[0].area - 78.5).abs() < 15.0, "{}", found[0].area);
    }

    /// Dots close together keep only the levels where they still show apart: radius-4
    /// dots 12 px apart are wide enough for three levels, but at quarter resolution
    /// they average into one grey, and a wrap of the field shrank over 60 of 1,024.
    #[test]
    fn the_pyramid_is_no_deeper_than_the_gaps_between_objects_stay_resolved() {
        let n = 384;
        let dots = dot_grid(n, 12, 11, 4);
        assert_eq!(dark_levels(&dots), 2);
        let wrap = Shape::Rect {
            min: Point::new(2.0, 2.0),
            max: Point::new(n as f64 - 2.0, n as f64 - 2.0),
        };
        assert_eq!(dark_regions(&dots, wrap).len(), 1024);
    }

    /// The seeds and a run without shapes read the same full-resolution level: the
    /// automatic seeds see the mask the evolution will see.
    #[test]
    fn seeds_and_a_run_share_level_0() {
        let img = disks(120, 90);
        for modality in [
            Modality::Generic,
            Modality::Fluorescence,
            Modality::PhaseContrast,
        ] {
            let seeds =
                ImageModel::prepare(&img, &ModelParams::seeds(Polarity::Bright, modality), &[]);
            let run = ImageModel::prepare(&img, &run_params(Polarity::Bright, modality), &[]);
            assert_eq!(seeds.levels(), 1);
            assert!(run.levels() > 1);
            assert_eq!(seeds.fine().data, run.fine().data);
            assert_eq!(seeds.global(), run.global());
            assert_eq!(seeds.radius(), run.radius());
            let (a, b) = (seeds.decision(0).unwrap(), run.decision(0).unwrap());
            assert_eq!(a.level.data, b.level.data);
            assert_eq!(a.half.data, b.half.data);
        }
    }

    /// A probe at a pixel centre scores the pixel as [`LevelView::pixel_score`] does,
    /// with local levels and with the global model alone.
    #[test]
    fn a_probe_at_a_pixel_centre_scores_the_pixel() {
        let img = disks(120, 90);
        for local in [true, false] {
            let params = ModelParams {
                local,
                ..run_params(Polarity::Bright, Modality::Generic)
            };
            let model = ImageModel::prepare(&img, &params, &[]);
            assert_eq!(model.decision(0).is_some(), local);
            for l in 0..model.levels() {
                let view = model.level(l);
                let w = view.image().width;
                for i in (0..view.image().data.len()).step_by(7) {
                    let x = Point::new((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
                    let p = view.probe(x, Point::new(1.0, 0.0));
                    assert_eq!(p.score, view.pixel_score(i), "level {l} pixel {i}");
                    assert!(p.stop > 0.0 && p.stop <= 1.0);
                    assert!((-1.0..=1.0).contains(&p.edge));
                }
            }
        }
    }

    /// The user's shapes change the model (their medians are the hints); no shape, no
    /// hint.
    #[test]
    fn shapes_give_the_hints() {
        let img = disks(120, 90);
        let params = run_params(Polarity::Bright, Modality::Generic);
        let plain = ImageModel::prepare(&img, &params, &[]);
        let dim_seed = [Shape::Disk {
            center: Point::new(80.0, 50.0),
            radius: 6.0,
        }];
        let hinted = ImageModel::prepare(&img, &params, &dim_seed);
        assert!(hinted.global().object < plain.global().object);
        assert!((hinted.global().object - 0.45).abs() < 0.05);
        // A polygon round the bright disk: a drawn shape or a seed's basin does not
        // hint; outlines of carried cells do, but only against an Otsu split that missed
        // the objects ([`IntensityModel::beside_outlined`]), which this one did not.
        let ring: Vec<Point> = (0..24)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 24.0;
                Point::new(30.0 + 8.0 * a.cos(), 30.0 + 8.0 * a.sin())
            })
            .collect();
        let outline = [Shape::Polygon(ring)];
        let drawn = ImageModel::prepare(&img, &params, &outline);
        assert_eq!(drawn.global().object, plain.global().object);
        let carried = ModelParams {
            outline_hints: true,
            ..params
        };
        let carried = ImageModel::prepare(&img, &carried, &outline);
        assert_eq!(carried.global().object, plain.global().object);
    }
}
