//! Output files written all or nothing, that can never destroy an input or a special file.
//!
//! [`OutputFiles::prepare`] runs before any work: it refuses an output that names an
//! input of the run (the image, a session file; also through `..`, a symlink or a hard
//! link), the same file twice, an existing path that is not a regular file (a FIFO, a
//! device such as `/dev/null` or `/dev/full`, a socket, a folder), a name longer than the
//! file system allows (the rename at the end would fail after other outputs were
//! replaced), and a folder it cannot write into. It creates one temporary file
//! per output right away, exclusively (`O_EXCL`) with an unpredictable short name in the
//! output's folder, so a planted symlink cannot redirect the write and a long output name
//! cannot make the temporary's name too long. [`OutputFiles::commit`] writes every
//! temporary and only then renames them into place; a failure before the renames removes
//! every temporary and leaves no output at all. A kill during the run leaves at most a
//! hidden temporary, never a half-written output. A replaced file keeps its permissions
//! (a private 0600 result stays private).
//!
//! Every temporary alive is listed ([`remove_temporaries`]): the command line's signal
//! handler removes them on SIGINT, SIGTERM or SIGHUP before the process ends, so an
//! interrupted run leaves nothing behind (only `kill -9` can leave a hidden temporary).
//!
//! The temporaries are not fsynced before the rename: readers, and later runs, see the
//! old file or the whole new one either way; only a power cut right after the rename
//! could leave an empty file on some file systems. We choose the batch user's speed: an
//! fsync per output costs 3–4 ms on a typical VM disk, more than segmenting a small image.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The temporaries not yet renamed or removed, for a signal handler to remove.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    // A panic while holding the lock leaves a list that is still right.
    LIVE.lock().unwrap_or_else(|e| e.into_inner())
}

fn forget_temporary(path: &Path) {
    let mut l = live();
    if let Some(i) = l.iter().position(|p| p == path) {
        l.swap_remove(i);
    }
}

/// Removes every temporary of every [`OutputFiles`] alive, and keeps them from being
/// made again: for a handler that ends the process right after. Outputs already renamed
/// into place stay; the rest of the run's outputs are never written.
pub fn remove_temporaries() {
    let mut l = live();
    for p in l.drain(..) {
        let _ = std::fs::remove_file(p);
    }
    // The lock is held until the process exits: a temporary being made now waits.
    std::mem::forget(l);
}

/// Why an output cannot be written. Every variant is the user's to fix (exit code 2).
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The path has no file name.
    #[error("cannot write {0}: it is not a file name")]
    NotAFileName(PathBuf),
    #[error("cannot write {path}: folder {dir} does not exist")]
    /// The output's folder does not exist.
    NoFolder {
        /// The output.
        path: PathBuf,
        /// Its folder.
        dir: PathBuf,
    },
    /// The path exists and is not a regular file.
    #[error("cannot write {0}: it exists and is not a regular file")]
    NotRegular(PathBuf),
    /// The path is an input of the run (what: "input image", "session file").
    #[error("cannot write {0}: it is the {1}")]
    IsInput(PathBuf, &'static str),
    /// The file name or the whole path is longer than the file system takes.
    #[error("cannot write {0}: the name is too long for the file system")]
    NameTooLong(PathBuf),
    /// Two outputs name one file.
    #[error("{0} is given to two outputs")]
    Twice(PathBuf),
    /// Creating or writing failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The output.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
}

/// Where a path leads: the file it names if that exists (device and inode), else its
/// folder's canonical path joined with its name.
#[derive(PartialEq, Eq, Debug)]
enum Identity {
    Existing(u64, u64),
    New(PathBuf),
}

fn identity_of_existing(meta: &std::fs::Metadata) -> Identity {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        Identity::Existing(meta.dev(), meta.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        Identity::New(PathBuf::new())
    }
}

/// A listed temporary: unlisted when it is renamed into place or removed.
struct Temporary(Option<tempfile::NamedTempFile>);

impl Temporary {
    fn file(&mut self) -> &mut tempfile::NamedTempFile {
        self.0.as_mut().expect("a temporary not yet renamed")
    }

    fn persist(mut self, path: &Path) -> std::io::Result<()> {
        let tmp = self.0.take().expect("a temporary not yet renamed");
        let tmp_path = tmp.path().to_path_buf();
        // The replaced file's permissions, not the umask's (a 0600 file stays 0600).
        if let Ok(meta) = std::fs::metadata(path) {
            let _ = std::fs::set_permissions(&tmp_path, meta.permissions());
        }
        let persisted = tmp.persist(path).map(drop).map_err(|e| e.error);
        forget_temporary(&tmp_path);
        persisted
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if let Some(tmp) = self.0.take() {
            let path = tmp.path().to_path_buf();
            drop(tmp); // removes the file
            forget_temporary(&path);
        }
    }
}

/// The output files of one run, checked and with their temporaries created.
pub struct OutputFiles {
    files: Vec<(PathBuf, Temporary)>,
}

impl OutputFiles {
    /// Checks `outputs` against each other and against `input` (the image the run reads,
    /// if any) and creates their temporaries. Nothing visible is created or changed.
    pub fn prepare(input: Option<&Path>, outputs: &[&Path]) -> Result<Self, OutputError> {
        let inputs: Vec<(&Path, &'static str)> =
            input.map(|p| (p, "input image")).into_iter().collect();
        Self::prepare_for(&inputs, outputs)
    }

    /// [`OutputFiles::prepare`] for a run with several inputs, each with what it is
    /// ("input image", "session file") for the refusal.
    pub fn prepare_for(
        inputs: &[(&Path, &'static str)],
        outputs: &[&Path],
    ) -> Result<Self, OutputError> {
        let input_ids: Vec<(Identity, &'static str)> = inputs
            .iter()
            .filter_map(|&(p, what)| {
                Some((identity_of_existing(&std::fs::metadata(p).ok()?), what))
            })
            .collect();
        let mut seen: Vec<Identity> = Vec::new();
        let mut files = Vec::new();
        for &path in outputs {
            let name = path
                .file_name()
                .filter(|n| *n != "." && *n != "..")
                .ok_or_else(|| OutputError::NotAFileName(path.into()))?;
            let dir = path
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."));
            if !dir.is_dir() {
                return Err(OutputError::NoFolder {
                    path: path.into(),
                    dir: dir.into(),
                });
            }
            if name.len() > name_max(dir) || path.as_os_str().len() >= PATH_MAX {
                return Err(OutputError::NameTooLong(path.into()));
            }
            let id = match std::fs::metadata(path) {
                Ok(meta) if !meta.is_file() => return Err(OutputError::NotRegular(path.into())),
                Ok(meta) => identity_of_existing(&meta),
                Err(_) => {
                    let canonical = dir.canonicalize().map_err(|source| OutputError::Io {
                        path: path.into(),
                        source,
                    })?;
                    Identity::New(canonical.join(name))
                }
            };
            if let Some(&(_, what)) = input_ids.iter().find(|(i, _)| *i == id) {
                return Err(OutputError::IsInput(path.into(), what));
            }
            if seen.contains(&id) {
                return Err(OutputError::Twice(path.into()));
            }
            seen.push(id);
            let tmp = temporary_in(dir).map_err(|source| OutputError::Io {
                path: path.into(),
                source,
            })?;
            files.push((path.to_path_buf(), tmp));
        }
        Ok(OutputFiles { files })
    }

    /// Writes `contents` (one per output, in the order given to `prepare`) and renames
    /// every temporary into place once all are written.
    ///
    /// # Panics
    /// If `contents` does not have one entry per output.
    pub fn commit(self, contents: Vec<Vec<u8>>) -> Result<(), OutputError> {
        assert_eq!(contents.len(), self.files.len(), "one content per output");
        let mut written = Vec::with_capacity(self.files.len());
        for ((path, mut tmp), bytes) in self.files.into_iter().zip(contents) {
            let file = tmp.file();
            file.write_all(&bytes)
                .and_then(|()| file.flush())
                .map_err(|source| OutputError::Io {
                    path: path.clone(),
                    source,
                })?;
            written.push((path, tmp));
        }
        for (path, tmp) in written {
            tmp.persist(&path)
                .map_err(|source| OutputError::Io { path, source })?;
        }
        Ok(())
    }
}

/// The longest path the kernel takes (Linux's PATH_MAX, with its final NUL).
const PATH_MAX: usize = 4096;

/// The longest file name the file system of `dir` takes, in bytes.
fn name_max(dir: &Path) -> usize {
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        if let Ok(c) = std::ffi::CString::new(dir.as_os_str().as_bytes()) {
            // SAFETY: a valid NUL-terminated path; pathconf only reads it.
            let n = unsafe { libc::pathconf(c.as_ptr(), libc::_PC_NAME_MAX) };
            if n > 0 {
                return n as usize;
            }
        }
    }
    let _ = dir;
    255
}

/// A temporary file in `dir`, created exclusively with a random name; mode 0666 before
/// the umask, as any file the user's programs create.
fn temporary_in(dir: &Path) -> std::io::Result<Temporary> {
    let mut b = tempfile::Builder::new();
    b.prefix(".topocontour-").suffix(".tmp");
    #[cfg(unix)]
    b.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut l = live();
    let tmp = b.tempfile_in(dir)?;
    l.push(tmp.path().to_path_buf());
    Ok(Temporary(Some(tmp)))
}

/// Writes one file atomically with the checks of [`OutputFiles::prepare`].
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    OutputFiles::prepare(None, &[path])?.commit(vec![bytes.to_vec()])
}
