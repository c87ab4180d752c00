//! The Train tool (issue 25): the user paints strokes of three labels — background,
//! object, and the boundary between touching objects — and a pixel classifier
//! ([`crate::learn`], ilastik's pixel classification) trained on them predicts every
//! pixel; the probability map is shown as an overlay and the contours read it.
//!
//! The strokes are part of the [`super::Document`] (a stroke is one undo step; sessions
//! save them), the map is not: it is derived, on a background thread ([`Trainer`]) so
//! the window stays responsive. Requests carry the strokes' revision; the thread takes
//! only the newest request waiting (latest wins) and the window drops an answer whose
//! revision is no longer the document's (stale); a newer request also stops the one in
//! flight between rows of its prediction, so two quick strokes wait for one map. The
//! map comes in two parts: a half-resolution preview (the forest's own prediction at
//! every other pixel, a quarter of the work, shown and labelled as such) then the full
//! map, which alone the contours read. The thread keeps the features of the
//! image it saw last, so a stroke costs a training and a prediction, not the filters;
//! and it computes them as soon as the Train tool is on an image ([`Trainer::warm`]),
//! while the user paints the first strokes (on the 908×783 phase-contrast colony the
//! features are about 1 s of the first map's 1.4).
//! Training here is [`crate::learn::Teach::apply`]'s, step for step, so a run in the
//! app and its session's replay read the same probabilities.

use crate::evolution::Field;
use crate::learn::Probabilities;
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
    /// The request's number: the thread stops it once a newer one is asked.
    seq: u64,
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
    /// The newest preview accepted: the map of its key at half resolution, until the
    /// full map comes.
    pub preview: Option<(Key, Arc<Probabilities>)>,
    /// Stroke to map shown, the last time, ms.
    pub latency_ms: Option<f64>,
    /// Stroke to preview shown, the last time, ms.
    pub preview_ms: Option<f64>,
    /// The newest request's number (the thread drops the others).
    newest: Arc<AtomicU64>,
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
        let seq = self.newest.fetch_add(1, Ordering::AcqRel) + 1;
        let req = Request {
            key,
            seq,
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
            let (tx, rx) = spawn(wake, self.ready.clone(), self.newest.clone());
            (self.tx, self.rx) = (Some(tx), Some(rx));
        }
        self.tx.as_ref().is_some_and(|tx| tx.send(m).is_ok())
    }

    /// Takes a map computed in the window's thread.
    pub fn accept(&mut self, key: Key, taught: Taught) {
        // The thread's request in flight is this one: it stops.
        self.newest.fetch_add(1, Ordering::AcqRel);
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
        while let Ok(answer) = rx.try_recv() {
            let (k, result) = match answer {
                Answer::Preview(k, p) => {
                    if Some(k) == key {
                        self.preview = Some((k, p));
                        if let Some((_, at)) = self.requested.filter(|(q, _)| *q == k) {
                            self.preview_ms = Some(at.elapsed().as_secs_f64() * 1e3);
                        }
                    }
                    continue;
                }
                Answer::Map(k, result) => (k, result),
            };
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

    /// The preview of `key` while its full map has not come.
    pub fn preview_of(&self, key: Key) -> Option<&Arc<Probabilities>> {
        if self.map_of(key).is_some() {
            return None;
        }
        self.preview
            .as_ref()
            .filter(|(k, _)| *k == key)
            .map(|(_, p)| p)
    }
}

/// What the thread answers, with the key of the map it is of.
enum Answer {
    /// The map at half resolution (the pixels of even x and y).
    Preview(Key, Arc<Probabilities>),
    /// The map (or why teaching failed).
    Map(Key, Result<Taught, String>),
}

/// The thread: waits for a request, skips to the newest waiting, answers it; an image
/// to warm is taken only when no map is asked for.
fn spawn(
    wake: Option<egui::Context>,
    ready: Arc<AtomicUsize>,
    newest: Arc<AtomicU64>,
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
            // Numbers only grow, so once stopped a request stays stopped.
            let stop = || newest.load(Ordering::Acquire) != req.seq;
            let mut gone = false;
            let send = |a: Answer| {
                gone |= answers.send(a).is_err();
                if let Some(c) = &wake {
                    c.request_repaint();
                }
            };
            answer(&req, &mut cache, &stop, send);
            if let Some((image, _, _)) = &cache {
                ready.store(Arc::as_ptr(image) as usize, Ordering::Release);
            }
            if gone {
                break;
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

/// Answers `req` through `send`: its preview, then its map (or why it cannot be
/// taught); nothing more once `stop` says a newer request waits.
fn answer(
    req: &Request,
    cache: &mut Option<(Arc<Field>, FeatureSet, Features)>,
    stop: &(dyn Fn() -> bool + Sync),
    mut send: impl FnMut(Answer),
) {
    let (classifier, features) = match classifier_of(req, cache) {
        Ok(c) => c,
        Err(e) => return send(Answer::Map(req.key, Err(e))),
    };
    let Some(preview) = classifier.predict_preview(features, stop) else {
        return;
    };
    let preview = Arc::new(preview);
    send(Answer::Preview(req.key, preview.clone()));
    let Some(probabilities) = classifier.predict_rest(features, &preview, stop) else {
        return;
    };
    let taught = Taught {
        classifier,
        probabilities,
    };
    send(Answer::Map(req.key, Ok(taught)));
}

/// [`crate::learn::Teach::apply`] with the image's features kept between requests.
fn teach(
    req: &Request,
    cache: &mut Option<(Arc<Field>, FeatureSet, Features)>,
) -> Result<Taught, String> {
    let (classifier, features) = classifier_of(req, cache)?;
    let probabilities = classifier.predict(features);
    Ok(Taught {
        classifier,
        probabilities,
    })
}

/// The classifier of `req` (trained, or the one loaded) and the image's features.
fn classifier_of<'a>(
    req: &Request,
    cache: &'a mut Option<(Arc<Field>, FeatureSet, Features)>,
) -> Result<(Arc<Classifier>, &'a Features), String> {
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
    Ok((classifier, features))
}

/// The map computed here and now (the window waits): for a run asked for before the
/// thread answered.
pub fn teach_now(image: &Arc<Field>, name: &str, source: Source) -> Result<Taught, String> {
    let req = Request {
        key: (0, 0),
        seq: 0,
        image: image.clone(),
        name: name.to_string(),
        source,
    };
    teach(&req, &mut None)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 24×20 image with a bright square, and strokes of object and background.
    fn request(key: Key) -> Request {
        let (w, h) = (24, 20);
        let inside = |i: usize| (6..14).contains(&(i % w)) && (5..13).contains(&(i / w));
        let data = (0..w * h)
            .map(|i| if inside(i) { 0.8 } else { 0.2 } + 0.01 * (i % 7) as f32)
            .collect();
        let labels = (0..w * h)
            .map(|i| match (i % w, i / w) {
                (9..=11, 9) => 2,
                (_, 17) => 1,
                _ => 0,
            })
            .collect();
        Request {
            key,
            seq: 1,
            image: Arc::new(Field::new(w, h, data)),
            name: "square".into(),
            source: Source::Strokes(Arc::new(Strokes::new(w, h, labels).unwrap())),
        }
    }

    /// A trainer whose answers come from the test, not from a thread.
    fn fake() -> (Trainer, Sender<Answer>) {
        let (tx, rx) = channel();
        let t = Trainer {
            rx: Some(rx),
            ..Trainer::default()
        };
        (t, tx)
    }

    fn taught() -> Taught {
        teach(&request((0, 0)), &mut None).unwrap()
    }

    #[test]
    fn an_old_map_arriving_late_is_dropped() {
        let (old, new) = ((1, 7), (2, 7));
        let (mut t, tx) = fake();
        let p = taught().probabilities;
        // The newer stroke's preview and map come; the older's come after them.
        tx.send(Answer::Preview(new, Arc::new(p.clone()))).unwrap();
        assert_eq!(t.poll(Some(new)), (false, None), "a preview is not the map");
        assert!(t.preview_of(new).is_some() && t.map_of(new).is_none());
        tx.send(Answer::Map(new, Ok(taught()))).unwrap();
        assert_eq!(t.poll(Some(new)), (true, None));
        assert!(
            t.preview_of(new).is_none(),
            "the full map replaces the preview"
        );
        tx.send(Answer::Preview(old, Arc::new(p))).unwrap();
        tx.send(Answer::Map(old, Ok(taught()))).unwrap();
        assert_eq!(t.poll(Some(new)), (false, None));
        assert_eq!(t.map.as_ref().unwrap().key, new, "the newer map stays");
        assert_eq!(t.preview.as_ref().unwrap().0, new);
    }

    #[test]
    fn a_stopped_request_answers_nothing_and_a_running_one_its_preview_then_its_map() {
        let mut cache = None;
        let mut sent = Vec::new();
        answer(&request((3, 1)), &mut cache, &|| true, |a| sent.push(a));
        assert!(sent.is_empty(), "a newer request waits: nothing is sent");
        answer(&request((4, 1)), &mut cache, &|| false, |a| sent.push(a));
        let want = taught().probabilities;
        match sent.as_slice() {
            [Answer::Preview(k, p), Answer::Map(k2, Ok(m))] => {
                assert_eq!((*k, *k2), ((4, 1), (4, 1)));
                assert_eq!((p.width, p.height), (12, 10));
                assert_eq!(m.probabilities, want, "the full map is predict's");
            }
            _ => panic!("preview then map expected"),
        }
    }

    /// Through the real thread: a request that a newer one followed gives no map and
    /// no preview, whether the thread finds it in the queue or already working on it.
    #[test]
    fn of_two_quick_requests_only_the_newer_is_answered() {
        let newest = Arc::new(AtomicU64::new(0));
        let (tx, rx) = spawn(None, Arc::default(), newest.clone());
        let (mut a, mut b) = (request((5, 1)), request((6, 1)));
        (a.seq, b.seq) = (1, 2);
        // The newer is asked before the thread can have finished the older.
        newest.store(2, Ordering::Release);
        tx.send(Message::Teach(a)).unwrap();
        tx.send(Message::Teach(b)).unwrap();
        let mut keys = Vec::new();
        loop {
            match rx.recv_timeout(std::time::Duration::from_secs(60)) {
                Ok(Answer::Map(k, m)) => {
                    assert!(m.is_ok());
                    keys.push(k);
                    break;
                }
                Ok(Answer::Preview(k, _)) => keys.push(k),
                Err(e) => panic!("no map came: {e}"),
            }
        }
        assert_eq!(keys, [(6, 1), (6, 1)], "the newer's preview and map only");
    }
}
