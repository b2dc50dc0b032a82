//! What the server's request handler and the render thread share: the scene text and its edits,
//! the scene waiting to be rendered after an edit, and the latest frame. An edit is checked and
//! loaded by the handler (a bad one changes nothing), then handed to the render thread, which
//! drops its accumulation and starts again from 0 spp.
use crate::camera::Pose;
use crate::edits::Edits;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use tessera_scene::LoadedScene;

/// An image the render thread finished: a full-resolution pass, or the reduced-resolution
/// preview that follows a change.
#[derive(Clone, Debug)]
pub struct Frame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Linear RGB, row-major, top row first.
    pub rgb: Vec<[f32; 3]>,
    /// Samples per pixel accumulated (0 for a preview).
    pub spp: u64,
    /// Whether this is the preview of a change (1 spp at reduced resolution).
    pub preview: bool,
    /// The scene generation it shows (it grows by one with every edit).
    pub generation: u64,
    /// Seconds since the generation started rendering.
    pub elapsed: f64,
    /// Samples per second of the passes of this generation.
    pub samples_per_second: f64,
    /// The image's relative MSE estimated from its own samples (two halves, as `tessera
    /// render --target-error` estimates it), from 16 spp on.
    pub rel_mse: Option<f64>,
}

/// Facts about the current scene for `GET /api/state`.
#[derive(Clone, Debug)]
pub struct SceneFacts {
    /// Image size.
    pub width: u32,
    /// Image size.
    pub height: u32,
    /// Integrator name.
    pub integrator: String,
    /// Its max depth (-1: unbounded), if it has one.
    pub max_depth: Option<i64>,
    /// The camera pose.
    pub pose: Pose,
}

impl SceneFacts {
    /// The facts of a loaded scene whose camera is at `pose`.
    pub fn of(loaded: &LoadedScene, pose: Pose) -> SceneFacts {
        let spec = &loaded.integrator_spec;
        let takes = tessera_scene::plugin_declaration("integrator", &spec.name)
            .is_some_and(|d| d.params.iter().any(|p| p.name == "max_depth"));
        SceneFacts {
            width: loaded.scene.camera.width,
            height: loaded.scene.camera.height,
            integrator: spec.name.clone(),
            max_depth: takes.then(|| spec.max_depth.map_or(-1, i64::from)),
            pose,
        }
    }
}

/// The mutable part.
pub struct Inner {
    /// The edits made so far.
    pub edits: Edits,
    /// The base text with the edits applied: the scene being rendered.
    pub text: String,
    /// A loaded scene the render thread has not picked up yet.
    pub pending: Option<Box<LoadedScene>>,
    /// Number of edits taken (the generation of `pending` or of the scene rendering).
    pub generation: u64,
    /// The current scene's facts.
    pub facts: SceneFacts,
    /// The latest frame.
    pub frame: Option<Arc<Frame>>,
}

/// Shared between the request handler and the render thread.
pub struct Shared {
    /// The scene file.
    pub path: PathBuf,
    /// The file's text with the `-D` defines baked in: what edits apply to.
    pub base: String,
    /// Why edits are refused, if they are.
    pub not_editable: Option<String>,
    /// Stop refining at this many spp (`None`: never).
    pub spp_limit: Option<u64>,
    /// Worker threads.
    pub threads: usize,
    /// The mutable part.
    pub inner: Mutex<Inner>,
    /// Wakes the render thread (an edit or shutdown).
    pub wake: Condvar,
    /// Set to cut the pass in flight short (at a tile boundary): an edit or shutdown.
    pub stop: AtomicBool,
    /// Set when the server ends.
    pub shutdown: AtomicBool,
}

impl Shared {
    /// The lock on the mutable part (a panicked holder leaves data that is still whole).
    pub fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Loads `text` as the scene file would be (relative paths beside it), set up to render
    /// as `tessera render` renders it.
    pub fn load(&self, text: &str) -> Result<LoadedScene, String> {
        load(text, &self.path)
    }

    /// Hands a new scene to the render thread: it stops the pass in flight and starts again.
    pub fn hand_over(&self, inner: &mut Inner, loaded: LoadedScene) {
        inner.pending = Some(Box::new(loaded));
        inner.generation += 1;
        self.stop.store(true, Ordering::SeqCst);
        self.wake.notify_all();
    }
}

/// Loads scene text as if read from `path`, with the sampler set up as `tessera render` sets
/// it up for the scene's own sample count (so pass after pass gives the same bits).
pub fn load(text: &str, path: &Path) -> Result<LoadedScene, String> {
    let mut loaded = tessera_scene::load_scene_str(text, path, &[]).map_err(|e| e.to_string())?;
    let spp = loaded.spp;
    loaded.set_sampler(None, spp)?;
    Ok(loaded)
}
