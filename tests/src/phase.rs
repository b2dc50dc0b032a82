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
    l.scene.media.media[0].phase().clone()
}
