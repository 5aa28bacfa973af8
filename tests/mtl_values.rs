//! MTL colours that are no colour (`Ke nan`, `Ke 1e38`, `Kd -1`, `Kd inf`):
//! each is repaired, with a note naming the object, the OBJ file, the
//! material and the statement, and the image stays finite. Before, a NaN
//! `Ke` silently turned the light off and a `Ke` of 1e38 made the light's
//! power infinite.

use crate::common;

use ronray::load::{Loaded, Overrides};

/// A unit quad lit by a glowing quad whose MTL material says `glow`.
fn load_with_glow(glow: &str) -> Loaded {
    let dir = tempfile::tempdir().expect("temp dir");
    let obj = "mtllib m.mtl\n\
               v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n\
               v -1 2 -1\nv 1 2 -1\nv 1 2 1\nv -1 2 1\n\
               usemtl floor\nf 1 3 2\nf 1 4 3\n\
               usemtl glow\nf 5 6 7\nf 5 7 8\n";
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    let mtl = format!("newmtl floor\nKd 0.5 0.5 0.5\n\nnewmtl glow\nKd 0.5 0.5 0.5\n{glow}\n");
    std::fs::write(dir.path().join("m.mtl"), mtl).expect("mtl");
    let scene = "Scene(camera: (eye: (0, 1, 4), target: (0, 1, 0), fov_y_degrees: 60), \
                 film: (width: 8, height: 8, spp: 2), integrator: Path(max_depth: 3), \
                 objects: [Mesh(file: \"m.obj\")])";
    common::load_in(dir.path(), scene, &Overrides::default())
}

#[test]
fn mtl_ke_that_is_no_radiance_is_repaired_with_a_note_saying_which() {
    for (ke, what) in [
        ("Ke nan 1 1", "NaN"),
        ("Ke inf 1 1", "infinite"),
        ("Ke -5 1 1", "negative"),
        ("Ke 1e38 1e38 1e38", "above the largest value read"),
    ] {
        let l = load_with_glow(ke);
        let n = common::notes_text(&l);
        assert!(
            n.contains("objects[0]") && n.contains("m.obj") && n.contains("MTL material `glow`"),
            "{ke}: the note does not say where: {n}"
        );
        assert!(
            n.contains(&format!("`{}", ke.split(' ').next().unwrap_or("Ke"))),
            "{ke}: {n}"
        );
        assert!(n.contains(what), "{ke}: expected a note saying {what}: {n}");
        for light in &l.scene.lights {
            let p = light.power();
            assert!(p.is_finite(), "{ke}: a light's power is {p:?}");
        }
        let img = common::render_loaded(&l);
        assert!(
            img.pixels.iter().all(|p| p.is_finite()),
            "{ke}: the image has non-finite pixels"
        );
    }
    // The finite channels of a repaired `Ke` still glow.
    let l = load_with_glow("Ke nan 1 1");
    assert!(!l.scene.lights.is_empty(), "`Ke nan 1 1` turned the light off");
}

#[test]
fn mtl_kd_that_is_no_colour_is_repaired_with_a_note() {
    for kd in ["Kd nan 0.5 0.5", "Kd -1 0.5 0.5", "Kd inf 0.5 0.5"] {
        let l = load_with_glow(&format!("{kd}\nKe 1 1 1"));
        let n = common::notes_text(&l);
        assert!(
            n.contains("`Kd") && n.contains("MTL material `glow`"),
            "{kd}: {n}"
        );
        let img = common::render_loaded(&l);
        assert!(
            img.pixels.iter().all(|p| p.is_finite()),
            "{kd}: non-finite pixels"
        );
    }
}
