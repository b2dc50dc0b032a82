//! Objects while a load is under way ([`Draft`]s in an arena), and turning them into the final
//! [`Object`] tree once every file is read.
//!
//! A `<ref>` may name an object declared later in the file, or in a file included later
//! (Mitsuba resolves references after reading everything). So the parser keeps objects as
//! drafts whose children are arena indices or still-unresolved ids, and builds the shared
//! `Rc<Object>` tree only at the end: unknown ids and reference cycles are reported then, at
//! the `<ref>`.

use std::collections::HashMap;
use std::path::PathBuf;
use std::rc::Rc;

use super::object::{Child, Kind, Object, Prop};
use crate::error::{InputError, Loc};

/// What a child of a draft points to.
#[derive(Debug, Clone)]
pub(super) enum Target {
    /// A draft already in the arena.
    Node(usize),
    /// An id not declared yet when the `<ref>` was read.
    Id(String),
}

/// One child of a draft: a nested object or a `<ref>`.
#[derive(Debug, Clone)]
pub(super) struct DraftChild {
    pub(super) name: Option<String>,
    pub(super) target: Target,
    pub(super) loc: Loc,
    pub(super) is_ref: bool,
}

/// An object read, not yet final.
#[derive(Debug)]
pub(super) struct Draft {
    pub(super) kind: Kind,
    pub(super) plugin: String,
    pub(super) id: Option<String>,
    pub(super) name: Option<String>,
    pub(super) loc: Loc,
    pub(super) props: Vec<Prop>,
    pub(super) children: Vec<DraftChild>,
}

/// Builds the final tree of the draft `root`: ids resolved through `ids`, every object
/// sharing `search` (the folders relative file names are looked up in).
///
/// Iterative (an explicit stack), so a long chain of references cannot overflow the stack.
pub(super) fn finalize(
    drafts: &mut [Option<Draft>],
    ids: &HashMap<String, (usize, Loc)>,
    root: usize,
    search: &Rc<[PathBuf]>,
) -> Result<Object, InputError> {
    // Resolve ids first: every target becomes an index.
    for d in drafts.iter_mut().flatten() {
        for c in &mut d.children {
            if let Target::Id(id) = &c.target {
                let Some((i, _)) = ids.get(id) else {
                    return Err(InputError::at(
                        &c.loc,
                        format!("unknown id \"{id}\" (no object is declared with it)"),
                    ));
                };
                c.target = Target::Node(*i);
            }
        }
    }
    let index = |c: &DraftChild| match c.target {
        Target::Node(i) => i,
        Target::Id(_) => unreachable!("ids are resolved above"),
    };
    let mut done: Vec<Option<Rc<Object>>> = vec![None; drafts.len()];
    let mut on_stack = vec![false; drafts.len()];
    // (draft, next child to visit, the child that led here)
    let mut stack: Vec<(usize, usize, Option<Loc>)> = vec![(root, 0, None)];
    on_stack[root] = true;
    while let Some(&mut (at, ref mut next, _)) = stack.last_mut() {
        let d = drafts[at].as_ref().expect("drafts are finalized once");
        if let Some(c) = d.children.get(*next) {
            *next += 1;
            let to = index(c);
            if done[to].is_some() {
                continue;
            }
            if on_stack[to] {
                let id = drafts[to]
                    .as_ref()
                    .and_then(|d| d.id.clone())
                    .unwrap_or_default();
                return Err(InputError::at(
                    &c.loc,
                    format!(
                        "reference cycle: id \"{id}\" refers to an object that contains this \
                         reference"
                    ),
                ));
            }
            on_stack[to] = true;
            stack.push((to, 0, Some(c.loc.clone())));
            continue;
        }
        stack.pop();
        on_stack[at] = false;
        let d = drafts[at].take().expect("drafts are finalized once");
        let children = d
            .children
            .iter()
            .map(|c| {
                let obj = done[index(c)].clone().expect("children are built first");
                if c.is_ref {
                    obj.mark_referenced();
                }
                Child::new(c.name.clone(), obj, c.loc.clone(), c.is_ref)
            })
            .collect();
        let mut obj = Object::new(d.kind, d.plugin, d.id, d.name, d.loc, d.props, children);
        obj.search = search.clone();
        if stack.is_empty() {
            return Ok(obj);
        }
        done[at] = Some(Rc::new(obj));
    }
    unreachable!("the root is returned when its frame is popped")
}
