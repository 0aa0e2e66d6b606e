//! Every example renders small without exceptions, and pixels whose value
//! is known from the scene are checked: background pixels are `bg_color`,
//! the environment map shows the sky in the right direction, shadows darken
//! what they fall on, the Cornell box's walls have their `.mtl` colours, the
//! bunny's shadow side is darker than its lit side, each callable BRDF
//! shades its own object.

use examples::bunny::{self, MeshView};
use examples::{
    EXAMPLES, Image, Rendered, Settings, callable_brdfs, cornell, diffuse, envmap, instances, mesh, receiver_grid,
    tutorial,
};
use glam::{Vec3, Vec4};

const W: u32 = 64;
const H: u32 = 48;

fn settings() -> Settings {
    Settings::new(W, H).with_spp(2)
}

fn render(name: &str) -> Rendered {
    let example = examples::example(name).unwrap_or_else(|| panic!("no example {name}"));
    let mut scene = (example.build)(&settings()).unwrap_or_else(|e| panic!("{name}: {e}"));
    let rendered = scene.render(&mut |_| {}).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        rendered.exceptions.is_empty(),
        "{name} raised {:?}",
        &rendered.exceptions[..rendered.exceptions.len().min(5)]
    );
    rendered
}

fn luminance(c: Vec4) -> f32 {
    c.truncate().dot(Vec3::new(0.3, 0.59, 0.11))
}

/// The pixel of world point `p` in the tutorial camera's view.
fn tutorial_pixel(image: &Image, p: Vec3) -> Vec4 {
    let (x, y) = tutorial::camera().pixel_of(p, W, H).unwrap_or_else(|| panic!("{p} is out of the frame"));
    image.at(x, y)
}

#[test]
fn every_example_renders_a_picture_without_exceptions() {
    for example in &EXAMPLES {
        let rendered = render(example.name);
        let image = &rendered.image;
        assert_eq!((image.width, image.height, image.pixels.len()), (W, H, (W * H) as usize));
        let first = image.pixels[0];
        assert!(image.pixels.iter().any(|&p| (p - first).abs().max_element() > 0.05), "{} is one colour", example.name);
        assert!(image.pixels.iter().all(|p| p.is_finite()), "{} has non-finite pixels", example.name);
        assert!(rendered.rays >= (W * H) as u64, "{} traced {} rays", example.name, rendered.rays);
        assert!(!image.encode_png().unwrap().is_empty());
    }
}

#[test]
fn background_pixels_are_bg_color() {
    for name in ["normal", "diffuse", "phong", "shadows", "reflections"] {
        let image = render(name).image;
        // The top row looks above the horizon.
        for x in [0, W / 2, W - 1] {
            assert_eq!(image.at(x, H - 1).truncate(), tutorial::BG_COLOR, "{name} pixel ({x}, top)");
        }
    }
}

#[test]
fn the_normal_shader_shows_the_sphere_facing_the_camera() {
    let image = render("normal").image;
    let center = tutorial::SPHERE.truncate();
    let toward_eye = (tutorial::camera().eye - center).normalize();
    let c = tutorial_pixel(&image, center);
    assert!((c.truncate() - (toward_eye * 0.5 + 0.5)).abs().max_element() < 0.1, "{c} vs normal {toward_eye}");
    // The floor's normal is +y everywhere.
    let floor = tutorial_pixel(&image, Vec3::new(0.0, 0.0, 3.5));
    assert!((floor.truncate() - Vec3::new(0.5, 1.0, 0.5)).abs().max_element() < 1e-4, "{floor}");
}

#[test]
fn diffuse_light_falls_on_the_side_facing_the_key_light() {
    let image = render("diffuse").image;
    let center = tutorial::SPHERE.truncate();
    let key = tutorial::lights()[0].pos;
    let lit = tutorial_pixel(&image, center + (key - center).normalize());
    let dark = tutorial_pixel(&image, center + Vec3::new(0.5, -0.6, 0.62).normalize());
    assert!(luminance(lit) > 2.0 * luminance(dark), "lit {lit} vs dark {dark}");
    // Lambert only: the red sphere stays red.
    assert!(lit.x > lit.y && lit.x > lit.z, "{lit}");
}

#[test]
fn the_sphere_shadows_the_floor_only_when_shadow_rays_are_traced() {
    let phong = render("phong").image;
    let shadows = render("shadows").image;
    // A point inside the sphere casts its shadow where the key light's ray
    // through it meets the floor.
    let key = tutorial::lights()[0].pos;
    let inside = tutorial::SPHERE.truncate() + Vec3::new(0.0, 0.5, 0.0);
    let on_floor = key + (inside - key) * (key.y / (key.y - inside.y));
    let (lit, shadowed) = (tutorial_pixel(&phong, on_floor), tutorial_pixel(&shadows, on_floor));
    assert!(luminance(shadowed) < 0.6 * luminance(lit), "shadowed {shadowed} vs unshadowed {lit}");
    // Away from every shadow the two agree.
    let open = Vec3::new(-1.5, 0.0, 3.5);
    let (a, b) = (tutorial_pixel(&phong, open), tutorial_pixel(&shadows, open));
    assert!((a - b).abs().max_element() < 1e-3, "{a} vs {b}");
}

#[test]
fn the_chrome_sphere_reflects_instead_of_showing_its_own_colour() {
    let image = render("reflections").image;
    let c = tutorial_pixel(&image, tutorial::SPHERE.truncate());
    assert!(c.z > c.x, "the sphere's centre reflects the blue-grey world, not red: {c}");
}

#[test]
fn the_environment_map_is_seen_in_the_direction_it_was_made_for() {
    let image = render("envmap").image;
    let camera = tutorial::camera();
    for x in [0, W / 3, W - 1] {
        let d = camera.ray_direction(x, H - 1, W, H);
        let expected = envmap::sky(d);
        let got = image.at(x, H - 1).truncate();
        assert!(
            (got - expected).abs().max_element() < 0.04,
            "pixel ({x}, top) looks along {d}: {got} vs sky {expected}"
        );
    }
}

#[test]
fn the_glass_gem_changes_what_is_seen_through_it() {
    let envmap = render("envmap").image;
    let glass = render("convex_hull").image;
    let p = examples::convex_hull::GEM_CENTER + Vec3::new(0.0, 1.0, 0.0);
    let (behind, through) = (tutorial_pixel(&envmap, p), tutorial_pixel(&glass, p));
    assert!((behind - through).abs().max_element() > 0.05, "{behind} vs {through}");
    // Refraction found something: not black, not the exception colour.
    assert!(luminance(through) > 0.05 && through != Vec4::new(1.0, 0.0, 1.0, 1.0), "{through}");
}

#[test]
fn cornell_walls_have_their_mtl_colours_and_the_light_is_bright() {
    let image = render("cornell").image;
    let camera = cornell::camera(W as f32 / H as f32);
    let at = |p: Vec3| {
        let (x, y) = camera.pixel_of(p, W, H).unwrap_or_else(|| panic!("{p} is out of the frame"));
        image.at(x, y)
    };
    let red = at(Vec3::new(552.0, 300.0, 400.0));
    assert!(red.x > 3.0 * red.y.max(red.z) && red.x > 0.2, "red wall {red}");
    let green = at(Vec3::new(1.0, 300.0, 400.0));
    assert!(green.y > 3.0 * green.x.max(green.z) && green.y > 0.2, "green wall {green}");
    let light = at(Vec3::new(278.0, 547.0, 280.0));
    assert!(light.truncate().min_element() > 0.95, "the light {light}");
    // Beside the box's opening there is nothing: black.
    assert_eq!(image.at(0, H / 2).truncate(), Vec3::ZERO);
}

#[test]
fn the_bunnys_shadow_side_is_darker_than_its_lit_side() {
    let image = render("bunny").image;
    let loaded = mesh::load_obj(&examples::scene::shared_scene("stanford-bunny.obj")).unwrap();
    let view = MeshView::default();
    let camera = bunny::camera(&loaded, view, W as f32 / H as f32);
    let light = bunny::key_light_position(&loaded, view);
    let (mut lit, mut dark) = (Vec::new(), Vec::new());
    let m = &loaded.mesh;
    for t in &m.indices {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let p = (a + b + c) / 3.0;
        if n.dot((camera.eye - p).normalize()) < 0.4 {
            continue;
        }
        let Some((x, y)) = camera.pixel_of(p, W, H) else { continue };
        let n_dot_l = n.dot((light - p).normalize());
        if n_dot_l > 0.7 {
            lit.push(luminance(image.at(x, y)));
        } else if n_dot_l < -0.1 {
            dark.push(luminance(image.at(x, y)));
        }
    }
    assert!(lit.len() > 20 && dark.len() > 20, "{} lit and {} dark samples", lit.len(), dark.len());
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    assert!(mean(&lit) > 1.3 * mean(&dark), "lit {} vs shadow side {}", mean(&lit), mean(&dark));
}

#[test]
fn instances_share_one_mesh_but_not_one_colour() {
    let image = render("instances").image;
    let camera = instances::camera();
    let mut hues = Vec::new();
    for m in instances::transforms() {
        // The middle of the teapot's body.
        let p = m.transform_point3(Vec3::new(0.0, 1.2, 0.0));
        let Some((x, y)) = camera.pixel_of(p, W, H) else { continue };
        let c = image.at(x, y).truncate();
        let chroma = (c / c.element_sum().max(1e-6) * 5.0).round();
        if !hues.contains(&chroma) {
            hues.push(chroma);
        }
    }
    assert_eq!(instances::transforms().len(), 100);
    assert!(hues.len() >= 4, "only {} colours among the instances: {hues:?}", hues.len());
}

/// The receiver grid's pixel over floor point `(x, z)`.
fn grid_pixel(image: &Image, x: f32, z: f32) -> (u32, u32) {
    let half = glam::Vec2::new(2.0 * W as f32 / H as f32, 2.0);
    let u = (x / half.x * 0.5 + 0.5) * W as f32;
    let v = (z / half.y * 0.5 + 0.5) * H as f32;
    assert!(
        u >= 0.0 && v >= 0.0 && (u as u32) < image.width && (v as u32) < image.height,
        "({x}, {z}) is off the grid"
    );
    (u as u32, v as u32)
}

#[test]
fn the_receiver_grid_counts_the_inverse_square_law_and_the_walls_shadow() {
    let image = render("receiver_grid").image;
    let s = receiver_grid::SOURCE;
    // A source emitting uniformly over its lower hemisphere puts N / (2 pi h^2)
    // rays per unit area at its foot; a uniform spread over the floor
    // (2w x 2d) would put N / (4 w d). The picture shows their ratio a as
    // 1 - exp(-1.2 a) in red (plus a little of the reflected field's).
    let floor_area = 4.0 * (2.0 * W as f32 / H as f32) * 2.0;
    let a = floor_area / (std::f32::consts::TAU * s.y * s.y);
    let want = 1.0 - (-1.2 * a).exp();
    let (px, py) = grid_pixel(&image, s.x, s.z);
    let mut red = 0.0;
    for dy in 0..5 {
        for dx in 0..5 {
            red += image.at(px + dx - 2, py + dy - 2).x / 25.0;
        }
    }
    assert!((red - want).abs() < 0.06, "red {red} at the source's foot, want {want} (a = {a})");
    // Behind the long wall (z from -1.5 to -1.3, 1.2 high), seen from the
    // source 1.8 high: no direct ray reaches the floor to the far edge, so
    // red is only the reflected field's share (0.15 of its blue).
    let shadow = image.at(grid_pixel(&image, 0.5, -1.8).0, grid_pixel(&image, 0.5, -1.8).1);
    assert!(shadow.x <= 0.15 * shadow.z + 0.02, "direct sound behind the wall: {shadow}");
    // The obstacles' tops are grey.
    let top = image.at(grid_pixel(&image, -1.3, -0.25).0, grid_pixel(&image, -1.3, -0.25).1);
    assert!((top.x - top.y).abs() < 1e-6 && (top.y - top.z).abs() < 1e-6 && top.x > 0.3, "box top: {top}");
}

#[test]
fn each_callable_brdf_shades_its_own_object() {
    let brdfs = render("callable_brdfs").image;
    let plain = render("diffuse").image;
    let eye = tutorial::camera().eye;
    let lights = tutorial::lights();
    // The floor's BRDF is Lambert: the diffuse example's floor.
    let floor = Vec3::new(1.0, 0.0, 3.0);
    let (a, b) = (tutorial_pixel(&brdfs, floor), tutorial_pixel(&plain, floor));
    assert!((a - b).abs().max_element() < 1e-5, "floor: {a} with the callable, {b} diffuse");
    // The sphere's is the toon shade: where it faces the eye (no highlight
    // there), `kd` times the ambient light plus each light's colour times
    // one of the bands; where its normal is the half vector of the key
    // light and the eye, the hard white highlight.
    let c = tutorial::SPHERE.truncate();
    let facing = c + (eye - c).normalize();
    let got = tutorial_pixel(&brdfs, facing).truncate();
    let bands = callable_brdfs::TOON_BANDS;
    let banded = bands.iter().flat_map(|k| bands.iter().map(move |f| (*k, *f))).find(|(k, f)| {
        let want = diffuse::SPHERE_KD * (diffuse::AMBIENT + lights[0].color * *k + lights[1].color * *f);
        (want - got).abs().max_element() < 1e-4
    });
    assert!(banded.is_some(), "sphere facing the eye: {got} is no band of the toon shade");
    let h = ((lights[0].pos - c).normalize() + (eye - c).normalize()).normalize();
    let (a, b) = (tutorial_pixel(&brdfs, c + h), tutorial_pixel(&plain, c + h));
    assert!(luminance(a) > luminance(b) + 0.2, "sphere highlight: {a} with the callable, {b} diffuse");
    // The box's is Blinn-Phong: the diffuse example's box plus each light's
    // highlight (the front face's middle, where the pixel's ray hits within
    // half a pixel).
    let center = (tutorial::BOX_MIN + tutorial::BOX_MAX) * 0.5;
    let n = glam::Quat::from_rotation_y(tutorial::BOX_YAW) * Vec3::Z;
    let front = center + n;
    let v = (eye - front).normalize();
    let highlight: Vec3 = lights
        .iter()
        .map(|light| {
            let h = ((light.pos - front).normalize() + v).normalize();
            light.color * callable_brdfs::BLINN_KS * n.dot(h).max(0.0).powf(callable_brdfs::BLINN_EXP)
        })
        .sum();
    let got = (tutorial_pixel(&brdfs, front) - tutorial_pixel(&plain, front)).truncate();
    assert!(highlight.min_element() > 0.01, "the front face has a highlight to see: {highlight}");
    assert!((got - highlight).abs().max_element() < 0.004, "box front: {got} over diffuse, want {highlight}");
}

/// `Scene::render_async` (the browser page's) gives what `Scene::render`
/// gives: the same picture and, for a scene that accumulates, the same
/// radiance.
#[test]
fn render_async_gives_what_render_gives() {
    let example = examples::example("bunny").unwrap();
    let mut scene = (example.build)(&settings()).unwrap();
    let blocking = scene.render(&mut |_| {}).unwrap();
    let mut scene = (example.build)(&settings()).unwrap();
    let awaited = pollster::block_on(scene.render_async()).unwrap();
    assert_eq!(awaited.image, blocking.image);
    assert!(blocking.radiance.is_some(), "the bunny accumulates");
    assert_eq!(awaited.radiance, blocking.radiance);
    assert_eq!((awaited.rays, awaited.launches, awaited.exceptions.len()), (blocking.rays, blocking.launches, 0));
}
