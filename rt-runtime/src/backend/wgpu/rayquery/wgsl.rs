//! The ray-query traversal's part of a kernel: its bindings (the side
//! table, one TLAS per root slot), the loop (`search.wgsl`) and
//! `rt_search` switching on the traced root's slot. A leaf: the linker
//! ([`super::super::kernel`]) and the device's layout read it.

/// The binding of the side table, then of the TLASes (one per slot).
pub(crate) const SIDE_BINDING: u32 = 16;

const SEARCH: &str = include_str!("search.wgsl");

/// The kernel's ray-query part for `slots` roots: the bindings, the loop
/// and `rt_search` switching on the root's slot.
pub(crate) fn search_wgsl(slots: u32) -> String {
    let mut out = format!("\n@group(0) @binding({SIDE_BINDING}) var<storage, read> rt_query_side: array<u32>;\n");
    let mut cases = String::new();
    for s in 0..slots {
        out.push_str(&format!(
            "@group(0) @binding({}) var rt_tlas{s}: acceleration_structure;\n",
            SIDE_BINDING + 1 + s
        ));
        cases.push_str(&format!(
            "        case {s}u: {{\n            rt_query_search(rt_tlas{s}, ray, flags, mask);\n        }}\n"
        ));
    }
    out.push_str(SEARCH);
    out.push_str(&format!(
        "
fn rt_search(object: u32, ray: RtRay, flags: u32, mask: u32) {{
    rt_query_begin(ray, flags);
    let slot = rt_query_slot(object);
    if slot != RT_NONE {{
        rt_q_paths = rt_query_side[rt_query_nodes() + object * 2u + 1u];
    }}
    switch slot {{
{cases}        default: {{
            // Not a root the launch found in a variable. (Every node a
            // program traces comes from an `Object` variable: an Object
            // is no buffer element or field, nor made in a program.)
            rt_raise(RT_EXC_INVALID_RAY);
        }}
    }}
}}
"
    ));
    out
}
