#!/usr/bin/python3
"""moraine: the inflow and outflow columns of a run's diagnostics, read back.

usage: check_inflow_series.py OUTDIR

OUTDIR holds what examples/channel_inflow/deck.lua writes (a jet from an
inflow source leaving through a free face): diagnostics.csv and
diagnostics.h5. Checks, with the csv module and h5py:
  - both carry E_inflow, W_inflow and E_outflow, with units J/m in the series;
  - the CSV rows equal the series' rows (17 significant digits);
  - E_inflow grows, and both E_inflow and E_outflow end positive (material
    came in and went out);
  - W_MPM equals E_total - E_ref - W_plastic - W_friction - W_damping -
    W_external - E_inflow - W_inflow + E_outflow row by row (E_ref the first
    row's E_total; the run starts empty) to 1e-9 of the energy scale."""
import csv
import os
import sys

import h5py
import numpy as np

NEW = ("E_inflow", "W_inflow", "E_outflow")


def main(outdir):
    with open(os.path.join(outdir, "diagnostics.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    with h5py.File(os.path.join(outdir, "diagnostics.h5"), "r") as f:
        for k in NEW:
            assert k in cols, "diagnostics.csv has no column %s" % k
            assert k in f, "diagnostics.h5 has no dataset %s" % k
            assert f[k].attrs["units"].decode() == "J/m", "%s: units %r" % (k, f[k].attrs["units"])
        for k in cols:
            series = f[k][()]
            assert series.shape == cols[k].shape, "%s: %s rows in the series, %s in the CSV" % (k, series.shape,
                                                                                               cols[k].shape)
            assert np.allclose(series, cols[k], rtol=1e-15, atol=0), "%s: the CSV differs from the series" % k
    e_in, w_in, e_out = cols["E_inflow"], cols["W_inflow"], cols["E_outflow"]
    assert np.all(np.diff(e_in) >= 0), "E_inflow decreases"
    assert e_in[-1] > 0 and e_out[-1] > 0, "E_inflow %g, E_outflow %g at the end" % (e_in[-1], e_out[-1])
    booked = (cols["E_total"] - cols["E_total"][0] - cols["W_plastic"] - cols["W_friction"] - cols["W_damping"] -
              cols["W_external"] - e_in - w_in + e_out)
    scale = np.max(np.abs(e_in) + np.abs(w_in) + np.abs(e_out))
    err = np.max(np.abs(booked - cols["W_MPM"])) / scale
    assert err < 1e-9, "W_MPM differs from its definition by %.3g of the energy scale" % err
    print("inflow series: %d rows; E_inflow %.6g, W_inflow %.6g, E_outflow %.6g J/m at the end; W_MPM as defined "
          "to %.2g" % (len(rows), e_in[-1], w_in[-1], e_out[-1], err))


if __name__ == "__main__":
    main(sys.argv[1])
