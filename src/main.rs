//! The `topocontour` binary: the desktop app by default, headless subcommands otherwise.

use clap::Parser;
use std::io::Write;
use topocontour::cli::{
    batch, bench, note, replay, segment, track, train, usage_line, Cli, Command, Failure,
};

#[cfg(feature = "gui")]
fn open_app(image: Option<std::path::PathBuf>) -> Result<(), Failure> {
    if let Some(p) = &image {
        if !p.is_file() {
            let why = if p.exists() {
                "not a regular file"
            } else {
                "no such file"
            };
            return Err(Failure {
                code: 2,
                message: format!("cannot open {}: {why}", p.display()),
            });
        }
    }
    // No display, or no GL: eframe says so; report it as one line, exit 1.
    topocontour::app::run_app(image).map_err(|e| Failure {
        code: 1,
        message: format!(
            "cannot open the window: {}; the subcommands run without one (topocontour --help)",
            without_source_location(&e).trim_end_matches('.')
        ),
    })
}

/// `message` without the source locations a library puts in its errors (winit's "os
/// error at /home/…/src/platform_impl/linux/mod.rs:765: …"): they name a file on the
/// machine that built the binary, nothing the user can act on.
#[cfg(feature = "gui")]
fn without_source_location(message: &str) -> String {
    let mut out = message.to_string();
    let mut from = 0;
    while let Some(at) = out[from..].find(" at /").map(|k| k + from) {
        // The location is one word: a path ending in ".rs:LINE" (then ": " or the end).
        let rest = &out[at + 4..];
        let word = &rest[..rest.find(char::is_whitespace).unwrap_or(rest.len())];
        let line = word.find(".rs:").map(|rs| {
            let digits = word[rs + 4..]
                .chars()
                .take_while(char::is_ascii_digit)
                .count();
            (rs + 4, digits)
        });
        match line {
            Some((end, digits)) if digits > 0 => out.replace_range(at..at + 4 + end + digits, ""),
            _ => from = at + 4,
        }
    }
    out
}

#[cfg(not(feature = "gui"))]
fn open_app(_image: Option<std::path::PathBuf>) -> Result<(), Failure> {
    Err(Failure {
        code: 2,
        message: "built without the `gui` feature; use `topocontour segment IMAGE …` (see --help)"
            .into(),
    })
}

/// glibc returns freed blocks of 128 KiB and more to the kernel at once (munmap), and on
/// a multi-core machine each return costs a TLB shootdown across cores; a headless run
/// frees dozens of image-sized buffers. Keeping them in the heap saves milliseconds per
/// process (measured with perf: ~15% of a small case's time was in those shootdowns).
/// Blocks of 16 MiB and more (an image of 2048² and up) still go to the kernel: in the
/// heap, the coarse levels a large run frees leave holes its full-resolution buffers do
/// not fit, and a 4096² run peaked at 318 MB where its heap never held more than 250
/// (docs/decisions.md, 2026-12-02).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn keep_freed_memory() {
    extern "C" {
        fn mallopt(param: i32, value: i32) -> i32;
    }
    const M_TRIM_THRESHOLD: i32 = -1;
    const M_MMAP_THRESHOLD: i32 = -3;
    // SAFETY: mallopt only tunes glibc's allocator; called before any other thread exists.
    unsafe {
        mallopt(M_MMAP_THRESHOLD, 16 << 20);
        mallopt(M_TRIM_THRESHOLD, 512 << 20);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_freed_memory() {}

fn main() {
    keep_freed_memory();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help and --version: the text on stdout; a closed stdout loses it quietly.
            let _ = write!(std::io::stdout().lock(), "{e}");
            std::process::exit(0);
        }
        Err(e) => {
            note(&usage_line(&e));
            std::process::exit(2);
        }
    };
    if cli.command.is_some() {
        topocontour::cli::signals::install();
    }
    let result = match &cli.command {
        // The finished evolver is not dropped: the process ends right after.
        Some(Command::Segment(a)) => segment(a).map(std::mem::forget),
        Some(Command::Replay(r)) => replay(r).map(std::mem::forget),
        Some(Command::Batch(b)) => batch(b),
        Some(Command::Bench(b)) => bench(b),
        Some(Command::Track(t)) => track(t),
        Some(Command::Train(t)) => train(t),
        None => open_app(cli.image.clone()),
    };
    if let Err(f) = result {
        note(&f.message);
        std::process::exit(f.code);
    }
}

#[cfg(all(test, feature = "gui"))]
mod tests {
    use super::without_source_location;

    #[test]
    fn a_library_error_loses_its_source_location_and_keeps_its_reason() {
        let winit = "winit EventLoopError: os error at /root/.cargo/registry/src/index.crates.io-1949cf8c6b5b557f/winit-0.30.13/src/platform_impl/linux/mod.rs:765: neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set.";
        assert_eq!(
            without_source_location(winit),
            "winit EventLoopError: os error: neither WAYLAND_DISPLAY nor WAYLAND_SOCKET nor DISPLAY is set."
        );
        let plain = "no GL context at /dev/dri: permission denied";
        assert_eq!(without_source_location(plain), plain);
        let both = "no GL at /dev/dri: denied; os error at /src/x.rs:3: bad";
        assert_eq!(
            without_source_location(both),
            "no GL at /dev/dri: denied; os error: bad"
        );
    }
}
