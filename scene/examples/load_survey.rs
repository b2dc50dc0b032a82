//! Loads every scene file named on the command line and prints one line per file:
//! `OK <path>` or `ERR <path>\t<first error>`. Used by `scripts/real_scenes_survey.sh` to
//! measure how many real-world scene files load; it only parses and builds, never renders.

use std::path::Path;

fn main() {
    for arg in std::env::args().skip(1) {
        match tessera_scene::load_scene(Path::new(&arg), &[]) {
            Ok(_) => println!("OK {arg}"),
            Err(e) => {
                let msg = e.to_string();
                let first = msg.lines().next().unwrap_or("");
                println!("ERR {arg}\t{first}");
            }
        }
    }
}
