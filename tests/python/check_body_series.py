#!/usr/bin/python3
"""moraine: the rigid-body columns of a run's diagnostics, read back.

usage: check_body_series.py OUTDIR

OUTDIR holds what examples/rigid_footing/deck.lua writes (a footing, a rigid
body, released onto soil): diagnostics.csv and diagnostics.h5. Checks, with
the csv module and h5py:
  - both carry E_bodies, W_bodies and the footing's wall.footing.* columns,
    E_bodies and W_bodies with units J/m in the series;
  - the CSV rows equal the series' rows (17 significant digits);
  - the footing fell: W_bodies ends positive, E_bodies starts at 0 and is
    positive while it moves;
  - W_MPM equals E_total + E_bodies - E_ref - W_plastic - W_friction -
    W_damping - W_external - W_walls - W_bodies - E_inflow - W_inflow +
    E_outflow row by row (E_ref the first row's E_total + E_bodies, the
    works zero there) to 1e-9 of the energy scale;
  - W_walls stays 0: the footing's work on the soil is inside the system."""
import csv
import os
import sys

import h5py
import numpy as np

NEW = ("E_bodies", "W_bodies")


def main(outdir):
    with open(os.path.join(outdir, "diagnostics.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    with h5py.File(os.path.join(outdir, "diagnostics.h5"), "r") as f:
        for k in NEW + ("wall.footing.force_y", "wall.footing.work"):
            assert k in cols, "diagnostics.csv has no column %s" % k
            assert k in f, "diagnostics.h5 has no dataset %s" % k
        for k in NEW:
            assert f[k].attrs["units"].decode() == "J/m", "%s: units %r" % (k, f[k].attrs["units"])
        for k in cols:
            series = f[k][()]
            assert series.shape == cols[k].shape, "%s: %s rows in the series, %s in the CSV" % (k, series.shape,
                                                                                               cols[k].shape)
            assert np.allclose(series, cols[k], rtol=1e-15, atol=0), "%s: the CSV differs from the series" % k
    e_b, w_b = cols["E_bodies"], cols["W_bodies"]
    assert e_b[0] == 0 and w_b[0] == 0, "E_bodies %g, W_bodies %g at the start" % (e_b[0], w_b[0])
    assert w_b[-1] > 0 and np.max(e_b) > 0, "the footing did not fall: W_bodies %g, max E_bodies %g" % (
        w_b[-1], np.max(e_b))
    assert np.all(cols["W_walls"] == 0), "W_walls is not 0: the body's work leaked into it"
    booked = (cols["E_total"] + e_b - cols["E_total"][0] - cols["W_plastic"] - cols["W_friction"] -
              cols["W_damping"] - cols["W_external"] - cols["W_walls"] - w_b - cols["E_inflow"] - cols["W_inflow"] +
              cols["E_outflow"])
    scale = np.max(np.abs(w_b))
    err = np.max(np.abs(booked - cols["W_MPM"])) / scale
    assert err < 1e-9, "W_MPM differs from its definition by %.3g of the energy scale" % err
    print("body series: %d rows; W_bodies %.6g J/m, max E_bodies %.6g J/m, W_MPM %.4g J/m at the end; W_MPM as "
          "defined to %.2g" % (len(rows), w_b[-1], np.max(e_b), cols["W_MPM"][-1], err))


if __name__ == "__main__":
    main(sys.argv[1])
