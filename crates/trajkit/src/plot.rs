//! SVG plots of sampled trajectories, with limits.
//!
//! [`svg`] draws small multiples: one row per joint and one column per derivative present in
//! the table (position q, velocity q̇, acceleration q̈, jerk q⃛). Every panel has its own value
//! range, widened to include the joint's finite limits, which are drawn as dashed red lines
//! (the position range for q; the maximum and the possibly direction-dependent minimum for the
//! derivatives). The curve is a dark blue polyline.
//!
//! Long tables are decimated per panel: the samples falling in each pixel column are reduced
//! to their minimum and maximum (kept in time order), so a one-sample spike still shows at its
//! full height while a panel never holds more than two points per pixel column.
//!
//! The output is a self-contained SVG document built as a string; it needs no dependency.
//!
//! ```
//! use trajkit::{plot::{svg, PlotOptions}, Limits, SampleTable};
//! let t = vec![0.0, 0.5, 1.0];
//! let table = SampleTable::new(1, t, [Some(vec![0.0, 0.4, 1.0]), None, None, None])?;
//! let doc = svg(&table, Some(&Limits::uniform(1, 2.0, 5.0, 50.0)?), &PlotOptions::default())?;
//! assert!(doc.starts_with("<svg"));
//! # Ok::<(), trajkit::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::limits::Limits;
use crate::sample::SampleTable;
use crate::traj::Order;
use std::fmt::Write as _;

/// Size and title of a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotOptions {
    /// Title written above the panels (may be empty).
    pub title: String,
    /// Width of the whole figure in pixels (default 1200).
    pub width: f64,
    /// Height of one row of panels in pixels (default 110).
    pub panel_height: f64,
}

impl Default for PlotOptions {
    fn default() -> Self {
        PlotOptions {
            title: String::new(),
            width: 1200.0,
            panel_height: 110.0,
        }
    }
}

const CURVE: &str = "#1a3a7a";
const LIMIT: &str = "#d62728";
const GRID: &str = "#e4e4e4";
const FRAME: &str = "#888888";

/// Left column holding the joint names.
const LABEL_W: f64 = 110.0;
/// Space for the value tick labels left of each panel.
const YAXIS_W: f64 = 52.0;
/// Gap right of each panel.
const PANEL_GAP: f64 = 12.0;
/// Space below each panel for the time tick labels.
const XAXIS_H: f64 = 16.0;
/// Gap above each panel.
const ROW_GAP: f64 = 6.0;

/// Escapes text for XML content and attribute values.
fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&apos;"),
            // Characters XML 1.0 does not allow at all.
            c if (c as u32) < 0x20 && !matches!(c, '\t' | '\n' | '\r') => s.push('?'),
            c => s.push(c),
        }
    }
    s
}

/// Column header of a derivative, with its unit.
fn header(order: Order) -> &'static str {
    match order {
        Order::Position => "q [rad]",
        Order::Velocity => "q\u{307} [rad/s]",
        Order::Acceleration => "q\u{308} [rad/s²]",
        Order::Jerk => "q\u{20db} [rad/s³]",
    }
}

/// A "nice" step (1, 2 or 5 × 10^k) giving about `count` intervals over `span`.
fn nice_step(span: f64, count: f64) -> f64 {
    let raw = span / count.max(1.0);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// Tick values within `[lo, hi]` and the number of decimals to print them with.
fn ticks(lo: f64, hi: f64, count: f64) -> (Vec<f64>, usize) {
    let step = nice_step(hi - lo, count);
    if !(step.is_finite() && step > 0.0) {
        return (vec![lo], 0);
    }
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let v = (first..=last.min(first + 50))
        .map(|k| k as f64 * step)
        .collect();
    (v, decimals)
}

fn tick_label(x: f64, decimals: usize) -> String {
    let s = format!("{x:.decimals$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// Indices of the samples to draw: all when they fit, else per pixel column the minimum and
/// the maximum, in time order.
fn decimate(t: &[f64], v: &[f64], t0: f64, t1: f64, pixels: usize) -> Vec<usize> {
    let n = t.len();
    let pixels = pixels.max(1);
    if n <= 2 * pixels {
        return (0..n).collect();
    }
    let scale = pixels as f64 / (t1 - t0);
    let column = |ti: f64| (((ti - t0) * scale) as usize).min(pixels - 1);
    let mut out = Vec::with_capacity(2 * pixels);
    let mut current = column(t[0]);
    let (mut lo, mut hi) = (0usize, 0usize);
    let flush = |out: &mut Vec<usize>, lo: usize, hi: usize| {
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push(a);
        if b != a {
            out.push(b);
        }
    };
    for i in 1..n {
        let c = column(t[i]);
        if c != current {
            flush(&mut out, lo, hi);
            current = c;
            lo = i;
            hi = i;
        } else {
            if v[i] < v[lo] {
                lo = i;
            }
            if v[i] > v[hi] {
                hi = i;
            }
        }
    }
    flush(&mut out, lo, hi);
    out
}

/// Where things go: the panels' columns (one per order the table has), sizes and time span.
struct Layout {
    orders: Vec<Order>,
    cell_w: f64,
    plot_w: f64,
    plot_h: f64,
    panel_height: f64,
    t0: f64,
    t1: f64,
    title_h: f64,
    top: f64,
    width: f64,
    height: f64,
}

impl Layout {
    /// The layout of `table` drawn with `opts`; errors as [`svg`] says.
    fn new(table: &SampleTable, opts: &PlotOptions) -> Result<Layout> {
        if table.is_empty() {
            return Err(Error::InvalidValue {
                field: "sample table row count".into(),
                value: 0.0,
                reason: "leaves nothing to plot",
            });
        }
        let orders: Vec<Order> = Order::ALL.into_iter().filter(|&o| table.has(o)).collect();
        let ncols = orders.len() as f64;
        let cell_w = (opts.width - LABEL_W) / ncols;
        let plot_w = cell_w - YAXIS_W - PANEL_GAP;
        if !(opts.width.is_finite() && plot_w >= 20.0) {
            return Err(Error::InvalidValue {
                field: "plot width".into(),
                value: opts.width,
                reason: "is too small (or not finite) for the panels",
            });
        }
        let plot_h = opts.panel_height - XAXIS_H - ROW_GAP;
        if !(opts.panel_height.is_finite() && plot_h >= 20.0) {
            return Err(Error::InvalidValue {
                field: "plot panel height".into(),
                value: opts.panel_height,
                reason: "is too small (or not finite); use at least 42",
            });
        }
        let times = table.times();
        let (mut t0, mut t1) = (times[0], times[table.len() - 1]);
        if t1 <= t0 {
            t0 -= 0.5;
            t1 += 0.5;
        }
        let title_h = if opts.title.is_empty() { 8.0 } else { 30.0 };
        let header_h = 18.0;
        let top = title_h + header_h;
        Ok(Layout {
            orders,
            cell_w,
            plot_w,
            plot_h,
            panel_height: opts.panel_height,
            t0,
            t1,
            title_h,
            top,
            width: opts.width,
            height: top + table.dof() as f64 * opts.panel_height + 24.0,
        })
    }

    /// Left edge of the plot area of column `c`.
    fn px(&self, c: usize) -> f64 {
        LABEL_W + c as f64 * self.cell_w + YAXIS_W
    }

    /// Top edge of the plot area of joint `j`'s row.
    fn py(&self, j: usize) -> f64 {
        self.top + j as f64 * self.panel_height + ROW_GAP
    }
}

/// Draws `table` as an SVG document (see the module documentation). With `limits`, their
/// joint count must match the table's; joint names come from the table, else the limits.
///
/// Errors: [`Error::DimensionMismatch`] for limits of another joint count;
/// [`Error::InvalidValue`] for an empty table or a size too small to draw in.
pub fn svg(table: &SampleTable, limits: Option<&Limits>, opts: &PlotOptions) -> Result<String> {
    if let Some(l) = limits {
        l.expect_dof(table.dof(), "the plotted table")?;
    }
    let lay = Layout::new(table, opts)?;
    let (width, height) = (lay.width, lay.height);
    let mut s = String::new();
    document_head(&mut s, &lay, &opts.title);
    let mut series = vec![0.0; table.len()];
    for j in 0..table.dof() {
        joint_row(&mut s, &lay, table, limits, j, &mut series);
    }
    // `write!` into a String cannot fail; its results are ignored here and below.
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">t [s]</text>"#,
        LABEL_W + (width - LABEL_W) / 2.0,
        height - 6.0
    );
    s.push_str("</svg>\n");
    Ok(s)
}

/// The `<svg>` element, its background, the title (when not empty) and the column headers.
fn document_head(s: &mut String, lay: &Layout, title: &str) {
    let (width, height) = (lay.width, lay.height);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="10">"#
    );
    let _ = writeln!(
        s,
        r#"<rect width="{width}" height="{height}" fill="white"/>"#
    );
    if !title.is_empty() {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="20" font-size="14" text-anchor="middle">{}</text>"#,
            width / 2.0,
            escape(title)
        );
    }
    for (c, &order) in lay.orders.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle">{}</text>"#,
            lay.px(c) + lay.plot_w / 2.0,
            lay.title_h + 12.0,
            escape(header(order))
        );
    }
}

/// Joint `j`'s row: its name and one panel per plotted order the table has (`series` is
/// scratch of the table's length).
fn joint_row(
    s: &mut String,
    lay: &Layout,
    table: &SampleTable,
    limits: Option<&Limits>,
    j: usize,
    series: &mut [f64],
) {
    let dof = table.dof();
    let jl = limits.map(|l| l.joint(j));
    let name = match (table.names().get(j), jl) {
        (Some(n), _) if !n.is_empty() => n.clone(),
        (_, Some(l)) if !l.name.is_empty() => l.name.clone(),
        _ => format!("joint {}", j + 1),
    };
    let _ = writeln!(
        s,
        r#"<text class="joint" x="6" y="{:.1}" font-size="11">{}</text>"#,
        lay.py(j) + lay.plot_h / 2.0 + 4.0,
        escape(&name)
    );
    for (c, &order) in lay.orders.iter().enumerate() {
        let Some(m) = table.matrix(order) else {
            continue;
        };
        for (i, x) in series.iter_mut().enumerate() {
            *x = m[i * dof + j];
        }
        let limit_values: Vec<f64> = match jl {
            Some(l) => {
                let (lo, hi) = l.range(order);
                [lo, hi].into_iter().filter(|x| x.is_finite()).collect()
            }
            None => Vec::new(),
        };
        let at = (lay.px(c), lay.py(j));
        panel(s, lay, at, (j, order), table.times(), series, &limit_values);
    }
}

/// The value range of a panel: `series` and `limit_values`, padded by 6 % (or around a
/// constant).
fn value_range(series: &[f64], limit_values: &[f64]) -> (f64, f64) {
    let (mut lo, mut hi) = series
        .iter()
        .chain(limit_values.iter())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let span = hi - lo;
    if span <= 1e-12 * lo.abs().max(hi.abs()) || span <= f64::MIN_POSITIVE {
        let pad = (lo.abs() * 0.1).max(1.0);
        lo -= pad;
        hi += pad;
    } else {
        lo -= 0.06 * span;
        hi += 0.06 * span;
    }
    (lo, hi)
}

/// A panel's grid with value and time ticks, and its frame, for values in `[lo, hi]`.
fn panel_axes(s: &mut String, lay: &Layout, (px, py): (f64, f64), (lo, hi): (f64, f64)) {
    let (t0, t1, plot_w, plot_h) = (lay.t0, lay.t1, lay.plot_w, lay.plot_h);
    let xmap = |t: f64| px + (t - t0) / (t1 - t0) * plot_w;
    let ymap = |v: f64| py + (hi - v) / (hi - lo) * plot_h;
    // Grid and value ticks.
    let (yt, yd) = ticks(lo, hi, (plot_h / 28.0).max(2.0));
    for v in yt {
        let y = ymap(v);
        let _ = writeln!(
            s,
            r#"<line x1="{px:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="{GRID}"/><text x="{:.2}" y="{:.2}" text-anchor="end">{}</text>"#,
            px + plot_w,
            px - 4.0,
            y + 3.5,
            tick_label(v, yd)
        );
    }
    // Time ticks.
    let (xt, xd) = ticks(t0, t1, (plot_w / 60.0).max(2.0));
    for t in xt {
        let x = xmap(t);
        let _ = writeln!(
            s,
            r#"<line x1="{x:.2}" y1="{py:.2}" x2="{x:.2}" y2="{:.2}" stroke="{GRID}"/><text x="{x:.2}" y="{:.2}" text-anchor="middle">{}</text>"#,
            py + plot_h,
            py + plot_h + 12.0,
            tick_label(t, xd)
        );
    }
    let _ = writeln!(
        s,
        r#"<rect x="{px:.2}" y="{py:.2}" width="{plot_w:.2}" height="{plot_h:.2}" fill="none" stroke="{FRAME}"/>"#
    );
}

/// One panel at `(px, py)`: joint `j`'s `series` of `order` over `times`, the value range
/// padded around the series and its finite `limit_values`, grid, ticks, frame, limit lines
/// and the (decimated) curve.
fn panel(
    s: &mut String,
    lay: &Layout,
    (px, py): (f64, f64),
    (j, order): (usize, Order),
    times: &[f64],
    series: &[f64],
    limit_values: &[f64],
) {
    let (t0, t1, plot_w) = (lay.t0, lay.t1, lay.plot_w);
    let (lo, hi) = value_range(series, limit_values);
    let xmap = |t: f64| px + (t - t0) / (t1 - t0) * plot_w;
    let ymap = |v: f64| py + (hi - v) / (hi - lo) * lay.plot_h;
    let _ = writeln!(
        s,
        r#"<g class="panel" data-joint="{j}" data-order="{}">"#,
        order.name()
    );
    panel_axes(s, lay, (px, py), (lo, hi));
    for v in limit_values {
        let y = ymap(*v);
        let _ = writeln!(
            s,
            r#"<line class="limit" x1="{px:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="{LIMIT}" stroke-width="1" stroke-dasharray="5 3"><title>limit {}</title></line>"#,
            px + plot_w,
            escape(&format!("{v}"))
        );
    }
    let keep = decimate(times, series, t0, t1, plot_w.floor() as usize);
    let _ = write!(
        s,
        r#"<polyline fill="none" stroke="{CURVE}" stroke-width="1.2" stroke-linejoin="round" points=""#
    );
    for (k, &i) in keep.iter().enumerate() {
        if k > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{:.2},{:.2}", xmap(times[i]), ymap(series[i]));
    }
    s.push_str("\"/>\n</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::JointLimits;

    fn table(n: usize, with_derivs: bool) -> SampleTable {
        let t: Vec<f64> = (0..n).map(|i| i as f64 / (n - 1) as f64).collect();
        let q: Vec<f64> = t.iter().flat_map(|&t| [t.sin(), -t]).collect();
        let d = |f: fn(f64) -> f64| Some(t.iter().flat_map(|&t| [f(t), -1.0]).collect());
        let cols = if with_derivs {
            [Some(q), d(f64::cos), d(|t| -t.sin()), None]
        } else {
            [Some(q), None, None, None]
        };
        SampleTable::new(2, t, cols)
            .unwrap()
            .with_names(vec!["shoulder".into(), "a<b&c".into()])
            .unwrap()
    }

    fn panels<'a, 'i>(doc: &'a roxmltree::Document<'i>) -> Vec<roxmltree::Node<'a, 'i>> {
        doc.descendants()
            .filter(|n| n.has_tag_name("g") && n.attribute("class") == Some("panel"))
            .collect()
    }

    #[test]
    fn well_formed_with_one_polyline_per_panel_and_limits() {
        let tb = table(200, true);
        let mut jl = JointLimits::symmetric(2.0, 3.0, 10.0);
        jl.position_min = -1.5;
        jl.position_max = 1.5;
        jl.min_velocity = Some(-1.0);
        let lim = Limits::new(vec![jl, JointLimits::symmetric(2.0, 3.0, 10.0)]).unwrap();
        let opts = PlotOptions {
            title: "move \"A\" <fast>".into(),
            ..Default::default()
        };
        let out = svg(&tb, Some(&lim), &opts).unwrap();
        let doc = roxmltree::Document::parse(&out).unwrap();
        let ps = panels(&doc);
        assert_eq!(ps.len(), 2 * 3); // jerk absent: 3 columns
        for p in &ps {
            let lines = p.children().filter(|n| n.has_tag_name("polyline")).count();
            assert_eq!(lines, 1);
        }
        // Joint 1 position panel: two limits; velocity: +2 and -1; joint 2 position: none.
        let limits_in = |j: &str, o: &str| {
            let p = ps
                .iter()
                .find(|p| {
                    p.attribute("data-joint") == Some(j) && p.attribute("data-order") == Some(o)
                })
                .unwrap();
            p.children()
                .filter(|n| n.attribute("class") == Some("limit"))
                .map(|n| {
                    n.descendants()
                        .find(|d| d.is_text())
                        .unwrap()
                        .text()
                        .unwrap()
                        .to_string()
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(limits_in("0", "position"), ["limit -1.5", "limit 1.5"]);
        assert_eq!(limits_in("0", "velocity"), ["limit -1", "limit 2"]);
        assert!(limits_in("1", "position").is_empty());
        assert_eq!(limits_in("1", "acceleration").len(), 2);
        let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
        assert!(texts.contains(&"move \"A\" <fast>"));
        assert!(texts.contains(&"a<b&c"));
        assert!(texts.contains(&"q\u{308} [rad/s²]"));
        assert!(!texts.iter().any(|t| t.contains("[rad/s³]")));
        // Without limits there are no limit lines.
        let out = svg(&tb, None, &PlotOptions::default()).unwrap();
        let doc = roxmltree::Document::parse(&out).unwrap();
        assert!(!doc
            .descendants()
            .any(|n| n.attribute("class") == Some("limit")));
    }

    #[test]
    fn decimation_keeps_a_spike() {
        let n = 100_000;
        let t: Vec<f64> = (0..n).map(|i| i as f64 * 1e-4).collect();
        let mut q = vec![0.0; n];
        q[54_321] = 1.0;
        let tb = SampleTable::new(1, t, [Some(q), None, None, None]).unwrap();
        let out = svg(&tb, None, &PlotOptions::default()).unwrap();
        let doc = roxmltree::Document::parse(&out).unwrap();
        let pl = doc
            .descendants()
            .find(|n| n.has_tag_name("polyline"))
            .unwrap();
        let pts: Vec<(f64, f64)> = pl
            .attribute("points")
            .unwrap()
            .split(' ')
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                (x.parse().unwrap(), y.parse().unwrap())
            })
            .collect();
        let plot_w = 1200.0 - LABEL_W - YAXIS_W - PANEL_GAP;
        assert!(pts.len() <= 2 * plot_w as usize, "{}", pts.len());
        assert!(pts.windows(2).all(|w| w[1].0 >= w[0].0));
        let ymin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        let ymax = pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
        let plot_h = 110.0 - XAXIS_H - ROW_GAP;
        // The spike (value 1) and the base (value 0) span the range minus its padding.
        assert!(ymax - ymin > 0.8 * plot_h, "{ymin} {ymax}");
        // And the spike is at its time (0.54321 of 9.9999 s).
        let spike = pts.iter().find(|p| p.1 == ymin).unwrap();
        let x0 = LABEL_W + YAXIS_W;
        assert!(
            (spike.0 - (x0 + 5.4321 / 9.9999 * plot_w)).abs() < 1.0,
            "{spike:?}"
        );
    }

    #[test]
    fn bad_inputs_are_errors() {
        let tb = table(10, false);
        assert!(svg(
            &tb,
            Some(&Limits::uniform(3, 1.0, 1.0, 1.0).unwrap()),
            &PlotOptions::default()
        )
        .is_err());
        let small = PlotOptions {
            width: 150.0,
            ..Default::default()
        };
        assert!(svg(&tb, None, &small).is_err());
        let nan = PlotOptions {
            panel_height: f64::NAN,
            ..Default::default()
        };
        assert!(svg(&tb, None, &nan).is_err());
        let empty = SampleTable::new(1, vec![], [Some(vec![]), None, None, None]).unwrap();
        assert!(svg(&empty, None, &PlotOptions::default()).is_err());
        // One sample, constant data: still a valid document.
        let one = SampleTable::new(1, vec![2.0], [Some(vec![0.0]), None, None, None]).unwrap();
        let out = svg(&one, None, &PlotOptions::default()).unwrap();
        assert!(roxmltree::Document::parse(&out).is_ok());
    }

    #[test]
    fn ticks_and_escape() {
        let (t, d) = ticks(0.0, 1.0, 5.0);
        assert_eq!(d, 1);
        assert_eq!(t.len(), 6);
        assert_eq!(tick_label(-0.0001, 2), "0.00");
        assert_eq!(escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&apos;");
    }
}
