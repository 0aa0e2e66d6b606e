//! The GPU records the runtime writes and the megakernel reads, declared
//! once: each a Rust struct with its word layout, from which the WGSL
//! declaration is generated, so no offset is kept by hand in two languages.

use crate::wgsl::u32_constants;

/// One field of a record: its WGSL name and type and its first word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    pub name: &'static str,
    pub wgsl: &'static str,
    pub word: u32,
}

/// The launch uniform (WGSL `RtLaunch`, binding 3): one per dispatched tile
/// of a launch.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LaunchUniform {
    /// The launch's grid: its width, and its height times its depth (a 3D
    /// launch runs as slices of rows; programs see `dim.y / depth` rows).
    pub dim: [u32; 2],
    /// The tile's first launch index.
    pub origin: [u32; 2],
    /// The entry point's ray-generation program: dispatch case and the heap
    /// word of its variables.
    pub ray_generation: [u32; 2],
    /// The same for its exception program.
    pub exception: [u32; 2],
    /// How many exceptions the log records.
    pub log_capacity: u32,
    /// Whether `rt_printf` prints (0 or 1).
    pub print_enabled: u32,
    /// The launch index printing is limited to (`u32::MAX` for any).
    pub print_filter: [u32; 2],
    /// The exception kinds raised, as [`exception_kind_bit`](crate::constants::exception_kind_bit)s:
    /// a disabled kind's check still guards the operation (an index out of
    /// bounds still reads nothing), but raises nothing.
    pub exceptions: u32,
    /// The heap word of the bindless buffer table ([`BufferTable`]).
    pub buffer_table: u32,
    /// The launch's depth: 1 but for 3D launches.
    pub depth: u32,
    /// Zero: WGSL rounds the struct to its 8-byte alignment.
    pub reserved: u32,
}

impl LaunchUniform {
    /// Its size in 32-bit words.
    pub const WORDS: usize = 16;

    /// Its fields in order, as WGSL declares them.
    pub const FIELDS: &'static [Field] = &[
        Field { name: "dim", wgsl: "vec2<u32>", word: 0 },
        Field { name: "origin", wgsl: "vec2<u32>", word: 2 },
        Field { name: "ray_generation", wgsl: "vec2<u32>", word: 4 },
        Field { name: "exception", wgsl: "vec2<u32>", word: 6 },
        Field { name: "log_capacity", wgsl: "u32", word: 8 },
        Field { name: "print_enabled", wgsl: "u32", word: 9 },
        Field { name: "print_filter", wgsl: "vec2<u32>", word: 10 },
        Field { name: "exceptions", wgsl: "u32", word: 12 },
        Field { name: "buffer_table", wgsl: "u32", word: 13 },
        Field { name: "depth", wgsl: "u32", word: 14 },
        Field { name: "reserved", wgsl: "u32", word: 15 },
    ];

    /// The words the uniform buffer holds.
    pub fn words(&self) -> [u32; Self::WORDS] {
        let [dx, dy] = self.dim;
        let [ox, oy] = self.origin;
        let [rc, rv] = self.ray_generation;
        let [ec, ev] = self.exception;
        let [fx, fy] = self.print_filter;
        [
            dx,
            dy,
            ox,
            oy,
            rc,
            rv,
            ec,
            ev,
            self.log_capacity,
            self.print_enabled,
            fx,
            fy,
            self.exceptions,
            self.buffer_table,
            self.depth,
            self.reserved,
        ]
    }

    /// The WGSL declaration, `struct RtLaunch { ... }`.
    pub fn wgsl() -> String {
        record_wgsl("RtLaunch", Self::FIELDS)
    }
}

/// The bindless buffer table in the heap, at the launch uniform's
/// `buffer_table` word: the number of buffers, then one entry of
/// [`WORDS`](Self::WORDS) per buffer, the entry of bindless id `id`
/// (`rt_std::BindlessBuffer`; the context's buffer index plus one, zero for
/// none) at `buffer_table + 1 + (id - 1) * WORDS`. The megakernel's
/// `rt_bufid_ok` checks an id against it, `rt_bufid` reads the buffer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BufferTable {
    /// The heap word of the buffer's first element.
    pub offset: u32,
    /// Its elements (`width * height` for a 2D buffer).
    pub len: u32,
    /// [`layout_tag`] of its element type's name.
    pub tag: u32,
    /// Whether programs may write it (1) or not (0).
    pub writable: u32,
}

impl BufferTable {
    /// An entry's size in 32-bit words.
    pub const WORDS: u32 = 4;
    pub const OFFSET: u32 = 0;
    pub const LEN: u32 = 1;
    pub const TAG: u32 = 2;
    pub const WRITABLE: u32 = 3;

    /// The entry's words.
    pub fn words(&self) -> [u32; Self::WORDS as usize] {
        let mut w = [0u32; Self::WORDS as usize];
        w[Self::OFFSET as usize] = self.offset;
        w[Self::LEN as usize] = self.len;
        w[Self::TAG as usize] = self.tag;
        w[Self::WRITABLE as usize] = self.writable;
        w
    }

    /// The WGSL constants the megakernel reads an entry by.
    pub fn wgsl_constants() -> String {
        u32_constants(&[
            ("RT_BUFID_WORDS", Self::WORDS),
            ("RT_BUFID_OFFSET", Self::OFFSET),
            ("RT_BUFID_LEN", Self::LEN),
            ("RT_BUFID_TAG", Self::TAG),
            ("RT_BUFID_WRITABLE", Self::WRITABLE),
        ])
    }
}

/// The bindless sampler table in the heap, right after the
/// [`BufferTable`] (at `buffer_table + 1 + buffers * BufferTable::WORDS`,
/// so the launch uniform needs no word of its own): the number of
/// samplers, then one entry of [`WORDS`](Self::WORDS) per sampler, the
/// entry of bindless sampler id `id` (`rt_std::BindlessSampler`; the
/// context's sampler index plus one, zero for none) at
/// `table + 1 + (id - 1) * WORDS`. The megakernel's `rt_texid` checks an
/// id's shape against it and reads the sampler's record.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SamplerTable {
    /// The heap word of the sampler's first texel.
    pub offset: u32,
    /// Level 0's width in texels (a cube map's face size).
    pub width: u32,
    /// Level 0's height in texels.
    pub height: u32,
    /// A 3D sampler's depth in texels (1 for the others).
    pub depth: u32,
    /// The modes word, as `RtSampler.mode`.
    pub mode: u32,
    /// [`SHAPE_2D`](Self::SHAPE_2D), [`SHAPE_3D`](Self::SHAPE_3D) or
    /// [`SHAPE_CUBE`](Self::SHAPE_CUBE).
    pub shape: u32,
}

impl SamplerTable {
    /// An entry's size in 32-bit words.
    pub const WORDS: u32 = 6;
    pub const OFFSET: u32 = 0;
    pub const WIDTH: u32 = 1;
    pub const HEIGHT: u32 = 2;
    pub const DEPTH: u32 = 3;
    pub const MODE: u32 = 4;
    pub const SHAPE: u32 = 5;
    /// A `Sampler2d`'s shape.
    pub const SHAPE_2D: u32 = 1;
    /// A `Sampler3d`'s shape.
    pub const SHAPE_3D: u32 = 2;
    /// A `SamplerCube`'s shape.
    pub const SHAPE_CUBE: u32 = 3;

    /// The entry's words.
    pub fn words(&self) -> [u32; Self::WORDS as usize] {
        let mut w = [0u32; Self::WORDS as usize];
        w[Self::OFFSET as usize] = self.offset;
        w[Self::WIDTH as usize] = self.width;
        w[Self::HEIGHT as usize] = self.height;
        w[Self::DEPTH as usize] = self.depth;
        w[Self::MODE as usize] = self.mode;
        w[Self::SHAPE as usize] = self.shape;
        w
    }

    /// The WGSL constants the megakernel reads an entry by.
    pub fn wgsl_constants() -> String {
        u32_constants(&[
            ("RT_TEXID_WORDS", Self::WORDS),
            ("RT_TEXID_OFFSET", Self::OFFSET),
            ("RT_TEXID_WIDTH", Self::WIDTH),
            ("RT_TEXID_HEIGHT", Self::HEIGHT),
            ("RT_TEXID_DEPTH", Self::DEPTH),
            ("RT_TEXID_MODE", Self::MODE),
            ("RT_TEXID_SHAPE", Self::SHAPE),
            ("RT_TEXID_3D", Self::SHAPE_3D),
        ])
    }
}

/// The tag of an element type, by its Rust name as its layout spells it
/// (`Vec3`, `Radiance`, `BindlessBuffer`): 32-bit FNV-1a. The compiler
/// writes the tag of a bindless id's element type into its accessors and
/// the runtime the tag of each buffer's into the [`BufferTable`], so that
/// an id read as a buffer of another element type is refused.
pub const fn layout_tag(name: &str) -> u32 {
    let bytes = name.as_bytes();
    let mut h: u32 = 0x811c_9dc5;
    let mut i = 0;
    while i < bytes.len() {
        h ^= bytes[i] as u32;
        h = h.wrapping_mul(0x0100_0193);
        i += 1;
    }
    h
}

/// One instance of the two-level scene (a geometry group, or a chain of
/// transforms above one), in the scene's instance table: 40 words at
/// `rt_scene[1] + instance * WORDS`. The megakernel reads it through the
/// `RT_INST_*` constants of [`InstanceRecord::wgsl_constants`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct InstanceRecord {
    /// Object to world, column-major.
    pub object_to_world: [f32; 16],
    /// Its inverse, column-major.
    pub world_to_object: [f32; 16],
    /// Scene word of the geometry group's BVH.
    pub bvh: u32,
    /// Scene word of its primitive table.
    pub primitives: u32,
    /// The visibility word: up to four 8-bit masks, one per byte, each of
    /// which a ray mask must share a bit with (the chain of transforms down
    /// to the geometry group; the wgpu encoder's `visibility`).
    pub mask: u32,
    /// The geometry group's node index.
    pub geometry_group: u32,
    /// Scene word of its triangle slots.
    pub triangles: u32,
    /// Scene word of its geometry group's geometry instances: `[count,
    /// geometry instance.., their instance ids..]` (for `instance_index`
    /// and `instance_id`).
    pub geometry_instances: u32,
    /// The instance id of the chain of transforms the record stands for
    /// (its innermost transform with one), or `u32::MAX`.
    pub instance_id: u32,
}

impl InstanceRecord {
    /// Its size in 32-bit words (one word of padding at the end).
    pub const WORDS: u32 = 40;
    pub const OBJECT_TO_WORLD: u32 = 0;
    pub const WORLD_TO_OBJECT: u32 = 16;
    pub const BVH: u32 = 32;
    pub const PRIMITIVES: u32 = 33;
    pub const MASK: u32 = 34;
    pub const GEOMETRY_GROUP: u32 = 35;
    pub const TRIANGLES: u32 = 36;
    pub const GEOMETRY_INSTANCES: u32 = 37;
    pub const INSTANCE_ID: u32 = 38;

    /// The record's words, floats as their bits.
    pub fn words(&self) -> [u32; Self::WORDS as usize] {
        let mut w = [0u32; Self::WORDS as usize];
        let at = |o: u32| o as usize;
        for (i, v) in self.object_to_world.iter().enumerate() {
            w[at(Self::OBJECT_TO_WORLD) + i] = v.to_bits();
        }
        for (i, v) in self.world_to_object.iter().enumerate() {
            w[at(Self::WORLD_TO_OBJECT) + i] = v.to_bits();
        }
        w[at(Self::BVH)] = self.bvh;
        w[at(Self::PRIMITIVES)] = self.primitives;
        w[at(Self::MASK)] = self.mask;
        w[at(Self::GEOMETRY_GROUP)] = self.geometry_group;
        w[at(Self::TRIANGLES)] = self.triangles;
        w[at(Self::GEOMETRY_INSTANCES)] = self.geometry_instances;
        w[at(Self::INSTANCE_ID)] = self.instance_id;
        w
    }

    /// The WGSL constants the megakernel reads the record by.
    pub fn wgsl_constants() -> String {
        u32_constants(&[
            ("RT_INST_WORDS", Self::WORDS),
            ("RT_INST_O2W", Self::OBJECT_TO_WORLD),
            ("RT_INST_W2O", Self::WORLD_TO_OBJECT),
            ("RT_INST_BVH", Self::BVH),
            ("RT_INST_PRIMS", Self::PRIMITIVES),
            ("RT_INST_MASK", Self::MASK),
            ("RT_INST_GG", Self::GEOMETRY_GROUP),
            ("RT_INST_TRIS", Self::TRIANGLES),
            ("RT_INST_GIS", Self::GEOMETRY_INSTANCES),
            ("RT_INST_ID", Self::INSTANCE_ID),
        ])
    }
}

/// The kind of an entry of the scene's node table. Each entry is four
/// words, `[kind, a, b, mask]`, where `mask` is the visibility word of the
/// nodes it stands for (up to four 8-bit masks, one per byte, each of which
/// a ray's mask must share a bit with).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum NodeEntry {
    /// A geometry group, or a transform chain down to one: `a` is its
    /// instance.
    Instance = 0,
    /// A group whose children are all instances: `a` is its BVH, `b` its
    /// leaf table: two words a leaf, its instance index and the instance
    /// index (`instance_index`) of the child's first geometry instance
    /// counted from the group's.
    InstanceGroup = 1,
    /// A group with other children: leaves (two words, as above) are
    /// instance indices, or node indices with the node bit set.
    Group = 2,
    /// A transform chain above a group or selector: `a` is the scene word of
    /// `[object-to-world, world-to-object, instance id]` (the chain's
    /// innermost id, or `u32::MAX`), `b` the node below.
    Transform = 3,
    /// A selector: `a` is the scene word of `[visit case, visit record,
    /// child count, child nodes..., the children's instance index
    /// offsets...]`.
    Selector = 4,
    /// A motion transform (one node): `a` is the scene word of `[instance
    /// id, key kind, key count, t0, t1, keys...]` (rt-runtime's
    /// `MotionTransform::encode` after the id), `b` the node below.
    MotionTransform = 5,
}

impl NodeEntry {
    /// The WGSL constants the megakernel matches the kinds by.
    pub fn wgsl_constants() -> String {
        u32_constants(&[
            ("RT_NODE_INSTANCE", NodeEntry::Instance as u32),
            ("RT_NODE_INSTANCE_GROUP", NodeEntry::InstanceGroup as u32),
            ("RT_NODE_GROUP", NodeEntry::Group as u32),
            ("RT_NODE_TRANSFORM", NodeEntry::Transform as u32),
            ("RT_NODE_SELECTOR", NodeEntry::Selector as u32),
            ("RT_NODE_MOTION_TRANSFORM", NodeEntry::MotionTransform as u32),
        ])
    }
}

/// `struct name { field: type, ... }` with one line a field.
fn record_wgsl(name: &str, fields: &[Field]) -> String {
    let mut s = format!("struct {name} {{\n");
    for f in fields {
        s.push_str(&format!("    {}: {},\n", f.name, f.wgsl));
    }
    s.push_str("}\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Words of a WGSL type in a uniform of only `u32`s and `vec2<u32>`s
    /// (which align to 2 words).
    fn words_of(wgsl: &str) -> u32 {
        match wgsl {
            "u32" => 1,
            "vec2<u32>" => 2,
            other => panic!("no layout for `{other}`"),
        }
    }

    #[test]
    fn fields_follow_wgsl_layout_and_fill_the_record() {
        let mut next = 0u32;
        for f in LaunchUniform::FIELDS {
            let size = words_of(f.wgsl);
            let aligned = next.div_ceil(size) * size;
            assert_eq!(f.word, aligned, "`{}` starts at word {aligned} in WGSL", f.name);
            next = aligned + size;
        }
        assert_eq!(next as usize, LaunchUniform::WORDS);
    }

    #[test]
    fn each_field_lands_at_its_word() {
        let u = LaunchUniform {
            dim: [1, 2],
            origin: [3, 4],
            ray_generation: [5, 6],
            exception: [7, 8],
            log_capacity: 9,
            print_enabled: 10,
            print_filter: [11, 12],
            exceptions: 13,
            buffer_table: 14,
            depth: 15,
            reserved: 16,
        };
        let w = u.words();
        let first = [1, 3, 5, 7, 9, 10, 11, 13, 14, 15, 16];
        for (f, v) in LaunchUniform::FIELDS.iter().zip(first) {
            assert_eq!(w[f.word as usize], v, "`{}`", f.name);
        }
        assert!(LaunchUniform::wgsl().contains("    print_filter: vec2<u32>,\n"));
    }

    #[test]
    fn instance_fields_land_at_their_words() {
        let mut o2w = [0.0f32; 16];
        let mut w2o = [0.0f32; 16];
        for i in 0..16 {
            o2w[i] = i as f32 + 1.0;
            w2o[i] = -(i as f32) - 1.0;
        }
        let r = InstanceRecord {
            object_to_world: o2w,
            world_to_object: w2o,
            bvh: 101,
            primitives: 102,
            mask: 0x7f,
            geometry_group: 104,
            triangles: 105,
            geometry_instances: 106,
            instance_id: 107,
        };
        let w = r.words();
        assert_eq!(f32::from_bits(w[InstanceRecord::OBJECT_TO_WORLD as usize + 5]), 6.0);
        assert_eq!(f32::from_bits(w[InstanceRecord::WORLD_TO_OBJECT as usize + 15]), -16.0);
        let fields = [
            (InstanceRecord::BVH, 101),
            (InstanceRecord::PRIMITIVES, 102),
            (InstanceRecord::MASK, 0x7f),
            (InstanceRecord::GEOMETRY_GROUP, 104),
            (InstanceRecord::TRIANGLES, 105),
            (InstanceRecord::GEOMETRY_INSTANCES, 106),
            (InstanceRecord::INSTANCE_ID, 107),
        ];
        for (at, v) in fields {
            assert_eq!(w[at as usize], v);
        }
        assert!(w[39..].iter().all(|&p| p == 0));
        assert!(InstanceRecord::wgsl_constants().contains("const RT_INST_MASK: u32 = 34u;\n"));
    }

    #[test]
    fn sampler_table_fields_land_at_their_words() {
        let e = SamplerTable { offset: 11, width: 12, height: 13, depth: 14, mode: 15, shape: SamplerTable::SHAPE_3D };
        let w = e.words();
        let fields = [
            (SamplerTable::OFFSET, 11),
            (SamplerTable::WIDTH, 12),
            (SamplerTable::HEIGHT, 13),
            (SamplerTable::DEPTH, 14),
            (SamplerTable::MODE, 15),
            (SamplerTable::SHAPE, 2),
        ];
        for (at, v) in fields {
            assert_eq!(w[at as usize], v);
        }
        assert!(SamplerTable::wgsl_constants().contains("const RT_TEXID_SHAPE: u32 = 5u;\n"));
        // The shapes are distinct and none is 0, an entry's unset word.
        let shapes = [SamplerTable::SHAPE_2D, SamplerTable::SHAPE_3D, SamplerTable::SHAPE_CUBE];
        assert!(
            shapes.iter().all(|&s| s != 0)
                && shapes[0] != shapes[1]
                && shapes[1] != shapes[2]
                && shapes[0] != shapes[2]
        );
    }
}
