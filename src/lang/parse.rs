//! From text to [`Program`]: the pest parser, the Pratt table, and one lowering function per
//! grammar rule.
//!
//! A parse runs three stages, each of which may reject the input with a [`ParseError`]:
//! 1. the pre-scan ([`prescan`]), a flat loop over bytes, so that nothing recursive ever sees
//!    more than `max_depth` nested brackets and pest never sees a line longer than
//!    `max_line_len`;
//! 2. pest, on the grammar in `grammar/dqsym.pest`;
//! 3. lowering, which builds the tree, checks what the grammar accepts only to explain
//!    (`1.5`, `2x`, keywords as names, `a*b = 1`), and bounds the depth of the tree.
//!
//! No stage recurses deeper than the nesting of the input, which stages 1 and 3 bound, so no
//! input can overflow the stack; every stage is linear in the input.

use super::ast::{AddOp, Expr, ExprKind, Ident, MulOp, Program, Span, Stmt, StmtKind, UnaryOp};
use super::error::{from_pest, ParseError, ParseErrorKind};
use super::names::normalize_name;
use super::scan::{blank, prescan, SourceMap};
use crate::scalar::parse_decimal;
use num_bigint::BigUint;
use pest::iterators::Pair;
use pest::pratt_parser::{pratt_precedence, Assoc, ConstPrattParser, Op};
use pest::Parser;

/// The pest parser generated from the grammar.
#[derive(pest_derive::Parser)]
#[grammar = "../grammar/dqsym.pest"]
pub(crate) struct DqParser;

/// Operator precedence, loosest first: `+ -`, then `* /`, then unary minus, then `^` (right
/// associative, so `-x^2` is `-(x^2)` and `2^-1` is `2^(-1)`), then postfix `'`.
static PRATT: ConstPrattParser<Rule, 8> = ConstPrattParser::new_const(pratt_precedence![
    Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left),
    Op::infix(Rule::mul, Assoc::Left) | Op::infix(Rule::div, Assoc::Left),
    Op::prefix(Rule::neg) | Op::prefix(Rule::plus),
    Op::infix(Rule::pow, Assoc::Right),
    Op::postfix(Rule::conj),
]);

/// Limits that keep parsing of hostile input fast and safe.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseOptions {
    /// Deepest allowed nesting, counted both in brackets and in levels of the tree (each
    /// operator or call adds a level). Recursive code downstream (the evaluator, `Display`,
    /// `Drop`) relies on it.
    pub max_depth: usize,
    /// Longest allowed integer literal, in digits. Converting decimal digits to binary is
    /// quadratic, so a 1 MB literal would take seconds.
    pub max_integer_digits: usize,
    /// Longest allowed line, in bytes. pest costs a few microseconds per token, so this bounds
    /// the time a single line can take.
    pub max_line_len: usize,
}

/// The default [`ParseOptions::max_depth`].
pub const DEFAULT_MAX_DEPTH: usize = 256;

impl Default for ParseOptions {
    fn default() -> Self {
        ParseOptions {
            max_depth: DEFAULT_MAX_DEPTH,
            max_integer_digits: 10_000,
            max_line_len: 65_536,
        }
    }
}

/// Parses a script with the default [`ParseOptions`].
pub fn parse(src: &str) -> std::result::Result<Program, ParseError> {
    parse_with(src, &ParseOptions::default())
}

/// Parses a script.
pub fn parse_with(src: &str, options: &ParseOptions) -> std::result::Result<Program, ParseError> {
    let map = SourceMap::new(src);
    let text = scanned(&map, options)?;
    let lower = Lower {
        map,
        text: &text,
        options,
    };
    let pair = lower.run(Rule::program)?;
    lower.program(pair)
}

/// Runs the bracket pre-scan over `map`; the text the grammar reads (line breaks inside
/// parentheses as spaces).
fn scanned<'s>(
    map: &SourceMap<'s>,
    options: &ParseOptions,
) -> std::result::Result<std::borrow::Cow<'s, str>, ParseError> {
    let ranges = prescan(map, options.max_depth, options.max_line_len)
        .map_err(|(kind, start, end)| ParseError::new(map, kind, start, end))?;
    Ok(blank(map.src(), &ranges))
}

/// Parses a single expression (all of `src`) with the default [`ParseOptions`].
pub fn parse_expr(src: &str) -> std::result::Result<Expr, ParseError> {
    parse_expr_with(src, &ParseOptions::default())
}

/// Parses a single expression (all of `src`).
pub fn parse_expr_with(src: &str, options: &ParseOptions) -> std::result::Result<Expr, ParseError> {
    let map = SourceMap::new(src);
    let text = scanned(&map, options)?;
    let lower = Lower {
        map,
        text: &text,
        options,
    };
    let pair = lower.run(Rule::expression)?;
    let expr = pair.into_inner().next().expect("expression holds an expr");
    Ok(lower.expr(expr)?.expr)
}

/// A lowered expression with the height of its tree, which lowering bounds.
struct Node {
    expr: Expr,
    height: usize,
}

/// An expression being folded by the Pratt parser. `open` marks a sum or product built by the
/// current fold that a following operator of the same level extends; one that came from
/// parentheses is closed, so `(a + b) + c` keeps its shape and printing round-trips.
struct Folded {
    node: Node,
    open: bool,
}

type Result<T> = std::result::Result<T, ParseError>;

/// Lowering state: the source map, the text the grammar reads (the source with line breaks
/// inside parentheses as spaces, byte for byte as long) and the limits.
struct Lower<'s> {
    map: SourceMap<'s>,
    text: &'s str,
    options: &'s ParseOptions,
}

impl<'s> Lower<'s> {
    /// Runs pest from `rule` and returns its single top pair.
    fn run(&self, rule: Rule) -> Result<Pair<'s, Rule>> {
        let mut pairs = DqParser::parse(rule, self.text).map_err(|e| from_pest(&self.map, e))?;
        Ok(pairs.next().expect("a successful parse has a top pair"))
    }

    fn error(&self, kind: ParseErrorKind, start: usize, end: usize) -> ParseError {
        ParseError::new(&self.map, kind, start, end)
    }

    fn error_at(&self, kind: ParseErrorKind, pair: &Pair<'_, Rule>) -> ParseError {
        let span = self.span(pair);
        self.error(kind, span.start, span.end)
    }

    /// The span of `pair` without trailing whitespace and comments, which pest includes in a
    /// rule when an optional or repeated part after them fails to match (`x % note` in
    /// `name ~ args?`). Every rule ends with a token rule or is atomic, so the end of the
    /// innermost last pair is the end of the last token.
    fn span(&self, pair: &Pair<'_, Rule>) -> Span {
        let mut last = pair.clone();
        while let Some(inner) = last.clone().into_inner().last() {
            last = inner;
        }
        self.map.span(pair.as_span().start(), last.as_span().end())
    }

    /// Wraps `kind` at `span` as a node `height` levels high, refusing it above the limit.
    fn node(&self, kind: ExprKind, span: Span, height: usize) -> Result<Node> {
        if height > self.options.max_depth {
            let limit = self.options.max_depth;
            return Err(self.error(
                ParseErrorKind::TooDeep { limit },
                span.start,
                span.start + 1,
            ));
        }
        Ok(Node {
            expr: Expr { kind, span },
            height,
        })
    }

    /// `program`: the statements, skipping separators.
    fn program(&self, pair: Pair<'s, Rule>) -> Result<Program> {
        let mut statements = Vec::new();
        let mut pairs = pair.into_inner().peekable();
        while let Some(p) = pairs.next() {
            let span = self.span(&p);
            let kind = match p.as_rule() {
                Rule::syms_decl => self.syms_decl(p)?,
                Rule::halfangle_decl => self.halfangle_decl(p)?,
                Rule::expr_statement => self.expr_statement(p)?,
                _ => continue, // separators and EOI
            };
            let quiet = pairs
                .peek()
                .is_some_and(|next| next.as_rule() == Rule::separator && next.as_str() == ";");
            statements.push(Stmt { kind, span, quiet });
        }
        Ok(Program { statements })
    }

    /// `syms_decl`: at least one name.
    fn syms_decl(&self, pair: Pair<'s, Rule>) -> Result<StmtKind> {
        let keyword = pair
            .clone()
            .into_inner()
            .next()
            .expect("syms_decl has its keyword");
        let names: Vec<Ident> = pair
            .into_inner()
            .filter(|p| p.as_rule() == Rule::name)
            .map(|p| self.name(&p))
            .collect();
        if names.is_empty() {
            return Err(self.error_at(ParseErrorKind::EmptySyms, &keyword));
        }
        Ok(StmtKind::Syms(names))
    }

    /// `halfangle_decl`: two names and the angle.
    fn halfangle_decl(&self, pair: Pair<'s, Rule>) -> Result<StmtKind> {
        let mut names = Vec::new();
        let mut angle = None;
        for p in pair.into_inner() {
            match p.as_rule() {
                Rule::name => names.push(self.name(&p)),
                Rule::expr => angle = Some(self.expr(p)?.expr),
                _ => {}
            }
        }
        let [cos, sin] = <[Ident; 2]>::try_from(names).expect("halfangle_decl has two names");
        let angle = angle.expect("halfangle_decl has an angle");
        Ok(StmtKind::HalfAngle { cos, sin, angle })
    }

    /// `expr_statement`: an expression, or an assignment whose left side must have lowered to a
    /// plain name.
    fn expr_statement(&self, pair: Pair<'s, Rule>) -> Result<StmtKind> {
        let mut exprs = pair.into_inner().filter(|p| p.as_rule() == Rule::expr);
        let first = self
            .expr(exprs.next().expect("expr_statement has an expr"))?
            .expr;
        let Some(value) = exprs.next() else {
            return Ok(StmtKind::Expr(first));
        };
        let value = self.expr(value)?.expr;
        match first.kind {
            ExprKind::Name(name) => Ok(StmtKind::Assign {
                name: Ident {
                    name,
                    span: first.span,
                },
                value,
            }),
            _ => {
                let (start, end) = (first.span.start, first.span.end);
                Err(self.error(ParseErrorKind::AssignToExpr, start, end))
            }
        }
    }

    /// `expr`: the Pratt fold over operands and operators.
    fn expr(&self, pair: Pair<'s, Rule>) -> Result<Node> {
        self.check_pending_operators(&pair)?;
        let folded = PRATT
            .map_primary(|p| {
                Ok(Folded {
                    node: self.primary(p)?,
                    open: false,
                })
            })
            .map_prefix(|op, rhs| self.prefix(op, rhs?))
            .map_postfix(|lhs, op| self.postfix(lhs?, op))
            .map_infix(|lhs, op, rhs| self.infix(lhs?, op, rhs?))
            .parse(pair.into_inner())?;
        Ok(folded.node)
    }

    /// Refuses runs of prefix operators and powers longer than `max_depth` before the Pratt
    /// parser sees them: it recurses once per such operator (`- - - x`, `x^x^x`), and each one
    /// nests the tree a level deeper. A looser operator (`+ - * /`) ends every pending one.
    fn check_pending_operators(&self, pair: &Pair<'s, Rule>) -> Result<()> {
        let mut pending = 0;
        for p in pair.clone().into_inner() {
            match p.as_rule() {
                Rule::neg | Rule::plus | Rule::pow => pending += 1,
                Rule::add | Rule::sub | Rule::mul | Rule::div => pending = 0,
                _ => {}
            }
            if pending > self.options.max_depth {
                let limit = self.options.max_depth;
                return Err(self.error_at(ParseErrorKind::TooDeep { limit }, &p));
            }
        }
        Ok(())
    }

    /// Prefix operators: `-x` becomes a node, `+x` is `x`.
    fn prefix(&self, op: Pair<'s, Rule>, rhs: Folded) -> Result<Folded> {
        let span = self.map.span(op.as_span().start(), rhs.node.expr.span.end);
        let node = match op.as_rule() {
            Rule::neg => {
                let operand = Box::new(rhs.node.expr);
                let kind = ExprKind::Unary {
                    op: UnaryOp::Neg,
                    operand,
                };
                self.node(kind, span, rhs.node.height + 1)?
            }
            _ => Node {
                expr: Expr {
                    kind: rhs.node.expr.kind,
                    span,
                },
                height: rhs.node.height,
            },
        };
        Ok(Folded { node, open: false })
    }

    /// Postfix `'`.
    fn postfix(&self, lhs: Folded, op: Pair<'s, Rule>) -> Result<Folded> {
        let span = self.map.span(lhs.node.expr.span.start, op.as_span().end());
        let kind = ExprKind::Unary {
            op: UnaryOp::Conj,
            operand: Box::new(lhs.node.expr),
        };
        let node = self.node(kind, span, lhs.node.height + 1)?;
        Ok(Folded { node, open: false })
    }

    /// Infix operators: `+ -` and `* /` extend an open chain of their level or start one.
    fn infix(&self, lhs: Folded, op: Pair<'s, Rule>, rhs: Folded) -> Result<Folded> {
        let span = self
            .map
            .span(lhs.node.expr.span.start, rhs.node.expr.span.end);
        let height = lhs.node.height.max(rhs.node.height + 1);
        let kind = match (op.as_rule(), lhs.node.expr.kind) {
            (Rule::add | Rule::sub, ExprKind::Sum { first, mut rest }) if lhs.open => {
                rest.push((add_op(&op), rhs.node.expr));
                ExprKind::Sum { first, rest }
            }
            (Rule::mul | Rule::div, ExprKind::Product { first, mut rest }) if lhs.open => {
                rest.push((mul_op(&op), rhs.node.expr));
                ExprKind::Product { first, rest }
            }
            (rule, kind) => {
                let first = Box::new(Expr {
                    kind,
                    span: lhs.node.expr.span,
                });
                let fresh = height.max(lhs.node.height + 1);
                let kind = match rule {
                    Rule::add | Rule::sub => ExprKind::Sum {
                        first,
                        rest: vec![(add_op(&op), rhs.node.expr)],
                    },
                    Rule::mul | Rule::div => ExprKind::Product {
                        first,
                        rest: vec![(mul_op(&op), rhs.node.expr)],
                    },
                    _ => ExprKind::Pow {
                        base: first,
                        exponent: Box::new(rhs.node.expr),
                    },
                };
                let open = !matches!(kind, ExprKind::Pow { .. });
                let node = self.node(kind, span, fresh)?;
                return Ok(Folded { node, open });
            }
        };
        let node = self.node(kind, span, height)?;
        Ok(Folded { node, open: true })
    }

    /// The primaries: numbers, names and calls, parentheses, matrices, and keywords (accepted
    /// only to be explained).
    fn primary(&self, pair: Pair<'s, Rule>) -> Result<Node> {
        match pair.as_rule() {
            Rule::reference => self.reference(pair),
            Rule::number => self.number(&pair),
            Rule::paren => self.paren(pair),
            Rule::matrix => self.matrix(pair),
            Rule::keyword => {
                let word = pair.as_str().to_owned();
                Err(self.error_at(ParseErrorKind::Keyword { word }, &pair))
            }
            rule => unreachable!("{rule:?} is not a primary"),
        }
    }

    /// `number`: an integer, a decimal or scientific literal (exact: `0.4318` is 2159/5000),
    /// each within the digit limit, or a number of degrees (`90deg`); other names run into a
    /// number are refused with the fix to write.
    fn number(&self, pair: &Pair<'s, Rule>) -> Result<Node> {
        let text = pair.as_str();
        let (number, name) = split_number(text);
        if !name.is_empty() && name != "deg" {
            let kind = ParseErrorKind::GluedNumber {
                number: number.to_owned(),
                name: name.to_owned(),
            };
            return Err(self.error_at(kind, pair));
        }
        let limit = self.options.max_integer_digits;
        let span = self.span(pair);
        if name.is_empty() && number.bytes().all(|b| b.is_ascii_digit()) {
            if text.len() > limit {
                let digits = text.len();
                return Err(self.error_at(ParseErrorKind::LongInteger { digits, limit }, pair));
            }
            let value = BigUint::parse_bytes(text.as_bytes(), 10).expect("integer is digits");
            return self.node(ExprKind::Int(value), span, 1);
        }
        let Some(value) = parse_decimal(number, limit) else {
            let literal = number.to_owned();
            let (start, end) = (
                pair.as_span().start(),
                pair.as_span().start() + number.len(),
            );
            return Err(self.error(ParseErrorKind::LongDecimal { literal, limit }, start, end));
        };
        let text = number.to_owned();
        let kind = if name == "deg" {
            ExprKind::Degrees { text, value }
        } else {
            ExprKind::Decimal { text, value }
        };
        self.node(kind, span, 1)
    }

    /// `reference`: a name, or a call when an argument list (even an empty one) follows.
    fn reference(&self, pair: Pair<'s, Rule>) -> Result<Node> {
        let span = self.span(&pair);
        let mut inner = pair.into_inner().peekable();
        let func = self.name(&inner.next().expect("reference starts with a name"));
        if inner.peek().is_none() {
            return self.node(ExprKind::Name(func.name), span, 1);
        }
        let (args, height) = self.exprs(inner)?;
        self.node(ExprKind::Call { func, args }, span, height + 1)
    }

    /// `name`, with Greek letters spelled out.
    fn name(&self, pair: &Pair<'s, Rule>) -> Ident {
        Ident {
            name: normalize_name(pair.as_str()),
            span: self.span(pair),
        }
    }

    /// The expressions among `pairs` (skipping commas and closing brackets), lowered, with
    /// their greatest height.
    fn exprs(&self, pairs: impl Iterator<Item = Pair<'s, Rule>>) -> Result<(Vec<Expr>, usize)> {
        let mut out = Vec::new();
        let mut height = 0;
        for p in pairs.filter(|p| p.as_rule() == Rule::expr) {
            let node = self.expr(p)?;
            height = height.max(node.height);
            out.push(node.expr);
        }
        Ok((out, height))
    }

    /// `paren`: grouping for one expression (whose span grows to the parentheses), a tuple
    /// for more.
    fn paren(&self, pair: Pair<'s, Rule>) -> Result<Node> {
        let span = self.span(&pair);
        let (mut items, height) = self.exprs(pair.into_inner())?;
        if items.len() == 1 {
            let mut expr = items.pop().expect("one item");
            expr.span = span;
            return Ok(Node { expr, height });
        }
        self.node(ExprKind::Tuple(items), span, height + 1)
    }

    /// `matrix`: rows of equal length.
    fn matrix(&self, pair: Pair<'s, Rule>) -> Result<Node> {
        let span = self.span(&pair);
        let mut rows: Vec<Vec<Expr>> = Vec::new();
        let mut height = 0;
        for row in pair.into_inner().filter(|p| p.as_rule() == Rule::row) {
            let row_pair = row.clone();
            let (items, h) = self.exprs(row.into_inner())?;
            if let Some(first) = rows.first() {
                if items.len() != first.len() {
                    let kind = ParseErrorKind::RaggedMatrix {
                        row: rows.len() + 1,
                        len: items.len(),
                        first: first.len(),
                    };
                    return Err(self.error_at(kind, &row_pair));
                }
            }
            height = height.max(h);
            rows.push(items);
        }
        self.node(ExprKind::Matrix(rows), span, height + 1)
    }
}

/// Splits a `number` token into its numeric literal and the name run into it: `2x` gives
/// `("2", "x")`, `1.5e3` gives `("1.5e3", "")`, `2e` gives `("2", "e")`.
fn split_number(text: &str) -> (&str, &str) {
    let b = text.as_bytes();
    let digits = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        i
    };
    let mut i = digits(0);
    if b.get(i) == Some(&b'.') {
        i = digits(i + 1);
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(i + 1), Some(b'+' | b'-')));
        let end = digits(i + 1 + sign);
        if end > i + 1 + sign {
            i = end;
        }
    }
    text.split_at(i)
}

/// The [`AddOp`] of an `add` or `sub` pair.
fn add_op(op: &Pair<'_, Rule>) -> AddOp {
    if op.as_rule() == Rule::add {
        AddOp::Add
    } else {
        AddOp::Sub
    }
}

/// The [`MulOp`] of a `mul` or `div` pair.
fn mul_op(op: &Pair<'_, Rule>) -> MulOp {
    if op.as_rule() == Rule::mul {
        MulOp::Mul
    } else {
        MulOp::Div
    }
}
