"""Every option of every command has help text, and no help text names an option that does not exist."""

from __future__ import annotations

import argparse
import re

from moving_bogie.cli import build_parser
from moving_bogie.cli.docs import subcommands


def _commands():
    parser = build_parser()
    return {"moving-bogie": parser} | subcommands(parser)


def test_every_option_has_help():
    missing = [
        f"{name} {'/'.join(action.option_strings) or action.dest}"
        for name, parser in _commands().items()
        for action in parser._actions
        if not isinstance(action, (argparse._HelpAction, argparse._SubParsersAction))
        and action.help != argparse.SUPPRESS
        and not (action.help or "").strip()
    ]
    assert not missing, "options without help text: " + ", ".join(missing)


def test_help_names_only_existing_options():
    """A help text that says "instead of --mu_v" while the option is --mu-v sends the reader nowhere."""
    wrong = []
    for name, parser in _commands().items():
        options = {s for action in parser._actions for s in action.option_strings}
        for action in parser._actions:
            for named in re.findall(r"(?<![\w-])--[A-Za-z][\w-]*", action.help or ""):
                if named not in options and not any(
                    named in p._option_string_actions for p in _commands().values()
                ):
                    wrong.append(f"{name} {'/'.join(action.option_strings)}: {named}")
    assert not wrong, "help texts naming no option: " + ", ".join(wrong)


def test_metavars_are_not_internal_names():
    """A metavar shows what to type; an internal destination name (THETA_MAX) says nothing to the user."""
    parser = build_parser()
    text = "\n".join(p.format_help() for p in subcommands(parser).values())
    assert "THETA" not in text


def test_timeseries_plot_only_does_not_claim_rows_written(tmp_path, capsys, compute_once):
    """``timeseries --plot`` without --csv writes no data file, so it must not say "rows written"."""
    import moving_bogie.roots.frequencies as fq
    from moving_bogie.cli import main

    compute_once(fq, "induced_frequencies")  # both runs search the same roots (Case 7): once
    png, csv = tmp_path / "s.png", tmp_path / "s.csv"
    base = ["timeseries", "--case", "7", "--tmax", "10", "--points", "11", "--no-branch-cut"]
    assert main(base + ["--plot", str(png)]) == 0
    out = capsys.readouterr().out
    assert "written" not in out and f"11 rows not printed (drawn in {png}" in out
    assert main(base + ["--csv", str(csv)]) == 0
    assert f"11 rows written to {csv}" in capsys.readouterr().out


def test_the_vehicle_help_names_every_vehicle_of_the_catalogue():
    from moving_bogie.model.catalogue import default_catalogue

    vehicles = default_catalogue().vehicles
    assert len(vehicles) >= 2
    for name, parser in _commands().items():
        for action in parser._actions:
            if "--vehicle" in action.option_strings:
                missing = [v for v in vehicles if f"{v}: " not in action.help]
                assert not missing, f"{name} --vehicle help lacks {missing}"
