//! Statements: scopes, blocks, loops, `match` arms, buffers and places.

use super::*;

impl Interp<'_> {
    pub(super) fn bind(&mut self, n: &str, v: V) {
        self.scopes.last_mut().unwrap().push((n.to_string(), v));
    }

    pub(super) fn var(&self, n: &str) -> V {
        self.scopes
            .iter()
            .rev()
            .flat_map(|s| s.iter().rev())
            .find(|(m, _)| m == n)
            .map(|(_, v)| v.clone())
            .unwrap_or_else(|| panic!("no variable `{n}`"))
    }

    pub(super) fn var_mut(&mut self, n: &str) -> &mut V {
        self.scopes
            .iter_mut()
            .rev()
            .flat_map(|s| s.iter_mut().rev())
            .find(|(m, _)| m == n)
            .map(|(_, v)| v)
            .unwrap_or_else(|| panic!("no variable `{n}`"))
    }

    /// `RT_FUZZ_TRACE=<launch index>` prints every value bound or assigned.
    fn trace(&self, name: &str, v: &V) {
        if std::env::var("RT_FUZZ_TRACE").ok().and_then(|l| l.parse::<u32>().ok()) == Some(self.lane) {
            eprintln!("[{}] {name} = {v:?}", self.lane);
        }
    }

    fn tick(&mut self) {
        self.steps += 1;
        assert!(self.steps < 1_000_000, "generator bug: a program runs too long");
    }

    pub(super) fn block(&mut self, b: &Block) -> R<(Flow, Option<V>)> {
        self.scopes.push(Vec::new());
        let r = self.block_inner(b);
        self.scopes.pop();
        r
    }

    fn block_inner(&mut self, b: &Block) -> R<(Flow, Option<V>)> {
        for s in &b.stmts {
            match self.stmt(s)? {
                Flow::Normal => {}
                f => return Ok((f, None)),
            }
        }
        match &b.tail {
            Some(e) => Ok((Flow::Normal, Some(self.expr(e)?))),
            None => Ok((Flow::Normal, None)),
        }
    }

    /// A block used as a value: its tail, or the value it returns from the
    /// helper (`Flow::Return`) passed up.
    pub(super) fn value_block(&mut self, b: &Block) -> R<Result<V, Flow>> {
        match self.block(b)? {
            (Flow::Normal, Some(v)) => Ok(Ok(v)),
            (f @ (Flow::Return(_) | Flow::Break | Flow::BreakTo(_) | Flow::Continue), _) => Ok(Err(f)),
            (Flow::Normal, None) => panic!("a value block without a value"),
        }
    }

    fn stmt(&mut self, s: &Stmt) -> R<Flow> {
        self.tick();
        match s {
            Stmt::Let { name, init, .. } => {
                let v = self.expr(init)?;
                self.trace(name, &v);
                self.bind(name, v);
            }
            Stmt::Assign(place, op, value) => {
                // Rust evaluates the value, then the place (indices); but
                // `op=` on a vector or struct is a trait call whose `&mut`
                // place comes first.
                let place_first = op.is_some() && !self.place_is_scalar(place);
                let early = if place_first { Some(self.place_path(place)?) } else { None };
                let v = self.expr(value)?;
                let path = match early {
                    Some(p) => p,
                    None => self.place_path(place)?,
                };
                let cur = self.read_path(&path);
                let new = match op {
                    None => v,
                    Some(op) => bin(*op, &cur, &v)?,
                };
                self.trace(&path.0, &new);
                self.write_path(&path, new);
            }
            Stmt::If(c, t, e) => {
                let c = self.expr(c)?.certain_bool("an `if` condition")?;
                let r = if c {
                    self.block(t)?
                } else if let Some(e) = e {
                    self.block(e)?
                } else {
                    (Flow::Normal, None)
                };
                return Ok(r.0);
            }
            Stmt::For { var, ty, start, end, inclusive, body } => {
                let end = self.expr(end)?.certain_u64("a loop bound")?;
                let last = if *inclusive { end } else { end - 1 };
                let values = (*start..=last).map(|i| {
                    let v = if *ty == Scalar::I32 { V::I(i as i32, false) } else { V::U(i as u32, false) };
                    vec![(var.as_str(), v)]
                });
                if let Some(f) = self.iterations(values, body)? {
                    return Ok(f);
                }
            }
            Stmt::Each { var, index, array, rev, body, .. } => {
                let V::Arr(items) = self.expr(array)? else { unreachable!("an array by construction") };
                let order: Vec<usize> =
                    if *rev { (0..items.len()).rev().collect() } else { (0..items.len()).collect() };
                let values = order.into_iter().map(|k| {
                    let mut binds = vec![(var.as_str(), items[k].clone())];
                    if let Some((raw, _)) = index {
                        binds.push((raw.as_str(), V::U(k as u32, false)));
                    }
                    binds
                });
                if let Some(f) = self.iterations(values, body)? {
                    return Ok(f);
                }
            }
            Stmt::While(c, body) => loop {
                self.tick();
                if !self.expr(c)?.certain_bool("a `while` condition")? {
                    break;
                }
                match self.block(body)?.0 {
                    Flow::Break => break,
                    f @ (Flow::Return(_) | Flow::BreakTo(_)) => return Ok(f),
                    _ => {}
                }
            },
            Stmt::Loop(body) => loop {
                self.tick();
                match self.block(body)?.0 {
                    Flow::Break => break,
                    f @ (Flow::Return(_) | Flow::BreakTo(_)) => return Ok(f),
                    _ => {}
                }
            },
            Stmt::Labelled(n, inner) => {
                return Ok(match self.stmt(inner)? {
                    Flow::BreakTo(k) if k == *n => Flow::Normal,
                    f => f,
                });
            }
            Stmt::BreakTo(n) => return Ok(Flow::BreakTo(*n)),
            Stmt::Break => return Ok(Flow::Break),
            Stmt::Continue => return Ok(Flow::Continue),
            Stmt::Match(e, arms) => {
                let v = self.expr(e)?;
                let arm = self.pick_arm(&v, arms)?;
                self.scopes.push(Vec::new());
                if let Some(b) = &arm.bind {
                    self.bind(b, v.clone());
                }
                let r = self.block(&arm.body);
                self.scopes.pop();
                return Ok(r?.0);
            }
            Stmt::Store { buf, index, value, form } => self.store_stmt(*buf, index, value, *form)?,
            Stmt::Expr(e) => {
                self.expr(e)?;
            }
            Stmt::Return(e) => {
                let v = e.as_ref().map(|e| self.expr(e)).transpose()?;
                return Ok(Flow::Return(v));
            }
            Stmt::Trace(_) => {}
        }
        Ok(Flow::Normal)
    }

    /// `buf.store(i, v)` evaluates `i` first; `buf[i] = v` (and `op=`)
    /// evaluates `v` first, as Rust does for `IndexMut` assignments of
    /// `Copy` values.
    fn store_stmt(&mut self, buf: usize, index: &Expr, value: &Expr, form: StoreForm) -> R<()> {
        let (i, v) = match form {
            StoreForm::Method => {
                let i = self.expr(index)?;
                (i, self.expr(value)?)
            }
            _ => {
                let v = self.expr(value)?;
                (self.expr(index)?, v)
            }
        };
        let i = i.certain_u64("a store index")?;
        let v = match form {
            StoreForm::Compound(op) => bin(op, &self.load(buf, i), &v)?,
            _ => v,
        };
        self.store(buf, i, &v);
        Ok(())
    }

    /// A counted loop: `body` once per item of `iterations`, in a scope of
    /// its own with the item's bindings, until a `break`; a `return`
    /// passed up.
    fn iterations<'a>(&mut self, iterations: impl Iterator<Item = Vec<(&'a str, V)>>, body: &Block) -> R<Option<Flow>> {
        for binds in iterations {
            self.tick();
            self.scopes.push(Vec::new());
            for (name, v) in binds {
                self.bind(name, v);
            }
            let r = self.block(body);
            self.scopes.pop();
            match r?.0 {
                Flow::Break => break,
                f @ (Flow::Return(_) | Flow::BreakTo(_)) => return Ok(Some(f)),
                _ => {}
            }
        }
        Ok(None)
    }

    fn local_index(&self, i: i64) -> usize {
        let slots = self.p.slots as i64;
        assert!(i / slots == self.lane as i64 && i >= 0, "generator bug: lane {} accesses element {i}", self.lane);
        (i % slots) as usize
    }

    pub(super) fn load(&self, buf: usize, i: i64) -> V {
        let t = &self.p.outputs[buf].1;
        let w = self.p.words(t) as usize;
        let k = self.local_index(i);
        let mut it = self.outputs[buf][k * w..(k + 1) * w].iter().copied();
        V::from_interp_words(self.p, t, &mut it)
    }

    fn store(&mut self, buf: usize, i: i64, v: &V) {
        let w = self.p.words(&self.p.outputs[buf].1) as usize;
        let k = self.local_index(i);
        let mut words = Vec::new();
        v.words(&mut words);
        assert_eq!(words.len(), w);
        self.outputs[buf][k * w..(k + 1) * w].copy_from_slice(&words);
    }

    pub(super) fn pick_arm<'a>(&self, v: &V, arms: &'a [Arm]) -> R<&'a Arm> {
        let x = v.certain_u64("a `match` scrutinee")?;
        for a in arms {
            let hit = a.pats.is_empty()
                || a.pats.iter().any(|p| match p {
                    LitV::I32(i) => *i as i64 == x,
                    LitV::U32(u) => *u as i64 == x,
                    _ => false,
                });
            if hit {
                return Ok(a);
            }
        }
        panic!("generator bug: no arm matches {x}");
    }

    /// A place as a variable name and a path of component indices, with
    /// index expressions evaluated.
    fn place_path(&mut self, p: &Place) -> R<(String, Vec<usize>)> {
        Ok(match p {
            Place::Var(n) | Place::Deref(n) => (n.clone(), Vec::new()),
            Place::Field(b, _, i) => {
                let (n, mut path) = self.place_path(b)?;
                path.push(*i);
                (n, path)
            }
            Place::Index(b, i) => {
                let (n, mut path) = self.place_path(b)?;
                let k = self.expr(i)?.certain_u64("an index")?;
                path.push(k as usize);
                (n, path)
            }
        })
    }

    /// Whether a place holds a scalar (its indices unevaluated).
    fn place_is_scalar(&self, p: &Place) -> bool {
        fn at(v: V, p: &Place, interp: &Interp<'_>) -> V {
            match p {
                Place::Var(n) | Place::Deref(n) => interp.var(n),
                Place::Field(b, _, i) => match at(v, b, interp) {
                    V::Vec(c) | V::Struct(c) | V::Arr(c) => c[*i].clone(),
                    other => other,
                },
                Place::Index(b, _) => match at(v, b, interp) {
                    V::Vec(c) | V::Struct(c) | V::Arr(c) => c[0].clone(),
                    other => other,
                },
            }
        }
        matches!(at(V::B(false, false), p, self), V::B(..) | V::I(..) | V::U(..) | V::F(..))
    }

    fn read_path(&self, (n, path): &(String, Vec<usize>)) -> V {
        let mut v = self.var(n);
        for i in path {
            v = match v {
                V::Vec(c) | V::Struct(c) | V::Arr(c) => c[*i].clone(),
                other => panic!("cannot index {other:?}"),
            };
        }
        v
    }

    fn write_path(&mut self, (n, path): &(String, Vec<usize>), new: V) {
        let mut v = self.var_mut(n);
        for i in path {
            v = match v {
                V::Vec(c) | V::Struct(c) | V::Arr(c) => &mut c[*i],
                other => panic!("cannot index {other:?}"),
            };
        }
        *v = new;
    }
}
