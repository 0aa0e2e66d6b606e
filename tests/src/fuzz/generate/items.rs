//! Program-level items: the entry point's body, the final dump of the
//! live locals, `#[rt_function]` helpers.

use super::*;

impl Gen {
    pub(super) fn generate(&mut self, id: usize) {
        let _ = id;
        // The program's vector types.
        let all: Vec<Ty> =
            [Scalar::F32, Scalar::I32, Scalar::U32].iter().flat_map(|s| (2..=4).map(move |n| Ty::V(n, *s))).collect();
        for _ in 0..self.r.range(2, 4) {
            let t = self.r.pick(&all);
            if !self.vecs.contains(&t) {
                self.vecs.push(t);
            }
        }
        // Structs (a later one may contain an earlier one).
        for i in 0..self.r.range(0, 2) as usize {
            let mut fields = Vec::new();
            for k in 0..self.r.range(2, 4) {
                let t = match self.r.weighted(&[4, 3, if i > 0 { 1 } else { 0 }]) {
                    0 => Ty::S(self.scalar()),
                    1 => self.r.pick(&self.vecs),
                    _ => Ty::Struct(i - 1),
                };
                fields.push((format!("f{k}"), t));
            }
            self.p
                .structs
                .push(StructDef { name: format!("Fz{}S{i}", self.p.name.trim_start_matches("fuzz")), fields });
        }
        // Helpers, each may call the earlier ones.
        let n_helpers = self.r.range(0, 3) as usize;
        let mut_helper =
            if n_helpers > 0 && self.r.chance(70) { Some(self.r.below(n_helpers as u64) as usize) } else { None };
        for i in 0..n_helpers {
            self.callable = i;
            let h = self.helper(i, mut_helper == Some(i));
            self.p.helpers.push(h);
        }
        self.callable = n_helpers;
        // Inputs and outputs.
        for k in 0..self.r.range(2, 5) {
            let t = self.var_ty();
            self.p.inputs.push((format!("in{k}"), t));
        }
        self.p.outputs.push(("out_u".into(), U32));
        self.p.outputs.push(("out_f".into(), F32));
        let mut v_types = self.vecs.clone();
        v_types.extend((0..self.p.structs.len()).map(Ty::Struct));
        v_types.push(I32);
        let vt = self.r.pick(&v_types);
        self.p.outputs.push(("out_v".into(), vt));
        // The body.
        self.scopes = vec![Vec::new()];
        for (n, t) in self.p.inputs.clone() {
            self.bind(&n, t, false, Kind::Input);
        }
        self.bind("slot", U32, false, Kind::ReadOnly);
        self.stmts_left = self.r.range(8, 28) as u32;
        let mut stmts = Vec::new();
        while self.stmts_left > 0 {
            self.stmts_left -= 1;
            self.stmt(&mut stmts);
        }
        // Every local still in scope, to the outputs.
        let mut counts = [SCRATCH; 3];
        let locals: Vec<Var> = self.scopes[0].iter().filter(|v| v.kind == Kind::Local).cloned().collect();
        for v in locals {
            self.dump(Expr::Var(v.name.clone()), &v.ty, &mut counts, &mut stmts);
        }
        let slots = counts.iter().copied().max().unwrap();
        self.p.slots = slots;
        stmts.insert(
            0,
            Stmt::Let {
                name: "slot".into(),
                mutable: false,
                ty: U32,
                annotate: false,
                init: bin(BinOp::Mul, Expr::LaunchX, lit(LitV::U32(slots), false)),
            },
        );
        self.p.body = Block { stmts, tail: None };
    }

    /// Stores `e` (of type `t`) into the next free output elements.
    pub(super) fn dump(&mut self, e: Expr, t: &Ty, counts: &mut [u32; 3], out: &mut Vec<Stmt>) {
        const MAX: u32 = SCRATCH + 40;
        let store = |g: &mut Gen, buf: usize, value: Expr, counts: &mut [u32; 3], out: &mut Vec<Stmt>| {
            if counts[buf] >= MAX {
                return;
            }
            let index = bin(BinOp::Add, Expr::Var("slot".into()), lit(LitV::U32(counts[buf]), false));
            let form = if g.r.chance(50) { StoreForm::Method } else { StoreForm::Index };
            out.push(Stmt::Store { buf, index, value, form });
            counts[buf] += 1;
        };
        if *t == self.p.outputs[2].1 && self.r.chance(70) {
            return store(self, 2, e, counts, out);
        }
        match t {
            Ty::S(Scalar::F32) => store(self, 1, e, counts, out),
            Ty::S(Scalar::U32) => store(self, 0, e, counts, out),
            Ty::S(_) => store(self, 0, Expr::Cast(b(e), Scalar::U32), counts, out),
            Ty::V(n, s) => {
                for i in 0..*n as usize {
                    self.dump(Expr::Field(b(e.clone()), COMP[i].into(), i), &Ty::S(*s), counts, out);
                }
            }
            Ty::Struct(k) => {
                for (i, (f, ft)) in self.p.structs[*k].fields.clone().iter().enumerate() {
                    self.dump(Expr::Field(b(e.clone()), f.clone(), i), ft, counts, out);
                }
            }
            Ty::Arr(et, n) => {
                for i in 0..*n {
                    self.dump(Expr::Index(b(e.clone()), b(lit(LitV::U32(i), false))), et, counts, out);
                }
            }
        }
    }

    pub(super) fn helper(&mut self, i: usize, takes_mut: bool) -> Helper {
        let name = format!("{}_h{i}", self.p.name);
        self.scopes = vec![Vec::new()];
        let mut params = Vec::new();
        // The last struct may get methods (see `method_form`): give some
        // helpers it as their first parameter.
        let last_struct = self.p.structs.len().checked_sub(1).map(Ty::Struct);
        let mut_ty = match &last_struct {
            Some(t) if self.r.chance(60) => t.clone(),
            _ => U32,
        };
        if takes_mut {
            let n = format!("state{i}");
            self.bind(&n, mut_ty.clone(), true, Kind::RefParam);
            params.push(Param::MutRef(n, mut_ty.clone()));
        }
        // An operator's shape (see `method_form`): the struct and a right
        // operand, the struct back.
        let operator = match &last_struct {
            Some(t) if !takes_mut && self.r.chance(60) => self.free_operator().map(|op| (op, t.clone())),
            _ => None,
        };
        if let Some((op, t)) = &operator {
            let rhs = if op.scalar_rhs() { F32 } else { t.clone() };
            for (k, t) in [t.clone(), rhs].into_iter().enumerate() {
                let n = format!("p{i}_{k}");
                self.bind(&n, t.clone(), false, Kind::ReadOnly);
                params.push(Param::Val(n, t));
            }
        } else {
            for k in 0..self.r.range(if takes_mut { 0 } else { 1 }, 3) {
                let t = match &last_struct {
                    Some(t) if k == 0 && !takes_mut && self.r.chance(70) => t.clone(),
                    _ => self.var_ty(),
                };
                let n = format!("p{i}_{k}");
                self.bind(&n, t.clone(), false, Kind::ReadOnly);
                params.push(Param::Val(n, t));
            }
        }
        let ret = match &operator {
            Some((_, t)) => t.clone(),
            None => self.var_ty(),
        };
        self.ret = Some(ret.clone());
        self.stmts_left = self.r.range(1, 8) as u32;
        let mut stmts = Vec::new();
        while self.stmts_left > 0 {
            self.stmts_left -= 1;
            self.stmt(&mut stmts);
        }
        if takes_mut {
            // At least one write through the reference.
            let v = self.expr(&mut_ty, DEPTH, true);
            let op = if mut_ty == U32 {
                self.r.pick(&[None, Some(BinOp::Add), Some(BinOp::BitXor), Some(BinOp::Mul)])
            } else {
                None
            };
            stmts.push(Stmt::Assign(Place::Deref(format!("state{i}")), op, v));
        }
        let tail = self.expr(&ret, DEPTH, true);
        self.ret = None;
        let body = Block { stmts, tail: Some(tail) };
        let method = self.method_form(&params, &body, operator.map(|(op, _)| op));
        Helper { name, params, ret: Some(ret), body, method }
    }

    /// An operator trait the last struct does not implement yet, at random.
    fn free_operator(&mut self) -> Option<OpTrait> {
        let used: Vec<OpTrait> = self
            .p
            .helpers
            .iter()
            .filter_map(|h| match h.method?.form {
                MethodForm::Operator(op) => Some(op),
                _ => None,
            })
            .collect();
        let free: Vec<OpTrait> = OpTrait::ALL.into_iter().filter(|op| !used.contains(op)).collect();
        (!free.is_empty()).then(|| self.r.pick(&free))
    }

    /// Whether a helper is printed as a method (and how), with its first
    /// parameter as the receiver: only of the last struct, which no other
    /// struct contains, and only if the body calls no helper but the
    /// struct's own methods. So the method's impl never names an item
    /// whose own link in the macro chain names the struct back, a cycle
    /// the chain cannot close (see `rt_compiler::methods`).
    /// A helper of an operator's shape (`operator`) becomes that operator's
    /// impl; another method goes to the inherent block or to the trait.
    fn method_form(&mut self, params: &[Param], body: &Block, operator: Option<OpTrait>) -> Option<Method> {
        let of = self.p.structs.len().checked_sub(1)?;
        let receiver = match params.first()? {
            Param::MutRef(_, Ty::Struct(k)) if *k == of => Receiver::MutRef,
            Param::Val(_, Ty::Struct(k)) if *k == of => {
                if self.r.chance(50) {
                    Receiver::Value
                } else {
                    Receiver::Ref
                }
            }
            _ => return None,
        };
        let mut own_calls_only = true;
        body.visit(&mut |e| {
            if let Expr::Call(h, _) = e {
                own_calls_only &= self.p.helpers[*h].method.is_some_and(|m| m.of == of);
            }
        });
        if !own_calls_only || !self.r.chance(90) {
            return None;
        }
        if let Some(op) = operator {
            // (`ufcs`: called by name, `a.add(b)`.)
            let by_name = self.r.chance(30);
            return Some(Method { of, receiver: Receiver::Value, ufcs: by_name, form: MethodForm::Operator(op) });
        }
        let form = if self.r.chance(50) { MethodForm::Trait } else { MethodForm::Inherent };
        Some(Method { of, receiver, ufcs: self.r.chance(30), form })
    }
}
