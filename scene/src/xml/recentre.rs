//! Renders a scene far from the origin in a frame centred on its camera.
//!
//! The core stores positions in f32, whose spacing grows with the distance from the origin:
//! 1e5 away, coordinates are 0.0078 apart and a sphere of radius 2 is visibly faceted (an
//! emitting sphere seen from inside came out 3-5% dark). What a camera sees is near the camera,
//! so the loader moves the whole scene, in f64 and before anything is stored in f32, so that the
//! camera sits at the origin: the sensor, every shape (a shape without `to_world` gets one),
//! every `<volume>` (a heterogeneous medium's extent, likewise),
//! positioned lights (`point`, `spot`) and Nori's `simple` integrator's light. Directions,
//! environments and light nested in shapes do not depend on the frame.
//!
//! Scenes whose camera is within [`RECENTRE_FROM`] of the origin along every axis are left as
//! written (every example and test scene is), so their images do not change; positions a
//! report prints (`--debug-pixel`) are in the camera's frame for the others.
use glam::{DMat4, DVec3};

use super::draft::{Draft, Target};
use super::object::{Kind, Prop, Value};
use std::collections::HashSet;

/// Distance from the origin (along any axis) from which a camera's scene is recentred.
pub const RECENTRE_FROM: f64 = 256.0;

/// Moves every positioned object of `drafts` by minus the camera's position, when the camera is
/// at least [`RECENTRE_FROM`] from the origin along some axis; returns the shift applied.
pub(super) fn recentre(drafts: &mut [Option<Draft>]) -> Option<DVec3> {
    let camera = drafts
        .iter()
        .flatten()
        .find(|d| d.kind == Kind::Sensor)
        .and_then(|d| transform(d, "to_world"))?;
    let c = camera.transform_point3(DVec3::ZERO);
    if !(c.abs().max_element() >= RECENTRE_FROM) || !c.is_finite() {
        return None;
    }
    let shift = DMat4::from_translation(-c);
    // A shape group's members are in the group's own space: its instances move instead.
    let members: HashSet<usize> = drafts
        .iter()
        .flatten()
        .filter(|d| d.kind == Kind::Shape && d.plugin == "shapegroup")
        .flat_map(|d| &d.children)
        .filter_map(|c| match c.target {
            Target::Node(i) if !c.is_ref => Some(i),
            _ => None,
        })
        .collect();
    for (i, d) in drafts.iter_mut().enumerate() {
        let Some(d) = d else { continue };
        if members.contains(&i) || (d.kind == Kind::Shape && d.plugin == "shapegroup") {
            continue;
        }
        match (d.kind, d.plugin.as_str()) {
            // A sphere placed by its centre alone: move the centre, which the builder may
            // store before applying a transform.
            (Kind::Shape, _) if transform(d, "to_world").is_none() && has(d, "center") => {
                move_point(d, "center", c);
            }
            (Kind::Sensor | Kind::Shape | Kind::Volume, _) | (Kind::Emitter, "spot") => {
                prepend(d, shift)
            }
            (Kind::Emitter, "point") => move_or_prepend(d, "position", c, shift),
            (Kind::Integrator, "simple") => {
                move_point(d, "position", c);
            }
            _ => {}
        }
    }
    Some(c)
}

/// Whether `d` has a property `name`.
fn has(d: &Draft, name: &str) -> bool {
    d.props.iter().any(|p| p.name == name)
}

/// The transform `name` of `d`, if it has one of that type.
fn transform(d: &Draft, name: &str) -> Option<DMat4> {
    d.props
        .iter()
        .find(|p| p.name == name)
        .and_then(|p| match p.value {
            Value::Transform(m) => Some(m),
            _ => None,
        })
}

/// `to_world := shift * to_world`, adding `to_world = shift` where there is none (a value of
/// another type is left for the builder to refuse).
fn prepend(d: &mut Draft, shift: DMat4) {
    match d.props.iter_mut().find(|p| p.name == "to_world") {
        Some(p) => {
            if let Value::Transform(m) = p.value {
                p.value = Value::Transform(shift * m);
            }
        }
        None => {
            let loc = d.loc.clone();
            d.props
                .push(Prop::new("to_world", Value::Transform(shift), loc));
        }
    }
}

/// Moves the point `name` of `d` by `-c` if `d` has it, else shifts its `to_world`.
fn move_or_prepend(d: &mut Draft, name: &str, c: DVec3, shift: DMat4) {
    if !move_point(d, name, c) {
        prepend(d, shift);
    }
}

/// Moves the point `name` of `d` by `-c`; whether `d` has it.
fn move_point(d: &mut Draft, name: &str, c: DVec3) -> bool {
    match d.props.iter_mut().find(|p| p.name == name) {
        Some(p) => {
            if let Value::Point(v) | Value::Vector(v) = &mut p.value {
                *v = (DVec3::from_array(*v) - c).to_array();
            }
            true
        }
        None => false,
    }
}
