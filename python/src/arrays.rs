//! NumPy arrays in and out: a 2-D image copied into the engine's samples while the GIL is
//! held, fields and rasters handed back as arrays. An image's dtype is read as a TIFF
//! page of that sample type is (`topocontour::io`): 8 and 16 bit integers, signed or
//! not, by their type's range (a signed one shifted into the unsigned one, exactly);
//! wider integers and every float as float32, by their own range.

use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use std::path::PathBuf;
use topocontour::evolution::Field;
use topocontour::geometry::Point;
use topocontour::io::{load_image_page, Samples};

/// An image's samples, owned (copied out of the array before the GIL is released).
pub enum Owned {
    U8(Vec<u8>),
    U16(Vec<u16>),
    F32(Vec<f32>),
}

impl Owned {
    pub fn samples(&self) -> Samples<'_> {
        match self {
            Owned::U8(v) => Samples::U8(v),
            Owned::U16(v) => Samples::U16(v),
            Owned::F32(v) => Samples::F32(v),
        }
    }
}

/// A 2-D image's (width, height, samples), or the one-line reason it is not one.
pub fn image_samples(image: &Bound<'_, PyAny>) -> PyResult<(usize, usize, Owned)> {
    let array = image.cast::<PyUntypedArray>().map_err(|_| {
        PyTypeError::new_err(format!(
            "the image must be a NumPy array or a path, got {}",
            image
                .get_type()
                .name()
                .map(|n| n.to_string())
                .unwrap_or_default()
        ))
    })?;
    let shape = array.shape().to_vec();
    if shape.len() != 2 {
        return Err(PyValueError::new_err(format!(
            "the image must be a 2-D array (height, width), got shape {}",
            shape_text(&shape)
        )));
    }
    let (height, width) = (shape[0], shape[1]);
    // Every sample of `$t` through `$f` into the owned kind `$k`.
    macro_rules! read {
        ($t:ty, $k:ident, $f:expr) => {
            image
                .cast::<PyArray2<$t>>()
                .ok()
                .map(|a| Owned::$k(a.readonly().as_array().iter().map($f).collect()))
        };
    }
    let owned = read!(u8, U8, |&x| x)
        .or_else(|| read!(u16, U16, |&x| x))
        .or_else(|| read!(f32, F32, |&x| x))
        .or_else(|| read!(i8, U8, |&x| (x as i16 + 128) as u8))
        .or_else(|| read!(i16, U16, |&x| (x as i32 + 32768) as u16))
        .or_else(|| read!(f64, F32, |&x| x as f32))
        .or_else(|| read!(u32, F32, |&x| x as f32))
        .or_else(|| read!(i32, F32, |&x| x as f32))
        .or_else(|| read!(u64, F32, |&x| x as f32))
        .or_else(|| read!(i64, F32, |&x| x as f32));
    let Some(owned) = owned else {
        let dtype = array
            .dtype()
            .str()
            .map(|s| s.to_string())
            .unwrap_or_default();
        return Err(PyValueError::new_err(format!(
            "images of dtype {dtype} are not supported: give integers, float32 or float64 (convert with .astype)"
        )));
    };
    Ok((width, height, owned))
}

/// `(2, 3, 4)` as Python writes a shape.
fn shape_text(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A field as a (height, width) float32 array.
pub fn field_array<'py>(py: Python<'py>, f: Field) -> Bound<'py, PyArray2<f32>> {
    raster(py, f.data, f.width, f.height)
}

/// Values row by row as a (height, width) array.
pub fn raster<T: numpy::Element>(
    py: Python<'_>,
    data: Vec<T>,
    width: usize,
    height: usize,
) -> Bound<'_, PyArray2<T>> {
    numpy::ndarray::Array2::from_shape_vec((height, width), data)
        .expect("a raster of its size")
        .into_pyarray(py)
}

/// Points as an (N, 2) float64 array of (x, y) rows.
pub fn points_array<'py>(py: Python<'py>, pts: &[Point]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = pts.iter().flat_map(|p| [p.x, p.y]).collect();
    raster(py, flat, 2, pts.len())
}

/// `load(path, page=0)`: page `page` (from 0) of an image file as the engine reads it:
/// a (height, width) float32 array of luminance in [0, 1] (an image of a narrow range
/// stretched to fill it, so a label image's values are not its labels).
#[pyfunction]
#[pyo3(signature = (path, page = 0))]
pub fn load(py: Python<'_>, path: PathBuf, page: usize) -> PyResult<Bound<'_, PyArray2<f32>>> {
    let (field, _) = py
        .detach(|| load_image_page(&path, page))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(field_array(py, field))
}
