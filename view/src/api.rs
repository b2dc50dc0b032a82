//! The JSON API's handlers: the state, and the three edits (camera, material, integrator).
//! Each edit is checked (ranges from the plugin declarations, then a full load of the edited
//! text), and only a scene that loads replaces the one rendering; a refused edit changes
//! nothing and answers one line saying why.
use crate::camera::{Move, Pose};
use crate::edits::{integrator_choices, Edits};
use crate::materials::{self, Key, Value};
use crate::state::{SceneFacts, Shared};
use crate::xml_text::parse;
use glam::DVec3;
use serde::Deserialize;
use serde_json::{json, Value as Json};

/// A refused request: HTTP status and a one-line message.
pub type Refusal = (u16, String);

fn bad(msg: impl Into<String>) -> Refusal {
    (400, msg.into())
}

/// Parses a JSON body into `T`, refusing unknown fields with serde's one-line message.
fn body<'a, T: Deserialize<'a>>(text: &'a str) -> Result<T, Refusal> {
    serde_json::from_str(text).map_err(|e| bad(format!("bad JSON: {e}")))
}

/// `GET /api/state`.
pub fn state(shared: &Shared) -> Json {
    let inner = shared.lock();
    let f = &inner.facts;
    let frame = inner
        .frame
        .as_ref()
        .filter(|fr| fr.generation == inner.generation);
    let bsdfs = parse(&inner.text)
        .map(|d| materials::list(&d))
        .unwrap_or_default();
    json!({
        "scene": shared.path.display().to_string(),
        "generation": inner.generation,
        "spp": frame.map_or(0, |fr| fr.spp),
        "spp_limit": shared.spp_limit,
        "preview": frame.is_some_and(|fr| fr.preview),
        "elapsed": frame.map_or(0.0, |fr| fr.elapsed),
        "samples_per_second": frame.map_or(0.0, |fr| fr.samples_per_second),
        "rel_mse": frame.and_then(|fr| fr.rel_mse),
        "resolution": [f.width, f.height],
        "frame_resolution": frame.map(|fr| [fr.width, fr.height]),
        "integrator": f.integrator,
        "max_depth": f.max_depth,
        "integrators": integrator_choices(),
        "camera": f.pose,
        "bsdfs": bsdfs,
        "editable": shared.not_editable.is_none(),
        "not_editable": shared.not_editable,
        "threads": shared.threads,
    })
}

/// Applies `edits` if the edited text loads; the scene goes to the render thread.
fn commit(shared: &Shared, edits: Edits) -> Result<Json, Refusal> {
    if let Some(why) = &shared.not_editable {
        return Err(bad(why.clone()));
    }
    let text = edits.apply(&shared.base).map_err(bad)?;
    let loaded = shared.load(&text).map_err(bad)?;
    let pose = match edits.camera {
        Some(p) => p,
        None => Pose::of_scene(&loaded),
    };
    let facts = SceneFacts::of(&loaded, pose);
    let mut inner = shared.lock();
    inner.edits = edits;
    inner.text = text;
    inner.facts = facts;
    shared.hand_over(&mut inner, loaded);
    Ok(json!({ "generation": inner.generation }))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CameraRequest {
    orbit: Option<[f64; 2]>,
    pan: Option<[f64; 2]>,
    dolly: Option<f64>,
    origin: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    #[serde(default)]
    reset: bool,
}

fn limited(what: &str, v: &[f64], limit: f64) -> Result<(), Refusal> {
    match v.iter().all(|c| c.is_finite() && c.abs() <= limit) {
        true => Ok(()),
        false => Err(bad(format!("{what} must be at most {limit} in size"))),
    }
}

/// `POST /api/camera`: `{"orbit": [yaw, pitch]}` (degrees), `{"pan": [right, up]}` (in
/// distances to the target), `{"dolly": f}` (distance times `exp(-f)`), `{"origin": [..],
/// "target": [..], "up": [..]}`, or `{"reset": true}`.
pub fn camera(shared: &Shared, text: &str) -> Result<Json, Refusal> {
    let req: CameraRequest = body(text)?;
    let (mut edits, pose) = {
        let inner = shared.lock();
        (inner.edits.clone(), inner.facts.pose)
    };
    let explicit = req.origin.is_some() || req.target.is_some() || req.up.is_some();
    let relative = req.orbit.is_some() || req.pan.is_some() || req.dolly.is_some();
    match (req.reset, explicit, relative) {
        (true, false, false) => {
            edits.camera = None;
            return commit(shared, edits);
        }
        (false, true, false) => {
            let (Some(o), Some(t)) = (req.origin, req.target) else {
                return Err(bad("an explicit camera needs \"origin\" and \"target\""));
            };
            let up = req.up.unwrap_or(pose.up);
            let m = Move::Set {
                origin: DVec3::from_array(o),
                target: DVec3::from_array(t),
                up: DVec3::from_array(up),
            };
            edits.camera = Some(pose.moved(m).map_err(bad)?);
        }
        (false, false, true) => {
            let mut p = pose;
            if let Some([yaw, pitch]) = req.orbit {
                limited("orbit", &[yaw, pitch], 360.0)?;
                p = p.moved(Move::Orbit { yaw, pitch }).map_err(bad)?;
            }
            if let Some([right, up]) = req.pan {
                limited("pan", &[right, up], 100.0)?;
                p = p.moved(Move::Pan { right, up }).map_err(bad)?;
            }
            if let Some(amount) = req.dolly {
                limited("dolly", &[amount], 20.0)?;
                p = p.moved(Move::Dolly { amount }).map_err(bad)?;
            }
            edits.camera = Some(p);
        }
        _ => {
            return Err(bad(
                "give one of: orbit/pan/dolly, origin+target(+up), or reset: true",
            ))
        }
    }
    commit(shared, edits)
}

#[derive(Deserialize)]
#[serde(untagged)]
enum KeyJson {
    Index(usize),
    Id(String),
}

#[derive(Deserialize)]
#[serde(untagged)]
enum ValueJson {
    Float(f64),
    Rgb([f64; 3]),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialRequest {
    bsdf: KeyJson,
    param: String,
    value: ValueJson,
}

/// `POST /api/material`: `{"bsdf": index or "id", "param": "reflectance", "value": [r, g, b]}`
/// (or a number).
pub fn material(shared: &Shared, text: &str) -> Result<Json, Refusal> {
    let req: MaterialRequest = body(text)?;
    let key = match req.bsdf {
        KeyJson::Index(i) => Key::Index(i),
        KeyJson::Id(s) => Key::Id(s),
    };
    let value = match req.value {
        ValueJson::Float(x) => Value::Float(x),
        ValueJson::Rgb(c) => Value::Rgb(c),
    };
    let mut edits = shared.lock().edits.clone();
    if shared.not_editable.is_none() {
        edits
            .set_material(&shared.base, &key, &req.param, &value)
            .map_err(bad)?;
    }
    commit(shared, edits)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct IntegratorRequest {
    r#type: Option<String>,
    max_depth: Option<i64>,
}

/// `POST /api/integrator`: `{"type": "path", "max_depth": 8}` (either may be left out;
/// `max_depth` -1 is unbounded).
pub fn integrator(shared: &Shared, text: &str) -> Result<Json, Refusal> {
    let req: IntegratorRequest = body(text)?;
    let mut edits = shared.lock().edits.clone();
    if let Some(t) = &req.r#type {
        let choices = integrator_choices();
        if !choices.contains(&t.as_str()) {
            return Err(bad(format!(
                "unknown integrator \"{t}\" (the view offers: {})",
                choices.join(", ")
            )));
        }
        edits.integrator = Some(t.clone());
        // A depth set for the old integrator is not carried to a new one that takes none.
        let takes = tessera_scene::plugin_declaration("integrator", t)
            .is_some_and(|d| d.params.iter().any(|p| p.name == "max_depth"));
        if !takes {
            edits.max_depth = None;
        }
    }
    if let Some(d) = req.max_depth {
        if !(-1..=1024).contains(&d) {
            return Err(bad(format!(
                "max_depth must be -1 (unbounded) or 0 to 1024, found {d}"
            )));
        }
        edits.max_depth = Some(d);
    }
    if req.r#type.is_none() && req.max_depth.is_none() {
        return Err(bad("give \"type\" and/or \"max_depth\""));
    }
    commit(shared, edits)
}
