"""Writers of the validation report: self-contained HTML, JSON, Markdown, BibTeX."""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

from ..citations import BIBLIOGRAPHY

__all__ = ["write_report", "write_html", "write_json", "write_markdown", "markdown"]


def _num(v) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    v = float(v)
    if v == 0:
        return "0"
    if 1e-3 <= abs(v) < 1e5:
        return f"{v:.4g}"
    return f"{v:.3e}"


def _tol(r) -> str:
    t = r.tolerance
    if isinstance(t, tuple):
        lo, hi = t
        return f"in ({_num(lo)}, {_num(hi) if math.isfinite(hi) else '∞'})"
    if r.status == "skipped":
        return "–"
    return f"≤ {_num(t)}"


def _err(r) -> str:
    if r.measure == "band" or r.status == "skipped":
        return "–"
    return _num(r.error)


def _load_text(env) -> str:
    b, a = env.get("load_before"), env.get("load_after")
    fmt = (lambda x: "/".join(f"{v:g}" for v in x) if x else "n/a")
    return f"load average (1/5/15 min) {fmt(b)} before, {fmt(a)} after; {env.get('cpus')} CPUs"


def _header_lines(report) -> list[str]:
    env = report.environment
    c = report.counts()
    kind = "quick (`--quick`)" if report.quick else "full"
    return [
        f"Run: {kind}, {env.get('date_utc', '')} UTC, wheelrail {env.get('wheelrail', '')}, "
        f"Python {env.get('python', '')}, NumPy {env.get('numpy', '')}, {env.get('platform', '')}.",
        f"Total time: {report.total_time:.1f} s on one process; {_load_text(env)} "
        "(the machine is shared, so times are upper bounds).",
        f"Rows: {len(report.rows)} — {c['passed']} passed, {c['failed']} failed, "
        f"{c['known-failure']} known failures (reported defects or model limits), "
        f"{c['skipped']} skipped.",
    ]


_ACCENTS = {'{\\"u}': "ü", '{\\"o}': "ö", '{\\"a}': "ä", "{\\ss}": "ß", "{\\'e}": "é",
            "{\\`e}": "è", "{\\`a}": "à"}


def _detex(text) -> str:
    """BibTeX field text as plain Unicode (the accents used in the database)."""
    for tex, char in _ACCENTS.items():
        text = text.replace(tex, char)
    return text.replace("{", "").replace("}", "")


def _md_cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def markdown(report) -> str:
    """The report as a Markdown page (GFM tables, no raw HTML)."""

    out = ["# Validation report", ""]
    for line in _header_lines(report):
        out += [line, ""]
    out += ["Each row compares a method with an independent reference (never with its own "
            "earlier output). *error* is relative unless the quantity says otherwise; a "
            "tolerance written as an interval bounds the value itself (fitted orders, "
            "documented bias bands). *time* is the wall time of the check that produced the "
            "row.", ""]
    out += ["| method | reference | quantity | value | reference value | error | tolerance | "
            "status | time [s] |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in report.rows:
        status = {"passed": "pass", "failed": "**FAIL**", "known-failure": "known failure",
                  "skipped": "skipped"}[r.status]
        out.append("| " + " | ".join(_md_cell(x) for x in (
            f"`{r.method}`", r.reference, r.quantity, _num(r.value), _num(r.reference_value),
            _err(r), _tol(r), status, f"{r.time:.2f}" if math.isfinite(r.time) else "–")) + " |")
    out.append("")
    notes = [r for r in report.rows if r.status in ("failed", "known-failure", "skipped")]
    if notes:
        out += ["## Failures, known failures and skipped rows", ""]
        for r in notes:
            out.append(f"- `{r.method}`, {_md_cell(r.quantity)} ({r.status}): "
                       f"{_md_cell(r.note or 'outside its tolerance')}")
        out.append("")
    out += ["## Where the tolerances come from", ""]
    seen = []
    for r in report.rows:
        key = (r.check, r.tolerance_source)
        if r.tolerance_source and key not in seen:
            seen.append(key)
            out.append(f"- `{r.check}`: {_md_cell(r.tolerance_source)}")
    out += ["", "## References", ""]
    for key in report.citation_keys():
        kind, f = BIBLIOGRAPHY[key]
        where = f.get("journal") or f.get("booktitle") or f.get("publisher") or \
            f.get("school") or f.get("institution") or f.get("howpublished") or \
            f.get("organization", "")
        vol = f" {f['volume']}" if "volume" in f and kind == "article" else ""
        pages = f", {f['pages'].replace('--', '–')}" if "pages" in f else ""
        out.append(f"- [{key}] {_detex(f['author'])}: {_detex(f['title'])}. {_detex(where)}{vol} "
                   f"({f.get('year', 'n.d.')}){pages}.")
    out += ["", "BibTeX of all of them: `wr.citation(...)` or `citations.bib` next to this "
            "report.", ""]
    return "\n".join(out)


def write_markdown(report, path) -> Path:
    """Write :func:`markdown` to ``path``."""
    path = Path(path)
    path.write_text(markdown(report), encoding="utf-8")
    return path


def write_json(report, path) -> Path:
    """Every number of the report (rows, environment, counts, citation keys) as JSON."""
    path = Path(path)
    data = {"quick": report.quick, "total_time_s": report.total_time,
            "environment": report.environment, "counts": report.counts(),
            "passed": report.passed, "errors": report.errors,
            "citations": report.citation_keys(),
            "rows": [r.to_dict() for r in report.rows]}
    path.write_text(json.dumps(data, indent=1, allow_nan=False), encoding="utf-8")
    return path


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:1.5em;color:#222}
table{border-collapse:collapse;font-size:13px;width:100%}
th,td{border:1px solid #ccc;padding:3px 6px;vertical-align:top;text-align:left}
th{background:#f0f0f0;position:sticky;top:0}
tr.passed td.st{background:#d8f5d8} tr.failed td.st{background:#f8c8c8;font-weight:bold}
tr.known-failure td.st{background:#fde9b6} tr.skipped td.st{background:#e8e8e8}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
.note{color:#555;font-size:12px} figure{display:inline-block;margin:0.5em;border:1px solid #ddd;padding:4px}
figcaption{font-size:12px;max-width:380px} pre{background:#f7f7f7;padding:8px;font-size:12px;overflow:auto}
"""


def html_page(report) -> str:
    """The report as one self-contained HTML page (inline CSS, figures as data URIs)."""
    e = html.escape
    parts = ["<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
             "<title>wheelrail validation report</title>", f"<style>{_CSS}</style></head><body>",
             "<h1>wheelrail validation report</h1>"]
    for line in _header_lines(report):
        parts.append(f"<p>{e(line.replace('`', ''))}</p>")
    parts.append("<p>Each row compares a method with an independent reference (never with its "
                 "own earlier output). Error is relative unless the quantity says otherwise; an "
                 "interval tolerance bounds the value itself (fitted orders, bias bands).</p>")
    parts.append("<table><thead><tr><th>method</th><th>reference</th><th>quantity</th>"
                 "<th>value</th><th>reference value</th><th>error</th><th>tolerance</th>"
                 "<th>status</th><th>time [s]</th><th>tolerance source / note</th>"
                 "<th>cites</th></tr></thead><tbody>")
    for i, r in enumerate(report.rows):
        fig = f" <a href='#fig{i}'>figure</a>" if r.figure else ""
        note = e(r.tolerance_source) + (f"<br><b>{e(r.note)}</b>" if r.note else "")
        parts.append(
            f"<tr class='{e(r.status)}'><td><code>{e(r.method)}</code></td>"
            f"<td>{e(r.reference)}</td><td>{e(r.quantity)}{fig}</td>"
            f"<td class='num'>{e(_num(r.value))}</td><td class='num'>{e(_num(r.reference_value))}</td>"
            f"<td class='num'>{e(_err(r))}</td><td class='num'>{e(_tol(r))}</td>"
            f"<td class='st'>{e(r.status)}</td>"
            f"<td class='num'>{e(f'{r.time:.2f}' if math.isfinite(r.time) else '–')}</td>"
            f"<td class='note'>{note}</td><td class='note'>{e(r.source)}</td></tr>")
    parts.append("</tbody></table>")
    figs = [(i, r) for i, r in enumerate(report.rows) if r.figure]
    if figs:
        parts.append("<h2>Figures</h2>")
        for i, r in figs:
            parts.append(f"<figure id='fig{i}'><img alt='{e(r.quantity)}' "
                         f"src='data:image/png;base64,{r.figure}'>"
                         f"<figcaption><code>{e(r.method)}</code>: {e(r.quantity)} — "
                         f"{e(r.reference)}</figcaption></figure>")
    if report.errors:
        parts.append("<h2>Checks that raised</h2><ul>")
        parts += [f"<li><code>{e(k)}</code>: {e(v)}</li>" for k, v in report.errors.items()]
        parts.append("</ul>")
    parts.append("<h2>References (BibTeX)</h2>")
    parts.append(f"<pre>{e(report.bibtex())}</pre>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_html(report, path) -> Path:
    """Write :func:`html_page` to ``path``."""
    path = Path(path)
    path.write_text(html_page(report), encoding="utf-8")
    return path


def write_report(report, out) -> dict:
    """Write ``report.html``, ``report.json``, ``report.md`` and ``citations.bib`` into ``out``.

    Parameters
    ----------
    report : ValidationReport
    out : str or Path
        Directory (created if missing).

    Returns
    -------
    dict
        ``{"html": Path, "json": Path, "md": Path, "bib": Path}``.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    bib = out / "citations.bib"
    bib.write_text(report.bibtex(), encoding="utf-8")
    return {"html": write_html(report, out / "report.html"),
            "json": write_json(report, out / "report.json"),
            "md": write_markdown(report, out / "report.md"), "bib": bib}
