//! Every integrator reads its sample dimensions by the fixed per-bounce layout
//! (`tessera_core::sampling::dimension_of`): each draw is preceded by a `start_stage` and stays
//! within that stage's budget, no dimension is read twice in one sample, and the camera reads
//! only the camera dimensions (and a thin lens its two lens dimensions). Checked exactly, by a sampler that records what it is asked for,
//! on the repository's scenes (mirrors, glass, delta and area lights, environments) with every
//! integrator and Russian roulette from the first bounce, and on `cbox.xml` seen through a thin
//! lens. Control: the checker flags a draw past
//! a stage's budget, a stage started twice and a start inside a stage.
use tessera_core::camera::{Projection, ThinLens};
use tessera_core::integrator::{DirectIntegrator, Heuristic, Integrator};
use tessera_core::sampling::{
    dimension_of, Sampler, Stage, BOUNCE_DIMENSIONS, CAMERA_DIMENSIONS, LENS_DIMENSION,
};
use tessera_core::scene::Scene;
use tessera_lab::stats::rng::Pcg32;
use tessera_tests::load_file;

/// A sampler that checks the layout: uniform values from a PCG32, and a list of violations.
struct LayoutChecker {
    rng: Pcg32,
    /// Next dimension.
    dim: u32,
    /// End of the current stage's budget.
    end: u32,
    /// Dimensions read in this sample.
    read: Vec<u32>,
    /// Draws per stage (camera, light, BSDF, roulette, lens), to show the check is not vacuous.
    draws: [u64; 5],
    stage: usize,
    errors: Vec<String>,
}

impl LayoutChecker {
    fn new(seed: u64) -> Self {
        LayoutChecker {
            rng: Pcg32::new(seed),
            dim: 0,
            end: CAMERA_DIMENSIONS,
            read: Vec::new(),
            draws: [0; 5],
            stage: 0,
            errors: Vec::new(),
        }
    }

    /// Starts a new camera sample.
    fn start_sample(&mut self) {
        self.dim = 0;
        self.end = CAMERA_DIMENSIONS;
        self.stage = 0;
        self.read.clear();
    }
}

impl Sampler for LayoutChecker {
    fn next_1d(&mut self) -> f32 {
        if self.dim >= self.end {
            self.errors.push(format!(
                "dimension {} read past its stage's budget",
                self.dim
            ));
        }
        if self.read.contains(&self.dim) {
            self.errors
                .push(format!("dimension {} read twice in one sample", self.dim));
        }
        self.read.push(self.dim);
        self.draws[self.stage] += 1;
        self.dim += 1;
        self.rng.next_f32()
    }

    fn start_dimension(&mut self, dim: u32) {
        let (stage, width) = match dim.checked_sub(CAMERA_DIMENSIONS) {
            _ if dim == LENS_DIMENSION => (4, 2),
            Some(d) if d % BOUNCE_DIMENSIONS == 0 => (1, 3),
            Some(d) if d % BOUNCE_DIMENSIONS == 3 => (2, 3),
            Some(d) if d % BOUNCE_DIMENSIONS == 6 => (3, 1),
            _ => {
                self.errors
                    .push(format!("start at dimension {dim}, not a stage's first"));
                (0, 0)
            }
        };
        self.dim = dim;
        self.end = dim + width;
        self.stage = stage;
    }
}

/// Traces `spp` samples of every pixel of `scene` with `integrator` through the checker, the
/// way `RenderJob::sample` does (camera 2D, the lens's 2D for a thin lens, then the integrator).
fn check(scene: &Scene, integrator: &Integrator, spp: u32, s: &mut LayoutChecker) {
    for y in 0..scene.camera.height {
        for x in 0..scene.camera.width {
            for _ in 0..spp {
                s.start_sample();
                let offset = scene.filter.sample(s.next_2d());
                let pos = glam::Vec2::new(x as f32 + 0.5 + offset.x, y as f32 + 0.5 + offset.y);
                let ray = scene.camera.sample_ray(pos, s);
                let _ = integrator.li(scene, ray, s);
            }
        }
    }
}

#[test]
fn every_integrator_follows_the_dimension_layout() {
    let mut s = LayoutChecker::new(1);
    let scenes = [
        "cbox.xml",
        "veach_mis.xml",
        "materials.xml",
        "cs500_spheres.xml",
        "envmap.xml",
    ];
    for name in scenes {
        let defines = [
            ("res", "12"),
            ("rfilter", "box"),
            ("rr_depth", "1"),
            ("max_depth", "12"),
        ];
        let mut l = load_file(name, &defines);
        for integ in [
            "path_mis",
            "path_half",
            "path_ems",
            "path_mats",
            "direct",
            "direct_ems",
            "direct_mats",
            "direct_mis",
        ] {
            l.set_integrator(Some(integ), None)
                .expect("known integrator");
            check(&l.scene, &l.integrator, 4, &mut s);
            assert!(s.errors.is_empty(), "{name} {integ}: {:?}", &s.errors[..1]);
        }
        // Several samples per strategy: each reads its own dimensions.
        let direct = Integrator::Direct(DirectIntegrator {
            emitter_samples: 3,
            bsdf_samples: 2,
            heuristic: Heuristic::Power,
            hide_emitters: false,
        });
        check(&l.scene, &direct, 2, &mut s);
        assert!(
            s.errors.is_empty(),
            "{name} direct 3+2: {:?}",
            &s.errors[..1]
        );
    }
    // The Cornell box through a thin lens focused on the far wall.
    let mut l = load_file(
        "cbox.xml",
        &[("res", "12"), ("rfilter", "box"), ("rr_depth", "1")],
    );
    let Projection::Perspective(pinhole) = l.scene.camera.projection.clone() else {
        unreachable!("cbox has a pinhole camera")
    };
    l.scene.camera.projection = Projection::ThinLens(ThinLens {
        pinhole,
        aperture_radius: 0.3,
        focus_distance: 10.0,
    });
    for integ in ["path_mis", "path_ems", "path_mats", "direct_mis"] {
        l.set_integrator(Some(integ), None)
            .expect("known integrator");
        check(&l.scene, &l.integrator, 16, &mut s);
        assert!(
            s.errors.is_empty(),
            "thin lens {integ}: {:?}",
            &s.errors[..1]
        );
    }
    eprintln!("draws (camera, light, bsdf, roulette, lens): {:?}", s.draws);
    assert!(s.draws.iter().all(|&n| n > 10_000), "{:?}", s.draws);
}

#[test]
fn the_layout_checker_catches_violations() {
    let mut s = LayoutChecker::new(2);
    // Four draws in a three-dimension stage.
    s.start_sample();
    s.start_stage(0, Stage::Light);
    for _ in 0..4 {
        let _ = s.next_1d();
    }
    assert_eq!(s.errors.len(), 1, "{:?}", s.errors);
    // The same stage twice in one sample.
    s.errors.clear();
    s.start_sample();
    s.start_stage(1, Stage::Bsdf);
    s.next_1d();
    s.start_stage(1, Stage::Bsdf);
    s.next_1d();
    assert_eq!(s.errors.len(), 1, "{:?}", s.errors);
    // A start inside a stage, and a camera that reads a third dimension.
    s.errors.clear();
    s.start_sample();
    s.start_dimension(dimension_of(2, Stage::Light) + 1);
    assert_eq!(s.errors.len(), 1, "{:?}", s.errors);
    s.errors.clear();
    s.start_sample();
    for _ in 0..3 {
        let _ = s.next_1d();
    }
    assert_eq!(s.errors.len(), 1, "{:?}", s.errors);
}
