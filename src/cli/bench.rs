//! `topocontour bench CASES…`: the whole pipeline timed in-process on case folders.

use super::run::{choices, evolve, BROAD_PHASES, MODES};
use super::{bad, Failure, SegmentArgs};
use crate::contours::BroadPhaseKind;
use crate::evolution::Mode;
use crate::io::Outputs;
use clap::Args;
use std::io::Write;
use std::path::PathBuf;

/// The arguments of `bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Case folders (image.png + case.json), or folders of them.
    pub cases: Vec<PathBuf>,
    /// Runs per case.
    #[arg(long, default_value_t = 10)]
    pub runs: usize,
    /// Broad phase of the crossing search.
    #[arg(long, default_value = "bins", value_parser = choices::<BroadPhaseKind>(BROAD_PHASES))]
    pub broad_phase: BroadPhaseKind,
    /// Engine to time.
    #[arg(long, default_value = "adaptive", value_parser = choices::<Mode>(MODES))]
    pub mode: Mode,
}

/// Times `segment` (in memory, without writing) on case folders.
pub fn bench(b: &BenchArgs) -> Result<(), Failure> {
    let mut dirs = Vec::new();
    for c in &b.cases {
        // A case.json that is there but not a regular file (a FIFO, a link to a device)
        // is an error of that case, not a folder to skip.
        if has_case(c) {
            dirs.push(c.clone());
        } else if let Ok(rd) = std::fs::read_dir(c) {
            let mut sub: Vec<PathBuf> = rd
                .flatten()
                .map(|e| e.path())
                .filter(|p| has_case(p))
                .collect();
            sub.sort();
            dirs.extend(sub);
        } else {
            return Err(bad(format!("{} is not a case folder", c.display())));
        }
    }
    let mut stdout = std::io::stdout().lock();
    // A closed pipe (`| head`) ends the output quietly; any other failure (a full disk)
    // is one.
    if let Err(e) = writeln!(
        stdout,
        "{:<18} {:>8} {:>8} {:>8} {:>7} {:>9}",
        "case", "min ms", "median", "max ms", "frames", "contours"
    ) {
        return table_end(e);
    }
    for d in dirs {
        let mut args = SegmentArgs::from_case(&d)?;
        args.run.broad_phase = b.broad_phase;
        args.run.mode = Some(b.mode);
        let mut times = Vec::new();
        let (mut frames, mut contours) = (0, 0);
        for _ in 0..b.runs.max(1) {
            let t = std::time::Instant::now();
            let ev = evolve(&args.image, &args.run, None)?.1.ev;
            let out = Outputs::of(&ev, ev.contours(), "");
            std::hint::black_box((out.json(), out.mask_png()));
            times.push(t.elapsed().as_secs_f64() * 1e3);
            frames = ev.frames();
            contours = ev.contours().contour_count();
        }
        times.sort_by(f64::total_cmp);
        let name = crate::io::folder::file_name(&d);
        if let Err(e) = writeln!(
            stdout,
            "{:<18} {:>8.1} {:>8.1} {:>8.1} {:>7} {:>9}",
            name,
            times[0],
            times[times.len() / 2],
            times[times.len() - 1],
            frames,
            contours
        ) {
            return table_end(e);
        }
    }
    stdout.flush().or_else(table_end)
}

/// Whether `dir` holds an entry named case.json, whatever it is.
fn has_case(dir: &std::path::Path) -> bool {
    dir.join("case.json").symlink_metadata().is_ok()
}

/// A failed write of the table: the reader went away (fine), or the output failed.
fn table_end(e: std::io::Error) -> Result<(), Failure> {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        return Ok(());
    }
    Err(Failure {
        code: 1,
        message: format!("cannot write the table: {e}"),
    })
}
