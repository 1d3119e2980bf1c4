"""
Commands that list the bundled data: ``cameras``, ``datasets``.
"""

from __future__ import annotations

import argparse

from .common import (add_common, emit, range_text, table)


def add_parsers(commands) -> None:
    """Add the parsers of cameras, datasets."""
    p = commands.add_parser("cameras", run=command_cameras, help="list bundled cameras")
    add_common(p)

    p = commands.add_parser("datasets", run=command_datasets,
                            help="list reflectance sets with source, licence, count, range")
    add_common(p)


def command_cameras(args: argparse.Namespace) -> None:
    from ..datasets import list_cameras

    cameras = list_cameras()
    text = table([[c["name"], range_text(c["wavelengths"]), c["source"]] for c in cameras],
                  ["name", "wavelengths", "source"])
    emit(args, {"cameras": cameras}, text)


def command_datasets(args: argparse.Namespace) -> None:
    from ..datasets import list_reflectances

    datasets = list_reflectances()
    text = table(
        [[d["name"], d["count"], range_text(d["wavelengths"]), d["licence"]] for d in datasets],
        ["name", "count", "wavelengths", "licence"],
    )
    emit(args, {"datasets": datasets}, text)
