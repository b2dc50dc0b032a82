//! The `tessera` command line. Exit codes: 0 success, 1 failure while running (e.g. writing an
//! output), 2 bad input or usage (with a one-line `file:line:col: message`).
use clap::error::ErrorKind;
use clap::Parser;
use tessera_cli::{Cli, Command};

/// jemalloc, built to back its mappings with transparent huge pages (`.cargo/config.toml`): a
/// large scene's acceleration structure then takes few TLB entries (see
/// `docs/performance.md`, "Against Embree", for what it measured).
#[cfg(not(target_env = "msvc"))]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) => {
            e.exit()
        }
        Err(e) => {
            // One line, like every other bad-input message: clap's first paragraph (which may
            // list missing arguments on the lines after the first) joined into one.
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .skip_while(|l| l.trim().is_empty())
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let first = if first.is_empty() {
                "error: bad usage".to_string()
            } else {
                first.join(" ")
            };
            eprintln!("{first} (see tessera --help)");
            std::process::exit(tessera::InputError::EXIT_CODE);
        }
    };
    let code = match cli.command {
        Command::Render(args) => tessera_cli::render::run(&args),
        Command::Test(args) => tessera_cli::test::run(&args),
        Command::Bench(args) => tessera_cli::bench::run(&args),
        Command::Compare(args) => tessera_cli::compare::run(&args),
        Command::Merge(args) => tessera_cli::merge::run(&args),
        Command::Plugins(args) => tessera_cli::plugins::run(&args),
        Command::Info(args) => tessera_cli::info::run(&args),
        Command::View(args) => tessera_cli::view::run(&args),
    };
    std::process::exit(code);
}
