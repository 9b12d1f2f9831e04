//! A walkthrough as one self-contained web page: the steps, formulas typeset by KaTeX in the
//! browser, and the drawing of the mechanism. KaTeX's script, stylesheet and fonts are inlined
//! (fonts as `data:` URIs), so the page needs no network when it is viewed.

use super::svg::{mechanism_svg, xml_escape, Config, SvgOptions};
use super::text::{page, Piece};

use super::{WalkError, Walkthrough};

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

const STYLE: &str = "body{font-family:Georgia,serif;max-width:980px;margin:2em auto;padding:0 1em;\
color:#222;line-height:1.45}h1{font-size:1.6em}h2{font-size:1.15em;margin-top:1.6em;\
border-bottom:1px solid #ddd}.display{overflow-x:auto;margin:.6em 0 .6em 1.5em}\
figure{margin:1em 0}figcaption{font-size:.9em;color:#555}code{font-size:.9em}";

const RENDER: &str = "document.querySelectorAll('[data-tex]').forEach(function(el){\
katex.render(el.getAttribute('data-tex'),el,{displayMode:el.classList.contains('display'),\
throwOnError:false});});";

/// The walkthrough as a self-contained HTML page, with the mechanism drawn at `cfg`.
///
/// # Errors
/// When a value cannot be shown or the mechanism cannot be evaluated.
pub fn walk_html(w: &Walkthrough, katex: &KatexAssets, cfg: &Config) -> Result<String, WalkError> {
    let title = format!("Walkthrough: {}", w.title);
    let p = page(w)?;
    let mut body = format!("<h1>{}</h1>\n", xml_escape(&title));
    for l in &p.legend {
        body += &format!("<p class=\"legend\">{}</p>\n", inline(l));
    }
    if let Some(m) = &w.mechanism {
        body += "<figure>\n";
        body += &mechanism_svg(m, cfg, &SvgOptions::default())?;
        body += "<figcaption>The mechanism of the final result: links through the joints, \
                 joint axes as arrows.</figcaption>\n</figure>\n";
    }
    for (head, parts) in p.sections {
        body += &format!("<section class=\"step\">\n<h2>{}</h2>\n", inline(&head));
        for p in parts {
            match p {
                Piece::Text(t) => body += &format!("<p>{}</p>\n", inline(&t)),
                Piece::Display(d) => {
                    body += &format!(
                        "<div class=\"tex display\" data-tex=\"{}\"></div>\n",
                        xml_escape(&d)
                    )
                }
                Piece::Folded(summary, d) => {
                    body += &format!(
                        "<details><summary>{}</summary>\n<div class=\"tex display\" data-tex=\"{}\"></div>\n</details>\n",
                        inline(&summary),
                        xml_escape(&d)
                    )
                }
            }
        }
        body += "</section>\n";
    }
    Ok(format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>{}</title>\n<style>{}</style>\n<style>{STYLE}</style>\n</head>\n<body>\n<main>\n\
         {body}</main>\n<script>{}</script>\n<script>{RENDER}</script>\n</body>\n</html>\n",
        xml_escape(&title),
        katex.css,
        katex.js
    ))
}
