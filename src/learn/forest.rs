//! A random forest (Breiman 2001) of CART trees with Gini splits, bootstrap samples and
//! √F features tried per split, as scikit-learn's `RandomForestClassifier` and ilastik's
//! vigra forest grow them; seeded, so one training set always gives one forest.
//!
//! Why our own and not smartcore's or linfa-ensemble's: the contours need class
//! *probabilities* on every pixel, and both crates' forests vote labels only (smartcore's
//! measured here, linfa-ensemble's not); and
//! prediction is the cost that repeats (every image, every stroke in the app): on the
//! 512² fluorescence case with 49 features and 50 trees of depth ≤ 10, smartcore 0.7
//! predicted the labels in 0.28 CPU seconds, ours the probabilities in 0.13
//! (docs/decisions.md 2026-12-01, `LEARN_BENCH_SMARTCORE=1 cargo bench --bench learn --
//! IMAGE STROKES`; the default is 32 trees since, see [`ForestParams`]). Two choices
//! make ours fast:
//! - training bins each feature into at most [`BINS`] quantile intervals of the
//!   training values (as LightGBM and scikit-learn's histogram forests do), so a split
//!   search is a histogram per feature rather than a sort; thresholds are the midpoints
//!   between training values, as CART's;
//! - prediction walks a chunk of pixels through one tree at a time, eight neighbouring
//!   pixels in lockstep, every leaf looping to itself until all eight have arrived
//!   (a child's index says whether it is a leaf, so arriving costs no extra round;
//!   trees here are shallow: 1.1 and 2.5 splits per pixel and tree on two public
//!   cases; left or right is an index, not a branch, since no predictor can guess
//!   it): the walks' loads overlap, the one branch is predictable (neighbours
//!   mostly end in leaves of one depth), and the chunk's features, copied into one
//!   buffer so that a step's value is one load away from it, stay in cache across
//!   the trees; the walk indexes without bounds checks (its indices are made
//!   in range once per image, where [`Forest::predictor`] lays the forest out) and a
//!   leaf's values lie at its own index, not behind a lookup.
//!
//! tests/learn_forest.rs checks the predictions against smartcore's forest trained on
//! the same data.

/// Largest number of bins a feature is cut into for the split search.
pub const BINS: usize = 64;

/// Pixels predicted together: their features stay in cache across the trees.
const CHUNK: usize = 256;

/// How a forest is grown.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ForestParams {
    /// Number of trees.
    pub trees: usize,
    /// Largest depth of a tree (the root is depth 0).
    pub max_depth: usize,
    /// Seed of the bootstrap and feature draws.
    pub seed: u64,
}

impl Default for ForestParams {
    /// 32 trees of depth at most 10. scikit-learn's trainable segmentation, as
    /// `shared/tools/peer.py` runs it, grows 50; 32 gave the same scores with the
    /// strokes of every public real case (mean Dice and SEG within +0.003) in a third
    /// less prediction time (docs/decisions.md, 2026-12-02).
    fn default() -> Self {
        ForestParams {
            trees: 32,
            max_depth: 10,
            seed: 0,
        }
    }
}

/// A node: a split (`feature`, `threshold`: values ≤ it go `left`), or a leaf whose
/// children are itself (so its threshold does not matter).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Node {
    /// The feature compared.
    pub feature: u32,
    /// Values ≤ this go left.
    pub threshold: f32,
    /// The left child.
    pub left: u32,
    /// The right child.
    pub right: u32,
}

/// The flag of a node index that is a leaf's, in [`Walk`].
const LEAF: u32 = 1 << 31;

/// A node as the prediction walks it: its children's indices carry [`LEAF`] when they
/// are leaves, so the walk sees that all its lanes have arrived without reading a node.
#[derive(Clone, Copy)]
struct Step {
    /// Where the feature's values start in a chunk's buffer: its index · [`CHUNK`].
    feature: u32,
    threshold: f32,
    /// Left (values ≤ threshold), right.
    child: [u32; 2],
}

/// The forest laid out for prediction: its steps, each tree's root (with [`LEAF`]) and,
/// `classes` per step, the leaves' class distributions already divided by the number
/// of trees (indexed by the step, so arriving needs no lookup of where they lie).
struct Walk {
    steps: Vec<Step>,
    roots: Vec<u32>,
    values: Vec<f32>,
}

/// A trained forest.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Forest {
    /// Number of classes (indices 0..classes).
    pub classes: usize,
    /// Number of features a sample has.
    pub features: usize,
    /// All trees' nodes.
    pub nodes: Vec<Node>,
    /// Per tree, its root and its depth.
    pub roots: Vec<(u32, u32)>,
    /// Per node, where its class distribution starts in `leaf_values` (leaves only).
    pub leaf_of: Vec<u32>,
    /// Class distributions of the leaves, `classes` values each.
    pub leaf_values: Vec<f32>,
}

/// A [`Forest`] laid out for prediction ([`Forest::predictor`]).
pub struct Predictor<'a> {
    forest: &'a Forest,
    walk: Walk,
}

impl Predictor<'_> {
    /// As [`Forest::predict_block`].
    pub fn predict_block(&self, planes: &[&[f32]], start: usize, out: &mut [f32]) {
        let c = self.forest.classes;
        let len = out.len() / c;
        assert!(
            planes.len() == self.forest.features && planes.iter().all(|p| p.len() >= start + len)
        );
        // A chunk of neighbouring pixels through every tree, copied into one buffer
        // (feature f of pixel k at f · CHUNK + k): the eight lanes of a walk that test
        // one feature read one cache line, the chunk stays in cache across the trees,
        // and a walk's value is one load after its step's, not two (the feature's
        // slice, then the value), in walks that are chains of dependent loads.
        let mut buf = vec![0.0f32; planes.len() * CHUNK];
        for from in (0..len).step_by(CHUNK) {
            let n = CHUNK.min(len - from);
            for (dst, p) in buf.chunks_exact_mut(CHUNK).zip(planes) {
                dst[..n].copy_from_slice(&p[start + from..start + from + n]);
            }
            self.forest
                .walk_chunk(&buf, &mut out[from * c..(from + n) * c], &self.walk);
        }
    }
}

/// SplitMix64: small, seeded, and the same on every platform.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The training data binned: per feature its thresholds and each sample's bin.
struct Binned {
    /// Per feature, the bin upper edges (values ≤ edge[b] are in bins 0..=b).
    edges: Vec<Vec<f32>>,
    /// Feature-major: bins[f * n + i].
    bins: Vec<u8>,
    n: usize,
}

fn bin_features(x: &[f32], n: usize, nf: usize) -> Binned {
    let mut edges = Vec::with_capacity(nf);
    let mut bins = vec![0u8; nf * n];
    let mut column: Vec<f32> = Vec::with_capacity(n);
    for f in 0..nf {
        column.clear();
        column.extend((0..n).map(|i| x[i * nf + f]));
        let mut sorted = column.clone();
        sorted.sort_by(f32::total_cmp);
        // Cut between distinct values at even ranks: at most BINS − 1 edges.
        let mut e: Vec<f32> = Vec::new();
        for k in 1..BINS {
            let i = k * n / BINS;
            if i == 0 || i >= n {
                continue;
            }
            // The first change of value at or after rank i.
            let Some(j) = (i..n).find(|&j| sorted[j] > sorted[j - 1]) else {
                break;
            };
            let mid = 0.5 * (sorted[j - 1] + sorted[j]);
            if e.last().is_none_or(|&last| mid > last) {
                e.push(mid);
            }
        }
        for (i, &v) in column.iter().enumerate() {
            bins[f * n + i] = e.partition_point(|&edge| edge < v) as u8;
        }
        edges.push(e);
    }
    Binned { edges, bins, n }
}

/// Gini impurity times weight: w − Σ c²/w.
#[inline]
fn gini_mass(counts: &[f64]) -> f64 {
    let w: f64 = counts.iter().sum();
    if w <= 0.0 {
        0.0
    } else {
        w - counts.iter().map(|c| c * c).sum::<f64>() / w
    }
}

struct Grower<'a> {
    data: &'a Binned,
    y: &'a [u8],
    weight: &'a [f64],
    classes: usize,
    mtry: usize,
    max_depth: usize,
    rng: Rng,
    nodes: Vec<Node>,
    leaf_of: Vec<u32>,
    leaf_values: Vec<f32>,
    depth: u32,
}

impl Grower<'_> {
    fn counts(&self, idx: &[u32]) -> Vec<f64> {
        let mut c = vec![0.0; self.classes];
        for &i in idx {
            c[self.y[i as usize] as usize] += self.weight[i as usize];
        }
        c
    }

    /// The best (feature, bin) among `mtry` random features, if any split separates.
    fn best_split(&mut self, idx: &[u32], total: &[f64]) -> Option<(usize, usize)> {
        let nf = self.data.edges.len();
        let c = self.classes;
        let parent = gini_mass(total);
        let mut order: Vec<usize> = (0..nf).collect();
        let mut best: Option<(f64, usize, usize)> = None;
        let mut hist = vec![0.0; BINS * c];
        for k in 0..self.mtry.min(nf) {
            let j = k + self.rng.below(nf - k);
            order.swap(k, j);
            let f = order[k];
            let nb = self.data.edges[f].len() + 1;
            if nb < 2 {
                continue;
            }
            hist[..nb * c].iter_mut().for_each(|h| *h = 0.0);
            let col = &self.data.bins[f * self.data.n..(f + 1) * self.data.n];
            for &i in idx {
                let i = i as usize;
                hist[col[i] as usize * c + self.y[i] as usize] += self.weight[i];
            }
            let mut left = vec![0.0; c];
            for b in 0..nb - 1 {
                for (l, h) in left.iter_mut().zip(&hist[b * c..(b + 1) * c]) {
                    *l += h;
                }
                let right: Vec<f64> = total.iter().zip(&left).map(|(t, l)| t - l).collect();
                let (wl, wr): (f64, f64) = (left.iter().sum(), right.iter().sum());
                if wl <= 0.0 || wr <= 0.0 {
                    continue;
                }
                let gain = parent - gini_mass(&left) - gini_mass(&right);
                if gain > 1e-9 && best.is_none_or(|(g, _, _)| gain > g) {
                    best = Some((gain, f, b));
                }
            }
        }
        best.map(|(_, f, b)| (f, b))
    }

    /// Grows the subtree of the samples `idx` at `depth`; returns its node index.
    fn grow(&mut self, idx: &mut [u32], depth: usize) -> u32 {
        let at = self.nodes.len() as u32;
        self.depth = self.depth.max(depth as u32);
        let total = self.counts(idx);
        let pure = total.iter().filter(|&&v| v > 0.0).count() <= 1;
        let split = if pure || depth >= self.max_depth || idx.len() < 2 {
            None
        } else {
            self.best_split(idx, &total)
        };
        let Some((f, b)) = split else {
            let w: f64 = total.iter().sum();
            self.nodes.push(Node {
                feature: 0,
                // Either way leads back here; finite, so the file (JSON) holds it.
                threshold: 0.0,
                left: at,
                right: at,
            });
            self.leaf_of.push(self.leaf_values.len() as u32);
            self.leaf_values
                .extend(total.iter().map(|&v| (v / w.max(1e-12)) as f32));
            return at;
        };
        self.nodes.push(Node {
            feature: f as u32,
            threshold: self.data.edges[f][b],
            left: at + 1,
            right: 0,
        });
        self.leaf_of.push(u32::MAX);
        let col = &self.data.bins[f * self.data.n..(f + 1) * self.data.n];
        // Partition in place: bins ≤ b first.
        let mut m = 0;
        for k in 0..idx.len() {
            if col[idx[k] as usize] as usize <= b {
                idx.swap(k, m);
                m += 1;
            }
        }
        let (l, r) = idx.split_at_mut(m);
        self.grow(l, depth + 1);
        let right = self.grow(r, depth + 1);
        self.nodes[at as usize].right = right;
        at
    }
}

impl Forest {
    /// Trains on `n` samples of `nf` features (`x` row-major, `n × nf`) with class
    /// indices `y` (< `classes`).
    ///
    /// # Panics
    /// If the sizes disagree, `n` is 0 or a class index is out of range.
    pub fn train(x: &[f32], y: &[u8], nf: usize, classes: usize, p: &ForestParams) -> Forest {
        let n = y.len();
        assert!(n > 0 && x.len() == n * nf, "training set size");
        assert!(y.iter().all(|&c| (c as usize) < classes), "class index");
        let data = bin_features(x, n, nf);
        let mtry = ((nf as f64).sqrt().floor() as usize).max(1);
        let mut forest = Forest {
            classes,
            features: nf,
            nodes: Vec::new(),
            roots: Vec::new(),
            leaf_of: Vec::new(),
            leaf_values: Vec::new(),
        };
        let mut rng = Rng(p.seed);
        for _ in 0..p.trees.max(1) {
            // The bootstrap as weights: how often each sample was drawn.
            let mut weight = vec![0.0; n];
            for _ in 0..n {
                weight[rng.below(n)] += 1.0;
            }
            let mut idx: Vec<u32> = (0..n as u32)
                .filter(|&i| weight[i as usize] > 0.0)
                .collect();
            let mut g = Grower {
                data: &data,
                y,
                weight: &weight,
                classes,
                mtry,
                max_depth: p.max_depth,
                rng: Rng(rng.next()),
                nodes: Vec::new(),
                leaf_of: Vec::new(),
                leaf_values: Vec::new(),
                depth: 0,
            };
            g.grow(&mut idx, 0);
            forest.append(g.nodes, g.leaf_of, g.leaf_values, g.depth);
        }
        forest
    }

    /// Adds one tree (node indices local to it).
    fn append(&mut self, nodes: Vec<Node>, leaf_of: Vec<u32>, values: Vec<f32>, depth: u32) {
        let base = self.nodes.len() as u32;
        let vbase = self.leaf_values.len() as u32;
        self.roots.push((base, depth));
        self.nodes.extend(nodes.into_iter().map(|nd| Node {
            left: nd.left + base,
            right: nd.right + base,
            ..nd
        }));
        self.leaf_of.extend(
            leaf_of
                .into_iter()
                .map(|o| if o == u32::MAX { o } else { o + vbase }),
        );
        self.leaf_values.extend(values);
    }

    /// Adds the mean class distribution of pixels `start..start + out.len() / classes`
    /// into `out` (`classes` per pixel, zeroed by the caller); `planes[f]` holds feature
    /// f of every pixel.
    pub fn predict_block(&self, planes: &[&[f32]], start: usize, out: &mut [f32]) {
        self.predictor().predict_block(planes, start, out);
    }

    /// The forest laid out for prediction once, for many [`Predictor::predict_block`]
    /// calls (the rows of an image).
    pub fn predictor(&self) -> Predictor<'_> {
        Predictor {
            forest: self,
            walk: self.walk(),
        }
    }

    /// Every tree over the pixels of `buf` (feature f of pixel k at `buf[f · CHUNK +
    /// k]`, k < CHUNK), summed into `out`.
    fn walk_chunk(&self, buf: &[f32], out: &mut [f32], walk: &Walk) {
        const LANES: usize = 8;
        let c = self.classes;
        let n = out.len() / c;
        assert!(n > 0 && n <= CHUNK && buf.len() == self.features * CHUNK);
        let steps = &walk.steps[..];
        let values = &walk.values[..];
        for (&(_, depth), &start) in self.roots.iter().zip(&walk.roots) {
            for p in (0..n).step_by(LANES) {
                let lanes = LANES.min(n - p);
                // Lanes past the chunk's end re-read its last pixel.
                let px: [usize; LANES] = std::array::from_fn(|k| p + k.min(lanes - 1));
                let mut at = [start; LANES];
                // Eight walks in lockstep (a leaf loops to itself): the loads overlap,
                // and the one branch, "all eight in leaves" (their LEAF bits), is as
                // predictable as neighbouring pixels are alike.
                for _ in 0..depth {
                    if at.iter().fold(LEAF, |all, &a| all & a) != 0 {
                        break;
                    }
                    for k in 0..LANES {
                        // SAFETY: `Forest::walk` made every index a step holds (root,
                        // children) below `steps.len()` and every `feature` (an offset
                        // f · CHUNK) below `self.features · CHUNK`, which is
                        // `buf.len()` (asserted above), and px[k] < n ≤ CHUNK.
                        let (s, v) = unsafe {
                            let s = *steps.get_unchecked((at[k] & !LEAF) as usize);
                            let v = *buf.get_unchecked(s.feature as usize + px[k]);
                            (s, v)
                        };
                        // Values ≤ the threshold go left, NaN right (so "not ≤", not
                        // ">"): an index rather than a branch that no predictor could
                        // guess.
                        #[allow(clippy::neg_cmp_op_on_partial_ord)]
                        let right = !(v <= s.threshold) as usize;
                        at[k] = s.child[right];
                    }
                }
                for (k, &a) in at.iter().enumerate().take(lanes) {
                    let o = (a & !LEAF) as usize * c;
                    // SAFETY: `Forest::walk` made `values` `c` per step and `a` a
                    // step's index; p + k < n, so the pixel's `c` values lie in
                    // `out` (n · c long).
                    let (to, from) = unsafe {
                        (
                            out.get_unchecked_mut((p + k) * c..(p + k + 1) * c),
                            values.get_unchecked(o..o + c),
                        )
                    };
                    for (d, v) in to.iter_mut().zip(from) {
                        *d += v;
                    }
                }
            }
        }
    }

    /// The forest as [`Forest::walk_chunk`] reads it, every index in range so that its
    /// walk may index without bounds checks: a node with an index out of range (none
    /// that [`Forest::misfit`] passed can be reached) becomes a leaf with no class
    /// distribution.
    ///
    /// # Panics
    /// If the forest has no features or a root is out of range (`misfit` refuses both).
    fn walk(&self) -> Walk {
        let n = self.nodes.len();
        let c = self.classes;
        assert!(n < LEAF as usize, "node count");
        assert!(self.features > 0, "a forest without features");
        assert!(
            self.features.saturating_mul(CHUNK) <= u32::MAX as usize,
            "feature count"
        );
        assert!(
            self.roots.iter().all(|&(r, _)| (r as usize) < n),
            "a root out of range"
        );
        let fits = |nd: &Node| {
            (nd.left as usize) < n
                && (nd.right as usize) < n
                && (nd.feature as usize) < self.features
        };
        let is_leaf = |i: usize| {
            let nd = &self.nodes[i];
            !fits(nd) || (nd.left as usize == i && nd.right as usize == i)
        };
        let mark = |i: u32| if is_leaf(i as usize) { i | LEAF } else { i };
        let scale = 1.0 / self.roots.len() as f32;
        // Per step its tree's share of the class distribution (leaves; zero for splits,
        // which no walk ends in): the product each tree adds, as `v * scale` in the walk
        // would give it.
        let mut values = vec![0.0f32; n * c];
        for (i, dst) in values.chunks_exact_mut(c.max(1)).enumerate() {
            let o = self.leaf_of.get(i).map_or(usize::MAX, |&o| o as usize);
            let src = o.checked_add(c).and_then(|e| self.leaf_values.get(o..e));
            if let (true, Some(src)) = (is_leaf(i), src) {
                for (d, v) in dst.iter_mut().zip(src) {
                    *d = v * scale;
                }
            }
        }
        Walk {
            steps: self
                .nodes
                .iter()
                .enumerate()
                .map(|(i, nd)| {
                    if fits(nd) {
                        Step {
                            feature: nd.feature * CHUNK as u32,
                            threshold: nd.threshold,
                            child: [mark(nd.left), mark(nd.right)],
                        }
                    } else {
                        let me = i as u32 | LEAF;
                        Step {
                            feature: 0,
                            threshold: 0.0,
                            child: [me, me],
                        }
                    }
                })
                .collect(),
            roots: self.roots.iter().map(|&(r, _)| mark(r)).collect(),
            values,
        }
    }

    /// Why the forest cannot be walked over `features` features into `classes`
    /// classes (a damaged or foreign file), or `None`: every tree's walks end in a leaf
    /// within its depth, and every index is in range.
    pub fn misfit(&self, features: usize, classes: usize) -> Option<String> {
        if (self.features, self.classes) != (features, classes) {
            return Some(format!(
                "{} features and {} classes, expected {features} and {classes}",
                self.features, self.classes
            ));
        }
        let n = self.nodes.len();
        if self.leaf_of.len() != n || self.roots.is_empty() {
            return Some("node tables of different lengths".into());
        }
        let mut stack: Vec<(u32, u32)> = Vec::new();
        for &(root, depth) in &self.roots {
            stack.push((root, 0));
            while let Some((at, level)) = stack.pop() {
                let Some(nd) = self.nodes.get(at as usize) else {
                    return Some(format!("node {at} of {n}"));
                };
                if nd.left == at && nd.right == at {
                    let o = self.leaf_of[at as usize] as usize;
                    if o.checked_add(classes)
                        .is_none_or(|e| e > self.leaf_values.len())
                    {
                        return Some(format!("leaf {at} has no class distribution"));
                    }
                } else if level >= depth || nd.feature as usize >= features {
                    return Some(format!(
                        "node {at} splits past its tree's depth or features"
                    ));
                } else {
                    stack.extend([(nd.left, level + 1), (nd.right, level + 1)]);
                }
            }
        }
        None
    }

    /// The class distribution of one sample (`features` values).
    pub fn predict_one(&self, sample: &[f32]) -> Vec<f32> {
        let planes: Vec<&[f32]> = sample.chunks(1).collect();
        let mut out = vec![0.0; self.classes];
        self.predict_block(&planes, 0, &mut out);
        out
    }
}
