"""The steady-state figures speak the stability vocabulary: under exact Coulomb friction no branch
state is drawn or named stable (the rolling field's states are neutral), under viscous friction
the stable ones are; one structure draws one panel."""

import phasekit as pk
import phasekit.studies as ps
from phasekit.viz.stability import COLOURS, state_word

import numpy as np
import pytest

BODY = pk.Spheroid(1.5, offset=0.2)


@pytest.fixture(scope="module")
def structures():
    return {"coulomb": pk.steady_structure(BODY, pk.Coulomb(0.1)), "viscous": pk.steady_structure(BODY, pk.Viscous(0.1))}


def _legend(fig) -> list[str]:
    return [t.get_text() for leg in fig.legends for t in leg.get_texts()]


def _line_colours(fig) -> set[str]:
    from matplotlib.colors import to_hex

    return {to_hex(line.get_color()) for ax in fig.axes for line in ax.get_lines()}


def test_classes_figure_names_coulomb_states_neutral_and_viscous_ones_stable(structures):
    coulomb = ps.plot_classes({"c": structures["coulomb"]}, note="")
    viscous = ps.plot_classes({"v": structures["viscous"]}, note="")
    try:
        c, v = _legend(coulomb), _legend(viscous)
        assert any(t.startswith("neutral") and "rolling, no decay" in t for t in c)
        assert not any(t.startswith("stable") for t in c) and COLOURS["stable"] not in _line_colours(coulomb)
        assert COLOURS["neutral"] in _line_colours(coulomb)
        assert "stable (viscous $\\mu$ = 0.1)" in v and "unstable" in v
        assert not any("rolling" in t for t in v) and COLOURS["stable"] in _line_colours(viscous)
    finally:
        pk.viz.pyplot().close("all")


def test_every_coulomb_branch_state_is_neutral_and_the_viscous_words_follow_the_classification(structures):
    """The rolling spectrum is symmetric about the imaginary axis: a state that does not grow
    does not decay either, so under exact Coulomb no state is stable."""
    words = [state_word(p) for b in structures["coulomb"].branches for p in b.points]
    lams = [p.eigenvalues for b in structures["coulomb"].branches for p in b.points]
    assert set(words) == {"neutral"} and max(float(np.max(lam.real)) for lam in lams) < 1e-6
    seen = set()
    for b in structures["viscous"].branches:  # the word from the spectrum's counts, not from the label's text
        for p in b.points:
            expected = ("unstable" if p.n_unstable else "undecided" if p.n_undecided
                        else "stable" if p.n_neutral <= 2 else "neutral")
            assert state_word(p) == expected
            seen.add(expected)
    assert {"stable", "unstable"} <= seen


def test_classes_figure_draws_one_panel_per_structure(structures):
    for n in (1, 2, 4):
        fig = ps.plot_classes({f"s{k}": structures["viscous"] for k in range(n)}, note="demo")
        try:
            assert len(fig.axes) == n
            title = fig._suptitle.get_text()
            assert ("every class" not in title) and ((f"each of {n} classes" in title) == (n > 1))
        finally:
            pk.viz.pyplot().close(fig)


@pytest.mark.render
def test_structure_scene_names_and_draws_coulomb_states_neutral(structures, tmp_path, monkeypatch):
    import pyvista as pv
    from PIL import Image

    legends = []
    add_legend = pv.Plotter.add_legend

    def recording(self, labels=None, *args, **kwargs):
        legends.append([entry[0] for entry in labels])
        return add_legend(self, labels, *args, **kwargs)

    monkeypatch.setattr(pv.Plotter, "add_legend", recording)
    pixels = {}
    for name, s in structures.items():
        ps.render_structure(s, tmp_path / f"{name}.png", window_size=(600, 420))
        img = np.asarray(Image.open(tmp_path / f"{name}.png").convert("RGB")).astype(int)
        pixels[name] = {w: int(np.sum(np.abs(img - [int(COLOURS[w][i:i + 2], 16) for i in (1, 3, 5)]).sum(axis=2) < 30))
                        for w in ("stable", "neutral")}
    coulomb, viscous = legends
    assert any(t.startswith("neutral") and "rolling, no decay" in t for t in coulomb)
    assert not any(t.startswith("stable") for t in coulomb)
    assert any(t.startswith("stable (viscous") for t in viscous) and not any("rolling" in t for t in viscous)
    assert pixels["coulomb"]["stable"] == 0 and pixels["coulomb"]["neutral"] > 300
    assert pixels["viscous"]["stable"] > 300
