//! The camera as the view edits it: a look-at pose (origin, target, up) in world coordinates,
//! moved by orbit, pan and dolly steps, and written back into the scene file as the sensor's
//! `<transform name="to_world">` (a `<lookat>`, after a `<scale>` when the file's camera was
//! mirrored or scaled, so that editing the pose keeps the file's handedness and, for an
//! orthographic camera, its view size).
use glam::{DMat4, DVec3};
use serde::Serialize;
use tessera_core::math::{Norm, Ray};
use tessera_scene::LoadedScene;

/// A look-at camera pose, in world coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Pose {
    /// Where the camera is.
    pub origin: [f64; 3],
    /// The point it looks at (and orbits around).
    pub target: [f64; 3],
    /// Its up direction (not necessarily orthogonal to the view direction).
    pub up: [f64; 3],
    /// The scale the file's camera transform had along its own axes (negative x: mirrored),
    /// kept when the pose is written.
    #[serde(skip)]
    pub scale: [f64; 3],
}

/// One change of the camera, as `POST /api/camera` gives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Move {
    /// Turn around the target: `yaw` degrees about the up axis, `pitch` degrees up or down.
    Orbit { yaw: f64, pitch: f64 },
    /// Move origin and target together, across the view: `right` and `up` in units of the
    /// distance to the target.
    Pan { right: f64, up: f64 },
    /// Move towards the target: the distance is multiplied by `exp(-amount)`.
    Dolly { amount: f64 },
    /// An explicit pose.
    Set {
        origin: DVec3,
        target: DVec3,
        up: DVec3,
    },
}

fn v(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

impl Pose {
    /// The pose of the loaded scene's camera. The target is where the centre ray first hits the
    /// scene (else the point level with the scene's centre, else one unit ahead), so that
    /// orbiting turns around what the view is centred on.
    pub fn of_scene(loaded: &LoadedScene) -> Pose {
        let cam = &loaded.scene.camera;
        let m = cam.to_world.m.as_dmat4();
        let shift = v(loaded.frame_origin);
        let origin_core = m.transform_point3(DVec3::ZERO);
        let (x, y, z) = (
            m.transform_vector3(DVec3::X),
            m.transform_vector3(DVec3::Y),
            m.transform_vector3(DVec3::Z),
        );
        let dir = z.unit_or(DVec3::Z);
        let up = y.unit_or(DVec3::Y);
        // A look-at's own x axis is up x dir; the file's may point the other way (mirrored).
        let left = up.cross(dir);
        let sx = if x.dot(left) < 0.0 {
            -x.norm()
        } else {
            x.norm()
        };
        let ray = Ray::new(origin_core.as_vec3(), dir.as_vec3());
        let hit = loaded.scene.intersect_hit(&ray).map(|h| h.t as f64);
        let dist = hit
            .filter(|t| t.is_finite() && *t > 1e-4)
            .unwrap_or_else(|| {
                let b = loaded.scene.bounds();
                let centre = ((b.min + b.max) * 0.5).as_dvec3();
                let d = (centre - origin_core).dot(dir);
                if d.is_finite() && d > 1e-4 {
                    d
                } else {
                    1.0
                }
            });
        let origin = origin_core + shift;
        Pose {
            origin: origin.to_array(),
            target: (origin + dir * dist).to_array(),
            up: up.to_array(),
            scale: [sx, y.norm(), z.norm()],
        }
    }

    /// The pose after `m`, or why it cannot be taken (a degenerate look-at).
    pub fn moved(&self, m: Move) -> Result<Pose, String> {
        let (o, t, up) = (v(self.origin), v(self.target), v(self.up).unit());
        let offset = o - t;
        let dist = offset.norm();
        let (o, t, up) = match m {
            Move::Orbit { yaw, pitch } => {
                let yawed = DMat4::from_axis_angle(up, yaw.to_radians()).transform_vector3(offset);
                // Pitch about the camera's horizontal axis, kept a degree away from the poles.
                let right = up.cross(yawed).unit_or_zero();
                let now = yawed.unit().dot(up).clamp(-1.0, 1.0).acos().to_degrees();
                let p = pitch.clamp(now - 179.0, now - 1.0);
                let turned = match right == DVec3::ZERO {
                    true => yawed,
                    false => {
                        DMat4::from_axis_angle(right, -p.to_radians()).transform_vector3(yawed)
                    }
                };
                (t + turned, t, up)
            }
            Move::Pan { right, up: u } => {
                let dir = -offset / dist;
                let side = dir.cross(up).unit_or_zero();
                let cam_up = side.cross(dir);
                let d = (side * right + cam_up * u) * dist;
                (o + d, t + d, up)
            }
            Move::Dolly { amount } => {
                let new = (dist * (-amount).exp()).max(1e-6);
                (t + offset / dist * new, t, up)
            }
            Move::Set { origin, target, up } => (origin, target, up),
        };
        let pose = Pose {
            origin: o.to_array(),
            target: t.to_array(),
            up: up.to_array(),
            scale: self.scale,
        };
        pose.check()?;
        Ok(pose)
    }

    /// Refuses poses the loader would refuse or that say nothing: non-finite or huge
    /// coordinates, target at the origin, up along the view direction.
    pub fn check(&self) -> Result<(), String> {
        let all = self.origin.iter().chain(&self.target).chain(&self.up);
        if all.clone().any(|c| !c.is_finite() || c.abs() > 1e12) {
            return Err("camera coordinates must be finite numbers below 1e12".into());
        }
        let dir = v(self.target) - v(self.origin);
        if dir.norm() < 1e-9 {
            return Err("the camera's target must differ from its origin".into());
        }
        let up = v(self.up);
        if up.norm() < 1e-9 || dir.unit().cross(up.unit()).norm() < 1e-6 {
            return Err("the camera's up must not be along its view direction".into());
        }
        Ok(())
    }

    /// The `<transform name="to_world">` element that places the camera at this pose.
    pub fn to_world_xml(&self, name: &str) -> String {
        let n = crate::xml_text::number;
        let t = |a: [f64; 3]| format!("{}, {}, {}", n(a[0]), n(a[1]), n(a[2]));
        let s = self.scale;
        let near_one = |c: f64| (c - 1.0).abs() < 1e-6;
        let scale = match s.iter().all(|c| near_one(*c)) {
            true => String::new(),
            false => format!("<scale value=\"{}\"/>", t(s)),
        };
        format!(
            "<transform name=\"{name}\">{scale}<lookat origin=\"{}\" target=\"{}\" up=\"{}\"/></transform>",
            t(self.origin),
            t(self.target),
            t(self.up)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose() -> Pose {
        Pose {
            origin: [0.0, 0.0, 5.0],
            target: [0.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            scale: [1.0; 3],
        }
    }

    #[test]
    fn orbit_keeps_the_distance_and_dolly_scales_it() {
        let p = pose()
            .moved(Move::Orbit {
                yaw: 90.0,
                pitch: 30.0,
            })
            .unwrap();
        let o = v(p.origin);
        assert!((o.norm() - 5.0).abs() < 1e-9, "{o}");
        assert!((o.y - 2.5).abs() < 1e-9, "30 degrees up: {o}");
        assert!((o.x - 5.0 * 30f64.to_radians().cos()).abs() < 1e-9, "{o}");
        let d = pose().moved(Move::Dolly { amount: 2f64.ln() }).unwrap();
        assert!((v(d.origin).z - 2.5).abs() < 1e-12);
        let pan = pose()
            .moved(Move::Pan {
                right: 0.1,
                up: 0.0,
            })
            .unwrap();
        assert!((v(pan.target) - v(pan.origin)).z < 0.0 && v(pan.target).x.abs() > 0.4);
    }

    /// The file's camera, written back as a pose, is the same camera: mirrored (Nori files
    /// write `<scale x="-1"/>`), scaled (an orthographic view's size) or neither.
    #[test]
    fn the_file_camera_written_as_a_pose_is_the_same_camera() {
        for (sensor, prefix) in [
            ("perspective", ""),
            ("perspective", r#"<scale value="-1, 1, 1"/>"#),
            ("orthographic", r#"<scale value="2, 3, 1"/>"#),
        ] {
            let text = format!(
                r#"<scene version="3.0.0"><sensor type="{sensor}">
                <transform name="to_world">{prefix}<lookat origin="1, 2, 5" target="0.5, 0, 0" up="0.2, 1, 0"/></transform>
                <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
                <shape type="sphere"><float name="radius" value="0.7"/></shape></scene>"#
            );
            let path = std::path::Path::new("inline.xml");
            let loaded = crate::state::load(&text, path).unwrap();
            let pose = Pose::of_scene(&loaded);
            // The centre ray hits the sphere: the target is on it, in front of the camera.
            let d = (v(pose.target) - v(pose.origin)).norm();
            assert!(d > 3.0 && d < 6.0, "{sensor} {prefix}: target at {d}");
            let edits = crate::edits::Edits {
                camera: Some(pose),
                ..Default::default()
            };
            let again = crate::state::load(&edits.apply(&text).unwrap(), path).unwrap();
            let (a, b) = (
                loaded.scene.camera.to_world.m,
                again.scene.camera.to_world.m,
            );
            let err = (a - b)
                .to_cols_array()
                .iter()
                .fold(0f32, |m, x| m.max(x.abs()));
            assert!(err < 1e-5, "{sensor} {prefix}: {a} vs {b}");
            // Control: an orbit of one degree moves the camera by more than that.
            let moved = Pose::moved(
                &pose,
                Move::Orbit {
                    yaw: 1.0,
                    pitch: 0.0,
                },
            )
            .unwrap();
            let edits = crate::edits::Edits {
                camera: Some(moved),
                ..Default::default()
            };
            let m = crate::state::load(&edits.apply(&text).unwrap(), path).unwrap();
            let c = m.scene.camera.to_world.m;
            let err = (a - c)
                .to_cols_array()
                .iter()
                .fold(0f32, |m, x| m.max(x.abs()));
            assert!(err > 1e-3, "{sensor} {prefix}: the orbit moved nothing");
        }
    }

    #[test]
    fn degenerate_poses_are_refused() {
        let same = Move::Set {
            origin: DVec3::ONE,
            target: DVec3::ONE,
            up: DVec3::Y,
        };
        assert!(pose().moved(same).is_err());
        let along = Move::Set {
            origin: DVec3::ZERO,
            target: DVec3::Y,
            up: DVec3::Y,
        };
        assert!(pose().moved(along).is_err());
        // Pitch stops short of the pole.
        let p = pose()
            .moved(Move::Orbit {
                yaw: 0.0,
                pitch: 500.0,
            })
            .unwrap();
        assert!(p.check().is_ok());
    }
}
