"""Generated calls of the movie writers (phasekit.viz.animate, film_strip, check_movie_options) on a
short cheap run: frames, fps, t_span, timing, scale, gap_scale, camera, panel, window_size, title
and output paths (suffixes, directories, wrong types), mostly valid, one field at a time bad.
Every case ends in one of three outcomes:

* ``valid``  - the file is written, with as many frames as asked, each of the reported size
  (a GIF read back by Pillow, an MP4 by ffmpeg, a PNG's size), and with ``timing="real"`` the
  playback speed of the span in seconds (sqrt(b/g) from b and g by hand);
* ``failed`` - a PhasekitError with a one-line reason (an MP4 without ``phasekit[movie]``);
* ``error``  - a ParameterError naming an argument of the call, in one line.

check_movie_options, which the CLI runs before simulating, agrees with animate: it refuses
exactly the options animate refuses (naming the same argument, or animate names one it does not
take: t_span, title). Derandomised; ``pytest -s`` prints the counts.
"""

import collections
import itertools
import math
import os
import warnings

import phasekit as pk
from phasekit.viz import animate, film_strip
from phasekit.viz.animate import check_movie_options

import numpy as np
import pytest

from ..generated_inputs import fuzz, generated, hang_guard, mostly, report, st, thin_suites

pytestmark = pytest.mark.render
COUNTS: dict[str, collections.Counter] = collections.defaultdict(collections.Counter)
COVERED: collections.Counter = collections.Counter()  # what the valid movies were: suffix, panel, timing, scale
CASE = itertools.count()
MOVIE_ARGS = {"traj", "path", "frames", "fps", "t_span", "timing", "scale", "gap_scale", "camera", "panel",
              "window_size", "title", "progress"}
STRIP_ARGS = {"traj", "path", "frames", "t_span", "times", "columns", "scale", "gap_scale", "camera", "window_size",
              "title"}
B, G = 0.0215, 9.81  # the scales' b (m) and g (m/s^2)


@pytest.fixture(scope="module")
def run():
    body = pk.Spheroid(1.5)
    return pk.simulate(pk.Model(body, pk.Coulomb(0.1)), pk.gyroscopic_start(body, 1.55, omega0=11.0), 6.0)


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    report(COUNTS, "generated movie calls (valid / failed with a reason / clear error):", None,
           lines_after=[f"  valid movies: {dict(sorted(COVERED.items()))}"])
    assert thin_suites(COUNTS) == {} and {".gif", ".mp4"} <= set(COVERED)  # a suite that wrote movies


def classify(allowed: set[str], call):
    """(outcome, result, the argument a ParameterError named)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # a warning that leaks to the user is a bug here
            result = call()
    except pk.ParameterError as exc:
        msg = str(exc)
        assert exc.param in allowed, f"ParameterError names `{exc.param}`, not one of {sorted(allowed)}: {msg}"
        assert msg.startswith(f"`{exc.param}` ") and "\n" not in msg, msg
        return "error", None, exc.param
    except pk.PhasekitError as exc:
        assert str(exc) and "\n" not in str(exc), repr(exc)
        return "failed", None, None
    return "valid", result, None


# -- strategies ------------------------------------------------------------------------------------

SCALES = {"none": None, "21.5 mm": pk.Scale("21.5 mm"), "21.5 mm, 57 g": pk.Scale("21.5 mm", mass="57 g")}


def paths():
    good = st.sampled_from([".gif", ".gif", ".mp4", ".mp4", ".GIF", ".png", "new/sub/x.gif"])
    bad = st.sampled_from([".avi", "", ".gif.txt", "DIR.gif", 5, None, b"x.gif"])
    return mostly(good, bad, n_good=10)


def frames():
    return mostly(st.sampled_from([1, 2, 3]), st.sampled_from([0, -1, 10_001, 2.5, "3", None, True, np.int64(2)]))


def windows():
    good = st.sampled_from([(64, 64), (96, 72), (120, 90), [100, 80]])
    bad = st.sampled_from([(63, 64), (64, 4097), (100,), (100.0, 80), "100x80", None, (True, 80), (100, 80, 3)])
    return mostly(good, bad)


def options():
    return st.fixed_dictionaries({
        "frames": frames(),
        "fps": mostly(st.sampled_from([24.0, 1, 240, 12.5]), st.sampled_from([0, -1, 241, math.nan, math.inf, "24",
                                                                              True])),
        "timing": mostly(st.sampled_from(["body", "real"]), st.sampled_from(["BODY", "", None, 1])),
        "scale": mostly(st.sampled_from(sorted(SCALES)).map(SCALES.get), st.sampled_from(["21.5 mm", 1.0, []])),
        "gap_scale": mostly(st.sampled_from([1.0, 25.0, 2]), st.sampled_from([0.5, 0, -1, math.nan, math.inf, "2",
                                                                              True])),
        "camera": mostly(st.sampled_from(["follow", "fixed"]), st.sampled_from(["top", "", None, 1])),
        "panel": mostly(st.sampled_from([None, None, "R", "phase", "none"]), st.sampled_from(["Q", "r", 1, []])),
        "window_size": windows(),
    })


def spans():
    return mostly(st.sampled_from([None, (0.0, 3.0), (2.0, 6.0)]),
                  st.sampled_from([(3.0, 1.0), (0.0, 7.0), (-1.0, 2.0), "x", (math.nan, 1.0), (1.0,), 4.0]))


def titles():
    return mostly(st.sampled_from([None, "a title", "two\nlines"]), st.sampled_from([5, b"t", ["t"]]), n_good=12)


def _target(tmp_path, suffix):
    if isinstance(suffix, bytes):  # a bytes path, inside the test's directory all the same
        return os.fsencode(tmp_path / suffix.decode())
    if not isinstance(suffix, str):
        return suffix
    n = next(CASE)
    if suffix == "DIR.gif":
        (tmp_path / f"d{n}.gif").mkdir()
        return tmp_path / f"d{n}.gif"
    if "/" in suffix:
        return tmp_path / f"new{n}" / suffix
    return tmp_path / f"case{n}{suffix}"


# -- what a written movie holds ----------------------------------------------------------------------


def _check_written(info, path, n_frames: int, opts: dict, span) -> None:
    from PIL import Image

    w, h = (int(v) for v in opts["window_size"])
    panel = opts["panel"] not in (None, "none")
    assert info.frame_size == (w + (h if panel else 0), h) and info.n_frames == n_frames
    assert info.bytes == path.stat().st_size > 0
    np.testing.assert_allclose(info.times, np.linspace(span[0], span[1], n_frames), rtol=1e-14, atol=1e-14)
    suffix = path.suffix.lower()
    if suffix in (".gif", ".png"):
        im = Image.open(path)
        assert im.size == info.frame_size
        assert getattr(im, "n_frames", 1) == (n_frames if suffix == ".gif" else 1)
    else:
        import imageio_ffmpeg

        reader = imageio_ffmpeg.read_frames(str(path))
        meta = next(reader)
        assert tuple(meta["size"]) == tuple(-(-v // 16) * 16 for v in info.frame_size)  # padded to macroblocks
        assert sum(1 for _ in reader) == n_frames
    if opts["scale"] is not None:
        seconds = (span[1] - span[0]) * math.sqrt(B / G)
        assert info.speed == pytest.approx(seconds / (n_frames / float(opts["fps"])), rel=1e-9)
    else:
        assert info.speed is None


def _movie_args(opts: dict) -> dict:
    return {k: opts[k] for k in ("frames", "fps", "timing", "gap_scale", "camera", "panel", "window_size", "scale")}


@hang_guard(1200)
@generated(paths, options, spans, titles, **fuzz(36))
def test_generated_animate(run, tmp_path, suffix, opts, t_span, title):
    path = _target(tmp_path, suffix)
    early = classify(MOVIE_ARGS, lambda: check_movie_options(path, **_movie_args(opts)))
    outcome, info, named = classify(MOVIE_ARGS, lambda: animate(run, path, t_span=t_span, title=title, progress=False,
                                                                **_movie_args(opts)))
    COUNTS["animate"][outcome] += 1
    if early[0] == "error":  # refused before any simulation: animate refuses it too
        assert outcome == "error" and named in {early[2], "t_span", "title"}, (early, named)
    elif early[0] == "failed":
        assert outcome in ("failed", "error") and named in (None, "t_span", "title")
    else:
        assert outcome == "valid" or named in {"t_span", "title"}, (outcome, named)
    if outcome == "valid":
        span = (run.t0, run.t) if t_span is None else tuple(float(v) for v in t_span)
        _check_written(info, path, int(opts["frames"]), opts, span)
        COVERED.update([path.suffix.lower(), f"panel {opts['panel']}", f"timing {opts['timing']}",
                        f"scale {opts['scale'] is not None}"])


@hang_guard(1200)
@generated(lambda: mostly(st.sampled_from([".png", ".png", ".PNG"]), st.sampled_from([".gif", "", "DIR.gif", None]),
                          n_good=6),
           lambda: mostly(st.sampled_from([1, 2, 3]), st.sampled_from([0, 101, 2.5, "2"]), n_good=6),
           lambda: mostly(st.sampled_from([None, None, [0.5, 1.0], (5.9,)]),
                          st.sampled_from([[], [7.0], [math.nan], list(range(101)), "1.0"]), n_good=6),
           lambda: mostly(st.sampled_from([None, 1, 2]), st.sampled_from([0, 101, 1.5, "2"]), n_good=6),
           windows, titles, **fuzz(20))
def test_generated_film_strip(run, tmp_path, suffix, n, times, columns, window_size, title):
    from PIL import Image

    path = _target(tmp_path, suffix)
    outcome, info, _ = classify(STRIP_ARGS, lambda: film_strip(run, path, n, times=times, columns=columns,
                                                              window_size=window_size, title=title))
    COUNTS["film_strip"][outcome] += 1
    if outcome == "valid":
        k = len(times) if times is not None else int(n)
        cols = k if columns is None else int(columns)
        w, h = (int(v) for v in window_size)
        band = 30 if title else 0  # the title's white band
        assert info.n_frames == k and Image.open(path).size == info.frame_size
        assert info.frame_size == (w * cols, h * math.ceil(k / cols) + band)


@hang_guard(600)
@generated(paths, options, **fuzz(120))
def test_generated_movie_options(tmp_path, suffix, opts):
    """The check the CLI runs first draws nothing and names what it refuses."""
    outcome, result, _ = classify(MOVIE_ARGS - {"traj", "t_span", "title"},
                                  lambda: check_movie_options(_target(tmp_path, suffix), **_movie_args(opts)))
    COUNTS["check_movie_options"][outcome] += 1
    assert result is None and [p for p in tmp_path.rglob("*") if p.is_file()] == []
