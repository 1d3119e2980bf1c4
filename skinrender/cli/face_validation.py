"""
``skinrender validate`` on a face scene (being built: issue 13).
"""

from __future__ import annotations

import argparse

from ..errors import SkinrenderError

__all__ = ["command_validate_face"]


def command_validate_face(args: argparse.Namespace) -> None:
    """Validate a face render against the analytic limits of its level of physics."""
    raise SkinrenderError(f"validate {args.scene}: validating a face scene is not built yet (issue 13)")
