//! The GPU records the runtime writes and the megakernel reads, declared
//! once: each a Rust struct with its word layout, from which the WGSL
//! declaration is generated, so no offset is kept by hand in two languages.

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
    /// The launch's size.
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
}

impl LaunchUniform {
    /// Its size in 32-bit words.
    pub const WORDS: usize = 12;

    /// Its fields in order, as WGSL declares them.
    pub const FIELDS: &'static [Field] = &[
        Field { name: "dim", wgsl: "vec2<u32>", word: 0 },
        Field { name: "origin", wgsl: "vec2<u32>", word: 2 },
        Field { name: "ray_generation", wgsl: "vec2<u32>", word: 4 },
        Field { name: "exception", wgsl: "vec2<u32>", word: 6 },
        Field { name: "log_capacity", wgsl: "u32", word: 8 },
        Field { name: "print_enabled", wgsl: "u32", word: 9 },
        Field { name: "print_filter", wgsl: "vec2<u32>", word: 10 },
    ];

    /// The words the uniform buffer holds.
    pub fn words(&self) -> [u32; Self::WORDS] {
        let [dx, dy] = self.dim;
        let [ox, oy] = self.origin;
        let [rc, rv] = self.ray_generation;
        let [ec, ev] = self.exception;
        let [fx, fy] = self.print_filter;
        [dx, dy, ox, oy, rc, rv, ec, ev, self.log_capacity, self.print_enabled, fx, fy]
    }

    /// The WGSL declaration, `struct RtLaunch { ... }`.
    pub fn wgsl() -> String {
        record_wgsl("RtLaunch", Self::FIELDS)
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
        };
        let w = u.words();
        let first = [1, 3, 5, 7, 9, 10, 11];
        for (f, v) in LaunchUniform::FIELDS.iter().zip(first) {
            assert_eq!(w[f.word as usize], v, "`{}`", f.name);
        }
        assert!(LaunchUniform::wgsl().contains("    print_filter: vec2<u32>,\n"));
    }
}
