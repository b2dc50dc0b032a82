//! Light selection at a vertex (`light_selection` `contribution`): its probabilities are a
//! distribution that keeps every light, `pick` draws from exactly that distribution
//! (chi-square), it puts shadow rays where light arrives (a lower-variance emitter estimate on
//! Veach's plates than a uniform choice), and it changes the noise, never the image.
use tessera_core::integrator::NoProbe;
use tessera_core::light::{
    sample_light, LightBound, LightSelection, VertexSelection, UNIFORM_SHARE,
};
use tessera_core::sampling::{IndependentSampler, Sampler};
use tessera_core::scene::Scene;
use tessera_lab::stats::{chi2_test, sidak_alpha, DEFAULT_MIN_EXPECTED};
use tessera_tests::{load_file, load_xml, region_stats, render_loaded, worst_region};

const RES: u32 = 64;
const BLOCK: u32 = 8;

/// Surface points the camera sees on a grid of pixel centres, with their selections.
fn vertices(
    scene: &Scene,
    step: u32,
) -> Vec<(tessera_core::geometry::Interaction, VertexSelection)> {
    let mut out = Vec::new();
    for y in (0..RES).step_by(step as usize) {
        for x in (0..RES).step_by(step as usize) {
            let ray = scene
                .camera
                .generate_ray(glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            let Some(si) = scene.intersect(&ray) else {
                continue;
            };
            let bsdf = &scene.bsdfs[scene.shapes[si.shape as usize].bsdf as usize];
            if !bsdf.has_smooth() {
                continue;
            }
            let wi = si.frame.to_local(si.wi);
            let sel = VertexSelection::new(
                scene.light_bounds(),
                scene.lights().lanes(),
                &si,
                bsdf,
                &si.uv.into(),
                wi,
            )
            .expect("2 to 8 lights give a vertex selection");
            out.push((si, sel));
        }
    }
    out
}

fn scene(name: &str) -> Scene {
    load_file(name, &[("res", "64"), ("rfilter", "box")]).scene
}

/// Probabilities sum to 1 and none falls below the uniform share; the scene-wide choice
/// applies with one light.
#[test]
fn probabilities_form_a_distribution_that_keeps_every_light() {
    for name in ["veach_mis.xml", "cs500_spheres.xml", "materials.xml"] {
        let s = scene(name);
        let n = s.emitters.len();
        let vs = vertices(&s, 2);
        assert!(vs.len() > 100, "{name}: only {} vertices", vs.len());
        for (_, sel) in &vs {
            let total: f32 = (0..n).map(|k| sel.pdf(k)).sum();
            assert!((total - 1.0).abs() < 1e-5, "{name}: sum {total}");
            for k in 0..n {
                assert!(
                    sel.pdf(k) >= UNIFORM_SHARE / n as f32 * (1.0 - 1e-5),
                    "{name}: light {k} has probability {}",
                    sel.pdf(k)
                );
            }
        }
    }
    assert!(scene("cbox.xml").light_bounds().is_empty());
}

/// `pick` draws light k with probability `pdf(k)`: chi-square over 20000 draws at each of a
/// few vertices, Sidak-corrected; a control with the probabilities of the neighbouring vertex
/// (different on glossy plates) is rejected.
#[test]
fn pick_follows_the_probabilities() {
    let s = scene("veach_mis.xml");
    let n = s.emitters.len();
    let vs = vertices(&s, 8);
    let draws = 20000u64;
    let alpha = sidak_alpha(0.01, vs.len());
    let mut rejected_controls = 0;
    for (i, (_, sel)) in vs.iter().enumerate() {
        let mut sampler = IndependentSampler::new(7, i as u32, 0, 0);
        let mut counts = vec![0u64; n];
        for _ in 0..draws {
            let (k, p) = sel.pick(sampler.next_1d());
            assert_eq!(p, sel.pdf(k));
            counts[k] += 1;
        }
        let observed: Vec<f64> = counts.iter().map(|&c| c as f64).collect();
        let p_of = |pdf: &dyn Fn(usize) -> f32| {
            let expected: Vec<f64> = (0..n).map(|k| pdf(k) as f64 * draws as f64).collect();
            chi2_test(&observed, &expected, DEFAULT_MIN_EXPECTED).p_value
        };
        let p = p_of(&|k| sel.pdf(k));
        assert!(p >= alpha, "vertex {i}: p = {p:.3e}");
        let other = &vs[(i + 1) % vs.len()].1;
        let differs = (0..n).any(|k| (other.pdf(k) - sel.pdf(k)).abs() > 0.05);
        if differs && p_of(&|k| other.pdf(k)) < alpha {
            rejected_controls += 1;
        }
    }
    assert!(rejected_controls > 0, "no control was rejected");
}

/// Mean variance of one emitter sample's luminance at the vertices, over `m` samples each.
fn emitter_sample_variance(
    s: &Scene,
    vs: &[(tessera_core::geometry::Interaction, VertexSelection)],
    own: bool,
) -> f64 {
    let m = 256;
    let mut total = 0.0;
    for (i, (si, sel)) in vs.iter().enumerate() {
        let bsdf = &s.bsdfs[s.shapes[si.shape as usize].bsdf as usize];
        let wi = si.frame.to_local(si.wi);
        let (mut sum, mut sum2) = (0.0f64, 0.0f64);
        for j in 0..m {
            let mut sampler = IndependentSampler::new(3, i as u32, 0, j);
            let sel = own.then_some(sel);
            let v = sample_light(
                s,
                si,
                bsdf,
                &si.uv.into(),
                wi,
                &mut sampler,
                false,
                sel,
                &mut NoProbe,
            )
            .map_or(0.0, |ls| tessera_core::emitter::luminance(ls.value) as f64);
            sum += v;
            sum2 += v * v;
        }
        let mean = sum / m as f64;
        total += sum2 / m as f64 - mean * mean;
    }
    total / vs.len() as f64
}

/// On Veach's glossy plates the vertex's own choice gives the emitter estimate at least half
/// the variance of a uniform choice (measured: about a quarter).
#[test]
fn shadow_rays_go_where_light_arrives() {
    let mut l = load_file("veach_mis.xml", &[("res", "64"), ("rfilter", "box")]);
    let vs = vertices(&l.scene, 2);
    let own = emitter_sample_variance(&l.scene, &vs, true);
    l.scene.set_light_selection(LightSelection::Uniform);
    let uniform = emitter_sample_variance(&l.scene, &vs, false);
    eprintln!("emitter sample variance: vertex selection {own:.4e}, uniform {uniform:.4e}");
    assert!(own < 0.5 * uniform, "{own:.4e} vs uniform {uniform:.4e}");
}

/// Renders with the vertex choice and with a scene-wide one agree region by region (path_mis
/// and direct_mis, whose MIS weights read the selection probability of the vertex a ray left),
/// as do path_mis and path_ems, which weighs no strategy by density.
#[test]
fn selection_changes_the_noise_not_the_image() {
    let cases = [
        ("veach_mis.xml", "path_mis", LightSelection::Uniform),
        (
            "cs500_spheres.xml",
            "path_ems",
            LightSelection::Contribution,
        ),
        ("cs500_spheres.xml", "path_mis", LightSelection::Power),
        ("cs500_spheres.xml", "direct_mis", LightSelection::Uniform),
    ];
    let alpha = sidak_alpha(0.01, cases.len() * (RES / BLOCK).pow(2) as usize * 3);
    for (i, (name, other, how)) in cases.into_iter().enumerate() {
        let mut l = load_file(name, &[("res", "64"), ("rfilter", "box")]);
        let integrator = if other == "direct_mis" {
            "direct_mis"
        } else {
            "path_mis"
        };
        l.set_integrator(Some(integrator), None)
            .expect("integrator");
        let ours = render_loaded(&l, 256, 31 + i as u64);
        l.set_integrator(Some(other), None).expect("integrator");
        l.scene.set_light_selection(how);
        let theirs = render_loaded(&l, 256, 41 + i as u64);
        let (p, what) = worst_region(&ours, RES, BLOCK, |bx, by, k| {
            region_stats(&theirs, bx * BLOCK, by * BLOCK, BLOCK, BLOCK)[k]
        });
        eprintln!(
            "{name}: {integrator} (contribution) vs {other} ({how:?}): worst p = {p:.3e} at {what}"
        );
        assert!(
            p >= alpha,
            "{name}: {integrator} vs {other} ({how:?}): p = {p:.3e} at {what}"
        );
    }
}

/// Each light kind gets its bound: a sphere its cone, a rectangle and a disk a one-sided flat
/// light facing where the shape's normal (after `flip_normals`) points, a cube a solid, a point
/// light a point; `light_selection` `power` and `uniform` turn vertex selection off.
#[test]
fn each_light_gets_its_bound() {
    let xml = |selection: &str| {
        format!(
            r#"<scene version="3.0.0">
            <integrator type="path"><string name="light_selection" value="{selection}"/></integrator>
            <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="4"/>
                <integer name="height" value="4"/></film></sensor>
            <shape type="sphere"><float name="radius" value="0.5"/>
                <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
            <shape type="rectangle"><boolean name="flip_normals" value="true"/>
                <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
            <shape type="disk"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
            <shape type="cube"><emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>
            <emitter type="point"><point name="position" value="0, 0, 5"/></emitter>
            </scene>"#
        )
    };
    let l = load_xml(&xml("contribution"), &[]);
    let b = l.scene.light_bounds();
    assert_eq!(b.len(), 5);
    assert!(matches!(b[0], LightBound::Sphere { radius, .. } if radius == 0.5));
    assert!(
        matches!(b[1], LightBound::Flat { normal, area, .. }
        if normal == -glam::Vec3::Z && (area - 4.0).abs() < 1e-5),
        "{:?}",
        b[1]
    );
    assert!(
        matches!(b[2], LightBound::Flat { normal, .. } if normal == glam::Vec3::Z),
        "{:?}",
        b[2]
    );
    assert!(
        matches!(b[3], LightBound::Solid { area, .. } if (area - 24.0).abs() < 1e-4),
        "{:?}",
        b[3]
    );
    assert!(matches!(b[4], LightBound::Point { .. }), "{:?}", b[4]);
    for other in ["power", "uniform"] {
        assert!(
            load_xml(&xml(other), &[]).scene.light_bounds().is_empty(),
            "{other}"
        );
    }
}
