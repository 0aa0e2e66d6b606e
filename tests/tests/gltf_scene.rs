//! A glTF file written here with the `gltf` crate's JSON types (two nodes
//! instancing one textured quad under different transforms, and a camera)
//! loaded by `rt-scene` and rendered on
//! both backends, against the same scene built by hand through the
//! runtime's API: the same image, bit for bit, and the texture's colours
//! where they belong. Also the EXR round trip: `Context::save_exr` read
//! back by the `image` crate gives the same bits.

use examples::{Camera, Scene, Settings};
use glam::{Mat4, Vec2, Vec3, Vec4};
use gltf::json::{self, accessor::ComponentType, accessor::Type, validation::Checked::Valid, validation::USize64};
use rt_runtime::{Acceleration, Backend, BufferType, Builder, Context, Scope, TriangleMesh};
use rt_std::prelude::*;
use std::path::{Path, PathBuf};

#[rt_payload]
pub struct Colour {
    pub result: Vec3,
}

/// One ray through each pixel's centre, as `examples::Camera` sets `u`,
/// `v`, `w`.
#[rt_program(ray_generation)]
pub fn pinhole(
    #[var] eye: Vec3,
    #[var] u: Vec3,
    #[var] v: Vec3,
    #[var] w: Vec3,
    #[var] top_object: Object,
    #[var] mut output_buffer: RwBuffer2d<Vec4>,
) {
    let d = (launch_index().as_vec2() + 0.5) / launch_dim().as_vec2() * 2.0 - 1.0;
    let mut prd = Colour { result: Vec3::ZERO };
    rt_trace(top_object, Ray::new(eye, (d.x * u + d.y * v + w).normalize(), 0, 1e-4, f32::INFINITY), &mut prd);
    output_buffer[launch_index()] = prd.result.extend(1.0);
}

#[rt_program(miss)]
pub fn sky(prd: &mut Colour, #[var] bg_color: Vec3) {
    prd.result = bg_color;
}

#[rt_attributes]
pub struct Surface {
    pub texcoord: Vec2,
}

/// What the loader's material variables say: base colour times texture.
#[rt_program(closest_hit)]
pub fn textured(prd: &mut Colour, attr: &Surface, #[var] base_color: Vec3, #[var] base_color_texture: Sampler2d) {
    prd.result = base_color * base_color_texture.sample(attr.texcoord).xyz();
}

const W: u32 = 48;
const H: u32 = 36;
const BASE: Vec3 = Vec3::new(1.0, 0.5, 1.0);
/// The 2x2 texture, top row first: red, green / blue, white (0 and 1 are
/// the same in sRGB and linear).
const TEXELS: [Vec4; 4] =
    [Vec4::new(1.0, 0.0, 0.0, 1.0), Vec4::new(0.0, 1.0, 0.0, 1.0), Vec4::new(0.0, 0.0, 1.0, 1.0), Vec4::ONE];

/// A unit quad in z = 0 facing +z, texture coordinate (0, 0) at its top
/// left as glTF has it.
fn quad() -> TriangleMesh {
    TriangleMesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: Some(vec![Vec3::Z; 4]),
        texcoords: Some(vec![Vec2::new(0.0, 1.0), Vec2::ONE, Vec2::new(1.0, 0.0), Vec2::ZERO]),
        material_indices: None,
    }
}

fn second() -> Mat4 {
    Mat4::from_translation(Vec3::new(1.4, -0.2, -0.5)) * Mat4::from_rotation_z(0.3)
}

fn camera() -> Camera {
    Camera { eye: Vec3::new(1.2, 0.5, 4.0), look_at: Vec3::new(1.2, 0.5, 0.0), up: Vec3::Y, vfov_degrees: 40.0 }
}

fn png() -> Vec<u8> {
    let img = image::RgbaImage::from_fn(2, 2, |x, y| {
        let t = TEXELS[(y * 2 + x) as usize];
        image::Rgba([(t.x * 255.0) as u8, (t.y * 255.0) as u8, (t.z * 255.0) as u8, 255])
    });
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).unwrap();
    bytes.into_inner()
}

/// The file, written with the `gltf` crate's own JSON types (not
/// `rt_scene::glb`, so the loader is checked against a writer of its own)
/// as a `.glb`: one textured quad mesh, two nodes showing it (the second
/// under [`second`]), a camera node.
fn write_file(dir: &Path) -> PathBuf {
    let mut doc = Document { root: json::Root::default(), bin: Vec::new() };
    let (attributes, index) = quad_accessors(&mut doc);
    let material = textured_material(&mut doc);
    let quad_mesh = doc.root.push(json::Mesh {
        extensions: None,
        extras: Default::default(),
        name: Some("quad".into()),
        primitives: vec![json::mesh::Primitive {
            attributes: attributes.into_iter().map(|(s, a)| (Valid(s), a)).collect(),
            extensions: None,
            extras: Default::default(),
            indices: Some(index),
            material: Some(material),
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        }],
        weights: None,
    });
    let first = doc.root.push(json::Node { mesh: Some(quad_mesh), ..Default::default() });
    let moved = doc.root.push(json::Node {
        mesh: Some(quad_mesh),
        matrix: Some(second().to_cols_array()),
        ..Default::default()
    });
    let viewer = camera_node(&mut doc);
    let scene = doc.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: None,
        nodes: vec![first, moved, viewer],
    });
    doc.root.scene = Some(scene);
    let path = dir.join("instanced.glb");
    std::fs::write(&path, doc.glb()).unwrap();
    path
}

/// A glTF document being written: its JSON and its binary chunk.
struct Document {
    root: json::Root,
    bin: Vec<u8>,
}

impl Document {
    /// `bytes` appended to the binary chunk (4-byte aligned) as a buffer
    /// view.
    fn view(&mut self, bytes: &[u8]) -> json::Index<json::buffer::View> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let v = json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(bytes.len()),
            byte_offset: Some(USize64::from(self.bin.len())),
            byte_stride: None,
            name: None,
            target: None,
            extensions: None,
            extras: Default::default(),
        };
        self.bin.extend_from_slice(bytes);
        self.root.push(v)
    }

    /// `count` elements of `bytes` (in a view of their own) as an accessor.
    fn accessor(
        &mut self,
        bytes: &[u8],
        count: usize,
        component: ComponentType,
        type_: Type,
        bounds: Option<(Vec3, Vec3)>,
    ) -> json::Index<json::Accessor> {
        let view = self.view(bytes);
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(type_),
            min: bounds.map(|(lo, _)| json::Value::from(lo.to_array().to_vec())),
            max: bounds.map(|(_, hi)| json::Value::from(hi.to_array().to_vec())),
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    /// The document as a `.glb`, its one buffer the binary chunk.
    fn glb(mut self) -> Vec<u8> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.root.push(json::Buffer {
            byte_length: USize64::from(self.bin.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: Default::default(),
        });
        let json = self.root.to_vec().expect("the document serialises");
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header { magic: *b"glTF", version: 2, length: 0 },
            json: json.into(),
            bin: Some(self.bin.into()),
        };
        glb.to_vec().expect("the GLB assembles")
    }
}

/// A vertex attribute of a mesh primitive: its semantic and accessor.
type Attribute = (json::mesh::Semantic, json::Index<json::Accessor>);

/// [`quad`]'s vertex attributes (positions, normals, texture coordinates)
/// and its indices as accessors.
fn quad_accessors(doc: &mut Document) -> ([Attribute; 3], json::Index<json::Accessor>) {
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let mesh = quad();
    let positions: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let normals: Vec<f32> = mesh.normals.as_ref().unwrap().iter().flat_map(|n| n.to_array()).collect();
    let texcoords: Vec<f32> = mesh.texcoords.as_ref().unwrap().iter().flat_map(|t| t.to_array()).collect();
    let indices: Vec<u8> = mesh.indices.iter().flatten().flat_map(|i| (*i as u16).to_le_bytes()).collect();
    let bounds = Some((Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0)));
    let position = doc.accessor(&floats(&positions), 4, ComponentType::F32, Type::Vec3, bounds);
    let normal = doc.accessor(&floats(&normals), 4, ComponentType::F32, Type::Vec3, None);
    let texcoord = doc.accessor(&floats(&texcoords), 4, ComponentType::F32, Type::Vec2, None);
    let index = doc.accessor(&indices, 6, ComponentType::U16, Type::Scalar, None);
    let attributes = [
        (json::mesh::Semantic::Positions, position),
        (json::mesh::Semantic::Normals, normal),
        (json::mesh::Semantic::TexCoords(0), texcoord),
    ];
    (attributes, index)
}

/// The material: [`BASE`] times the [`png`] texture (embedded in the
/// binary chunk).
fn textured_material(doc: &mut Document) -> json::Index<json::Material> {
    let v = doc.view(&png());
    let image = doc.root.push(json::Image {
        buffer_view: Some(v),
        mime_type: Some(json::image::MimeType("image/png".into())),
        name: None,
        uri: None,
        extensions: None,
        extras: Default::default(),
    });
    let texture = doc.root.push(json::Texture {
        name: None,
        sampler: None,
        source: image,
        extensions: None,
        extras: Default::default(),
    });
    doc.root.push(json::Material {
        name: Some("textured".into()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor(BASE.extend(1.0).to_array()),
            base_color_texture: Some(json::texture::Info {
                index: texture,
                tex_coord: 0,
                extensions: None,
                extras: Default::default(),
            }),
            metallic_factor: json::material::StrengthFactor(0.0),
            ..Default::default()
        },
        ..Default::default()
    })
}

/// The [`camera`] as a perspective camera's node.
fn camera_node(doc: &mut Document) -> json::Index<json::Node> {
    let c = camera();
    let lens = doc.root.push(json::Camera {
        name: None,
        orthographic: None,
        perspective: Some(json::camera::Perspective {
            aspect_ratio: None,
            yfov: c.vfov_degrees.to_radians(),
            zfar: None,
            znear: 0.01,
            extensions: None,
            extras: Default::default(),
        }),
        type_: Valid(json::camera::Type::Perspective),
        extensions: None,
        extras: Default::default(),
    });
    // The camera looks down its -z: from the eye towards the quads, +y up.
    doc.root.push(json::Node { camera: Some(lens), translation: Some(c.eye.to_array()), ..Default::default() })
}

/// The programs, camera and background both scenes share.
fn start(backend: Backend, camera: &Camera) -> (Context, rt_runtime::BufferId, rt_runtime::ProgramId) {
    let settings = Settings { spp: 1, backend, ..Settings::new(W, H) };
    let (mut ctx, output) = Scene::start(&settings, 1e-4).unwrap();
    ctx.set_ray_type_count(1);
    let rg = ctx.create_program(&pinhole::PROGRAM);
    ctx.set_ray_generation_program(0, rg).unwrap();
    let miss = ctx.create_program(&sky::PROGRAM);
    ctx.set_miss_program(0, miss).unwrap();
    ctx.set_var(Scope::Context, "bg_color", Vec3::new(0.0, 0.0, 0.2)).unwrap();
    camera.set_vars(&mut ctx, W as f32 / H as f32).unwrap();
    let shade = ctx.create_program(&textured::PROGRAM);
    (ctx, output, shade)
}

fn render(ctx: Context, output: rt_runtime::BufferId, backend: Backend) -> Vec<Vec4> {
    let settings = Settings { spp: 1, backend, ..Settings::new(W, H) };
    let mut scene = Scene::new(ctx, output, &settings);
    let rendered = scene.render(&mut |_| {}).unwrap_or_else(|e| panic!("{}: {e}", backend.name()));
    assert!(rendered.exceptions.is_empty(), "{:?}", rendered.exceptions);
    rendered.image.pixels
}

fn loaded(backend: Backend, path: &Path) -> Vec<Vec4> {
    let file_camera = rt_scene::gltf::read(path).unwrap().camera.expect("the file has a camera");
    let c = camera();
    assert!((file_camera.eye - c.eye).length() < 1e-6, "{file_camera:?}");
    assert!((file_camera.forward - -Vec3::Z).length() < 1e-6, "{file_camera:?}");
    assert!((file_camera.vfov_degrees - c.vfov_degrees).abs() < 1e-4, "{file_camera:?}");
    let (mut ctx, output, shade) = start(backend, &c);
    let scene = rt_scene::load(&mut ctx, path).unwrap();
    assert_eq!((scene.info.meshes, scene.info.instances), (1, 2));
    for m in &scene.materials {
        ctx.set_closest_hit_program(m.id, 0, shade).unwrap();
    }
    ctx.set_var(Scope::Context, "top_object", scene.top).unwrap();
    render(ctx, output, backend)
}

fn by_hand(backend: Backend) -> Vec<Vec4> {
    let (mut ctx, output, shade) = start(backend, &camera());
    let material = ctx.create_material();
    ctx.set_closest_hit_program(material, 0, shade).unwrap();
    let texture = ctx.create_sampler(TEXELS.to_vec(), 2, 2, WrapMode::Repeat, FilterMode::Linear).unwrap();
    ctx.set_var(material, "base_color", BASE).unwrap();
    ctx.set_var(material, "base_color_texture", texture).unwrap();
    let geometry = ctx.create_triangles(quad()).unwrap();
    let instance = ctx.create_geometry_instance(geometry, &[material]).unwrap();
    let group = ctx.create_geometry_group(&[instance], Acceleration::new(Builder::Bvh)).unwrap();
    let moved = ctx.create_transform(second(), group).unwrap();
    let top = ctx.create_group(&[group, moved], Acceleration::new(Builder::Bvh)).unwrap();
    ctx.set_var(Scope::Context, "top_object", top).unwrap();
    render(ctx, output, backend)
}

fn pixel_at(pixels: &[Vec4], p: Vec3) -> Vec4 {
    let (x, y) = camera().pixel_of(p, W, H).expect("in view");
    pixels[(y * W + x) as usize]
}

#[test]
fn a_gltf_with_an_instanced_textured_mesh_renders_as_the_same_scene_built_by_hand() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("gltf-scene");
    std::fs::create_dir_all(&dir).unwrap();
    let path = write_file(&dir);
    for backend in [Backend::Cpu, Backend::Wgpu] {
        let from_file = loaded(backend, &path);
        let built = by_hand(backend);
        let differing = from_file.iter().zip(&built).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "{}: {differing} pixels differ", backend.name());
        // The first instance's top-left quarter is the red texel times the
        // base colour; its bottom-right, white times the base colour.
        let red = pixel_at(&from_file, Vec3::new(0.25, 0.75, 0.0));
        assert!((red.truncate() - Vec3::new(1.0, 0.0, 0.0)).abs().max_element() < 0.2, "{}: {red}", backend.name());
        let white = pixel_at(&from_file, Vec3::new(0.75, 0.25, 0.0));
        assert!((white.truncate() - BASE).abs().max_element() < 0.2, "{}: {white}", backend.name());
        // The second instance is there too, where its transform put it.
        let moved = pixel_at(&from_file, second().transform_point3(Vec3::new(0.75, 0.25, 0.0)));
        assert!((moved.truncate() - BASE).abs().max_element() < 0.2, "{}: {moved}", backend.name());
        let sky = pixel_at(&from_file, Vec3::new(-0.5, 1.8, 0.0));
        assert_eq!(sky.truncate(), Vec3::new(0.0, 0.0, 0.2), "{}", backend.name());
    }
}

#[test]
fn exr_round_trips_bit_exactly() {
    let (w, h) = (5u32, 3u32);
    let values: Vec<Vec4> = (0..w * h)
        .map(|i| {
            let f = i as f32;
            Vec4::new(f * 0.1 - 0.5, 1.0 / (f + 3.0), 1e-30 * f + 1e5, std::f32::consts::PI * f)
        })
        .collect();
    let mut ctx = Context::new();
    let buffer = ctx.create_buffer_2d::<Vec4>(BufferType::Output, w, h).unwrap();
    ctx.write_buffer(buffer, &values).unwrap();
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("round-trip.exr");
    ctx.save_exr(buffer, &path).unwrap();
    let back = image::open(&path).unwrap();
    assert!(matches!(back, image::DynamicImage::ImageRgba32F(_)), "{:?}", back.color());
    let back = back.to_rgba32f();
    assert_eq!(back.dimensions(), (w, h));
    for y in 0..h {
        for x in 0..w {
            // Launch index (0, 0) is the bottom-left pixel: rows flip.
            let want = values[((h - 1 - y) * w + x) as usize].to_array().map(f32::to_bits);
            let got = back.get_pixel(x, y).0.map(f32::to_bits);
            assert_eq!(got, want, "pixel ({x}, {y})");
        }
    }
}
