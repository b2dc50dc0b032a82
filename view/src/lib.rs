//! `tessera view`: a live view of a progressive render, as a local web page served by the
//! `tessera` binary (the same on a laptop and on a render node reached through an SSH tunnel).
//! The image refines pass after pass; the page moves the camera, edits BSDF colours and numbers,
//! switches the integrator and its depth, and saves the image and the edited scene.
//!
//! Edits are rewrites of the scene file's text (see [`edits`]): the scene being rendered is the
//! file's text with the edits applied, loaded by the ordinary loader, and `GET /api/scene.xml`
//! is that text, so `tessera render` of it at N spp is the view's frame at N spp, bit for bit.
//!
//! Threads: one serves HTTP ([`server`]), one renders ([`renderer`], which runs the render's
//! worker threads). See `docs/guide/view.md` for the API.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
pub mod api;
pub mod camera;
pub mod edits;
pub mod encode;
pub mod materials;
pub mod renderer;
pub mod server;
pub mod state;
pub mod xml_text;

use camera::Pose;
use edits::Edits;
use state::{Inner, SceneFacts, Shared};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex};
use std::thread::JoinHandle;

/// How to start a view.
#[derive(Clone, Debug)]
pub struct Config {
    /// The scene file.
    pub scene: PathBuf,
    /// `-D name=value` overrides of the file's `<default>`s (baked into the served text).
    pub defines: Vec<(String, String)>,
    /// Address to listen on (`127.0.0.1` unless told otherwise).
    pub bind: String,
    /// Port (0: any free one).
    pub port: u16,
    /// Render worker threads.
    pub threads: usize,
    /// Integrator to start with (`None`: the file's).
    pub integrator: Option<String>,
    /// Its max depth (`None`: the file's).
    pub max_depth: Option<i64>,
    /// Sampler to use (`None`: the file's).
    pub sampler: Option<String>,
    /// Stop refining at this many spp (`None`: refine until the server ends).
    pub spp_limit: Option<u64>,
}

/// A running view: the HTTP thread and the render thread.
pub struct View {
    shared: Arc<Shared>,
    server: Arc<tiny_http::Server>,
    addr: SocketAddr,
    threads: Vec<JoinHandle<()>>,
}

/// Why a view cannot start: bad input (exit code 2) or a failure to listen (exit code 1).
#[derive(Debug)]
pub enum StartError {
    /// The scene file, a define or an option is wrong (one line, located where it can be).
    Input(String),
    /// The address cannot be listened on.
    Listen(String),
}

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StartError::Input(s) | StartError::Listen(s) => write!(f, "{s}"),
        }
    }
}

impl View {
    /// Loads the scene, starts rendering and listens. Warnings of the loader come back in the
    /// second element, one line each.
    pub fn start(cfg: &Config) -> Result<(View, Vec<String>), StartError> {
        let input = StartError::Input;
        let text = std::fs::read_to_string(&cfg.scene)
            .map_err(|e| input(format!("{}: cannot read: {e}", cfg.scene.display())))?;
        let base = edits::bake_defines(&text, &cfg.defines)
            .map_err(|e| input(format!("{}: {e}", cfg.scene.display())))?;
        let not_editable = xml_text::parse(&base)
            .map_err(|e| input(format!("{}: {e}", cfg.scene.display())))
            .map(|d| edits::not_editable(&d))?;
        let edits = Edits {
            integrator: cfg.integrator.clone(),
            max_depth: cfg.max_depth,
            sampler: cfg.sampler.clone(),
            ..Default::default()
        };
        let wants_edits =
            edits.integrator.is_some() || edits.max_depth.is_some() || edits.sampler.is_some();
        if let (Some(why), true) = (&not_editable, wants_edits) {
            return Err(input(format!(
                "{}: --integrator, --max-depth and --sampler: {why}",
                cfg.scene.display()
            )));
        }
        if let Some(i) = &cfg.integrator {
            let choices = edits::integrator_choices();
            if !choices.contains(&i.as_str()) {
                return Err(input(format!(
                    "unknown integrator \"{i}\" (the view offers: {})",
                    choices.join(", ")
                )));
            }
        }
        let text = edits
            .apply(&base)
            .map_err(|e| input(format!("{}: {e}", cfg.scene.display())))?;
        let loaded = state::load(&text, &cfg.scene).map_err(input)?;
        let warnings = loaded.warnings.clone();
        let facts = SceneFacts::of(&loaded, Pose::of_scene(&loaded));
        let server = tiny_http::Server::http((cfg.bind.as_str(), cfg.port)).map_err(|e| {
            StartError::Listen(format!("cannot listen on {}:{}: {e}", cfg.bind, cfg.port))
        })?;
        let addr = server
            .server_addr()
            .to_ip()
            .ok_or_else(|| StartError::Listen("not listening on an IP address".into()))?;
        let shared = Arc::new(Shared {
            path: cfg.scene.clone(),
            base,
            not_editable,
            spp_limit: cfg.spp_limit,
            threads: cfg.threads.max(1),
            inner: Mutex::new(Inner {
                edits,
                text,
                pending: None,
                generation: 0,
                facts,
                frame: None,
            }),
            wake: Condvar::new(),
            stop: AtomicBool::new(false),
            shutdown: AtomicBool::new(false),
        });
        {
            let mut inner = shared.lock();
            shared.hand_over(&mut inner, loaded);
        }
        let server = Arc::new(server);
        let render = {
            let shared = Arc::clone(&shared);
            std::thread::Builder::new()
                .name("tessera-view-render".into())
                .spawn(move || renderer::run(shared))
                .map_err(|e| StartError::Listen(format!("cannot start the render thread: {e}")))?
        };
        let http = {
            let (server, shared) = (Arc::clone(&server), Arc::clone(&shared));
            std::thread::Builder::new()
                .name("tessera-view-http".into())
                .spawn(move || server::run(server, shared))
                .map_err(|e| StartError::Listen(format!("cannot start the server thread: {e}")))?
        };
        let view = View {
            shared,
            server,
            addr,
            threads: vec![render, http],
        };
        Ok((view, warnings))
    }

    /// The address listened on (with the real port when 0 was asked for).
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's URL.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Serves until the process ends.
    pub fn wait(mut self) {
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }

    /// Stops rendering (at a tile boundary) and serving; returns when both threads ended.
    pub fn stop(mut self) {
        self.shared.shutdown.store(true, Ordering::SeqCst);
        self.shared.stop.store(true, Ordering::SeqCst);
        self.shared.wake.notify_all();
        self.server.unblock();
        for t in self.threads.drain(..) {
            let _ = t.join();
        }
    }
}
