//! What a run records besides its contours: the topology events with their frame
//! ([`FrameEvent`]) and the user's interventions ([`Edit`]), which a session replays.

use super::forces::ForceWeights;
use crate::geometry::Point;
use crate::topology::TopologyEvent;

/// A topology event with the frame it happened in.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct FrameEvent {
    /// Frames done when it happened.
    pub frame: usize,
    /// What happened.
    #[serde(flatten)]
    pub event: TopologyEvent,
}

/// A user's intervention in a run, at the frame it was made: what a session replays.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "edit", rename_all = "snake_case")]
pub enum Edit {
    /// New force weights and step from this frame on.
    Forces {
        /// Frames done when it was made.
        frame: usize,
        /// The new weights.
        weights: ForceWeights,
        /// The new step, in grid spacings.
        step: f64,
    },
    /// A hand drag of a contour vertex ([`super::Evolver::hand_drag`]).
    Drag {
        /// Frames done when it was made.
        frame: usize,
        /// The vertex.
        vertex: u32,
        /// Where to.
        to: Point,
    },
    /// A brush stroke ([`super::Evolver::brush`]).
    Brush {
        /// Frames done when it was made.
        frame: usize,
        /// Where the brush's centre started.
        from: Point,
        /// Where it ended.
        to: Point,
        /// The brush's radius, pixels.
        radius: f64,
    },
    /// A contour deleted by hand ([`super::Evolver::delete_contour`]).
    Delete {
        /// Frames done when it was made.
        frame: usize,
        /// The contour.
        contour: u32,
    },
}

impl Edit {
    /// Frames done when the edit was made.
    pub fn frame(&self) -> usize {
        match *self {
            Edit::Forces { frame, .. }
            | Edit::Drag { frame, .. }
            | Edit::Brush { frame, .. }
            | Edit::Delete { frame, .. } => frame,
        }
    }
}
