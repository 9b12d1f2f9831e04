//! The script parser: good inputs, precedence, Greek names, spans, printing round trips,
//! hostile input, and one snapshot per bad input in tests/data/bad.

use dqsym::{
    lang::{
        parse_expr, parse_with, AddOp, Expr as AstExpr, ExprKind, MulOp, ParseErrorKind,
        ParseOptions, StmtKind, UnaryOp,
    },
    parse, Session,
};
use proptest::prelude::*;

/// Snapshots live in the top-level snapshots/ folder, named after the test alone.
fn snapshot_settings() -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/snapshots"));
    settings.set_prepend_module_to_snapshot(false);
    settings
}

/// The tree as an s-expression, to state precedence and associativity exactly.
fn sexpr(e: &AstExpr) -> String {
    let join = |items: &[AstExpr]| items.iter().map(sexpr).collect::<Vec<_>>().join(" ");
    match &e.kind {
        ExprKind::Int(n) => n.to_string(),
        ExprKind::Decimal { text, .. } => text.clone(),
        ExprKind::Degrees { text, .. } => format!("{text}deg"),
        ExprKind::Name(name) => name.clone(),
        ExprKind::Unary { op, operand } => {
            let op = if *op == UnaryOp::Neg { "neg" } else { "conj" };
            format!("({op} {})", sexpr(operand))
        }
        ExprKind::Sum { first, rest } => {
            let mut out = format!("(sum {}", sexpr(first));
            for (op, term) in rest {
                let sign = if *op == AddOp::Add { "+" } else { "-" };
                out += &format!(" {sign}{}", sexpr(term));
            }
            out + ")"
        }
        ExprKind::Product { first, rest } => {
            let mut out = format!("(prod {}", sexpr(first));
            for (op, factor) in rest {
                let op = if *op == MulOp::Mul { "*" } else { "/" };
                out += &format!(" {op}{}", sexpr(factor));
            }
            out + ")"
        }
        ExprKind::Pow { base, exponent } => format!("(^ {} {})", sexpr(base), sexpr(exponent)),
        ExprKind::Call { func, args } => format!("({} {})", func.name, join(args)),
        ExprKind::Tuple(items) => format!("(tuple {})", join(items)),
        ExprKind::Matrix(rows) => {
            let rows: Vec<String> = rows.iter().map(|r| format!("[{}]", join(r))).collect();
            format!("(matrix {})", rows.join(" "))
        }
    }
}

fn tree(src: &str) -> String {
    sexpr(&parse_expr(src).unwrap_or_else(|e| panic!("{src:?} should parse:\n{e}")))
}

fn error_kind(src: &str) -> ParseErrorKind {
    parse(src).expect_err("should fail").kind().clone()
}

#[test]
fn appendix3_listing_parses_and_prints_as_snapshot() {
    let src = include_str!("../../examples/appendix3_rrr.dq");
    let program = parse(src).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(program.statements.len(), 16);
    snapshot_settings().bind(|| insta::assert_snapshot!(program.to_string()));
}

#[test]
fn appendix2_listing_runs_verbatim() {
    let src = "syms q1\nsyms I\nsyms q2\nsyms q3\nsyms q4\nsyms qa\nsyms qb\n\
               qa=q1+I*q2\nqb=q3+I*q4\nQ=qa*qb\n";
    let program = parse(src).unwrap();
    assert_eq!(program.to_string().lines().last(), Some("Q = qa*qb"));
}

#[test]
fn dual_quaternion_literal_is_tuple_plus_dual_unit_times_vector() {
    assert_eq!(
        tree("(c3,s3,0,0)+I*(0,0,-(l1+l2)*s3)"),
        "(sum (tuple c3 s3 0 0) +(prod I *(tuple 0 0 (prod (neg (sum l1 +l2)) *s3))))"
    );
    assert_eq!(
        tree("1+eps*(0,l1+l2+l3,0)"),
        "(sum 1 +(prod eps *(tuple 0 (sum l1 +l2 +l3) 0)))"
    );
}

#[test]
fn power_binds_tighter_than_unary_minus_and_is_right_associative() {
    assert_eq!(tree("-x^2"), "(neg (^ x 2))");
    assert_eq!(tree("a^b^c"), "(^ a (^ b c))");
    assert_eq!(tree("2^-3*4"), "(prod (^ 2 (neg 3)) *4)");
    assert_eq!(tree("-a*b"), "(prod (neg a) *b)");
    assert_eq!(tree("a - -b"), "(sum a -(neg b))");
}

#[test]
fn sums_and_products_are_left_to_right_chains() {
    assert_eq!(tree("a - b + c"), "(sum a -b +c)");
    assert_eq!(tree("a/b*c"), "(prod a /b *c)");
    assert_eq!(
        tree("a + b*c - d/e^f"),
        "(sum a +(prod b *c) -(prod d /(^ e f)))"
    );
    assert_eq!(tree("(a + b) + c"), "(sum (sum a +b) +c)");
    assert_eq!(tree("a*(b*c)"), "(prod a *(prod b *c))");
}

#[test]
fn postfix_conjugate_binds_tightest() {
    assert_eq!(tree("-q'"), "(neg (conj q))");
    assert_eq!(tree("a*b'"), "(prod a *(conj b))");
    assert_eq!(tree("q''^2"), "(^ (conj (conj q)) 2)");
    assert_eq!(tree("(a*b)'"), "(conj (prod a *b))");
}

#[test]
fn unary_plus_is_dropped() {
    assert_eq!(tree("+x"), "x");
    assert_eq!(tree("a*+b"), "(prod a *b)");
}

#[test]
fn calls_tuples_grouping_and_matrices() {
    assert_eq!(tree("f()"), "(f )");
    assert_eq!(
        tree("conj(q) + dconj(q) + cconj(q)"),
        "(sum (conj q) +(dconj q) +(cconj q))"
    );
    assert_eq!(tree("((x))"), "x");
    assert_eq!(tree("(x, (y, z))"), "(tuple x (tuple y z))");
    assert_eq!(tree("[a, b; c, d]"), "(matrix [a b] [c d])");
    assert_eq!(tree("[1, 2\n 3, 4;]"), "(matrix [1 2] [3 4])");
}

#[test]
fn greek_letters_name_the_same_symbols_as_their_spelling() {
    assert_eq!(
        parse_expr("θ1").unwrap().kind,
        ExprKind::Name("theta1".into())
    );
    assert_eq!(tree("α + β_2 + ε + π"), "(sum alpha +beta_2 +eps +pi)");
    let mut greek = parse_expr("cos(θ1)*ε").unwrap();
    let mut ascii = parse_expr("cos(theta1)*eps").unwrap();
    greek.erase_spans();
    ascii.erase_spans();
    assert_eq!(greek, ascii);
}

#[test]
fn statements_of_every_kind() {
    let program =
        parse("syms a b; halfangle c3, s3 = θ3\r\nx = a + b % sum\n\n# note\nx // show").unwrap();
    let kinds: Vec<&StmtKind> = program.statements.iter().map(|s| &s.kind).collect();
    assert!(matches!(kinds[0], StmtKind::Syms(names) if names.len() == 2));
    assert!(
        matches!(kinds[1], StmtKind::HalfAngle { cos, sin, .. } if cos.name == "c3" && sin.name == "s3")
    );
    assert!(matches!(kinds[2], StmtKind::Assign { name, .. } if name.name == "x"));
    assert!(matches!(kinds[3], StmtKind::Expr(_)));
    assert_eq!(kinds.len(), 4);
}

#[test]
fn keywords_only_reserve_whole_words() {
    assert_eq!(tree("symsx + halfangles"), "(sum symsx +halfangles)");
}

#[test]
fn spans_give_line_and_character_column() {
    let program = parse("x = 1\n  θ1 = c1 + s1*θ2").unwrap();
    let StmtKind::Assign { name, value } = &program.statements[1].kind else {
        panic!("an assignment");
    };
    assert_eq!((name.span.line, name.span.col), (2, 3));
    assert_eq!((value.span.line, value.span.col), (2, 8));
    let ExprKind::Sum { rest, .. } = &value.kind else {
        panic!("a sum");
    };
    assert_eq!(rest[0].1.span.col, 13);
    assert_eq!(
        &"x = 1\n  θ1 = c1 + s1*θ2"[value.span.start..value.span.end],
        "c1 + s1*θ2"
    );
}

#[test]
fn errors_carry_line_column_and_a_caret() {
    let err = parse("x = 1\ny = (1 + )").unwrap_err();
    assert_eq!((err.line(), err.col()), (2, 10));
    assert_eq!(err.message(), "expected an expression, found `)`");
    assert_eq!(
        err.to_string(),
        "error: expected an expression, found `)`\n --> 2:10\n  |\n2 | y = (1 + )\n  |          ^"
    );
}

#[test]
fn decimals_and_degrees_are_exact_and_print_as_written() {
    for (src, exact) in [
        ("0.4318", "2159/5000"),
        ("1e-3", "1/1000"),
        (".25*l1", "1/4*l1"),
        ("3.", "3"),
        ("2.5E2", "250"),
        ("90deg", "pi/2"),
        ("22.5deg", "pi/8"),
        ("-0.39225", "-1569/4000"),
    ] {
        let program = parse(&format!("x = {src}")).unwrap();
        let mut reference = Session::new();
        reference
            .run(&parse(&format!("syms l1\nx = {exact}")).unwrap())
            .unwrap();
        let mut s = Session::new();
        s.run(&parse("syms l1").unwrap()).unwrap();
        s.run(&program).unwrap();
        assert_eq!(s.get("x"), reference.get("x"), "{src}");
        // The tree prints back as written.
        let printed = program.to_string();
        assert!(printed.contains(src.trim_start_matches('-')), "{printed}");
    }
    assert_eq!(
        error_kind("x = 1e99999"),
        ParseErrorKind::LongDecimal {
            literal: "1e99999".into(),
            limit: 10_000
        }
    );
}

#[test]
fn twenty_thousand_nested_parentheses_are_refused_not_overflowed() {
    let src = format!("{}x{}", "(".repeat(20_000), ")".repeat(20_000));
    assert_eq!(error_kind(&src), ParseErrorKind::TooDeep { limit: 256 });
}

#[test]
fn nesting_up_to_the_limit_parses() {
    let src = format!("{}x{}", "(".repeat(256), ")".repeat(256));
    assert!(parse(&src).is_ok());
    let src = format!("{}x{}", "(".repeat(257), ")".repeat(257));
    assert_eq!(error_kind(&src), ParseErrorKind::TooDeep { limit: 256 });
    let options = ParseOptions {
        max_depth: 4,
        ..ParseOptions::default()
    };
    let err = parse_with("x = -(-(-(-(-(y)))))", &options).unwrap_err();
    assert!(matches!(err.kind(), ParseErrorKind::TooDeep { limit: 4 }));
}

#[test]
fn tree_depth_is_bounded_even_when_bracket_depth_is_not_exceeded() {
    let src = format!("{}y{}", "-f(".repeat(200), ")".repeat(200));
    assert_eq!(error_kind(&src), ParseErrorKind::TooDeep { limit: 256 });
    let src = format!("{}y", "-".repeat(60_000));
    assert_eq!(error_kind(&src), ParseErrorKind::TooDeep { limit: 256 });
}

#[test]
fn long_sums_are_wide_not_deep() {
    let src = format!("x = {}", vec!["a*b"; 5_000].join(" + "));
    let program = parse(&src).unwrap();
    let StmtKind::Assign { value, .. } = &program.statements[0].kind else {
        panic!("an assignment");
    };
    assert!(matches!(&value.kind, ExprKind::Sum { rest, .. } if rest.len() == 4_999));
}

#[test]
fn a_one_megabyte_line_is_refused_at_once() {
    let src = format!("x = {}", "1+".repeat(500_000));
    assert_eq!(error_kind(&src), ParseErrorKind::LongLine { limit: 65_536 });
    let src = format!("x = {}", "θ".repeat(500_000));
    assert_eq!(error_kind(&src), ParseErrorKind::LongLine { limit: 65_536 });
}

#[test]
fn a_line_break_inside_parentheses_continues_the_expression() {
    // The REPL's continuation rule: an open `(` continues onto the next line, in scripts too;
    // a comment before the line break is still a comment.
    let split =
        parse("x = dh(theta1, % the joint\r\n  d1, a1,\n alpha1) + (1 +\n 2)\ny = 3").unwrap();
    let one = parse("x = dh(theta1, d1, a1, alpha1) + (1 + 2)\ny = 3").unwrap();
    assert_eq!(split.to_string(), one.to_string());
    assert_eq!(split.statements.len(), 2);
    assert_eq!(split.statements[1].span.line, 5);
    // Inside a matrix a line break still separates rows.
    let m = parse("m = [f(1,\n 2), 3\n 4, 5]").unwrap();
    assert_eq!(
        m.to_string(),
        parse("m = [f(1, 2), 3; 4, 5]").unwrap().to_string()
    );
}

#[test]
fn bad_inputs_have_clear_messages() {
    snapshot_settings().bind(|| {
        insta::glob!(
            concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data"),
            "bad/*.dq",
            |path| {
                let src = std::fs::read_to_string(path).unwrap();
                let semantic = path
                    .file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("semantic_"));
                let shown = match parse(&src) {
                    Err(e) => {
                        assert!(!semantic, "{path:?} should parse:\n{e}");
                        e.to_string()
                    }
                    Ok(program) => {
                        assert!(semantic, "{path:?} should not parse");
                        let err = Session::new()
                            .run(&program)
                            .expect_err("the evaluator must reject it");
                        let rendered = err.render(&src);
                        assert!(rendered.contains('^'), "{rendered}");
                        let message = err.message();
                        assert!(!message.ends_with('.'), "{message}");
                        assert!(!message.starts_with(char::is_uppercase), "{message}");
                        rendered
                    }
                };
                insta::assert_snapshot!(shown);
            }
        );
    });
}

#[test]
fn messages_are_lowercase_without_trailing_period() {
    for entry in std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bad")).unwrap()
    {
        let src = std::fs::read_to_string(entry.unwrap().path()).unwrap();
        if let Err(e) = parse(&src) {
            let message = e.message();
            assert!(!message.ends_with('.'), "{message}");
            assert!(!message.starts_with(char::is_uppercase), "{message}");
        }
    }
}

/// Trees the parser can produce: names, integers, decimals, degrees, and every operator and
/// bracket form.
fn arb_expr() -> impl Strategy<Value = AstExpr> {
    let name = prop::sample::select(vec!["a", "x1", "theta_2", "I", "eps", "l1"]);
    let leaf = prop_oneof![
        (0u64..1000).prop_map(|n| AstExpr::new(ExprKind::Int(n.into()))),
        (0u64..100_000, 1u32..5, any::<bool>()).prop_map(|(n, places, degrees)| {
            let den = 10u64.pow(places);
            let text = format!("{}.{:0w$}", n / den, n % den, w = places as usize);
            let value = dqsym::scalar::parse_decimal(&text, 100).unwrap();
            AstExpr::new(if degrees {
                ExprKind::Degrees { text, value }
            } else {
                ExprKind::Decimal { text, value }
            })
        }),
        name.prop_map(|n| AstExpr::new(ExprKind::Name(n.into()))),
    ];
    leaf.prop_recursive(5, 48, 4, |inner| {
        let add = prop_oneof![Just(AddOp::Add), Just(AddOp::Sub)];
        let mul = prop_oneof![Just(MulOp::Mul), Just(MulOp::Div)];
        let unary = prop_oneof![Just(UnaryOp::Neg), Just(UnaryOp::Conj)];
        let boxed = |e: AstExpr| Box::new(e);
        prop_oneof![
            (unary, inner.clone()).prop_map(move |(op, e)| AstExpr::new(ExprKind::Unary {
                op,
                operand: boxed(e)
            })),
            (
                inner.clone(),
                prop::collection::vec((add, inner.clone()), 1..3)
            )
                .prop_map(|(first, rest)| AstExpr::new(ExprKind::Sum {
                    first: Box::new(first),
                    rest
                })),
            (
                inner.clone(),
                prop::collection::vec((mul, inner.clone()), 1..3)
            )
                .prop_map(|(first, rest)| AstExpr::new(ExprKind::Product {
                    first: Box::new(first),
                    rest
                })),
            (inner.clone(), inner.clone()).prop_map(|(b, e)| AstExpr::new(ExprKind::Pow {
                base: Box::new(b),
                exponent: Box::new(e)
            })),
            prop::collection::vec(inner.clone(), 2..4)
                .prop_map(|v| AstExpr::new(ExprKind::Tuple(v))),
            prop::collection::vec(inner.clone(), 0..3).prop_map(|args| AstExpr::new(
                ExprKind::Call {
                    func: dqsym::lang::Ident {
                        name: "rot".into(),
                        span: Default::default()
                    },
                    args
                }
            )),
            (1usize..3, 1usize..3)
                .prop_flat_map(move |(r, c)| prop::collection::vec(
                    prop::collection::vec(inner.clone(), c),
                    r
                ))
                .prop_map(|rows| AstExpr::new(ExprKind::Matrix(rows))),
        ]
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn printing_then_parsing_gives_the_same_tree(e in arb_expr()) {
        let text = e.to_string();
        let mut back = parse_expr(&text).map_err(|err| TestCaseError::fail(format!("{text}\n{err}")))?;
        back.erase_spans();
        prop_assert_eq!(back, e, "printed as {}", text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1500))]

    #[test]
    fn parsing_never_panics(src in "[-+*/^'()\\[\\],;=.%#/ \t\r\na-z0-9θεé_]{0,80}") {
        let _ = parse(&src);
        let _ = parse_expr(&src);
    }

    #[test]
    fn every_error_points_inside_the_input(src in "[-+*/^'()\\[\\],;=.x1 \n]{0,40}") {
        if let Err(e) = parse(&src) {
            prop_assert!(e.span().start <= src.len() && e.span().end <= src.len());
            prop_assert!(e.rendered().contains('^'));
        }
    }
}
