"""Table 2 of the paper: the induced frequencies of the 13 cases of Table 1, compared with the print.

The printed values (six decimals; Cases 7-13 withheld from the reference data) are compared with the
computed roots rounded the same way: a difference beyond half a unit of the sixth decimal is a mismatch.
Roots are matched to printed ones by proximity, not by position.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from decimal import Decimal
from typing import Any

import mpmath

from moving_bogie.kernels.bound import BoundModel
from moving_bogie.model.cases import TABLE1_CASES, table1_case, table2_printed
from moving_bogie.roots.count.strip import branch_point_text
from moving_bogie.roots.damping_limit import DampingLimit, damping_limit
from moving_bogie.roots.frequencies import FrequencyResult, induced_frequencies
from moving_bogie.roots.frequency_result import InducedFrequency
from moving_bogie.roots.proof.certify import ProofVerdict
from moving_bogie.roots.refine.polish import fixed_text

#: Half a unit of the print's last decimal (six decimals).
PRINT_TOLERANCE = Decimal("0.0000005")


@dataclass(frozen=True)
class CaseRow:
    case: int
    result: FrequencyResult
    printed: tuple[tuple[str, str], ...]  # (re, im) decimal strings, possibly empty
    differences: tuple[tuple[Decimal, Decimal] | None, ...]  # per computed root: (dre, dim), None when
    # nothing is printed
    limit: DampingLimit | None = None  # the real roots of an eta_f = 0 case under eta_f -> 0+

    @property
    def ok(self) -> bool:
        if not self.result.count_ok:
            return False
        return all(
            d is None or (abs(d[0]) <= PRINT_TOLERANCE and abs(d[1]) <= PRINT_TOLERANCE)
            for d in self.differences
        )


@dataclass(frozen=True)
class Table2:
    rows: tuple[CaseRow, ...]

    @property
    def ok(self) -> bool:
        return all(row.ok for row in self.rows)

    @property
    def printed_cases(self) -> tuple[int, ...]:
        """The cases whose printed values the reference data hold (Cases 1-6)."""
        return tuple(row.case for row in self.rows if row.printed)

    def to_dict(self) -> dict[str, Any]:
        cases = []
        for row in self.rows:
            d = row.result.to_dict()
            d["case"] = row.case
            d["printed"] = [{"re": re, "im": im} for re, im in row.printed]
            d["difference"] = [
                None if x is None else {"re": str(x[0]), "im": str(x[1])} for x in row.differences
            ]
            d["ok"] = row.ok
            d["damping_limit"] = None if row.limit is None else row.limit.to_dict()
            if row.result.certificate is not None:
                d["certified"]["printed_enclosed"] = printed_enclosed(row)
            cases.append(d)
        return {
            "cases": cases,
            "printed_cases": list(self.printed_cases),
            "ok": self.ok,
            "print_tolerance": str(PRINT_TOLERANCE),
        }


def compare_with_print(
    result: FrequencyResult, printed: Sequence[tuple[str, str]]
) -> tuple[tuple[Decimal, Decimal] | None, ...]:
    """Differences (computed - printed) for each computed root, matching printed roots by proximity."""
    remaining = list(printed)
    out: list[tuple[Decimal, Decimal] | None] = []
    for r in result.roots:
        if not remaining:
            out.append(None)
            continue
        q = complex(r.q)
        best = min(remaining, key=lambda pr: abs(q - complex(float(pr[0]), float(pr[1]))))
        remaining.remove(best)
        re_printed, im_printed = best
        out.append((Decimal(r.re_text) - Decimal(re_printed), Decimal(r.im_text) - Decimal(im_printed)))
    return tuple(out)


def printed_enclosed(row: CaseRow) -> list[bool | None]:
    """Per computed root with a printed value: whether its proven enclosure rounds, at every point, to the
    printed digits (None where nothing is printed or nothing was proven)."""
    certificate = row.result.certificate
    assert certificate is not None  # only a certified row has enclosures
    out: list[bool | None] = []
    for r, e, diff in zip(row.result.roots, certificate.roots, row.differences):
        if diff is None or not e.certified:
            out.append(None)
            continue
        pr_re, pr_im = _printed_for(row, r)
        decimals = len(pr_re.split(".")[1])
        out.append(e.rounds_to(pr_re, pr_im, decimals))
    return out


def compute_table2(
    *,
    dps: int = 30,
    cases: Iterable[int] = TABLE1_CASES,
    progress: Callable[[float], None] | None = None,
    certify: bool = False,
) -> Table2:
    """Table 2 by :func:`induced_frequencies` per case (with ``certify``, each result carries its proof)."""
    rows = []
    cases = tuple(cases)
    for k, case in enumerate(cases):
        bound = BoundModel(table1_case(case))  # Table 1: the bogie, each case bound once here
        result = induced_frequencies(bound, dps=dps, certify=certify)
        printed = tuple(table2_printed(case))
        limit = damping_limit(result)
        rows.append(CaseRow(case, result, printed, compare_with_print(result, printed), limit))
        if progress:
            progress((k + 1) / len(cases))
    return Table2(tuple(rows))


def format_table2(table: Table2, decimals: int = 6) -> str:
    """The paper's layout: per case, q^r (with +-) and q^i of each root; printed value and difference."""
    lines = ["Table 2. Induced frequencies (one root of each pair q, -conj(q); Re q >= 0)"]
    lines.append(f"printed: the paper's values for {case_list(table.printed_cases)}; {_unprinted(table)}")
    lines.append("")
    head = (
        f"{'case':>4} {'#':>2} {'q^r':>{decimals + 5}} {'q^i':>{decimals + 5}}   {'printed':>22}   difference"
    )
    lines.append(head)
    for row in table.rows:
        for k, (r, diff) in enumerate(zip(row.result.roots, row.differences), 1):
            shown = min(decimals, r.decimals)  # never show an unconfirmed digit
            re = fixed_text(mpmath.re(r.q), shown)
            im = fixed_text(mpmath.im(r.q), shown)
            pr = ""
            dd = ""
            if diff is not None:
                pr_re, pr_im = _printed_for(row, r)
                pr = f"+-{pr_re} {pr_im:>10}"
                dd = f"{float(diff[0]):+.1e} {float(diff[1]):+.1e}"
            flag = " unstable" if r.unstable else ""
            lines.append(
                f"{row.case if k == 1 else '':>4} {k:>2} {'+-' + re:>{decimals + 5}} {im:>{decimals + 5}}   "
                f"{pr:>22}   {dd}{flag}"
            )
        status = "count ok" if row.result.count_ok else "COUNT MISMATCH"
        state = row.result.verdict
        verdict = {"stable": _stable_text(row.result), "unstable": "UNSTABLE"}.get(state.state) or (
            "verdict UNDETERMINED (" + ", ".join(note.reason.value for note in state.reasons) + ")"
        )
        match = (
            "no printed value to compare"
            if not row.printed
            else ("matches print" if row.ok else "DIFFERS FROM PRINT")
        )
        lines.append(f"{'':>7} {status}, {verdict}{', ' + match if match else ''}")
        if row.limit is not None:
            lines.append(f"{'':>7} {row.limit.statement()}")
        if row.result.certificate is not None:
            lines.append(f"{'':>7} {certificate_line(row)}")
    lines.append("")
    lines += summary_lines(table)
    return "\n".join(lines)


def summary_lines(table: Table2) -> list[str]:
    """The closing lines: print and counts; the unstable cases, then the stable ones (undetermined named);
    the undamped cases whose verdict the strip below the cut decided, on a line of their own; the proofs."""
    by_state = {
        state: [row.case for row in table.rows if row.result.verdict.state == state]
        for state in ("unstable", "stable", "undetermined")
    }
    verdicts = (
        f"verdicts: {len(by_state['unstable'])} unstable ({case_list(by_state['unstable'])}: an induced "
        f"frequency with Im q < 0), {len(by_state['stable'])} stable ({case_list(by_state['stable'])})"
    )
    if by_state["undetermined"]:
        verdicts += f", UNDETERMINED for {case_list(by_state['undetermined'])}"
    undamped = [row.case for row in table.rows if row.result.strip is not None and row.result.strip.decided]
    lines = [
        "all cases match the print and their counts" if table.ok else "MISMATCH: see the rows marked above"
    ]
    lines.append(verdicts)
    if undamped:
        lines.append(
            f"undamped (eta_f = 0): {case_list(undamped)}, each verdict decided by counting the strip below "
            "the cut on the real axis with K as the limit from below"
        )
    if any(row.result.certificate is not None for row in table.rows):
        unproven = [
            row.case
            for row in table.rows
            if row.result.certificate is not None
            and row.result.certificate.verdict is ProofVerdict.NOT_PROVEN
        ]
        lines.append(
            "proofs: every verdict proven"
            if not unproven
            else f"proofs: verdict NOT PROVEN for {case_list(unproven)} (the rows above say what remains)"
        )
    return lines


def _stable_text(result: FrequencyResult) -> str:
    real = sum(r.marginal for r in result.roots)
    return f"stable ({real} real root(s), neutral)" if real else "stable"


def case_list(numbers: Iterable[int]) -> str:
    """'Case 3', 'Cases 1, 5, 12, 13', runs of three or more as 'Cases 2-4, 6-11'; 'no case' when empty."""
    cases = list(numbers)
    if not cases:
        return "no case"
    if len(cases) == 1:
        return f"Case {cases[0]}"
    runs: list[list[int]] = []
    for case in cases:
        if runs and case == runs[-1][-1] + 1:
            runs[-1].append(case)
        else:
            runs.append([case])
    parts = []
    for run in runs:
        parts += [f"{run[0]}-{run[-1]}"] if len(run) > 2 else [str(c) for c in run]
    return "Cases " + ", ".join(parts)


def _unprinted(table: Table2) -> str:
    rest = tuple(row.case for row in table.rows if not row.printed)
    if not rest:
        return "every case is compared"
    return f"{case_list(rest)} have no printed values in the reference data (computed only, column blank)"


def certificate_line(row: CaseRow) -> str:
    """One line: roots and count proven, the proven verdict, whether the printed digits are enclosed."""
    c = row.result.certificate
    assert c is not None  # a line for a certified row
    text = f"proven: {c.proven_roots}/{len(c.roots)} roots, count {c.count}, verdict {c.verdict}"
    below = c.below
    if c.verdict is ProofVerdict.NOT_PROVEN and below is not None and below.count == 0:
        text += (
            f" (the strip below the cut on the real axis holds no root; what remains is the square of "
            f"half-side {below.notch:.0e} under {branch_point_text(below.notches)}, where K is infinite)"
        )
    elif c.verdict is ProofVerdict.NOT_PROVEN:
        text += f" ({c.reason})"
    enclosed = [x for x in printed_enclosed(row) if x is not None]
    if enclosed:
        text += ", printed digits " + ("enclosed" if all(enclosed) else "NOT ENCLOSED")
    return text


def _printed_for(row: CaseRow, root: InducedFrequency) -> tuple[str, str]:
    q = complex(root.q)
    return min(row.printed, key=lambda pr: abs(q - complex(float(pr[0]), float(pr[1]))))
