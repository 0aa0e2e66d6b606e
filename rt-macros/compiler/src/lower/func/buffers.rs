//! Buffers and samplers: `Buffer`/`RwBuffer` (1D, 2D and 3D) indexing and
//! methods through the heap accessors, and `Sampler2d`'s methods.

use super::*;
use crate::lower::accessors::AtomicOp;

impl FnLowerer<'_> {
    pub(super) fn buffer_index(&mut self, kind: BufferKind, e: &Expr) -> Result<Val> {
        let want = kind.index_ty();
        let v = self.expr(e, Some(&want))?;
        let v = self.deref(v);
        self.coerce(v, &want, e.span())
    }

    #[allow(clippy::too_many_arguments)]
    pub(super) fn buffer_method(
        &mut self,
        recv: Val,
        kind: BufferKind,
        elem: &Ty,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let want_args = |n: usize| -> Result<()> {
            if args.len() != n {
                Err(Error::new(
                    name_span,
                    format!("`{}::{name}` takes {n} argument(s), found {}", kind.rust_name(), args.len()),
                ))
            } else {
                Ok(())
            }
        };
        if let Some(op) = AtomicOp::of_method(name) {
            return self.buffer_atomic(recv, kind, elem, op, name, args, name_span, span);
        }
        match (name, kind.dims) {
            ("len", 1) => {
                want_args(0)?;
                Ok(Val::new(format!("{}.len", recv.code), U32).with_effects(recv.effects).with_reads(recv.reads))
            }
            ("is_empty", 1) => {
                want_args(0)?;
                Ok(Val::new(format!("({}.len == 0u)", recv.code), BOOL)
                    .with_effects(recv.effects)
                    .with_reads(recv.reads))
            }
            ("size", 2) => {
                want_args(0)?;
                let size = format!("vec2<u32>({0}.width, {0}.height)", recv.code);
                Ok(Val::new(size, Ty::Vec(2, Scalar::U32)).with_effects(recv.effects).with_reads(recv.reads))
            }
            ("size", 3) => {
                want_args(0)?;
                let size = format!("rt_buf_size3({})", recv.code);
                Ok(Val::new(size, Ty::Vec(3, Scalar::U32)).with_effects(recv.effects).with_reads(recv.reads))
            }
            ("load", _) => {
                want_args(1)?;
                let idx = self.buffer_index(kind, args[0])?;
                let f = self.m.accessors.borrow_mut().buffer_load(kind.dims, elem);
                let effects = recv.effects || idx.effects;
                Ok(Val::new(format!("{f}({}, {})", recv.code, idx.code), elem.clone())
                    .with_effects(effects)
                    .with_reads(true))
            }
            ("store", _) => {
                want_args(2)?;
                if !kind.writable {
                    return Err(Error::new(
                        name_span,
                        format!(
                            "cannot store into a read-only `{}`: declare the variable as `{}`",
                            kind.rust_name(),
                            BufferKind { writable: true, ..kind }.rust_name()
                        ),
                    ));
                }
                let mut idx = self.buffer_index(kind, args[0])?;
                let at = self.here();
                let v = self.expr(args[1], Some(elem))?;
                let v = self.deref(v);
                let v = self.coerce(v, elem, args[1].span())?;
                self.spill(at, &mut [&mut idx]);
                let f = self.m.accessors.borrow_mut().buffer_store(kind.dims, elem);
                let line = self.mark(span, &format!("{f}({}, {}, {});", recv.code, idx.code, v.code));
                self.emit(line);
                Ok(Val::new("", Ty::Unit))
            }
            _ => Err(Error::new(
                name_span,
                format!(
                    "no method `{name}` on `{}<{elem}>` (it has load, store, {}, and the atomic_* updates on `RwBuffer`s of `u32`, `i32` and `f32`)",
                    kind.rust_name(),
                    if kind.dims == 1 { "len, is_empty" } else { "size" }
                ),
            )),
        }
    }

    /// `buffer.atomic_<op>(index, value)` (`atomic_compare_exchange(index,
    /// current, new)`): the old value, through a `let` so the update happens
    /// once, in Rust's order.
    #[allow(clippy::too_many_arguments)]
    fn buffer_atomic(
        &mut self,
        recv: Val,
        kind: BufferKind,
        elem: &Ty,
        op: AtomicOp,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let ty_name = format!("{}<{elem}>", kind.rust_name());
        if kind.dims == 3 {
            return Err(Error::new(
                name_span,
                format!("`{name}` on a 3D buffer is not supported yet: atomics are on `RwBuffer`s and `RwBuffer2d`s"),
            ));
        }
        if !kind.writable {
            return Err(Error::new(
                name_span,
                format!(
                    "cannot update a read-only `{ty_name}` atomically: declare the variable as `{}`",
                    BufferKind { writable: true, ..kind }.rust_name()
                ),
            ));
        }
        let scalar = match elem {
            Ty::Scalar(s @ (Scalar::U32 | Scalar::I32)) => *s,
            Ty::Scalar(Scalar::F32) if !op.integer_only() => Scalar::F32,
            Ty::Scalar(Scalar::F32) => {
                return Err(Error::new(
                    name_span,
                    format!("`{name}` needs integer elements (`u32` or `i32`), found `{ty_name}`"),
                ));
            }
            _ => {
                return Err(Error::new(
                    name_span,
                    format!(
                        "`{name}` updates one 32-bit element: it needs a buffer of `u32`, `i32` or `f32`, found `{ty_name}`"
                    ),
                ));
            }
        };
        let n = if op == AtomicOp::CompareExchange { 3 } else { 2 };
        if args.len() != n {
            return Err(Error::new(
                name_span,
                format!("`{}::{name}` takes {n} argument(s), found {}", kind.rust_name(), args.len()),
            ));
        }
        let mut idx = self.buffer_index(kind, args[0])?;
        let mut vals: Vec<Val> = Vec::new();
        for a in &args[1..] {
            let at = self.here();
            let v = self.expr(a, Some(elem))?;
            let v = self.deref(v);
            let v = self.coerce(v, elem, a.span())?;
            let mut earlier: Vec<&mut Val> = vec![&mut idx];
            earlier.extend(vals.iter_mut());
            self.spill(at, &mut earlier);
            vals.push(v);
        }
        let f = self.m.accessors.borrow_mut().buffer_atomic(kind.dims, op, scalar);
        let t = self.tmp();
        let codes: Vec<String> = vals.iter().map(|v| v.code.clone()).collect();
        let line = self.mark(span, &format!("let {t} = {f}({}, {}, {});", recv.code, idx.code, codes.join(", ")));
        self.emit(line);
        Ok(Val::new(t, elem.clone()))
    }

    /// `Sampler3d`'s methods: `sample(uvw)`, `sample_lod(uvw, lod)`,
    /// `sample_grad(uvw, dx, dy)`, `fetch(texel)`, `size()`, `levels()`.
    pub(super) fn sampler3d_method(&mut self, recv: Val, name: &str, args: &[&Expr], name_span: Span) -> Result<Val> {
        let (f, params): (&str, &[(&str, Ty)]) = match name {
            "sample" => ("rt_tex3_sample", &[("uvw", Ty::vec(3))]),
            "sample_lod" => ("rt_tex3_sample_lod", &[("uvw", Ty::vec(3)), ("lod", Ty::Scalar(Scalar::F32))]),
            "sample_grad" => ("rt_tex3_sample_grad", &[("uvw", Ty::vec(3)), ("dx", Ty::vec(3)), ("dy", Ty::vec(3))]),
            "fetch" => ("rt_tex3_fetch", &[("texel", Ty::Vec(3, Scalar::U32))]),
            "size" | "levels" => {
                if !args.is_empty() {
                    return Err(Error::new(name_span, format!("`Sampler3d::{name}` takes no arguments")));
                }
                let (code, ty) = if name == "size" {
                    (format!("vec3<u32>({0}.width, {0}.height, {0}.depth)", recv.code), Ty::Vec(3, Scalar::U32))
                } else {
                    // prelude.wgsl's RtSampler3d.mode: the level count's byte.
                    (format!("max({}.mode >> 24u, 1u)", recv.code), Ty::Scalar(Scalar::U32))
                };
                return Ok(Val::new(code, ty).with_effects(recv.effects).with_reads(recv.reads));
            }
            _ => {
                return Err(Error::new(
                    name_span,
                    format!(
                        "no method `{name}` on `Sampler3d` (it has sample, sample_lod, sample_grad, fetch, size, levels)"
                    ),
                ));
            }
        };
        self.texture_call(recv, "Sampler3d", f, name, params, args, name_span)
    }

    /// `SamplerCube`'s methods: `sample_dir(dir)`, `sample_dir_lod(dir,
    /// lod)`, `size()`, `levels()`.
    pub(super) fn sampler_cube_method(
        &mut self,
        recv: Val,
        name: &str,
        args: &[&Expr],
        name_span: Span,
    ) -> Result<Val> {
        let (f, params): (&str, &[(&str, Ty)]) = match name {
            "sample_dir" => ("rt_texcube_sample", &[("dir", Ty::vec(3))]),
            "sample_dir_lod" => ("rt_texcube_sample_lod", &[("dir", Ty::vec(3)), ("lod", Ty::Scalar(Scalar::F32))]),
            "size" | "levels" => {
                if !args.is_empty() {
                    return Err(Error::new(name_span, format!("`SamplerCube::{name}` takes no arguments")));
                }
                let code = if name == "size" {
                    format!("{}.width", recv.code)
                } else {
                    // prelude.wgsl's RtSampler.mode: the level count's byte.
                    format!("max({}.mode >> 24u, 1u)", recv.code)
                };
                return Ok(Val::new(code, Ty::Scalar(Scalar::U32)).with_effects(recv.effects).with_reads(recv.reads));
            }
            _ => {
                return Err(Error::new(
                    name_span,
                    format!("no method `{name}` on `SamplerCube` (it has sample_dir, sample_dir_lod, size, levels)"),
                ));
            }
        };
        self.texture_call(recv, "SamplerCube", f, name, params, args, name_span)
    }

    /// `f(recv, args..)` for a sampler method of `params`, the arguments
    /// checked against them and evaluated in order.
    #[allow(clippy::too_many_arguments)]
    fn texture_call(
        &mut self,
        recv: Val,
        owner: &str,
        f: &str,
        name: &str,
        params: &[(&str, Ty)],
        args: &[&Expr],
        name_span: Span,
    ) -> Result<Val> {
        if args.len() != params.len() {
            let list: Vec<String> = params.iter().map(|(p, ty)| format!("`{p}: {ty}`")).collect();
            return Err(Error::new(
                name_span,
                format!(
                    "`{owner}::{name}` takes {} argument{} ({}), found {}",
                    params.len(),
                    if params.len() == 1 { "" } else { "s" },
                    list.join(", "),
                    args.len()
                ),
            ));
        }
        let mut vals: Vec<Val> = Vec::with_capacity(args.len());
        for (a, (_, ty)) in args.iter().zip(params) {
            let at = self.here();
            let v = self.expr(a, Some(ty))?;
            let v = self.deref(v);
            let v = self.coerce(v, ty, a.span())?;
            let mut earlier: Vec<&mut Val> = vals.iter_mut().collect();
            self.spill(at, &mut earlier);
            vals.push(v);
        }
        let effects = recv.effects || vals.iter().any(|v| v.effects);
        let reads = recv.reads || vals.iter().any(|v| v.reads);
        let codes: Vec<String> = vals.iter().map(|v| v.code.clone()).collect();
        Ok(Val::new(format!("{f}({}, {})", recv.code, codes.join(", ")), Ty::vec(4))
            .with_effects(effects)
            .with_reads(reads))
    }

    pub(super) fn sampler_method(
        &mut self,
        recv: Val,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        _span: Span,
    ) -> Result<Val> {
        let (f, arg_tys): (&str, &[(&str, Ty)]) = match name {
            "sample" => ("rt_tex_sample", &[("uv", Ty::vec(2))]),
            "sample_lod" => ("rt_tex_sample_lod", &[("uv", Ty::vec(2)), ("lod", Ty::Scalar(Scalar::F32))]),
            "sample_grad" => ("rt_tex_sample_grad", &[("uv", Ty::vec(2)), ("dx", Ty::vec(2)), ("dy", Ty::vec(2))]),
            "fetch" => ("rt_tex_fetch", &[("texel", Ty::Vec(2, Scalar::U32))]),
            "size" | "levels" => {
                if !args.is_empty() {
                    return Err(Error::new(name_span, format!("`Sampler2d::{name}` takes no arguments")));
                }
                let (code, ty) = if name == "size" {
                    (format!("vec2<u32>({0}.width, {0}.height)", recv.code), Ty::Vec(2, Scalar::U32))
                } else {
                    // prelude.wgsl's RtSampler.mode: the level count's byte.
                    (format!("max({}.mode >> 24u, 1u)", recv.code), Ty::Scalar(Scalar::U32))
                };
                return Ok(Val::new(code, ty).with_effects(recv.effects).with_reads(recv.reads));
            }
            _ => {
                return Err(Error::new(
                    name_span,
                    format!(
                        "no method `{name}` on `Sampler2d` (it has sample, sample_lod, sample_grad, fetch, size, levels)"
                    ),
                ));
            }
        };
        self.texture_call(recv, "Sampler2d", f, name, arg_tys, args, name_span)
    }
}
