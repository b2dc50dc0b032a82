//! `Bsdf::sample_inputs`: the integrators skip drawing the random inputs a BSDF says it ignores,
//! which is only exact if `sample` really ignores them. For every material in
//! `tests/bsdf_cases/` and the Chalmers/Wakame ones, sampling with the ignored input changed gives
//! the same bits, over many directions and inputs. Control: the materials that claim an input do
//! change with it somewhere, so the comparison can fail.
use glam::{Vec2, Vec3};
use tessera_core::bsdf::{Bsdf, BsdfSample, Mirror};
use tessera_lab::stats::Pcg32;
use tessera_scene::load_bsdf_file;
use tessera_tests::bsdf::{bsdf_case_files, load_bsdf_xml, uniform_direction};

const UV: Vec2 = Vec2::new(0.25, 0.75);
const TRIALS: usize = 4000;

fn materials() -> Vec<(String, Bsdf)> {
    let paths = bsdf_case_files();
    let mut v: Vec<(String, Bsdf)> = paths
        .iter()
        .map(|p| {
            let name = p.file_stem().unwrap().to_string_lossy().into_owned();
            (name, load_bsdf_file(p).expect("case loads"))
        })
        .collect();
    let snippets = [
        (
            "blinnphong_metal",
            r#"<bsdf type="blinnphong_metal"><float name="shininess" value="50"/><rgb name="color" value="0.9, 0.6, 0.3"/><float name="fresnel" value="0.3"/></bsdf>"#,
        ),
        (
            "twosided diffuse",
            r#"<bsdf type="twosided"><bsdf type="diffuse"/></bsdf>"#,
        ),
        (
            "twosided roughconductor",
            r#"<bsdf type="twosided"><bsdf type="roughconductor"/></bsdf>"#,
        ),
    ];
    for (name, xml) in snippets {
        v.push((name.to_string(), load_bsdf_xml(xml)));
    }
    v.push(("mirror".to_string(), Bsdf::Mirror(Mirror {})));
    v
}

fn bits(s: Option<BsdfSample>) -> Option<[u32; 8]> {
    s.map(|s| {
        [
            s.wo.x.to_bits(),
            s.wo.y.to_bits(),
            s.wo.z.to_bits(),
            s.weight.x.to_bits(),
            s.weight.y.to_bits(),
            s.weight.z.to_bits(),
            s.pdf.to_bits(),
            u32::from(s.delta) ^ s.eta.to_bits(),
        ]
    })
}

/// Number of trials in which changing (u1, u2) as asked changes the sample.
fn changes(b: &Bsdf, rng: &mut Pcg32, change_u1: bool, change_u2: bool) -> usize {
    let mut changed = 0;
    for _ in 0..TRIALS {
        let wi: Vec3 = uniform_direction(Vec2::new(rng.next_f32(), rng.next_f32()), true);
        let (u1, u2) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
        let (v1, v2) = (rng.next_f32(), Vec2::new(rng.next_f32(), rng.next_f32()));
        let a = b.sample(wi, u1, u2, UV);
        let c = b.sample(
            wi,
            if change_u1 { v1 } else { u1 },
            if change_u2 { v2 } else { u2 },
            UV,
        );
        changed += usize::from(bits(a) != bits(c));
    }
    changed
}

#[test]
fn ignored_sample_inputs_are_really_ignored() {
    let mut rng = Pcg32::new(7);
    let mut skipping = 0;
    for (name, b) in materials() {
        let (uses_u1, uses_u2) = b.sample_inputs();
        if !uses_u1 {
            assert_eq!(changes(&b, &mut rng, true, false), 0, "{name}: u1");
            skipping += 1;
        }
        if !uses_u2 {
            assert_eq!(changes(&b, &mut rng, false, true), 0, "{name}: u2");
            skipping += 1;
        }
    }
    // diffuse, conductors, rough conductors, dielectric, thin dielectric, mirror, Chalmers metal.
    assert!(skipping >= 15, "{skipping} skipped inputs");
}

/// Control: a material that claims an input changes with it (plastic chooses its lobe by `u1`,
/// diffuse its direction by `u2`), so a claim to ignore it would be caught above.
#[test]
fn control_used_inputs_change_the_sample() {
    let mut rng = Pcg32::new(9);
    let plastic = load_bsdf_xml(r#"<bsdf type="plastic"/>"#);
    assert_eq!(plastic.sample_inputs(), (true, true));
    assert!(changes(&plastic, &mut rng, true, false) > TRIALS / 10);
    let diffuse = load_bsdf_xml(r#"<bsdf type="diffuse"/>"#);
    // One-sided: about half the directions (from below) give no sample at all.
    assert!(changes(&diffuse, &mut rng, false, true) > TRIALS / 4);
}

/// The path loop reads a vertex's BSDF traits from the scene's table (filled when the scene is
/// built) instead of asking the BSDF: the table answers what the BSDF itself does, entry by
/// entry, in scenes whose materials differ (one of each kind in `materials.xml`).
#[test]
fn scene_bsdf_traits_are_each_bsdfs_own() {
    use tessera_core::bsdf::BsdfTraits;
    for name in ["materials.xml", "veach_mis.xml", "cbox.xml"] {
        let s = tessera_tests::load_file(name, &[("res", "16")]).scene;
        let mut kinds = std::collections::HashSet::new();
        for (i, b) in s.bsdfs.iter().enumerate() {
            let t = s.bsdf_traits(i as u32);
            assert_eq!(t, BsdfTraits::of(b), "{name}: bsdf {i}");
            assert_eq!(
                (t.uses_u1, t.uses_u2),
                b.sample_inputs(),
                "{name}: bsdf {i}"
            );
            assert_eq!(t.has_smooth, b.has_smooth(), "{name}: bsdf {i}");
            kinds.insert((t.uses_u1, t.uses_u2, t.has_smooth));
        }
        // Control: materials.xml's table is not one entry repeated, so a shifted or constant
        // table would fail above.
        if name == "materials.xml" {
            assert!(kinds.len() >= 3, "{name}: only {} kinds", kinds.len());
        }
    }
}
