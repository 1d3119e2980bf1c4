"""
Tests for :mod:`skinrender.workload`: work that grows with a count is refused above a cap on its estimated time,
naming the flag, the estimate and the flag that raises the cap.
"""

from __future__ import annotations

import io

import pytest

from skinrender.errors import SkinrenderError
from skinrender.workload import MINUTES_MAX, announce, check_work, duration_text, progress_bar


@pytest.mark.parametrize("seconds, text", [(0.5, "0.5 s"), (42, "42 s"), (90, "1.5 min"), (3600, "1 h"),
                                           (86400, "24 h"), (86400 * 42, "42 days"), (float("inf"), "forever")])
def test_durations_read_as_a_person_reads_them(seconds, text):
    assert duration_text(seconds) == text


def test_work_under_the_cap_runs_and_over_it_is_refused_with_the_estimate():
    check_work(60 * MINUTES_MAX, "--samples", "some samples")
    with pytest.raises(SkinrenderError) as caught:
        check_work(60 * MINUTES_MAX + 1, "--samples", "some samples", fewer="ask for fewer --samples")
    line = str(caught.value)
    assert line.startswith("--samples: some samples would take about 1 h (estimated)") and caught.value.flag == "--samples"
    assert "raise --max-minutes or ask for fewer --samples" in line


def test_raising_the_cap_lets_longer_work_run():
    check_work(7200, "--repeat", "repetitions", limit_minutes=121)
    with pytest.raises(SkinrenderError, match="--max-minutes must be a finite number of minutes > 0"):
        check_work(1, "--repeat", "repetitions", limit_minutes=0)


class Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


@pytest.mark.parametrize("stream, drawn, announced", [(Terminal(), True, False), (io.StringIO(), False, True),
                                                      (None, False, False)])
def test_progress_is_a_bar_on_a_terminal_and_one_line_elsewhere(stream, drawn, announced):
    """The one progress bar of the package (the search's triplets, the face renders): drawn on a terminal only; a
    log or a pipe gets one line saying the work started; --quiet (no stream) gets nothing."""
    bar = progress_bar(3, "renders", stream, "render")
    announce(stream, "renders", 3, "render")
    bar.update(3)
    bar.close()
    text = "" if stream is None else stream.getvalue()
    assert ("3/3" in text) is drawn and ("render/s" in text) is drawn
    assert ("renders: 3 renders …" in text) is announced
