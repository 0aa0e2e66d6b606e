//! Calls through a callable id, `shade.call(n, l)`: the arguments checked
//! against the id's signature and passed to the signature's dispatch
//! function, whose stub the module's prelude declares and whose `switch`
//! the linker writes.

use super::*;
use crate::types::CallSig;
use std::rc::Rc;

impl FnLowerer<'_> {
    pub(super) fn callable_call(
        &mut self,
        recv: Val,
        sig: &Rc<CallSig>,
        name: &str,
        args: &[&Expr],
        name_span: Span,
        span: Span,
    ) -> Result<Val> {
        let ty = Ty::Callable(sig.clone());
        if name != "call" {
            return Err(Error::new(name_span, format!("no method `{name}` on `{ty}` in ray programs (it has `call`)")));
        }
        if self.kind() == Some(Kind::BoundingBox) {
            return Err(Error::new(
                name_span,
                "a bounding_box program cannot call callable programs: it runs at build time, outside any launch",
            ));
        }
        if args.len() != sig.params.len() {
            let n = sig.params.len();
            return Err(Error::new(
                name_span,
                format!("`{ty}` takes {n} argument{}, found {}", if n == 1 { "" } else { "s" }, args.len()),
            ));
        }
        let mut vals = vec![recv];
        for (a, p) in args.iter().zip(&sig.params) {
            let at = self.here();
            let v = self.expr(a, Some(p))?;
            let v = self.deref(v);
            let v = self.coerce(v, p, a.span())?;
            self.spill(at, &mut vals.iter_mut().collect::<Vec<_>>());
            vals.push(v);
        }
        let dispatch = sig.dispatch();
        self.m.call_types.borrow_mut().insert(dispatch.clone(), sig.clone());
        let code = format!("{dispatch}({})", codes(&vals).join(", "));
        if matches!(sig.ret, Ty::Unit) {
            let line = self.mark(span, &format!("{code};"));
            self.emit(line);
            return Ok(Val::new("", Ty::Unit));
        }
        // A callable may write buffers and raise: its result is taken here,
        // in evaluation order.
        let t = self.tmp();
        let line = self.mark(span, &format!("let {t} = {code};"));
        self.emit(line);
        Ok(Val::new(t, sig.ret.clone()))
    }
}
