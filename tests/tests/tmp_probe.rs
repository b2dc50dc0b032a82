use tessera_core::glam::Vec3;
use tessera_tests::load_xml;
#[test]
fn probe() {
    let xml = r#"<scene version="3.0.0">
  <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/></film></sensor>
  <emitter type="envmap"><string name="filename" value="/tmp/emitexp/rand.exr"/><float name="scale" value="1.5"/>
  <transform name="to_world"><rotate x="0.3" y="1" z="0.2" angle="37"/></transform></emitter>
</scene>"#;
    let l = load_xml(xml, &[]);
    let e = &l.scene.emitters[0];
    let txt = std::fs::read_to_string("/tmp/emitexp/dirs.txt").unwrap();
    let mut worst = 0.0f32;
    for line in txt.lines() {
        let v: Vec<f32> = line
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect();
        let d = Vec3::new(v[0], v[1], v[2]);
        let ours = e.eval_environment(d);
        let theirs = Vec3::new(v[3], v[4], v[5]);
        let rel = ((ours - theirs).abs() / theirs).max_element();
        worst = worst.max(rel);
        println!("{d:?} ours {ours:?} mitsuba {theirs:?} rel {rel:.2e}");
    }
    println!("worst relative difference {worst:.3e}");
}
