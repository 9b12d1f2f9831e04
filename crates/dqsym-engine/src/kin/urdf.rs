//! URDF import: a serial chain of a URDF file as a screw-form (or local-form) [`Robot`],
//! exactly.
//!
//! Each joint of the chain from the base link to the tip link has an `origin` (a constant
//! frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` from its parent link) and an `axis` in its
//! own frame. The pose `F₁ J₁(q₁) F₂ J₂(q₂) … Fₙ Jₙ(qₙ)` is rewritten in product-of-exponentials
//! form (the paper's sec 6): joint i turns about (or slides along) its axis carried to the
//! base by `F₁ … Fᵢ`, the home pose, and the chain ends with the tool frames `F₁ … Fₙ` (whose
//! product is the tip's home pose). Fixed joints are frames like any other origin, so they
//! fold into the constants; a `mimic` joint's value is `multiplier · q + offset` in the
//! variable q of the joint it follows.
//!
//! That rewriting multiplies the frames out: joint i's axis holds every origin before it.
//! With numbers that is cheap, but each angle kept as a parameter (below) doubles the terms of
//! every later axis, and a few such angles put a 4-joint file past the term limit. A file
//! whose origins hold a parameter is therefore read in local form instead
//! ([`Convention::Local`]): each moving joint keeps the frames since the previous one and its
//! axis in its own frame ([`JointGeometry::Local`]), the frames after the last moving joint are
//! the tool frames, and nothing multiplies the frames together but the pose itself (which
//! `fk` then gives as its recurrence over the joint factors).
//!
//! Lengths are exact decimals read from the text (`0.4318` is 2159/5000). Angles are exact
//! too: an `rpy` angle (or a mimic offset of a revolute joint) within the tolerance of its
//! decimals of a multiple of pi/12 (1.5708, 3.14159; the rule robot files share,
//! [`super::angles`]) is read as that multiple, reported in
//! [`UrdfRobot::notes`]. Any other angle (-1.42889927219074, -0.17453), and every angle when
//! [`UrdfOptions::snap_angles`] is off, becomes a named parameter of the robot
//! (`ELBOW_yaw`): the results are exact in it, and its decimal is the robot's nominal value
//! ([`Robot::values`]), as a hand derivation names a constant angle.

use super::angles::{self, AngleReading};
use super::robot::{frame_dq, unit_numeric};
use super::{local_frame_dq, Chain, Convention, Frame, Joint, JointGeometry, JointKind, Robot};
use crate::emit::names::terminal_text;
use crate::{DualQuat, Scalar};
use num_rational::BigRational;
use num_traits::ToPrimitive;
use std::collections::{BTreeMap, BTreeSet};
use thiserror::Error;

/// How far (radians) an angle with 3 decimals may be from a multiple of pi/12 to be read as
/// it; with more decimals the tolerance is smaller ([`angles::snap_tolerance`]).
pub const SNAP_TOLERANCE: f64 = 1e-3;

/// The longest decimal literal, in digits, a URDF number may need.
const MAX_DIGITS: usize = 1_000;

/// Which chain of the file to read, and how.
#[derive(Clone, Debug)]
pub struct UrdfOptions {
    /// The last link of the chain; by default the only leaf link.
    pub tip: Option<String>,
    /// The first link of the chain; by default the root link.
    pub base: Option<String>,
    /// Read angles near a multiple of pi/12 as that multiple (reported); when off, every
    /// nonzero angle is a named parameter.
    pub snap_angles: bool,
}

impl Default for UrdfOptions {
    fn default() -> Self {
        UrdfOptions {
            tip: None,
            base: None,
            snap_angles: true,
        }
    }
}

/// A robot read from a URDF file, with what was rounded on the way.
#[derive(Clone, Debug)]
pub struct UrdfRobot {
    /// The chain, in screw form (local form when an origin holds a parameter).
    pub robot: Robot,
    /// One line per angle read as a multiple of pi (`joint `elbow`, origin rpy[0]: 1.5708
    /// read as pi/2`) or kept as a named parameter.
    pub notes: Vec<String>,
}

/// What is wrong with a URDF file; every message names the file and, where there is one, the
/// element.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum UrdfError {
    /// Not well-formed XML, or not a `<robot>`.
    #[error("{}: {}", terminal_text(file), terminal_text(message))]
    Xml {
        /// The file name.
        file: String,
        /// What is wrong, with line and column.
        message: String,
    },
    /// An element is missing, wrong or unsupported.
    #[error(
        "{}: {}: {}",
        terminal_text(file),
        terminal_text(element),
        terminal_text(message)
    )]
    Element {
        /// The file name.
        file: String,
        /// The element, as `joint `elbow`` or `link `tool0``.
        element: String,
        /// What is wrong.
        message: String,
    },
}

/// One `<joint>` as written.
struct UrdfJoint {
    name: String,
    kind: String,
    parent: String,
    child: String,
    xyz: [BigRational; 3],
    rpy: [BigRational; 3],
    axis: [BigRational; 3],
    mimic: Option<(String, BigRational, BigRational)>,
    line: u32,
}

/// Reads the chain of a URDF file. `file` names it in messages.
///
/// # Errors
/// Malformed XML, a joint without parent or child, a link that is not declared, a loop, an
/// unknown or unsupported joint type (floating, planar), several leaf links without
/// `tip`.
pub fn parse_urdf(text: &str, file: &str, o: &UrdfOptions) -> Result<UrdfRobot, UrdfError> {
    let xml_err = |message: String| UrdfError::Xml {
        file: file.to_string(),
        message,
    };
    let doc = roxmltree::Document::parse(text).map_err(|e| xml_err(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        return Err(xml_err(format!(
            "the root element is <{}>, expected <robot>",
            root.tag_name().name()
        )));
    }
    let el_err = |element: String, message: String| UrdfError::Element {
        file: file.to_string(),
        element,
        message,
    };
    let (links, joints) = read_elements(text, root, &el_err)?;
    let parent_of = tree(&links, &joints, &el_err)?;
    let tip = choose_tip(o, &links, &joints, &parent_of, &xml_err, &el_err)?;
    let (path, base_link) = path_to_tip(o, &tip, &joints, &parent_of, &el_err)?;

    // Names: one variable per moving joint, named after it (a mimic joint uses its
    // leader's), and one parameter per angle that is not read as a multiple of pi.
    let by_name: BTreeMap<&str, &UrdfJoint> = joints.iter().map(|j| (j.name.as_str(), j)).collect();
    let mut names = Names::default();
    let mut notes = Vec::new();
    let mut params: Vec<(String, f64)> = Vec::new();
    let mut angle = |x: &BigRational,
                     what: String,
                     param: String,
                     names: &mut Names|
     -> Result<Scalar, UrdfError> {
        match snap_angle(x, o.snap_angles) {
            Some((s, note)) => {
                if let Some(n) = note {
                    notes.push(format!("{what}: {n}"));
                }
                Ok(s)
            }
            None => {
                let v = x
                    .to_f64()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| el_err(what.clone(), "the angle is out of range".into()))?;
                let name = names.fresh(&param);
                names.params.insert(name.clone());
                notes.push(format!(
                    "{what}: {} kept as the parameter `{name}`{}",
                    decimal_text(x),
                    match (o.snap_angles, angles::read_angle(x)) {
                        (false, _) => String::new(),
                        (true, AngleReading::Literal { near: Some(k) }) => {
                            format!(" ({})", angles::near_note(x, k))
                        }
                        (true, _) => " (not near a multiple of pi/12)".to_owned(),
                    }
                ));
                params.push((name.clone(), v));
                Ok(Scalar::sym(&name))
            }
        }
    };

    let mut read = Vec::with_capacity(path.len());
    let mut variables: Vec<String> = Vec::new();
    // Whether an origin angle was kept as a parameter (a symbol other than pi).
    let mut origin_params = false;
    for &k in &path {
        let j = &joints[k];
        let el = format!("joint `{}` (line {})", j.name, j.line);
        let stem = sanitize(&j.name);
        let mut rpy = Vec::with_capacity(3);
        for (k, part) in ["roll", "pitch", "yaw"].into_iter().enumerate() {
            let what = format!("{el}, origin rpy[{k}]");
            rpy.push(angle(
                &j.rpy[k],
                what,
                format!("{stem}_{part}"),
                &mut names,
            )?);
        }
        let rpy: [Scalar; 3] = rpy.try_into().expect("three angles");
        origin_params |= rpy.iter().any(|a| a.symbols().iter().any(|s| !s.is_pi()));
        let frame = Frame {
            xyz: j.xyz.clone().map(Scalar::rational),
            rpy,
        };
        let fdq =
            frame_dq(&frame.xyz, &frame.rpy).map_err(|e| el_err(el.clone(), e.to_string()))?;
        let kind = match j.kind.as_str() {
            "fixed" => {
                read.push(ReadJoint {
                    frame,
                    fdq,
                    motion: None,
                });
                continue;
            }
            "revolute" | "continuous" => JointKind::Revolute,
            "prismatic" => JointKind::Prismatic,
            _ => unreachable!("read_joint refuses other types"),
        };
        let axis = unit_numeric(&j.axis.clone().map(Scalar::rational))
            .map_err(|m| el_err(el.clone(), format!("<axis>: {m}")))?;
        let value = match &j.mimic {
            None => Scalar::sym(&names.var_of(&j.name)),
            Some((leader, mult, offset)) => {
                let err = |m: String| el_err(el.clone(), m);
                let (lead, m, off) =
                    mimic_leader(&by_name, leader, mult, offset, joints.len(), &err)?;
                let off = match kind {
                    JointKind::Revolute => angle(
                        &off,
                        format!("{el}, mimic offset"),
                        format!("{stem}_offset"),
                        &mut names,
                    )?,
                    JointKind::Prismatic => Scalar::rational(off),
                };
                Scalar::rational(m) * Scalar::sym(&names.var_of(lead)) + off
            }
        };
        names.add_variables(&value, &mut variables);
        read.push(ReadJoint {
            frame,
            fdq,
            motion: Some((kind, axis, value)),
        });
    }
    let name = root.attribute("name").unwrap_or(file);
    let name = format!("{name} ({base_link} to {tip})");
    Ok(assemble(
        read,
        origin_params,
        name,
        variables,
        params,
        notes,
    ))
}

/// The robot of the joints read: in local form when an origin holds a parameter, else in
/// screw form.
fn assemble(
    read: Vec<ReadJoint>,
    origin_params: bool,
    name: String,
    variables: Vec<String>,
    params: Vec<(String, f64)>,
    notes: Vec<String>,
) -> UrdfRobot {
    // A file whose origins are numbers is written in screw form (its home axes are numbers
    // too); an origin at an angle kept as a parameter keeps every joint in its own frame,
    // since carrying the axes to the base multiplies out the frames before them and each
    // symbolic angle doubles the terms of every later axis.
    let (chain, frames, values, convention) = if origin_params {
        local_chain(read)
    } else {
        screw_chain(read)
    };
    let decimals = origin_lengths(&read_frames(&chain, &frames));
    UrdfRobot {
        robot: Robot {
            name,
            convention,
            variables,
            joint_values: values,
            chain,
            base_frames: Vec::new(),
            tool_frames: frames,
            tool: None,
            values: params,
            notes: notes.clone(),
            decimals,
        },
        notes,
    }
}

/// One joint of the chain as read: its origin frame, that frame as a DQ, and for a moving
/// joint its kind, unit axis (in its own frame) and value.
struct ReadJoint {
    frame: Frame,
    fdq: DualQuat<Scalar>,
    motion: Option<(JointKind, [Scalar; 3], Scalar)>,
}

/// The chain, its tool frames, joint values and convention.
type Built = (Chain<Scalar>, Vec<Frame>, Vec<Scalar>, Convention);

/// The screw form: joint i turns about its axis carried to the base by the frames before it
/// (the home pose); every frame is a tool frame, their product the tool motion.
fn screw_chain(read: Vec<ReadJoint>) -> Built {
    let mut home = DualQuat::identity();
    let (mut joints, mut frames, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for r in read {
        home = home * r.fdq;
        frames.push(r.frame);
        let Some((kind, axis, value)) = r.motion else {
            continue;
        };
        let dir = DualQuat::from_real(home.real.clone()).transform_point(&axis);
        joints.push(match kind {
            JointKind::Revolute => Joint::revolute_screw(dir, home.translation_part()),
            JointKind::Prismatic => Joint::prismatic_screw(dir),
        });
        values.push(value);
    }
    let chain = Chain::new(joints).with_tool(home);
    (chain, frames, values, Convention::Screw)
}

/// The local form: each moving joint holds the frames since the previous moving joint and its
/// axis in its own frame ([`JointGeometry::Local`]); the frames after the last moving joint are
/// the tool frames.
fn local_chain(read: Vec<ReadJoint>) -> Built {
    let (mut joints, mut pending, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for r in read {
        pending.push((r.frame.xyz, r.frame.rpy));
        let Some((kind, axis, value)) = r.motion else {
            continue;
        };
        let frames = std::mem::take(&mut pending);
        joints.push(Joint::new(kind, JointGeometry::Local { frames, axis }));
        values.push(value);
    }
    let tool: Vec<Frame> = pending
        .into_iter()
        .map(|(xyz, rpy)| Frame { xyz, rpy })
        .collect();
    let motion = tool.iter().fold(DualQuat::identity(), |acc, f| {
        acc * local_frame_dq(&(f.xyz.clone(), f.rpy.clone()))
    });
    let chain = Chain::new(joints).with_tool(motion);
    (chain, tool, values, Convention::Local)
}

/// Every origin frame of the chain: the joints' own (local form) and the tool frames.
fn read_frames(chain: &Chain<Scalar>, tool: &[Frame]) -> Vec<Frame> {
    let mut out: Vec<Frame> = chain
        .joints
        .iter()
        .flat_map(|j| match &j.geometry {
            JointGeometry::Local { frames, .. } => frames.clone(),
            _ => Vec::new(),
        })
        .map(|(xyz, rpy)| Frame { xyz, rpy })
        .collect();
    out.extend(tool.iter().cloned());
    out
}

/// URDF numbers are decimals by the format: the lengths of the chain's origins, sorted and
/// distinct.
fn origin_lengths(frames: &[Frame]) -> Vec<BigRational> {
    let mut decimals: Vec<BigRational> = frames
        .iter()
        .flat_map(|f| f.xyz.iter().filter_map(Scalar::as_rational))
        .map(|x| num_traits::Signed::abs(&x))
        .filter(|x| !num_traits::Zero::is_zero(x))
        .collect();
    decimals.sort();
    decimals.dedup();
    decimals
}

/// An element error of the file being read: (element, message).
type ElErr<'a> = dyn Fn(String, String) -> UrdfError + 'a;

/// The `<link>` names and the `<joint>`s of the document, with their line numbers.
fn read_elements(
    text: &str,
    root: roxmltree::Node,
    el_err: &ElErr,
) -> Result<(BTreeSet<String>, Vec<UrdfJoint>), UrdfError> {
    let mut links: BTreeSet<String> = BTreeSet::new();
    let mut joints: Vec<UrdfJoint> = Vec::new();
    // Line numbers counted as the elements come, in document order: `text_pos_at` scans the
    // text from its start at each call, quadratic in the elements (most of the time of a URDF
    // of 2,000 joints).
    let (mut counted, mut row) = (0usize, 1u32);
    for node in root.children().filter(|n| n.is_element()) {
        let start = node.range().start;
        if start >= counted {
            row += text.as_bytes()[counted..start]
                .iter()
                .filter(|&&b| b == b'\n')
                .count() as u32;
            counted = start;
        }
        let line = row;
        match node.tag_name().name() {
            "link" => {
                let name = node
                    .attribute("name")
                    .ok_or_else(|| el_err(format!("<link> at line {line}"), "no `name`".into()))?;
                links.insert(name.to_string());
            }
            "joint" => joints.push(read_joint(node, line, &el_err)?),
            _ => {}
        }
    }
    Ok((links, joints))
}

/// The parent joint of each link, checking that every joint joins two declared links, every
/// link has at most one parent joint and some link is the root.
fn tree<'a>(
    links: &BTreeSet<String>,
    joints: &'a [UrdfJoint],
    el_err: &ElErr,
) -> Result<BTreeMap<&'a str, usize>, UrdfError> {
    // Every joint joins two declared links; every link has at most one parent joint.
    let mut parent_of: BTreeMap<&str, usize> = BTreeMap::new();
    let mut names: BTreeSet<&str> = BTreeSet::new();
    for (i, j) in joints.iter().enumerate() {
        let el = || format!("joint `{}` (line {})", j.name, j.line);
        if !names.insert(&j.name) {
            return Err(el_err(el(), "a second joint with this name".into()));
        }
        for (role, l) in [("parent", &j.parent), ("child", &j.child)] {
            if !links.contains(l) {
                return Err(el_err(
                    el(),
                    format!("{role} link `{l}` is not a <link> of the file"),
                ));
            }
        }
        if let Some(&k) = parent_of.get(j.child.as_str()) {
            return Err(el_err(
                format!("link `{}`", j.child),
                format!(
                    "child of two joints, `{}` and `{}`: a URDF is a tree",
                    joints[k].name, j.name
                ),
            ));
        }
        parent_of.insert(&j.child, i);
    }
    let roots: Vec<&String> = links
        .iter()
        .filter(|l| !parent_of.contains_key(l.as_str()))
        .collect();
    if roots.is_empty() && !links.is_empty() {
        let l = links.iter().next().map(String::as_str).unwrap_or("");
        return Err(el_err(
            format!("link `{l}`"),
            "the joints form a loop: no link is the root".into(),
        ));
    }
    Ok(parent_of)
}

/// The tip link: `o.tip`, or the only leaf (several leaves are refused, listed with the number
/// of moving joints before each).
fn choose_tip(
    o: &UrdfOptions,
    links: &BTreeSet<String>,
    joints: &[UrdfJoint],
    parent_of: &BTreeMap<&str, usize>,
    xml_err: &dyn Fn(String) -> UrdfError,
    el_err: &ElErr,
) -> Result<String, UrdfError> {
    let is_parent: BTreeSet<&str> = joints.iter().map(|j| j.parent.as_str()).collect();
    Ok(match &o.tip {
        Some(t) => {
            if !links.contains(t) {
                return Err(el_err(format!("--tip `{t}`"), "no such <link>".into()));
            }
            t.clone()
        }
        None => {
            let leaves: Vec<&String> = links
                .iter()
                .filter(|l| !is_parent.contains(l.as_str()))
                .collect();
            match leaves.as_slice() {
                [one] => (*one).clone(),
                [] => return Err(xml_err("no links".into())),
                many => {
                    // Each leaf with the number of joints that move between it and the root
                    // (most first): the arm's tool is usually among the first.
                    let moving = |leaf: &str| {
                        let (mut at, mut n, mut hops) = (leaf, 0usize, 0usize);
                        while let Some(&k) = parent_of.get(at) {
                            n += usize::from(joints[k].kind != "fixed");
                            at = joints[k].parent.as_str();
                            hops += 1;
                            if hops > joints.len() {
                                break;
                            }
                        }
                        n
                    };
                    let mut listed: Vec<(usize, &String)> =
                        many.iter().map(|l| (moving(l), *l)).collect();
                    listed.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(b.1)));
                    return Err(xml_err(format!(
                        "several leaf links ({}): choose the tip with --tip",
                        listed
                            .iter()
                            .map(|(n, s)| format!(
                                "`{s}` after {n} moving joint{}",
                                if *n == 1 { "" } else { "s" }
                            ))
                            .collect::<Vec<_>>()
                            .join(", ")
                    )));
                }
            }
        }
    })
}

/// The joints from the base (`o.base`, or the root) to `tip`, in order, and the base link;
/// loops are refused.
fn path_to_tip(
    o: &UrdfOptions,
    tip: &str,
    joints: &[UrdfJoint],
    parent_of: &BTreeMap<&str, usize>,
    el_err: &ElErr,
) -> Result<(Vec<usize>, String), UrdfError> {
    // Walk from the tip to the base (or the root), refusing loops.
    let mut path: Vec<usize> = Vec::new();
    let mut at = tip;
    let mut seen: BTreeSet<&str> = BTreeSet::new();
    loop {
        if o.base.as_deref() == Some(at) {
            break;
        }
        if !seen.insert(at) {
            return Err(el_err(
                format!("link `{at}`"),
                "the joints form a loop through this link".into(),
            ));
        }
        match parent_of.get(at) {
            Some(&k) => {
                path.push(k);
                at = joints[k].parent.as_str();
            }
            None => {
                if let Some(b) = &o.base {
                    return Err(el_err(
                        format!("--base `{b}`"),
                        format!("not a link between the root `{at}` and the tip `{tip}`"),
                    ));
                }
                break;
            }
        }
    }
    let base_link = at.to_string();
    path.reverse();
    Ok((path, base_link))
}

/// The joint a `<mimic>` of `leader` (times `mult`, plus `offset`) finally follows, through
/// leaders that themselves follow another joint, with the composed factor and offset.
fn mimic_leader<'a>(
    by_name: &BTreeMap<&'a str, &'a UrdfJoint>,
    leader: &'a str,
    mult: &BigRational,
    offset: &BigRational,
    joints: usize,
    err: &dyn Fn(String) -> UrdfError,
) -> Result<(&'a str, BigRational, BigRational), UrdfError> {
    let (mut lead, mut m, mut off) = (leader, mult.clone(), offset.clone());
    let mut hops = 0;
    while let Some(Some((l2, m2, o2))) = by_name.get(lead).map(|lj| lj.mimic.as_ref()) {
        hops += 1;
        if hops > joints {
            return Err(err("<mimic> joints follow each other in a loop".into()));
        }
        off = &m * o2 + off;
        m = &m * m2;
        lead = l2;
    }
    if !by_name.contains_key(lead) {
        return Err(err(format!(
            "<mimic> follows `{lead}`, which is not a <joint>"
        )));
    }
    Ok((lead, m, off))
}

/// One `<joint>`: its attributes and children, or what is missing or unsupported.
fn read_joint(
    node: roxmltree::Node,
    line: u32,
    el_err: &dyn Fn(String, String) -> UrdfError,
) -> Result<UrdfJoint, UrdfError> {
    let name = node
        .attribute("name")
        .ok_or_else(|| el_err(format!("<joint> at line {line}"), "no `name`".into()))?
        .to_string();
    let el = format!("joint `{name}` (line {line})");
    let kind = node
        .attribute("type")
        .ok_or_else(|| el_err(el.clone(), "no `type`".into()))?
        .to_string();
    match kind.as_str() {
        "revolute" | "continuous" | "prismatic" | "fixed" => {}
        "floating" | "planar" => {
            return Err(el_err(
                el,
                format!("type `{kind}` is not supported: only one-degree-of-freedom joints (revolute, continuous, prismatic) and fixed joints make a serial chain"),
            ))
        }
        other => {
            return Err(el_err(
                el,
                format!("unknown type `{other}` (expected revolute, continuous, prismatic or fixed)"),
            ))
        }
    }
    let child = |tag: &str| node.children().find(|n| n.has_tag_name(tag));
    let link = |tag: &str| -> Result<String, UrdfError> {
        child(tag)
            .and_then(|n| n.attribute("link"))
            .map(str::to_string)
            .ok_or_else(|| el_err(el.clone(), format!("no <{tag} link=\"...\"/>")))
    };
    let (parent, child_link) = (link("parent")?, link("child")?);
    let vec = |tag: &str, attr: &str, default: [i64; 3]| -> Result<[BigRational; 3], UrdfError> {
        let Some(text) = child(tag).and_then(|n| n.attribute(attr)) else {
            return Ok(default.map(|x| BigRational::from_integer(x.into())));
        };
        let parts: Vec<&str> = text.split_whitespace().collect();
        if parts.len() != 3 {
            return Err(el_err(
                el.clone(),
                format!(
                    "<{tag} {attr}=\"{text}\">: expected 3 numbers, found {}",
                    parts.len()
                ),
            ));
        }
        let mut out = Vec::new();
        for p in parts {
            out.push(number(p).ok_or_else(|| {
                el_err(
                    el.clone(),
                    format!("<{tag} {attr}=\"{text}\">: `{p}` is not a number"),
                )
            })?);
        }
        Ok([out[0].clone(), out[1].clone(), out[2].clone()])
    };
    let mimic = match child("mimic") {
        None => None,
        Some(m) => {
            let leader = m
                .attribute("joint")
                .ok_or_else(|| el_err(el.clone(), "<mimic> without `joint`".into()))?
                .to_string();
            let num = |attr: &str, default: i64| -> Result<BigRational, UrdfError> {
                match m.attribute(attr) {
                    None => Ok(BigRational::from_integer(default.into())),
                    Some(t) => number(t).ok_or_else(|| {
                        el_err(el.clone(), format!("<mimic {attr}=\"{t}\">: not a number"))
                    }),
                }
            };
            Some((leader, num("multiplier", 1)?, num("offset", 0)?))
        }
    };
    Ok(UrdfJoint {
        xyz: vec("origin", "xyz", [0, 0, 0])?,
        rpy: vec("origin", "rpy", [0, 0, 0])?,
        axis: vec("axis", "xyz", [1, 0, 0])?,
        name,
        kind,
        parent,
        child: child_link,
        mimic,
        line,
    })
}

/// A URDF number, exactly.
fn number(text: &str) -> Option<BigRational> {
    crate::scalar::parse_decimal(text.trim(), MAX_DIGITS)
}

/// The exact angle an URDF angle stands for: itself when it is 0, else (when `snap`) the
/// multiple of pi/12 the shared rule reads it as ([`super::angles`]), with a note saying so;
/// `None` when it is neither: the caller names it (`near` the advice for a decimal with too
/// few digits near a multiple).
fn snap_angle(x: &BigRational, snap: bool) -> Option<(Scalar, Option<String>)> {
    match angles::read_angle(x) {
        AngleReading::Zero => Some((Scalar::int(0), None)),
        AngleReading::Multiple { twelfths } if snap => Some((
            angles::pi_twelfths(twelfths),
            Some(angles::snapped_note(x, twelfths)),
        )),
        _ => None,
    }
}

fn decimal_text(x: &BigRational) -> String {
    angles::number_text(x)
}

/// The names a URDF chain gives: variables after joints, parameters after angles, all distinct.
#[derive(Default)]
struct Names {
    var_names: BTreeMap<String, String>,
    used: BTreeSet<String>,
    params: BTreeSet<String>,
}

impl Names {
    /// The variable of a joint (the same name every time it is asked).
    fn var_of(&mut self, joint: &str) -> String {
        if let Some(v) = self.var_names.get(joint) {
            return v.clone();
        }
        let v = self.fresh(&sanitize(joint));
        self.var_names.insert(joint.to_string(), v.clone());
        v
    }

    /// Appends the symbols of a joint's value that are neither `pi` nor parameters to
    /// `variables`, each once.
    fn add_variables(&self, value: &Scalar, variables: &mut Vec<String>) {
        for s in value.symbols().iter().filter(|s| !s.is_pi()) {
            let n = s.name().to_string();
            if !variables.contains(&n) && !self.params.contains(&n) {
                variables.push(n);
            }
        }
    }

    /// `stem`, or `stem_`, `stem__`, ... : a name not given before.
    fn fresh(&mut self, stem: &str) -> String {
        let mut v = stem.to_string();
        while self.used.contains(&v) {
            v.push('_');
        }
        self.used.insert(v.clone());
        v
    }
}

/// A joint name as a variable name: letters, digits and `_`, starting with a letter, never a
/// name the language reserves (`pi`, `I`, `eps`, ...).
fn sanitize(name: &str) -> String {
    let mut s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !s.starts_with(|c: char| c.is_ascii_alphabetic()) {
        s = format!("q_{s}");
    }
    // The language's constants and keywords, and the built-ins a robot file could not use
    // as a symbol.
    const RESERVED: [&str; 5] = ["pi", "I", "eps", "syms", "halfangle"];
    if RESERVED.contains(&s.as_str()) {
        s = format!("q_{s}");
    }
    s
}
