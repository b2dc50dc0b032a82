//! Every material in `tests/bsdf_cases/` evaluates as Mitsuba 3 does.
//!
//! Each `NAME.xml` holds one `<bsdf>` in Mitsuba 3 syntax; `NAME.csv` beside it was written by
//! `scripts/mitsuba_bsdf_eval.py` from Mitsuba 3.9.1 (scalar_rgb) and lists `eval` (cosine
//! included) and `pdf` on a fixed grid of incident directions (both sides) and outgoing
//! directions (the whole sphere). Tessera loads the same file and must give the same numbers:
//! eval within 1e-3 relative plus 1e-5 absolute per channel, pdf within 1e-3 relative plus
//! 1e-5 absolute. Both are single-precision evaluations of the same closed forms, so the
//! tolerance only covers rounding; a wrong factor, sign convention or Fresnel term fails. A
//! case file without its table fails too. A table whose comment states a geometry (`#
//! geometry dp_du=.. dp_dv=.. n=..`, the `bumpmap` cases) is evaluated at a shading point with
//! those partials and that geometric normal; the others at the flat unit parametrisation.

use std::path::Path;

use glam::{Vec2, Vec3};
use tessera_core::geometry::{Partials, ShadingPoint};
use tessera_scene::load_bsdf_file;
use tessera_tests::bsdf::{bsdf_case_files, csv_rows};

const UV: Vec2 = Vec2::new(0.25, 0.75);

fn close(a: f32, b: f32) -> bool {
    (a - b).abs() <= 1e-3 * a.abs().max(b.abs()) + 1e-5
}

/// The partials a table was made at: those its comment states, else none (the flat unit
/// parametrisation).
fn partials(text: &str) -> Option<Partials<'static>> {
    let line = text.lines().find_map(|l| l.strip_prefix("# geometry "))?;
    let mut g = Partials::FLAT;
    for field in line.split_whitespace() {
        let (key, value) = field.split_once('=').expect("key=x,y,z");
        let c: Vec<f32> = value.split(',').map(|x| x.parse().unwrap()).collect();
        let v = Vec3::new(c[0], c[1], c[2]);
        match key {
            "dp_du" => g.dp_du = v,
            "dp_dv" => g.dp_dv = v,
            "n" => g.ng = v,
            _ => panic!("unknown geometry field {key}"),
        }
    }
    Some(g)
}

fn check(case: &Path) -> Vec<String> {
    let bsdf = match load_bsdf_file(case) {
        Ok(b) => b,
        Err(e) => return vec![format!("{e}")],
    };
    let table = case.with_extension("csv");
    let text = match std::fs::read_to_string(&table) {
        Ok(t) => t,
        Err(e) => {
            return vec![format!(
                "{}: {e} (run scripts/mitsuba_bsdf_eval.py)",
                table.display()
            )]
        }
    };
    let g = partials(&text);
    let at = ShadingPoint {
        uv: UV,
        partials: g.as_ref(),
        memo: None,
    };
    let mut bad = Vec::new();
    let mut rows = 0;
    for v in csv_rows(&text, "wi_x") {
        let wi = Vec3::new(v[0], v[1], v[2]);
        let wo = Vec3::new(v[3], v[4], v[5]);
        let want = Vec3::new(v[6], v[7], v[8]);
        let f = bsdf.eval(wi, wo, at);
        let p = bsdf.pdf(wi, wo, at);
        rows += 1;
        if !(0..3).all(|c| close(f[c], want[c])) || !close(p, v[9]) {
            bad.push(format!(
                "{}: wi {wi} wo {wo}: eval {f} (Mitsuba {want}), pdf {p} (Mitsuba {})",
                case.display(),
                v[9]
            ));
        }
    }
    if rows == 0 {
        bad.push(format!("{}: empty table", table.display()));
    }
    bad
}

#[test]
fn every_case_matches_mitsuba() {
    let cases = bsdf_case_files();
    assert!(!cases.is_empty());
    let mut failures = Vec::new();
    for c in &cases {
        let bad = check(c);
        println!("{}: {} mismatches", c.display(), bad.len());
        failures.extend(bad.into_iter().take(5));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_wrong_material_is_caught() {
    // Control: the diffuse table against a diffuse BSDF of another colour.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases");
    let tmp = std::env::temp_dir().join(format!("tessera_bsdf_case_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let xml = tmp.join("diffuse.xml");
    std::fs::write(
        &xml,
        r#"<scene version="3.0.0"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.81"/></bsdf></scene>"#,
    )
    .unwrap();
    std::fs::copy(dir.join("diffuse.csv"), tmp.join("diffuse.csv")).unwrap();
    let bad = check(&xml);
    std::fs::remove_dir_all(&tmp).ok();
    assert!(!bad.is_empty());
}

/// `check` of the table `NAME.csv` against `xml` (a case file written to a scratch folder).
fn check_table_against(table: &str, xml: &str) -> Vec<String> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases");
    let tmp = std::env::temp_dir().join(format!(
        "tessera_bsdf_control_{table}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&tmp).unwrap();
    let case = tmp.join(format!("{table}.xml"));
    std::fs::write(&case, xml).unwrap();
    std::fs::copy(
        dir.join(format!("{table}.csv")),
        tmp.join(format!("{table}.csv")),
    )
    .unwrap();
    let bad = check(&case);
    std::fs::remove_dir_all(&tmp).ok();
    bad
}

#[test]
fn a_slightly_wrong_principled_is_caught() {
    // Controls: each `principled` table against its material with one lobe parameter moved a
    // little (clearcoat gloss 0.4 -> 0.45, eta 1.45 -> 1.46, sheen tint 0.6 -> 0.55).
    let wrap = |body: &str| {
        format!(r#"<scene version="3.0.0"><bsdf type="principled">{body}</bsdf></scene>"#)
    };
    let controls = [
        (
            "principled_clearcoat",
            r#"<rgb name="base_color" value="0.1, 0.3, 0.6"/><float name="roughness" value="0.45"/>
            <float name="clearcoat" value="0.8"/><float name="clearcoat_gloss" value="0.45"/>
            <float name="clearcoat_sampling_rate" value="2"/>"#,
        ),
        (
            "principled_spec_trans",
            r#"<rgb name="base_color" value="0.9, 0.8, 0.6"/><float name="roughness" value="0.3"/>
            <float name="spec_trans" value="0.7"/><float name="eta" value="1.46"/>
            <float name="diffuse_reflectance_sampling_rate" value="0.5"/>"#,
        ),
        (
            "principled_sheen",
            r#"<rgb name="base_color" value="0.6, 0.2, 0.4"/><float name="roughness" value="0.9"/>
            <float name="sheen" value="0.8"/><float name="sheen_tint" value="0.55"/>
            <float name="flatness" value="0.3"/>"#,
        ),
    ];
    for (table, body) in controls {
        let bad = check_table_against(table, &wrap(body));
        println!("{table}, moved: {} mismatches", bad.len());
        assert!(
            !bad.is_empty(),
            "{table}: the moved parameter is not caught"
        );
    }
}

#[test]
fn a_wrong_normal_map_or_roughness_texture_is_caught() {
    // Controls for the textured cases: each table against its material with the texture read
    // differently (the normal map's green channel inverted, the other handedness; the normals
    // never flipped toward the viewer; the sRGB-encoded roughness read raw; the rough glass's
    // textured alpha_u replaced by its constant mean).
    let tex = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases/textures");
    let t = |name: &str| tex.join(name).display().to_string();
    let normalmap = |file: &str, extra: &str, nested: &str| {
        format!(
            r#"<scene version="3.0.0"><bsdf type="normalmap">{extra}
            <texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="{}"/></texture>{nested}</bsdf></scene>"#,
            t(file)
        )
    };
    let conductor = r#"<bsdf type="roughconductor"><string name="material" value="Cu"/>
        <string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/>
        <float name="alpha_v" value="0.35"/></bsdf>"#;
    let controls = [
        (
            "normalmap_roughconductor",
            normalmap("normal_tilt_green_flipped.png", "", conductor),
        ),
        (
            "normalmap_roughconductor",
            normalmap(
                "normal_tilt.png",
                r#"<boolean name="flip_invalid_normals" value="false"/>"#,
                conductor,
            ),
        ),
        (
            "normalmap_diffuse_noflip",
            normalmap(
                "normal_tilt.png",
                r#"<boolean name="flip_invalid_normals" value="false"/>"#,
                r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>"#,
            ),
        ),
        (
            "roughconductor_alpha_texture",
            format!(
                r#"<scene version="3.0.0"><bsdf type="roughconductor"><string name="material" value="Au"/>
                <string name="distribution" value="ggx"/><texture name="alpha" type="bitmap">
                <boolean name="raw" value="true"/><string name="filename" value="{}"/></texture>
                </bsdf></scene>"#,
                t("roughness.png")
            ),
        ),
        (
            "roughdielectric_alpha_uv_texture",
            r#"<scene version="3.0.0"><bsdf type="roughdielectric"><string name="distribution" value="ggx"/>
            <float name="int_ior" value="1.33"/><float name="alpha_u" value="0.3"/>
            <float name="alpha_v" value="0.08"/></bsdf></scene>"#
                .to_string(),
        ),
    ];
    for (table, xml) in controls {
        let bad = check_table_against(table, &xml);
        println!("{table}, changed: {} mismatches", bad.len());
        assert!(
            !bad.is_empty(),
            "{table}: the changed texture is not caught"
        );
    }
}

#[test]
fn a_slightly_wrong_pplastic_is_caught() {
    // Controls: each `pplastic` table against its material with one thing changed a little
    // (eta 1.33 -> 1.36; the two roughnesses swapped; roughplastic, the coupled model of the
    // same parameters, in place of pplastic; the checkerboard albedo replaced by its mean; the
    // eta bitmap replaced by its mean, 1.5).
    let tex = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases/textures");
    let wrap = |plugin: &str, body: &str| {
        format!(r#"<scene version="3.0.0"><bsdf type="{plugin}">{body}</bsdf></scene>"#)
    };
    let aniso = |eta: &str, au: &str, av: &str| {
        wrap(
            "pplastic",
            &format!(
                r#"<string name="distribution" value="ggx"/><float name="alpha_u" value="{au}"/>
                <float name="alpha_v" value="{av}"/><float name="eta" value="{eta}"/>
                <rgb name="diffuse_reflectance" value="0.05, 0.03, 0.1"/>"#
            ),
        )
    };
    let controls = [
        ("pplastic_aniso_eta", aniso("1.36", "0.08", "0.45")),
        ("pplastic_aniso_eta", aniso("1.33", "0.45", "0.08")),
        ("pplastic_default", wrap("roughplastic", "")),
        (
            "pplastic_textured",
            wrap(
                "pplastic",
                &format!(
                    r#"<rgb name="diffuse_reflectance" value="0.425, 0.3, 0.6"/>
                    <texture name="alpha" type="bitmap"><string name="filename" value="{}"/>
                    </texture><rgb name="specular_reflectance" value="0.5, 0.6, 0.7"/>"#,
                    tex.join("roughness.png").display()
                ),
            ),
        ),
        (
            "pplastic_eta_texture",
            wrap(
                "pplastic",
                r#"<float name="eta" value="1.5"/><float name="alpha_u" value="0.3"/>
                <float name="alpha_v" value="0.1"/>
                <rgb name="diffuse_reflectance" value="0.3, 0.6, 0.2"/>"#,
            ),
        ),
    ];
    for (table, xml) in controls {
        let bad = check_table_against(table, &xml);
        println!("{table}, changed: {} mismatches", bad.len());
        assert!(!bad.is_empty(), "{table}: the change is not caught");
    }
    // The unchanged material passes the same route (the controls fail for their change).
    assert!(check_table_against("pplastic_aniso_eta", &aniso("1.33", "0.08", "0.45")).is_empty());
}

#[test]
fn a_wrong_bump_map_is_caught() {
    // Controls for the bumpmap cases: the diffuse and rough-conductor tables against their
    // materials with the height's scale negated or doubled, and against the right material
    // evaluated without the table's geometry (the flat unit parametrisation instead of its
    // partials), so the gradient's sign, its size and the use of dp/du, dp/dv all matter.
    let tex = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases/textures");
    let height = tex.join("height.png").display().to_string();
    let bump = |scale: f32, nested: &str| {
        format!(
            r#"<scene version="3.0.0"><bsdf type="bumpmap"><float name="scale" value="{scale}"/>
            <texture name="height" type="bitmap"><boolean name="raw" value="true"/>
            <string name="filename" value="{height}"/></texture>{nested}</bsdf></scene>"#
        )
    };
    let diffuse = r#"<bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>"#;
    let conductor = r#"<bsdf type="roughconductor"><string name="material" value="Cu"/>
        <string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/>
        <float name="alpha_v" value="0.35"/></bsdf>"#;
    // The right materials first: they must pass, or the controls prove nothing.
    for (table, xml) in [
        ("bumpmap_diffuse", bump(1.0, diffuse)),
        ("bumpmap_roughconductor", bump(0.6, conductor)),
    ] {
        let bad = check_table_against(table, &xml);
        assert!(bad.is_empty(), "{table}: {}", bad.join("\n"));
    }
    for (table, xml) in [
        ("bumpmap_diffuse", bump(-1.0, diffuse)),
        ("bumpmap_diffuse", bump(2.0, diffuse)),
        ("bumpmap_roughconductor", bump(-0.6, conductor)),
        ("bumpmap_roughconductor", bump(1.2, conductor)),
    ] {
        let bad = check_table_against(table, &xml);
        println!("{table}, wrong scale: {} mismatches", bad.len());
        assert!(!bad.is_empty(), "{table}: a wrong scale is not caught");
    }
    // The right material at the wrong geometry: the table without its geometry line.
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("bsdf_cases");
    let tmp = std::env::temp_dir().join(format!("tessera_bump_flat_{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let text = std::fs::read_to_string(dir.join("bumpmap_diffuse.csv")).unwrap();
    assert!(text.contains("# geometry "));
    let flat: String = text
        .lines()
        .filter(|l| !l.starts_with("# geometry "))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(tmp.join("bumpmap_diffuse.csv"), flat).unwrap();
    std::fs::write(tmp.join("bumpmap_diffuse.xml"), bump(1.0, diffuse)).unwrap();
    let bad = check(&tmp.join("bumpmap_diffuse.xml"));
    std::fs::remove_dir_all(&tmp).ok();
    println!(
        "bumpmap_diffuse without its geometry: {} mismatches",
        bad.len()
    );
    assert!(!bad.is_empty(), "the partials are not used");
}
