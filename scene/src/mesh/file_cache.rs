//! Mesh files read once per scene load however many shapes name them.
//!
//! Test and showcase scenes often place one file many times, each with its own transform and
//! material (Mitsuba's BSDF test grid reads one sphere OBJ for twelve shapes), and parsing was
//! most of such a load. Before the shapes are built, the loader counts how often each file is
//! named ([`Plan`]); a file named more than once is parsed at its first use and its object-space
//! data kept until its last use takes it. A file named once is never kept, so a large mesh
//! does not cost a second copy while the scene builds. Each shape still transforms its own
//! copy, so sharing changes no value.
//!
//! The plan lives in a thread-local for the duration of one load (the shape builders are
//! plugin functions with a fixed signature) and is dropped with the guard [`Plan::enter`]
//! returns, whatever way the load ends.
use super::data::MeshData;
use crate::error::InputError;
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// What a read depends on: the file (its canonical path), the reader, and which mesh of the
/// file (`serialized` files hold several).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) struct ReadKey {
    path: PathBuf,
    reader: &'static str,
    index: u64,
}

impl ReadKey {
    /// The key of reading mesh `index` of `path` with `reader`; `None` when the file cannot be
    /// found (the read then reports it).
    pub(crate) fn new(path: &Path, reader: &'static str, index: u64) -> Option<ReadKey> {
        Some(ReadKey {
            path: std::fs::canonicalize(path).ok()?,
            reader,
            index,
        })
    }
}

/// A file's uses still to come and, after the first, its data.
#[derive(Default)]
struct Entry {
    uses_left: usize,
    data: Option<Arc<MeshData>>,
}

/// The reads a load will make, counted before it builds its shapes.
#[derive(Default)]
pub(crate) struct Plan {
    entries: HashMap<ReadKey, Entry>,
}

thread_local! {
    static PLAN: RefCell<Option<Plan>> = const { RefCell::new(None) };
}

impl Plan {
    /// Counts one more use of `key`.
    pub(crate) fn count(&mut self, key: ReadKey) {
        self.entries.entry(key).or_default().uses_left += 1;
    }

    /// Makes this the plan of the loads on this thread until the guard drops (a nested load
    /// keeps the outer plan).
    pub(crate) fn enter(mut self) -> PlanGuard {
        self.entries.retain(|_, e| e.uses_left > 1);
        let installed = PLAN.with(|p| {
            let mut p = p.borrow_mut();
            if p.is_some() {
                return false;
            }
            *p = Some(self);
            true
        });
        PlanGuard { installed }
    }
}

/// Ends the plan it installed when dropped.
pub(crate) struct PlanGuard {
    installed: bool,
}

impl Drop for PlanGuard {
    fn drop(&mut self) {
        if self.installed {
            PLAN.with(|p| p.borrow_mut().take());
        }
    }
}

/// The data `read` returns for `key`: shared with an earlier use of the same read when the plan
/// counted more than one, else read now. Errors are not kept (the load stops at the first).
pub(crate) fn read_shared(
    key: Option<ReadKey>,
    read: impl FnOnce() -> Result<MeshData, InputError>,
) -> Result<MeshData, InputError> {
    let Some(key) = key else { return read() };
    let planned = PLAN.with(|p| {
        let mut p = p.borrow_mut();
        let entry = p.as_mut()?.entries.get_mut(&key)?;
        entry.uses_left = entry.uses_left.saturating_sub(1);
        Some((entry.data.clone(), entry.uses_left))
    });
    let Some((held, uses_left)) = planned else {
        return read();
    };
    let data = match held {
        Some(d) => d,
        None => Arc::new(read()?),
    };
    PLAN.with(|p| {
        if let Some(entries) = p.borrow_mut().as_mut().map(|p| &mut p.entries) {
            match uses_left {
                0 => {
                    entries.remove(&key);
                }
                _ => {
                    if let Some(e) = entries.get_mut(&key) {
                        e.data = Some(data.clone());
                    }
                }
            }
        }
    });
    // The last use takes the data without copying it.
    Ok(Arc::try_unwrap(data).unwrap_or_else(|d| (*d).clone()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    fn key_of(path: &Path) -> Option<ReadKey> {
        ReadKey::new(path, "obj", 0)
    }

    /// A file counted three times is read once and each use gets the same data; one counted
    /// once is read at each use (never kept); without a plan every use reads. Control: the
    /// counts are what the plan changes, so without `enter` the shared file is read thrice.
    #[test]
    fn a_file_named_often_is_read_once() {
        let dir = std::env::temp_dir().join(format!("tessera_file_cache_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (a, b) = (dir.join("a.obj"), dir.join("b.obj"));
        std::fs::write(&a, "v 0 0 0\n").unwrap();
        std::fs::write(&b, "v 0 0 0\n").unwrap();
        let reads = Cell::new(0);
        let data = || {
            reads.set(reads.get() + 1);
            Ok(MeshData {
                positions: vec![[1.0, 2.0, 3.0]],
                ..MeshData::default()
            })
        };
        for planned in [true, false] {
            reads.set(0);
            let mut plan = Plan::default();
            for _ in 0..3 {
                plan.count(key_of(&a).unwrap());
            }
            plan.count(key_of(&b).unwrap());
            let guard = planned.then(|| plan.enter());
            for _ in 0..3 {
                let d = read_shared(key_of(&a), data).unwrap();
                assert_eq!(d.positions, vec![[1.0, 2.0, 3.0]]);
            }
            read_shared(key_of(&b), data).unwrap();
            assert_eq!(reads.get(), if planned { 2 } else { 4 });
            if planned {
                let left = PLAN.with(|p| p.borrow().as_ref().unwrap().entries.len());
                assert_eq!(left, 0, "the last use frees the kept data");
            }
            drop(guard);
            assert!(PLAN.with(|p| p.borrow().is_none()));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
