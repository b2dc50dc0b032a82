//! `tessera view`'s HTTP API, in process: a view started on port 0 over a 32x32 scene, talked to
//! with a few lines of HTTP over `TcpStream`. The frame after N spp is `tessera render` of
//! `/api/scene.xml` at N spp bit for bit, before and after camera and material edits (controls:
//! the frame differs from the render at N-1 spp, and the edits change it); the PNG is the
//! render's sRGB codes; the error estimate in `/api/state` is within a factor of 2 of the error
//! measured against a converged render (control: a render with a quarter of the samples is
//! outside that band); bad requests are refused with 400/404 and change nothing while the render
//! goes on.
use std::collections::HashMap;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use tessera::image_io::{read_image, RgbImage};
use tessera_lab::bench::errors;
use tessera_view::{Config, View};

/// A small scene of its own: a diffuse ball (id `ball`) on a diffuse floor under a constant sky.
const SCENE: &str = r#"<scene version="3.0.0">
    <default name="res" value="32"/>
    <integrator type="path"><integer name="max_depth" value="4"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm">
            <integer name="width" value="$res"/><integer name="height" value="$res"/>
            <rfilter type="box"/>
        </film>
    </sensor>
    <shape type="sphere"><point name="center" value="0, 0.5, 0"/><float name="radius" value="0.5"/>
        <bsdf type="diffuse" id="ball"><rgb name="reflectance" value="0.2, 0.6, 0.3"/></bsdf>
    </shape>
    <shape type="rectangle">
        <transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/></transform>
        <bsdf type="diffuse"/>
    </shape>
    <emitter type="constant"><rgb name="radiance" value="1, 1, 1"/></emitter>
</scene>
"#;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("tessera-view-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn config(dir: &Path, spp_limit: Option<u64>) -> Config {
    let scene = dir.join("scene.xml");
    std::fs::write(&scene, SCENE).unwrap();
    Config {
        scene,
        defines: vec![],
        bind: "127.0.0.1".into(),
        port: 0,
        threads: 2,
        integrator: None,
        max_depth: None,
        sampler: None,
        spp_limit,
    }
}

fn start(dir: &Path, spp_limit: Option<u64>) -> View {
    View::start(&config(dir, spp_limit))
        .expect("the view starts")
        .0
}

struct Reply {
    status: u16,
    headers: HashMap<String, String>,
    body: Vec<u8>,
}

/// One HTTP/1.1 request on its own connection.
fn http(addr: SocketAddr, method: &str, path: &str, body: &[u8]) -> Reply {
    http_from(addr, method, path, body, "")
}

/// [`http`] with extra header lines (each ending in CRLF).
fn http_from(addr: SocketAddr, method: &str, path: &str, body: &[u8], extra: &str) -> Reply {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let head = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\n{extra}Connection: close\r\nContent-Length: {}\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).unwrap();
    let _ = s.write_all(body); // the server may refuse before reading a large body
    let mut raw = Vec::new();
    s.read_to_end(&mut raw).unwrap();
    let split = raw
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("a header");
    let head = String::from_utf8_lossy(&raw[..split]).to_string();
    let mut lines = head.lines();
    let status = lines
        .next()
        .unwrap()
        .split(' ')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    let headers = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(k, v)| (k.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    Reply {
        status,
        headers,
        body: raw[split + 4..].to_vec(),
    }
}

fn state(addr: SocketAddr) -> serde_json::Value {
    let r = http(addr, "GET", "/api/state", b"");
    assert_eq!(r.status, 200);
    serde_json::from_slice(&r.body).unwrap()
}

fn post(addr: SocketAddr, path: &str, json: &str) -> Reply {
    http(addr, "POST", path, json.as_bytes())
}

/// Waits until the state's generation is `generation` and its frame has `spp` spp.
fn wait_for(addr: SocketAddr, generation: u64, spp: u64) {
    let t0 = Instant::now();
    loop {
        let s = state(addr);
        if s["generation"] == generation && s["spp"] == spp {
            return;
        }
        assert!(t0.elapsed() < Duration::from_secs(30), "timed out: {s}");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// An image served by the API, decoded (written to a file for the driver's reader).
fn decode(dir: &Path, name: &str, bytes: &[u8]) -> RgbImage {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    read_image(&p).unwrap()
}

/// `tessera render` (in process) of `scene` at `spp`, written as EXR and read back.
fn render(scene: &Path, spp: u64) -> RgbImage {
    use clap::Parser;
    let out = scene.with_extension(format!("{spp}.exr"));
    let args = [
        "tessera",
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--spp",
        &spp.to_string(),
        "--quiet",
    ];
    let cli = tessera_cli::Cli::try_parse_from(args).unwrap();
    let tessera_cli::Command::Render(a) = cli.command else {
        unreachable!()
    };
    assert_eq!(tessera_cli::render::run(&a), 0);
    read_image(&out).unwrap()
}

fn bits(img: &RgbImage) -> Vec<u32> {
    img.data.iter().flatten().map(|c| c.to_bits()).collect()
}

/// The served scene text, saved beside the original (its relative paths resolve there).
fn served_scene(addr: SocketAddr, dir: &Path, name: &str) -> PathBuf {
    let r = http(addr, "GET", "/api/scene.xml", b"");
    assert_eq!(r.status, 200);
    let p = dir.join(name);
    std::fs::write(&p, &r.body).unwrap();
    p
}

#[test]
fn the_frame_after_n_spp_is_tessera_render_of_the_served_scene_before_and_after_edits() {
    const N: u64 = 8;
    let dir = scratch("bits");
    let view = start(&dir, Some(N));
    let addr = view.addr();
    wait_for(addr, 1, N);
    let exr = http(addr, "GET", "/api/image.exr", b"");
    assert_eq!(exr.status, 200);
    assert_eq!(exr.headers["x-tessera-spp"], N.to_string());
    let frame = decode(&dir, "frame0.exr", &exr.body);
    assert!(state(addr)["rel_mse"].is_null(), "no estimate below 16 spp");
    let scene = served_scene(addr, &dir, "served0.xml");
    let reference = render(&scene, N);
    assert_eq!(
        bits(&frame),
        bits(&reference),
        "the frame is the render at {N} spp"
    );
    assert_ne!(
        bits(&frame),
        bits(&render(&scene, N - 1)),
        "control: {} spp differs",
        N - 1
    );
    // The PNG is the render's sRGB codes (read back as codes / 255); +1 stop brightens it.
    let png = http(addr, "GET", "/api/image.png", b"");
    assert_eq!(png.headers["content-type"], "image/png");
    let png = decode(&dir, "frame0.png", &png.body);
    let codes = tessera::image_io::to_srgb8(&reference);
    let served: Vec<u8> = png
        .data
        .iter()
        .flatten()
        .map(|c| (c * 255.0).round() as u8)
        .collect();
    assert_eq!(served, codes);
    let mean = |v: &[u8]| v.iter().map(|c| *c as f64).sum::<f64>() / v.len() as f64;
    assert!(
        mean(&codes) > 40.0,
        "the image shows the scene: mean code {}",
        mean(&codes)
    );
    let bright = http(addr, "GET", "/api/image.png?exposure=1", b"");
    let bright = decode(&dir, "bright.png", &bright.body);
    let bright: Vec<u8> = bright
        .data
        .iter()
        .flatten()
        .map(|c| (c * 255.0).round() as u8)
        .collect();
    assert!(mean(&bright) > mean(&codes) + 10.0);

    // A camera edit and a material edit: each starts a new generation. That accumulation
    // restarts from 0 shows in the bits: a frame holding any sample of the old scene would not
    // be the render of the new one.
    let r = post(addr, "/api/camera", r#"{"orbit": [30, 10]}"#);
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    assert_eq!(state(addr)["generation"], 2);
    let r = post(
        addr,
        "/api/material",
        r#"{"bsdf": "ball", "param": "reflectance", "value": [0.9, 0.1, 0.1]}"#,
    );
    assert_eq!(r.status, 200, "{}", String::from_utf8_lossy(&r.body));
    wait_for(addr, 3, N);
    let exr = http(addr, "GET", "/api/image.exr", b"");
    assert_eq!(exr.headers["x-tessera-generation"], "3");
    let edited = decode(&dir, "frame1.exr", &exr.body);
    assert_ne!(bits(&edited), bits(&frame), "the edits change the image");
    let scene = served_scene(addr, &dir, "served1.xml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(
        text.contains(r#"<rgb name="reflectance" value="0.9, 0.1, 0.1"/>"#),
        "{text}"
    );
    assert!(text.contains("<lookat origin="), "{text}");
    assert_eq!(
        bits(&edited),
        bits(&render(&scene, N)),
        "edited: the render at {N} spp"
    );

    // Reset view: back to the file's camera (with the edited material).
    assert_eq!(post(addr, "/api/camera", r#"{"reset": true}"#).status, 200);
    wait_for(addr, 4, N);
    let text = std::fs::read_to_string(served_scene(addr, &dir, "served2.xml")).unwrap();
    assert!(text.contains(r#"<lookat origin="0, 1, 5" target="0, 0.5, 0" up="0, 1, 0"/>"#));
    view.stop();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_error_estimate_is_the_measured_error() {
    const N: u64 = 64;
    let dir = scratch("error");
    let view = start(&dir, Some(N));
    let addr = view.addr();
    wait_for(addr, 1, N);
    let estimate = state(addr)["rel_mse"]
        .as_f64()
        .expect("an estimate at 64 spp");
    let frame = decode(
        &dir,
        "frame.exr",
        &http(addr, "GET", "/api/image.exr", b"").body,
    );
    let scene = served_scene(addr, &dir, "served.xml");
    let converged = render(&scene, 4096);
    let measured = errors(&frame.data, &converged.data).relmse;
    println!("relMSE at {N} spp: estimated {estimate:.3e}, measured {measured:.3e}");
    assert!(
        estimate > measured / 2.0 && estimate < measured * 2.0,
        "estimated {estimate:.3e}, measured {measured:.3e}"
    );
    // Control: the error of a render with a quarter of the samples is outside the band.
    let coarse = errors(&render(&scene, N / 4).data, &converged.data).relmse;
    assert!(
        coarse > estimate * 2.0,
        "{coarse:.3e} against {estimate:.3e}"
    );
}

#[test]
fn bad_requests_are_refused_change_nothing_and_the_render_goes_on() {
    let dir = scratch("bad");
    let view = start(&dir, None);
    let addr = view.addr();
    let t0 = Instant::now();
    while state(addr)["spp"].as_u64() == Some(0) {
        assert!(t0.elapsed() < Duration::from_secs(30));
        std::thread::sleep(Duration::from_millis(10));
    }
    let before = http(addr, "GET", "/api/scene.xml", b"").body;
    let huge = vec![b' '; 70 * 1024];
    let cases: &[(&str, &str, &[u8], u16)] = &[
        ("POST", "/api/camera", b"{not json", 400),
        ("POST", "/api/camera", br#"{"orbit": [1e9, 0]}"#, 400),
        (
            "POST",
            "/api/camera",
            br#"{"origin": [0,0,0], "target": [0,0,0]}"#,
            400,
        ),
        ("POST", "/api/camera", br#"{"spin": 3}"#, 400),
        (
            "POST",
            "/api/material",
            br#"{"bsdf": "ball", "param": "reflectance", "value": [1.5, 0, 0]}"#,
            400,
        ),
        (
            "POST",
            "/api/material",
            br#"{"bsdf": "nobody", "param": "reflectance", "value": 0.5}"#,
            400,
        ),
        (
            "POST",
            "/api/material",
            br#"{"bsdf": 7, "param": "reflectance", "value": 0.5}"#,
            400,
        ),
        (
            "POST",
            "/api/material",
            br#"{"bsdf": 0, "param": "shininess", "value": 0.5}"#,
            400,
        ),
        ("POST", "/api/integrator", br#"{"type": "warp"}"#, 400),
        ("POST", "/api/integrator", br#"{"max_depth": -7}"#, 400),
        (
            "POST",
            "/api/integrator",
            br#"{"type": "direct", "max_depth": 3}"#,
            400,
        ),
        ("POST", "/api/material", &huge, 400),
        ("GET", "/api/camera", b"", 400),
        ("GET", "/api/image.png?exposure=nan", b"", 400),
        ("GET", "/api/nothing", b"", 404),
        ("GET", "/../etc/passwd", b"", 404),
    ];
    for (method, path, body, status) in cases {
        let r = http(addr, method, path, body);
        let msg = String::from_utf8_lossy(&r.body).to_string();
        assert_eq!(r.status, *status, "{method} {path}: {msg}");
        assert_eq!(msg.trim_end().lines().count(), 1, "one line: {msg:?}");
    }
    // Nothing bad was taken, and the render goes on.
    let s = state(addr);
    assert_eq!(s["generation"], 1, "{s}");
    assert_eq!(http(addr, "GET", "/api/scene.xml", b"").body, before);
    let spp = s["spp"].as_u64().unwrap();
    let t0 = Instant::now();
    while state(addr)["spp"].as_u64().unwrap() <= spp {
        assert!(t0.elapsed() < Duration::from_secs(30), "the render goes on");
        std::thread::sleep(Duration::from_millis(10));
    }
    // A page of another site posting an edit is refused; controls: the same request from the
    // view's own page, and a good integrator edit, are taken.
    let edit = br#"{"dolly": 0.1}"#;
    let other = http_from(
        addr,
        "POST",
        "/api/camera",
        edit,
        "Origin: http://evil.example\r\n",
    );
    assert_eq!(other.status, 403);
    assert_eq!(state(addr)["generation"], 1);
    let own = format!("Origin: http://{addr}\r\n");
    assert_eq!(
        http_from(addr, "POST", "/api/camera", edit, &own).status,
        200
    );
    assert_eq!(state(addr)["generation"], 2);
    let ok = post(addr, "/api/integrator", r#"{"type": "direct"}"#);
    assert_eq!(ok.status, 200, "{}", String::from_utf8_lossy(&ok.body));
    assert_eq!(state(addr)["generation"], 3);
    assert_eq!(state(addr)["integrator"], "direct");
    view.stop();
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn command_line_overrides_and_defines_are_written_into_the_served_scene() {
    const N: u64 = 4;
    let dir = scratch("flags");
    let cfg = Config {
        integrator: Some("path".into()),
        max_depth: Some(2),
        sampler: Some("zsobol".into()),
        defines: vec![("res".into(), "24".into())],
        ..config(&dir, Some(N))
    };
    let view = View::start(&cfg).expect("the view starts").0;
    let addr = view.addr();
    wait_for(addr, 1, N);
    assert_eq!(state(addr)["resolution"], serde_json::json!([24, 24]));
    assert_eq!(state(addr)["max_depth"], 2);
    let scene = served_scene(addr, &dir, "served.xml");
    let text = std::fs::read_to_string(&scene).unwrap();
    assert!(text.contains(r#"<sampler type="zsobol">"#), "{text}");
    assert!(
        text.contains(r#"<integer name="max_depth" value="2"/>"#),
        "{text}"
    );
    assert!(
        text.contains(r#"<default name="res" value="24"/>"#),
        "{text}"
    );
    let frame = decode(
        &dir,
        "f.exr",
        &http(addr, "GET", "/api/image.exr", b"").body,
    );
    assert_eq!(bits(&frame), bits(&render(&scene, N)));
    // Control: the served scene with the file's own sampler back is another image.
    let independent = dir.join("independent.xml");
    std::fs::write(&independent, text.replace("zsobol", "independent")).unwrap();
    assert_ne!(bits(&frame), bits(&render(&independent, N)));
    view.stop();
    let _ = std::fs::remove_dir_all(&dir);
}
