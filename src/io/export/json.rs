//! The JSON document of the CLI contract (DESIGN.md): every ring with its parent and
//! area, the topology events with their frames, the run's engine and parameters. Keys
//! come out in alphabetical order, as they always have.

use super::Outputs;
use crate::contours::ContourId;
use serde::Serialize;

/// The whole document.
#[derive(Serialize)]
struct Document<'a> {
    contours: Vec<Contour>,
    converged: bool,
    events: Vec<Event>,
    frames: usize,
    height: usize,
    held: usize,
    image: &'a str,
    mode: &'static str,
    /// As a JSON object, so its keys are sorted like the document's.
    params: serde_json::Value,
    width: usize,
}

/// One ring.
#[derive(Serialize)]
struct Contour {
    area: f64,
    hole: bool,
    id: ContourId,
    parent: Option<ContourId>,
    points: Vec<[f64; 2]>,
}

/// One topology event.
#[derive(Serialize)]
struct Event {
    contours: Vec<ContourId>,
    frame: usize,
    kind: &'static str,
}

impl Outputs<'_> {
    /// The JSON document of the CLI contract.
    pub fn json(&self) -> String {
        let contours = self
            .set
            .parents()
            .into_iter()
            .map(|(id, parent)| Contour {
                area: self.set.signed_area(id).abs(),
                hole: self.set.is_hole(id),
                id,
                parent,
                points: self
                    .set
                    .ring_points(id)
                    .iter()
                    .map(|p| [p.x, p.y])
                    .collect(),
            })
            .collect();
        let events = self
            .events
            .iter()
            .map(|e| Event {
                contours: e.event.contours(),
                frame: e.frame,
                kind: e.event.kind(),
            })
            .collect();
        let doc = Document {
            contours,
            converged: self.converged,
            events,
            frames: self.frames,
            height: self.height,
            held: self.held,
            image: self.image,
            mode: self.params.mode.name(),
            params: serde_json::to_value(self.params).expect("parameters are plain data"),
            width: self.width,
        };
        serde_json::to_string(&doc).expect("JSON of plain data")
    }
}
