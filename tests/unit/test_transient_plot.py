"""Transient figures (seed 001 Figs. 7, 8, 10) are drawn and written."""

import numpy as np

import wheelrail as wr
from wheelrail.transient.plot import plot_centreline, plot_creepage, plot_state


def test_figures_written(tmp_path):
    hc = wr.hertz_from_radii(10e3, 0.5, -0.409, 0.3, material=wr.STEEL)
    res = wr.transient_rolling(hc, travel=1.2e-3, step=3e-4, mu=0.4, Fx=2000.0,
                               elements=6, frames=3)
    fig = plot_creepage(res, path=tmp_path / "xi.png")
    line = fig.axes[0].lines[0]
    assert np.allclose(line.get_ydata(), res.xi[1:])
    assert len(plot_centreline(res, path=tmp_path / "p.png").axes[0].lines) == 3
    plot_state(res, 1.2e-3, path=tmp_path / "s.png")
    for name in ("xi.png", "p.png", "s.png"):
        assert (tmp_path / name).stat().st_size > 1000
    ds = res.dataset
    ds.to_netcdf(tmp_path / "run.nc")
    import xarray as xr
    with xr.open_dataset(tmp_path / "run.nc") as back:
        assert np.allclose(back.xi.values, res.xi)
