//! Claims of the README that no other test backed when `docs/claims.md` was
//! written (issue 46): the first command's output, the camera's axes, the
//! sidedness of materials and area lights, counts over their limit, and the
//! test suite's own rule for a missing tool.

mod common;

use common::{load_text, render_loaded, root};
use ronray::imageio::Image;
use ronray::load::{Overrides, load_str};

/// The README's first command, `ronray render scenes/cornell.ron`, writes
/// `cornell.png` in the current folder (not beside the scene).
#[test]
fn first_readme_command_writes_cornell_png_in_the_current_folder() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = root().join("scenes/cornell.ron");
    let out = common::ronray_in(
        dir.path(),
        &[
            "render",
            scene.to_str().expect("utf-8 path"),
            "--size",
            "16x16",
            "--spp",
            "1",
        ],
    );
    assert!(
        out.status.success(),
        "render failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        dir.path().join("cornell.png").is_file(),
        "no cornell.png in the current folder; it holds {:?}",
        std::fs::read_dir(dir.path())
            .expect("read temp dir")
            .flatten()
            .map(|e| e.file_name())
            .collect::<Vec<_>>()
    );
}

/// The (x, y) of the brightest pixel.
fn brightest(img: &Image) -> (u32, u32) {
    let i = (0..img.pixels.len())
        .max_by(|&a, &b| common::sum(&img.pixels[a]).total_cmp(&common::sum(&img.pixels[b])))
        .expect("pixels");
    (i as u32 % img.width, i as u32 / img.width)
}

/// `right = normalize(forward × up)`, image x runs toward `right` and row 0
/// is the top: a glowing ball up and to the right of the view lands in the
/// image's top-right quarter, and moved to the left, in its top-left one.
#[test]
fn camera_right_is_forward_cross_up_and_row_0_is_the_top() {
    let scene = |x: f32| {
        format!(
            "Scene(camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 60),
             film: (width: 32, height: 32, spp: 4),
             materials: {{ \"black\": Lambert(albedo: 0) }},
             objects: [Sphere(center: ({x}, 0.8, -3), radius: 0.3, material: \"black\",
                              emission: (radiance: (5, 5, 5)))])"
        )
    };
    let (x, y) = brightest(&render_loaded(&load_text(&scene(1.0))));
    assert!(x > 16 && y < 16, "ball up and right seen at ({x}, {y}) of 32×32");
    let (x, y) = brightest(&render_loaded(&load_text(&scene(-1.0))));
    assert!(x < 16 && y < 16, "ball up and left seen at ({x}, {y}) of 32×32");
}

/// Mean of the pixels' channel sums.
fn mean(img: &Image) -> f64 {
    img.pixels.iter().map(common::sum).sum::<f64>() / img.pixels.len() as f64
}

/// A rectangle facing the camera, or turned away by swapping its edges.
fn facing(toward_camera: bool) -> &'static str {
    if toward_camera {
        "half_u: (1, 0, 0), half_v: (0, 1, 0)"
    } else {
        "half_u: (0, 1, 0), half_v: (1, 0, 0)"
    }
}

/// Materials are two-sided: a Lambert rectangle seen from behind (its
/// normal turned away) shades like its front.
#[test]
fn materials_shade_the_back_like_the_front() {
    let render = |front: bool| {
        let text = format!(
            "Scene(camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 40),
             film: (width: 16, height: 16, spp: 8),
             materials: {{ \"grey\": Lambert(albedo: 0.5) }},
             lights: [Point(position: (0.3, 0.3, 0), intensity: (5, 5, 5))],
             objects: [Rect(center: (0, 0, -2), {}, material: \"grey\")])",
            facing(front)
        );
        mean(&render_loaded(&load_text(&text)))
    };
    let (front, back) = (render(true), render(false));
    assert!(front > 0.01, "the lit rectangle renders black: {front}");
    assert!(
        (front - back).abs() <= 1e-4 * front,
        "front {front} and back {back} differ"
    );
}

/// A `Rect` light emits only on the side of `half_u × half_v`: seen from
/// that side it shows its radiance, from behind it is black.
#[test]
fn area_lights_emit_on_one_side_and_are_black_from_behind() {
    let render = |front: bool| {
        let text = format!(
            "Scene(camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 20),
             film: (width: 8, height: 8, spp: 4),
             lights: [Rect(center: (0, 0, -2), {}, radiance: (4, 4, 4))])",
            facing(front)
        );
        render_loaded(&load_text(&text))
    };
    let lit = render(true);
    assert!(
        lit.pixels.iter().all(|p| (common::sum(p) - 12.0).abs() < 1e-3),
        "the light seen from its front is not its radiance 4 in every pixel"
    );
    let back = render(false);
    assert!(
        back.pixels.iter().all(|p| common::sum(p) == 0.0),
        "the light seen from behind is not black"
    );
}

/// Counts the README's *Limits* table bounds in `src/load/validate.rs` are
/// refused one over the limit, with a message that names the limit.
#[test]
fn counts_one_over_their_limit_are_refused_naming_it() {
    let cases = [
        ("film: (width: N, height: 8)", 16384),
        ("film: (spp: N)", 1_048_576),
        ("integrator: Direct(light_samples: N)", 4096),
        ("integrator: Whitted(max_depth: N)", 64),
        ("integrator: Path(rr_depth: N)", 1024),
        ("integrator: Path(splits: N)", 16),
    ];
    let path = root().join("scenes/limit_test.ron");
    for (field, limit) in cases {
        let scene = |n: u32| {
            format!(
                "Scene(camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40), {},
                 lights: [Point(position: (0, 2, 2), intensity: (1, 1, 1))])",
                field.replace('N', &n.to_string())
            )
        };
        match load_str(&path, &scene(limit + 1), &Overrides::default()) {
            Ok(_) => panic!("`{field}` one over {limit} was accepted"),
            Err(e) => {
                let msg = common::message(&e);
                let named = [limit.to_string(), format!("2^{}", limit.ilog2())];
                assert!(
                    named.iter().any(|n| msg.contains(n.as_str())),
                    "`{field}`: the error does not name {limit}:\n{msg}"
                );
            }
        }
        if let Err(e) = load_str(&path, &scene(limit), &Overrides::default()) {
            panic!("`{field}` at {limit} is refused:\n{}", common::message(&e));
        }
    }
}

/// A test that needs a missing tool is skipped with a line saying so,
/// unless `RONRAY_REQUIRE_TOOLS=1` makes it fail (whichever the environment
/// of this run asks for is what is checked).
#[test]
fn a_missing_tool_skips_the_test_unless_tools_are_required() {
    let required = std::env::var("RONRAY_REQUIRE_TOOLS").as_deref() == Ok("1");
    let outcome = std::panic::catch_unwind(|| {
        common::tool_or_skip("ronray-no-such-tool", "this test", "nowhere to install it")
    });
    match outcome {
        Ok(found) => {
            assert!(!required, "a missing tool passed under RONRAY_REQUIRE_TOOLS=1");
            assert!(found.is_none(), "a tool that does not exist was found");
        }
        Err(_) => assert!(required, "a missing tool failed without RONRAY_REQUIRE_TOOLS=1"),
    }
}

/// `ronray new NAME` never replaces an existing file unless given `--force`.
#[test]
fn new_keeps_an_existing_scene_unless_forced() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = dir.path().join("room.ron");
    std::fs::write(&scene, "mine").expect("write");
    let out = common::ronray_in(dir.path(), &["new", "room"]);
    assert!(!out.status.success(), "`new` over an existing file succeeded");
    assert_eq!(std::fs::read_to_string(&scene).expect("read"), "mine");
    let out = common::ronray_in(dir.path(), &["new", "room", "--force"]);
    assert!(
        out.status.success(),
        "`new --force` failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_ne!(std::fs::read_to_string(&scene).expect("read"), "mine");
}

/// `render --stats` prints the mesh and instance counts with each mesh's
/// BVH, the marches and steps of SDFs, the sky map's size with its read and
/// table times, and rays per second.
#[test]
fn stats_name_meshes_marches_and_the_sky_map() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (scene, expect) in [
        (
            "bunny",
            &["meshes: 1 in memory", "mesh 0: 3674 triangles", "rays/s"][..],
        ),
        (
            "sdf_shapes",
            &["marches", "steps per march", "steps histogram"][..],
        ),
        (
            "env_spheres",
            &["environment: ", "map read in", "sampling tables built in"][..],
        ),
    ] {
        let path = root().join(format!("scenes/{scene}.ron"));
        let out = dir.path().join(format!("{scene}.png"));
        let run = common::ronray(&[
            "render",
            path.to_str().expect("utf-8"),
            "--stats",
            "--size",
            "8x8",
            "--spp",
            "1",
            "-o",
            out.to_str().expect("utf-8"),
        ]);
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&run.stdout),
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(run.status.success(), "{scene}: {text}");
        for e in expect {
            assert!(
                text.contains(e),
                "{scene}: `--stats` does not print `{e}`:\n{text}"
            );
        }
    }
}

/// A key track holds at most 10,000 keys (`MAX_KEYS`): one more is a
/// located error that names the limit, and 10,000 load.
#[test]
fn a_track_of_more_than_ten_thousand_keys_is_refused() {
    let scene = |n: usize| {
        let keys: String = (0..n)
            .map(|i| {
                format!(
                    "(frame: {i}, transform: [Translate(({}, 0, 0))]),",
                    i as f32 * 1e-4
                )
            })
            .collect();
        format!(
            "Scene(camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
             materials: {{ \"white\": Lambert(albedo: 0.8) }},
             lights: [Point(position: (0, 2, 2), intensity: (1, 1, 1))],
             meshes: {{ \"block\": (file: \"../assets/short_block.obj\") }},
             objects: [Instance(mesh: \"block\", material: \"white\", keys: [{keys}])])"
        )
    };
    let path = root().join("scenes/keys_test.ron");
    let err = match load_str(&path, &scene(10_001), &Overrides::default()) {
        Ok(_) => panic!("10,001 keys were accepted"),
        Err(e) => common::message(&e),
    };
    assert!(err.contains("10000"), "the error does not name the limit:\n{err}");
    if let Err(e) = load_str(&path, &scene(10_000), &Overrides::default()) {
        panic!("10,000 keys are refused:\n{}", common::message(&e));
    }
}

/// A density grid whose optical depth across its box is above 10,000
/// (`MAX_GRID_OPTICAL_DEPTH`) is refused naming the limit.
#[test]
fn a_grid_too_dense_to_track_is_refused() {
    let dir = tempfile::tempdir().expect("temp dir");
    let bytes = ronray::media::vol::write_vol([2, 2, 2], &[1.0; 8], [-1.0; 3], [1.0; 3]);
    std::fs::write(dir.path().join("g.vol"), bytes).expect("write .vol");
    let scene = |scale: f32| {
        format!(
            "Scene(camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
             integrator: Path(max_depth: 4),
             media: {{ \"smoke\": Grid(file: \"g.vol\", min: (-1, -1, -1), max: (1, 1, 1), scale: {scale}) }},
             medium: \"smoke\",
             lights: [Point(position: (0, 2, 2), intensity: (1, 1, 1))])"
        )
    };
    let path = dir.path().join("grid.ron");
    let err = match load_str(&path, &scene(1e5), &Overrides::default()) {
        Ok(_) => panic!("a grid of optical depth 2e5 was accepted"),
        Err(e) => common::message(&e),
    };
    assert!(err.contains("10000"), "the error does not name the limit:\n{err}");
    if let Err(e) = load_str(&path, &scene(1.0), &Overrides::default()) {
        panic!("a grid of optical depth 2 is refused:\n{}", common::message(&e));
    }
}
