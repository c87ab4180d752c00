//! The Train tool (issue 25): the user paints strokes of three labels — background,
//! object, and the boundary between touching objects — and a pixel classifier
//! ([`crate::learn`], ilastik's pixel classification) trained on them predicts every
//! pixel; the probability map is shown as an overlay and the contours read it.
//!
//! The strokes are part of the [`super::Document`] (a stroke is one undo step; sessions
//! save them), the map is not: it is derived, on a background thread ([`Trainer`]) so
//! the window stays responsive. Requests carry the strokes' revision; the thread takes
//! only the newest request waiting (latest wins) and the window drops an answer whose
//! revision is no longer the document's (stale). The thread keeps the features of the
//! image it saw last, so a stroke costs a training and a prediction, not the filters;
//! and it computes them as soon as the Train tool is on an image ([`Trainer::warm`]),
//! while the user paints the first strokes (on the 908×783 phase-contrast colony the
//! features are about 1 s of the first map's 1.4).
//! Training here is [`crate::learn::Teach::apply`]'s, step for step, so a run in the
//! app and its session's replay read the same probabilities.

use crate::evolution::Field;
use crate::learn::{Classifier, FeatureSet, Features, ForestParams, Strokes, Taught};
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::time::Instant;

/// The user's strokes and the classifier loaded from a file (document state).
#[derive(Clone, Debug, Default)]
pub struct Training {
    /// Per pixel 0 (none), 1 background, 2 object, 3 boundary; empty before the first
    /// stroke.
    pub labels: Arc<Vec<u8>>,
    /// Changes with every stroke, load or clear (unique over the app's life).
    pub revision: u64,
    /// A classifier loaded from a file: applied while no strokes teach one (kept when
    /// another image opens, so one model serves many images).
    pub loaded: Option<Arc<Classifier>>,
    /// Pixels painted with each label (index 0: unpainted, unused).
    counts: [usize; 4],
}

/// What a probability map is of: the strokes' revision and the image (by address).
pub type Key = (u64, usize);

/// A new [`Training::revision`].
pub fn next_revision() -> u64 {
    static REVISIONS: AtomicU64 = AtomicU64::new(1);
    REVISIONS.fetch_add(1, Ordering::Relaxed)
}

/// What teaches a classifier now.
#[derive(Clone, Debug)]
pub enum Source {
    /// Strokes that hold an object class and one more.
    Strokes(Arc<Strokes>),
    /// The classifier loaded.
    Loaded(Arc<Classifier>),
}

impl Training {
    /// Whether the strokes can train a classifier (an object class and one more).
    pub fn trainable(&self) -> bool {
        let c = &self.counts;
        c[2] > 0 && (c[1] > 0 || c[3] > 0)
    }

    /// The strokes as checked strokes (none when they mark no object or one class only).
    pub fn strokes(&self, width: usize, height: usize) -> Option<Strokes> {
        if !self.trainable() || self.labels.len() != width * height {
            return None;
        }
        Strokes::new(width, height, self.labels.to_vec()).ok()
    }

    /// Strokes read from a session.
    pub fn of_strokes(s: &Strokes) -> Self {
        let mut t = Training {
            labels: Arc::new(s.labels.clone()),
            revision: next_revision(),
            ..Training::default()
        };
        for &l in &s.labels {
            t.counts[l.min(3) as usize] += 1;
        }
        t
    }

    /// A classifier loaded (from a file or a session), with no strokes.
    pub fn of_classifier(c: Classifier) -> Self {
        Training {
            loaded: Some(Arc::new(c)),
            revision: next_revision(),
            ..Training::default()
        }
    }

    /// What a map for `image` teaches from now is of (none: nothing teaches).
    pub fn key(&self, image: &Arc<Field>) -> Option<Key> {
        (self.trainable() || self.loaded.is_some())
            .then_some((self.revision, Arc::as_ptr(image) as usize))
    }

    /// What teaches the run: valid strokes first, else the loaded classifier.
    pub fn source(&self, width: usize, height: usize) -> Option<Source> {
        match self.strokes(width, height) {
            Some(s) => Some(Source::Strokes(Arc::new(s))),
            None => self.loaded.clone().map(Source::Loaded),
        }
    }

    /// Whether any pixel is painted.
    pub fn painted(&self) -> bool {
        self.counts[1..].iter().any(|&n| n > 0)
    }

    /// The strokes wiped (the loaded classifier stays).
    pub fn clear(&mut self) {
        (self.labels, self.counts) = (Arc::default(), [0; 4]);
        self.revision = next_revision();
    }

    /// Paints `label` (0 erases) on every pixel whose centre is within `radius` of the
    /// segment `from`–`to`, on a `width`×`height` image.
    pub fn paint(
        &mut self,
        seg: [crate::geometry::Point; 2],
        radius: f64,
        label: u8,
        size: (usize, usize),
    ) {
        let (w, h) = size;
        let labels = Arc::make_mut(&mut self.labels);
        if labels.len() != w * h {
            *labels = vec![0; w * h];
            self.counts = [w * h, 0, 0, 0];
        }
        let label = label.min(3);
        let [a, b] = seg;
        let d = b - a;
        let (x0, x1) = (
            (a.x.min(b.x) - radius).floor(),
            (a.x.max(b.x) + radius).ceil(),
        );
        let (y0, y1) = (
            (a.y.min(b.y) - radius).floor(),
            (a.y.max(b.y) + radius).ceil(),
        );
        let clampi = |v: f64, n: usize| (v.max(0.0) as usize).min(n);
        for y in clampi(y0, h)..clampi(y1 + 1.0, h) {
            for x in clampi(x0, w)..clampi(x1 + 1.0, w) {
                let p = crate::geometry::Point::new(x as f64 + 0.5, y as f64 + 0.5);
                let t = if d.norm2() > 0.0 {
                    ((p - a).dot(d) / d.norm2()).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let old = &mut labels[y * w + x];
                if p.dist(a + d * t) <= radius && *old != label {
                    self.counts[*old as usize] -= 1;
                    self.counts[label as usize] += 1;
                    *old = label;
                }
            }
        }
        self.revision = next_revision();
    }
}

/// A probability map for one revision of the strokes.
#[derive(Clone, Debug)]
pub struct Map {
    /// The strokes' revision and image it was trained for.
    pub key: Key,
    /// The classifier and its probabilities on the image.
    pub taught: Taught,
}

/// What the window asks the thread.
struct Request {
    key: Key,
    image: Arc<Field>,
    name: String,
    source: Source,
}

/// What the window sends the thread: a map to make, or an image whose features to make
/// ahead of the first strokes.
enum Message {
    Teach(Request),
    Warm(Arc<Field>),
}

/// The background trainer: one thread, latest request wins.
#[derive(Default)]
pub struct Trainer {
    tx: Option<Sender<Message>>,
    rx: Option<Receiver<Answer>>,
    /// The map last asked for, and when.
    pub requested: Option<(Key, Instant)>,
    /// The newest map accepted.
    pub map: Option<Arc<Map>>,
    /// Stroke to map shown, the last time, ms.
    pub latency_ms: Option<f64>,
    /// The image (by address) whose features were asked for ahead of the strokes.
    warmed: Option<usize>,
    /// The image (by address, 0: none) whose features the thread holds now.
    ready: Arc<AtomicUsize>,
}

impl Trainer {
    /// Whether the map of `key` was asked for last.
    pub fn asked(&self, key: Key) -> bool {
        self.requested.is_some_and(|(k, _)| k == key)
    }

    /// Asks for the map of `key` (the thread answers the newest request waiting).
    pub fn request(
        &mut self,
        key: Key,
        image: Arc<Field>,
        name: String,
        source: Source,
        wake: Option<egui::Context>,
    ) {
        let req = Request {
            key,
            image,
            name,
            source,
        };
        if self.send(Message::Teach(req), wake) {
            self.requested = Some((key, Instant::now()));
        }
    }

    /// Asks the thread to compute the default features of `image` now, once per image,
    /// so that the first strokes' map costs a training and a prediction only.
    pub fn warm(&mut self, image: Arc<Field>, wake: Option<egui::Context>) {
        let at = Arc::as_ptr(&image) as usize;
        if self.warmed != Some(at) && self.send(Message::Warm(image), wake) {
            self.warmed = Some(at);
        }
    }

    /// Whether the thread holds the features of `image` (computed ahead or for a map).
    pub fn features_ready(&self, image: &Arc<Field>) -> bool {
        self.ready.load(Ordering::Acquire) == Arc::as_ptr(image) as usize
    }

    /// Sends `m` to the thread (started on first use); whether it went.
    fn send(&mut self, m: Message, wake: Option<egui::Context>) -> bool {
        if self.tx.is_none() {
            let (tx, rx) = spawn(wake, self.ready.clone());
            (self.tx, self.rx) = (Some(tx), Some(rx));
        }
        self.tx.as_ref().is_some_and(|tx| tx.send(m).is_ok())
    }

    /// Takes a map computed in the window's thread.
    pub fn accept(&mut self, key: Key, taught: Taught) {
        self.map = Some(Arc::new(Map { key, taught }));
        self.requested = Some((key, Instant::now()));
    }

    /// Takes the answers that came: the one for `key` becomes the map, others (stale)
    /// are dropped. Whether a map came, and the error if teaching failed.
    pub fn poll(&mut self, key: Option<Key>) -> (bool, Option<String>) {
        let Some(rx) = self.rx.as_ref() else {
            return (false, None);
        };
        let (mut came, mut error) = (false, None);
        while let Ok((k, result)) = rx.try_recv() {
            if Some(k) != key {
                continue;
            }
            match result {
                Ok(taught) => {
                    self.map = Some(Arc::new(Map { key: k, taught }));
                    came = true;
                    if let Some((_, at)) = self.requested.filter(|(q, _)| *q == k) {
                        self.latency_ms = Some(at.elapsed().as_secs_f64() * 1e3);
                    }
                }
                Err(e) => error = Some(e),
            }
        }
        (came, error)
    }

    /// Whether an answer for the last request is still to come.
    pub fn busy(&self) -> bool {
        self.requested
            .is_some_and(|(k, _)| self.map.as_ref().is_none_or(|m| m.key != k))
    }

    /// The map of `key`, if it is there.
    pub fn map_of(&self, key: Key) -> Option<&Map> {
        self.map.as_deref().filter(|m| m.key == key)
    }
}

/// What the thread answers: the map's key and the map (or why teaching failed).
type Answer = (Key, Result<Taught, String>);

/// The thread: waits for a request, skips to the newest waiting, answers it; an image
/// to warm is taken only when no map is asked for.
fn spawn(
    wake: Option<egui::Context>,
    ready: Arc<AtomicUsize>,
) -> (Sender<Message>, Receiver<Answer>) {
    let (tx, requests) = channel::<Message>();
    let (answers, rx) = channel();
    std::thread::spawn(move || {
        let mut cache: Option<(Arc<Field>, FeatureSet, Features)> = None;
        while let Ok(first) = requests.recv() {
            let (mut teach_req, mut warm) = (None, None);
            for m in std::iter::once(first).chain(requests.try_iter()) {
                match m {
                    Message::Teach(r) => teach_req = Some(r),
                    Message::Warm(image) => warm = Some(image),
                }
            }
            let Some(req) = teach_req else {
                if let Some(image) = warm {
                    features_of(&image, FeatureSet::default(), &mut cache);
                    ready.store(Arc::as_ptr(&image) as usize, Ordering::Release);
                }
                continue;
            };
            let result = teach(&req, &mut cache);
            if let Some((image, _, _)) = &cache {
                ready.store(Arc::as_ptr(image) as usize, Ordering::Release);
            }
            if answers.send((req.key, result)).is_err() {
                break;
            }
            if let Some(c) = &wake {
                c.request_repaint();
            }
        }
    });
    (tx, rx)
}

/// The features of `image` by `set`, from `cache` when it holds them (else made and kept).
fn features_of<'a>(
    image: &Arc<Field>,
    set: FeatureSet,
    cache: &'a mut Option<(Arc<Field>, FeatureSet, Features)>,
) -> &'a Features {
    let fresh = cache
        .as_ref()
        .is_none_or(|(img, s, _)| !Arc::ptr_eq(img, image) || *s != set);
    if fresh {
        let f = set.compute(image.width, image.height, &image.data);
        *cache = Some((image.clone(), set, f));
    }
    &cache.as_ref().expect("just filled").2
}

/// [`crate::learn::Teach::apply`] with the image's features kept between requests.
fn teach(
    req: &Request,
    cache: &mut Option<(Arc<Field>, FeatureSet, Features)>,
) -> Result<Taught, String> {
    let set = match &req.source {
        Source::Strokes(_) => FeatureSet::default(),
        Source::Loaded(c) => {
            if let Some(why) = c.misfit() {
                return Err(format!("the classifier does not fit: {why}"));
            }
            c.features.clone()
        }
    };
    let features = features_of(&req.image, set.clone(), cache);
    let classifier = match &req.source {
        Source::Strokes(s) => {
            let mut c = Classifier::train_with(set, features, s, &ForestParams::default());
            c.images = vec![req.name.clone()];
            Arc::new(c)
        }
        Source::Loaded(c) => c.clone(),
    };
    let probabilities = classifier.predict(features);
    Ok(Taught {
        classifier,
        probabilities,
    })
}

/// The map computed here and now (the window waits): for a run asked for before the
/// thread answered.
pub fn teach_now(image: &Arc<Field>, name: &str, source: Source) -> Result<Taught, String> {
    let req = Request {
        key: (0, 0),
        image: image.clone(),
        name: name.to_string(),
        source,
    };
    teach(&req, &mut None)
}
