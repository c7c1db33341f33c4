"""Recipes of the paper's tables: Table 1 (input data of the cases) and Table 2 (induced frequencies)."""

from __future__ import annotations

import html
import json
from collections.abc import Sequence
from decimal import Decimal
from typing import Any

from moving_bogie.paper.recipe import BuildContext, Built

__all__ = ["TABLE1_COLUMNS", "build_table1", "build_table2"]

#: Columns of Table 1: parameter name, HTML heading, Markdown (TeX) heading.
TABLE1_COLUMNS = (
    ("eta_f", "η<sub>f</sub>", "$\\eta_f$"),
    ("eta_M", "η<sub>M</sub>", "$\\eta_M$"),
    ("d", "d̃", "$\\tilde{d}$"),
    ("cf1", "cf<sub>1</sub>", "$cf_1$"),
    ("cf2", "cf<sub>2</sub>", "$cf_2$"),
    ("kappa_v", "κ<sub>v</sub>", "$\\kappa_v$"),
    ("eta_v", "η<sub>v</sub>", "$\\eta_v$"),
    ("alpha", "α", "$\\alpha$"),
)


def build_table1(ctx: BuildContext) -> Built:
    """Table 1 from the packaged case data (``moving_bogie/data/table1_cases.csv``)."""
    from moving_bogie.model.cases import TABLE1_CASES, table1_case

    rows = [(n, table1_case(n).to_dict()) for n in TABLE1_CASES]
    head = "".join(f"<th>{h}</th>" for _, h, _ in TABLE1_COLUMNS)
    body = "\n".join(
        f"<tr><th>Case {n}</th>" + "".join(f"<td>{d[key]}</td>" for key, _, _ in TABLE1_COLUMNS) + "</tr>"
        for n, d in rows
    )
    table = f'<table class="data">\n<tr><th>Parameter</th>{head}</tr>\n{body}\n</table>'
    md_head = "| Parameter | " + " | ".join(m for _, _, m in TABLE1_COLUMNS) + " |"
    md_rule = "|" + "---|" * (len(TABLE1_COLUMNS) + 1)
    md_rows = [
        f"| Case {n} | " + " | ".join(f"{d[key]}" for key, _, _ in TABLE1_COLUMNS) + " |" for n, d in rows
    ]
    ctx.progress(1.0)
    return Built(
        html=table,
        markdown="\n".join([md_head, md_rule, *md_rows]),
        notes=[
            "Read from the packaged data file moving_bogie/data/table1_cases.csv (mu_v, J_b by Eq. (63))."
        ],
    )


def build_table2(ctx: BuildContext) -> Built:
    """Table 2: every induced frequency with its confirmed digits, beside the printed value."""
    from moving_bogie.roots.table2 import compute_table2, format_table2

    table = compute_table2(dps=ctx.dps, progress=ctx.progress)
    ctx.table2 = table
    (ctx.out / "table2.txt").write_text(format_table2(table) + "\n", encoding="utf-8")
    (ctx.out / "table2.json").write_text(json.dumps(table.to_dict(), indent=2) + "\n", encoding="utf-8")
    html_rows, md_rows = [], []
    for row in table.rows:
        verdict = "stable" if row.result.stable else "UNSTABLE"
        count = "count ok" if row.result.count_ok else "COUNT MISMATCH"
        match = "" if not row.printed else ("matches print" if row.ok else "DIFFERS FROM PRINT")
        status = ", ".join(x for x in (count, verdict, match) if x)
        n = len(row.result.roots)
        for k, (root, diff) in enumerate(zip(row.result.roots, row.differences)):
            shown = min(6, root.decimals)
            re6, im6 = _round_text(root.re_text, shown), _round_text(root.im_text, shown)
            printed = _printed_for(row.printed, root) if diff is not None else None
            pr = f"±{printed[0]}" if printed else "withheld" if not row.printed else "—"
            pi = printed[1] if printed else ""
            dd = f"{float(diff[0]):+.1e}, {float(diff[1]):+.1e}" if diff is not None else ""
            cls = ' class="unstable"' if root.unstable else ""
            first = (
                f'<th rowspan="{n}">Case {row.case}<br><small>{html.escape(status)}</small></th>'
                if k == 0
                else ""
            )
            html_rows.append(
                f"<tr{cls}>{first}<td>{k + 1}</td><td>±{re6}</td><td>{im6}</td><td>{pr}</td><td>{pi}</td>"
                f'<td>{dd}</td><td class="digits">±{root.re_text}<br>{root.im_text}<br>'
                f"<small>{root.digits} digits confirmed</small></td></tr>"
            )
            md_rows.append(
                f"| {'Case ' + str(row.case) if k == 0 else ''} | {k + 1} | ±{re6} | {im6} | {pr} | {pi} "
                f"| {dd} | "
                f"{root.digits} | {status if k == 0 else ''} |"
            )
    head = (
        "<tr><th>Case</th><th>#</th><th>q<sup>r</sup></th><th>q<sup>i</sup></th>"
        "<th>printed q<sup>r</sup></th>"
        "<th>printed q<sup>i</sup></th><th>computed − printed</th><th>all confirmed digits</th></tr>"
    )
    table_html = f'<table class="data">\n{head}\n' + "\n".join(html_rows) + "\n</table>"
    md = "\n".join(
        [
            "| Case | # | $q^r$ | $q^i$ | printed $q^r$ | printed $q^i$ | computed − printed | digits "
            "| verdict |",
            "|---|---|---|---|---|---|---|---|---|",
            *md_rows,
        ]
    )
    notes = [
        f"Computed at {ctx.dps} digits; every digit shown is confirmed by recomputation at higher precision. "
        "One root of each pair q, −conj(q) is listed (Re q ≥ 0); rows in red are unstable (Im q < 0).",
        "The preprint withholds the printed rows of Cases 7-13: those are computed only.",
        "Also written: table2.txt (the layout of `moving-bogie table2`) and table2.json.",
    ]
    if not table.ok:
        notes.append("MISMATCH: some case differs from the print or has a count mismatch (see table2.txt).")
    return Built(files=["table2.txt", "table2.json"], html=table_html, markdown=md, notes=notes, ok=table.ok)


def _round_text(text: str, decimals: int) -> str:
    """Round the decimal `text` of a confirmed digit string to `decimals` places (no "-0.000")."""
    value = Decimal(text).quantize(Decimal(1).scaleb(-decimals))
    if value == 0:
        value = abs(value)
    return f"{value:.{decimals}f}"


def _printed_for(printed: Sequence[tuple[str, str]], root: Any) -> tuple[str, str]:
    """The printed (Re q, Im q) nearest to the computed `root`."""
    q = complex(root.q)
    return min(printed, key=lambda pr: abs(q - complex(float(pr[0]), float(pr[1]))))
