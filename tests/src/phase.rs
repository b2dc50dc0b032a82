//! Phase functions built from scene text the way a file gives them: a `<phase>` element is put
//! in a homogeneous medium inside a sphere, the scene loaded, and the medium's phase function
//! taken back, so that tests see what the loader builds (names, defaults, nesting).
use crate::load_xml;
use tessera_core::medium::PhaseFunction;

/// The phase function `phase_xml` (one `<phase>` element) builds.
pub fn phase_from_xml(phase_xml: &str) -> PhaseFunction {
    let xml = format!(
        r#"<scene version="3.0.0">
  <integrator type="volpath"/>
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  <shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior">{phase_xml}</medium>
  </shape>
</scene>"#
    );
    let l = load_xml(&xml, &[]);
    l.scene.media.media[0]
        .phase_at(glam::Vec3::ZERO)
        .into_owned()
}

/// `∫ p(wi, ω) dω` over the sphere by the midpoint rule on a grid of `nz` steps in the z
/// coordinate and `nphi` in the azimuth about z. With `wi = -z` the z coordinate is the cosine
/// of the scattering angle, so a function symmetric about the direction of travel needs few
/// azimuths and many cosines (sharp peaks); one that is not (SGGX) needs both.
pub fn sphere_integral(p: &PhaseFunction, wi: glam::Vec3, nz: usize, nphi: usize) -> f64 {
    let mut sum = 0.0;
    for i in 0..nz {
        let z = -1.0 + (i as f64 + 0.5) * 2.0 / nz as f64;
        let s = (1.0 - z * z).sqrt();
        for j in 0..nphi {
            let phi = (j as f64 + 0.5) * std::f64::consts::TAU / nphi as f64;
            let wo = glam::Vec3::new((s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32);
            sum += f64::from(p.eval(wi, wo));
        }
    }
    sum * (2.0 / nz as f64) * (std::f64::consts::TAU / nphi as f64)
}
