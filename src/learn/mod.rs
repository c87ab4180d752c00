//! Teaching by example: a pixel classifier trained from a user's strokes, as ilastik's
//! pixel classification (Sommer et al. 2011), Labkit and QuPath's pixel classifier do.
//! The user paints a few strokes — background, object, and the boundary between
//! touching objects — a random forest ([`forest`]) on multiscale filter features
//! ([`features`]) learns them, and predicts every pixel's class probabilities
//! ([`Probabilities`]). The contours then read those probabilities instead of the
//! intensity (see [`guide`]): the boundary class is what keeps
//! touching cells with no intensity step between them apart.

pub mod features;
pub mod filters;
pub mod forest;
pub mod guide;
pub mod strokes;
pub mod teach;

pub use features::{FeatureSet, Features};
pub use forest::{Forest, ForestParams};
pub use strokes::{StrokeError, Strokes, BACKGROUND, BOUNDARY, OBJECT};
pub use teach::{Taught, Teach, TeachError};

/// Channels of the images a classifier reads: images are read as one gray channel.
pub const CHANNELS: u32 = 1;

/// A trained pixel classifier: the features it reads, the stroke labels of its classes
/// and the forest.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Classifier {
    /// The feature definitions' version ([`features::FEATURE_VERSION`]).
    pub feature_version: u32,
    /// The features.
    pub features: FeatureSet,
    /// Channels of the images it was trained on ([`CHANNELS`]).
    pub channels: u32,
    /// The names of the images it was trained on (for the user; not checked).
    pub images: Vec<String>,
    /// The stroke label of each class index (1 background, 2 object, 3 boundary).
    pub labels: Vec<u8>,
    /// How the forest was grown.
    pub params: ForestParams,
    /// The forest.
    pub forest: Forest,
}

/// Per pixel, the probability of each stroke label.
#[derive(Clone, Debug, PartialEq)]
pub struct Probabilities {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// The stroke label of each class, in the order of `data`.
    pub labels: Vec<u8>,
    /// Per pixel, `labels.len()` probabilities summing to 1.
    pub data: Vec<f32>,
}

impl Probabilities {
    /// P(`label`) at every pixel (0 everywhere for a label the classifier never saw).
    pub fn of(&self, label: u8) -> Vec<f32> {
        let c = self.labels.len();
        match self.labels.iter().position(|&l| l == label) {
            Some(k) => self.data.iter().skip(k).step_by(c).copied().collect(),
            None => vec![0.0; self.width * self.height],
        }
    }

    /// The most probable label at every pixel (ties: the lower label).
    pub fn argmax(&self) -> Vec<u8> {
        let c = self.labels.len();
        self.data
            .chunks_exact(c)
            .map(|p| {
                let k = (0..c).fold(0, |b, k| if p[k] > p[b] { k } else { b });
                self.labels[k]
            })
            .collect()
    }
}

impl Classifier {
    /// Trains on the pixels the strokes label, with the default features.
    pub fn train(features: &Features, strokes: &Strokes, params: &ForestParams) -> Self {
        Self::train_with(FeatureSet::default(), features, strokes, params)
    }

    /// Trains on the pixels the strokes label; `set` must be what made `features`.
    ///
    /// # Panics
    /// If the features and the strokes differ in size.
    pub fn train_with(
        set: FeatureSet,
        features: &Features,
        strokes: &Strokes,
        params: &ForestParams,
    ) -> Self {
        Self::train_many(set, &[(features, strokes)], params)
    }

    /// Trains on the pixels the strokes of several images label (each pair one image's
    /// features and strokes, all made by `set`); the classes are those any image marks.
    ///
    /// # Panics
    /// If a pair differs in size, or `pairs` is empty.
    pub fn train_many(
        set: FeatureSet,
        pairs: &[(&Features, &Strokes)],
        params: &ForestParams,
    ) -> Self {
        assert!(!pairs.is_empty(), "no training image");
        let mut labels: Vec<u8> = pairs.iter().flat_map(|(_, s)| s.classes()).collect();
        labels.sort_unstable();
        labels.dedup();
        let nf = set.len();
        let mut x = Vec::new();
        let mut y = Vec::new();
        for (features, strokes) in pairs {
            assert_eq!(
                (features.width, features.height, features.planes.len()),
                (strokes.width, strokes.height, nf),
                "features and strokes size"
            );
            for (i, &l) in strokes.labels.iter().enumerate() {
                if let Some(k) = labels.iter().position(|&c| c == l) {
                    x.extend(features.planes.iter().map(|p| p[i]));
                    y.push(k as u8);
                }
            }
        }
        let forest = Forest::train(&x, &y, nf, labels.len(), params);
        Classifier {
            feature_version: features::FEATURE_VERSION,
            features: set,
            channels: CHANNELS,
            images: Vec::new(),
            labels,
            params: *params,
            forest,
        }
    }

    /// Why this build cannot apply the classifier (other features, channels or classes),
    /// or `None` when it fits.
    pub fn misfit(&self) -> Option<String> {
        let want = features::FEATURE_VERSION;
        if self.feature_version != want {
            return Some(format!(
                "it reads features of version {}, this build computes version {want}; train it again",
                self.feature_version
            ));
        }
        if self.channels != CHANNELS {
            return Some(format!(
                "it was trained on {}-channel images, this build reads images as {CHANNELS} gray channel",
                self.channels
            ));
        }
        let labels_ok = self.labels.windows(2).all(|w| w[0] < w[1])
            && self
                .labels
                .iter()
                .all(|l| (BACKGROUND..=BOUNDARY).contains(l));
        if !labels_ok || !self.labels.contains(&OBJECT) || self.labels.len() < 2 {
            return Some(format!(
                "its classes {:?} are not object (2) and background (1) or boundary (3)",
                self.labels
            ));
        }
        self.forest
            .misfit(self.features.len(), self.labels.len())
            .map(|why| format!("its forest is damaged: {why}"))
    }

    /// The class probabilities of every pixel of `features`.
    pub fn predict(&self, features: &Features) -> Probabilities {
        let (w, h) = (features.width, features.height);
        let c = self.labels.len();
        let planes: Vec<&[f32]> = features.planes.iter().map(|p| p.as_slice()).collect();
        let mut data = filters::written_zeros(w * h * c);
        // Laid out once for all rows, not once per row.
        let forest = self.forest.predictor();
        filters::for_rows(&mut data, w * c, |y, row| {
            forest.predict_block(&planes, y * w, row);
        });
        Probabilities {
            width: w,
            height: h,
            labels: self.labels.clone(),
            data,
        }
    }
}

/// The map in two parts, for a front end that shows a map while it is made (ilastik
/// predicts the visible tiles first): a half-resolution preview — the pixels at even x
/// and y, a quarter of the work — then the rest. Each part is the forest's own
/// prediction (the same values [`Classifier::predict`] gives those pixels; no pixel is
/// predicted twice), and each stops between rows once `stop` says so, so a newer
/// request need not wait for an older one.
impl Classifier {
    /// The probabilities at the pixels of even x and y, as a ⌈w/2⌉×⌈h/2⌉ map; `None`
    /// when `stop` returned true before the last row.
    pub fn predict_preview(
        &self,
        features: &Features,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Probabilities> {
        let (w, h) = (features.width, features.height);
        let (hw, hh) = (w.div_ceil(2), h.div_ceil(2));
        let c = self.labels.len();
        let forest = self.forest.predictor();
        let mut data = filters::written_zeros(hw * hh * c);
        filters::for_rows(&mut data, hw * c, |y, row| {
            if stop() {
                return;
            }
            let cols = gather(features, 2 * y, 0);
            let refs: Vec<&[f32]> = cols.iter().map(|p| p.as_slice()).collect();
            forest.predict_block(&refs, 0, row);
        });
        (!stop()).then(|| Probabilities {
            width: hw,
            height: hh,
            labels: self.labels.clone(),
            data,
        })
    }

    /// The full map, `preview` ([`Classifier::predict_preview`] of these features)
    /// giving its pixels: only the others are predicted. `None` when stopped.
    ///
    /// # Panics
    /// If `preview` is not of this size and these classes.
    pub fn predict_rest(
        &self,
        features: &Features,
        preview: &Probabilities,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Probabilities> {
        let (w, h) = (features.width, features.height);
        let (hw, c) = (w.div_ceil(2), self.labels.len());
        assert!(
            (preview.width, preview.height) == (hw, h.div_ceil(2)) && preview.labels == self.labels,
            "preview of another map"
        );
        let planes: Vec<&[f32]> = features.planes.iter().map(|p| p.as_slice()).collect();
        let forest = self.forest.predictor();
        let mut data = filters::written_zeros(w * h * c);
        filters::for_rows(&mut data, w * c, |y, row| {
            if stop() {
                return;
            }
            if y % 2 == 1 {
                forest.predict_block(&planes, y * w, row);
                return;
            }
            let known = &preview.data[(y / 2) * hw * c..(y / 2 + 1) * hw * c];
            let cols = gather(features, y, 1);
            let refs: Vec<&[f32]> = cols.iter().map(|p| p.as_slice()).collect();
            let mut odd = vec![0.0f32; (w / 2) * c];
            forest.predict_block(&refs, 0, &mut odd);
            for x in 0..w {
                let from = if x % 2 == 0 {
                    &known[(x / 2) * c..(x / 2 + 1) * c]
                } else {
                    &odd[(x / 2) * c..(x / 2 + 1) * c]
                };
                row[x * c..(x + 1) * c].copy_from_slice(from);
            }
        });
        (!stop()).then(|| Probabilities {
            width: w,
            height: h,
            labels: self.labels.clone(),
            data,
        })
    }
}

/// Row `y` of every feature plane at the columns `first`, `first + 2`, …
fn gather(features: &Features, y: usize, first: usize) -> Vec<Vec<f32>> {
    let w = features.width;
    let row = y * w;
    features
        .planes
        .iter()
        .map(|p| p[row + first..row + w].iter().step_by(2).copied().collect())
        .collect()
}
