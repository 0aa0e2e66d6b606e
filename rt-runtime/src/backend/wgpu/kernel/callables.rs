//! Callable programs in the megakernel: one dispatch function per
//! signature, `rt_call_<signature>(id, args..)`, a `switch` over the ids of
//! the linked callables of that signature whose default raises
//! `EXCEPTION_PROGRAM_ID_INVALID` and returns zero. A callable's `#[var]`
//! variables come from its record, which the scene's table at header word 3
//! locates by program index (`encode`). Which callables a kernel
//! links (those of a signature some linked program calls, and so on through
//! the callables' own calls) and the refusal of cycles (WGSL has no
//! recursion) are the link's, the same for every backend
//! (`crate::link::callables`).

use crate::link::callables::{LinkedCallable, of_signature};
use rt_std::program::CallableSignature;
use std::collections::BTreeMap;

/// The dispatch functions of `called` over the `linked` callables.
pub fn dispatch(called: &BTreeMap<&'static str, CallableSignature>, linked: &[LinkedCallable]) -> String {
    let mut out = String::new();
    for (name, sig) in called {
        let params: String = sig.params.iter().enumerate().map(|(i, t)| format!(", a{i}: {t}")).collect();
        let mut cases = String::new();
        for c in of_signature(linked, name) {
            let f = c.desc.wgsl_entry;
            // Variables first (the compiler's parameter order), from the
            // callable's record in the scene's table by program index.
            let mut all = super::var_args(c.desc, "v");
            all.extend((0..sig.params.len()).map(|i| format!("a{i}")));
            let all = all.join(", ");
            let record = match crate::scene::ProgramId::from_callable_id(c.id) {
                Some(p) if !c.desc.variables.is_empty() => format!("let v = rt_scene[rt_scene[3] + {}u]; ", p.index()),
                _ => String::new(),
            };
            let call = match sig.ret {
                Some(_) => format!("return {f}({all});"),
                None => format!("{f}({all});"),
            };
            cases.push_str(&format!("        case {}u: {{ {record}{call} }}\n", c.id));
        }
        let (ret, tail) = match sig.ret {
            Some(r) => (format!(" -> {r}"), format!("    var r: {r};\n    return r;\n")),
            None => (String::new(), String::new()),
        };
        out.push_str(&format!(
            "fn {name}(id: u32{params}){ret} {{\n    switch id {{\n{cases}        default: {{ rt_raise(RT_EXC_PROGRAM_ID); }}\n    }}\n{tail}}}\n"
        ));
    }
    out
}
