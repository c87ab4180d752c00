//! The `topocontour` binary: the headless command line (the desktop app comes later).

use clap::Parser;

/// Polygonal active contours that change topology correctly.
#[derive(Parser, Debug)]
#[command(name = "topocontour", version, about)]
struct Cli {}

fn main() {
    let _ = Cli::parse();
    println!("topocontour {}: see --help", env!("CARGO_PKG_VERSION"));
}
