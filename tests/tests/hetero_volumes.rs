//! Volumes and the heterogeneous medium's inputs: `gridvolume` lookups agree with Mitsuba 3.9.1's
//! own (`tests/volume_cases/gridvolume_eval.csv`, made by `scripts/mitsuba_gridvolume_eval.py`:
//! every filter and wrap mode, a rotated and scaled `to_world`, `use_grid_bbox` on and off,
//! points inside, near and outside the grid), while a vertex-centred lookup (the control) does
//! not; and every bad input is refused with a located one-line error.
use glam::Vec3;
use tessera_core::medium::{Medium, Volume};
use tessera_scene::load_scene_str;
use tessera_tests::{load_xml, scenes_dir};

fn cases_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("volume_cases")
}

/// The sigma_t volume of a scene holding one heterogeneous medium whose sigma_t is `volume`.
fn sigma_t_of(volume: &str) -> Volume {
    let xml = format!(
        r#"<scene version="3.0.0"><sensor type="perspective"/><integrator type="volpath"/>
<medium type="heterogeneous" id="m">{volume}</medium></scene>"#
    );
    let l = load_xml(&xml, &[]);
    match &l.scene.media.media[0] {
        Medium::Heterogeneous(h) => h.sigma_t.clone(),
        other => panic!("not heterogeneous: {other:?}"),
    }
}

fn grid_xml(filter: &str, wrap: &str, bbox: bool, extra: &str) -> String {
    format!(
        r#"<volume type="gridvolume" name="sigma_t">
  <string name="filename" value="{}"/>
  <string name="filter_type" value="{filter}"/><string name="wrap_mode" value="{wrap}"/>
  <boolean name="use_grid_bbox" value="{bbox}"/>
  <transform name="to_world"><scale x="1.5" y="0.8" z="1.2"/><rotate x="0.6" y="0" z="0.8" angle="30"/>
    <translate x="0.3" y="-0.2" z="0.5"/></transform>{extra}
</volume>"#,
        cases_dir().join("grid.vol").display()
    )
}

#[test]
fn gridvolume_lookups_match_mitsuba() {
    let text = std::fs::read_to_string(cases_dir().join("gridvolume_eval.csv")).expect("csv");
    let mut rows = 0;
    let mut control_differs = 0;
    let mut last: Option<(String, Volume)> = None;
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let key = format!("{},{},{}", f[0], f[1], f[2]);
        if last.as_ref().map(|(k, _)| k != &key).unwrap_or(true) {
            let v = sigma_t_of(&grid_xml(f[0], f[1], f[2] == "1", ""));
            last = Some((key.clone(), v));
        }
        let v = &last.as_ref().expect("volume").1;
        let n: Vec<f32> = f[3..].iter().map(|s| s.parse().expect("number")).collect();
        let p = Vec3::new(n[0], n[1], n[2]);
        let want = Vec3::new(n[3], n[4], n[5]);
        // A nearest lookup on a voxel face reads the side the inverse transform's rounding
        // picks, in Mitsuba and here alike: such points are skipped.
        let local = v.to_world.inv.transform_point3(p);
        let res = match &v.data {
            tessera_core::medium::VolumeData::Grid(g) => g.grid.res(),
            _ => unreachable!(),
        };
        let on_face = (0..3).any(|a| {
            let x = local[a] * res[a] as f32;
            (x - x.round()).abs() < 1e-4
        });
        if f[0] == "nearest" && on_face {
            continue;
        }
        let got = v.eval(p);
        let err = (got - want).abs().max_element();
        assert!(
            err <= 2e-5 * (1.0 + want.abs().max_element()),
            "{key} at {p}: ours {got}, Mitsuba {want}"
        );
        // Control: a vertex-centred grid (values at i / (n - 1)) reads other values.
        let shifted = Vec3::new(
            (local.x * (res[0] - 1) as f32 + 0.5) / res[0] as f32,
            (local.y * (res[1] - 1) as f32 + 0.5) / res[1] as f32,
            (local.z * (res[2] - 1) as f32 + 0.5) / res[2] as f32,
        );
        let vertex = v.eval(v.to_world.m.transform_point3(shifted));
        if (vertex - want).abs().max_element() > 1e-3 {
            control_differs += 1;
        }
        rows += 1;
    }
    println!("{rows} lookups agree; the vertex-centred control differs at {control_differs}");
    assert!(rows >= 270, "only {rows} lookups compared");
    assert!(
        control_differs > rows / 2,
        "the vertex-centred control differs at only {control_differs} of {rows}"
    );
}

#[test]
fn a_constant_sigma_t_fills_the_unit_cube_as_in_mitsuba() {
    let v = sigma_t_of(r#"<rgb name="sigma_t" value="1, 2, 3"/>"#);
    assert_eq!(v.eval(Vec3::splat(0.5)), Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(v.to_world.m, glam::Mat4::IDENTITY);
}

/// Loads `body` inside a scene written to `scenes/` (relative files resolve there) and returns
/// the error.
fn error_of(body: &str) -> String {
    let xml = format!("<scene version=\"3.0.0\">\n{body}\n<sensor type=\"perspective\"/></scene>");
    match load_scene_str(&xml, &scenes_dir().join("hetero-inputs.xml"), &[]) {
        Ok(_) => panic!("loaded: {body}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_volumes_are_refused_where_they_are_written() {
    let dir = std::env::temp_dir().join(format!("tessera-hetero-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let good = std::fs::read(cases_dir().join("grid.vol")).expect("grid.vol");
    let write = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).expect("write");
        p.display().to_string()
    };
    let truncated = write("truncated.vol", &good[..good.len() - 3]);
    let mut v2 = good.clone();
    v2[3] = 2;
    let version = write("version.vol", &v2);
    let mut empty_box = good.clone();
    empty_box[36..40].copy_from_slice(&(-5.0f32).to_le_bytes());
    let empty_box = write("box.vol", &empty_box);
    let medium = |vol: &str| {
        format!("  <medium type=\"heterogeneous\">\n    <volume type=\"gridvolume\" name=\"sigma_t\">\n      {vol}\n    </volume>\n  </medium>")
    };
    let file = |p: &str| format!("<string name=\"filename\" value=\"{p}\"/>");
    let cases = [
        (medium(&file(&truncated)), ":4:7:", "truncated .vol file"),
        (medium(&file(&version)), ":4:7:", "version 2"),
        (medium(&file("missing.vol")), ":4:7:", "cannot read the .vol file"),
        (
            medium(&format!(
                "{}<boolean name=\"use_grid_bbox\" value=\"true\"/>",
                file(&empty_box)
            )),
            ":4:",
            "bounding box",
        ),
        (
            medium(&format!(
                "{}<string name=\"filter_type\" value=\"cubic\"/>",
                file(&truncated)
            )),
            ":4:",
            "filter_type",
        ),
        (medium(""), ":3:5:", "needs \"filename\""),
        (
            "  <medium type=\"heterogeneous\">\n    <float name=\"sigma_t\" value=\"-1\"/>\n  </medium>".into(),
            ":3:5:",
            "sigma_t",
        ),
        (
            "  <medium type=\"heterogeneous\">\n    <texture type=\"checkerboard\" name=\"albedo\"/>\n  </medium>".into(),
            ":3:5:",
            "must be a volume or a value",
        ),
        (
            "  <volume type=\"voxels\" id=\"v\"/>".into(),
            ":2:3:",
            "unknown volume",
        ),
    ];
    for (body, at, words) in cases {
        let e = error_of(&body);
        println!("{e}");
        assert!(
            e.contains(at) && e.contains(words),
            "{e:?} should say {at} {words:?}"
        );
        assert_eq!(e.lines().count(), 1, "{e:?}");
    }
    // Control: the good file with the same markup loads.
    let ok = medium(&file(&cases_dir().join("grid.vol").display().to_string()));
    let xml = format!(
        "<scene version=\"3.0.0\">\n{ok}\n<sensor type=\"perspective\"/><integrator type=\"volpath\"/></scene>"
    );
    assert!(load_scene_str(&xml, &scenes_dir().join("hetero-inputs.xml"), &[]).is_ok());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--stats` counts heterogeneous media's work: a grid medium in a `null` cube under a sky, seen
/// by a 4x4 camera, has null collisions on paths (delta tracking) and shadow rays (ratio
/// tracking); the same scene with a homogeneous medium has none.
#[test]
fn probe_counts_null_collisions() {
    use tessera::render::RenderOptions;
    use tessera::render_stats::render_with_stats;
    use tessera_core::render::RenderJob;
    let count = |medium: &str| {
        let xml = format!(
            r#"<scene version="3.0.0"><integrator type="volpath"/>
  <sensor type="perspective"><transform name="to_world"><lookat origin="0.5, 0.5, 4" target="0.5, 0.5, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  <emitter type="constant"/>
  <shape type="cube"><transform name="to_world"><scale value="0.6"/><translate x="0.5" y="0.5" z="0.5"/></transform>
    <bsdf type="null"/>{medium}</shape>
</scene>"#
        );
        let l = load_scene_str(&xml, &scenes_dir().join("hetero-stats.xml"), &[]).expect("loads");
        let job = RenderJob::new(&l.scene, &l.integrator, 1);
        let opts = RenderOptions {
            threads: 1,
            ..Default::default()
        };
        render_with_stats(&job, 0..64, &opts, &mut |_, _| {}).1
    };
    let c = count(&format!(
        r#"<medium type="heterogeneous" name="interior"><volume type="gridvolume" name="sigma_t">
      <string name="filename" value="{}"/></volume></medium>"#,
        cases_dir().join("grid.vol").display()
    ));
    println!("{c:?}");
    assert!(c.medium_scatters > 0 && c.null_collisions > 0, "{c:?}");
    assert!(c.shadow_null_collisions > 0, "{c:?}");
    // Control: a homogeneous medium has no null collisions.
    let c = count(
        r#"<medium type="homogeneous" name="interior"><float name="sigma_t" value="2"/></medium>"#,
    );
    assert!(c.medium_scatters > 0, "{c:?}");
    assert_eq!((c.null_collisions, c.shadow_null_collisions), (0, 0));
}
