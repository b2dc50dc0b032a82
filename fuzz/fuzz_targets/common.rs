//! Shared by the fuzz targets: a private scratch directory holding the input under test and a
//! few small files the input may refer to (an include, meshes, an MTL library).
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

const OBJ: &str =
    "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nusemtl red\nf 1 2 3\n";
const MTL: &str = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl glass\nillum 7\nNi 1.5\n";
const PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
const INC: &str = "<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"inc\"/></scene>\n";

/// The scratch directory (created once per process, with `mesh.obj`, `m.mtl`, `mesh.ply` and
/// `inc.xml` in it).
pub fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("tessera-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("scratch directory");
        for (name, text) in [
            ("mesh.obj", OBJ),
            ("m.mtl", MTL),
            ("mesh.ply", PLY),
            ("inc.xml", INC),
        ] {
            std::fs::write(d.join(name), text).expect("scratch file");
        }
        d
    })
}

/// Writes `data` to `name` in the scratch directory and returns its path (unused by
/// `xml_scene`).
#[allow(dead_code)]
pub fn put(name: &str, data: &[u8]) -> PathBuf {
    let p = dir().join(name);
    std::fs::write(&p, data).expect("scratch file");
    p
}
