//! The `topocontour` binary: the desktop app by default, headless subcommands otherwise.

use clap::Parser;
use topocontour::cli::{bench, segment, Cli, Command, Failure};

#[cfg(feature = "gui")]
fn open_app(image: Option<std::path::PathBuf>) -> Result<(), Failure> {
    if let Some(p) = &image {
        if !p.is_file() {
            return Err(Failure {
                code: 2,
                message: format!("cannot open {}: no such file", p.display()),
            });
        }
    }
    // No display, or no GL: eframe says so; report it as one line, exit 1.
    topocontour::app::run_app(image).map_err(|e| Failure {
        code: 1,
        message: format!("cannot open the window: {e}"),
    })
}

#[cfg(not(feature = "gui"))]
fn open_app(_image: Option<std::path::PathBuf>) -> Result<(), Failure> {
    Err(Failure {
        code: 2,
        message: "built without the `gui` feature; use `topocontour segment IMAGE …` (see --help)"
            .into(),
    })
}

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Some(Command::Segment(a)) => segment(a).map(|_| ()),
        Some(Command::Bench(b)) => bench(b),
        None => open_app(cli.image.clone()),
    };
    if let Err(f) = result {
        eprintln!("topocontour: {}", f.message);
        std::process::exit(f.code);
    }
}
