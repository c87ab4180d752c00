//! Settings kept between runs and sessions, and the contrast window of an image.

use super::command::Tool;
use crate::contours::BroadPhaseKind;
use crate::evolution::{Field, ForceWeights, Modality, Mode, Params, Polarity};
use std::path::PathBuf;

/// Settings kept between runs (eframe persistence).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Settings {
    /// Objects darker or brighter than the background.
    pub polarity: Polarity,
    /// The kind of image.
    pub modality: Modality,
    /// The engine.
    pub mode: Mode,
    /// The adaptive engine opens holes in clear background inside a region.
    pub open_holes: bool,
    /// The broad phase of the crossing search.
    pub broad_phase: BroadPhaseKind,
    /// The engine shown side by side with `mode`, if any.
    pub compare: Option<Mode>,
    /// Force weights.
    pub weights: ForceWeights,
    /// Largest step per frame, in grid spacings.
    pub step: f64,
    /// Smallest region or hole kept, square pixels.
    pub min_area: f64,
    /// Frames per second while playing.
    pub speed: f32,
    /// The canvas tool.
    pub tool: Tool,
    /// Contrast window (low, high) of the image on screen.
    pub contrast: (f32, f32),
    /// Fill regions on the canvas.
    pub show_fill: bool,
    /// Radius of the brush, image pixels.
    pub brush_radius: f64,
    /// The folder of the last file opened.
    pub last_dir: Option<PathBuf>,
}

impl Default for Settings {
    fn default() -> Self {
        let p = Params::default();
        Settings {
            polarity: Polarity::Dark,
            modality: Modality::Generic,
            mode: Mode::Adaptive,
            open_holes: p.open_holes,
            broad_phase: p.broad_phase,
            compare: None,
            weights: p.weights,
            step: p.step,
            min_area: p.min_area,
            speed: 30.0,
            tool: Tool::Seed,
            contrast: (0.0, 1.0),
            show_fill: true,
            brush_radius: 8.0,
            last_dir: None,
        }
    }
}

/// The contrast window of an image: its 0.5th and 99.5th percentiles (a sample of at most
/// a million pixels), at least 1/255 apart.
pub fn auto_contrast(f: &Field) -> (f32, f32) {
    let step = (f.data.len() / 1_000_000).max(1);
    let mut v: Vec<f32> = f.data.iter().step_by(step).copied().collect();
    let n = v.len();
    let at = |v: &mut Vec<f32>, q: f64| {
        let k = ((n - 1) as f64 * q).round() as usize;
        *v.select_nth_unstable_by(k, f32::total_cmp).1
    };
    let (lo, hi) = (at(&mut v, 0.005), at(&mut v, 0.995));
    if hi - lo < 1.0 / 255.0 {
        ((lo - 0.5 / 255.0).max(0.0), (hi + 0.5 / 255.0).min(1.0))
    } else {
        (lo, hi)
    }
}
