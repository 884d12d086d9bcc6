//! A log-log line plot written as SVG by hand (the style of the `elastokin` command's plots): decade grid,
//! one polyline with markers per series, a legend. Points that cannot sit on a log axis (zero, negative,
//! not finite) are left out and counted in a note under the plot, never drawn at a made-up place.

/// One line of the plot.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// `(x, y)` points in drawing order.
    pub points: Vec<(f64, f64)>,
}

const W: f64 = 720.0;
const H: f64 = 460.0;
const LEFT: f64 = 70.0;
const RIGHT: f64 = 230.0;
const TOP: f64 = 40.0;
const BOTTOM: f64 = 50.0;
const COLOURS: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"];

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

fn plottable(p: &(f64, f64)) -> bool {
    p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0
}

/// Decade range `[floor(log10 lo), ceil(log10 hi)]`, at least one decade wide.
fn decades(lo: f64, hi: f64) -> (i32, i32) {
    let a = lo.log10().floor() as i32;
    let b = (hi.log10().ceil() as i32).max(a + 1);
    (a, b)
}

/// The plot as an SVG document.
pub fn log_log_plot(title: &str, x_label: &str, y_label: &str, series: &[Series]) -> String {
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.points.iter().copied()).filter(plottable).collect();
    let left_out = series.iter().map(|s| s.points.len()).sum::<usize>() - all.len();
    let (x0, x1, y0, y1) = if all.is_empty() {
        (1.0, 10.0, 1.0, 10.0)
    } else {
        all.iter().fold((f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64), |(a, b, c, d), &(x, y)| {
            (a.min(x), b.max(x), c.min(y), d.max(y))
        })
    };
    let (dx0, dx1) = decades(x0, x1);
    let (dy0, dy1) = decades(y0, y1);
    let sx = |x: f64| LEFT + (x.log10() - dx0 as f64) / (dx1 - dx0) as f64 * (W - LEFT - RIGHT);
    let sy = |y: f64| H - BOTTOM - (y.log10() - dy0 as f64) / (dy1 - dy0) as f64 * (H - TOP - BOTTOM);
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{H}\" font-family=\"sans-serif\" font-size=\"12\">\n\
         <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n\
         <text x=\"{:.1}\" y=\"24\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
        (LEFT + W - RIGHT) / 2.0,
        escape(title)
    );
    // Decade grid with labels; thin lines at 2…9 within each decade when there are few decades.
    let minor = |d0: i32, d1: i32| d1 - d0 <= 6;
    for d in dx0..=dx1 {
        let x = sx(10f64.powi(d));
        svg += &format!(
            "<line x1=\"{x:.1}\" y1=\"{TOP}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#ccc\"/>\
             <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">1e{d}</text>\n",
            H - BOTTOM,
            H - BOTTOM + 16.0
        );
        if minor(dx0, dx1) && d < dx1 {
            for m in 2..10 {
                let x = sx(m as f64 * 10f64.powi(d));
                svg += &format!(
                    "<line x1=\"{x:.1}\" y1=\"{TOP}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#eee\"/>\n",
                    H - BOTTOM
                );
            }
        }
    }
    for d in dy0..=dy1 {
        let y = sy(10f64.powi(d));
        svg += &format!(
            "<line x1=\"{LEFT}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#ccc\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">1e{d}</text>\n",
            W - RIGHT,
            LEFT - 6.0,
            y + 4.0
        );
    }
    svg += &format!(
        "<rect x=\"{LEFT}\" y=\"{TOP}\" width=\"{:.1}\" height=\"{:.1}\" fill=\"none\" stroke=\"#333\"/>\n\
         <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>\n\
         <text transform=\"translate(16 {:.1}) rotate(-90)\" text-anchor=\"middle\">{}</text>\n",
        W - LEFT - RIGHT,
        H - TOP - BOTTOM,
        (LEFT + W - RIGHT) / 2.0,
        H - 12.0,
        escape(x_label),
        (TOP + H - BOTTOM) / 2.0,
        escape(y_label)
    );
    for (k, s) in series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let pts: Vec<(f64, f64)> = s.points.iter().copied().filter(plottable).map(|(x, y)| (sx(x), sy(y))).collect();
        if pts.len() > 1 {
            let path: Vec<String> = pts.iter().map(|(x, y)| format!("{x:.2},{y:.2}")).collect();
            svg += &format!(
                "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\" points=\"{}\"/>\n",
                path.join(" ")
            );
        }
        for (x, y) in &pts {
            svg += &format!("<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"3\" fill=\"{colour}\"/>\n");
        }
        let ly = TOP + 10.0 + 18.0 * k as f64;
        svg += &format!(
            "<line x1=\"{:.1}\" y1=\"{ly:.1}\" x2=\"{:.1}\" y2=\"{ly:.1}\" stroke=\"{colour}\" stroke-width=\"2\"/>\
             <circle cx=\"{:.1}\" cy=\"{ly:.1}\" r=\"3\" fill=\"{colour}\"/>\
             <text x=\"{:.1}\" y=\"{:.1}\">{}</text>\n",
            W - RIGHT + 12.0,
            W - RIGHT + 36.0,
            W - RIGHT + 24.0,
            W - RIGHT + 42.0,
            ly + 4.0,
            escape(&s.name)
        );
    }
    if left_out > 0 {
        svg += &format!(
            "<text x=\"{LEFT}\" y=\"{:.1}\" font-size=\"10\">{left_out} point(s) with a zero or failed value are not drawn</text>\n",
            H - 2.0
        );
    }
    svg + "</svg>\n"
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every number in the document's attributes.
    fn numbers(svg: &str) -> Vec<f64> {
        svg.split('"')
            .skip(1)
            .step_by(2)
            .flat_map(|attr| attr.split([',', ' ']).map(str::to_string).collect::<Vec<_>>())
            .filter_map(|s| s.parse::<f64>().ok())
            .collect()
    }

    #[test]
    fn coordinates_are_finite_and_inside_the_canvas() {
        let svg = log_log_plot(
            "error & time",
            "time (s)",
            "error",
            &[
                Series { name: "paper".into(), points: vec![(1e-4, 1e-2), (1e-3, 1e-3), (1e-2, 1e-4)] },
                Series { name: "corrected".into(), points: vec![(2e-4, 1e-12), (3e-4, 0.0), (f64::NAN, 1.0)] },
            ],
        );
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
        assert!(svg.contains("error &amp; time"));
        assert!(svg.contains("2 point(s)"), "the zero and the NaN point are counted, not drawn");
        let nums = numbers(&svg);
        assert!(!nums.is_empty());
        assert!(nums.iter().all(|v| v.is_finite() && *v >= -1.0 && *v <= W.max(H) + 1.0), "{nums:?}");
    }

    #[test]
    fn empty_and_single_point_plots_are_well_formed() {
        for series in [vec![], vec![Series { name: "one".into(), points: vec![(5.0, 5.0)] }]] {
            let svg = log_log_plot("t", "x", "y", &series);
            assert!(svg.trim_end().ends_with("</svg>"));
            assert!(numbers(&svg).iter().all(|v| v.is_finite()));
        }
    }

    #[test]
    fn decades_cover_the_data() {
        assert_eq!(decades(3e-5, 2e-2), (-5, -1));
        assert_eq!(decades(1.0, 1.0), (0, 1));
    }
}
