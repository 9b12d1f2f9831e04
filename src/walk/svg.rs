//! The mechanism as an SVG drawing: links as polylines through the joints, joints as circles,
//! joint axes as short arrows; the home pose dashed, a chosen configuration solid.
//!
//! Joint positions are computed numerically from the chain's elementary matrices. A planar
//! mechanism (every axis along x, every point in the yz plane, as the paper's RRR arm) is
//! drawn in the yz plane; any other in an isometric view. Coordinates are printed with one
//! decimal, so the text is the same on every run.

use super::motion::Motion;
use super::{Mechanism, WalkError};
use crate::{mdh_link_matrix, Matrix4, Scalar};

/// Values of symbols for the drawn configuration: joint variables and lengths.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Config {
    /// `(name, value)` pairs in the order given.
    pub values: Vec<(String, f64)>,
}

/// The joint values used when a configuration does not give one (radians or lengths).
const DEFAULT_JOINTS: [f64; 6] = [0.5, -0.7, 0.6, 0.4, -0.5, 0.8];

impl Config {
    /// Parses `theta1=0.3,theta2=-0.5,l1=2` (spaces allowed; empty text is the default).
    ///
    /// # Errors
    /// An entry that is not `name=number`, or a value that is not finite.
    pub fn parse(text: &str) -> Result<Config, WalkError> {
        let mut values = Vec::new();
        for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
            let Some((name, value)) = part.split_once('=') else {
                return Err(WalkError::Config(format!(
                    "`{part}` is not name=value (for example theta1=0.3)"
                )));
            };
            let (name, value) = (name.trim(), value.trim());
            if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
                return Err(WalkError::Config(format!("`{name}` is not a symbol name")));
            }
            let v: f64 = value
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| WalkError::Config(format!("`{value}` is not a finite number")))?;
            values.push((name.to_owned(), v));
        }
        Ok(Config { values })
    }

    fn get(&self, name: &str) -> Option<f64> {
        self.values
            .iter()
            .rev()
            .find(|(n, _)| n == name)
            .map(|(_, v)| *v)
    }
}

/// How the drawing is laid out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SvgOptions {
    /// The width in pixels; the height follows the mechanism's extent.
    pub width: f64,
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions { width: 640.0 }
    }
}

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// The point of the line `p + t n` (unit `n`) nearest `x`.
fn project(x: V3, p: V3, n: V3) -> V3 {
    let t = dot(sub(x, p), n);
    [p[0] + t * n[0], p[1] + t * n[1], p[2] + t * n[2]]
}

fn rotate(m: &Matrix4<f64>, v: V3) -> V3 {
    let r = &m.rows;
    [
        r[0][0] * v[0] + r[0][1] * v[1] + r[0][2] * v[2],
        r[1][0] * v[0] + r[1][1] * v[1] + r[1][2] * v[2],
        r[2][0] * v[0] + r[2][1] * v[1] + r[2][2] * v[2],
    ]
}

/// One pose of the mechanism: the polyline, and each joint's position and axis direction.
struct Pose {
    line: Vec<V3>,
    joints: Vec<(V3, V3)>,
}

fn eval3(v: &[Scalar; 3], env: &dyn Fn(&str) -> Option<f64>) -> Result<V3, WalkError> {
    Ok([v[0].eval(env)?, v[1].eval(env)?, v[2].eval(env)?])
}

/// Screw joints: where on its axis each joint is drawn, in the home pose. The point of the
/// axis nearest the previous joint; when that is the previous joint itself (two axes meeting,
/// as at a wrist), the point nearest the next joint's given point instead.
fn screw_anchors(
    m: &Mechanism,
    env: &dyn Fn(&str) -> Option<f64>,
) -> Result<Vec<Option<V3>>, WalkError> {
    let mut geo: Vec<Option<(V3, V3)>> = Vec::new();
    for x in &m.motions {
        geo.push(match x {
            Motion::Screw { axis, point, .. } => {
                let n = eval3(axis, env)?;
                let l = norm(n);
                let n = if l > 0.0 {
                    [n[0] / l, n[1] / l, n[2] / l]
                } else {
                    n
                };
                Some((eval3(point, env)?, n))
            }
            _ => None,
        });
    }
    let mut prev = [0.0; 3];
    let mut out = Vec::new();
    for (i, g) in geo.iter().enumerate() {
        let Some((p, n)) = g else {
            out.push(None);
            continue;
        };
        let mut a = project(prev, *p, *n);
        if norm(sub(a, prev)) < 1e-9 {
            if let Some(Some((q, _))) = geo[i + 1..].iter().find(|g| g.is_some()) {
                a = project(*q, *p, *n);
            }
        }
        out.push(Some(a));
        prev = a;
    }
    Ok(out)
}

fn pose(
    m: &Mechanism,
    env: &dyn Fn(&str) -> Option<f64>,
    anchors: &[Option<V3>],
) -> Result<Pose, WalkError> {
    let mut acc = Matrix4::identity();
    let mut line = vec![[0.0; 3]];
    let mut joints = Vec::new();
    for (x, anchor) in m.motions.iter().zip(anchors) {
        match x {
            Motion::Screw { axis, .. } => {
                if let Some(a) = anchor {
                    let p = acc.transform_point(a);
                    joints.push((p, rotate(&acc, eval3(axis, env)?)));
                    line.push(p);
                }
            }
            Motion::Dh { .. } => {
                let p = acc.transform_point(&[0.0; 3]);
                joints.push((p, rotate(&acc, [0.0, 0.0, 1.0])));
                line.push(p);
            }
            Motion::Mdh { alpha, a, .. } => {
                let f = &acc * mdh_link_matrix(&alpha.eval(env)?, &a.eval(env)?, &0.0, &0.0);
                let p = f.transform_point(&[0.0; 3]);
                joints.push((p, rotate(&f, [0.0, 0.0, 1.0])));
                line.push(p);
            }
            Motion::Translation { .. } => {}
        }
        acc = acc * x.matrix(env)?;
    }
    match &m.tool {
        Some(t) => line.push(acc.transform_point(&eval3(t, env)?)),
        None => line.push(acc.transform_point(&[0.0; 3])),
    }
    Ok(Pose { line, joints })
}

/// The joint variable of each motion.
/// The Levenshtein distance of two names, in characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

fn variables(m: &Mechanism) -> Vec<String> {
    m.motions
        .iter()
        .filter_map(|x| x.variables().into_iter().next())
        .collect()
}

/// The mechanism drawn at its home pose (all joint variables 0, dashed) and at `cfg` (solid).
///
/// # Errors
/// When a parameter cannot be evaluated, or a `--config` name is not a symbol of the
/// mechanism (the message suggests the closest one).
pub fn mechanism_svg(m: &Mechanism, cfg: &Config, o: &SvgOptions) -> Result<String, WalkError> {
    let vars = variables(m);
    let length = |n: &str| cfg.get(n).unwrap_or(1.0);
    // The symbols the drawing reads: every --config name must be one of them.
    let asked = std::cell::RefCell::new(std::collections::BTreeSet::<String>::new());
    let home_env = |n: &str| -> Option<f64> {
        asked.borrow_mut().insert(n.to_owned());
        match n {
            "pi" | "1" => None,
            _ if vars.iter().any(|v| v == n) => Some(0.0),
            _ => Some(length(n)),
        }
    };
    let conf_env = |n: &str| -> Option<f64> {
        match n {
            "pi" | "1" => None,
            _ => cfg.get(n).or_else(|| {
                vars.iter()
                    .position(|v| v == n)
                    .map(|i| DEFAULT_JOINTS[i % DEFAULT_JOINTS.len()])
                    .or(Some(1.0))
            }),
        }
    };
    let anchors = screw_anchors(m, &home_env)?;
    let home = pose(m, &home_env, &anchors)?;
    let conf = pose(m, &conf_env, &anchors)?;
    let asked = asked.into_inner();
    if let Some((name, _)) = cfg.values.iter().find(|(n, _)| !asked.contains(n)) {
        let known: Vec<&String> = asked.iter().filter(|n| *n != "pi" && *n != "1").collect();
        let closest = known
            .iter()
            .min_by_key(|k| edit_distance(k, name))
            .filter(|k| edit_distance(k, name) <= 2.max(name.len() / 3));
        let hint = match closest {
            Some(k) => format!("; did you mean `{k}`?"),
            None => String::new(),
        };
        let list = known
            .iter()
            .map(|k| k.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        return Err(WalkError::Config(format!(
            "`{name}` is not a symbol of this mechanism{hint} (its symbols: {list})"
        )));
    }
    let planar = home
        .joints
        .iter()
        .all(|(p, n)| p[0].abs() < 1e-9 && n[1].abs() < 1e-9 && n[2].abs() < 1e-9)
        && home.line.iter().all(|p| p[0].abs() < 1e-9);
    // Screen coordinates, y down.
    let proj = |p: V3| -> (f64, f64) {
        if planar {
            (p[1], -p[2])
        } else {
            let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
            ((p[1] - p[0]) * c, -(p[2] - (p[0] + p[1]) * s))
        }
    };
    let extent = home
        .line
        .iter()
        .chain(&conf.line)
        .map(|p| norm(*p))
        .fold(0.0f64, f64::max)
        .max(1e-6);
    let arrow = 0.22 * extent;
    let tip = |(p, n): &(V3, V3)| -> V3 {
        let l = norm(*n).max(1e-12);
        [
            p[0] + arrow * n[0] / l,
            p[1] + arrow * n[1] / l,
            p[2] + arrow * n[2] / l,
        ]
    };
    let mut all: Vec<(f64, f64)> = Vec::new();
    for ps in [&home, &conf] {
        all.extend(ps.line.iter().map(|p| proj(*p)));
        all.extend(ps.joints.iter().map(|j| proj(tip(j))));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in &all {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    let margin = 30.0;
    let legend_h = 78.0;
    let span = (x1 - x0).max(y1 - y0).max(1e-6);
    let scale = (o.width - 2.0 * margin) / span;
    let height = ((y1 - y0) * scale + 2.0 * margin + legend_h).max(160.0);
    let at = |p: V3| -> (f64, f64) {
        let (x, y) = proj(p);
        (
            margin + (x - x0) * scale + ((o.width - 2.0 * margin) - (x1 - x0) * scale) / 2.0,
            legend_h + margin + (y - y0) * scale,
        )
    };
    let f = |v: f64| {
        let s = format!("{v:.1}");
        if s == "-0.0" {
            "0.0".to_owned()
        } else {
            s
        }
    };
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"mechanism\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"13\">\n",
        w = f(o.width),
        h = f(height)
    );
    s += &format!(
        "<title>The mechanism, {} view: home pose dashed, configuration solid</title>\n",
        if planar { "yz-plane" } else { "isometric" }
    );
    s += "<defs><marker id=\"axis-head\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" \
          markerWidth=\"7\" markerHeight=\"7\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" \
          fill=\"#c0392b\"/></marker></defs>\n";
    s += &format!(
        "<rect x=\"0.5\" y=\"0.5\" width=\"{}\" height=\"{}\" fill=\"#fcfcfa\" stroke=\"#ddd\"/>\n",
        f(o.width - 1.0),
        f(height - 1.0)
    );
    let draw = |ps: &Pose, home: bool, s: &mut String| {
        let (stroke, dash, width) = if home {
            ("#999999", " stroke-dasharray=\"6 4\"", "2")
        } else {
            ("#1f5fbf", "", "3.5")
        };
        let pts: Vec<String> = ps
            .line
            .iter()
            .map(|p| {
                let (x, y) = at(*p);
                format!("{},{}", f(x), f(y))
            })
            .collect();
        *s += &format!(
            "<polyline class=\"{}\" points=\"{}\" fill=\"none\" stroke=\"{stroke}\" stroke-width=\"{width}\" stroke-linejoin=\"round\"{dash}/>\n",
            if home { "home" } else { "config" },
            pts.join(" ")
        );
        for (i, j) in ps.joints.iter().enumerate() {
            let (x, y) = at(j.0);
            let (tx, ty) = at(tip(j));
            let op = if home { "0.45" } else { "1" };
            if !planar {
                *s += &format!(
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#c0392b\" stroke-width=\"1.5\" opacity=\"{op}\" marker-end=\"url(#axis-head)\"{dash}/>\n",
                    f(x), f(y), f(tx), f(ty)
                );
            }
            *s += &format!(
                "<circle cx=\"{}\" cy=\"{}\" r=\"6\" fill=\"#ffffff\" stroke=\"{stroke}\" stroke-width=\"2\"{dash}/>\n",
                f(x), f(y)
            );
            if planar {
                // The axis is normal to the drawing: out of the page.
                *s += &format!(
                    "<circle cx=\"{}\" cy=\"{}\" r=\"2\" fill=\"#c0392b\" opacity=\"{op}\"/>\n",
                    f(x),
                    f(y)
                );
            }
            if !home {
                *s += &format!(
                    "<text x=\"{}\" y=\"{}\" fill=\"#1f5fbf\">{}</text>\n",
                    f(x + 8.0),
                    f(y - 8.0),
                    i + 1
                );
            }
        }
        if let Some(p) = ps.line.last() {
            let (x, y) = at(*p);
            *s += &format!(
                "<rect x=\"{}\" y=\"{}\" width=\"8\" height=\"8\" fill=\"{stroke}\"/>\n",
                f(x - 4.0),
                f(y - 4.0)
            );
        }
    };
    draw(&home, true, &mut s);
    draw(&conf, false, &mut s);
    let (bx, by) = at([0.0; 3]);
    s += &format!(
        "<path d=\"M{},{} l-9,14 h18 z\" fill=\"#555555\"/>\n",
        f(bx),
        f(by)
    );
    let config_text: Vec<String> = vars
        .iter()
        .map(|v| format!("{v}={:.2}", conf_env(v).unwrap_or(0.0)))
        .collect();
    s += "<g class=\"legend\">\n";
    s += "<line x1=\"14\" y1=\"18\" x2=\"44\" y2=\"18\" stroke=\"#999999\" stroke-width=\"2\" stroke-dasharray=\"6 4\"/>\n";
    s += "<text x=\"52\" y=\"22\">home pose (every joint variable 0)</text>\n";
    s +=
        "<line x1=\"14\" y1=\"40\" x2=\"44\" y2=\"40\" stroke=\"#1f5fbf\" stroke-width=\"3.5\"/>\n";
    s += &format!(
        "<text x=\"52\" y=\"44\">configuration: {}</text>\n",
        xml_escape(&config_text.join(", "))
    );
    if planar {
        s += "<circle cx=\"29\" cy=\"62\" r=\"6\" fill=\"#ffffff\" stroke=\"#1f5fbf\" stroke-width=\"2\"/><circle cx=\"29\" cy=\"62\" r=\"2\" fill=\"#c0392b\"/>\n";
        s += "<text x=\"52\" y=\"66\">joints, axes (x) out of the page; squares: the tool; view of the yz plane</text>\n";
    } else {
        s += "<line x1=\"14\" y1=\"62\" x2=\"44\" y2=\"62\" stroke=\"#c0392b\" stroke-width=\"1.5\" marker-end=\"url(#axis-head)\"/>\n";
        s += "<text x=\"52\" y=\"66\">joint axes; circles are joints, squares the tool; isometric view</text>\n";
    }
    s += "</g>\n</svg>\n";
    Ok(s)
}

pub(crate) fn xml_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
