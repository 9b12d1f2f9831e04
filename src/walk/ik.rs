//! The walkthrough of a derived inverse kinematics (`dqsym walk ROBOT --ik`), as the same
//! [`Walkthrough`] data the forward walkthrough is: the notation, the joint axes as Plücker
//! lines, the geometry decided exactly, the two identities, each joint's subproblem with its
//! closed-form parts, and the solver run on the pose of the drawing's configuration at the
//! robot's own values, every solution's pose compared with the target by independent 4x4
//! matrices. The engine's derivation ([`IkSolution`]) is data; this module only arranges it.

use super::check::oracle;
use super::robot::robot_mechanism;
use super::svg::{number, Config, Scene, Source};
use super::Mechanism;
use super::{Block, Prose, Shown, SolutionRow, Step, WalkError, Walkthrough};
use crate::emit::latex_symbol;
use crate::ik::{home_axes, Formula, IkSolution, TARGET_SYMBOLS};
use crate::kin::Robot;
use crate::{closed_form, Matrix4, Sym};

/// Two solutions whose joint values differ by less than this (radians or lengths) are one: at
/// a singularity the branches come from the same clamped radicand, so they agree to rounding
/// (about 1e-15 relative); 1e-9 leaves room for the later joints computed from them, and is
/// far below any two genuinely distinct solutions of a pose the page can show (1e-4 apart).
pub(crate) const SAME_SOLUTION: f64 = 1e-9;

/// The walkthrough of `sol`, derived for `robot`.
///
/// # Errors
/// When a closed form fails or a parameter cannot be evaluated.
pub fn walk_ik(robot: &Robot, sol: &IkSolution) -> Result<Walkthrough, WalkError> {
    let mechanism = robot_mechanism(robot);
    let scene = Scene::new(&mechanism, &Config::default())?;
    let mut steps = vec![Step::Legend(legend(sol, &scene))];
    steps.push(axes_step(robot)?);
    steps.push(geometry_step(sol));
    steps.push(identities_step());
    let forms = sol.forms().map_err(|e| WalkError::Config(e.to_string()))?;
    for (i, (step, parts)) in sol.steps.iter().zip(forms).enumerate() {
        let q = &step.variable;
        let mut blocks = vec![Block::Text(marked(&format!("{}.", step.method)))];
        blocks.push(Block::Formulas(
            parts
                .iter()
                .map(|(n, e)| Shown {
                    label: (*n).to_owned(),
                    parts: vec![e.clone()],
                })
                .collect(),
        ));
        blocks.extend(formula_blocks(&step.formula, q));
        if let Some((n, p, m)) = step.branch.as_ref().map(crate::ik::Branch::words) {
            blocks.push(Block::Text(Prose::text(format!(
                "Branch {n}: + is {p}, − is {m}."
            ))));
        }
        blocks.push(Block::Text(marked(&format!(
            "Singular: {}.",
            step.singular
        ))));
        steps.push(Step::Explain {
            title: Prose {
                tex: format!("Step {}: ${}$", i + 1, latex_symbol(q)),
                plain: format!("Step {}: {q}", i + 1),
            },
            blocks,
        });
    }
    if let Some(info) = &sol.general {
        let blocks = crate::ik::general::elimination_lines(sol, info)
            .into_iter()
            .map(|l| Block::Text(Prose::text(l)))
            .collect();
        steps.push(Step::Explain {
            title: Prose::text("The general 6R elimination".to_owned()),
            blocks,
        });
        steps.push(exact_step(sol, info)?);
    }
    steps.push(solutions_step(sol, &mechanism, &scene)?);
    let mut w = Walkthrough {
        title: format!("inverse kinematics of {}", sol.robot),
        steps,
        mechanism: Some(mechanism),
        forms: super::Forms::default(),
    };
    w.prepare();
    Ok(w)
}

/// The general method's equations, exactly: the target's quantities, every equation's `Am`
/// and `Bm` coefficients and its half-angle polynomial (`ik::general::exact`).
fn exact_step(sol: &IkSolution, info: &crate::ik::general::GeneralInfo) -> Result<Step, WalkError> {
    let title = Prose::text("The exact equations".to_owned());
    use crate::ik::general::exact::ExactError;
    let shown = crate::ik::general::exact::exact_equations(sol, info).and_then(|eq| {
        Ok::<_, ExactError>((
            crate::ik::general::exact_scope_text(sol, &eq),
            eq.shown(sol)?,
        ))
    });
    let (scope, groups) = match shown {
        Ok(x) => x,
        Err(ExactError::Scalar(e @ crate::ScalarError::Cancelled)) => {
            return Err(WalkError::Config(e.to_string()))
        }
        // Past the term limit or the work budget the rest of the walkthrough still stands.
        Err(e) => {
            return Ok(Step::Explain {
                title,
                blocks: vec![Block::Text(Prose::text(format!("Not shown ({e}).")))],
            })
        }
    };
    let mut blocks = vec![Block::Text(Prose::text(format!(
        "Bm X12 = Am X45 with every coefficient exact: {scope}."
    )))];
    for g in groups {
        blocks.push(Block::Text(Prose::text(format!("{}:", g.title))));
        blocks.push(Block::Formulas(
            g.items
                .into_iter()
                .map(|s| Shown {
                    label: s.label,
                    parts: vec![s.expr],
                })
                .collect(),
        ));
    }
    Ok(Step::Explain { title, blocks })
}

/// What the target's entries, the joint variables and the parameters are.
fn legend(sol: &IkSolution, scene: &Scene) -> Vec<Prose> {
    let rows: Vec<String> = TARGET_SYMBOLS
        .iter()
        .map(|r| r.map(target_tex).join(" & "))
        .collect();
    let mut out = vec![Prose {
        tex: format!(
            "The target pose $T = \\begin{{pmatrix}} {} \\\\ 0 & 0 & 0 & 1 \\end{{pmatrix}}$: \
             $r_{{ij}}$ is its rotation, $p_x, p_y, p_z$ its position.",
            rows.join(" \\\\ ")
        ),
        plain: "The target pose T = [[r11 r12 r13 px] [r21 r22 r23 py] [r31 r32 r33 pz] \
                [0 0 0 1]]: rij is its rotation, px, py, pz its position."
            .to_owned(),
    }];
    let vars: Vec<&str> = sol.variables.iter().map(String::as_str).collect();
    out.push(Prose {
        tex: format!(
            "The joint variables, solved for: {}. The joint axes: $k_i$ the direction and \
             $m_i = p_i \\times k_i$ the moment of axis $i$ ($p_i$ a point on it); $R_i$ the \
             rotation of joint $i$, $R$ the target's rotation.",
            vars.iter()
                .map(|v| format!("${}$", latex_symbol(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        plain: format!(
            "The joint variables, solved for: {}. The joint axes: ki the direction and \
             mi = pi x ki the moment of axis i (pi a point on it); Ri the rotation of joint i, R \
             the target's rotation.",
            vars.join(", ")
        ),
    });
    if !sol.params.is_empty() {
        let value = |p: &str| {
            scene
                .symbols
                .iter()
                .find(|s| s.name == p)
                .map(|s| (s.value, s.source))
        };
        let each = |tex: bool| -> Vec<String> {
            sol.params
                .iter()
                .map(|p| {
                    let name = if tex {
                        format!("${}$", latex_symbol(p))
                    } else {
                        p.clone()
                    };
                    match value(p) {
                        Some((v, Source::File)) => format!("{name} (robot file: {})", number(v)),
                        Some((v, _)) => format!("{name} (checked at {})", number(v)),
                        None => name,
                    }
                })
                .collect()
        };
        out.push(Prose {
            tex: format!(
                "The robot's parameters stay symbols in the formulas: {}.",
                each(true).join(", ")
            ),
            plain: format!(
                "The robot's parameters stay symbols in the formulas: {}.",
                each(false).join(", ")
            ),
        });
    }
    out
}

/// `r_{11}`, `p_{x}`: a target entry in LaTeX (`px` is one symbol, never `p x`).
pub(crate) fn target_tex(name: &str) -> String {
    match name.strip_prefix('p') {
        Some(axis) if axis.len() == 1 => format!("p_{{{axis}}}"),
        _ => latex_symbol(name),
    }
}

/// Engine prose (a subproblem, a singular set, a geometry fact) with its symbols typeset:
/// names with an index (`k2`, `R1ᵀ`, `theta1`, `p56`, `d4`), a lone `R`, `T`, `G` or `M`,
/// the Greek names and `·`; the words stay text.
pub(crate) fn marked(t: &str) -> Prose {
    let mut tex = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, tex: &mut String| {
        if word.is_empty() {
            return;
        }
        let (base, transposed) = match word.strip_suffix('ᵀ') {
            Some(b) => (b, true),
            None => (word.as_str(), false),
        };
        let letters = base.trim_end_matches(|c: char| c.is_ascii_digit());
        let indexed = !letters.is_empty()
            && letters.len() < base.len()
            && letters.chars().all(|c| c.is_ascii_alphabetic());
        let lone = matches!(base, "R" | "T" | "G" | "M");
        let greek = matches!(base, "theta" | "beta" | "gamma");
        if indexed || lone || greek || target_symbol(base) {
            let sym = if target_symbol(base) {
                target_tex(base)
            } else {
                latex_symbol(base)
            };
            tex.push_str(&format!("${sym}{}$", if transposed { "^{T}" } else { "" }));
        } else {
            tex.push_str(word);
        }
        word.clear();
    };
    for c in t.chars() {
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
            continue;
        }
        flush(&mut word, &mut tex);
        match c {
            '·' => tex.push_str("$\\cdot$"),
            '$' => tex.push_str("\\$"),
            _ => tex.push(c),
        }
    }
    flush(&mut word, &mut tex);
    Prose {
        tex,
        plain: t.to_owned(),
    }
}

/// The head of a joint's column in a table of solutions: the variable typeset when it is
/// short, else `j1`, `j2`, ... (a URDF joint name would widen the table past a phone's width;
/// [`column_key`] lists them under the table).
pub(crate) fn column_head(v: &str, k: usize) -> String {
    if v.chars().count() <= 8 {
        format!("${}$", latex_symbol(v))
    } else {
        format!("$j_{{{}}}$", k + 1)
    }
}

/// What the `j1`, `j2`, ... columns of [`column_head`] are, when there are any.
pub(crate) fn column_key(vars: &[String]) -> Option<String> {
    let long: Vec<String> = vars
        .iter()
        .enumerate()
        .filter(|(_, v)| v.chars().count() > 8)
        .map(|(k, v)| format!("$j_{{{}}}$: `{v}`", k + 1))
        .collect();
    (!long.is_empty()).then(|| format!("Columns: {}.", long.join(", ")))
}

fn target_symbol(name: &str) -> bool {
    TARGET_SYMBOLS.iter().flatten().any(|s| *s == name)
}

/// The axes in the home pose, each as its Plücker coordinates.
fn axes_step(robot: &Robot) -> Result<Step, WalkError> {
    let (axes, _) = home_axes(robot);
    let mut rows = Vec::new();
    let mut which = Vec::new();
    for (i, a) in axes.iter().enumerate() {
        let forms = |v: &[crate::Scalar; 3]| -> Result<Vec<crate::Expr>, WalkError> {
            Ok(v.iter().map(closed_form).collect::<Result<_, _>>()?)
        };
        rows.push(Shown {
            label: format!("k{}", i + 1),
            parts: forms(&a.dir)?,
        });
        rows.push(Shown {
            label: format!("m{}", i + 1),
            parts: forms(&a.moment)?,
        });
        which.push(Prose {
            tex: format!("axis {}: joint ${}$", i + 1, latex_symbol(&a.variable)),
            plain: format!("axis {}: joint {}", i + 1, a.variable),
        });
    }
    Ok(Step::Explain {
        title: Prose::text("The joint axes as Plücker lines (home pose)"),
        blocks: vec![
            Block::Text(Prose {
                tex: "Every joint, whatever its convention, turns about (or slides along) a line \
                      of the home pose: $\\mathrm{FK}(q) = E_1(q_1) \\cdots E_n(q_n)\\, M$. Each \
                      line is its direction $k$ and moment $m = p \\times k$, computed exactly \
                      from the chain's home-pose prefix products."
                    .into(),
                plain: "Every joint, whatever its convention, turns about (or slides along) a \
                        line of the home pose: FK(q) = E1(q1) ... En(qn) M. Each line is its \
                        direction k and moment m = p x k, computed exactly from the chain's \
                        home-pose prefix products."
                    .into(),
            }),
            Block::List(which),
            Block::Formulas(rows),
        ],
    })
}

/// The geometry facts the derivation decided, and the family they give.
fn geometry_step(sol: &IkSolution) -> Step {
    Step::Explain {
        title: Prose::text("The geometry, decided exactly"),
        blocks: vec![
            Block::Text(Prose {
                tex: "Two axes are parallel when $k_1 \\times k_2 = 0$, and intersect when they \
                      are not parallel and the reciprocal product $k_1 \\cdot m_2 + k_2 \\cdot \
                      m_1 = 0$. A symbolic product is a condition."
                    .into(),
                plain: "Two axes are parallel when k1 x k2 = 0, and intersect when they are not \
                        parallel and the reciprocal product k1·m2 + k2·m1 = 0. A symbolic \
                        product is a condition."
                    .into(),
            }),
            Block::List(
                sol.geometry
                    .iter()
                    .map(|g| marked(&g.to_string()))
                    .collect(),
            ),
            Block::Text(marked(&format!("Family: {}.", sol.family))),
        ],
    }
}

/// The two identities every subproblem is written as.
fn identities_step() -> Step {
    Step::Explain {
        title: Prose::text("The subproblems"),
        blocks: vec![
            Block::Text(Prose {
                tex: "The target pose $T$ gives $G = T M^{-1} = E_1 \\cdots E_n$. Each joint \
                      below is one Paden-Kahan subproblem on the exact axis data, written as one \
                      of two identities: two branches, none when the radicand is negative (out \
                      of reach),"
                    .into(),
                plain: "The target pose T gives G = T M^-1 = E1 ... En. Each joint below is one \
                        Paden-Kahan subproblem on the exact axis data, written as one of two \
                        identities: two branches, none when the radicand is negative (out of \
                        reach),"
                    .into(),
            }),
            Block::Display(Prose {
                tex: "a \\cos q + b \\sin q = c \\;\\Rightarrow\\; q = \\operatorname{atan2}(b, a) \
                      \\pm \\operatorname{atan2}\\bigl(\\sqrt{a^2 + b^2 - c^2},\\, c\\bigr)"
                    .into(),
                plain: "a cos q + b sin q = c  has  q = atan2(b, a) ± atan2(sqrt(a² + b² − c²), c)"
                    .into(),
            }),
            Block::Text(Prose::text("and, for a rotation carrying a vector onto another,")),
            Block::Display(Prose {
                tex: "\\operatorname{Rot}(k, q)\\, u = v \\;\\Rightarrow\\; q = \
                      \\operatorname{atan2}\\bigl(k \\cdot (u \\times v),\\; u \\cdot v - (k \\cdot \
                      u)(k \\cdot v)\\bigr)"
                    .into(),
                plain: "Rot(k, q) u = v  has  q = atan2(k·(u x v), u·v − (k·u)(k·v))".into(),
            }),
        ],
    }
}

/// The closed form of a joint from its parts, and where it exists.
fn formula_blocks(f: &Formula, q: &str) -> Vec<Block> {
    let t = latex_symbol(q);
    let (tex, plain, exists) = match f {
        Formula::Atan2 { .. } => (
            format!("{t} = \\operatorname{{atan2}}(y, x)"),
            format!("{q} = atan2(y, x)"),
            None,
        ),
        Formula::Trig { .. } => (
            format!(
                "{t} = \\operatorname{{atan2}}(b, a) \\pm \\operatorname{{atan2}}\\bigl(\\sqrt{{a^2 \
                 + b^2 - c^2}},\\, c\\bigr)"
            ),
            format!("{q} = atan2(b, a) ± atan2(sqrt(a² + b² − c²), c)"),
            Some(Prose {
                tex: "It exists where $a^2 + b^2 - c^2 \\ge 0$.".into(),
                plain: "It exists where a² + b² − c² ≥ 0.".into(),
            }),
        ),
        Formula::Value { .. } => (format!("{t} = v"), format!("{q} = v"), None),
        Formula::Linear { .. } => (
            format!("a {t} = b \\;\\Rightarrow\\; {t} = \\frac{{b}}{{a}}"),
            format!("a {q} = b: {q} = b / a"),
            Some(Prose {
                tex: "It is singular where $a = 0$ (the slides' directions do not span).".into(),
                plain: "It is singular where a = 0 (the slides' directions do not span).".into(),
            }),
        ),
        Formula::Quadratic { .. } => (
            format!(
                "{t}^2 + 2 \\beta {t} + \\gamma = 0 \\;\\Rightarrow\\; {t} = -\\beta \\pm \
                 \\sqrt{{\\beta^2 - \\gamma}}"
            ),
            format!("{q}² + 2 beta {q} + gamma = 0: {q} = −beta ± sqrt(beta² − gamma)"),
            Some(Prose {
                tex: "It exists where $\\beta^2 \\ge \\gamma$.".into(),
                plain: "It exists where beta² ≥ gamma.".into(),
            }),
        ),
    };
    let mut out = vec![Block::Display(Prose { tex, plain })];
    out.extend(exists.map(Block::Text));
    out
}

/// The product of the motions' elementary matrices at the values `env`.
/// The pose of the end `ik` solves for (the one `fk` reports): the motions' product, moved to
/// the tool point (in the last frame) when the robot has one.
fn pose(mech: &Mechanism, env: &[(String, f64)]) -> Result<Matrix4<f64>, WalkError> {
    let look = |s: &Sym| env.iter().find(|(n, _)| n == s.name()).map(|(_, v)| *v);
    let mut m = Matrix4::identity();
    for x in &mech.motions {
        m = m * x.matrix(&look)?;
    }
    if let Some(p) = &mech.tool {
        let mut t = Matrix4::identity();
        for (r, x) in p.iter().enumerate() {
            t.rows[r][3] = x
                .eval(&|n: &str| env.iter().find(|(k, _)| k == n).map(|(_, v)| *v))
                .map_err(|e| WalkError::Config(format!("the tool point: {e}")))?;
        }
        m = m * t;
    }
    Ok(m)
}

/// The solver on the pose of the drawing's configuration, at the robot's values.
fn solutions_step(sol: &IkSolution, mech: &Mechanism, scene: &Scene) -> Result<Step, WalkError> {
    let motions = &mech.motions[..];
    let env: Vec<(String, f64)> = scene
        .symbols
        .iter()
        .map(|s| (s.name.clone(), s.value))
        .collect();
    let target = pose(mech, &env)?;
    let params: Vec<(&str, f64)> = sol
        .params
        .iter()
        .map(|p| {
            let v = env.iter().find(|(n, _)| n == p).map_or(1.0, |(_, v)| *v);
            (p.as_str(), v)
        })
        .collect();
    let found = sol
        .solve_numeric(&target.rows, &params)
        .map_err(|e| WalkError::Config(e.to_string()))?;
    let mut rows: Vec<SolutionRow> = Vec::new();
    for s in found {
        let mut at = env.clone();
        for (v, x) in sol.variables.iter().zip(&s.q) {
            at.retain(|(n, _)| n != v);
            at.push((v.clone(), *x));
        }
        let back = pose(mech, &at)?;
        let mut deviation: f64 = 0.0;
        for r in 0..3 {
            for c in 0..4 {
                if !(sol.position_only && c < 3) {
                    deviation = deviation.max((back.rows[r][c] - target.rows[r][c]).abs());
                }
            }
        }
        merge(
            &mut rows,
            SolutionRow {
                q: s.q,
                branches: 1,
                singular: s.singular,
                deviation,
            },
        );
    }
    let said = |joint: bool, tex: bool| -> Vec<String> {
        scene
            .symbols
            .iter()
            .filter(|s| s.joint.is_some() == joint)
            .map(|s| {
                let n = if tex {
                    latex_symbol(&s.name)
                } else {
                    s.name.clone()
                };
                if tex {
                    format!("${n} = {}$", number(s.value))
                } else {
                    format!("{n} = {}", number(s.value))
                }
            })
            .collect()
    };
    let what = |tex: bool| {
        let lengths = said(false, tex);
        format!(
            "The target is the pose of the drawing's configuration, {}{}, computed as {}; each \
             solution's own pose is computed the same way. The solver returns {} distinct \
             solutions{}:",
            said(true, tex).join(", "),
            if lengths.is_empty() {
                String::new()
            } else {
                format!(", at the robot's values {}", lengths.join(", "))
            },
            oracle(motions),
            rows.len(),
            if rows.iter().any(|r| r.branches > 1) {
                " (branches that meet at a singularity are counted once)"
            } else {
                ""
            }
        )
    };
    Ok(Step::Solutions {
        what: Prose {
            tex: what(true),
            plain: what(false),
        },
        variables: sol.variables.clone(),
        rows,
    })
}

/// Adds `row` to `rows`, or counts it as one more branch of an equal row.
fn merge(rows: &mut Vec<SolutionRow>, row: SolutionRow) {
    let same = |a: &[f64], b: &[f64]| {
        a.iter().zip(b).all(|(x, y)| {
            // Angles a whole turn apart are one solution.
            let d = (x - y).abs() % std::f64::consts::TAU;
            d.min(std::f64::consts::TAU - d) < SAME_SOLUTION
        })
    };
    if let Some(r) = rows.iter_mut().find(|r| same(&r.q, &row.q)) {
        r.branches += 1;
        r.singular |= row.singular;
        r.deviation = r.deviation.max(row.deviation);
    } else {
        rows.push(row);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engine_prose_has_its_symbols_typeset() {
        let p = marked("R6 (Rᵀ R1 k2) = R5ᵀ k2, where theta1 = 0 and px·k2");
        assert_eq!(
            p.tex,
            "$R_{6}$ ($R^{T}$ $R_{1}$ $k_{2}$) = $R_{5}^{T}$ $k_{2}$, where $\\theta_{1}$ = 0 \
             and $p_{x}$$\\cdot$$k_{2}$"
        );
        assert_eq!(
            p.plain,
            "R6 (Rᵀ R1 k2) = R5ᵀ k2, where theta1 = 0 and px·k2"
        );
    }

    #[test]
    fn branches_that_meet_are_one_row() {
        let mut rows = Vec::new();
        let row = |q: Vec<f64>| SolutionRow {
            q,
            branches: 1,
            singular: true,
            deviation: 0.0,
        };
        merge(&mut rows, row(vec![0.5, std::f64::consts::PI]));
        merge(&mut rows, row(vec![0.5, -std::f64::consts::PI]));
        merge(&mut rows, row(vec![0.5, 1.0]));
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].branches, 2);
    }
}
