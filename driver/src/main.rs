//! The `tessera` command line. Exit codes: 0 success, 1 failure while running (e.g. writing an
//! output), 2 bad input or usage (with a one-line `file:line:col: message`).
use clap::Parser;
use tessera::cli::{Cli, Command};

fn main() {
    let cli = Cli::parse();
    let code = match cli.command {
        Command::Render(args) => tessera::cli::render::run(&args),
    };
    std::process::exit(code);
}
