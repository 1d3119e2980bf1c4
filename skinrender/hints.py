"""
Type hints
==========

The one import point for the type hints used across :mod:`skinrender`
(as ``colour.hints`` is for colour-science).
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["ArrayLike", "NDArrayFloat", "NDArrayInt", "NDArrayBool", "Literal"]

NDArrayFloat = NDArray[np.float64]
NDArrayInt = NDArray[np.int_]
NDArrayBool = NDArray[np.bool_]
