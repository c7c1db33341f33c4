"""``sweep --file`` on a soil-track file (:mod:`moving_bogie.sweep.soil`): the options it takes, checked."""

from __future__ import annotations

import argparse
import tomllib
from typing import TYPE_CHECKING

from moving_bogie.errors import ParameterError

from .common import first_given, option_flag, parameter_options, soil_settings, vary_texts
from .job_size import check_points

if TYPE_CHECKING:
    from moving_bogie.sweep.soil import SoilSweepSpec

__all__ = ["soil_spec"]

#: the options of a sweep that a soil-track file does not take, and why
NOT_FOR_SOIL = {
    **dict.fromkeys(
        ("case", "beam", "track", "vehicle"), "the file sets the model (--set KEY=VALUE changes a value)"
    ),
    "roots": "a soil sweep stores the critical velocity of every point, not roots",
    "check": "a soil sweep has no root count to verify",
    "margin": "a soil sweep stores the critical velocity of every point, not a stability margin",
}


def soil_spec(args: argparse.Namespace) -> SoilSweepSpec:
    """The sweep of the soil-track file ``args.file``, every option and every axis's extreme values checked
    before any computation."""
    from moving_bogie.soil.file import load_soil_file
    from moving_bogie.sweep.design import parse_sample
    from moving_bogie.sweep.soil import make_soil_spec

    why = "give the values in the file (--set KEY=VALUE changes one)"
    table = NOT_FOR_SOIL | {name: why for name, _, _ in parameter_options()}
    dest = first_given(args, table)
    if dest is not None:
        flag = option_flag(dest)
        raise ParameterError(flag.lstrip("-"), f"{flag} does not apply to a soil-track file: {table[dest]}")
    if args.units == "dimensionless":
        raise ParameterError(
            "--units", "--units dimensionless does not apply to a soil-track file: it is in SI"
        )
    if args.workers is not None and args.scheduler:
        raise ParameterError("--workers", "give either --workers or --scheduler, not both")
    vary = vary_texts(args.vary)
    sample = parse_sample(args.sample) if args.sample else None
    if sample is not None:
        check_points(sample, "--sample")
    settings = soil_settings(args)
    load_soil_file(args.file, settings)  # the file and the settings checked: errors name the key
    try:
        data = tomllib.loads(args.file.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:
        raise ParameterError("file", f"{args.file}: not a valid TOML file: {exc}") from None
    block_points = 1 if args.chunk_points is None else args.chunk_points
    return make_soil_spec(
        data, str(args.file), vary, settings=settings, sample=sample, block_points=block_points
    )
