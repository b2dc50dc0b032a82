//! The `sggx` `<phase>` plugin: mirror microflakes whose normals follow the SGGX distribution of
//! a matrix `S` read from a 6-channel `gridvolume` (Mitsuba 3.9.1 reads `S` only so: its
//! `constvolume` has no 6-value lookup). Its conventions are in `tessera_core::medium::sggx`.
//!
//! A grid whose voxels are all equal becomes one fixed function; any other varies through
//! space and may only be a medium's own phase function (a `blendphase` has no position to look
//! it up at, and a `homogeneous` medium's extinction could not follow it). Every voxel's matrix
//! must be positive definite (Mitsuba 3 leaves that to the scene; a matrix that is not has no
//! distribution of normals), so a blend of them between voxels is too.
use super::phase::{PhaseNest, PhasePlugin};
use super::volumes::build_volume;
use crate::error::InputError;
use crate::plugin::{Default, Param, ParamType, Plugin, Range};
use crate::util::Result;
use crate::xml::{Kind, Object};
use tessera_core::medium::{MediumPhase, PhaseFunction, Sggx, VolumeData};

const S: Param = Param::new(
    "S",
    ParamType::Volume,
    Default::Required,
    Range::Note("a gridvolume of 6 channels, each voxel's matrix positive definite"),
    "the flakes' matrix per voxel, channels S_xx, S_yy, S_zz, S_xy, S_xz, S_yz",
);

/// `sggx`.
pub(crate) const SGGX: PhasePlugin = Plugin {
    name: "sggx",
    aliases: &[],
    doc: "Microflakes (Heitz et al. 2015): mirror flakes whose normals follow the SGGX \
          distribution of a symmetric matrix S, which may vary through space. A medium with it \
          has extinction sigma_t sqrt(w^T S w) along direction w (the flakes' projected area), \
          as in Mitsuba 3; scattering is D(h) / (4 sqrt(wi^T S wi)), sampled exactly from the \
          normals visible from wi. Nested in a blendphase it scatters alike but leaves the \
          extinction alone (as Mitsuba 3 does).",
    params: &[S],
    nested: "a <volume> named S (a 6-channel gridvolume)",
    build: build_sggx,
};

fn build_sggx(obj: &Object, _: PhaseNest) -> Result<MediumPhase> {
    let child = match obj.child(S.name) {
        Some(c) if c.obj.kind == Kind::Volume => c,
        Some(c) => {
            return Err(InputError::at(
                &c.loc,
                format!(
                    "parameter \"S\" of {} must be a gridvolume of 6 channels, found {}",
                    obj.describe(),
                    c.obj.describe()
                ),
            ))
        }
        None if obj.has(S.name) => {
            return Err(obj.error(format!(
                "parameter \"S\" of {} must be a gridvolume of 6 channels, not a value (as in \
                 Mitsuba 3)",
                obj.describe()
            )))
        }
        None => return Err(obj.missing(S.name)),
    };
    child.mark_used();
    let volume = build_volume(&child.obj)?;
    let VolumeData::Grid(g) = &volume.data else {
        return Err(InputError::at(
            &child.loc,
            format!(
                "\"S\" of {} is a constant: it must be a gridvolume of 6 channels (Mitsuba 3.9.1 \
                 looks S up in grids only)",
                obj.describe()
            ),
        ));
    };
    if g.grid.channels() != 6 {
        return Err(InputError::at(
            &child.loc,
            format!(
                "\"S\" of {} has {} channel(s) per voxel: it needs 6 (S_xx, S_yy, S_zz, S_xy, \
                 S_xz, S_yz)",
                obj.describe(),
                g.grid.channels()
            ),
        ));
    }
    let [nx, ny, nz] = g.grid.res();
    for z in 0..nz as usize {
        for y in 0..ny as usize {
            for x in 0..nx as usize {
                let m = g.grid.voxel_matrix(x, y, z);
                let (d, o) = (m.diag, m.off);
                let minor = d.x * d.y - o.x * o.x;
                if !(d.x > 0.0 && minor > 0.0 && m.det() > 0.0) {
                    return Err(InputError::at(
                        &child.loc,
                        format!(
                            "\"S\" of {}: the matrix of voxel ({x}, {y}, {z}) (diagonal {:?}, \
                             off-diagonal {:?}) is not positive definite",
                            obj.describe(),
                            d.to_array(),
                            o.to_array()
                        ),
                    ));
                }
            }
        }
    }
    if g.grid.is_uniform() {
        let s = g.grid.voxel_matrix(0, 0, 0);
        return Ok(MediumPhase::Fixed(PhaseFunction::Sggx(Sggx { s })));
    }
    Ok(MediumPhase::SggxGrid(Box::new(volume)))
}
