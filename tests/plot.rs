//! The plot module read back: the SVG is parsed as XML and its texts and frame are located by their
//! attributes; the PNG is decoded and compared with the SVG's size.

use elastokin::plot::{self, Chart, Scale, Series, YAxis};

fn axis(label: &str, scale: Scale, series: Vec<(&str, Vec<(f64, f64)>)>) -> YAxis {
    YAxis {
        label: label.into(),
        scale,
        series: series.into_iter().map(|(name, points)| Series { name: name.into(), points }).collect(),
    }
}

fn chart(left: YAxis, right: Option<YAxis>, design_x: Option<f64>) -> Chart {
    Chart {
        name: "test".into(),
        title: "toe and camber in parallel wheel travel".into(),
        subtitle: "test strut".into(),
        x_label: "wheel travel [mm], bump +".into(),
        x_scale: Scale::Linear,
        left,
        right,
        design_x,
    }
}

/// Toe and camber of a sweep from -80 to 80 mm, in degrees within ±0.02 and with binary rounding noise
/// (`0.1 - 0.12` is -0.019999999999999997).
fn small_angles() -> YAxis {
    let travel: Vec<f64> = (0..=16).map(|i| -80.0 + 10.0 * f64::from(i)).collect();
    axis(
        "angle [deg]",
        Scale::Linear,
        vec![
            ("toe (in +)", travel.iter().map(|&t| (t, (0.1 - 0.12) * t / -80.0)).collect()),
            ("camber (top out +)", travel.iter().map(|&t| (t, -0.01 * (t / 80.0).powi(2))).collect()),
        ],
    )
}

#[derive(Debug)]
struct Text {
    x: f64,
    y: f64,
    anchor: String,
    rotated: bool,
    content: String,
}

/// `(x, y, width, height)`.
type Frame = (f64, f64, f64, f64);

struct Svg {
    width: f64,
    height: f64,
    texts: Vec<Text>,
    frame: Frame,
    source: String,
}

fn number(node: roxmltree::Node, name: &str) -> f64 {
    node.attribute(name).and_then(|v| v.parse().ok()).unwrap_or_else(|| panic!("{name} of {node:?}"))
}

fn read(source: String) -> Svg {
    let document = roxmltree::Document::parse(&source).expect("the SVG is well-formed XML");
    let root = document.root_element();
    let texts = root
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| Text {
            x: number(n, "x"),
            y: number(n, "y"),
            anchor: n.attribute("text-anchor").unwrap_or("start").to_string(),
            rotated: n.attribute("transform").is_some(),
            content: n.text().unwrap_or("").trim().to_string(),
        })
        .collect();
    // The plotting rectangle is the one unfilled rectangle (the other is the white background).
    let frames: Vec<Frame> = root
        .descendants()
        .filter(|n| n.has_tag_name("rect") && n.attribute("fill") == Some("none"))
        .map(|n| (number(n, "x"), number(n, "y"), number(n, "width"), number(n, "height")))
        .collect();
    assert_eq!(frames.len(), 1, "one plotting rectangle");
    let (width, height) = (number(root, "width"), number(root, "height"));
    drop(document);
    Svg { width, height, texts, frame: frames[0], source }
}

impl Svg {
    fn text(&self, content: &str) -> Option<&Text> {
        self.texts.iter().find(|t| t.content == content)
    }

    /// Tick labels left of the frame (right-aligned against the left axis), top to bottom.
    fn left_ticks(&self) -> Vec<&str> {
        let mut ticks: Vec<&Text> =
            self.texts.iter().filter(|t| !t.rotated && t.anchor == "end" && t.x < self.frame.0).collect();
        ticks.sort_by(|a, b| b.y.total_cmp(&a.y));
        ticks.iter().map(|t| t.content.as_str()).collect()
    }

    /// Tick labels right of the frame (left-aligned against the right axis), bottom to top.
    fn right_ticks(&self) -> Vec<&str> {
        let right = self.frame.0 + self.frame.2;
        let mut ticks: Vec<&Text> =
            self.texts.iter().filter(|t| !t.rotated && t.anchor == "start" && t.x > right).collect();
        ticks.sort_by(|a, b| b.y.total_cmp(&a.y));
        ticks.iter().map(|t| t.content.as_str()).collect()
    }

    fn inside_frame(&self, t: &Text) -> bool {
        let (x, y, w, h) = self.frame;
        (x..=x + w).contains(&t.x) && (y..=y + h).contains(&t.y)
    }
}

#[test]
fn tick_labels_are_rounded_to_the_step() {
    let svg = read(plot::svg(&chart(small_angles(), None, Some(0.0))).unwrap());
    assert_eq!(svg.left_ticks(), ["-0.02", "-0.01", "0", "0.01", "0.02"]);
    let bottom = svg.frame.1 + svg.frame.3;
    let mut x_ticks: Vec<&Text> = svg.texts.iter().filter(|t| t.anchor == "middle" && t.y > bottom).collect();
    x_ticks.sort_by(|a, b| a.x.total_cmp(&b.x));
    let x_labels: Vec<&str> = x_ticks.iter().map(|t| t.content.as_str()).filter(|c| c.len() < 4).collect();
    assert_eq!(x_labels, ["-80", "-60", "-40", "-20", "0", "20", "40", "60", "80"]);
    assert!(!svg.source.contains("NaN") && !svg.source.contains("inf"));
}

#[test]
fn title_and_model_name_are_both_shown() {
    let svg = read(plot::svg(&chart(small_angles(), None, None)).unwrap());
    let (title, subtitle) =
        (svg.text("toe and camber in parallel wheel travel").unwrap(), svg.text("test strut").unwrap());
    assert!(title.y < subtitle.y && subtitle.y < svg.frame.1, "title, then model name, then the plot");
    assert_eq!((title.anchor.as_str(), title.x), ("middle", svg.width / 2.0));
}

#[test]
fn a_title_too_long_for_the_width_is_shortened_with_an_ellipsis() {
    let mut long = chart(small_angles(), None, None);
    long.title = "toe and camber ".repeat(20);
    let svg = read(plot::svg(&long).unwrap());
    let title = svg.texts.iter().find(|t| t.content.starts_with("toe and camber toe")).unwrap();
    assert!(title.content.ends_with('…'), "{}", title.content);
    // DejaVu Sans at the title size is about 9.6 px per character of this text: the 800 px between the
    // margins hold about 80.
    let chars = title.content.chars().count();
    assert!((50..100).contains(&chars), "{chars} characters kept"); // measured 83
}

#[test]
fn the_legend_lies_outside_the_plotting_area() {
    let svg = read(plot::svg(&chart(small_angles(), None, Some(0.0))).unwrap());
    for name in ["toe (in +)", "camber (top out +)"] {
        let entry = svg.text(name).unwrap_or_else(|| panic!("legend entry {name}"));
        assert!(!svg.inside_frame(entry), "{entry:?} against the frame {:?}", svg.frame);
        assert!(entry.y > svg.frame.1 + svg.frame.3, "below the frame");
        assert!(entry.y < svg.height);
    }
}

#[test]
fn the_design_position_is_marked_only_inside_the_range() {
    let marked = read(plot::svg(&chart(small_angles(), None, Some(0.0))).unwrap());
    let design = marked.text("design").expect("design marker label");
    // The label stands above the frame, at the x of travel 0, midway between -80 and 80.
    assert!(design.y <= marked.frame.1);
    let middle = marked.frame.0 + marked.frame.2 / 2.0;
    assert!((design.x - middle).abs() <= 1.0, "{} against {middle}", design.x);
    for outside in [Some(200.0), None, Some(f64::NAN)] {
        let svg = read(plot::svg(&chart(small_angles(), None, outside)).unwrap());
        assert!(svg.text("design").is_none(), "{outside:?}");
    }
}

/// A roll centre: height about 100 mm on the left axis, lateral position ±1100 mm on the right.
fn roll_centre() -> Chart {
    let roll: Vec<f64> = (0..=10).map(|i| -2.5 + 0.5 * f64::from(i)).collect();
    let height =
        axis("height [mm]", Scale::Linear, vec![("height", roll.iter().map(|&r| (r, 100.0 - 16.0 * r * r)).collect())]);
    let lateral =
        axis("lateral position [mm]", Scale::Linear, vec![("lateral", roll.iter().map(|&r| (r, 440.0 * r)).collect())]);
    chart(height, Some(lateral), Some(0.0))
}

#[test]
fn a_second_unit_gets_a_right_axis() {
    let svg = read(plot::svg(&roll_centre()).unwrap());
    // Height 0..100 on the left; lateral ±1100 on the right (440 × 2.5, padded by 5 %).
    assert_eq!(svg.left_ticks(), ["0", "20", "40", "60", "80", "100"]);
    assert_eq!(svg.right_ticks(), ["-1000", "-500", "0", "500", "1000"]);
    let right_label = svg.text("lateral position [mm]").expect("right axis label");
    assert!(right_label.rotated && right_label.x > svg.frame.0 + svg.frame.2);
    assert!(svg.text("height (left axis)").is_some() && svg.text("lateral (right axis)").is_some());
}

#[test]
fn non_finite_points_are_left_out_and_counted() {
    let left = axis(
        "angle [deg]",
        Scale::Linear,
        vec![(
            "toe",
            vec![(0.0, 0.0), (1.0, f64::NAN), (2.0, 2.0), (f64::INFINITY, 1.0), (3.0, f64::NEG_INFINITY), (4.0, 4.0)],
        )],
    );
    let svg = read(plot::svg(&chart(left, None, None)).unwrap());
    assert!(!svg.source.contains("NaN") && !svg.source.to_lowercase().contains("inf"));
    assert!(svg.text("3 point(s) with a non-finite value are not drawn").is_some());
    // The axis covers the finite points only: 0..4 padded.
    assert_eq!(svg.left_ticks(), ["0", "1", "2", "3", "4"]);
}

#[test]
fn empty_and_degenerate_charts_are_drawn() {
    let empty = read(plot::svg(&chart(axis("angle [deg]", Scale::Linear, vec![]), None, Some(0.0))).unwrap());
    assert!(empty.text("no point to draw").is_some());
    let all_nan = axis("angle [deg]", Scale::Linear, vec![("toe", vec![(f64::NAN, f64::NAN)])]);
    let svg = read(plot::svg(&chart(all_nan, None, None)).unwrap());
    let note = svg.texts.iter().find(|t| t.content.starts_with("no point to draw")).expect("note");
    assert_eq!(note.content, "no point to draw; 1 point(s) with a non-finite value are not drawn");
    assert!(!svg.source.contains("NaN"));
    // One point: a dot, and a band of ±10 % around its value (45..55, in steps of 2).
    let one = read(plot::svg(&chart(axis("y", Scale::Linear, vec![("one", vec![(1.0, 50.0)])]), None, None)).unwrap());
    assert!(one.source.contains("<circle"));
    assert_eq!(one.left_ticks(), ["46", "48", "50", "52", "54"]);
    // A flat curve: 1.8..2.2, eight steps of 0.05.
    let flat: Vec<(f64, f64)> = (0..5).map(|i| (f64::from(i), 2.0)).collect();
    let flat = read(plot::svg(&chart(axis("y", Scale::Linear, vec![("flat", flat)]), None, None)).unwrap());
    assert_eq!(flat.left_ticks(), ["1.8", "1.85", "1.9", "1.95", "2", "2.05", "2.1", "2.15", "2.2"]);
}

#[test]
fn log_scales_number_decades_and_count_what_they_leave_out() {
    let mut bench = chart(
        axis(
            "attitude error [rad]",
            Scale::Log,
            vec![
                ("paper", vec![(1e-4, 1e-2), (1e-3, 1e-3), (1e-2, 1e-4)]),
                ("corrected", vec![(2e-4, 1e-12), (3e-4, 0.0), (5e-4, -1.0)]),
            ],
        ),
        None,
        None,
    );
    bench.x_scale = Scale::Log;
    bench.x_label = "time per sweep [s]".into();
    let svg = read(plot::svg(&bench).unwrap());
    assert!(svg.text("2 point(s) at or below zero are not drawn on the log scale").is_some());
    // 1e-12..1e-2: eleven decades, every one numbered.
    let expected: Vec<String> =
        (-12..=-2).map(|d| if d >= -3 { format!("{}", 10f64.powi(d)) } else { format!("1e{d}") }).collect();
    assert_eq!(svg.left_ticks(), expected);
    assert!(svg.text("1e-4").is_some() && svg.text("0.01").is_some(), "x decades 1e-4..1e-2");
    assert!(!svg.source.contains("NaN") && !svg.source.contains("inf"));
}

/// The PNG's pixels, after checking that it has the size of the SVG of the same chart; the image is
/// also left in the target directory to be looked at.
fn png_pixels(chart: &Chart, file: &str) -> Vec<[u8; 3]> {
    let svg = read(plot::svg(chart).unwrap());
    let bytes = plot::png(chart).unwrap();
    std::fs::write(std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(file), &bytes).unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().unwrap();
    let mut image = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut image).unwrap();
    assert_eq!((f64::from(info.width), f64::from(info.height)), (svg.width, svg.height));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    image[..info.buffer_size()].chunks(3).map(|p| [p[0], p[1], p[2]]).collect()
}

#[test]
fn png_has_the_svg_size_and_shows_the_curves() {
    let pixels = png_pixels(&chart(small_angles(), None, Some(0.0)), "plot_sample.png");
    let count = |rgb: [u8; 3]| pixels.iter().filter(|p| **p == rgb).count();
    // The toe curve (first colour, 2 px wide, crossing the 710 px wide frame) and text in black.
    let toe = count([31, 119, 180]);
    assert!(toe > 1000, "{toe} toe pixels"); // measured 1951
    let dark = pixels.iter().filter(|p| p.iter().all(|&c| c < 64)).count();
    assert!(dark > 2000, "{dark} dark pixels (text, frame)"); // measured 5034
    let white = count([255, 255, 255]);
    // measured 416 433 of 437 880
    assert!(white > pixels.len() / 2, "mostly background: {white} of {}", pixels.len());
    // The second colour is the lateral position, drawn against the right axis.
    let two_axes = png_pixels(&roll_centre(), "plot_two_axes.png");
    let lateral = two_axes.iter().filter(|p| **p == [214, 39, 40]).count();
    assert!(lateral > 1000, "{lateral} pixels of the right-axis curve"); // measured 1869
}

#[test]
fn extreme_values_and_labels_still_give_a_plot() {
    let cases: Vec<Vec<(f64, f64)>> = vec![
        vec![(0.0, 1e-310), (1.0, 2e-310)],
        vec![(-1e299, 1e299), (1e299, -1e299)],
        vec![(0.0, 1e301), (1.0, 1.0)],
        vec![(1.0, 1.0 + 1e-15), (2.0, 1.0), (3.0, 1.0 - 1e-15)],
        vec![(0.0, -0.0), (0.0, 0.0)],
        (0..20_000).map(|i| (f64::from(i), (f64::from(i) * 1e-3).sin())).collect(),
    ];
    for points in cases {
        for scale in [Scale::Linear, Scale::Log] {
            let mut c = chart(axis("", scale, vec![("", points.clone())]), None, Some(0.5));
            c.x_scale = scale;
            c.title = String::new();
            c.subtitle = "x".repeat(500);
            let svg = read(plot::svg(&c).unwrap_or_else(|e| panic!("{points:?}: {e}")));
            assert!(!svg.source.contains("NaN") && !svg.source.contains("inf"));
            assert!(svg.texts.iter().all(|t| t.x.is_finite() && t.y.is_finite()));
        }
    }
    let many: Vec<(String, Vec<(f64, f64)>)> = (0..40)
        .map(|k| (format!("variant {k} with a long legend name"), vec![(0.0, f64::from(k)), (1.0, 1.0)]))
        .collect();
    let c = chart(axis("y", Scale::Linear, many.iter().map(|(n, p)| (n.as_str(), p.clone())).collect()), None, None);
    let svg = read(plot::svg(&c).unwrap());
    // Every legend entry is written, under the frame, inside the canvas.
    for (name, _) in &many {
        let entry = svg.text(name).unwrap_or_else(|| panic!("{name}"));
        assert!(entry.y > svg.frame.1 + svg.frame.3 && entry.y < svg.height, "{entry:?}");
    }
}
