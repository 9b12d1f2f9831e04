//! The common-subexpression machinery behind the Rust, C and Python emitters.
//!
//! All outputs of one function are lowered into a single hash-consed DAG of binary operations,
//! so a subexpression shared by two outputs (the `a2 c2 + a3 c23 - d4 s23` of `T[0][3]` and
//! `T[1][3]`) is one node. Sums and products are folded with their operands sorted by node id, so
//! `c1 s2` and `s2 c1` are one node too. A node used more than once becomes a temporary; the
//! others are written inline. Trigonometric values come from one `sin_cos` per *base angle*:
//! with [`CodegenOptions::expand_angles`] one per symbol (at the largest step all its
//! coefficients are multiples of, `theta1 / 2` when both `theta1` and `theta1 / 2` occur), the
//! sums and multiples built by the angle-addition formulas, themselves shared; without it, one
//! per distinct angle.

use crate::closed::{angle_text, shorthand_name, Angle, Expr};
use crate::scalar::{Small, Sym, Trig};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::collections::{BTreeMap, HashMap, HashSet};
use thiserror::Error;

/// How generated code is shaped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CodegenOptions {
    /// Call `sin_cos` once per symbol and build angle sums and multiples from the addition
    /// formulas (fewest calls, the fast choice); otherwise once per distinct angle.
    pub expand_angles: bool,
}

impl Default for CodegenOptions {
    fn default() -> Self {
        CodegenOptions {
            expand_angles: true,
        }
    }
}

/// One named result of a generated function: a scalar, a vector or a row-major matrix.
#[derive(Clone, Debug, PartialEq)]
pub struct Output {
    /// An identifier: the field (Rust), the out-parameter (C) or the dictionary key (Python).
    pub name: String,
    /// One line of documentation.
    pub doc: String,
    /// `None` for a scalar, `Some((rows, cols))` for a vector (1 row) or a matrix.
    pub shape: Option<(usize, usize)>,
    /// The values, row-major.
    pub values: Vec<Expr>,
    /// An intermediate result: computed but not returned. Entry `k` is the symbol
    /// `{name}_{k}` in the outputs after it (a recurrence `Q2 = Q1 L2` reads `Q1_0`, ...), so
    /// the function evaluates it once, as a local, and never takes it as an argument.
    pub intermediate: bool,
}

impl Output {
    /// A scalar result.
    pub fn scalar(name: &str, doc: &str, e: Expr) -> Output {
        Output {
            name: name.into(),
            doc: doc.into(),
            shape: None,
            values: vec![e],
            intermediate: false,
        }
    }

    /// A vector result (`[f64; n]`).
    pub fn vector(name: &str, doc: &str, v: Vec<Expr>) -> Output {
        Output {
            name: name.into(),
            doc: doc.into(),
            shape: Some((1, v.len())),
            values: v,
            intermediate: false,
        }
    }

    /// An intermediate vector (see [`Output::intermediate`](Output#structfield.intermediate)):
    /// entry `k` is read by later outputs as the symbol `{name}_{k}`.
    pub fn intermediate(name: &str, doc: &str, v: Vec<Expr>) -> Output {
        Output {
            intermediate: true,
            ..Output::vector(name, doc, v)
        }
    }

    /// The symbol later outputs read entry `k` of an intermediate output by.
    pub fn entry_symbol(&self, k: usize) -> String {
        format!("{}_{k}", self.name)
    }

    /// A matrix result (`[[f64; cols]; rows]`) from its rows.
    pub fn matrix(name: &str, doc: &str, rows: Vec<Vec<Expr>>) -> Output {
        let cols = rows.first().map_or(0, Vec::len);
        Output {
            name: name.into(),
            doc: doc.into(),
            shape: Some((rows.len(), cols)),
            values: rows.into_iter().flatten().collect(),
            intermediate: false,
        }
    }
}

/// Why code could not be generated.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum CodegenError {
    /// A symbol of an output is not among the arguments.
    #[error("symbol `{0}` is not an argument")]
    Unbound(String),
    /// A name is not an identifier in the target languages.
    #[error("`{0}` is not an identifier")]
    BadName(String),
    /// A matrix output whose rows differ in length, or an empty output.
    #[error("output `{0}` has a ragged or empty shape")]
    BadShape(String),
    /// Code asked of a text syntax (SymPy), which has no function writer.
    #[error("{0:?} text is not code")]
    NoWriter(super::names::Lang),
}

/// The arguments of a generated function: `joints` in joint order, then every other symbol of
/// the outputs in alphabetical order (`pi` and the entries of intermediate outputs excluded).
pub fn arguments(outputs: &[Output], joints: &[&str]) -> Vec<String> {
    let bound: HashSet<String> = outputs
        .iter()
        .filter(|o| o.intermediate)
        .flat_map(|o| (0..o.values.len()).map(|k| o.entry_symbol(k)))
        .collect();
    let mut rest: Vec<String> = outputs
        .iter()
        .flat_map(|o| o.values.iter())
        .flat_map(Expr::symbol_names)
        .filter(|n| !joints.contains(&n.as_str()) && !bound.contains(n))
        .collect();
    rest.sort();
    rest.dedup();
    joints.iter().map(|s| s.to_string()).chain(rest).collect()
}

/// Operation counts of generated code (or of any straight-line computation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Multiplications.
    pub mul: usize,
    /// Additions and subtractions.
    pub add: usize,
    /// Negations.
    pub neg: usize,
    /// Calls of sin and cos (a `sin_cos` counts as one call of each).
    pub trig: usize,
}

pub(crate) type Id = usize;

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Node {
    Arg(usize),
    /// An f64 constant, by its bits.
    Const(u64),
    Sin(usize),
    Cos(usize),
    Add(Id, Id),
    Sub(Id, Id),
    Mul(Id, Id),
    Neg(Id),
}

/// A base angle: `sin_cos` is called on it once.
pub(crate) struct Atom {
    pub angle: Angle,
    pub sin_name: String,
    pub cos_name: String,
}

/// A straight-line program computing every output.
pub(crate) struct Program {
    pub args: Vec<String>,
    /// The identifiers the arguments are written as (see [`super::names::safe_names`]).
    pub names: Vec<String>,
    pub atoms: Vec<Atom>,
    pub nodes: Vec<Node>,
    /// How many times each node is read by reachable nodes and outputs; 0 when unreachable.
    pub uses: Vec<usize>,
    /// The temporary's name for nodes read more than once.
    pub temp: HashMap<Id, String>,
    /// The returned outputs (intermediate ones are only reached through them).
    pub outputs: Vec<(Output, Vec<Id>)>,
}

struct Builder<'a> {
    args: &'a [String],
    o: CodegenOptions,
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    atoms: Vec<Angle>,
    atom_index: HashMap<Angle, usize>,
    /// Per symbol, the step all its coefficients are multiples of.
    step: BTreeMap<Sym, Small>,
    /// `(cos, sin)` of an angle given by integer multiples of the steps.
    trig: HashMap<Vec<(Sym, i64)>, (Id, Id)>,
    /// The entries of the intermediate outputs lowered so far: their node by symbol, and the
    /// local's name (`q2_3` for `Q2_3`) in the order they were lowered.
    bound: HashMap<String, Id>,
    locals: Vec<(Id, String)>,
}

fn is_ident(s: &str) -> bool {
    let mut c = s.chars();
    c.next()
        .is_some_and(|f| f.is_ascii_alphabetic() || f == '_')
        && c.all(|x| x.is_ascii_alphanumeric() || x == '_')
}

/// A product whose rational coefficient is below f64's normal range (a factored
/// `(3^700 + x)/3^700`), with the coefficient multiplied exactly into its first sum; `None`
/// for any other product. Written as it is, such a coefficient would round to 0 and the
/// product to NaN (`(inf + x) * 0`) or 0 where its value is near 1; distributed, each term
/// carries its own coefficient, which rounds to that term's own size (a term past the range
/// still becomes the language's infinity or 0, as a single constant does). A coefficient
/// past the top of the range stays outside: `(x - 10^100 y) * inf` keeps the sign of the
/// sum, where `x * inf - inf * y` would be NaN.
fn distributed(v: &[Expr]) -> Option<Expr> {
    let mut q = BigRational::one();
    for f in v {
        if let Expr::Num(n) = f {
            q *= n;
        }
    }
    let tiny = q
        .to_f64()
        .is_some_and(|f| f.is_finite() && f.abs() < f64::MIN_POSITIVE);
    if q.is_zero() || !tiny {
        return None;
    }
    let sum = v.iter().position(|f| matches!(f, Expr::Add(_)))?;
    // Every sum divided by its largest coefficient first (exactly; the quotient kept in
    // `q`): with two sums past the range, `(2^1100 + y) (x + 3^700) / (2^1100 3^700)`,
    // scaling the first alone leaves `(2^-1100 + ...) (x + inf)` = `0 * inf`.
    let mut rest = Vec::new();
    for (i, f) in v.iter().enumerate() {
        match f {
            Expr::Num(_) => {}
            Expr::Add(_) if i != sum => {
                let c = largest_coefficient(f);
                q *= &c;
                rest.push(scaled(f, &c.recip()));
            }
            f if i != sum => rest.push(f.clone()),
            _ => {}
        }
    }
    let scaled = scaled(&v[sum], &q);
    Some(if rest.is_empty() {
        scaled
    } else {
        rest.push(scaled);
        Expr::Mul(rest)
    })
}

/// The largest absolute rational coefficient of the terms of `e` (1 for a term without one).
fn largest_coefficient(e: &Expr) -> BigRational {
    fn coefficient(t: &Expr) -> BigRational {
        match t {
            Expr::Num(n) => n.abs(),
            Expr::Neg(x) => coefficient(x),
            Expr::Mul(v) => v
                .iter()
                .find_map(|f| match f {
                    Expr::Num(n) => Some(n.abs()),
                    _ => None,
                })
                .unwrap_or_else(BigRational::one),
            _ => BigRational::one(),
        }
    }
    let terms = match e {
        Expr::Add(v) => v.as_slice(),
        e => std::slice::from_ref(e),
    };
    terms
        .iter()
        .map(coefficient)
        .filter(|c| !c.is_zero())
        .max()
        .unwrap_or_else(BigRational::one)
}

/// `e` times the rational `q`, exactly: into every term of a sum, into a product's
/// coefficient.
fn scaled(e: &Expr, q: &BigRational) -> Expr {
    match e {
        Expr::Num(n) => Expr::Num(n * q),
        Expr::Neg(x) => Expr::Neg(Box::new(scaled(x, q))),
        Expr::Add(v) => Expr::Add(v.iter().map(|t| scaled(t, q)).collect()),
        Expr::Mul(v) if v.iter().any(|f| matches!(f, Expr::Num(_))) => {
            let mut done = false;
            Expr::Mul(
                v.iter()
                    .map(|f| match f {
                        Expr::Num(n) if !done => {
                            done = true;
                            Expr::Num(n * q)
                        }
                        f => f.clone(),
                    })
                    .collect(),
            )
        }
        Expr::Mul(v) => Expr::Mul(
            std::iter::once(Expr::Num(q.clone()))
                .chain(v.iter().cloned())
                .collect(),
        ),
        e => Expr::Mul(vec![Expr::Num(q.clone()), e.clone()]),
    }
}

/// Lowers the outputs into one program over `args`, each written as itself.
pub(crate) fn lower(
    outputs: &[Output],
    args: &[String],
    o: &CodegenOptions,
) -> Result<Program, CodegenError> {
    lower_named(outputs, args, args, o)
}

/// Lowers the outputs into one program over `args`, argument `i` written as `names[i]`
/// (its name in the target language, see [`super::names::safe_names`]); the locals' names
/// are chosen apart from `names`.
pub(crate) fn lower_named(
    outputs: &[Output],
    args: &[String],
    names: &[String],
    o: &CodegenOptions,
) -> Result<Program, CodegenError> {
    for a in args
        .iter()
        .chain(names)
        .chain(outputs.iter().map(|o| &o.name))
    {
        if !is_ident(a) {
            return Err(CodegenError::BadName(a.clone()));
        }
    }
    for out in outputs {
        let n = out.shape.map_or(1, |(r, c)| r * c);
        if n == 0 || n != out.values.len() {
            return Err(CodegenError::BadShape(out.name.clone()));
        }
    }
    let mut b = Builder {
        args,
        o: *o,
        nodes: Vec::new(),
        index: HashMap::new(),
        atoms: Vec::new(),
        atom_index: HashMap::new(),
        step: BTreeMap::new(),
        trig: HashMap::new(),
        bound: HashMap::new(),
        locals: Vec::new(),
    };
    for out in outputs {
        for e in &out.values {
            b.steps(e);
        }
    }
    let mut outs = Vec::new();
    for out in outputs {
        let ids = out
            .values
            .iter()
            .map(|e| b.expr(e))
            .collect::<Result<Vec<_>, _>>()?;
        if out.intermediate {
            for (k, id) in ids.into_iter().enumerate() {
                b.bound.insert(out.entry_symbol(k), id);
                b.locals
                    .push((id, out.entry_symbol(k).to_ascii_lowercase()));
            }
        } else {
            outs.push((out.clone(), ids));
        }
    }
    Ok(b.finish(outs, names))
}

impl Builder<'_> {
    fn node(&mut self, n: Node) -> Id {
        if let Some(&id) = self.index.get(&n) {
            return id;
        }
        self.nodes.push(n.clone());
        self.index.insert(n, self.nodes.len() - 1);
        self.nodes.len() - 1
    }

    fn constant(&mut self, v: f64) -> Id {
        // Negative constants are negations, so `x - 2.0 * y` never reads `x + -2.0 * y`.
        if v < 0.0 {
            let c = self.constant(-v);
            return self.neg(c);
        }
        self.node(Node::Const(v.to_bits()))
    }

    fn const_value(&self, id: Id) -> Option<f64> {
        match self.nodes[id] {
            Node::Const(b) => Some(f64::from_bits(b)),
            _ => None,
        }
    }

    fn neg(&mut self, a: Id) -> Id {
        match self.nodes[a] {
            Node::Neg(x) => x,
            // Through `sub`, so that `-(-y - x)` is `x + y`, never `x - -y`.
            Node::Sub(x, y) => self.sub(y, x),
            _ => self.node(Node::Neg(a)),
        }
    }

    fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.nodes[a].clone(), self.nodes[b].clone()) {
            (_, Node::Neg(y)) => self.sub(a, y),
            (Node::Neg(x), _) => self.sub(b, x),
            _ if self.const_value(a) == Some(0.0) => b,
            _ if self.const_value(b) == Some(0.0) => a,
            _ => {
                let (a, b) = (a.min(b), a.max(b));
                self.node(Node::Add(a, b))
            }
        }
    }

    fn sub(&mut self, a: Id, b: Id) -> Id {
        match self.nodes[b] {
            Node::Neg(y) => self.add(a, y),
            _ if self.const_value(b) == Some(0.0) => a,
            _ if self.const_value(a) == Some(0.0) => self.neg(b),
            _ => self.node(Node::Sub(a, b)),
        }
    }

    fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.nodes[a].clone(), self.nodes[b].clone()) {
            (Node::Neg(x), _) => {
                let m = self.mul(x, b);
                self.neg(m)
            }
            (_, Node::Neg(y)) => {
                let m = self.mul(a, y);
                self.neg(m)
            }
            _ if self.const_value(a) == Some(1.0) => b,
            _ if self.const_value(b) == Some(1.0) => a,
            _ => {
                let (a, b) = (a.min(b), a.max(b));
                self.node(Node::Mul(a, b))
            }
        }
    }

    /// Records the step of every symbol in every angle of `e`.
    fn steps(&mut self, e: &Expr) {
        match e {
            Expr::Trig { angle, .. } => {
                for (s, k) in &angle.terms {
                    let k = k.abs();
                    let g = match self.step.get(s) {
                        Some(g) => Small::new(g.numer().gcd(k.numer()), g.denom().lcm(k.denom())),
                        None => k,
                    };
                    self.step.insert(s.clone(), g);
                }
            }
            Expr::Add(v) | Expr::Mul(v) => v.iter().for_each(|x| self.steps(x)),
            Expr::Neg(x) | Expr::Pow(x, _) => self.steps(x),
            _ => {}
        }
    }

    fn expr(&mut self, e: &Expr) -> Result<Id, CodegenError> {
        Ok(match e {
            Expr::Num(q) => self.constant(q.to_f64().unwrap_or(f64::NAN)),
            Expr::Sqrt(n) => self.constant((*n as f64).sqrt()),
            Expr::Sym(s) if s.is_pi() => self.constant(std::f64::consts::PI),
            Expr::Sym(s) if self.bound.contains_key(s.name()) => self.bound[s.name()],
            Expr::Sym(s) => {
                let i = self
                    .args
                    .iter()
                    .position(|a| a == s.name())
                    .ok_or_else(|| CodegenError::Unbound(s.name().to_string()))?;
                self.node(Node::Arg(i))
            }
            Expr::Trig { f, angle } => {
                let (c, s) = self.cos_sin(angle)?;
                match f {
                    Trig::Cos => c,
                    Trig::Sin => s,
                }
            }
            Expr::Add(v) => {
                let mut pos = Vec::new();
                let mut neg = Vec::new();
                for t in v {
                    match t {
                        Expr::Neg(x) => neg.push(self.expr(x)?),
                        t => pos.push(self.expr(t)?),
                    }
                }
                pos.sort_unstable();
                neg.sort_unstable();
                let mut acc = match pos.split_first() {
                    Some((&f, rest)) => rest.iter().fold(f, |a, &t| self.add(a, t)),
                    None => {
                        let f = neg.remove(0);
                        self.neg(f)
                    }
                };
                for t in neg {
                    acc = self.sub(acc, t);
                }
                acc
            }
            Expr::Mul(v) => {
                if let Some(d) = distributed(v) {
                    return self.expr(&d);
                }
                let mut c = 1.0;
                let mut ids = Vec::new();
                for f in v {
                    match f {
                        Expr::Num(q) => c *= q.to_f64().unwrap_or(f64::NAN),
                        Expr::Sqrt(n) => c *= (*n as f64).sqrt(),
                        Expr::Pow(b, n) => {
                            let id = self.expr(b)?;
                            ids.extend((0..*n).map(|_| id));
                        }
                        f => ids.push(self.expr(f)?),
                    }
                }
                ids.sort_unstable();
                let mut acc = match ids.split_first() {
                    Some((&f, rest)) => rest.iter().fold(f, |a, &t| self.mul(a, t)),
                    None => return Ok(self.constant(c)),
                };
                if c != 1.0 {
                    let k = self.constant(c);
                    acc = self.mul(k, acc);
                }
                acc
            }
            Expr::Neg(x) => {
                let id = self.expr(x)?;
                self.neg(id)
            }
            Expr::Pow(b, n) => {
                let id = self.expr(b)?;
                (1..*n).fold(id, |a, _| self.mul(a, id))
            }
        })
    }

    fn atom(&mut self, angle: Angle) -> (Id, Id) {
        let i = match self.atom_index.get(&angle) {
            Some(&i) => i,
            None => {
                self.atoms.push(angle.clone());
                self.atom_index.insert(angle, self.atoms.len() - 1);
                self.atoms.len() - 1
            }
        };
        (self.node(Node::Cos(i)), self.node(Node::Sin(i)))
    }

    /// `(cos, sin)` of `a + b` from those of `a` and `b`.
    fn sum_rule(&mut self, (ca, sa): (Id, Id), (cb, sb): (Id, Id)) -> (Id, Id) {
        let (cc, ss) = (self.mul(ca, cb), self.mul(sa, sb));
        let (sc, cs) = (self.mul(sa, cb), self.mul(ca, sb));
        (self.sub(cc, ss), self.add(sc, cs))
    }

    /// `(cos, sin)` of `n` times the step of `s`.
    fn multiple(&mut self, s: &Sym, n: i64) -> (Id, Id) {
        if let Some(&cs) = self.trig.get(&vec![(s.clone(), n)]) {
            return cs;
        }
        let cs = if n < 0 {
            let (c, s1) = self.multiple(s, -n);
            (c, self.neg(s1))
        } else if n == 1 {
            let step = self.step[s];
            self.atom(Angle::new(
                vec![(s.clone(), step)],
                Small::zero(),
                Small::zero(),
            ))
        } else {
            let half = self.multiple(s, n / 2);
            let double = self.sum_rule(half, half);
            if n % 2 == 0 {
                double
            } else {
                let one = self.multiple(s, 1);
                self.sum_rule(double, one)
            }
        };
        self.trig.insert(vec![(s.clone(), n)], cs);
        cs
    }

    fn cos_sin(&mut self, angle: &Angle) -> Result<(Id, Id), CodegenError> {
        for (s, _) in &angle.terms {
            if !self.args.iter().any(|a| a == s.name()) {
                return Err(CodegenError::Unbound(s.name().to_string()));
            }
        }
        let sym_terms: Vec<(Sym, Small)> = angle.terms.clone();
        let unit: f64 = angle.constant.to_f64().unwrap_or(f64::NAN);
        let var = if sym_terms.is_empty() {
            None
        } else if self.o.expand_angles {
            // Prefix sums in symbol order, memoized: (t1 + t4)/2 serves (t1 + t4 +- t6)/2.
            let key: Vec<(Sym, i64)> = sym_terms
                .iter()
                .map(|(s, k)| (s.clone(), (*k / self.step[s]).to_integer()))
                .collect();
            let mut acc = self.multiple(&key[0].0, key[0].1);
            for i in 1..key.len() {
                let prefix = key[..=i].to_vec();
                acc = match self.trig.get(&prefix) {
                    Some(&cs) => cs,
                    None => {
                        let next = self.multiple(&key[i].0, key[i].1);
                        let cs = self.sum_rule(acc, next);
                        self.trig.insert(prefix, cs);
                        cs
                    }
                };
            }
            Some(acc)
        } else {
            Some(self.atom(Angle::new(sym_terms, Small::zero(), Small::zero())))
        };
        // The constant part: quarter turns exactly, any other constant numerically.
        let quarter = angle.pi * Small::from_integer(2);
        let (turns, rest) = if quarter.is_integer() {
            (quarter.to_integer().rem_euclid(4), unit)
        } else {
            (
                0,
                unit + angle.pi.to_f64().unwrap_or(f64::NAN) * std::f64::consts::PI,
            )
        };
        let mut cs = match var {
            Some(v) if rest == 0.0 => v,
            Some(v) => {
                let k = (self.constant(rest.cos()), self.constant(rest.sin()));
                self.sum_rule(v, k)
            }
            None => (self.constant(rest.cos()), self.constant(rest.sin())),
        };
        for _ in 0..turns {
            // cos(x + pi/2) = -sin x, sin(x + pi/2) = cos x.
            cs = (self.neg(cs.1), cs.0);
        }
        Ok(cs)
    }

    fn finish(self, outputs: Vec<(Output, Vec<Id>)>, names: &[String]) -> Program {
        let mut uses = vec![0usize; self.nodes.len()];
        let mut reached = vec![false; self.nodes.len()];
        let mut stack: Vec<Id> = Vec::new();
        for (_, ids) in &outputs {
            for &id in ids {
                uses[id] += 1;
                stack.push(id);
            }
        }
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut reached[id], true) {
                continue;
            }
            let kids: Vec<Id> = match self.nodes[id] {
                Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) => vec![a, b],
                Node::Neg(a) => vec![a],
                _ => vec![],
            };
            for k in kids {
                uses[k] += 1;
                stack.push(k);
            }
        }
        let mut taken: HashSet<String> = self.args.iter().chain(names).cloned().collect();
        let atoms: Vec<Atom> = self
            .atoms
            .iter()
            .enumerate()
            .map(|(i, a)| {
                let (s, c) = atom_names(a, i, &taken);
                taken.insert(s.clone());
                taken.insert(c.clone());
                Atom {
                    angle: a.clone(),
                    sin_name: s,
                    cos_name: c,
                }
            })
            .collect();
        // An intermediate entry read more than once is a local named after it (`q2_3`): the
        // first entry of a node names it, unless an argument or angle took the name.
        let mut entry_name: HashMap<Id, String> = HashMap::new();
        for (id, local) in &self.locals {
            let compound = matches!(
                self.nodes[*id],
                Node::Add(..) | Node::Sub(..) | Node::Mul(..) | Node::Neg(_)
            );
            if compound
                && uses[*id] > 1
                && !entry_name.contains_key(id)
                && taken.insert(local.clone())
            {
                entry_name.insert(*id, local.clone());
            }
        }
        // A prefix no argument, angle or local name is the prefix of, followed by digits.
        let clash = |p: &str| {
            taken.iter().any(|n| {
                n.strip_prefix(p)
                    .is_some_and(|d| d.chars().all(|c| c.is_ascii_digit()))
            })
        };
        let prefix = ["t", "tmp", "x_"]
            .into_iter()
            .find(|p| !clash(p))
            .unwrap_or("dqsym_t");
        let mut temp = HashMap::new();
        let mut generic = 0;
        for (id, n) in self.nodes.iter().enumerate() {
            let compound = matches!(
                n,
                Node::Add(..) | Node::Sub(..) | Node::Mul(..) | Node::Neg(_)
            );
            if compound && uses[id] > 1 {
                let name = entry_name.remove(&id).unwrap_or_else(|| {
                    generic += 1;
                    format!("{prefix}{}", generic - 1)
                });
                temp.insert(id, name);
            }
        }
        Program {
            args: self.args.to_vec(),
            names: names.to_vec(),
            atoms,
            nodes: self.nodes,
            uses,
            temp,
            outputs,
        }
    }
}

/// `s1, c1` for theta1, `sh1, ch1` for theta1 / 2, `s23, c23` for theta2 + theta3, else
/// `s_a<i>, c_a<i>`.
fn atom_names(a: &Angle, i: usize, taken: &HashSet<String>) -> (String, String) {
    let short = shorthand_name(Trig::Sin, a)
        .map(|s| s[1..].to_string())
        .or_else(|| {
            let half = a.scaled(Small::from_integer(2));
            let h = shorthand_name(Trig::Sin, &half)?;
            Some(format!("h{}", &h[1..]))
        });
    let body = short
        .map(|b| b.replace(',', "_"))
        .unwrap_or_else(|| format!("_a{i}"));
    let (mut s, mut c) = (format!("s{body}"), format!("c{body}"));
    while taken.contains(&s) || taken.contains(&c) {
        s.push('_');
        c.push('_');
    }
    (s, c)
}

/// Operator precedence of the C family (shared by Rust and Python for these operators).
const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const UNARY: u8 = 3;

impl Program {
    /// Whether the sine or cosine of atom `i` is read.
    pub fn atom_used(&self, i: usize, f: Trig) -> bool {
        let n = match f {
            Trig::Cos => Node::Cos(i),
            Trig::Sin => Node::Sin(i),
        };
        self.nodes
            .iter()
            .position(|x| *x == n)
            .is_some_and(|id| self.uses[id] > 0)
    }

    /// Whether argument `i` is read, directly or in an angle whose sine or cosine is.
    pub fn arg_used(&self, i: usize) -> bool {
        let direct = self
            .nodes
            .iter()
            .position(|x| *x == Node::Arg(i))
            .is_some_and(|id| self.uses[id] > 0);
        direct
            || self.atoms.iter().enumerate().any(|(k, a)| {
                (self.atom_used(k, Trig::Sin) || self.atom_used(k, Trig::Cos))
                    && a.angle.terms.iter().any(|(s, _)| s.name() == self.args[i])
            })
    }

    /// The reachable temporaries, in an order where each follows what it reads.
    pub fn temps(&self) -> Vec<(Id, &str)> {
        let mut v: Vec<(Id, &str)> = self.temp.iter().map(|(&i, n)| (i, n.as_str())).collect();
        v.sort_unstable();
        v
    }

    /// The angle of atom `i` as code: `0.5 * theta1`, `theta2 + theta3`.
    pub fn angle_code(&self, i: usize, lit: &dyn Fn(f64) -> String) -> String {
        let a = &self.atoms[i].angle;
        let mut s = String::new();
        for (k, (sym, c)) in a.terms.iter().enumerate() {
            let neg = c.is_negative();
            s.push_str(match (k, neg) {
                (0, true) => "-",
                (0, false) => "",
                (_, true) => " - ",
                (_, false) => " + ",
            });
            let c = c.abs();
            let name = self
                .args
                .iter()
                .position(|a| a == sym.name())
                .map_or(sym.name(), |i| self.names[i].as_str());
            if c.is_one() {
                s.push_str(name);
            } else {
                s.push_str(&format!("{} * {name}", lit(c.to_f64().unwrap_or(f64::NAN))));
            }
        }
        s
    }

    /// The angle of atom `i` as a comment: `theta1/2`.
    pub fn angle_comment(&self, i: usize) -> String {
        angle_text(&self.atoms[i].angle)
    }

    /// Node `id` as an expression: temporaries by name, single-use nodes inline.
    pub fn code(&self, id: Id, lit: &dyn Fn(f64) -> String) -> String {
        self.code_at(id, 0, lit, true)
    }

    /// The defining expression of a temporary (not its name).
    pub fn definition(&self, id: Id, lit: &dyn Fn(f64) -> String) -> String {
        self.code_at(id, 0, lit, false)
    }

    fn code_at(&self, id: Id, prec: u8, lit: &dyn Fn(f64) -> String, named: bool) -> String {
        if named {
            if let Some(n) = self.temp.get(&id) {
                return n.clone();
            }
        }
        let (text, p) = match &self.nodes[id] {
            Node::Arg(i) => (self.names[*i].clone(), 9),
            Node::Const(b) => (lit(f64::from_bits(*b)), 9),
            Node::Sin(i) => (self.atoms[*i].sin_name.clone(), 9),
            Node::Cos(i) => (self.atoms[*i].cos_name.clone(), 9),
            Node::Add(a, b) => (
                format!(
                    "{} + {}",
                    self.code_at(*a, SUM, lit, true),
                    self.code_at(*b, SUM, lit, true)
                ),
                SUM,
            ),
            Node::Sub(a, b) => (
                format!(
                    "{} - {}",
                    self.code_at(*a, SUM, lit, true),
                    self.code_at(*b, PRODUCT, lit, true)
                ),
                SUM,
            ),
            Node::Mul(a, b) => (
                format!(
                    "{} * {}",
                    self.code_at(*a, PRODUCT, lit, true),
                    self.code_at(*b, PRODUCT, lit, true)
                ),
                PRODUCT,
            ),
            Node::Neg(a) => (format!("-{}", self.code_at(*a, UNARY, lit, true)), UNARY),
        };
        if p < prec {
            format!("({text})")
        } else {
            text
        }
    }

    /// What evaluating the program costs: every reachable operation once.
    pub fn count(&self) -> OpCount {
        let mut c = OpCount::default();
        for (id, n) in self.nodes.iter().enumerate() {
            if self.uses[id] == 0 {
                continue;
            }
            match n {
                Node::Add(..) | Node::Sub(..) => c.add += 1,
                Node::Mul(..) => c.mul += 1,
                Node::Neg(_) => c.neg += 1,
                Node::Sin(_) | Node::Cos(_) => c.trig += 1,
                _ => {}
            }
        }
        c
    }
}

/// The constants of `std::f64::consts` (clippy's `approx_constant` rejects their digits).
pub(crate) const STD_CONSTS: &[(&str, f64)] = &[
    ("PI", std::f64::consts::PI),
    ("TAU", std::f64::consts::TAU),
    ("E", std::f64::consts::E),
    ("FRAC_1_PI", std::f64::consts::FRAC_1_PI),
    ("FRAC_2_PI", std::f64::consts::FRAC_2_PI),
    ("FRAC_2_SQRT_PI", std::f64::consts::FRAC_2_SQRT_PI),
    ("FRAC_PI_2", std::f64::consts::FRAC_PI_2),
    ("FRAC_PI_3", std::f64::consts::FRAC_PI_3),
    ("FRAC_PI_4", std::f64::consts::FRAC_PI_4),
    ("FRAC_PI_6", std::f64::consts::FRAC_PI_6),
    ("FRAC_PI_8", std::f64::consts::FRAC_PI_8),
    ("SQRT_2", std::f64::consts::SQRT_2),
    ("FRAC_1_SQRT_2", std::f64::consts::FRAC_1_SQRT_2),
    ("LN_2", std::f64::consts::LN_2),
    ("LN_10", std::f64::consts::LN_10),
    ("LOG2_E", std::f64::consts::LOG2_E),
    ("LOG10_E", std::f64::consts::LOG10_E),
    ("LOG2_10", std::f64::consts::LOG2_10),
    ("LOG10_2", std::f64::consts::LOG10_2),
];
