//! Generated WGSL accessors: reading and writing typed values in the
//! runtime's heap (packed words, see `types`, through the heap's `rt_hw` and
//! `rt_hw_set`), bounds-checked buffer element access on top of them (also
//! through bindless ids), and atomic updates of 32-bit buffer elements (over the atomic heap).

use crate::types::{Scalar, Ty};
use std::collections::BTreeMap;

/// Accessor functions a module needs, by WGSL name (sorted for stable output).
#[derive(Default)]
pub struct Accessors {
    pub functions: BTreeMap<String, String>,
}

impl Accessors {
    /// `rt_load_<T>(w: u32) -> T`: reads a `T` at word offset `w`.
    pub fn load(&mut self, ty: &Ty) -> String {
        let name = format!("rt_load_{}", ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let t = ty.wgsl();
        let body = match ty {
            Ty::Scalar(Scalar::F32) => "return bitcast<f32>(rt_hw(w));".to_string(),
            Ty::Scalar(Scalar::I32) => "return bitcast<i32>(rt_hw(w));".to_string(),
            _ if matches!(ty, Ty::Scalar(Scalar::U32 | Scalar::Usize)) || ty.is_u32_word() => {
                "return rt_hw(w);".to_string()
            }
            Ty::Scalar(Scalar::Bool) => "return rt_hw(w) != 0u;".to_string(),
            Ty::Vec(n, s) => {
                let f = self.load(&Ty::Scalar(*s));
                let parts: Vec<String> = (0..*n).map(|i| format!("{f}(w + {i}u)")).collect();
                format!("return {t}({});", parts.join(", "))
            }
            Ty::Mat(n) => {
                let f = self.load(&Ty::vec(*n));
                let parts: Vec<String> = (0..*n).map(|i| format!("{f}(w + {}u)", i * n)).collect();
                format!("return {t}({});", parts.join(", "))
            }
            Ty::Array(e, n) => {
                let f = self.load(e);
                format!(
                    "var a: {t};\n    for (var i = 0u; i < {n}u; i++) {{\n        a[i] = {f}(w + i * {}u);\n    }}\n    return a;",
                    e.words()
                )
            }
            _ => {
                let mut offset = 0;
                let mut parts = Vec::new();
                for (_, fty) in ty.fields() {
                    let f = self.load(&fty);
                    parts.push(format!("{f}(w + {offset}u)"));
                    offset += fty.words();
                }
                format!("return {t}({});", parts.join(", "))
            }
        };
        self.functions.insert(name.clone(), format!("fn {name}(w: u32) -> {t} {{\n    {body}\n}}\n"));
        name
    }

    /// `rt_store_<T>(w: u32, v: T)`: writes a `T` at word offset `w`.
    pub fn store(&mut self, ty: &Ty) -> String {
        let name = format!("rt_store_{}", ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let t = ty.wgsl();
        let body = match ty {
            Ty::Scalar(Scalar::F32) | Ty::Scalar(Scalar::I32) => "rt_hw_set(w, bitcast<u32>(v));".to_string(),
            _ if matches!(ty, Ty::Scalar(Scalar::U32 | Scalar::Usize)) || ty.is_u32_word() => {
                "rt_hw_set(w, v);".to_string()
            }
            Ty::Scalar(Scalar::Bool) => "rt_hw_set(w, select(0u, 1u, v));".to_string(),
            Ty::Vec(n, s) => {
                let f = self.store(&Ty::Scalar(*s));
                (0..*n).map(|i| format!("{f}(w + {i}u, v[{i}]);")).collect::<Vec<_>>().join("\n    ")
            }
            Ty::Mat(n) => {
                let f = self.store(&Ty::vec(*n));
                (0..*n).map(|i| format!("{f}(w + {}u, v[{i}]);", i * n)).collect::<Vec<_>>().join("\n    ")
            }
            Ty::Array(e, n) => {
                let f = self.store(e);
                format!("for (var i = 0u; i < {n}u; i++) {{\n        {f}(w + i * {}u, v[i]);\n    }}", e.words())
            }
            _ => {
                let mut offset = 0;
                let mut parts = Vec::new();
                for (fname, fty) in ty.fields() {
                    let f = self.store(&fty);
                    parts.push(format!("{f}(w + {offset}u, v.{});", super::resolve::wgsl_field(&fname)));
                    offset += fty.words();
                }
                parts.join("\n    ")
            }
        };
        self.functions.insert(name.clone(), format!("fn {name}(w: u32, v: {t}) {{\n    {body}\n}}\n"));
        name
    }

    /// Bounds-checked element load: `rt_bufload_<T>` (1D, `u32` index) or
    /// `rt_bufload2_<T>` (2D, `vec2<u32>` index). Out of bounds raises the
    /// buffer-index exception (in `rt_buf_check`) and yields the zero value.
    pub fn buffer_load(&mut self, dims: u8, ty: &Ty) -> String {
        let name = format!("rt_bufload{}_{}", dims_suffix(dims), ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let load = self.load(ty);
        let t = ty.wgsl();
        let (idx_ty, check, offset) = index_parts(dims);
        let words = ty.words();
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(b: RtBuffer, i: {idx_ty}) -> {t} {{\n    if {check} {{\n        return {load}(b.offset + {offset} * {words}u);\n    }}\n    return {t}();\n}}\n"
            ),
        );
        name
    }

    /// Bounds-checked element store (`rt_bufstore_<T>` / `rt_bufstore2_<T>`).
    pub fn buffer_store(&mut self, dims: u8, ty: &Ty) -> String {
        let name = format!("rt_bufstore{}_{}", dims_suffix(dims), ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let store = self.store(ty);
        let t = ty.wgsl();
        let (idx_ty, check, offset) = index_parts(dims);
        let words = ty.words();
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(b: RtBuffer, i: {idx_ty}, v: {t}) {{\n    if {check} {{\n        {store}(b.offset + {offset} * {words}u, v);\n    }}\n}}\n"
            ),
        );
        name
    }
}

/// The accessors of a bindless buffer id (`BindlessBuffer<T>`,
/// `RwBindlessBuffer<T>`): the id checked against the launch's buffer table
/// (`rt_bufid_ok`: it names a buffer of `T`'s tag, one programs may write
/// for a writable id; raising the invalid-id exception if not), then the
/// bounds-checked element access of the buffer it names. Through an
/// invalid id a load yields zero, a store writes nothing, `len` is 0.
impl Accessors {
    /// `rt_idload[w]_<T>(id, i) -> T`.
    pub fn bindless_load(&mut self, writable: bool, ty: &Ty) -> String {
        let name = format!("rt_idload{}_{}", if writable { "w" } else { "" }, ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let load = self.buffer_load(1, ty);
        let t = ty.wgsl();
        let ok = id_check(writable, ty);
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(id: u32, i: u32) -> {t} {{\n    if {ok} {{\n        return {load}(rt_bufid(id), i);\n    }}\n    return {t}();\n}}\n"
            ),
        );
        name
    }

    /// `rt_idstore_<T>(id, i, v)`, through a writable id.
    pub fn bindless_store(&mut self, ty: &Ty) -> String {
        let name = format!("rt_idstore_{}", ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let store = self.buffer_store(1, ty);
        let t = ty.wgsl();
        let ok = id_check(true, ty);
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(id: u32, i: u32, v: {t}) {{\n    if {ok} {{\n        {store}(rt_bufid(id), i, v);\n    }}\n}}\n"
            ),
        );
        name
    }

    /// `rt_idlen[w]_<T>(id) -> u32`.
    pub fn bindless_len(&mut self, writable: bool, ty: &Ty) -> String {
        let name = format!("rt_idlen{}_{}", if writable { "w" } else { "" }, ty.mangle());
        if self.functions.contains_key(&name) {
            return name;
        }
        let ok = id_check(writable, ty);
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(id: u32) -> u32 {{\n    if {ok} {{\n        return rt_bufid(id).len;\n    }}\n    return 0u;\n}}\n"
            ),
        );
        name
    }
}

/// `rt_bufid_ok(id, <tag of T>, writable)`: the tag of the element type's
/// layout name, as the runtime writes it for each buffer.
fn id_check(writable: bool, ty: &Ty) -> String {
    let tag = rt_abi::records::layout_tag(&ty.layout_name());
    format!("rt_bufid_ok(id, {tag}u, {writable})")
}

/// An atomic update of a 32-bit buffer element, as `RwBuffer::atomic_*`
/// names it. Each returns the element's old value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AtomicOp {
    Add,
    Sub,
    Min,
    Max,
    And,
    Or,
    Xor,
    Exchange,
    CompareExchange,
}

/// Each op with the name its method and accessor carry (`atomic_<name>`).
const ATOMIC_OPS: [(AtomicOp, &str); 9] = [
    (AtomicOp::Add, "add"),
    (AtomicOp::Sub, "sub"),
    (AtomicOp::Min, "min"),
    (AtomicOp::Max, "max"),
    (AtomicOp::And, "and"),
    (AtomicOp::Or, "or"),
    (AtomicOp::Xor, "xor"),
    (AtomicOp::Exchange, "exchange"),
    (AtomicOp::CompareExchange, "compare_exchange"),
];

impl AtomicOp {
    /// The op of method `name` (`atomic_add`, ...).
    pub fn of_method(name: &str) -> Option<AtomicOp> {
        let name = name.strip_prefix("atomic_")?;
        ATOMIC_OPS.iter().find(|(_, n)| *n == name).map(|(op, _)| *op)
    }

    fn name(self) -> &'static str {
        ATOMIC_OPS.iter().find(|(op, _)| *op == self).map(|(_, n)| *n).expect("every op is in ATOMIC_OPS")
    }

    /// Whether the op takes only integers (bitwise ops and `sub`).
    pub fn integer_only(self) -> bool {
        matches!(self, AtomicOp::Sub | AtomicOp::And | AtomicOp::Or | AtomicOp::Xor)
    }
}

impl Accessors {
    /// Whether the module updates buffer elements atomically (and so needs
    /// the atomic heap).
    pub fn atomic(&self) -> bool {
        rt_abi::wgsl::needs_atomic_heap(self.functions.keys().map(String::as_str))
    }

    /// `rt_atomic[2]_<op>_<T>(b, i, v[, new]) -> T`: a bounds-checked atomic
    /// update of element `i` of a buffer of `u32`, `i32` or `f32` (`scalar`),
    /// returning the old value (zero out of bounds, after the exception).
    /// WGSL's atomics work on the heap's `u32` words: `i32` add, sub and the
    /// bitwise ops are the same bits; `i32` min and max and every `f32`
    /// arithmetic op are a compare-exchange loop on the computed word;
    /// `compare_exchange` compares bits, retrying a weak failure until the
    /// word differs or the exchange happens (a strong compare-exchange).
    pub fn buffer_atomic(&mut self, dims: u8, op: AtomicOp, scalar: Scalar) -> String {
        let t = Ty::Scalar(scalar).wgsl();
        let name = format!("{}{}_{}_{t}", rt_abi::wgsl::ATOMIC_PREFIX, dims_suffix(dims), op.name());
        if self.functions.contains_key(&name) {
            return name;
        }
        let (idx_ty, check, offset) = index_parts(dims);
        let (to_word, from_word) = match scalar {
            Scalar::U32 => ("v", "old".to_string()),
            _ => ("bitcast<u32>(v)", format!("bitcast<{t}>(old)")),
        };
        let native = |f: &str| {
            format!(
                "let old = {f}(p, {to_word});
        return {from_word};"
            )
        };
        let cas = |new: &str| {
            format!(
                "var old = atomicLoad(p);
        loop {{
            let r = atomicCompareExchangeWeak(p, old, {new});
            if r.exchanged {{
                return {from_word};
            }}
            old = r.old_value;
        }}"
            )
        };
        let update = match (op, scalar) {
            (AtomicOp::Add, Scalar::F32) => cas(&format!("bitcast<u32>({from_word} + v)")),
            (AtomicOp::Min | AtomicOp::Max, Scalar::F32 | Scalar::I32) => {
                let cmp = if op == AtomicOp::Min { "<" } else { ">" };
                cas(&format!("bitcast<u32>(select({from_word}, v, v {cmp} {from_word}))"))
            }
            (AtomicOp::Add, _) => native("atomicAdd"),
            (AtomicOp::Sub, _) => native("atomicSub"),
            (AtomicOp::Min, _) => native("atomicMin"),
            (AtomicOp::Max, _) => native("atomicMax"),
            (AtomicOp::And, _) => native("atomicAnd"),
            (AtomicOp::Or, _) => native("atomicOr"),
            (AtomicOp::Xor, _) => native("atomicXor"),
            (AtomicOp::Exchange, _) => native("atomicExchange"),
            (AtomicOp::CompareExchange, _) => {
                let cur_word = if scalar == Scalar::U32 { "current" } else { "bitcast<u32>(current)" };
                format!(
                    "loop {{
            let r = atomicCompareExchangeWeak(p, {cur_word}, {to_word});
            if r.exchanged || r.old_value != {cur_word} {{
                let old = r.old_value;
                return {from_word};
            }}
        }}"
                )
            }
        };
        let params = if op == AtomicOp::CompareExchange { format!("current: {t}, v: {t}") } else { format!("v: {t}") };
        self.functions.insert(
            name.clone(),
            format!(
                "fn {name}(b: RtBuffer, i: {idx_ty}, {params}) -> {t} {{
    if {check} {{
        let p = &rt_heap[b.offset + {offset}];
        {update}
    }}
    return {t}();
}}
"
            ),
        );
        name
    }
}

fn index_parts(dims: u8) -> (&'static str, &'static str, &'static str) {
    match dims {
        2 => ("vec2<u32>", "rt_buf_check2(b, i)", "(i.y * b.width + i.x)"),
        // Row-major slices: x fastest, then y, then z (`rt_buf_check3`
        // keeps the product in range).
        3 => ("vec3<u32>", "rt_buf_check3(b, i)", "((i.z * b.height + i.y) * b.width + i.x)"),
        _ => ("u32", "rt_buf_check(b, i)", "i"),
    }
}

/// What an accessor's name says of its buffer's dimensions.
fn dims_suffix(dims: u8) -> &'static str {
    match dims {
        2 => "2",
        3 => "3",
        _ => "",
    }
}
