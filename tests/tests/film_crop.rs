//! Mitsuba 3's crop window (`hdrfilm`'s `crop_offset_x/y`, `crop_width/height`): the image is
//! that window of the whole film's image, as Mitsuba 3 renders it (checked with Mitsuba 3.9.1:
//! a 32x16 crop at (24, 8) of the 64x64 Cornell box has the mean of the full image's pixels
//! x 24..56, y 8..24).
//!
//! - Each projection's rays through a cropped film are bit for bit the whole film's rays through
//!   the same film positions moved by the offset (control: without the offset they differ).
//! - A cropped render of the Cornell box agrees, block by block, with the same window of
//!   Mitsuba 3's render of the whole film (`scenes/refs/cbox_64x64_mitsuba.exr`); the control,
//!   the window moved down by 8 pixels, is rejected.
//! - Windows off the film are located errors.
use glam::Vec2;
use tessera::image_io::{read_image, RgbImage};
use tessera_lab::stats::sidak_alpha;
use tessera_scene::{load_scene_str, LoadedScene};
use tessera_tests::{render_loaded, scenes_dir, worst_against_reference_rect};

const RES: u32 = 64;
const SPP: u64 = 512;
const REF_SPP: f64 = 16384.0;
const BLOCK: u32 = 4;

/// `scenes/cbox.xml` at 64x64 with a box filter and `film` added to its film.
fn cbox(film: &str, sensor: &str) -> Result<LoadedScene, String> {
    let path = scenes_dir().join("cbox.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let marker = "<integer name=\"height\" value=\"$res\"/>";
    assert!(text.contains(marker), "the film of scenes/cbox.xml changed");
    let text = text
        .replacen(marker, &format!("{marker}{film}"), 1)
        .replacen("<sensor type=\"perspective\">", sensor, 1);
    let defines = [("res", "64"), ("rfilter", "box")].map(|(k, v)| (k.into(), v.into()));
    load_scene_str(&text, &path, &defines).map_err(|e| e.to_string())
}

fn crop(x: u32, y: u32, w: u32, h: u32) -> String {
    format!(
        "<integer name=\"crop_offset_x\" value=\"{x}\"/><integer name=\"crop_offset_y\" value=\"{y}\"/>\
         <integer name=\"crop_width\" value=\"{w}\"/><integer name=\"crop_height\" value=\"{h}\"/>"
    )
}

const PERSPECTIVE: &str = "<sensor type=\"perspective\">";
const THINLENS: &str = "<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.1\"/>\
                        <float name=\"focus_distance\" value=\"9\"/>";
const ORTHOGRAPHIC: &str = "<sensor type=\"orthographic\">";

#[test]
fn cropped_rays_are_the_whole_films_rays_at_the_offset() {
    for sensor in [PERSPECTIVE, THINLENS, ORTHOGRAPHIC] {
        let (full, cropped) = if sensor == ORTHOGRAPHIC {
            (ortho(""), ortho(&crop(24, 8, 32, 16)))
        } else {
            (
                cbox("", sensor).unwrap(),
                cbox(&crop(24, 8, 32, 16), sensor).unwrap(),
            )
        };
        let (a, b) = (&full.scene.camera, &cropped.scene.camera);
        assert_eq!((b.width, b.height), (32, 16));
        let mut moved = 0;
        for (px, py) in [(0.0, 0.0), (0.5, 0.5), (13.25, 7.75), (31.9, 15.9)] {
            let pos = Vec2::new(px, py);
            for lens in [Vec2::new(0.5, 0.5), Vec2::new(0.1, 0.8)] {
                let r = b.generate_ray_through(pos, lens);
                let s = a.generate_ray_through(pos + Vec2::new(24.0, 8.0), lens);
                assert_eq!(
                    (r.o, r.d, r.t_max),
                    (s.o, s.d, s.t_max),
                    "{sensor} at {pos}"
                );
                // Control: the whole film's ray at the unmoved position is another ray.
                let c = a.generate_ray_through(pos, lens);
                moved += usize::from(c.o != r.o || c.d != r.d);
            }
        }
        assert_eq!(moved, 8, "{sensor}: the offset changed nothing");
    }
}

/// The Cornell box seen through an orthographic camera (its file has a perspective one).
fn ortho(film: &str) -> LoadedScene {
    let path = scenes_dir().join("cbox.xml");
    let text = std::fs::read_to_string(&path).unwrap();
    let text = text
        .replacen("<float name=\"fov\" value=\"39.3077\"/>", "", 1)
        .replacen("<string name=\"fov_axis\" value=\"x\"/>", "", 1);
    let marker = "<integer name=\"height\" value=\"$res\"/>";
    let text = text
        .replacen(marker, &format!("{marker}{film}"), 1)
        .replacen(PERSPECTIVE, ORTHOGRAPHIC, 1);
    let defines = [("res", "64"), ("rfilter", "box")].map(|(k, v)| (k.into(), v.into()));
    load_scene_str(&text, &path, &defines).unwrap_or_else(|e| panic!("{e}"))
}

/// The `w` x `h` window at (`x`, `y`) of `img`.
fn window(img: &RgbImage, x: u32, y: u32, w: u32, h: u32) -> RgbImage {
    let mut data = Vec::with_capacity((w * h) as usize);
    for j in y..y + h {
        for i in x..x + w {
            data.push(img.data[(j * img.width + i) as usize]);
        }
    }
    RgbImage {
        width: w,
        height: h,
        data,
    }
}

#[test]
fn a_cropped_render_is_mitsubas_window() {
    let reference = read_image(&scenes_dir().join("refs/cbox_64x64_mitsuba.exr")).unwrap();
    assert_eq!((reference.width, reference.height), (RES, RES));
    let mut loaded = cbox(&crop(24, 8, 32, 16), PERSPECTIVE).unwrap();
    loaded.set_integrator(Some("path_mis"), None).unwrap();
    let ours = render_loaded(&loaded, SPP, 41);
    assert_eq!((ours.width, ours.height), (32, 16));
    let alpha = sidak_alpha(0.01, (32 / BLOCK * 16 / BLOCK) as usize * 3);
    let p_at = |y: u32| {
        let r = window(&reference, 24, y, 32, 16);
        worst_against_reference_rect(&ours, &ours, SPP, &r, REF_SPP, BLOCK)
    };
    let (p, what) = p_at(8);
    eprintln!("crop vs Mitsuba's window: worst p = {p:.3e} at {what}");
    assert!(p >= alpha, "p = {p:.3e} < {alpha:.3e} at {what}");
    let (p, what) = p_at(16);
    eprintln!("control, the window 8 pixels lower: worst p = {p:.3e} at {what}");
    assert!(p < alpha, "a window 8 pixels lower passed (p = {p:.3e})");
}

#[test]
fn windows_off_the_film_are_located_errors() {
    for (film, says) in [
        (
            crop(40, 0, 32, 16),
            "the crop window 32x16 at (40, 0) does not lie on the 64x64 film",
        ),
        (
            crop(0, 60, 8, 8),
            "the crop window 8x8 at (0, 60) does not lie on the 64x64 film",
        ),
        (crop(0, 0, 0, 8), "crop_width"),
    ] {
        let Err(e) = cbox(&film, PERSPECTIVE) else {
            panic!("{film}: accepted")
        };
        assert!(e.contains("cbox.xml:"), "{e}");
        assert!(e.contains(says), "{e}");
    }
    // Offsets alone: the window runs to the film's far edges.
    let l = cbox(
        "<integer name=\"crop_offset_x\" value=\"60\"/>",
        PERSPECTIVE,
    )
    .unwrap();
    assert_eq!((l.scene.camera.width, l.scene.camera.height), (4, 64));
    // The whole film as a window is no crop at all.
    let l = cbox(&crop(0, 0, 64, 64), PERSPECTIVE).unwrap();
    assert!(l.scene.camera.crop.is_none());
}
