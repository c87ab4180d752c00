//! `track(movie, …)`: cells tracked through a movie by the CLI's own tracker
//! ([`topocontour::cli::tracker_for`], flags parsed by `topocontour track`'s clap
//! definitions), the GIL released; [`Tracks`] reads back what `track` writes (its JSON
//! and tracks CSV byte for byte, the CTC lineage, each frame's label image).

use crate::arrays::{image_samples, Owned};
use crate::run::{bad, flags_of, raise};
use clap::{CommandFactory, Parser};
use numpy::{IntoPyArray, PyArray3};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::PathBuf;
use topocontour::cli::{tracker_for, TrackArgs};
use topocontour::evolution::Field;
use topocontour::io::export::ctc;
use topocontour::io::field_from_samples;
use topocontour::io::movie::{normalise, Movie, MovieError};
use topocontour::track::{revise_labels, Lineage, TrackedFrame};

/// `topocontour track`'s flags, parsed as the command line parses them.
#[derive(Parser)]
#[command(name = "topocontour track")]
struct TrackFlags {
    #[command(flatten)]
    track: TrackArgs,
}

/// The flags that name output files: the Python result holds those outputs instead.
const OUTPUTS: [&str; 5] = ["ctc", "json", "tracks-csv", "overlay", "overlay-frame"];

/// Every flag of `track` that is a keyword of `topocontour.track`, as
/// [`crate::run::segment_flags`] lists them.
#[pyfunction]
pub fn track_flags() -> Vec<(String, String, String, String)> {
    flags_of(&TrackFlags::command(), &OUTPUTS)
}

/// The frames handed over: a movie file or folder, or 2-D arrays copied while the GIL is
/// held.
enum Frames {
    Path(PathBuf),
    Arrays(Vec<(usize, usize, Owned)>),
}

/// Tracks a movie (a path, or a list of 2-D frames named `name`) with the flags `argv`.
#[pyfunction]
pub fn track(
    py: Python<'_>,
    movie: &Bound<'_, PyAny>,
    argv: Vec<String>,
    name: String,
) -> PyResult<Tracks> {
    let frames = match movie.extract::<PathBuf>() {
        Ok(p) => Frames::Path(p),
        Err(_) => Frames::Arrays(
            movie
                .try_iter()?
                .map(|f| image_samples(&f?))
                .collect::<PyResult<_>>()?,
        ),
    };
    let label = match &frames {
        Frames::Path(p) => p.display().to_string(),
        Frames::Arrays(_) => name,
    };
    let args = ["track".to_string(), label.clone()].into_iter().chain(argv);
    let a = TrackFlags::try_parse_from(args)
        .map_err(|e| bad(topocontour::cli::usage_line(&e)))?
        .track;
    py.detach(move || match frames {
        Frames::Path(p) => {
            let movie = Movie::open(&p).map_err(bad)?;
            let (w, h) = movie.size();
            let read = movie.frames().map_err(bad)?;
            run(&a, label, w, h, read.map(|f| f.map_err(bad)))
        }
        Frames::Arrays(list) => {
            if list.len() < 2 {
                return Err(bad(MovieError::TooShort {
                    path: label,
                    frames: list.len(),
                }));
            }
            let (w, h) = (list[0].0, list[0].1);
            // Every frame the first's size, as the CLI checks a movie before tracking.
            if let Some((t, &(fw, fh, _))) =
                list.iter().enumerate().find(|(_, f)| (f.0, f.1) != (w, h))
            {
                return Err(bad(MovieError::SizeDiffers {
                    path: label,
                    frame: t,
                    at: String::new(),
                    width: fw,
                    height: fh,
                    first_width: w,
                    first_height: h,
                }));
            }
            let name = label.clone();
            let read = list.into_iter().map(move |(fw, fh, owned)| {
                let mut f = field_from_samples(&name, fw, fh, owned.samples()).map_err(bad)?;
                normalise(&mut f);
                Ok(f)
            });
            run(&a, label, w, h, read)
        }
    })
}

/// The CLI's tracking loop over `frames`, keeping what its outputs write.
fn run(
    a: &TrackArgs,
    name: String,
    w: usize,
    h: usize,
    frames: impl Iterator<Item = PyResult<Field>>,
) -> PyResult<Tracks> {
    let mut tracker = tracker_for(a, w, h).map_err(raise)?;
    let mut kept: Vec<TrackedFrame> = Vec::new();
    // The masks the CLI writes: each cell up to its frame's edges, once the next frame
    // can no longer revise it (a division taken back or dated there).
    let mut labels: Vec<u32> = Vec::new();
    let mut last: Option<(Vec<u32>, Field)> = None;
    let mut csv = String::from(ctc::CSV_HEADER);
    for image in frames {
        let image = image?;
        let frame = tracker.step(&image).map_err(bad)?;
        if let Some(before) = kept.last_mut() {
            before.revise(&frame);
        }
        if let Some((mut raw, before)) = last.take() {
            revise_labels(&mut raw, w, &frame);
            labels.extend(topocontour::image::widen::to_edges(&raw, &before));
        }
        last = Some((tracker.labels().to_vec(), image));
        kept.push(frame);
    }
    if let Some((raw, before)) = last {
        labels.extend(topocontour::image::widen::to_edges(&raw, &before));
    }
    for (frame, mask) in kept.iter().zip(labels.chunks_exact(w * h)) {
        csv.push_str(&ctc::csv_rows(frame.frame, mask, w, tracker.lineage()));
    }
    Ok(Tracks {
        name,
        size: (w, h),
        frames: kept,
        labels,
        lineage: tracker.lineage().clone(),
        csv,
    })
}

/// A tracked movie.
#[pyclass(module = "topocontour._core", frozen)]
pub struct Tracks {
    name: String,
    size: (usize, usize),
    frames: Vec<TrackedFrame>,
    labels: Vec<u32>,
    lineage: Lineage,
    csv: String,
}

#[pymethods]
impl Tracks {
    /// Per frame: frame, its cells (track, area, centroid, ring as an (N, 2) array) and
    /// the divisions whose children start there.
    #[getter]
    fn frames<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for f in &self.frames {
            let d = PyDict::new(py);
            d.set_item("frame", f.frame)?;
            let cells = PyList::empty(py);
            for o in &f.objects {
                let c = PyDict::new(py);
                c.set_item("track", o.track)?;
                c.set_item("area", o.area)?;
                c.set_item("centroid", (o.centroid.x, o.centroid.y))?;
                c.set_item("ring", crate::arrays::points_array(py, &o.ring))?;
                cells.append(c)?;
            }
            d.set_item("objects", cells)?;
            let divisions: Vec<(u32, [u32; 2])> =
                f.divisions.iter().map(|v| (v.parent, v.children)).collect();
            d.set_item("divisions", divisions)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Every track: label, first and last frame, parent (0: none), as res_track.txt.
    #[getter]
    fn tracks<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for t in self.lineage.tracks() {
            let d = PyDict::new(py);
            d.set_item("label", t.label)?;
            d.set_item("first", t.first)?;
            d.set_item("last", t.last)?;
            d.set_item("parent", t.parent)?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The divisions: (frame, parent, (child, child)).
    #[getter]
    fn divisions(&self) -> Vec<(usize, u32, [u32; 2])> {
        self.frames
            .iter()
            .flat_map(|f| f.divisions.iter().map(|d| (d.frame, d.parent, d.children)))
            .collect()
    }

    /// The track labels of every frame as a (frames, height, width) uint32 array: the
    /// values of the CLI's `--ctc` masks.
    fn labels<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<u32>> {
        let (w, h) = self.size;
        numpy::ndarray::Array3::from_shape_vec((self.frames.len(), h, w), self.labels.clone())
            .expect("a raster per frame")
            .into_pyarray(py)
    }

    /// The CLI's `--json` document, byte for byte.
    fn to_json(&self, py: Python<'_>) -> String {
        py.detach(|| ctc::json(&self.name, &self.frames, &self.lineage))
    }

    /// The CLI's `--tracks-csv` table.
    fn to_csv(&self) -> String {
        self.csv.clone()
    }

    /// The Cell Tracking Challenge's res_track.txt (the CLI's `--ctc OUT/res_track.txt`).
    fn to_ctc_tracks(&self) -> String {
        self.lineage.ctc_text()
    }

    fn __len__(&self) -> usize {
        self.frames.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "<topocontour.Tracks {}: {} frames, {} tracks>",
            self.name,
            self.frames.len(),
            self.lineage.tracks().len()
        )
    }
}
