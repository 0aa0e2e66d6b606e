//! A `switch`'s arms with identical bodies merged into one (`case 2u, 7u:`).
//!
//! A driver inlines every call, so each arm calling a program is one more
//! copy of that program, and of all it calls. The same program created
//! twice (two `ProgramId`s, two cases) must be one call site: with per-depth
//! clones a tracing program's arms multiply at every depth (two arms of
//! the same closest hit at five depths made 31 inlined traversals, and
//! lavapipe ran out of memory compiling them), and [`super::clone_estimate`]
//! counts each program once.

/// Arms in the order their first case was added.
#[derive(Default)]
pub(super) struct Arms {
    arms: Vec<(Vec<u32>, String)>,
}

impl Arms {
    /// Adds case `case` running `body` (statements, each line indented for
    /// the arm's block).
    pub(super) fn add(&mut self, case: u32, body: String) {
        match self.arms.iter_mut().find(|(_, b)| *b == body) {
            Some((cases, _)) => cases.push(case),
            None => self.arms.push((vec![case], body)),
        }
    }

    /// The arms as WGSL, each `        case ..: {\n<body>        }\n`.
    pub(super) fn render(&self) -> String {
        let mut out = String::new();
        for (cases, body) in &self.arms {
            let list: Vec<String> = cases.iter().map(|c| format!("{c}u")).collect();
            out.push_str(&format!("        case {}: {{\n{body}        }}\n", list.join(", ")));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_bodies_share_one_arm_in_first_case_order() {
        let mut arms = Arms::default();
        arms.add(4, "            f();\n".into());
        arms.add(2, "            g();\n".into());
        arms.add(8, "            f();\n".into());
        assert_eq!(
            arms.render(),
            "        case 4u, 8u: {\n            f();\n        }\n        case 2u: {\n            g();\n        }\n"
        );
    }
}
