//! A whole folder with the same settings: what `topocontour batch` and the app's "Apply
//! to folder…" share — which files are images, how one image is segmented and written,
//! and the rows of `summary.csv` (one per object, with its mean intensity).

use super::{Format, OutputFiles, Outputs};
use crate::evolution::regions;
use crate::image::Gray;
use crate::job::Job;
use std::path::{Path, PathBuf};

/// The header of `summary.csv`.
pub const SUMMARY_HEADER: &str =
    "image,id,area,perimeter,circularity,centroid_x,centroid_y,holes,mean_intensity,contour\n";

/// The images of `dir` (regular files ending in .png, .jpg, .jpeg, .tif or .tiff, not
/// hidden; not its subfolders), in natural name order (`frame_2` before `frame_10`).
pub fn list_images(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut images: Vec<PathBuf> = std::fs::read_dir(dir)?
        .flatten()
        .map(|e| e.path())
        // Hidden files are no frames: macOS leaves `._name.tif` beside each file it
        // copies (its resource fork), which no image reader opens.
        .filter(|p| !file_name(p).starts_with('.'))
        .filter(|p| p.is_file())
        .filter(|p| {
            p.extension().and_then(|e| e.to_str()).is_some_and(|e| {
                ["png", "jpg", "jpeg", "tif", "tiff"]
                    .iter()
                    .any(|x| e.eq_ignore_ascii_case(x))
            })
        })
        .collect();
    // Natural order, as a file browser shows them: frame_2 before frame_10 (numbers are
    // rarely zero-padded), so a folder of frames is a movie in the order it was taken.
    images.sort_by(|a, b| natord::compare(&file_name(a), &file_name(b)));
    Ok(images)
}

/// The file name of `path` (what outputs record of an image).
pub fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// The name of `path` without its extension.
pub fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// The stem each image's outputs are named after (`NAME.json`, …): its file stem, or its
/// whole file name where stems would collide (`a.png` and `a.tif` give `a.png.json` and
/// `a.tif.json`; an image called `summary` would meet `summary.csv`). Names are compared
/// ignoring case, as many file systems do (exFAT, macOS, Windows): `a.png` and `a.PNG`
/// are refused, naming both.
pub fn output_stems(images: &[PathBuf]) -> Result<Vec<String>, String> {
    let key = |s: &str| s.to_lowercase();
    let stems: Vec<String> = images.iter().map(|p| stem(p)).collect();
    let chosen: Vec<String> = images
        .iter()
        .zip(&stems)
        .map(|(p, st)| {
            let clash =
                key(st) == "summary" || stems.iter().filter(|o| key(o) == key(st)).count() > 1;
            if clash {
                file_name(p)
            } else {
                st.clone()
            }
        })
        .collect();
    for (i, a) in chosen.iter().enumerate() {
        if let Some(j) = chosen[..i].iter().position(|b| key(a) == key(b)) {
            return Err(format!(
                "{} and {} would get the same output names ({a}.*); rename one",
                file_name(&images[j]),
                file_name(&images[i])
            ));
        }
    }
    Ok(chosen)
}

/// One CSV row per region: the measurements of `Outputs::csv` and the mean intensity
/// (0–1 of the image's full scale) over the region's pixels.
pub fn summary_rows(name: &str, out: &Outputs, image: &dyn Gray) -> Vec<String> {
    let labels = out.labels();
    let regions = regions(out.set);
    let n = regions.len();
    let (mut sum, mut count) = (vec![0f64; n + 1], vec![0usize; n + 1]);
    for (i, &l) in labels.iter().enumerate() {
        sum[l as usize] += image.value(i) as f64;
        count[l as usize] += 1;
    }
    let quoted = super::export::csv_quoted(name);
    regions
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let mean = sum[k + 1] / count[k + 1].max(1) as f64;
            format!(
                "{quoted},{},{:.3},{:.3},{:.4},{:.3},{:.3},{},{:.5},{}\n",
                super::export::object_number(k),
                r.area,
                r.perimeter,
                r.circularity,
                r.centroid.x,
                r.centroid.y,
                r.holes.len(),
                mean,
                r.id
            )
        })
        .collect()
}

/// How every image of a folder is segmented (the app's "Apply to folder…"): one [`Job`]
/// as a template, pointed at each image in turn. With `job.auto_seeds` each image gets
/// the seeds found in it, never another image's.
#[derive(Clone, Debug)]
pub struct FolderJob {
    /// The template; its image is replaced by each image of the folder.
    pub job: Job,
    /// Where `NAME.json`, `NAME.csv` and `summary.csv` go.
    pub out: PathBuf,
}

impl FolderJob {
    /// Segments `img` and writes `NAME.json` and `NAME.csv` (all or nothing); returns its
    /// summary rows, or the reason it failed in one line.
    pub fn run_one(&self, img: &Path) -> Result<Vec<String>, String> {
        let stem = stem(img);
        let json = self.out.join(Format::Json.file_name(&stem));
        let csv = self.out.join(Format::Csv.file_name(&stem));
        let files = OutputFiles::prepare(Some(img), &[&json, &csv]).map_err(|e| e.to_string())?;
        let run = self.job.with_image(img).run().map_err(|e| e.to_string())?;
        let name = file_name(img);
        let out = Outputs::of(&run.ev, run.ev.contours(), &name).with_pixel_size(run.pixel.clone());
        files
            .commit(vec![out.json().into_bytes(), out.csv().into_bytes()])
            .map_err(|e| e.to_string())?;
        Ok(summary_rows(&name, &out, &run.image))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(names: &[&str]) -> Vec<PathBuf> {
        names.iter().map(PathBuf::from).collect()
    }

    #[test]
    fn images_are_listed_in_natural_order() {
        let dir = tempfile::tempdir().unwrap();
        for n in [
            "frame_10.png",
            "frame_2.png",
            "frame_1.png",
            "notes.txt",
            "._frame_1.png",
            "frame_0.png",
        ] {
            std::fs::write(dir.path().join(n), b"").unwrap();
        }
        let names: Vec<String> = list_images(dir.path())
            .unwrap()
            .iter()
            .map(|p| file_name(p))
            .collect();
        assert_eq!(
            names,
            ["frame_0.png", "frame_1.png", "frame_2.png", "frame_10.png"]
        );
    }

    #[test]
    fn output_stems_are_unique_or_refused() {
        let got = output_stems(&paths(&["a.png", "a.tif", "b.png", "summary.png"])).unwrap();
        assert_eq!(got, ["a.png", "a.tif", "b", "summary.png"]);
        let err = output_stems(&paths(&["a.png", "a.PNG"])).unwrap_err();
        assert!(err.contains("a.png and a.PNG"), "{err}");
        assert_eq!(
            output_stems(&paths(&["x.png", "y.png"])).unwrap(),
            ["x", "y"]
        );
    }
}
