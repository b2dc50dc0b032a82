//! `tessera view SCENE.xml`: serve a live, editable view of a progressive render on a local web
//! page (see `docs/guide/view.md`). Listens on 127.0.0.1 unless `--bind` says otherwise (on a
//! render node, reach it through an SSH tunnel: `ssh -L 8080:127.0.0.1:8080 node`).
use clap::Args;
use std::path::PathBuf;
use tessera::InputError;

/// Arguments of `tessera view`.
#[derive(Args, Debug, Clone)]
pub struct ViewArgs {
    /// The scene file (Mitsuba 3 XML; Nori files are shown without edits).
    pub scene: PathBuf,
    /// Override a scene `<default>`: -D name=value (written into the served scene text).
    #[arg(short = 'D', value_parser = super::define::parse_define)]
    pub defines: Vec<(String, String)>,
    /// Port to listen on (0: any free port; the real one is printed).
    #[arg(long, default_value_t = 8080)]
    pub port: u16,
    /// Address to listen on. The default serves this machine only; 0.0.0.0 serves every
    /// network the machine is on, to anyone who can reach it.
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: String,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Integrator to start with (the page can change it).
    #[arg(long)]
    pub integrator: Option<String>,
    /// Longest path to start with (-1 = unbounded).
    #[arg(long, allow_hyphen_values = true)]
    pub max_depth: Option<i64>,
    /// Sampler (independent, zsobol), overriding the scene file.
    #[arg(long)]
    pub sampler: Option<String>,
    /// Stop refining at this many samples per pixel (default: refine until stopped).
    #[arg(long)]
    pub spp: Option<u64>,
}

/// Runs the command (until the process is interrupted); returns the exit code.
pub fn run(args: &ViewArgs) -> i32 {
    let threads = args
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if threads == 0 {
        eprintln!("error: --threads must be at least 1");
        return InputError::EXIT_CODE;
    }
    if args.spp == Some(0) {
        eprintln!("error: --spp must be at least 1");
        return InputError::EXIT_CODE;
    }
    let cfg = tessera_view::Config {
        scene: args.scene.clone(),
        defines: args.defines.clone(),
        bind: args.bind.clone(),
        port: args.port,
        threads,
        integrator: args.integrator.clone(),
        max_depth: args.max_depth,
        sampler: args.sampler.clone(),
        spp_limit: args.spp,
    };
    let (view, warnings) = match tessera_view::View::start(&cfg) {
        Ok(v) => v,
        Err(e @ tessera_view::StartError::Input(_)) => {
            eprintln!("error: {e}");
            return InputError::EXIT_CODE;
        }
        Err(e) => {
            eprintln!("error: {e}");
            return 1;
        }
    };
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    println!("tessera view: {} (Ctrl-C to stop)", view.url());
    view.wait();
    0
}
