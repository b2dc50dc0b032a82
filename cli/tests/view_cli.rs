//! `tessera view` as a command: it prints the URL it serves (the real port when asked for port
//! 0), serves the page from the binary, and refuses bad input with exit code 2 and one line.
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Command, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_tessera");
const SCENES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");

#[test]
fn view_prints_its_url_and_serves_the_page() {
    let mut child = Command::new(BIN)
        .args([
            "view",
            &format!("{SCENES}/cbox.xml"),
            "-D",
            "res=16",
            "--port",
            "0",
        ])
        .args(["--threads", "1", "--spp", "2"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line.split_whitespace().find(|w| w.starts_with("http://"));
    let addr = url
        .and_then(|u| u.strip_prefix("http://"))
        .map(|a| a.trim_end_matches('/'));
    let addr = addr
        .unwrap_or_else(|| panic!("no URL in {line:?}"))
        .to_string();
    assert!(
        addr.starts_with("127.0.0.1:") && !addr.ends_with(":0"),
        "{addr}"
    );
    let mut s = TcpStream::connect(&addr).unwrap();
    write!(
        s,
        "GET / HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut page = String::new();
    s.read_to_string(&mut page).unwrap();
    child.kill().unwrap();
    let _ = child.wait();
    assert!(page.starts_with("HTTP/1.1 200"), "{page}");
    assert!(page.contains("<canvas id=\"view\""), "the page is served");
    assert!(
        !page.contains("https://") && !page.contains("src=\"http"),
        "nothing external"
    );
}

#[test]
fn view_refuses_bad_input_with_one_line() {
    for (args, words) in [
        (vec!["view", "no/such/scene.xml"], "cannot read"),
        (
            vec![
                "view",
                &format!("{SCENES}/cbox.xml"),
                "--integrator",
                "warp",
            ],
            "unknown integrator \"warp\"",
        ),
        (
            vec!["view", &format!("{SCENES}/cbox.xml"), "-D", "res=-3"],
            "cbox.xml:",
        ),
    ] {
        let out = Command::new(BIN).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(words), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}
