//! `topocontour._core`: the engine for Python (pyo3, abi3). Every run goes through the
//! same [`topocontour::job::Job`] as the command line, its flags parsed by the command
//! line's own clap definitions ([`topocontour::cli::RunSettings`]), so a keyword means
//! what its flag means and a bad value gets the flag's one-line message. The pure-Python
//! layer (`topocontour/__init__.py`) turns keywords into those flags; the GIL is released
//! for every run (`Python::detach`), so threads segment images side by side.

mod arrays;
mod learn;
mod run;
mod track;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(run::segment_array, m)?)?;
    m.add_function(wrap_pyfunction!(run::segment_path, m)?)?;
    m.add_function(wrap_pyfunction!(run::segment_flags, m)?)?;
    m.add_function(wrap_pyfunction!(arrays::load, m)?)?;
    m.add_function(wrap_pyfunction!(learn::train, m)?)?;
    m.add_function(wrap_pyfunction!(track::track, m)?)?;
    m.add_function(wrap_pyfunction!(track::track_flags, m)?)?;
    m.add_class::<run::Segmentation>()?;
    m.add_class::<learn::PyClassifier>()?;
    m.add_class::<track::Tracks>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
