//! The report pages' style, inline in each page's head.

/// Readable on screen and on paper; system fonts only, so the page looks the same without a network.
pub(super) const STYLE: &str = r#"
:root { color-scheme: light; }
body { font: 15px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", Roboto, sans-serif;
  color: #1b1f24; background: #fff; max-width: 1120px; margin: 0 auto; padding: 24px 32px 48px; }
h1 { font-size: 1.6em; margin: 0 0 4px; }
h2 { font-size: 1.25em; margin: 28px 0 8px; padding-bottom: 4px; border-bottom: 2px solid #d0d7de; }
header { border-bottom: 3px solid #1f4e79; padding-bottom: 10px; }
.lede, .note, .quiet { color: #57606a; }
.note { font-size: 0.9em; margin: 4px 0; }
.quiet { font-weight: normal; font-size: 0.85em; }
.none { color: #1a7f37; font-style: italic; }
.columns { display: flex; flex-wrap: wrap; gap: 8px 40px; }
.columns > section { flex: 1 1 420px; min-width: 0; }
dl { display: grid; grid-template-columns: max-content minmax(0, 1fr); gap: 2px 16px; margin: 0; }
dt { color: #57606a; }
dd { margin: 0; overflow-wrap: anywhere; }
dd dl { font-size: 0.95em; }
table { border-collapse: collapse; margin: 6px 0; }
th, td { padding: 3px 10px; border-bottom: 1px solid #d8dee4; text-align: left; vertical-align: top; }
thead th { border-bottom: 2px solid #8c959f; background: #f6f8fa; }
table.numbers td { text-align: right; font-variant-numeric: tabular-nums; }
table.numbers td:first-child { text-align: left; }
table.comparison td { white-space: nowrap; }
table.comparison td:first-child { white-space: normal; }
table.comparison tr.group th { background: #f6f8fa; text-align: left; font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; }
table.figures { min-width: 70%; }
table.figures td.value { text-align: right; font-variant-numeric: tabular-nums; font-weight: 600; }
table.figures td.error-estimate { color: #57606a; font-variant-numeric: tabular-nums; }
td.reason { color: #9a6700; }
td.error-estimate.over, td.over, p.over, span.over { color: #cf222e; }
.verdict { font-size: 1.05em; }
.summary-grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(min(100%, 500px), 1fr)); gap: 4px 28px; }
.summary-grid h3 { margin: 12px 0 2px; font-size: 1em; font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; }
table.compact { width: 100%; font-size: 0.9em; margin: 0; }
table.compact td { padding: 1px 6px; }
table.compact td.value { white-space: nowrap; }
tr.met td:first-child { border-left: 4px solid #1a7f37; }
tr.missed td:first-child { border-left: 4px solid #cf222e; }
tr.met td.aim { color: #1a7f37; }
table.compact td.aim, table.compact td.over { padding-left: 18px; border-top: 0; }
tr.missed td.aim { color: #cf222e; font-weight: 600; }
table.warnings td:nth-child(2) { white-space: nowrap; }
code { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 0.9em;
  background: #f6f8fa; padding: 0 3px; border-radius: 3px; }
ul.warnings { color: #9a6700; padding-left: 20px; }
ul.failed { color: #cf222e; padding-left: 20px; }
.ok { color: #1a7f37; font-weight: 600; }
.bad { color: #cf222e; font-weight: 600; }
.error { color: #cf222e; border-left: 3px solid #cf222e; padding: 4px 10px; background: #fff5f5; }
.accuracy { font-size: 0.92em; }
section.analysis { margin-top: 36px; }
section.analysis h2 { font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; }
.description { font-weight: 600; margin: 4px 0; }
.charts { display: flex; flex-wrap: wrap; gap: 16px; }
figure { margin: 8px 0; flex: 0 1 552px; max-width: 100%; }
figure svg { width: 100%; height: auto; display: block; border: 1px solid #e5e8eb; }
/* A chart drawn interactively stands in for its SVG on screen; the SVG is what prints. */
figure.live > svg { display: none; }
.live-chart { border: 1px solid #e5e8eb; }
.live-chart .u-title { font-size: 15px; font-weight: 600; }
.live-chart .u-legend { font-size: 13px; }
details { margin: 6px 0; }
summary { cursor: pointer; color: #0b5394; }
.scroll { overflow-x: auto; max-width: 100%; }
.scroll table { font-size: 0.85em; }
pre { background: #f6f8fa; padding: 10px; overflow-x: auto; font-size: 0.85em; }
nav ol { columns: 2; margin: 0; }
.views { display: flex; flex-wrap: wrap; gap: 12px; }
.views figure.view { flex: 1 1 300px; margin: 0; }
.views figure.view svg { border: 1px solid #e5e8eb; }
ul.view-legend { list-style: none; padding: 0; display: flex; flex-wrap: wrap; gap: 4px 18px; font-size: 0.85em; }
ul.view-legend svg { vertical-align: middle; }
figure.view3d { margin: 12px 0; }
figure.view3d canvas { width: 100%; height: 560px; display: block; border: 1px solid #e5e8eb; touch-action: none; }
.view3d-controls { display: flex; flex-wrap: wrap; gap: 8px; align-items: center; margin-bottom: 6px; }
.view3d-controls input[type=range] { flex: 1 1 200px; }
.live-bar button { font: inherit; padding: 2px 12px; }
#hardpoints input, #rates input { width: 6.5em; font: inherit; text-align: right; }
#rates input { width: 9em; }
#hardpoints input.moved, #rates input.moved { background: #fff8c5; }
#figures td.value, #figures td.quiet, #figures td.error { white-space: nowrap; }
#hardpoints button.point { font: inherit; border: none; background: none; padding: 0; color: #0969da; cursor: pointer; }
#hardpoints tr.selected td { background: #ddf4ff; }
#figures tr[data-key] { cursor: pointer; }
#figures tr.chosen td { background: #fbefff; }
#projections circle.handle { cursor: grab; touch-action: none; }
@media print {
  @page { size: A4 portrait; margin: 12mm; }
  body { max-width: none; padding: 0; font-size: 10pt; }
  section.analysis { break-before: page; }
  figure, table.figures, .accuracy, .summary-grid .card { break-inside: avoid; }
  summary { color: inherit; }
  a { color: inherit; text-decoration: none; }
  /* Plot sheets: one chart across the page, two to a page, as a rig's plots are filed. */
  .charts { display: block; }
  .charts figure { width: 100%; max-width: none; margin: 0 0 6mm; }
  .charts figure svg { height: 118mm; width: auto; max-width: 100%; margin: 0 auto; border: 0; }
  figure.view3d, .view3d-controls, .live-chart { display: none; }
  figure.live > svg { display: block; }
}
"#;
