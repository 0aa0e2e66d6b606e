//! Generated WGSL accessors: reading and writing typed values in the
//! runtime's heap (`rt_heap: array<u32>`, packed words, see `types`), and
//! bounds-checked buffer element access on top of them.

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
            Ty::Scalar(Scalar::F32) => "return bitcast<f32>(rt_heap[w]);".to_string(),
            Ty::Scalar(Scalar::I32) => "return bitcast<i32>(rt_heap[w]);".to_string(),
            Ty::Scalar(Scalar::U32) | Ty::Scalar(Scalar::Usize) | Ty::Object | Ty::TransformKind | Ty::Enum(_) => {
                "return rt_heap[w];".to_string()
            }
            Ty::Scalar(Scalar::Bool) => "return rt_heap[w] != 0u;".to_string(),
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
            Ty::Scalar(Scalar::F32) | Ty::Scalar(Scalar::I32) => "rt_heap[w] = bitcast<u32>(v);".to_string(),
            Ty::Scalar(Scalar::U32) | Ty::Scalar(Scalar::Usize) | Ty::Object | Ty::TransformKind | Ty::Enum(_) => {
                "rt_heap[w] = v;".to_string()
            }
            Ty::Scalar(Scalar::Bool) => "rt_heap[w] = select(0u, 1u, v);".to_string(),
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
                    parts.push(format!("{f}(w + {offset}u, v.{fname});"));
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
        let name = format!("rt_bufload{}_{}", if dims == 2 { "2" } else { "" }, ty.mangle());
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
        let name = format!("rt_bufstore{}_{}", if dims == 2 { "2" } else { "" }, ty.mangle());
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

fn index_parts(dims: u8) -> (&'static str, &'static str, &'static str) {
    if dims == 2 {
        ("vec2<u32>", "rt_buf_check2(b, i)", "(i.y * b.width + i.x)")
    } else {
        ("u32", "rt_buf_check(b, i)", "i")
    }
}
