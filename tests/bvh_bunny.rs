//! The BVH finds the same closest hits as brute force over a real mesh.

use glam::Vec3A;
use ronray::accel::Bvh;
use ronray::geometry::obj::load_obj;
use ronray::math::{Pcg32, Ray, sampling};
use std::path::Path;

#[test]
fn bvh_matches_brute_force_on_bunny() {
    let mesh =
        load_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.obj")).expect("bunny loads");
    assert_eq!(mesh.triangle_count(), 3674);
    let bounds: Vec<_> = (0..mesh.triangle_count() as u32)
        .map(|t| mesh.tri_bounds(t))
        .collect();
    let bvh = Bvh::build(&bounds);
    let (lo, hi) = bounds
        .iter()
        .fold((Vec3A::INFINITY, Vec3A::NEG_INFINITY), |(lo, hi), b| {
            (lo.min(b.min), hi.max(b.max))
        });
    let mut rng = Pcg32::new(2024, 7);
    let mut hits = 0;
    for i in 0..5000 {
        // Half the rays start inside the bounding box, half outside aiming in.
        let o = lo + (hi - lo) * Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        let ray = if i % 2 == 0 {
            Ray::new(o, sampling::uniform_sphere(rng.next_vec2()))
        } else {
            let from = 0.5 * (lo + hi) + 2.0 * (hi - lo).length() * sampling::uniform_sphere(rng.next_vec2());
            Ray::new(from, (o - from).normalize())
        };
        let got = bvh.intersect(&ray, f32::INFINITY, |t, r, tm| {
            mesh.intersect(t, r, tm).map(|h| h.0)
        });
        let mut want: Option<(u32, f32)> = None;
        for t in 0..mesh.triangle_count() as u32 {
            if let Some((d, _)) = mesh.intersect(t, &ray, want.map_or(f32::INFINITY, |w| w.1)) {
                want = Some((t, d));
            }
        }
        match (got, want) {
            (None, None) => {}
            (Some((gi, gt)), Some((wi, wt))) => {
                hits += 1;
                assert!(
                    (gt - wt).abs() <= 1e-6 * wt.max(1.0),
                    "ray {i}: t {gt} vs brute force {wt}"
                );
                // Equal t on a shared edge may pick either triangle.
                assert!(
                    gi == wi || (gt - wt).abs() == 0.0,
                    "ray {i}: primitive {gi} vs brute force {wi}"
                );
            }
            _ => panic!("ray {i}: BVH {got:?} vs brute force {want:?}"),
        }
        let occluded = bvh.occluded(&ray, f32::INFINITY, |t, r, tm| mesh.intersect(t, r, tm).is_some());
        assert_eq!(occluded, want.is_some(), "ray {i}: occlusion disagrees");
    }
    assert!(
        hits > 1000,
        "too few rays hit the bunny ({hits}) for the test to mean much"
    );
}
