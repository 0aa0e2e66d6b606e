//! The methods' items as printed: the `#[rt_trait] FuzzOps` that lists the
//! trait methods' signatures, and each struct's `#[rt_impl]` blocks (its
//! inherent block, its `FuzzOps` impl, one block per operator trait).

use super::*;
use std::fmt::Write;

impl Program {
    /// A helper's parameters as printed (`name: Type`, `name: &mut Type`).
    pub(super) fn params(&self, h: &Helper) -> Vec<String> {
        h.params
            .iter()
            .map(|p| match p {
                Param::Val(n, t) => format!("{n}: {}", t.rust(self)),
                Param::MutRef(n, t) => format!("{n}: &mut {}", t.rust(self)),
            })
            .collect()
    }

    /// The methods of `form`.
    fn of_form(&self, form: MethodForm) -> Vec<&Helper> {
        self.helpers.iter().filter(|h| h.method.is_some_and(|m| m.form == form)).collect()
    }

    /// The trait, where a method is in one, before the structs: the macro
    /// chain needs it declared before an impl names it, and it names the
    /// struct that implements it as `Self` (the struct's name would make a
    /// cycle: the struct names its impls).
    pub(super) fn trait_declaration(&self, s: &mut String) {
        let traits = self.of_form(MethodForm::Trait);
        let Some(of) = traits.first().and_then(|h| h.method).map(|m| m.of) else { return };
        let name = &self.structs[of].name;
        s.push_str("\n#[rt_trait]\npub trait FuzzOps {\n");
        for h in &traits {
            let (signature, _) = self.method_parts(h);
            let words: Vec<String> = signature
                .split_inclusive(|c: char| !c.is_alphanumeric() && c != '_')
                .map(|w| {
                    let (word, rest) = w.split_at(w.trim_end_matches(|c: char| !c.is_alphanumeric() && c != '_').len());
                    if word == name { format!("Self{rest}") } else { w.to_string() }
                })
                .collect();
            let _ = writeln!(s, "    fn {};", words.concat());
        }
        s.push_str("}\n");
    }

    /// Every `#[rt_impl]` block.
    pub(super) fn impl_blocks(&self, s: &mut String) {
        let of_form = |form: MethodForm| self.of_form(form);
        let traits = of_form(MethodForm::Trait);
        for (i, d) in self.structs.iter().enumerate() {
            let of = |h: &&Helper| h.method.is_some_and(|m| m.of == i);
            let traits: Vec<&Helper> = traits.iter().copied().filter(of).collect();
            let inherent: Vec<&Helper> = of_form(MethodForm::Inherent).into_iter().filter(of).collect();
            if !inherent.is_empty() {
                let _ = writeln!(s, "\n#[rt_impl]\nimpl {} {{", d.name);
                for h in inherent {
                    s.push_str("    pub ");
                    self.method(s, h);
                }
                s.push_str("}\n");
            }
            if !traits.is_empty() {
                let _ = writeln!(s, "\n#[rt_impl]\nimpl FuzzOps for {} {{", d.name);
                for h in traits {
                    s.push_str("    ");
                    self.method(s, h);
                }
                s.push_str("}\n");
            }
            for op in OpTrait::ALL {
                for h in of_form(MethodForm::Operator(op)).into_iter().filter(of) {
                    let _ = writeln!(
                        s,
                        "\n#[rt_impl]\nimpl {} for {} {{\n    type Output = {};",
                        op.rust(),
                        d.name,
                        d.name
                    );
                    s.push_str("    ");
                    self.method(s, h);
                    s.push_str("}\n");
                }
            }
        }
    }

    /// A method's `fn` and body, one level in.
    fn method(&self, s: &mut String, h: &Helper) {
        let (signature, body) = self.method_parts(h);
        let _ = write!(s, "fn {signature} ");
        self.block(s, &body, 1);
        s.push('\n');
    }

    /// A method's signature (its name, `self` for the first parameter, the
    /// result) and its body with the receiver renamed.
    fn method_parts(&self, h: &Helper) -> (String, Block) {
        let m = h.method.expect("a method");
        let mut ps = self.params(h);
        let (Param::Val(first, _) | Param::MutRef(first, _)) = &h.params[0];
        ps[0] = match m.receiver {
            Receiver::Value => "self".into(),
            Receiver::Ref => "&self".into(),
            Receiver::MutRef => "&mut self".into(),
        };
        let mut body = h.body.clone();
        rename::block(&mut body, first, m.receiver == Receiver::Ref);
        let ret = h.ret.as_ref().map(|t| format!(" -> {}", t.rust(self))).unwrap_or_default();
        let name = match m.form {
            MethodForm::Operator(op) => op.method(),
            _ => &h.name,
        };
        (format!("{name}({}){ret}", ps.join(", ")), body)
    }
}
