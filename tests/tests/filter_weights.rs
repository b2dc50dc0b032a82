//! The filters with negative lobes (`mitchell`, `catmullrom`, `lanczos`) are sampled
//! proportionally to `|f|` and weight each sample by `sign(f) * ∫|f| / ∫f` per axis, so the
//! estimator's expectation is the filter-normalised integral `∫ f g / ∫ f` of the image `g`,
//! which is what Mitsuba 3 computes by splatting. Student t-tests against closed forms, each
//! with controls that must be rejected:
//!
//! - the sampler alone: `g(x, y) = h(x) h(y)` with `h(x) = 1 + x²`, whose integral over each step
//!   of the filter's table is a polynomial (controls: the sign dropped, the weight dropped);
//! - the render path: an emitting half-plane whose edge falls between two pixel columns, so a
//!   pixel's expected value is the filter's signed mass on the lit side of the edge — checked
//!   through both per-sample paths (the group path of `path` and the single-sample path of
//!   `path` with `max_depth` 2). Control: the same pixels against the unweighted expectation
//!   `∫|f|` on the lit side over `∫|f|`, which is what a render that forgot the weight gets.
//!
//! The step tables (31 steps over `|x| ∈ [0, r]`, each the filter at its start, as Mitsuba 3
//! tabulates filters) are written here in f64, independently of the core.

use tessera_core::camera::{Filter, LanczosFilter, MitchellFilter};
use tessera_lab::stats::{sidak_alpha, t_test_mean, Moments, Pcg32};
use tessera_tests::filter_reference::{lanczos, mitchell};
use tessera_tests::{load_xml, region_stats, render_loaded, z_p_value};

const STEPS: usize = 31;

/// t-tests in this file: 3 filters in the sampler test, 2 integrators x 4 pixels in the render
/// test.
const N_TESTS: usize = 3 + 8;

fn alpha() -> f64 {
    sidak_alpha(0.01, N_TESTS)
}

/// A filter's step table: `values[i]` on `|x| ∈ [r i / 31, r (i + 1) / 31]`.
struct Steps {
    r: f64,
    values: Vec<f64>,
}

impl Steps {
    fn new(r: f64, f: impl Fn(f64) -> f64) -> Self {
        let values = (0..STEPS).map(|i| f(r * i as f64 / STEPS as f64)).collect();
        Steps { r, values }
    }

    /// `∫ g(f(x)) p(x) dx` over `[a, b]` (clipped to the support), where `p` has the primitive
    /// `big_p`, for the step function `f`.
    fn integral(&self, g: impl Fn(f64) -> f64, big_p: impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let h = self.r / STEPS as f64;
        let mut sum = 0.0;
        for (i, &v) in self.values.iter().enumerate() {
            let (lo, hi) = (h * i as f64, h * (i + 1) as f64);
            // The step on the positive side and its mirror on the negative side.
            for (s0, s1) in [(lo, hi), (-hi, -lo)] {
                let (x0, x1) = (s0.max(a), s1.min(b));
                if x1 > x0 {
                    sum += g(v) * (big_p(x1) - big_p(x0));
                }
            }
        }
        sum
    }
}

/// The three filters, each with its independent step table.
fn filters() -> Vec<(&'static str, Filter, Steps)> {
    let third = 1.0 / 3.0;
    vec![
        (
            "mitchell",
            Filter::Mitchell(MitchellFilter::new(third as f32, third as f32).unwrap()),
            Steps::new(2.0, |x| mitchell(third, third, x)),
        ),
        (
            "catmullrom",
            Filter::Mitchell(MitchellFilter::catmull_rom()),
            Steps::new(2.0, |x| mitchell(0.0, 0.5, x)),
        ),
        (
            "lanczos",
            Filter::Lanczos(LanczosFilter::new(3).unwrap()),
            Steps::new(3.0, |x| lanczos(3.0, x)),
        ),
    ]
}

fn id(v: f64) -> f64 {
    v
}

#[test]
fn weighted_offsets_average_the_filtered_image() {
    const N: usize = 2_000_000;
    let h = |x: f64| 1.0 + x * x;
    let big_h = |x: f64| x + x * x * x / 3.0;
    for (k, (name, filter, steps)) in filters().into_iter().enumerate() {
        let r = steps.r;
        let one_d = steps.integral(id, big_h, -r, r) / steps.integral(id, |x| x, -r, r);
        let expected = one_d * one_d;
        let (mut weighted, mut unsigned, mut unweighted) =
            (Moments::new(), Moments::new(), Moments::new());
        let mut rng = Pcg32::new(100 + k as u64);
        for _ in 0..N {
            let (o, w) = filter.sample_weighted(rng.next_vec2());
            let w = f64::from(w.expect("a filter with negative lobes weighs its samples"));
            let g = h(f64::from(o.x)) * h(f64::from(o.y));
            weighted.push(w * g);
            unsigned.push(w.abs() * g);
            unweighted.push(g);
        }
        let t = t_test_mean(&weighted, expected);
        println!("{name}: mean {} expected {expected}: {t}", weighted.mean());
        assert!(t.passes(alpha()), "{name}: {t}");
        // Controls: the sign dropped, the weight dropped.
        for (what, m) in [("unsigned", &unsigned), ("unweighted", &unweighted)] {
            let t = t_test_mean(m, expected);
            assert!(!t.passes(alpha()), "{name} {what} passed: {t}");
        }
    }
}

/// An 8 x 1 image of an emitting half-plane (radiance 1) whose edge, `x = 0` on the optical
/// axis, falls between columns 3 and 4.
fn half_plane(filter: &str, integrator: &str) -> String {
    format!(
        r#"<scene version="3.0.0">
    {integrator}
    <sensor type="perspective">
        <float name="fov" value="10"/>
        <string name="fov_axis" value="x"/>
        <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="8"/><integer name="height" value="1"/>
            {filter}
        </film>
    </sensor>
    <shape type="rectangle">
        <transform name="to_world"><scale value="50"/><translate x="50"/></transform>
        <emitter type="area"><rgb name="radiance" value="1, 1, 1"/></emitter>
    </shape>
</scene>"#
    )
}

#[test]
fn rendered_edge_is_the_signed_filter_mass() {
    const SPP: u64 = 1 << 17;
    let integrators = [
        ("group path", r#"<integrator type="path"/>"#),
        (
            "single-sample path",
            r#"<integrator type="path"><integer name="max_depth" value="2"/></integrator>"#,
        ),
    ];
    // Which side is lit: the box filter's image is exactly 0 or 1 per pixel.
    let boxed = render_loaded(
        &load_xml(
            &half_plane(r#"<rfilter type="box"/>"#, integrators[0].1),
            &[],
        ),
        16,
        1,
    );
    let lit_right = region_stats(&boxed, 7, 0, 1, 1)[0].0 == 1.0;
    assert_eq!(
        region_stats(&boxed, 0, 0, 1, 1)[0].0,
        if lit_right { 0.0 } else { 1.0 }
    );
    let (_, filter, steps) = filters().remove(0);
    assert!(matches!(filter, Filter::Mitchell(_)));
    let mut controls_rejected = 0;
    for (k, (iname, integrator)) in integrators.iter().enumerate() {
        let l = load_xml(
            &half_plane(r#"<rfilter type="mitchell"/>"#, integrator),
            &[],
        );
        let fb = render_loaded(&l, SPP, 7 + k as u64);
        // Columns 2..6: pixel centres 1.5 and 0.5 pixels from the edge on either side.
        for col in 2..6u32 {
            let centre = col as f64 + 0.5 - 4.0;
            let d = if lit_right { centre } else { -centre };
            // Lit offsets o: centre + o on the lit side, i.e. o > -d.
            let r = steps.r;
            let expected = steps.integral(id, |x| x, -d, r) / steps.integral(id, |x| x, -r, r);
            let unweighted =
                steps.integral(f64::abs, |x| x, -d, r) / steps.integral(f64::abs, |x| x, -r, r);
            let (mean, var) = region_stats(&fb, col, 0, 1, 1)[0];
            let p = z_p_value((mean - expected) / var.sqrt());
            println!(
                "{iname}: column {col}: {mean} (expected {expected}, unweighted {unweighted}), \
                 p = {p:.3e}"
            );
            assert!(
                p >= alpha(),
                "{iname}: column {col}: {mean} vs {expected}, p = {p:.3e}"
            );
            if z_p_value((mean - unweighted) / var.sqrt()) < alpha() {
                controls_rejected += 1;
            }
        }
    }
    // Control: the unweighted expectation (what a render that ignored the weights would give)
    // is rejected at every column of both paths.
    assert_eq!(
        controls_rejected, 8,
        "the unweighted expectation was not rejected everywhere"
    );
}
