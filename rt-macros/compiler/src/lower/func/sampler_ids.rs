//! Bindless sampler ids, `BindlessSampler<S>`: sampling through an id
//! (`tex.sample(uv)`, `tex.sample_lod(uv, lod)`, `tex.size()`, ...) lowered
//! as the sampler's own methods on the record the prelude's `rt_texid`
//! (`rt_texid3`) reads from the launch's sampler table: the id checked
//! against the table and the shape `S`, an empty sampler (every read zero)
//! after the invalid-texture-id exception if it fails. Ids made in a
//! program (`BindlessSampler::NONE`, `from_id`, `default`) are
//! `bindless.rs`'s, with the buffer ids'.

use super::*;
use rt_abi::records::SamplerTable;

impl FnLowerer<'_> {
    /// `tex.name(args)` on a bindless sampler id of shape `shape`.
    pub(super) fn sampler_id_method(
        &mut self,
        recv: Val,
        shape: &Ty,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let ty = Ty::SamplerId(Box::new(shape.clone()));
        let methods: &[&str] = match shape {
            Ty::Sampler => &["sample", "sample_lod", "sample_grad", "fetch", "size", "levels"],
            Ty::Sampler3d => &["sample", "sample_lod", "sample_grad", "fetch", "size", "levels"],
            _ => &["sample_dir", "sample_dir_lod", "size", "levels"],
        };
        if name == "id" {
            if !args.is_empty() {
                return Err(Error::new(name_span, format!("`{ty}::id` takes no arguments")));
            }
            return Ok(Val::new(recv.code.clone(), U32).with_effects(recv.effects).with_reads(recv.reads));
        }
        if !methods.contains(&name) {
            return Err(Error::new(
                name_span,
                format!("no method `{name}` on `{ty}` in ray programs (it has {}, id)", methods.join(", ")),
            ));
        }
        if self.kind() == Some(Kind::BoundingBox) {
            return Err(Error::new(
                name_span,
                "a bounding_box program cannot sample textures through bindless ids: it runs at build time, \
                 outside any launch; take the sampler as a `Sampler2d` variable",
            ));
        }
        // The sampler record once, whatever the method reads of it.
        let record = match shape {
            Ty::Sampler3d => format!("rt_texid3({})", recv.code),
            Ty::Sampler => format!("rt_texid({}, {}u)", recv.code, SamplerTable::SHAPE_2D),
            _ => format!("rt_texid({}, {}u)", recv.code, SamplerTable::SHAPE_CUBE),
        };
        let t = self.tmp();
        let line = self.mark(span, &format!("let {t} = {record};"));
        self.emit(line);
        let sampler = Val::new(t, shape.clone());
        match shape {
            Ty::Sampler => self.sampler_method(sampler, name, args, name_span, span),
            Ty::Sampler3d => self.sampler3d_method(sampler, name, args, name_span),
            _ => self.sampler_cube_method(sampler, name, args, name_span),
        }
    }
}
