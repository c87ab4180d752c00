//! The `topocontour` binary: headless subcommands (the desktop app is a later step).

use clap::Parser;
use topocontour::cli::{bench, segment, Cli, Command, Failure};

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Some(Command::Segment(a)) => segment(a).map(|_| ()),
        Some(Command::Bench(b)) => bench(b),
        None => Err(Failure {
            code: 2,
            message: "the desktop app is not in this build yet; use `topocontour segment IMAGE …` (see --help)".into(),
        }),
    };
    if let Err(f) = result {
        eprintln!("topocontour: {}", f.message);
        std::process::exit(f.code);
    }
}
