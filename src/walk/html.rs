//! A walkthrough as one self-contained web page: the steps, formulas typeset by KaTeX in the
//! browser, and the drawing of the mechanism. KaTeX's script, stylesheet and fonts are inlined
//! (fonts as `data:` URIs), so the page needs no network when it is viewed.

use super::svg::{number, range, scene_svg, slides, xml_escape, Config, Scene, SvgOptions, Symbol};
use super::text::{page, Piece};
use super::{Forms, Mechanism, WalkError, Walkthrough};
use crate::{
    emit::{javascript_function, latex_symbol, CodegenOptions, Output},
    Expr, Scalar,
};

/// KaTeX ready to inline: its stylesheet with the fonts embedded, and its script.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct KatexAssets {
    css: String,
    js: String,
}

impl KatexAssets {
    /// From `katex.min.css` and `katex.min.js`; `font` returns the bytes of a file of
    /// `dist/fonts/` by name. Each `@font-face` keeps its WOFF2 source, as a `data:` URI.
    ///
    /// # Errors
    /// When a font the stylesheet names is missing.
    pub fn new(
        css: &str,
        js: &str,
        font: &dyn Fn(&str) -> Option<Vec<u8>>,
    ) -> Result<KatexAssets, WalkError> {
        let mut out = String::with_capacity(css.len());
        let mut rest = css;
        while let Some(i) = rest.find("src:") {
            out.push_str(&rest[..i]);
            rest = &rest[i + 4..];
            let end = rest.find([';', '}']).unwrap_or(rest.len());
            let decl = &rest[..end];
            rest = &rest[end..];
            let woff2 = decl.split(',').find(|e| e.contains("woff2"));
            let name = woff2.and_then(|e| {
                let start = e.find("url(")? + 4;
                let stop = e[start..].find(')')? + start;
                Some(e[start..stop].trim_matches(['"', '\'']).to_owned())
            });
            let Some(name) = name else {
                out.push_str("src:");
                out.push_str(decl);
                continue;
            };
            let file = name.rsplit('/').next().unwrap_or(&name);
            let bytes = font(file).ok_or_else(|| {
                WalkError::Config(format!(
                    "KaTeX font `{file}` is missing from katex/dist/fonts"
                ))
            })?;
            out.push_str(&format!(
                "src:url(data:font/woff2;base64,{}) format(\"woff2\")",
                base64(&bytes)
            ));
        }
        out.push_str(rest);
        Ok(KatexAssets {
            css: out,
            // A script body must not close its own element.
            js: js.replace("</script", "<\\/script"),
        })
    }
}

fn base64(b: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(b.len().div_ceil(3) * 4);
    for c in b.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Prose with `$...$` math and `` `code` `` as HTML: math becomes elements KaTeX fills in.
fn inline(t: &str) -> String {
    let mut out = String::new();
    for (i, part) in t.split('$').enumerate() {
        if i % 2 == 1 {
            out += &format!(
                "<span class=\"tex\" data-tex=\"{}\"></span>",
                xml_escape(part)
            );
        } else {
            for (k, c) in part.split('`').enumerate() {
                if k % 2 == 1 {
                    out += &format!("<code>{}</code>", xml_escape(c));
                } else {
                    out += &xml_escape(c);
                }
            }
        }
    }
    out
}

/// The page's style. Display formulas scroll sideways inside their own box when wider than
/// the column, with shadows at the edges that have more to show (the scroll cue; the
/// backgrounds attached `local` cover the shadows when scrolled to that end); nothing makes the
/// page itself wider than the window, down to a phone's 390 px.
const STYLE: &str = "body{font-family:Georgia,serif;margin:0;color:#222;line-height:1.45;\
overflow-wrap:anywhere}main{max-width:1560px;margin:0 auto;padding:1em 16px}h1{font-size:1.6em}\
h2{font-size:1.15em;margin-top:1.6em;border-bottom:1px solid #ddd}\
.display{overflow-x:auto;overflow-y:hidden;margin:.6em 0 .6em 1em;padding:0 2px;\
scrollbar-width:thin;overflow-wrap:normal;\
background:linear-gradient(to right,#fff 30%,rgba(255,255,255,0)) left/32px 100% no-repeat local,\
linear-gradient(to left,#fff 30%,rgba(255,255,255,0)) right/32px 100% no-repeat local,\
radial-gradient(farthest-side at 0 50%,rgba(0,0,0,.28),rgba(0,0,0,0)) left/12px 100% no-repeat scroll,\
radial-gradient(farthest-side at 100% 50%,rgba(0,0,0,.28),rgba(0,0,0,0)) right/12px 100% no-repeat scroll}\
.display.scrolls{border-bottom:1px dashed #b8c4d8}\
span.tex.wide{display:inline-block;max-width:100%;overflow-x:auto;overflow-y:hidden;\
vertical-align:bottom;border-bottom:1px dashed #b8c4d8}\
p.legend .tex,li .tex{overflow-wrap:normal}\
figure{margin:0;flex:0 1 600px;max-width:600px;min-width:0}figcaption{font-size:.9em;color:#555}\
code{font-size:.9em}.layout{display:grid;grid-template-columns:minmax(0,1fr);gap:24px}\
.steps{min-width:0}.live{display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start;min-width:0}\
.controls{flex:1 1 300px;min-width:0;font-family:sans-serif;font-size:14px}\
.drawing-legend{font-family:sans-serif;font-size:13px;line-height:1.35;margin-bottom:4px}\
.drawing-legend p{margin:0 0 2px}.drawing-legend .swatch{vertical-align:middle}\
svg.mechanism{max-width:100%;height:auto;display:block;touch-action:pan-y;cursor:grab}\
.slider{display:grid;grid-template-columns:fit-content(40%) minmax(0,1fr) 4.5em;align-items:center;\
gap:6px}.slider>.tex{min-width:3em;overflow-x:auto;overflow-y:hidden}\
.slider output{font-variant-numeric:tabular-nums;text-align:right}\
.table-scroll{overflow-x:auto;max-width:100%}\
table.num{border-collapse:collapse;margin:.4em 0 .8em;white-space:nowrap;overflow-wrap:normal}table.num td,table.num th{padding:1px 5px;\
text-align:right;font-variant-numeric:tabular-nums;border-left:1px solid #ccc;font-weight:normal}\
table.num caption{text-align:left;font-weight:bold;padding-bottom:2px;white-space:normal}\
table.ik{font-size:13px}table.ik tr:first-child td{border-bottom:1px solid #ccc}\
details.code pre{font-size:11px;max-height:24em;overflow:auto;background:#f6f6f2;padding:6px}\
@media (max-width:600px){.display{margin-left:0}table.ik{font-size:12px}\
table.num td,table.num th{padding:1px 3px}}\
@media (min-width:1400px){.layout{grid-template-columns:minmax(0,1fr) 620px}\
.live{grid-column:2;grid-row:1;position:sticky;top:8px;align-self:start;max-height:calc(100vh - 16px);\
overflow-y:auto}.steps{grid-column:1;grid-row:1}.controls{flex-basis:100%}figure{flex-basis:100%}}";

/// KaTeX fills in every formula; a display wider than its box is marked (`scrolls`: a dashed
/// rule under it beside the edge shadows), and an inline formula that cannot break to fit
/// (`wide`) becomes a box of the column's width that scrolls, with the same rule. Every
/// measurement is read before any class is written, so the page is laid out once, not once
/// per formula.
const RENDER: &str = "document.querySelectorAll('[data-tex]').forEach(function(el){\
katex.render(el.getAttribute('data-tex'),el,{displayMode:el.classList.contains('display'),\
throwOnError:false});});function dqMarkScrolls(){var ds=document.querySelectorAll('.display'),\
ts=document.querySelectorAll('span.tex.wide');ts.forEach(function(el){el.classList.remove('wide');});\
var wide=[].filter.call(document.querySelectorAll('span.tex'),function(el){\
var p=el.parentElement.getBoundingClientRect(),r=el.getBoundingClientRect();\
return r.right>p.right+1||r.left<p.left-1;});var sc=[].map.call(ds,function(el){\
return el.scrollWidth>el.clientWidth+1;});wide.forEach(function(el){el.classList.add('wide');});\
ds.forEach(function(el,i){el.classList.toggle('scrolls',sc[i]);});}dqMarkScrolls();\
window.addEventListener('resize',dqMarkScrolls);document.fonts.ready.then(dqMarkScrolls);\
document.querySelectorAll('details').forEach(function(d){d.addEventListener('toggle',dqMarkScrolls);});";

/// The page's script: sliders, redrawing, numbers (see the file's first comment).
const PAGE_JS: &str = include_str!("page.js");

/// `**bold**` in legend prose.
fn bold(t: &str) -> String {
    let mut out = String::new();
    for (i, part) in t.split("**").enumerate() {
        if i % 2 == 1 {
            out += &format!("<strong>{part}</strong>");
        } else {
            out += part;
        }
    }
    out
}

/// The drawing's legend as HTML (text that wraps at any width), with the ids the page's
/// script updates.
fn legend_html(lines: &[super::svg::LegendLine]) -> String {
    let mut s = String::from("<div class=\"drawing-legend\">\n");
    for l in lines {
        let swatch = l.swatch.map_or(String::new(), |(colour, w, dash)| {
            format!(
                "<svg class=\"swatch\" width=\"30\" height=\"8\" aria-hidden=\"true\"><line x1=\"0\" \
                 y1=\"4\" x2=\"30\" y2=\"4\" stroke=\"{colour}\" stroke-width=\"{w}\" \
                 stroke-dasharray=\"{dash}\"/></svg> "
            )
        });
        let id = l.id.map(|i| format!(" id=\"{i}\"")).unwrap_or_default();
        s += &format!("<p>{swatch}<span{id}>{}</span></p>\n", xml_escape(&l.text));
    }
    s + "</div>\n"
}

/// The live part of the page: the drawing, a slider per symbol, the numbers, and the
/// generated function; `None` when the closed forms cannot be compiled to JavaScript.
fn live(m: &Mechanism, cfg: &Config, forms: &Forms) -> Result<(String, Option<String>), WalkError> {
    let scene = Scene::new(m, cfg)?;
    let opts = SvgOptions {
        legend: false,
        ..SvgOptions::default()
    };
    let layout = scene.layout()?;
    let scale = (opts.width / 2.0 - 24.0) / layout.reach;
    let legend = legend_html(&super::svg::legend_lines(&scene, &layout, scale));
    let drawing = scene_svg(&scene, &opts)?;
    let Ok(code) = live_function(&scene, forms) else {
        let mut s = String::from("<aside class=\"live\">\n<figure>\n");
        s += &legend;
        s += &drawing;
        s += "<figcaption>The mechanism drawn to scale at the configuration in the legend.</figcaption>\n</figure>\n</aside>\n";
        return Ok((s, None));
    };
    let view = layout.view;
    let mut s = String::from("<aside class=\"live\" id=\"live\">\n<figure>\n");
    s += &legend;
    s += &drawing;
    s += if view.planar {
        "<figcaption>The mechanism to scale. Move the sliders: the arm and the numbers are \
          recomputed by the function below, generated from the closed forms.</figcaption>\n"
    } else {
        "<figcaption>The mechanism to scale. Move the sliders: the arm and the numbers are \
          recomputed by the function below, generated from the closed forms. Drag the drawing \
          to turn the view.</figcaption>\n"
    };
    s += "</figure>\n<div class=\"controls\">\n";
    for (joint, what) in [(true, "Joints"), (false, "Lengths")] {
        let items: Vec<&Symbol> = scene
            .symbols
            .iter()
            .filter(|x| x.joint.is_some() == joint)
            .collect();
        if items.is_empty() {
            continue;
        }
        s += &format!("<p><strong>{what}</strong></p>\n");
        for x in items {
            let (lo, hi) = range(x);
            s += &format!(
                "<label class=\"slider\"><span class=\"tex\" data-tex=\"{}\"></span>\
                 <input type=\"range\" data-name=\"{}\"{} min=\"{lo}\" max=\"{hi}\" step=\"any\" \
                 value=\"{}\"><output>{}</output></label>\n",
                xml_escape(&latex_symbol(&x.name)),
                xml_escape(&x.name),
                if joint { " data-joint=\"1\"" } else { "" },
                x.value,
                number(x.value)
            );
        }
    }
    s += "<table class=\"num\"><caption>Tool point</caption><tr>";
    for k in 0..3 {
        s += &format!("<td data-out=\"p\" data-k=\"{k}\"></td>");
    }
    s += "</tr></table>\n<table class=\"num\"><caption>Pose: the 4x4 matrix</caption>";
    for i in 0..4 {
        s += "<tr>";
        for j in 0..4 {
            s += &format!("<td data-out=\"T\" data-k=\"{}\"></td>", 4 * i + j);
        }
        s += "</tr>";
    }
    s += "</table>\n<table class=\"num\"><caption>Pose: the dual quaternion (w, x, y, z) + \
          &#949; (w, x, y, z)</caption>";
    for part in 0..2 {
        s += "<tr>";
        for k in 0..4 {
            s += &format!("<td data-out=\"dq\" data-k=\"{}\"></td>", 4 * part + k);
        }
        s += "</tr>";
    }
    s += "</table>\n<details class=\"code\"><summary>The generated JavaScript</summary><pre>";
    s += &xml_escape(&code);
    s += "</pre></details>\n</div>\n</aside>\n";
    let args: Vec<String> = scene
        .symbols
        .iter()
        .map(|x| format!("\"{}\"", x.name))
        .collect();
    let data = format!(
        "{{\"args\":[{}],\"planar\":{},\"azimuth\":{},\"elevation\":{},\"width\":{},\
         \"legend\":0,\"slides\":{}}}",
        args.join(","),
        view.planar,
        view.azimuth,
        view.elevation,
        opts.width,
        slides(&scene.symbols)
    );
    let scripts = format!(
        "<script id=\"dq-data\" type=\"application/json\">{data}</script>\n<script>{}</script>\n<script>{}</script>\n",
        code.replace("</script", "<\\/script"),
        PAGE_JS.replace("</script", "<\\/script")
    );
    Ok((s, Some(scripts)))
}

/// The function of the page: the joints, their axes, the tool, the pose as a matrix and as a
/// dual quaternion, from the exact scene, by the JavaScript emitter.
fn live_function(scene: &Scene, forms: &Forms) -> Result<String, WalkError> {
    let c = |x: &Scalar| forms.of(x).cloned();
    let rows3 = |v: &mut dyn Iterator<Item = &[Scalar; 3]>| -> Result<Vec<Vec<Expr>>, WalkError> {
        v.map(|p| p.iter().map(c).collect()).collect()
    };
    let joints = rows3(&mut scene.joints.iter().map(|(p, _)| p))?;
    let axes = rows3(&mut scene.joints.iter().map(|(_, n)| n))?;
    let m = &scene.matrix;
    let t: Vec<Vec<Expr>> = m
        .rows
        .iter()
        .map(|r| r.iter().map(c).collect())
        .collect::<Result<_, _>>()?;
    let dq: Vec<Expr> = scene
        .pose
        .components()
        .iter()
        .map(c)
        .collect::<Result<_, _>>()?;
    let mut outputs = vec![
        Output::vector(
            "tool",
            "The tool point.",
            scene.tool.iter().map(c).collect::<Result<_, _>>()?,
        ),
        Output::matrix("T", "The pose as a 4x4 homogeneous matrix.", t),
        Output::vector("dq", "The pose as a unit dual quaternion.", dq),
    ];
    if !joints.is_empty() {
        outputs.push(Output::matrix("joints", "Each joint's position.", joints));
        outputs.push(Output::matrix("axes", "Each joint's axis direction.", axes));
    }
    let args: Vec<String> = scene.symbols.iter().map(|x| x.name.clone()).collect();
    let mut code = javascript_function(
        "dqsym_walk",
        "The mechanism of the walkthrough at the sliders' values, from its closed forms.",
        &outputs,
        &args,
        &CodegenOptions::default(),
    )
    .map_err(|e| WalkError::Config(e.to_string()))?;
    if scene.joints.is_empty() {
        code = code.replace(
            "    return {\n",
            "    return {\n        joints: [],\n        axes: [],\n",
        );
    }
    Ok(code)
}

/// The walkthrough as a self-contained HTML page: the notation, the mechanism drawn to scale
/// at `cfg` with a slider per joint variable and length that redraws it and recomputes the
/// pose by JavaScript generated from the closed forms, and the derivation steps beside it.
///
/// # Errors
/// When a value cannot be shown or the mechanism cannot be evaluated.
pub fn walk_html(w: &Walkthrough, katex: &KatexAssets, cfg: &Config) -> Result<String, WalkError> {
    let title = format!("Walkthrough: {}", w.title);
    page_html(w, &title, katex, cfg, None)
}

/// The page of a walkthrough; `ik` adds the solver's panel beside the drawing and its script.
fn page_html(
    w: &Walkthrough,
    title: &str,
    katex: &KatexAssets,
    cfg: &Config,
    ik: Option<&crate::ik::IkSolution>,
) -> Result<String, WalkError> {
    let p = page(w)?;
    let mut body = format!("<h1>{}</h1>\n", xml_escape(title));
    for l in &p.legend {
        body += &format!("<p class=\"legend\">{}</p>\n", bold(&inline(l)));
    }
    body += "<div class=\"layout\">\n";
    let mut scripts = None;
    if let Some(m) = &w.mechanism {
        let (aside, js) = live(m, cfg, &w.forms)?;
        match ik {
            Some(sol) => {
                body += &aside.replacen("</aside>\n", &ik_panel(sol), 1);
                if let Some(js) = js {
                    scripts = Some(js + &ik_script(sol)?);
                }
            }
            None => {
                body += &aside;
                scripts = js;
            }
        }
    } else if let Some((name, _)) = cfg.values.first() {
        // No drawing, so no configuration: a --config name would be silently ignored.
        return Err(WalkError::Config(format!(
            "`{name}` is not a symbol of a drawing: this walkthrough has no drawing of a \
             mechanism, so --config has nothing to set"
        )));
    }
    body += "<div class=\"steps\">\n";
    for (head, parts) in p.sections {
        body += &format!("<section class=\"step\">\n<h2>{}</h2>\n", inline(&head));
        for p in parts {
            body += &piece_html(p);
        }
        body += "</section>\n";
    }
    body += "</div>\n</div>\n";
    Ok(html_page(title, katex, &body, scripts.as_deref()))
}

/// One piece of a step as HTML.
fn piece_html(p: Piece) -> String {
    match p {
        Piece::Text(t) => format!("<p>{}</p>\n", inline(&t)),
        Piece::Display(d) => format!(
            "<div class=\"tex display\" data-tex=\"{}\"></div>\n",
            xml_escape(&d)
        ),
        Piece::Folded(summary, d) => format!(
            "<details><summary>{}</summary>\n<div class=\"tex display\" data-tex=\"{}\"></div>\n</details>\n",
            inline(&summary),
            xml_escape(&d)
        ),
        Piece::List(items) => {
            let items: String = items
                .iter()
                .map(|i| format!("<li>{}</li>", inline(i)))
                .collect();
            format!("<ul>{items}</ul>\n")
        }
        Piece::Table(head, rows) => {
            let mut t = String::from("<div class=\"table-scroll\"><table class=\"num ik\"><tr>");
            for h in head {
                t += &format!("<th>{}</th>", inline(&h));
            }
            t += "</tr>";
            for r in rows {
                t += "<tr>";
                for c in r {
                    t += &format!("<td>{}</td>", inline(&c));
                }
                t += "</tr>";
            }
            t + "</table></div>\n"
        }
    }
}

/// The inverse kinematics walkthrough ([`super::walk_ik`]) as a self-contained page: the
/// derivation beside the mechanism with its sliders; each slider move recomputes the pose and
/// runs the derived solver on it (JavaScript generated from the same closed forms, or for an
/// arm solved by the general 6R method the JavaScript port of its numeric core), listing every
/// distinct solution with its flags and the deviation of its own pose from the target.
///
/// # Errors
/// When a closed form cannot be written or the mechanism cannot be evaluated.
pub fn ik_walk_html(
    w: &Walkthrough,
    sol: &crate::ik::IkSolution,
    katex: &KatexAssets,
    cfg: &Config,
) -> Result<String, WalkError> {
    let title = format!("Inverse kinematics walkthrough: {}", sol.robot);
    page_html(w, &title, katex, cfg, Some(sol))
}

/// The solver's table beside the drawing: a head with the joint variables typeset, the rows
/// written by the page's script.
fn ik_panel(sol: &crate::ik::IkSolution) -> String {
    let mut head = String::from("<tr><th>#</th>");
    for (k, v) in sol.variables.iter().enumerate() {
        head += &format!(
            "<th title=\"{}\">{}</th>",
            xml_escape(v),
            inline(&super::ik::column_head(v, k))
        );
    }
    head += "<th title=\"branches that give it\">×</th><th title=\"deviation of its pose\">dev.</th></tr>";
    format!(
        "<div class=\"controls\"><div class=\"table-scroll\"><table class=\"num ik\" \
         id=\"ik-solutions\"><caption>The solver on this pose: every distinct solution; ×: how \
         many branches give it (more than one where they meet at a singularity), * singular, \
         ~ approximate (the closest reach); dev.: how far its own pose is from the target</caption><thead>{head}</thead><tbody></tbody></table></div>{key}</div>\n</aside>\n",
        key = super::ik::column_key(&sol.variables)
            .map(|k| format!("<p>{}</p>", inline(&k)))
            .unwrap_or_default()
    )
}

/// The solver of the page: one generated function per step (its parts from the target, the
/// parameters and the joints solved before), the axes and home pose (`dqsym_ik_chain`), the
/// numeric helpers every solver shares ([`crate::ik::ik_javascript_helpers`]: tolerances,
/// candidates, the check by forward kinematics) and a driver that branches as
/// [`crate::ik::candidates`] does; for the general method ([`crate::ik::ik_javascript_general`])
/// the driver hands the axes, home pose and target to its core instead of the (absent) steps.
fn ik_script(sol: &crate::ik::IkSolution) -> Result<String, WalkError> {
    use crate::ik::{Formula, TARGET_SYMBOLS};
    let forms = sol.forms()?;
    let target: Vec<String> = TARGET_SYMBOLS
        .iter()
        .flatten()
        .map(|s| s.to_string())
        .collect();
    let mut code = String::new();
    let mut steps = Vec::new();
    let mut solved: Vec<String> = Vec::new();
    for (k, (step, parts)) in sol.steps.iter().zip(forms).enumerate() {
        let args: Vec<String> = target
            .iter()
            .chain(&sol.params)
            .chain(&solved)
            .cloned()
            .collect();
        let outputs: Vec<Output> = parts
            .iter()
            .map(|(n, e)| Output::scalar(&format!("part_{n}"), "A part of the step.", e.clone()))
            .collect();
        code += &javascript_function(
            &format!("dqsym_ik_step{k}"),
            &format!(
                "Step {}: the parts of the formula for {}.",
                k + 1,
                step.variable
            ),
            &outputs,
            &args,
            &CodegenOptions::default(),
        )
        .map_err(|e| WalkError::Config(e.to_string()))?;
        let kind = match step.formula {
            Formula::Atan2 { .. } => "atan2",
            Formula::Trig { .. } => "trig",
            Formula::Value { .. } => "value",
            Formula::Linear { .. } => "linear",
            Formula::Quadratic { .. } => "quadratic",
        };
        let names: Vec<String> = parts.iter().map(|(n, _)| format!("\"part_{n}\"")).collect();
        let quoted: Vec<String> = args.iter().map(|a| format!("\"{a}\"")).collect();
        steps.push(format!(
            "{{\"f\":dqsym_ik_step{k},\"kind\":\"{kind}\",\"var\":\"{}\",\"joint\":{},\"args\":[{}],\"parts\":[{}]}}",
            step.variable,
            step.joint,
            quoted.join(","),
            names.join(",")
        ));
        solved.push(step.variable.clone());
    }
    // The axes and the home pose from the parameters, for the check of each solution.
    let mut chain = Vec::new();
    let closed =
        |x: &crate::Scalar| crate::closed_form(x).map_err(|e| WalkError::Config(e.to_string()));
    for (i, a) in sol.axes.iter().enumerate() {
        for (k, x) in a.dir.iter().chain(&a.point).enumerate() {
            chain.push(Output::scalar(
                &format!("ax{i}_{k}"),
                "An axis entry.",
                closed(x)?,
            ));
        }
    }
    for (r, row) in sol.home.rows.iter().take(3).enumerate() {
        for (c, x) in row.iter().enumerate() {
            chain.push(Output::scalar(
                &format!("home{r}{c}"),
                "A home pose entry.",
                closed(x)?,
            ));
        }
    }
    code += &javascript_function(
        "dqsym_ik_chain",
        "The joint axes (direction, point) and the home pose.",
        &chain,
        &sol.params,
        &CodegenOptions::default(),
    )
    .map_err(|e| WalkError::Config(e.to_string()))?;
    let degrees = crate::ik::ik_step_degrees(sol).map_err(|e| WalkError::Config(e.to_string()))?;
    let kinds: Vec<String> = sol
        .axes
        .iter()
        .map(|a| u8::from(a.kind == crate::JointKind::Prismatic).to_string())
        .collect();
    let quoted = |v: &[String]| -> String {
        v.iter()
            .map(|x| format!("\"{x}\""))
            .collect::<Vec<_>>()
            .join(",")
    };
    let degrees: Vec<String> = degrees.iter().map(i32::to_string).collect();
    let data = format!(
        "const IK = {{\"steps\":[{}],\"vars\":[{}],\"params\":[{}],\"kinds\":[{}],\"degrees\":[{}],\"position_only\":{},\"general\":{}}};\n",
        steps.join(","),
        quoted(&sol.variables),
        quoted(&sol.params),
        kinds.join(","),
        degrees.join(","),
        sol.position_only,
        sol.general.is_some()
    );
    // An arm solved by the general 6R method: its numeric core instead of the steps.
    let general = if sol.general.is_some() {
        crate::ik::ik_javascript_general(sol)
    } else {
        String::new()
    };
    Ok(format!(
        "<script>{}{data}{}{}{}</script>\n",
        code.replace("</script", "<\\/script"),
        crate::ik::ik_javascript_helpers(sol).replace("</script", "<\\/script"),
        general.replace("</script", "<\\/script"),
        IK_JS
    ))
}

/// The page's IK driver: after each slider move, the target from `dqsym_walk`, every branch of
/// the solver, each solution's own pose from `dqsym_walk` again.
const IK_JS: &str = r#"(function () {
    "use strict";
    const D = JSON.parse(document.getElementById("dq-data").textContent);
    const inputs = Array.from(document.querySelectorAll("input[data-name]"));
    const TARGET = ["r11","r12","r13","px","r21","r22","r23","py","r31","r32","r33","pz"];
    // Every branch, as the other solvers do: each step's candidates with its rounding
    // IK_ZERO_TOL L^d, each complete solution through ik_push (checked by forward kinematics
    // where a step asks for it, refined, flagged, de-duplicated).
    function solve(env, T) {
        const ch = dqsym_ik_chain(...IK.params.map((n) => env[n]));
        const ax = IK.kinds.map((k, i) => [k].concat([0, 1, 2, 3, 4, 5].map((j) => ch[`ax${i}_${j}`])));
        const home = [0, 1, 2].map((r) => [0, 1, 2, 3].map((c) => ch[`home${r}${c}`]));
        if (IK.general) return ik_general(ax, home, T);
        const len = ik_scale(ax, home, T);
        const out = [];
        (function go(k, env, sg, ck, smp) {
            if (k === IK.steps.length) {
                const q = IK.vars.map((n) => env[n]);
                ik_push(out, q, sg, ck, smp, ax, home, T, len, IK.position_only);
                return;
            }
            const s = IK.steps[k];
            const r = s.f(...s.args.map((n) => env[n]));
            const sig = IK_ZERO_TOL * Math.pow(len, IK.degrees[k]);
            const n0 = out.length;
            for (const [v, s1, c1, m1] of ik_cands(s.kind, s.parts.map((p) => r[p]), sig)) {
                // The pair beside a double root, for poses only near the singular set.
                if (m1 && s.kind === "trig" && out.slice(n0).some((row) => !row[2])) continue;
                env[s.var] = v;
                go(k + 1, env, sg || s1, ck || c1, smp || m1);
            }
            delete env[s.var];
        })(0, Object.assign({}, env), false, false, false);
        return out;
    }
    const run = (v) => dqsym_walk(...D.args.map((n) => v[n]));
    // The end ik solves for is the one fk reports: at the tool point, with the last frame's axes.
    const pose = (v) => {
        const w = run(v);
        return w.T.map((row, r) => (r < 3 ? [row[0], row[1], row[2], w.tool[r]] : row));
    };
    function update() {
        const v = {};
        for (const i of inputs) v[i.dataset.name] = Number(i.value);
        const T = pose(v);
        const env = Object.assign({}, v);
        TARGET.forEach((n, i) => { env[n] = T[Math.floor(i / 4)][i % 4]; });
        for (const n of IK.vars) delete env[n];
        const sols = solve(env, T);
        // Branches that meet at a singularity are one solution (ik.rs `merge`, SAME_SOLUTION).
        const rows = [];
        const same = (a, b) => IK.vars.every((n) => {
            const d = Math.abs(a[n] - b[n]) % (2 * Math.PI);
            return Math.min(d, 2 * Math.PI - d) < 1e-9;
        });
        for (const [q, sing, approx] of sols) {
            const s = {};
            IK.vars.forEach((n, i) => { s[n] = q[i]; });
            const r = rows.find((r) => same(r.s, s));
            if (r) {
                r.n += 1;
                r.sing = r.sing || sing;
                r.approx = r.approx || approx;
            } else rows.push({ s, sing, approx, n: 1 });
        }
        const table = document.getElementById("ik-solutions");
        let h = "";
        rows.forEach(({ s, sing, approx, n }, k) => {
            const back = pose(Object.assign({}, v, s));
            let dev = 0;
            for (let r = 0; r < 3; r++) for (let c = 0; c < 4; c++) {
                if (IK.position_only && c < 3) continue;
                dev = Math.max(dev, Math.abs(back[r][c] - T[r][c]));
            }
            h += `<tr data-dev="${dev}" data-q="${IK.vars.map((n) => s[n]).join(",")}"><td>${k + 1}</td>` +
                IK.vars.map((n) => `<td>${s[n].toFixed(3)}</td>`).join("") +
                `<td>${n}${sing ? "*" : ""}${approx ? "~" : ""}</td><td>${dev.toExponential(0)}</td></tr>`;
        });
        table.querySelector("tbody").innerHTML = h;
        table.dataset.count = String(rows.length);
        table.dataset.branches = String(sols.length);
    }
    inputs.forEach((i) => i.addEventListener("input", update));
    update();
})();
"#;

/// The tag every page carries in its head: how `dqsym walk --html` recognizes a file it wrote
/// (one it may write over without `--force`).
pub const PAGE_MARKER: &str = "<meta name=\"generator\" content=\"dqsym walk\">";

/// Whether `head`, the start of a file (its first kilobytes), is a page `dqsym walk --html`
/// wrote: it starts with the doctype and carries [`PAGE_MARKER`] in its head.
pub fn is_walk_page(head: &str) -> bool {
    let head = head.trim_start_matches('\u{feff}');
    head.starts_with("<!DOCTYPE html>")
        && head
            .split("</head>")
            .next()
            .is_some_and(|h| h.contains(PAGE_MARKER))
}

/// The page around a walkthrough's body: KaTeX's style and script inlined, the page's own
/// style and renderer, and the mechanism's scripts (if any) last.
fn html_page(title: &str, katex: &KatexAssets, body: &str, scripts: Option<&str>) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         {PAGE_MARKER}\n<title>{}</title>\n<style>{}</style>\n<style>{STYLE}</style>\n</head>\n<body>\n<main>\n\
         {body}</main>\n<script>{}</script>\n<script>{RENDER}</script>\n{}</body>\n</html>\n",
        xml_escape(title),
        katex.css,
        katex.js,
        scripts.unwrap_or_default()
    )
}
