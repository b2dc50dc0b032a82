//! Where relative file names are looked up: Mitsuba's file resolver.
//!
//! Mitsuba keeps a list of folders; a relative name resolves to the first folder that holds
//! it. Loading a scene puts the scene file's folder on the list, each `<path value="..."/>`
//! at the top level puts its folder in front, and an `<include>` reads its file with the
//! including file's folder in front (for the included file's own includes and `<path>`s,
//! which end with it). Files named by objects (meshes, images) resolve after the whole scene
//! is read, against the main file's final list; when none of those folders has the file,
//! Tessera also looks beside the file that names it (Nori's rule, and what files with
//! includes in sub-folders usually mean).

use std::path::{Path, PathBuf};

use super::object::Object;

/// The first `dir/name` that exists, for `dir` in `dirs` in order; `name` itself when it is
/// absolute.
pub(super) fn lookup(dirs: &[PathBuf], name: &Path) -> Option<PathBuf> {
    if name.is_absolute() {
        return Some(name.to_path_buf());
    }
    dirs.iter().map(|d| d.join(name)).find(|p| p.exists())
}

/// The folder of a file (`""` for a bare file name).
pub(super) fn folder_of(file: &Path) -> PathBuf {
    file.parent().map(Path::to_path_buf).unwrap_or_default()
}

impl Object {
    /// The path of a file this object names (a mesh, an image): the first of the scene's
    /// search folders that holds it, else the folder of the file that declares this object.
    /// When no folder holds it, the path beside the declaring file (so the error that follows
    /// names a plausible path).
    pub fn resolve_file(&self, name: &str) -> PathBuf {
        let name = Path::new(name);
        let own = folder_of(&self.loc.file);
        lookup(&self.search, name)
            .or_else(|| lookup(std::slice::from_ref(&own), name))
            .unwrap_or_else(|| own.join(name))
    }
}
