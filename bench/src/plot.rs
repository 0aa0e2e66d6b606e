//! `--plot DIR`: SVG charts of a run's Mrays/s, from this run's JSON object
//! or from one an earlier `--json` run printed (`--from FILE`).
//!
//! - `mrays_by_scene.svg`: grouped bars, one group per scene, one bar per
//!   backend or peer with a figure there.
//! - `mrays_vs_triangles.svg`: Mrays/s against the scene's triangle count
//!   (log axis), one line per backend or peer.

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde_json::Value;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The figures of `scenes.<name>.mrays_per_s` in legend order: the key and
/// its legend name. Keys the bench adds later are plotted after these,
/// under their key.
const SERIES: [(&str, &str); 11] = [
    ("cpu", "CPU backend"),
    ("cpu_walk_only", "CPU backend, walk only"),
    ("wgpu", "wgpu megakernel"),
    ("rayquery", "wgpu ray-query megakernel"),
    ("obvhs", "obvhs CWBVH"),
    ("embree", "Embree 3, best mode"),
    ("embree_intersect1", "Embree 3 rtcIntersect1"),
    ("embree_intersect16", "Embree 3 rtcIntersect16"),
    ("handwritten_wgsl", "hand-written WGSL, CWBVH"),
    ("handwritten_bvh2_wgsl", "hand-written WGSL, BVH2"),
    ("handwritten_rayquery", "hand-written ray query"),
];

/// One colour per entry of [`SERIES`] (Tableau's ten and a navy); later
/// keys take Palette99's.
const COLOURS: [RGBColor; 11] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0x17, 0xbe, 0xcf),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0xbc, 0xbd, 0x22),
    RGBColor(0x00, 0x00, 0x80),
];

/// The chart files [`write()`] makes, in its order.
pub const FILES: [&str; 2] = ["mrays_by_scene.svg", "mrays_vs_triangles.svg"];

/// A scene of the run.
pub struct Scene {
    pub name: String,
    /// Its triangle count, where the run recorded one.
    pub triangles: Option<f64>,
}

/// A backend or peer with a figure on at least one scene.
pub struct Series {
    /// Its key in `mrays_per_s`.
    pub key: String,
    pub label: String,
    pub colour: RGBColor,
    /// Mrays/s per scene, in [`Figures::scenes`]' order.
    pub mrays: Vec<Option<f64>>,
}

/// What the charts show: the scenes by triangle count, and each series'
/// Mrays/s on them.
pub struct Figures {
    /// `machine.threads` and `machine.resolution`, for the titles.
    pub machine: String,
    pub scenes: Vec<Scene>,
    pub series: Vec<Series>,
}

/// The figures of a JSON file an `rt-bench --json` run printed; errors name
/// the file.
pub fn read(path: &Path) -> Result<Figures, String> {
    let problem = |what: String| format!("{}: {what}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| problem(format!("cannot read it: {e}")))?;
    let run: Value = serde_json::from_str(&text).map_err(|e| problem(format!("not JSON: {e}")))?;
    figures(&run).map_err(problem)
}

/// The figures of a run's JSON object.
pub fn figures(run: &Value) -> Result<Figures, String> {
    let Some(scenes) = run.get("scenes").and_then(Value::as_object) else {
        return Err("no `scenes` object (not the output of `rt-bench --json`?)".into());
    };
    let machine = run.get("machine");
    let field = |key: &str| machine.and_then(|m| m.get(key)).map(|v| v.as_str().map_or(v.to_string(), str::to_string));
    let machine = match (field("threads"), field("resolution")) {
        (Some(t), Some(r)) => format!("{t} threads, {r}"),
        (Some(t), None) => format!("{t} threads"),
        (None, Some(r)) => r,
        (None, None) => "machine unrecorded".into(),
    };
    let mut named: Vec<(&String, &Value)> = scenes.iter().collect();
    named.sort_by(|(an, a), (bn, b)| {
        let (a, b) = (a.get("triangles").and_then(Value::as_f64), b.get("triangles").and_then(Value::as_f64));
        a.is_none().cmp(&b.is_none()).then(a.partial_cmp(&b).unwrap_or(std::cmp::Ordering::Equal)).then(an.cmp(bn))
    });
    let mut keys: Vec<(String, String, RGBColor)> =
        SERIES.iter().zip(COLOURS).map(|((k, l), c)| (k.to_string(), l.to_string(), c)).collect();
    for (_, scene) in &named {
        for key in scene.get("mrays_per_s").and_then(Value::as_object).into_iter().flat_map(|m| m.keys()) {
            if !keys.iter().any(|(k, _, _)| k == key) {
                let c = Palette99::pick(keys.len()).to_rgba();
                keys.push((key.clone(), key.clone(), RGBColor(c.0, c.1, c.2)));
            }
        }
    }
    let series: Vec<Series> = keys
        .into_iter()
        .map(|(key, label, colour)| {
            let mrays = named
                .iter()
                .map(|(_, s)| s.get("mrays_per_s").and_then(|m| m.get(&key)).and_then(Value::as_f64))
                .map(|x| x.filter(|x| x.is_finite() && *x > 0.0))
                .collect();
            Series { key, label, colour, mrays }
        })
        .filter(|s| s.mrays.iter().any(Option::is_some))
        .collect();
    if series.is_empty() {
        return Err("no scene has a Mrays/s figure (`scenes.<name>.mrays_per_s`)".into());
    }
    let scenes = named
        .into_iter()
        .map(|(name, s)| Scene { name: name.clone(), triangles: s.get("triangles").and_then(Value::as_f64) })
        .collect();
    Ok(Figures { machine, scenes, series })
}

/// Writes [`FILES`] into `dir` (created when absent); returns their paths.
pub fn write(fig: &Figures, dir: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create it: {e}", dir.display()))?;
    let paths: Vec<PathBuf> = FILES.iter().map(|f| dir.join(f)).collect();
    let failed = |p: &Path, e: String| format!("{}: {e}", p.display());
    by_scene(fig, &paths[0]).map_err(|e| failed(&paths[0], e))?;
    vs_triangles(fig, &paths[1]).map_err(|e| failed(&paths[1], e))?;
    Ok(paths)
}

/// Canvas size of each chart, in pixels.
const SIZE: (u32, u32) = (1200, 600);
/// Width of the legend on the right, in pixels.
const LEGEND_WIDTH: u32 = 290;
/// The one font: SVG names it and the viewer renders it.
const FONT: &str = "sans-serif";

/// A count as the axes and scene names show it: 69k, 2.1M.
fn count(x: f64) -> String {
    match x {
        x if x >= 1e6 => format!("{:.1}M", x / 1e6),
        x if x >= 1e4 => format!("{:.0}k", x / 1e3),
        x if x >= 1e3 => format!("{:.1}k", x / 1e3),
        x => format!("{x:.0}"),
    }
}

/// A figure as the bars' labels show it: two decimals under 1, one under
/// 10, none above.
fn figure(x: f64) -> String {
    match x {
        x if x < 1.0 => format!("{x:.2}"),
        x if x < 10.0 => format!("{x:.1}"),
        x => format!("{x:.0}"),
    }
}

/// The highest figure plotted, with headroom, for the y axis.
fn y_top(fig: &Figures) -> f64 {
    let max = fig.series.iter().flat_map(|s| s.mrays.iter().flatten()).fold(0.0f64, |a, &b| a.max(b));
    max * 1.15
}

/// A part of an SVG canvas, in pixels.
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The title area and the chart and legend areas below it.
fn canvas<'a>(root: &Area<'a>, title: &str) -> Result<(Area<'a>, Area<'a>), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let body = root.titled(title, (FONT, 22)).map_err(|e| e.to_string())?;
    Ok(body.split_horizontally(SIZE.0 - LEGEND_WIDTH))
}

/// The legend: each series' swatch (a bar's square or a line) and name.
fn legend(area: &Area<'_>, fig: &Figures, lines: bool) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<_>| e.to_string();
    area.draw(&Text::new("backend or peer", (10, 20), (FONT, 16).into_font().style(FontStyle::Bold))).map_err(e)?;
    for (i, s) in fig.series.iter().enumerate() {
        let y = 48 + 24 * i as i32;
        if lines {
            area.draw(&PathElement::new(vec![(10, y + 7), (34, y + 7)], line_style(s))).map_err(e)?;
            area.draw(&Circle::new((22, y + 7), 3, s.colour.filled())).map_err(e)?;
        } else {
            area.draw(&Rectangle::new([(14, y), (28, y + 14)], s.colour.filled())).map_err(e)?;
        }
        area.draw(&Text::new(s.label.as_str(), (42, y), (FONT, 15))).map_err(e)?;
    }
    Ok(())
}

/// The bar chart's x axis: scene `i` spans `i..i + 1`, its tick (and
/// name) at the centre.
#[derive(Clone)]
struct Groups(usize);

impl Ranged for Groups {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, x: &f64, (lo, hi): (i32, i32)) -> i32 {
        lo + (f64::from(hi - lo) * x / self.0.max(1) as f64).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, _: H) -> Vec<f64> {
        (0..self.0).map(|i| i as f64 + 0.5).collect()
    }

    fn range(&self) -> Range<f64> {
        0.0..self.0 as f64
    }
}

/// `mrays_by_scene.svg`: one group of bars per scene.
fn by_scene(fig: &Figures, path: &Path) -> Result<(), String> {
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    let (chart_area, legend_area) =
        canvas(&root, &format!("rt-bench: Mrays/s by scene, primary + AO rays ({})", fig.machine))?;
    let n = fig.scenes.len();
    let names: Vec<String> = fig
        .scenes
        .iter()
        .map(|s| match s.triangles {
            Some(t) => format!("{} ({} triangles)", s.name, count(t)),
            None => s.name.clone(),
        })
        .collect();
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(16)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d(Groups(n), 0.0..y_top(fig))
        .map_err(|e| e.to_string())?;
    let label = |x: &f64| names.get(x.floor() as usize).cloned().unwrap_or_default();
    chart
        .configure_mesh()
        .disable_x_mesh()
        .light_line_style(TRANSPARENT)
        .x_label_formatter(&label)
        .y_desc("Mrays/s (higher is better)")
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, _) in fig.scenes.iter().enumerate() {
        // Only the series with a figure here share the group's width.
        let here: Vec<(&Series, f64)> = fig.series.iter().filter_map(|s| s.mrays[i].map(|m| (s, m))).collect();
        let width = 0.8 / here.len().max(1) as f64;
        for (k, (s, m)) in here.iter().enumerate() {
            let x0 = i as f64 + 0.1 + k as f64 * width;
            let bar = Rectangle::new([(x0, 0.0), (x0 + width * 0.92, *m)], s.colour.filled());
            chart.draw_series(std::iter::once(bar)).map_err(|e| e.to_string())?;
            // The figure above its bar, upright, so a bar too short to see
            // still reads.
            let upright = TextStyle::from((FONT, 12).into_font().transform(FontTransform::Rotate270))
                .pos(Pos::new(HPos::Left, VPos::Center));
            let value = EmptyElement::at((x0 + width * 0.46, *m)) + Text::new(figure(*m), (0, -4), upright);
            chart.plotting_area().draw(&value).map_err(|e| e.to_string())?;
        }
    }
    legend(&legend_area, fig, false)?;
    root.present().map_err(|e| e.to_string())
}

/// A series' line: Embree's best mode is the faster of its two, so its
/// line lies on one of theirs; it is drawn wide and pale beneath them.
fn line_style(s: &Series) -> ShapeStyle {
    if s.key == "embree" { s.colour.mix(0.35).stroke_width(7) } else { s.colour.stroke_width(2) }
}

/// `mrays_vs_triangles.svg`: one line per series over the scenes with a
/// triangle count.
fn vs_triangles(fig: &Figures, path: &Path) -> Result<(), String> {
    let root = SVGBackend::new(path, SIZE).into_drawing_area();
    let (chart_area, legend_area) =
        canvas(&root, &format!("rt-bench: Mrays/s against triangles, primary + AO rays ({})", fig.machine))?;
    let tris: Vec<f64> = fig.scenes.iter().filter_map(|s| s.triangles).filter(|t| *t > 0.0).collect();
    let (lo, hi) = tris.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    let (lo, hi) = if tris.is_empty() { (1.0, 10.0) } else { (lo / 2.0, hi * 2.0) };
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(64)
        .build_cartesian_2d((lo..hi).log_scale(), 0.0..y_top(fig))
        .map_err(|e| e.to_string())?;
    let label = |x: &f64| count(*x);
    chart
        .configure_mesh()
        .x_label_formatter(&label)
        .x_desc("triangles (log scale)")
        .y_desc("Mrays/s (higher is better)")
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 16))
        .draw()
        .map_err(|e| e.to_string())?;
    let (wide, thin): (Vec<&Series>, Vec<&Series>) = fig.series.iter().partition(|s| s.key == "embree");
    for s in wide.into_iter().chain(thin) {
        let points: Vec<(f64, f64)> = fig
            .scenes
            .iter()
            .zip(&s.mrays)
            .filter_map(|(scene, m)| Some((scene.triangles.filter(|t| *t > 0.0)?, (*m)?)))
            .collect();
        chart.draw_series(LineSeries::new(points.clone(), line_style(s))).map_err(|e| e.to_string())?;
        chart
            .draw_series(points.into_iter().map(|p| Circle::new(p, 4, s.colour.filled())))
            .map_err(|e| e.to_string())?;
    }
    // The scenes' names at their triangle counts, along the top (the
    // headroom above the highest figure).
    let centred = (FONT, 13).into_font().color(&BLACK).pos(Pos::new(HPos::Center, VPos::Top));
    for scene in &fig.scenes {
        if let Some(t) = scene.triangles.filter(|t| *t > 0.0) {
            let name = Text::new(scene.name.as_str(), (t, y_top(fig) * 0.985), centred.clone());
            chart.plotting_area().draw(&name).map_err(|e| e.to_string())?;
        }
    }
    legend(&legend_area, fig, true)?;
    root.present().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh directory under the system's temporary one.
    fn temp_dir(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rt-bench-plot-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Two scenes, three peers with figures (Embree's on one scene only),
    /// wgpu skipped everywhere.
    const FIXTURE: &str = r#"{
        "machine": {"threads": 2, "resolution": "320x240", "reps": 3},
        "scenes": {
            "teapot": {"triangles": 6320, "mrays_per_s": {"cpu": 4.5, "wgpu": null, "obvhs": 5.25, "embree": null}},
            "bunny": {"triangles": 69451, "mrays_per_s": {"cpu": 3.0, "wgpu": null, "obvhs": 3.5, "embree": 8.0}}
        }
    }"#;

    #[test]
    fn plots_a_fixture_run() {
        let dir = temp_dir("fixture");
        let file = dir.join("run.json");
        std::fs::write(&file, FIXTURE).unwrap();
        let fig = read(&file).unwrap();
        assert_eq!(fig.machine, "2 threads, 320x240");
        let names: Vec<&str> = fig.scenes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["teapot", "bunny"], "scenes by triangle count");
        let paths = write(&fig, &dir.join("plots")).unwrap();
        assert_eq!(paths.len(), FILES.len());
        for path in &paths {
            let svg = std::fs::read_to_string(path).unwrap();
            assert!(svg.starts_with("<svg"), "{}", path.display());
            assert!(svg.contains("2 threads, 320x240"), "title in {}", path.display());
            for label in ["CPU backend", "obvhs CWBVH", "Embree 3, best mode"] {
                assert!(svg.contains(label), "{label} in {}", path.display());
            }
            assert!(!svg.contains("wgpu megakernel"), "no figure, no legend entry: {}", path.display());
            for scene in ["teapot", "bunny"] {
                assert!(svg.contains(scene), "{scene} in {}", path.display());
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn malformed_file_is_a_one_line_error_naming_it() {
        let dir = temp_dir("malformed");
        let file = dir.join("cut.json");
        std::fs::write(&file, r#"{"scenes": {"bunny": "#).unwrap();
        let e = read(&file).err().expect("a cut-off file is an error");
        assert!(e.starts_with(&format!("{}: not JSON: ", file.display())), "{e}");
        assert!(!e.contains('\n'), "{e}");
        std::fs::write(&file, r#"{"machine": {}}"#).unwrap();
        let e = read(&file).err().expect("JSON without scenes is an error");
        assert!(e.contains("no `scenes` object"), "{e}");
        let missing = dir.join("absent.json");
        let e = read(&missing).err().expect("a missing file is an error");
        assert!(e.starts_with(&format!("{}: cannot read it: ", missing.display())), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
