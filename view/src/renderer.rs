//! The render thread: passes of a growing number of samples per pixel over the whole image,
//! each bringing every pixel up to the pass's end with the driver's [`render_span`] and
//! [`Span::UpTo`] (the machinery of `tessera render`'s progressive passes), so the frame after
//! N spp is the same bits as `tessera render` of the same scene at N spp, whatever the pass
//! sizes were. After a change the accumulation starts again from 0; on large images the
//! first frame after a change is a 1 spp preview at a quarter of the resolution per edge.
use crate::state::{Frame, Shared};
use std::sync::atomic::Ordering;
use std::sync::Arc;
use std::time::{Duration, Instant};
use tessera::progressive::{spp_range, taken};
use tessera::render::{render_span, Framebuffer, RenderOptions, Span};
use tessera_core::error_estimate::{halves_rel_mse, MIN_CHECK_SPP};
use tessera_core::film::PixelAccum;
use tessera_core::integrator::NoProbe;
use tessera_core::render::RenderJob;
use tessera_scene::LoadedScene;

/// Images with at least this many pixels get a reduced-resolution preview after a change.
pub const PREVIEW_PIXELS: u64 = 256 * 256;

/// What a pass aims to last: short enough that the page refreshes often.
const PASS_SECONDS: f64 = 0.5;

/// One generation's accumulation.
struct Accumulation {
    loaded: Box<LoadedScene>,
    generation: u64,
    fb: Framebuffer,
    started: Instant,
    /// Seconds spent in completed passes and their samples.
    busy: f64,
    /// spp of the next pass.
    next: u64,
    preview_due: bool,
    /// The accumulators at an earlier pass's end and its spp: the first half of the error
    /// estimate, replaced once the render has doubled it.
    half: Option<(u64, Vec<PixelAccum>)>,
}

/// The relMSE floor of the estimate (that of `tessera bench` and `--target-error`).
const ERROR_FLOOR: f64 = 0.01;

/// Runs until shutdown.
pub fn run(shared: Arc<Shared>) {
    let opts = RenderOptions {
        threads: shared.threads.max(1),
        tile_size: 32,
        ..Default::default()
    };
    let mut acc: Option<Accumulation> = None;
    while !shared.shutdown.load(Ordering::SeqCst) {
        // Clear the flag before looking for a new scene: an edit after the look sets it again.
        shared.stop.store(false, Ordering::SeqCst);
        {
            let mut inner = shared.lock();
            if let Some(loaded) = inner.pending.take() {
                let (w, h) = (loaded.scene.camera.width, loaded.scene.camera.height);
                acc = Some(Accumulation {
                    fb: Framebuffer::with_footprint(w, h, loaded.scene.splat.as_ref()),
                    generation: inner.generation,
                    loaded,
                    started: Instant::now(),
                    busy: 0.0,
                    next: 1,
                    preview_due: w as u64 * h as u64 >= PREVIEW_PIXELS,
                    half: None,
                });
            }
            let idle = match &acc {
                None => true,
                Some(a) => shared.spp_limit.is_some_and(|l| spp_range(&a.fb).0 >= l),
            };
            if idle {
                let _unused = shared
                    .wake
                    .wait_timeout(inner, Duration::from_millis(200))
                    .map_err(|_| ());
                continue;
            }
        }
        let Some(a) = acc.as_mut() else { continue };
        if a.preview_due {
            a.preview_due = false;
            if let Some(frame) = preview(a, &opts, &shared) {
                shared.lock().frame = Some(Arc::new(frame));
            }
            continue;
        }
        pass(a, &opts, &shared);
    }
}

/// Renders the next pass; publishes the frame when it completes.
fn pass(a: &mut Accumulation, opts: &RenderOptions, shared: &Shared) {
    let low = spp_range(&a.fb).0;
    let mut end = low.saturating_add(a.next);
    if let Some(l) = shared.spp_limit {
        end = end.min(l);
    }
    let job = RenderJob::new(&a.loaded.scene, &a.loaded.integrator, a.loaded.seed);
    let t0 = Instant::now();
    let done = render_span::<NoProbe>(
        &job,
        opts,
        &mut a.fb,
        Span::UpTo(end),
        Some(&shared.stop),
        &mut |_, _| {},
    );
    if !done.complete {
        return; // an edit or shutdown: the loop's top sees it
    }
    let dt = t0.elapsed().as_secs_f64().max(1e-6);
    a.busy += dt;
    // The next pass: as many spp as fit in PASS_SECONDS, at most double this one.
    let rate = (end - low) as f64 / dt;
    a.next = ((rate * PASS_SECONDS) as u64).clamp(1, (end - low).saturating_mul(2));
    // The error estimate of `tessera render --target-error`, from the samples since the kept
    // state against those before it.
    let error = match &a.half {
        Some((_, before)) if end >= MIN_CHECK_SPP => {
            halves_rel_mse(before, &a.fb.pixels, ERROR_FLOOR)
        }
        _ => None,
    };
    if a.half.as_ref().is_none_or(|(s, _)| end >= 2 * *s) {
        a.half = Some((end, a.fb.pixels.clone()));
    }
    let frame = Frame {
        width: a.fb.width,
        height: a.fb.height,
        rgb: a.fb.rgb(),
        spp: end,
        preview: false,
        generation: a.generation,
        elapsed: a.started.elapsed().as_secs_f64(),
        samples_per_second: taken(&a.fb) as f64 / a.busy.max(1e-9),
        rel_mse: error,
    };
    let mut inner = shared.lock();
    if inner.pending.is_none() {
        inner.frame = Some(Arc::new(frame));
    }
}

/// 1 spp at a quarter of the resolution per edge (at least 1 pixel), into a buffer of its own:
/// the accumulation proper starts after it, from 0.
fn preview(a: &mut Accumulation, opts: &RenderOptions, shared: &Shared) -> Option<Frame> {
    let cam = &mut a.loaded.scene.camera;
    let (w, h) = (cam.width, cam.height);
    let (pw, ph) = ((w / 4).max(1), (h / 4).max(1));
    (cam.width, cam.height) = (pw, ph);
    let mut fb = Framebuffer::with_footprint(pw, ph, a.loaded.scene.splat.as_ref());
    let job = RenderJob::new(&a.loaded.scene, &a.loaded.integrator, a.loaded.seed);
    let span = Span::UpTo(1);
    let done = render_span::<NoProbe>(
        &job,
        opts,
        &mut fb,
        span,
        Some(&shared.stop),
        &mut |_, _| {},
    );
    let cam = &mut a.loaded.scene.camera;
    (cam.width, cam.height) = (w, h);
    done.complete.then(|| Frame {
        width: pw,
        height: ph,
        rgb: fb.rgb(),
        spp: 0,
        preview: true,
        generation: a.generation,
        elapsed: a.started.elapsed().as_secs_f64(),
        samples_per_second: 0.0,
        rel_mse: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Pose;
    use crate::edits::Edits;
    use crate::state::{Inner, SceneFacts};
    use std::path::Path;
    use std::sync::atomic::AtomicBool;
    use std::sync::{Condvar, Mutex};

    fn scene(res: u32) -> String {
        format!(
            r#"<scene version="3.0.0">
            <sensor type="perspective"><float name="fov" value="40"/>
                <transform name="to_world"><lookat origin="0, 0, 4" target="0, 0, 0" up="0, 1, 0"/></transform>
                <film type="hdrfilm"><integer name="width" value="{res}"/><integer name="height" value="{res}"/>
                <rfilter type="box"/></film></sensor>
            <shape type="sphere"><bsdf type="diffuse"/></shape>
            <emitter type="constant"/></scene>"#
        )
    }

    #[test]
    fn the_preview_is_the_scene_at_a_quarter_resolution_and_the_camera_is_restored() {
        let loaded = crate::state::load(&scene(256), Path::new("inline.xml")).unwrap();
        let facts = SceneFacts::of(&loaded, Pose::of_scene(&loaded));
        let shared = Shared {
            path: "inline.xml".into(),
            base: String::new(),
            not_editable: None,
            spp_limit: None,
            threads: 2,
            inner: Mutex::new(Inner {
                edits: Edits::default(),
                text: String::new(),
                pending: None,
                generation: 1,
                facts,
                frame: None,
            }),
            wake: Condvar::new(),
            stop: AtomicBool::new(false),
            shutdown: AtomicBool::new(false),
        };
        let opts = RenderOptions {
            threads: 2,
            ..Default::default()
        };
        let mut a = Accumulation {
            fb: Framebuffer::new(256, 256),
            loaded: Box::new(loaded),
            generation: 1,
            started: Instant::now(),
            busy: 0.0,
            next: 1,
            preview_due: true,
            half: None,
        };
        let f = preview(&mut a, &opts, &shared).expect("a preview");
        assert!(f.preview && f.spp == 0);
        assert_eq!((f.width, f.height), (64, 64));
        let cam = &a.loaded.scene.camera;
        assert_eq!(
            (cam.width, cam.height),
            (256, 256),
            "the camera is restored"
        );
        // The same scene loaded at 64x64 and rendered at 1 spp: the same bits.
        let small = crate::state::load(&scene(64), Path::new("inline.xml")).unwrap();
        let job = RenderJob::new(&small.scene, &small.integrator, small.seed);
        let fb = tessera::render::render(&job, 0..1, &opts, &mut |_, _| {});
        assert_eq!(f.rgb, fb.rgb());
        pass(&mut a, &opts, &shared);
        let full = shared.lock().frame.clone().expect("a full frame");
        assert_eq!((full.width, full.spp, full.preview), (256, 1, false));
    }
}
