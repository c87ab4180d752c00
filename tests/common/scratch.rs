//! Test files in folders of their own that are removed when the test is done: a test
//! run leaves nothing in the temporary folder.

use std::ops::Deref;
use std::path::{Path, PathBuf};

/// A path in a fresh temporary folder (or the folder itself), removed with everything
/// in it when dropped.
pub struct Scratch {
    _dir: tempfile::TempDir,
    path: PathBuf,
}

impl Scratch {
    /// A fresh folder named after `name` (a prefix; the rest is random).
    pub fn folder(name: &str) -> Scratch {
        let dir = tempfile::Builder::new()
            .prefix(&format!("topocontour-{name}-"))
            .tempdir()
            .expect("a temporary folder");
        let path = dir.path().to_path_buf();
        Scratch { _dir: dir, path }
    }

    /// The path `name` in a fresh folder (nothing is made there).
    pub fn file(name: &str) -> Scratch {
        let mut s = Scratch::folder("file");
        s.path = s.path.join(name);
        s
    }

    /// The path as an owned `PathBuf` (the folder still goes when `self` is dropped).
    pub fn to_path_buf(&self) -> PathBuf {
        self.path.clone()
    }
}

impl Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}
