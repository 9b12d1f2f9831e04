//! Where the drawing is seen from and where its joint labels go; the page's script
//! (`page.js`) runs the same rules when a slider moves or the view is dragged.
//!
//! The view is an orthographic projection along a direction given by azimuth and elevation,
//! chosen so that no link is foreshortened: of a grid of directions, the one whose smallest
//! ratio of a link's drawn length to its true length (over the home pose and the drawn
//! configuration) is largest, ties going to the directions nearest the isometric one. A fixed
//! isometric view draws a UR-type arm at its default pose as a knot: its upper arm points at
//! the viewer.

/// A point or direction in space.
pub(crate) type V3 = [f64; 3];

/// A label's box on the screen: x, y, width, height.
pub(crate) type LabelBox = [f64; 4];

/// The direction the mechanism is seen from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct View {
    /// Degrees about z from the x axis.
    pub azimuth: f64,
    /// Degrees above the xy plane.
    pub elevation: f64,
    /// A planar mechanism, drawn in its yz plane (x out of the page).
    pub planar: bool,
}

/// The isometric view: the azimuth and elevation of the direction (1, 1, 1).
pub(crate) const ISOMETRIC: (f64, f64) = (45.0, 35.264_389_682_754_654);

impl View {
    /// The screen's right and up directions in space (unit, orthogonal).
    pub(crate) fn basis(&self) -> (V3, V3) {
        if self.planar {
            return ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        }
        let (a, e) = (self.azimuth.to_radians(), self.elevation.to_radians());
        (
            [-a.sin(), a.cos(), 0.0],
            [-e.sin() * a.cos(), -e.sin() * a.sin(), e.cos()],
        )
    }

    /// The direction towards the viewer (unit).
    fn toward(&self) -> V3 {
        let (a, e) = (self.azimuth.to_radians(), self.elevation.to_radians());
        [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
    }

    /// A point on the screen relative to the drawing's centre, y down, in units of length.
    pub(crate) fn project(&self, p: V3) -> (f64, f64) {
        let (r, u) = self.basis();
        let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        (dot(p, r), -dot(p, u))
    }

    /// The words of the legend: `view of the yz plane` or `view from azimuth 45°, elevation 35°`.
    pub(crate) fn words(&self) -> String {
        if self.planar {
            "view of the yz plane".to_owned()
        } else {
            format!(
                "view from azimuth {:.0}°, elevation {:.0}°",
                self.azimuth, self.elevation
            )
        }
    }
}

/// The smallest ratio of drawn to true length over the segments of `lines` longer than a
/// millionth of their total (shorter ones are points at any view).
fn least_ratio(v: &View, segments: &[V3]) -> f64 {
    let d = v.toward();
    segments
        .iter()
        .map(|s| {
            let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            let c = (s[0] * d[0] + s[1] * d[1] + s[2] * d[2]) / n;
            (1.0 - c * c).max(0.0).sqrt()
        })
        .fold(1.0, f64::min)
}

/// The view of a mechanism whose polylines (home pose, configuration) are `lines`: planar
/// mechanisms in their plane; others from the direction of the grid (every 5° of azimuth,
/// elevations 5° to 65°) that foreshortens the worst link least. A small penalty for the
/// distance from the isometric view breaks ties (many directions see a vertical link
/// equally), so a mechanism the isometric view shows well keeps it.
pub(crate) fn choose_view(lines: &[&[V3]], planar: bool) -> View {
    if planar {
        return View {
            azimuth: 0.0,
            elevation: 0.0,
            planar,
        };
    }
    let mut segments = Vec::new();
    let mut total = 0.0;
    for l in lines {
        for w in l.windows(2) {
            let s = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
            let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
            total += n;
            segments.push((s, n));
        }
    }
    let segments: Vec<V3> = segments
        .into_iter()
        .filter(|(_, n)| *n > 1e-6 * total)
        .map(|(s, _)| s)
        .collect();
    let (ia, ie) = ISOMETRIC;
    let mut best = (f64::NEG_INFINITY, ia, ie);
    for k in 0..72 {
        let azimuth = 5.0 * f64::from(k);
        for j in 1..=13 {
            let elevation = 5.0 * f64::from(j);
            let v = View {
                azimuth,
                elevation,
                planar,
            };
            let turn = ((azimuth - ia + 540.0) % 360.0 - 180.0).abs();
            // 0.1 of ratio per 90° away from the isometric direction: a view that shows the
            // worst link 10% longer is worth turning by a right angle.
            let score = least_ratio(&v, &segments) - 0.1 * (turn + (elevation - ie).abs()) / 90.0;
            if score > best.0 {
                best = (score, azimuth, elevation);
            }
        }
    }
    View {
        azimuth: best.1,
        elevation: best.2,
        planar,
    }
}

fn meets(a: &LabelBox, b: &LabelBox) -> bool {
    a[0] < b[0] + b[2] && b[0] < a[0] + a[2] && a[1] < b[1] + b[3] && b[1] < a[1] + a[3]
}

/// Whether the segment `p`-`q` passes through the box `b` (Liang-Barsky clipping).
pub(crate) fn crosses(b: &LabelBox, p: (f64, f64), q: (f64, f64)) -> bool {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (pp, qq) in [
        (-dx, p.0 - b[0]),
        (dx, b[0] + b[2] - p.0),
        (-dy, p.1 - b[1]),
        (dy, b[1] + b[3] - p.1),
    ] {
        if pp == 0.0 {
            if qq < 0.0 {
                return false;
            }
        } else {
            let t = qq / pp;
            if pp < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return false;
            }
        }
    }
    true
}

/// A drawn segment on the screen.
pub(crate) type Segment = ((f64, f64), (f64, f64));

/// Boxes for the labels of joints at screen points `pts` (texts `1`, `2`, ...): for each, the
/// first place around its joint (16 directions, growing distance) inside `area` whose box
/// meets no label placed before, no joint, not the tool at `tool`, and (widened by the
/// 2 px of a link's half stroke) no segment of `avoid`; failing that, the first that only
/// keeps off labels and joints. The page's script runs the same rule.
pub(crate) fn place_labels(
    pts: &[(f64, f64)],
    tool: (f64, f64),
    avoid: &[Segment],
    area: LabelBox,
) -> Vec<LabelBox> {
    let mut joints: Vec<LabelBox> = pts
        .iter()
        .map(|(x, y)| [x - 7.0, y - 7.0, 14.0, 14.0])
        .collect();
    joints.push([tool.0 - 6.0, tool.1 - 6.0, 12.0, 12.0]);
    let inside = |b: &LabelBox| {
        b[0] >= area[0]
            && b[1] >= area[1]
            && b[0] + b[2] <= area[0] + area[2]
            && b[1] + b[3] <= area[1] + area[3]
    };
    let mut placed: Vec<LabelBox> = Vec::new();
    for (i, (x, y)) in pts.iter().enumerate() {
        let w = 8.0 * (i + 1).to_string().len() as f64 + 4.0;
        let h = 16.0;
        let free = |b: &LabelBox, placed: &[LabelBox], links: bool| {
            let wide = [b[0] - 2.0, b[1] - 2.0, b[2] + 4.0, b[3] + 4.0];
            inside(b)
                && !placed.iter().chain(&joints).any(|o| meets(b, o))
                && !(links && avoid.iter().any(|(p, q)| crosses(&wide, *p, *q)))
        };
        let mut best = None;
        'pass: for links in [true, false] {
            for step in 0..12 {
                let r = 13.0 + 6.0 * f64::from(step);
                for k in 0..16 {
                    let a = (22.5 * f64::from(k) - 45.0).to_radians();
                    let (cx, cy) = (x + r * a.cos(), y + r * a.sin());
                    let b = [cx - w / 2.0, cy - h / 2.0, w, h];
                    if free(&b, &placed, links) {
                        best = Some(b);
                        break 'pass;
                    }
                }
            }
        }
        placed.push(best.unwrap_or([x + 10.0, y - 24.0, w, h]));
    }
    placed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_segment_through_a_box_crosses_it_and_one_beside_it_does_not() {
        let b = [0.0, 0.0, 10.0, 10.0];
        assert!(crosses(&b, (-5.0, 5.0), (15.0, 5.0)));
        assert!(crosses(&b, (5.0, 5.0), (5.0, 6.0)));
        assert!(!crosses(&b, (-5.0, -1.0), (15.0, -1.0)));
        assert!(!crosses(&b, (11.0, -5.0), (30.0, 20.0)));
    }

    #[test]
    fn a_link_along_the_isometric_direction_turns_the_view() {
        // A link pointing at the isometric viewer is a point in that view; the chosen view
        // shows it at most slightly foreshortened, and a vertical link beside it too.
        let line = [[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [1.0, 1.0, 2.0]];
        let v = choose_view(&[&line], false);
        let iso = View {
            azimuth: ISOMETRIC.0,
            elevation: ISOMETRIC.1,
            planar: false,
        };
        let segs = [[1.0, 1.0, 1.0], [0.0, 0.0, 1.0]];
        assert!(least_ratio(&iso, &segs[..1]) < 1e-6);
        assert!(least_ratio(&v, &segs) > 0.5, "{v:?}");
    }
}
