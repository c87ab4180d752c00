//! `segment`: the command line's flags (as the Python layer spells them) parsed by the
//! command line's clap definitions, one [`Job`] run with the GIL released, and the
//! finished run ([`Segmentation`]) read back as the CLI's exports.

use crate::arrays::{image_samples, points_array, raster};
use crate::learn::{PyClassifier, StrokesIn};
use clap::{CommandFactory, Parser};
use numpy::PyArray2;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use topocontour::cli::{
    classifier_for, job_for, mode_of, run_loaded, teach_for, usage_line, Failure, RunSettings,
};
use topocontour::contours::ContourId;
use topocontour::evolution::Evolver;
use topocontour::evolution::Field;
use topocontour::io::folder::file_name;
use topocontour::io::{field_from_samples, ImageInfo, Outputs, PixelSize};
use topocontour::job::JobRun;
use topocontour::learn::{Classifier, Teach};

/// The flags `segment` and `batch` share, parsed as the command line parses them.
#[derive(Parser)]
#[command(name = "topocontour segment")]
struct Flags {
    #[command(flatten)]
    run: RunSettings,
}

/// A failure as the Python exception it is: bad input (the CLI's exit 2) a ValueError.
pub(crate) fn raise(f: Failure) -> PyErr {
    if f.code == 2 {
        PyValueError::new_err(f.message)
    } else {
        PyRuntimeError::new_err(f.message)
    }
}

pub(crate) fn bad(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// `argv` (`--wrap=6`, `--object=dark`, …) as the settings, or clap's message in the
/// CLI's one line.
fn settings(argv: Vec<String>) -> PyResult<RunSettings> {
    let args = std::iter::once("segment".to_string()).chain(argv);
    Flags::try_parse_from(args)
        .map(|f| f.run)
        .map_err(|e| bad(usage_line(&e)))
}

/// What teaches a run in memory (`classifier=` a [`PyClassifier`], `strokes=` an
/// array): it replaces the `--classifier` / `--train` placeholders the flags then hold
/// (kept there only so clap refuses the two together with its own line).
pub enum TeachIn {
    Classifier(Arc<Classifier>),
    Strokes(StrokesIn),
}

impl TeachIn {
    fn of(teach: Option<&Bound<'_, PyAny>>) -> PyResult<Option<TeachIn>> {
        let Some(t) = teach else { return Ok(None) };
        if let Ok(c) = t.cast::<PyClassifier>() {
            return Ok(Some(TeachIn::Classifier(c.get().inner.clone())));
        }
        Ok(Some(TeachIn::Strokes(StrokesIn::of(t)?)))
    }

    fn teach(self, image: &Field) -> PyResult<Teach> {
        Ok(match self {
            TeachIn::Classifier(c) => Teach::Classifier(c),
            TeachIn::Strokes(s) => Teach::strokes(s.read(image.width, image.height).map_err(bad)?),
        })
    }
}

/// The settings, with any in-memory teacher standing in for its flag.
fn settings_with(
    argv: Vec<String>,
    teach: Option<&Bound<'_, PyAny>>,
) -> PyResult<(RunSettings, Option<TeachIn>)> {
    let mut run = settings(argv)?;
    let teach = TeachIn::of(teach)?;
    if teach.is_some() {
        // Taught in memory: the engine is a taught run's, as with the flags.
        run.mode = Some(mode_of(&run));
        run.train = None;
        run.classifier = None;
    }
    Ok((run, teach))
}

/// The teacher of a run on `image`: the one in memory, else the flags'.
fn teacher(
    run: &RunSettings,
    given: Option<TeachIn>,
    flagged: Option<&Teach>,
    image: &Field,
) -> PyResult<Option<Teach>> {
    match given {
        Some(t) => t.teach(image).map(Some),
        None => teach_for(run, flagged, image).map_err(raise),
    }
}

/// Runs the settings on an image array; `name` stands for its file (the JSON's `image`,
/// messages); `teach` is a classifier or strokes array given in memory.
#[pyfunction]
#[pyo3(signature = (image, argv, name, teach = None))]
pub fn segment_array(
    py: Python<'_>,
    image: &Bound<'_, PyAny>,
    argv: Vec<String>,
    name: String,
    teach: Option<&Bound<'_, PyAny>>,
) -> PyResult<Segmentation> {
    let (run, given) = settings_with(argv, teach)?;
    if run.page.is_some() {
        return Err(bad("page applies to a file; an array is one page"));
    }
    let (width, height, owned) = image_samples(image)?;
    py.detach(move || {
        let field = field_from_samples(&name, width, height, owned.samples()).map_err(bad)?;
        drop(owned);
        let flagged = classifier_for(&run).map_err(raise)?;
        let mut job = job_for(Path::new(&name), &run).map_err(raise)?;
        job.teach = teacher(&run, given, flagged.as_ref(), &field)?;
        let info = ImageInfo {
            pages: 1,
            pixel_size: None,
        };
        let done = run_loaded(&mut job, &run, field, info).map_err(raise)?;
        Ok(Segmentation::of(done, file_name(Path::new(&name))))
    })
}

/// Runs the settings on an image file (page `page=` of a stack), as `topocontour segment
/// PATH` does.
#[pyfunction]
#[pyo3(signature = (path, argv, teach = None))]
pub fn segment_path(
    py: Python<'_>,
    path: PathBuf,
    argv: Vec<String>,
    teach: Option<&Bound<'_, PyAny>>,
) -> PyResult<Segmentation> {
    let (run, given) = settings_with(argv, teach)?;
    py.detach(move || {
        let flagged = classifier_for(&run).map_err(raise)?;
        let mut job = job_for(&path, &run).map_err(raise)?;
        let (image, info) = job.load().map_err(bad)?;
        job.teach = teacher(&run, given, flagged.as_ref(), &image)?;
        let done = run_loaded(&mut job, &run, image, info).map_err(raise)?;
        Ok(Segmentation::of(done, file_name(&path)))
    })
}

/// Every flag of the settings: (long name, value name or "" for a switch, the values it
/// takes or "", help), in the order `topocontour segment --help` lists them.
#[pyfunction]
pub fn segment_flags() -> Vec<(String, String, String, String)> {
    flags_of(&Flags::command(), &[])
}

/// The flags of `cmd` but those named in `skip`, as [`segment_flags`] lists them.
pub fn flags_of(cmd: &clap::Command, skip: &[&str]) -> Vec<(String, String, String, String)> {
    cmd.get_arguments()
        .filter_map(|a| {
            let long = a.get_long()?.to_string();
            if skip.contains(&long.as_str()) {
                return None;
            }
            let value = if a.get_action().takes_values() {
                let names = a.get_value_names().unwrap_or_default();
                let names: Vec<String> = names.iter().map(|n| n.to_string()).collect();
                match names.is_empty() {
                    true => a.get_id().to_string().to_uppercase(),
                    false => names.join(" "),
                }
            } else {
                String::new()
            };
            let choices: Vec<String> = a
                .get_possible_values()
                .iter()
                .filter(|v| !v.is_hide_set())
                .map(|v| v.get_name().to_string())
                .collect();
            let help = a.get_help().map(|h| h.to_string()).unwrap_or_default();
            Some((long, value, choices.join(", "), help))
        })
        .collect()
}

/// A finished run: its contours, events and the CLI's exports.
#[pyclass(module = "topocontour._core")]
pub struct Segmentation {
    ev: Evolver,
    name: String,
    pixel: Option<PixelSize>,
    classifier: Option<Arc<Classifier>>,
}

impl Segmentation {
    fn of(run: JobRun, name: String) -> Self {
        Segmentation {
            ev: run.ev,
            name,
            pixel: run.pixel,
            classifier: run.taught.map(|t| t.classifier),
        }
    }

    fn outputs(&self) -> Outputs<'_> {
        Outputs::of(&self.ev, self.ev.contours(), &self.name).with_pixel_size(self.pixel.clone())
    }
}

fn ids(v: &[ContourId]) -> Vec<u32> {
    v.iter().map(|c| c.0).collect()
}

#[pymethods]
impl Segmentation {
    /// Every ring (outer rings and holes) in the JSON's order.
    #[getter]
    fn contours<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let set = self.ev.contours();
        let list = PyList::empty(py);
        for (id, parent) in set.parents() {
            let d = PyDict::new(py);
            d.set_item("id", id.0)?;
            d.set_item("hole", set.is_hole(id))?;
            d.set_item("parent", parent.map(|p| p.0))?;
            d.set_item("area", set.signed_area(id).abs())?;
            d.set_item("points", points_array(py, &set.ring_points(id)))?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The topology events: kind, frame and the contours involved.
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for e in self.ev.events() {
            let d = PyDict::new(py);
            d.set_item("kind", e.event.kind())?;
            d.set_item("frame", e.frame)?;
            d.set_item("contours", ids(&e.event.contours()))?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// Frames run.
    #[getter]
    fn frames(&self) -> usize {
        self.ev.frames()
    }

    /// The classifier that taught the run (trained on `strokes=`, or the one given), as
    /// `segment --save-classifier` saves it; None for a run not taught.
    #[getter]
    fn classifier(&self) -> Option<PyClassifier> {
        self.classifier.clone().map(|inner| PyClassifier { inner })
    }

    /// Whether the contours settled before the frame limit.
    #[getter]
    fn converged(&self) -> bool {
        self.ev.is_converged()
    }

    /// (height, width) of the image.
    #[getter]
    fn shape(&self) -> (usize, usize) {
        let (w, h) = self.ev.size();
        (h, w)
    }

    /// The label image: each object's number (1, 2, … as the CSV, GeoJSON and the CLI's
    /// `--labels` give it), 0 outside, as a (height, width) uint32 array.
    fn labels<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<u32>> {
        let (w, h) = self.ev.size();
        let labels = py.detach(|| self.outputs().labels());
        raster(py, labels, w, h)
    }

    /// The mask: true where a pixel's centre lies inside (the CLI's `--mask` is 255 there).
    fn mask<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<bool>> {
        let (w, h) = self.ev.size();
        let mask: Vec<bool> = py.detach(|| self.outputs().mask().iter().map(|&m| m != 0).collect());
        raster(py, mask, w, h)
    }

    /// The CLI's `--json` document, byte for byte.
    fn to_json(&self, py: Python<'_>) -> String {
        py.detach(|| self.outputs().json())
    }

    /// The CLI's `--geojson` document (QuPath's polygons and measurements).
    fn to_geojson(&self, py: Python<'_>) -> String {
        py.detach(|| self.outputs().geojson())
    }

    /// The CLI's `--csv` table, one row per object.
    fn to_csv(&self, py: Python<'_>) -> String {
        py.detach(|| self.outputs().csv())
    }

    /// The CLI's `--svg` drawing of the regions.
    fn to_svg(&self, py: Python<'_>) -> String {
        py.detach(|| self.outputs().svg())
    }

    fn __repr__(&self) -> String {
        let set = self.ev.contours();
        format!(
            "<topocontour.Result {}: {} contours, {} events, {} frames>",
            self.name,
            set.contour_count(),
            self.ev.events().len(),
            self.ev.frames()
        )
    }
}
