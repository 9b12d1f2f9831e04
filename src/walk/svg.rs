//! The mechanism as an SVG drawing, to scale: links as a polyline from the base through the
//! joints to the tool, joints as circles numbered from 1, joint axes as arrows; the home pose
//! dashed, a chosen configuration solid; a base marker, an x/y/z triad, and a legend with the
//! values used for every symbol.
//!
//! The geometry is exact ([`Scene`]): each joint's position and axis in the configuration, and
//! the tool, as scalars of the joint variables and the lengths, from the product of the exact
//! factors. The drawing evaluates them at numbers; the interactive page compiles the same
//! scalars to JavaScript. A planar mechanism (every axis along x, every point in the yz plane,
//! as the paper's RRR arm) is drawn in the yz plane; any other in an isometric view. The scale
//! is fixed by the home pose (a reach bound), so moving a joint never rescales the drawing.
//! Joint labels are placed where their boxes meet no other label and no joint.

use super::motion::Motion;
use super::view::{choose_view, place_labels, Segment, View, V3};
use super::{Mechanism, WalkError};
use crate::{
    kin::{dh_link, dh_link_matrix, mdh_link, mdh_link_matrix},
    DualQuat, Matrix4, Scalar,
};
use std::fmt::Write as _;

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
    /// The width in pixels; the drawing area is square below the legend.
    pub width: f64,
    /// The legend inside the drawing (a page sets its own beside it, as text that wraps).
    pub legend: bool,
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions {
            width: 600.0,
            legend: true,
        }
    }
}

/// Where a value of the drawing comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Source {
    /// `--config`.
    Config,
    /// The robot file's `[values]`.
    File,
    /// Nothing gave it: a joint's fixed default, or 1 for a length.
    Default,
}

/// A symbol of the drawing with its value.
#[derive(Clone, Debug)]
pub(crate) struct Symbol {
    pub name: String,
    pub value: f64,
    pub source: Source,
    /// A joint variable: revolute (an angle) or prismatic (a slide).
    pub joint: Option<bool>,
}

/// The exact geometry of a mechanism in its configuration.
pub(crate) struct Scene {
    /// Each drawn joint: its position and its axis direction (unit at every configuration).
    pub joints: Vec<([Scalar; 3], [Scalar; 3])>,
    /// The tool point.
    pub tool: [Scalar; 3],
    /// The pose of the chain as a dual quaternion.
    pub pose: DualQuat<Scalar>,
    /// The pose of the chain as a 4x4 matrix (the product of the motions' matrices).
    pub matrix: Matrix4<Scalar>,
    /// Whether a tool point was given (else the tool is the last frame's origin).
    pub has_tool: bool,
    /// The joint variables (prismatic or not) in joint order, then the other symbols by name.
    pub symbols: Vec<Symbol>,
}

fn zero3() -> [Scalar; 3] {
    [Scalar::int(0), Scalar::int(0), Scalar::int(0)]
}

fn dot(a: &[Scalar; 3], b: &[Scalar; 3]) -> Scalar {
    &(&a[0] * &b[0] + &a[1] * &b[1]) + &(&a[2] * &b[2])
}

fn sub(a: &[Scalar; 3], b: &[Scalar; 3]) -> [Scalar; 3] {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// The point of the line `p + t n` nearest `x` (exact; `n` unit, else `p` itself).
fn project(x: &[Scalar; 3], p: &[Scalar; 3], n: &[Scalar; 3]) -> [Scalar; 3] {
    if dot(n, n) != Scalar::int(1) {
        return p.clone();
    }
    let t = dot(&sub(x, p), n);
    [
        &p[0] + &(&t * &n[0]),
        &p[1] + &(&t * &n[1]),
        &p[2] + &(&t * &n[2]),
    ]
}

fn eval3(v: &[Scalar; 3], env: &dyn Fn(&str) -> Option<f64>) -> Result<V3, WalkError> {
    Ok([v[0].eval(env)?, v[1].eval(env)?, v[2].eval(env)?])
}

fn rotate(m: &Matrix4<Scalar>, v: &[Scalar; 3]) -> [Scalar; 3] {
    let r = &m.rows;
    let row = |i: usize| &(&(&r[i][0] * &v[0]) + &(&r[i][1] * &v[1])) + &(&r[i][2] * &v[2]);
    [row(0), row(1), row(2)]
}

/// The exact 4x4 matrix of a motion, from elementary matrices in full angles (cheaper to
/// multiply than the half-angle dual quaternions).
fn motion_matrix(m: &Motion) -> Matrix4<Scalar> {
    match m {
        Motion::Screw {
            axis,
            point,
            angle,
            slide,
        } => {
            let minus = [-&point[0], -&point[1], -&point[2]];
            let along = [&axis[0] * slide, &axis[1] * slide, &axis[2] * slide];
            Matrix4::trans(point)
                * Matrix4::rotation(axis, angle)
                * Matrix4::trans(&minus)
                * Matrix4::trans(&along)
        }
        Motion::Translation { t } => Matrix4::trans(t),
        Motion::Dh { theta, d, a, alpha } => dh_link_matrix(theta, d, a, alpha),
        Motion::Mdh { alpha, a, theta, d } => mdh_link_matrix(alpha, a, theta, d),
    }
}

/// The exact factor of a motion.
fn motion_dq(m: &Motion) -> DualQuat<Scalar> {
    match m {
        Motion::Screw {
            axis,
            point,
            angle,
            slide,
        } => DualQuat::screw(axis, point, angle, slide),
        Motion::Translation { t } => DualQuat::translation(t),
        Motion::Dh { theta, d, a, alpha } => dh_link(theta, d, a, alpha),
        Motion::Mdh { alpha, a, theta, d } => mdh_link(alpha, a, theta, d),
    }
}

impl Scene {
    /// The exact scalars of the scene: joint positions and axes, tool, pose matrix and DQ.
    pub(crate) fn scalars(&self) -> impl Iterator<Item = &Scalar> {
        self.joints
            .iter()
            .flat_map(|(p, n)| p.iter().chain(n))
            .chain(&self.tool)
            .chain(self.matrix.rows.iter().flatten())
            .chain(
                [&self.pose.real, &self.pose.dual]
                    .into_iter()
                    .flat_map(|q| [&q.w, &q.x, &q.y, &q.z]),
            )
    }

    /// The scene of `m`, with the values of `cfg`, then of the robot file, then the defaults.
    pub(crate) fn new(m: &Mechanism, cfg: &Config) -> Result<Scene, WalkError> {
        let joints = joint_variables(m);
        let symbols = scene_symbols(m, cfg, &joints);
        check_config(cfg, &symbols)?;
        let anchors = screw_anchors(m, &symbols)?;
        let mut acc = Matrix4::identity();
        let mut pose = DualQuat::identity();
        let mut drawn = Vec::new();
        let z = [Scalar::int(0), Scalar::int(0), Scalar::int(1)];
        for (x, anchor) in m.motions.iter().zip(&anchors) {
            match x {
                Motion::Screw { axis, .. } => {
                    // Only joints have anchors.
                    if let Some(a) = anchor {
                        drawn.push((acc.transform_point(a), rotate(&acc, axis)));
                    }
                }
                Motion::Dh { .. } => {
                    drawn.push((acc.transform_point(&zero3()), rotate(&acc, &z)));
                }
                Motion::Mdh { alpha, a, .. } => {
                    let f = &acc * &mdh_link_matrix(alpha, a, &Scalar::int(0), &Scalar::int(0));
                    drawn.push((f.transform_point(&zero3()), rotate(&f, &z)));
                }
                Motion::Translation { .. } => {}
            }
            acc = &acc * &motion_matrix(x);
            pose = &pose * &motion_dq(x);
        }
        let tool = acc.transform_point(m.tool.as_ref().unwrap_or(&zero3()));
        Ok(Scene {
            joints: drawn,
            tool,
            matrix: acc,
            pose,
            has_tool: m.tool.is_some(),
            symbols,
        })
    }

    /// The value of each symbol, joints at `joints` (or their values when `None`).
    fn env(&self, home: bool) -> impl Fn(&str) -> Option<f64> + '_ {
        move |n: &str| {
            let s = self.symbols.iter().find(|s| s.name == n)?;
            Some(if home && s.joint.is_some() {
                0.0
            } else {
                s.value
            })
        }
    }

    /// The polyline (base, joints, tool) and the joints' axes at the home pose or at the
    /// configuration.
    fn numbers(&self, home: bool) -> Result<(Vec<V3>, Vec<V3>), WalkError> {
        let env = self.env(home);
        let mut line = vec![[0.0; 3]];
        let mut axes = Vec::new();
        for (p, n) in &self.joints {
            line.push(eval3(p, &env)?);
            axes.push(eval3(n, &env)?);
        }
        line.push(eval3(&self.tool, &env)?);
        // Values near the end of f64's range (`l1=-1e308`) make coordinates infinite or NaN;
        // the drawing would hold `NaN`. Every coordinate finite, and below 1e150 so that the
        // reach's squares stay finite too, or an error naming the values.
        if line
            .iter()
            .chain(&axes)
            .flatten()
            .any(|c| !c.is_finite() || c.abs() >= 1e150)
        {
            let values: Vec<String> = self
                .symbols
                .iter()
                .filter(|s| s.value.abs() >= 1e6)
                .map(|s| format!("{} = {:e}", s.name, s.value))
                .collect();
            return Err(WalkError::Config(format!(
                "the mechanism cannot be drawn: its coordinates leave the range of floating point \
                 numbers ({}); give smaller values with --config",
                if values.is_empty() {
                    "some values are too large".to_owned()
                } else {
                    values.join(", ")
                }
            )));
        }
        Ok((line, axes))
    }

    /// Whether the mechanism is drawn in the yz plane.
    fn planar(&self) -> Result<bool, WalkError> {
        let (line, axes) = self.numbers(true)?;
        Ok(line.iter().all(|p| p[0].abs() < 1e-9)
            && axes.iter().all(|n| n[1].abs() < 1e-9 && n[2].abs() < 1e-9))
    }
}

/// The length of a polyline.
pub(crate) fn reach(line: &[V3], slides: f64) -> f64 {
    let mut r = slides;
    for w in line.windows(2) {
        let d = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
        r += (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    }
    r.max(1e-6)
}

/// The slider range of a symbol: an angle over a full turn, a length or a slide around its
/// value.
pub(crate) fn range(s: &Symbol) -> (f64, f64) {
    match s.joint {
        Some(false) => (-std::f64::consts::PI, std::f64::consts::PI),
        _ => {
            let m = (2.0 * s.value.abs()).max(1.0);
            if s.joint.is_some() {
                (-m, m)
            } else if s.value < 0.0 {
                (-m, 0.0)
            } else {
                (0.0, m)
            }
        }
    }
}

/// The prismatic joints' largest slides, added to the reach bound.
pub(crate) fn slides(symbols: &[Symbol]) -> f64 {
    symbols
        .iter()
        .filter(|s| s.joint == Some(true))
        .map(|s| range(s).1)
        .sum()
}

/// The layout of the drawing, shared with the page's script: the legend's height above the
/// square drawing area, and the view.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub width: f64,
    pub legend: f64,
    pub view: View,
}

impl Frame {
    pub(crate) fn height(&self) -> f64 {
        self.legend + self.width
    }

    /// Pixels per unit of length for a mechanism of reach `r` (an orthographic projection
    /// draws every point within `r` of the base within `r` of the centre).
    pub(crate) fn scale(&self, r: f64) -> f64 {
        (self.width / 2.0 - 24.0) / r
    }

    /// A point on the screen (y down), the base at the centre of the square.
    pub(crate) fn at(&self, p: V3, scale: f64) -> (f64, f64) {
        let (u, v) = self.view.project(p);
        (
            self.width / 2.0 + u * scale,
            self.legend + self.width / 2.0 + v * scale,
        )
    }
}

/// The joint variables of `m`, in order, and whether each slides.
fn joint_variables(m: &Mechanism) -> Vec<(String, bool)> {
    let mut joints: Vec<(String, bool)> = Vec::new();
    for x in &m.motions {
        if let Some(v) = x.variables().into_iter().next() {
            let prismatic = match x {
                Motion::Screw { angle, .. } => angle.symbols().iter().all(|s| s.is_pi()),
                Motion::Translation { .. } => true,
                Motion::Dh { theta, .. } | Motion::Mdh { theta, .. } => {
                    !theta.symbols().iter().any(|s| s.name() == v)
                }
            };
            if !joints.iter().any(|(n, _)| *n == v) {
                joints.push((v, prismatic));
            }
        }
    }
    joints
}

/// The symbols of the drawing, joints first, each with its value: from `cfg`, then the robot
/// file, then the defaults.
fn scene_symbols(m: &Mechanism, cfg: &Config, joints: &[(String, bool)]) -> Vec<Symbol> {
    let value_of = |n: &str, k: Option<usize>| -> (f64, Source) {
        if let Some(v) = cfg.get(n) {
            return (v, Source::Config);
        }
        if let Some((_, v)) = m.values.iter().find(|(x, _)| x == n) {
            return (*v, Source::File);
        }
        match k {
            Some(i) => (DEFAULT_JOINTS[i % DEFAULT_JOINTS.len()], Source::Default),
            None => (1.0, Source::Default),
        }
    };
    let mut symbols: Vec<Symbol> = joints
        .iter()
        .enumerate()
        .map(|(i, (n, prismatic))| {
            let (value, source) = value_of(n, Some(i));
            Symbol {
                name: n.clone(),
                value,
                source,
                joint: Some(*prismatic),
            }
        })
        .collect();
    // The other symbols: whatever the motions and the tool mention.
    let mut others = std::collections::BTreeSet::new();
    let mut note = |x: &Scalar| {
        for s in x.symbols() {
            if !s.is_pi() && !s.is_one() && !joints.iter().any(|(n, _)| n == s.name()) {
                others.insert(s.name().to_owned());
            }
        }
    };
    for x in &m.motions {
        match x {
            Motion::Screw {
                axis,
                point,
                angle,
                slide,
            } => {
                axis.iter().chain(point).for_each(&mut note);
                note(angle);
                note(slide);
            }
            Motion::Translation { t } => t.iter().for_each(&mut note),
            Motion::Dh { theta, d, a, alpha } | Motion::Mdh { alpha, a, theta, d } => {
                [theta, d, a, alpha].into_iter().for_each(&mut note);
            }
        }
    }
    if let Some(t) = &m.tool {
        t.iter().for_each(&mut note);
    }
    for n in others {
        let (value, source) = value_of(&n, None);
        symbols.push(Symbol {
            name: n,
            value,
            source,
            joint: None,
        });
    }
    symbols
}

/// Every --config name must be a symbol of the mechanism: a misspelt name is an error with
/// the closest name suggested, never silently ignored.
fn check_config(cfg: &Config, symbols: &[Symbol]) -> Result<(), WalkError> {
    if let Some((name, _)) = cfg
        .values
        .iter()
        .find(|(n, _)| !symbols.iter().any(|s| &s.name == n))
    {
        let known: Vec<&str> = symbols.iter().map(|s| s.name.as_str()).collect();
        let closest = known
            .iter()
            .min_by_key(|k| edit_distance(k, name))
            .filter(|k| edit_distance(k, name) <= 2.max(name.len() / 3));
        let hint = match closest {
            Some(k) => format!("; did you mean `{k}`?"),
            None => String::new(),
        };
        return Err(WalkError::Config(format!(
            "`{name}` is not a symbol of this mechanism{hint} (its symbols: {})",
            known.join(", ")
        )));
    }
    Ok(())
}

/// Where on its axis each screw joint is drawn, in the home pose (`None` for other motions).
fn screw_anchors(m: &Mechanism, symbols: &[Symbol]) -> Result<Vec<Option<[Scalar; 3]>>, WalkError> {
    let home_env = |n: &str| -> Option<f64> {
        let s = symbols.iter().find(|s| s.name == n)?;
        Some(if s.joint.is_some() { 0.0 } else { s.value })
    };
    // Screw joints: where on its axis each is drawn, in the home pose. The point of the
    // axis nearest the previous joint; when that is the previous joint itself (two axes
    // meeting, as at a wrist), the point nearest the next joint's given point instead.
    let screws: Vec<Option<([Scalar; 3], [Scalar; 3])>> = m
        .motions
        .iter()
        .map(|x| match x {
            // A joint: a screw with a variable (a constant rotation of a base or tool
            // frame is not drawn as a joint).
            Motion::Screw { axis, point, .. } if !x.variables().is_empty() => {
                Some((point.clone(), axis.clone()))
            }
            _ => None,
        })
        .collect();
    let mut anchors: Vec<Option<[Scalar; 3]>> = Vec::new();
    let mut prev = zero3();
    for (i, g) in screws.iter().enumerate() {
        let Some((p, n)) = g else {
            anchors.push(None);
            continue;
        };
        let mut a = project(&prev, p, n);
        let gap = eval3(&sub(&a, &prev), &home_env)?;
        if gap.iter().map(|x| x * x).sum::<f64>() < 1e-18 {
            if let Some(Some((q, _))) = screws[i + 1..].iter().find(|g| g.is_some()) {
                a = project(q, p, n);
            }
        }
        prev = a.clone();
        anchors.push(Some(a));
    }
    Ok(anchors)
}

/// The numbers of a drawing: the polylines at the home pose and the configuration (base,
/// joints, tool), the joints' axes, the view and the scale.
pub(crate) struct Layout {
    pub home: Vec<V3>,
    pub conf: Vec<V3>,
    pub axes: Vec<V3>,
    pub view: View,
    pub reach: f64,
}

impl Scene {
    /// The numbers of the drawing, the view chosen from both poses.
    pub(crate) fn layout(&self) -> Result<Layout, WalkError> {
        let (home, _) = self.numbers(true)?;
        let (conf, axes) = self.numbers(false)?;
        let view = choose_view(&[&home, &conf], self.planar()?);
        let reach = reach(&home, slides(&self.symbols));
        Ok(Layout {
            home,
            conf,
            axes,
            view,
            reach,
        })
    }
}

/// The part of a polyline (base, joints, tool) drawn as links: from the first joint on (the
/// base to the first joint is a fixed offset, drawn apart).
fn links(line: &[V3]) -> &[V3] {
    if line.len() > 2 {
        &line[1..]
    } else {
        line
    }
}

/// One line of the drawing's legend, with the id the page's script updates it by.
pub(crate) struct LegendLine {
    pub id: Option<&'static str>,
    /// A sample of the stroke it explains: (colour, width, dash pattern).
    pub swatch: Option<(&'static str, f64, &'static str)>,
    pub text: String,
}

/// The colour, width and dashes of the fixed offset from the base to the first joint.
pub(crate) const BASE_LINK: (&str, f64, &str) = ("#a0703c", 2.5, "2 3");
const HOME: (&str, f64, &str) = ("#999999", 2.0, "6 4");
const ARM: (&str, f64, &str) = ("#1f5fbf", 3.5, "");

/// The legend of a drawing, line by line.
pub(crate) fn legend_lines(scene: &Scene, l: &Layout, scale: f64) -> Vec<LegendLine> {
    let joints_text = values_text(&scene.symbols, true);
    let lengths_text = values_text(&scene.symbols, false);
    let line = |id, swatch, text: String| LegendLine { id, swatch, text };
    let mut out = vec![
        line(
            None,
            Some(HOME),
            "home pose (every joint variable 0)".into(),
        ),
        line(None, Some(ARM), "the configuration:".into()),
        line(Some("dq-config"), None, joints_text),
        line(
            Some("dq-lengths"),
            None,
            if lengths_text.is_empty() {
                "no length parameters".to_owned()
            } else {
                format!("lengths: {lengths_text}")
            },
        ),
        line(
            None,
            None,
            format!(
                "circles: joints 1 to {}, {}; square: the {}; triangle: the base",
                scene.joints.len(),
                if l.view.planar {
                    "axes (x) out of the page"
                } else {
                    "arrows: joint axes"
                },
                if scene.has_tool {
                    "tool point"
                } else {
                    "last frame's origin"
                }
            ),
        ),
    ];
    if base_offset(&l.conf) {
        out.push(line(
            None,
            Some(BASE_LINK),
            "the fixed offset from the base to joint 1 (not a link)".into(),
        ));
    }
    out.push(line(
        Some("dq-scale"),
        None,
        format!(
            "{}, to scale: {} px per unit length",
            l.view.words(),
            number(scale)
        ),
    ));
    out
}

/// Whether the first joint is away from the base (a fixed offset to draw).
fn base_offset(line: &[V3]) -> bool {
    line.len() > 2 && line[1].iter().any(|x| x.abs() > 1e-9)
}

/// Text broken into lines of at most `max` characters after a `,` or `;` (so `a2 = -0.425`
/// stays on one line); a longer piece keeps its own line.
fn wrap(text: &str, max: usize) -> Vec<String> {
    let mut pieces: Vec<String> = Vec::new();
    let mut cur = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        cur.push(c);
        if matches!(c, ',' | ';') && chars.peek() == Some(&' ') {
            chars.next();
            pieces.push(std::mem::take(&mut cur));
        }
    }
    pieces.push(cur);
    let mut out: Vec<String> = Vec::new();
    let mut line = String::new();
    for p in pieces {
        if !line.is_empty() && line.chars().count() + 1 + p.chars().count() > max {
            out.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&p);
    }
    out.push(line);
    out
}

/// A legend of `lines` at the top of an SVG drawing `width` wide: its text and its height.
/// Lines wrap at the drawing's width (12 px sans-serif is under 7 px a character on average),
/// so long URDF joint names are never cut.
fn svg_legend(lines: &[LegendLine], width: f64) -> (String, f64) {
    let max = ((width - 28.0) / 7.0).max(20.0) as usize;
    let mut s = String::from("<g class=\"legend\" font-size=\"12\">\n");
    let mut y = 20.0;
    for l in lines {
        let x = if let Some((colour, w, dash)) = l.swatch {
            let _ = writeln!(
                s,
                "<line x1=\"14\" y1=\"{}\" x2=\"44\" y2=\"{}\" stroke=\"{colour}\" \
                 stroke-width=\"{w}\" stroke-dasharray=\"{dash}\"/>",
                f(y - 4.0),
                f(y - 4.0)
            );
            52.0
        } else {
            14.0
        };
        let id = l.id.map(|i| format!(" id=\"{i}\"")).unwrap_or_default();
        let _ = write!(s, "<text{id} x=\"{}\" y=\"{}\">", f(x), f(y));
        for (k, part) in wrap(&l.text, max).iter().enumerate() {
            if k > 0 {
                y += 16.0;
            }
            let _ = write!(
                s,
                "<tspan x=\"{}\" y=\"{}\">{}</tspan>",
                f(x),
                f(y),
                xml_escape(part)
            );
        }
        s += "</text>\n";
        y += 18.0;
    }
    s += "</g>\n";
    (s, y - 10.0)
}

/// The triad, bottom left: x, y, z of the base frame as drawn (each line has an id the page's
/// script turns with the view).
fn triad(frame: &Frame, h: f64) -> String {
    let (ox, oy) = (34.0, h - 34.0);
    let mut s = String::from("<g class=\"triad\">\n");
    for (k, name) in ["x", "y", "z"].iter().enumerate() {
        let mut e = [0.0; 3];
        e[k] = 1.0;
        let (dx, dy) = frame.view.project(e);
        let (dx, dy) = (dx * 22.0, dy * 22.0);
        let out = dx.abs() + dy.abs() < 1e-9;
        // Along the line of sight (x of a planar drawing): out of the page.
        let _ = writeln!(
            s,
            "<circle id=\"dq-triad-o{name}\" cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"none\" \
             stroke=\"#444444\"{}/><line id=\"dq-triad-{name}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" \
             y2=\"{}\" stroke=\"#444444\" stroke-width=\"1.5\" marker-end=\"url(#triad-head)\"{}/>\
             <text id=\"dq-triad-t{name}\" x=\"{}\" y=\"{}\" fill=\"#444444\" text-anchor=\"middle\" \
             dominant-baseline=\"central\">{name}</text>",
            f(ox),
            f(oy),
            if out { "" } else { " visibility=\"hidden\"" },
            f(ox),
            f(oy),
            f(ox + dx),
            f(oy + dy),
            if out { " visibility=\"hidden\"" } else { "" },
            f(if out { ox - 14.0 } else { ox + dx * 1.5 }),
            f(if out { oy + 12.0 } else { oy + dy * 1.5 }),
        );
    }
    s += "</g>\n";
    s
}

/// The segments a label must keep off: links (both poses), the base offset and the axes.
pub(crate) fn drawn_segments(
    home: &[(f64, f64)],
    conf: &[(f64, f64)],
    axes: &[Segment],
) -> Vec<Segment> {
    let mut out: Vec<Segment> = Vec::new();
    for l in [home, conf] {
        out.extend(l.windows(2).map(|w| (w[0], w[1])));
    }
    out.extend(axes);
    out
}

/// One decimal, never `-0.0`: the same text on every run.
fn f(v: f64) -> String {
    let s = format!("{v:.1}");
    if s == "-0.0" {
        "0.0".to_owned()
    } else {
        s
    }
}

/// The legend's line of values: `a2 = 0.4318, d3 = 0.15 (robot file); l1 = 1 (default)`.
pub(crate) fn values_text(symbols: &[Symbol], joints: bool) -> String {
    let mut parts: Vec<String> = Vec::new();
    for (source, what) in [
        (Source::Config, "--config"),
        (Source::File, "robot file"),
        (Source::Default, "default"),
    ] {
        let items: Vec<String> = symbols
            .iter()
            .filter(|s| s.source == source && s.joint.is_some() == joints)
            .map(|s| format!("{} = {}", s.name, number(s.value)))
            .collect();
        if !items.is_empty() {
            parts.push(format!("{} ({what})", items.join(", ")));
        }
    }
    parts.join("; ")
}

/// A value for the legend: at most 6 decimals, trailing zeros dropped.
pub(crate) fn number(v: f64) -> String {
    let s = format!("{v:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_owned();
    if s == "-0" {
        "0".to_owned()
    } else {
        s
    }
}

/// The mechanism drawn at its home pose (all joint variables 0, dashed) and at `cfg` (solid).
///
/// # Errors
/// When a parameter cannot be evaluated (a `--config` name that is not a symbol is ignored).
pub fn mechanism_svg(m: &Mechanism, cfg: &Config, o: &SvgOptions) -> Result<String, WalkError> {
    let scene = Scene::new(m, cfg)?;
    scene_svg(&scene, o)
}

/// The drawing of a scene.
pub(crate) fn scene_svg(scene: &Scene, o: &SvgOptions) -> Result<String, WalkError> {
    let l = scene.layout()?;
    let probe = Frame {
        width: o.width,
        legend: 0.0,
        view: l.view,
    };
    let scale = probe.scale(l.reach);
    let legend = o
        .legend
        .then(|| svg_legend(&legend_lines(scene, &l, scale), o.width));
    let frame = Frame {
        legend: legend.as_ref().map_or(0.0, |(_, h)| *h),
        ..probe
    };
    let at = |p: V3| frame.at(p, scale);
    let (w, h) = (o.width, frame.height());
    let mut s = svg_open(w, h, &l);
    if let Some((text, _)) = &legend {
        s += text;
    }
    s += &triad(&frame, h);
    let (base, first) = draw_base(&mut s, &at, &l);
    let (screen, axis_segments) = draw_joints(&mut s, &at, &l);
    let tool = draw_tool(&mut s, &at, &l);
    let on_screen = |line: &[V3]| -> Vec<(f64, f64)> { line.iter().map(|p| at(*p)).collect() };
    let mut avoid = drawn_segments(
        &on_screen(links(&l.home)),
        &on_screen(links(&l.conf)),
        &axis_segments,
    );
    if base_offset(&l.conf) {
        avoid.push((base, first));
    }
    let area = [0.0, frame.legend, w, w];
    for (i, b) in place_labels(&screen, tool, &avoid, area).iter().enumerate() {
        let _ = writeln!(
            s,
            "<text class=\"dq-label\" data-i=\"{i}\" x=\"{}\" y=\"{}\" fill=\"#1f5fbf\" \
             text-anchor=\"middle\" dominant-baseline=\"central\">{}</text>",
            f(b[0] + b[2] / 2.0),
            f(b[1] + b[3] / 2.0),
            i + 1
        );
    }
    s += "</svg>\n";
    Ok(s)
}

/// The opening of the drawing: the element, its title, the arrow heads and the background.
fn svg_open(w: f64, h: f64, l: &Layout) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"mechanism\" width=\"{}\" height=\"{}\" \
         viewBox=\"0 0 {} {}\" font-family=\"sans-serif\" font-size=\"13\">",
        f(w),
        f(h),
        f(w),
        f(h)
    );
    let _ = writeln!(
        s,
        "<title>The mechanism to scale, {}: home pose dashed, configuration solid</title>",
        l.view.words()
    );
    s += "<defs><marker id=\"axis-head\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" \
          markerWidth=\"7\" markerHeight=\"7\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\" \
          fill=\"#c0392b\"/></marker><marker id=\"triad-head\" viewBox=\"0 0 10 10\" refX=\"9\" \
          refY=\"5\" markerWidth=\"6\" markerHeight=\"6\" orient=\"auto\"><path \
          d=\"M0,0 L10,5 L0,10 z\" fill=\"#444444\"/></marker></defs>\n";
    let _ = writeln!(
        s,
        "<rect x=\"0.5\" y=\"0.5\" width=\"{}\" height=\"{}\" fill=\"#fcfcfa\" stroke=\"#dddddd\"/>",
        f(w - 1.0),
        f(h - 1.0)
    );
    s
}

/// The base, the fixed offset from it to the first joint (not a link), and both poses' links;
/// the base's and the first joint's places on the screen.
fn draw_base(
    s: &mut String,
    at: &dyn Fn(V3) -> (f64, f64),
    l: &Layout,
) -> ((f64, f64), (f64, f64)) {
    let (bx, by) = at([0.0; 3]);
    let _ = writeln!(
        s,
        "<path class=\"base\" d=\"M{},{} l-11,16 h22 z\" fill=\"#555555\"/>\
         <line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555555\" stroke-width=\"2\"/>",
        f(bx),
        f(by),
        f(bx - 18.0),
        f(by + 17.0),
        f(bx + 18.0),
        f(by + 17.0)
    );
    let first = at(l.conf[if l.conf.len() > 2 { 1 } else { 0 }]);
    let (colour, width, dash) = BASE_LINK;
    let _ = writeln!(
        s,
        "<line id=\"dq-base-link\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{colour}\" \
         stroke-width=\"{width}\" stroke-dasharray=\"{dash}\"/>",
        f(bx),
        f(by),
        f(first.0),
        f(first.1)
    );
    let pts = |line: &[V3]| -> String {
        line.iter()
            .map(|p| {
                let (x, y) = at(*p);
                format!("{},{}", f(x), f(y))
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    for (id, line, (colour, width, dash)) in [("dq-home", &l.home, HOME), ("dq-arm", &l.conf, ARM)]
    {
        let _ = writeln!(
            s,
            "<polyline id=\"{id}\" points=\"{}\" fill=\"none\" stroke=\"{colour}\" \
             stroke-width=\"{width}\" stroke-dasharray=\"{dash}\" stroke-linejoin=\"round\"/>",
            pts(links(line))
        );
    }
    ((bx, by), first)
}

/// The joints of the configuration with their axes (hidden in a planar view); the joints'
/// places on the screen and the axes' segments.
fn draw_joints(
    s: &mut String,
    at: &dyn Fn(V3) -> (f64, f64),
    l: &Layout,
) -> (Vec<(f64, f64)>, Vec<Segment>) {
    let conf = &l.conf;
    let arrow = 0.16 * l.reach;
    let screen: Vec<(f64, f64)> = conf[1..conf.len() - 1].iter().map(|p| at(*p)).collect();
    let mut axis_segments = Vec::new();
    for (i, ((x, y), n)) in screen.iter().zip(&l.axes).enumerate() {
        let p = conf[i + 1];
        let (tx, ty) = at([
            p[0] + n[0] * arrow,
            p[1] + n[1] * arrow,
            p[2] + n[2] * arrow,
        ]);
        if !l.view.planar {
            axis_segments.push(((*x, *y), (tx, ty)));
        }
        let _ = writeln!(
            s,
            "<line class=\"dq-axis\" data-i=\"{i}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" \
             stroke=\"#c0392b\" stroke-width=\"1.5\" marker-end=\"url(#axis-head)\"{}/>",
            f(*x),
            f(*y),
            f(tx),
            f(ty),
            if l.view.planar {
                " visibility=\"hidden\""
            } else {
                ""
            }
        );
    }
    for (i, (x, y)) in screen.iter().enumerate() {
        let p = conf[i + 1];
        let _ = writeln!(
            s,
            "<circle class=\"dq-joint\" data-i=\"{i}\" data-xyz=\"{:.9},{:.9},{:.9}\" cx=\"{}\" \
             cy=\"{}\" r=\"6\" fill=\"#ffffff\" stroke=\"#1f5fbf\" stroke-width=\"2\"/>",
            p[0],
            p[1],
            p[2],
            f(*x),
            f(*y)
        );
        if l.view.planar {
            let _ = writeln!(
                s,
                "<circle class=\"dq-dot\" data-i=\"{i}\" cx=\"{}\" cy=\"{}\" r=\"2\" fill=\"#c0392b\"/>",
                f(*x),
                f(*y)
            );
        }
    }
    (screen, axis_segments)
}

/// The tool point; its place on the screen.
fn draw_tool(s: &mut String, at: &dyn Fn(V3) -> (f64, f64), l: &Layout) -> (f64, f64) {
    let t = l.conf[l.conf.len() - 1];
    let (tx, ty) = at(t);
    let _ = writeln!(
        s,
        "<rect id=\"dq-tool\" data-xyz=\"{:.9},{:.9},{:.9}\" x=\"{}\" y=\"{}\" width=\"9\" \
         height=\"9\" fill=\"#1f5fbf\"/>",
        t[0],
        t[1],
        t[2],
        f(tx - 4.5),
        f(ty - 4.5)
    );
    (tx, ty)
}

pub(crate) fn xml_escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

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
