//! Teaching by example from Python: `train(image, strokes)` returns a [`PyClassifier`]
//! (the model `topocontour train` writes, byte for byte when saved), which `segment`
//! applies in memory; strokes given as an array teach a run without a file.

use crate::arrays::{image_samples, Owned};
use numpy::{PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;
use topocontour::cli::classifier_of;
use topocontour::evolution::Field;
use topocontour::io::folder::file_name;
use topocontour::io::{field_from_samples, load_image_page, write_atomic};
use topocontour::learn::{Classifier, FeatureSet, StrokeError, Strokes};

/// An image handed over: an array (copied while the GIL is held) or a file to load.
pub enum Image {
    Array(usize, usize, Owned, String),
    Path(PathBuf),
}

impl Image {
    /// An array or a path (`name` stands for an array's file).
    pub fn of(image: &Bound<'_, PyAny>, name: &str) -> PyResult<Image> {
        if let Ok(p) = image.extract::<PathBuf>() {
            return Ok(Image::Path(p));
        }
        let (w, h, owned) = image_samples(image)?;
        Ok(Image::Array(w, h, owned, name.to_string()))
    }

    /// The engine's field, as `topocontour` reads the file (page 1 of a stack), and the
    /// name the results give it.
    pub fn field(self) -> PyResult<(Field, String)> {
        match self {
            Image::Array(w, h, owned, name) => {
                let f = field_from_samples(&name, w, h, owned.samples()).map_err(bad)?;
                Ok((f, name))
            }
            Image::Path(p) => {
                let (f, _) = load_image_page(&p, 0).map_err(bad)?;
                Ok((f, p.display().to_string()))
            }
        }
    }
}

/// Strokes handed over: a uint8 label array (0 none, 1 background, 2 object, 3
/// boundary) or the PNG `--train` reads.
pub enum StrokesIn {
    Array(usize, usize, Vec<u8>),
    Path(PathBuf),
}

impl StrokesIn {
    pub fn of(strokes: &Bound<'_, PyAny>) -> PyResult<StrokesIn> {
        if let Ok(p) = strokes.extract::<PathBuf>() {
            return Ok(StrokesIn::Path(p));
        }
        let a = strokes.cast::<PyArray2<u8>>().map_err(|_| {
            PyTypeError::new_err("strokes must be a 2-D uint8 label array or the path of a PNG")
        })?;
        let (h, w) = (a.shape()[0], a.shape()[1]);
        let labels = a.readonly().as_array().iter().copied().collect();
        Ok(StrokesIn::Array(w, h, labels))
    }

    /// The strokes checked against a `width` × `height` image, in the order
    /// `Strokes::read` checks a file: the size first, then the values.
    pub fn read(self, width: usize, height: usize) -> Result<Strokes, StrokeError> {
        match self {
            StrokesIn::Path(p) => Strokes::read(&p, width, height),
            StrokesIn::Array(w, h, labels) => Strokes::for_image(w, h, labels, width, height),
        }
    }
}

fn bad(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(message.to_string())
}

/// A trained pixel classifier: `segment(image, classifier=…)` applies it.
#[pyclass(name = "Classifier", module = "topocontour._core", frozen)]
pub struct PyClassifier {
    pub inner: Arc<Classifier>,
}

#[pymethods]
impl PyClassifier {
    /// Writes the classifier file (`topocontour train --out`'s bytes), atomically.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let bytes = topocontour::io::classifier::to_bytes(&self.inner);
        py.detach(|| write_atomic(&path, &bytes)).map_err(bad)
    }

    /// Reads a classifier file (from `train`, `save` or `segment --save-classifier`),
    /// refused with the CLI's line when it does not fit this build.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<PyClassifier> {
        let c = py
            .detach(|| topocontour::io::classifier::read(&path))
            .map_err(bad)?;
        Ok(PyClassifier { inner: Arc::new(c) })
    }

    /// Its classes, by name: "background", "object", "boundary".
    #[getter]
    fn classes(&self) -> Vec<&'static str> {
        self.inner.labels.iter().map(|&l| class_name(l)).collect()
    }

    /// The names of the images it was trained on.
    #[getter]
    fn images(&self) -> Vec<String> {
        self.inner.images.clone()
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyClassifier>()
            .is_ok_and(|o| *o.get().inner == *self.inner)
    }

    fn __repr__(&self) -> String {
        format!(
            "<topocontour.Classifier of {} trained on {}>",
            self.classes().join(", "),
            self.inner.images.join(", ")
        )
    }
}

fn class_name(label: u8) -> &'static str {
    ["none", "background", "object", "boundary"][label.min(3) as usize]
}

/// `train(images, strokes, names)`: one classifier from each image's strokes, as
/// `topocontour train IMAGE STROKES … --out` trains it.
#[pyfunction]
pub fn train(
    py: Python<'_>,
    images: Vec<Bound<'_, PyAny>>,
    strokes: Vec<Bound<'_, PyAny>>,
    names: Vec<String>,
) -> PyResult<PyClassifier> {
    if images.is_empty() || images.len() != strokes.len() || names.len() != images.len() {
        return Err(bad(format!(
            "train takes pairs of an image and its strokes; got {} images and {} strokes",
            images.len(),
            strokes.len()
        )));
    }
    let inputs: Vec<(Image, StrokesIn)> = images
        .iter()
        .zip(&strokes)
        .zip(&names)
        .map(|((i, s), n)| Ok((Image::of(i, n)?, StrokesIn::of(s)?)))
        .collect::<PyResult<_>>()?;
    let clf = py.detach(move || {
        let set = FeatureSet::default();
        let mut taught = Vec::new();
        let mut names = Vec::new();
        for (image, strokes) in inputs {
            let (field, name) = image.field()?;
            let s = strokes
                .read(field.width, field.height)
                .map_err(|e| bad(format!("{name}: {e}")))?;
            taught.push((set.compute(field.width, field.height, &field.data), s));
            names.push(file_name(std::path::Path::new(&name)));
        }
        classifier_of(set, &taught, names).map_err(|f| bad(f.message))
    })?;
    Ok(PyClassifier {
        inner: Arc::new(clf),
    })
}
