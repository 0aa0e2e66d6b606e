//! Evaluation order and WGSL's constant expressions: operands that later
//! statements could change are spilled into temporaries to keep Rust's
//! left-to-right order, and integer arithmetic that WGSL would evaluate at
//! shader creation (with stricter rules than Rust's run time) is moved to
//! run time.
//!
//! What statements and values may change or read is recorded as they are
//! lowered ([`Val::effects`], [`Val::reads`], the block's per-statement
//! `writes`). Whether code is a WGSL const-expression, or one integer
//! literal, is asked of the lowered text itself (`wgsl_idents`,
//! `int_literal_value`): WGSL decides what it evaluates at shader creation
//! from the expression's form, and a builtin method's lowering is a closure
//! whose text is all there is to ask.

use super::*;

impl FnLowerer<'_> {
    /// The current position in the statements being emitted (see [`spill`]).
    ///
    /// [`spill`]: FnLowerer::spill
    pub(super) fn here(&self) -> usize {
        self.blocks.last().map_or(0, |b| b.len())
    }

    /// Rust evaluates operands left to right; a later operand that needs
    /// statements (an `if` or `match` value, a block) has them emitted
    /// before the whole expression, where they could change what an earlier
    /// operand reads (`x + { x += 1; 1 }`, a helper call through `&mut`).
    /// If statements were emitted since `at`, the `earlier` operands that
    /// read mutable state are evaluated into temporaries at `at`, first.
    pub(super) fn spill(&mut self, at: usize, earlier: &mut [&mut Val]) {
        // `let`s of effect-free values change nothing.
        if !self.blocks.last().unwrap().writes_since(at) {
            return;
        }
        let mut lets = Vec::new();
        for v in earlier.iter_mut() {
            if v.code.is_empty() || matches!(v.ty, Ty::Ref(..)) || !self.reads_state(v) {
                continue;
            }
            let t = self.tmp();
            let var = matches!(self.resolved(&v.ty), Ty::Array(..) | Ty::Mat(_));
            let kw = if var { "var" } else { "let" };
            lets.push((format!("{kw} {t} = {};", v.code), var || v.effects));
            v.code = t;
            v.effects = false;
            v.reads = false;
        }
        let block = self.blocks.last_mut().unwrap();
        for (i, (line, writes)) in lets.into_iter().enumerate() {
            block.insert(at + i, line, writes);
        }
    }

    /// Whether a value reads something that statements can change: a
    /// `var` local, a pointer parameter, a buffer, or a call with effects.
    pub(super) fn reads_state(&self, v: &Val) -> bool {
        v.effects || v.reads
    }

    /// Whether lowered code is a WGSL const-expression (literals,
    /// operators, constructors, builtins, constants). WGSL evaluates those
    /// when the shader is created, with stricter rules than Rust's run-time
    /// semantics: integer overflow in `+ - * <<` and shift amounts of 32 or
    /// more are errors there, where they wrap or are masked at run time.
    pub(super) fn is_const_code(&self, code: &str) -> bool {
        wgsl_idents(code).iter().all(|id| {
            is_reserved(id)
                || id == "true"
                || id == "false"
                || self.local_consts.contains(id)
                || self.m.consts.values().any(|c| c.wgsl_name == *id)
        })
    }

    /// `v` through a `let`, which WGSL evaluates at run time.
    pub(super) fn at_run_time(&mut self, v: Val) -> Val {
        if !self.in_function {
            return v;
        }
        let t = self.tmp();
        self.emit_let(format!("let {t} = {};", v.code), &v);
        Val::new(t, v.ty)
    }

    /// Integer `l op r` with both operands constant: run time, unless WGSL
    /// evaluates it at shader creation exactly as Rust does at run time
    /// (two literals, no overflow).
    pub(super) fn const_int_op(&mut self, op: &BinOp, l: Val, r: &Val) -> Val {
        let ty = self.resolved(&l.ty);
        if !(self.is_int(&ty) || matches!(ty, Ty::Vec(_, s) if s.is_int()))
            || !self.is_const_code(&l.code)
            || !self.is_const_code(&r.code)
        {
            return l;
        }
        let scalar = match ty {
            Ty::Scalar(s) => Some(s),
            _ => None,
        };
        match (int_literal_value(&l.code), int_literal_value(&r.code)) {
            (Some(a), Some(b)) if matches!(ty, Ty::Scalar(_) | Ty::IntVar(_)) && !const_overflows(op, a, b, scalar) => {
                l
            }
            _ => self.at_run_time(l),
        }
    }

    /// A shift amount that is a const-expression other than a literal below
    /// 32, masked as WGSL masks run-time amounts (a constant 32 or more is
    /// an error in WGSL; Rust masks it in release builds, glam's vector
    /// shifts included).
    pub(super) fn mask_amount(&self, amount: String, vector: Option<u8>) -> String {
        if !self.is_const_code(&amount) || literals_below_32(&amount) {
            return amount;
        }
        match vector {
            Some(n) => format!("({amount} & vec{n}<u32>(31u))"),
            None => format!("({amount} & 31u)"),
        }
    }
}

/// The identifiers lowered code names (not members after `.`, not literal
/// suffixes), markers and placeholders skipped.
fn wgsl_idents(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut chars = code.chars().peekable();
    let mut prev = ' ';
    while let Some(c) = chars.next() {
        match c {
            '\u{1}' => {
                chars.by_ref().take_while(|&d| d != '\u{2}').for_each(drop);
                continue;
            }
            '\u{4}' => {
                chars.by_ref().take_while(|&d| d != '\u{5}').for_each(drop);
                prev = '0';
                continue;
            }
            '\u{3}' => continue,
            c if c.is_ascii_digit() => {
                while chars.peek().is_some_and(|d| d.is_ascii_alphanumeric() || *d == '_' || *d == '.') {
                    chars.next();
                }
            }
            c if c.is_ascii_alphabetic() || c == '_' => {
                let mut id = String::from(c);
                while let Some(&d) = chars.peek() {
                    if d.is_ascii_alphanumeric() || d == '_' {
                        id.push(d);
                        chars.next();
                    } else {
                        break;
                    }
                }
                if prev != '.' {
                    out.push(id);
                }
            }
            _ => {}
        }
        prev = c;
    }
    out
}

/// The value of lowered code that is one integer literal (`5u`, `-3i`, a
/// literal placeholder), markers aside.
pub(super) fn int_literal_value(code: &str) -> Option<i64> {
    let mut text = String::new();
    let mut chars = code.chars();
    while let Some(c) = chars.next() {
        match c {
            '\u{1}' => chars.by_ref().take_while(|&d| d != '\u{2}').for_each(drop),
            '\u{3}' => {}
            '\u{4}' => {
                let body: String = chars.by_ref().take_while(|&d| d != '\u{5}').collect();
                text.push_str(body.strip_prefix('L')?.split_once(' ')?.1);
            }
            c => text.push(c),
        }
    }
    let text = text.trim_end_matches(['i', 'u']);
    let (neg, digits) = match text.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, text),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let v: i64 = digits.parse().ok()?;
    Some(if neg { -v } else { v })
}

/// Whether const code is only integer literals below 32, possibly in
/// vector constructors and conversions (`5u`, `vec2<u32>(1u, 2u)`).
fn literals_below_32(code: &str) -> bool {
    let text = text::strip(code).replace("<u32>", "").replace("<i32>", "");
    if text.contains(['+', '-', '*', '/', '%', '&', '|', '^', '~', '<', '>', '!', '.']) {
        return false;
    }
    // Constructors and conversions only, no functions (`reverseBits(5u)`).
    if wgsl_idents(&text).iter().any(|id| !matches!(id.as_str(), "vec2" | "vec3" | "vec4" | "u32" | "i32")) {
        return false;
    }
    text.split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|t| t.starts_with(|c: char| c.is_ascii_digit()))
        .all(|t| t.trim_end_matches(['i', 'u']).parse::<u32>().is_ok_and(|v| v < 32))
}

/// Whether WGSL's shader-creation evaluation of `a op b` fails (an
/// overflow, a shift of 32 or more) for the scalar type (`None`: not yet
/// inferred, either).
fn const_overflows(op: &BinOp, a: i64, b: i64, scalar: Option<Scalar>) -> bool {
    let fails = |signed: bool| -> bool {
        let (lo, hi) = if signed { (i32::MIN as i64, i32::MAX as i64) } else { (0, u32::MAX as i64) };
        let out = |v: i64| v < lo || v > hi;
        if out(a) || (!matches!(op, BinOp::Shl(_) | BinOp::Shr(_)) && out(b)) {
            return true;
        }
        match op {
            BinOp::Add(_) => out(a + b),
            BinOp::Sub(_) => out(a - b),
            BinOp::Mul(_) => out(a.saturating_mul(b)),
            BinOp::Shl(_) | BinOp::Shr(_) if !(0..32).contains(&b) => true,
            // The bits shifted out (and, signed, the sign) must not change.
            BinOp::Shl(_) => out(a << b),
            _ => false,
        }
    };
    match scalar {
        Some(Scalar::I32) => fails(true),
        Some(Scalar::U32 | Scalar::Usize) => fails(false),
        _ => fails(true) || fails(false),
    }
}
