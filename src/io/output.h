/* moraine: what a simulation writes while it runs (an observer of mrn_run).
 *
 *   OUTDIR/<vtk>_NNNNNN.vtp + OUTDIR/<vtk>.pvd   particle snapshots (ParaView)
 *   or OUTDIR/<vtk>_NNNNNN.vtkhdf + OUTDIR/<vtk>.vtkhdf.series
 *   OUTDIR/<vtk>_grid_NNNNNN.vti + OUTDIR/<vtk>_grid.pvd   grid snapshots
 *   OUTDIR/<diagnostics>                          CSV of the diagnostics
 * Every path is relative to the output directory (the -o option).
 *
 * In a distributed run (solver/dist.h) a .vtp snapshot is written as one
 * piece per process, OUTDIR/<vtk>_NNNNNN_p<rank>.vtp holding that
 * process's particles (none: an empty piece), and OUTDIR/<vtk>_NNNNNN.pvtp,
 * written by process 0 once every piece is complete, listing them; the
 * .pvd lists the .pvtp. With vtk_gather, and for .vtkhdf snapshots, the
 * particles are gathered on process 0 into the one file a single process
 * writes. The grid, the CSV and the HDF5 series are written by process 0
 * with the values of every process. */
#ifndef MRN_IO_OUTPUT_H
#define MRN_IO_OUTPUT_H

#include <sys/types.h>

#include "io/series_h5.h"
#include "io/stash.h"
#include "io/vtk.h"
#include "solver/diagnostics.h"
#include "solver/run.h"

#define MRN_OUTPUT_MAX_FIELDS 32

typedef struct mrn_output {
  char *dir;

  /* VTK series; disabled when vtk_name is NULL */
  char *vtk_name;
  double vtk_every_time;   /* > 0: write every this much model time */
  long vtk_every_steps;    /* > 0: write every this many steps */
  double vtk_next_time;
  long vtk_last_step;      /* step of the last snapshot (-1: none yet) */
  int vtk_count;
  mrn_vtk_encoding encoding;
  int vtk_compress; /* 0: raw; 1..9: zlib level of the snapshots */
  int vtk_float32;  /* Float64 arrays and points stored as Float32 */
  int vtkhdf;       /* .vtkhdf files in a .vtkhdf.series instead of .vtp in a .pvd */
  int vtk_gather;   /* distributed: one .vtp gathered on process 0 instead of pieces and a .pvtp */
  int nfields;
  /* names listed by the deck: built-in fields or fields it registered
   * (checked when a snapshot is written); none: every field */
  char fields[MRN_OUTPUT_MAX_FIELDS][48];
  mrn_pvd pvd;

  /* grid snapshots (.vti) beside the particle series, when set */
  int grid_vtk;
  mrn_pvd grid_pvd;

  /* HDF5 time series of the diagnostics and of values recorded from Lua,
   * written at the CSV's rows; disabled when series_name is NULL */
  char *series_name;
  mrn_series *series;
  char *run_name, *deck_path, *deck_text; /* its root attributes, or NULL */
  char *series_file;       /* the file in use, relative to dir (NAME_2.h5, ...) */
  long series_rows;        /* rows appended to it */

  /* diagnostics CSV; disabled when csv_name is NULL */
  char *csv_name;
  long csv_every;
  long csv_last_step;      /* step of the last row (-1: none yet) */
  int csv_fd;              /* -1 while not open */
  char *csv_path;          /* the open file, for messages */
  off_t csv_size;          /* bytes of whole rows in the file */
} mrn_output;

void mrn_output_init(mrn_output *o, const char *dir);
/* Close the files and free everything. 0, or MRN_ERR_IO with the file in the
 * message when the last rewrite of the HDF5 series, or syncing and closing
 * the CSV, failed. */
int mrn_output_free(mrn_output *o);
/* (re)configure the VTK series; name NULL disables it. A new name starts a new .pvd */
int mrn_output_set_vtk(mrn_output *o, const char *name, double every_time, long every_steps);
int mrn_output_set_csv(mrn_output *o, const char *name, long every);
/* .vtkhdf snapshots (vtkhdf set) or .vtp ones; a change starts the series
 * afresh, as a new name does */
void mrn_output_set_vtkhdf(mrn_output *o, int vtkhdf);
int mrn_output_set_series(mrn_output *o, const char *name);
/* The run's name, its deck's path and text for the HDF5 series' root
 * attributes (mrn_series_describe), now or when the series opens; NULL:
 * none. 0 or MRN_ERR_IO. */
int mrn_output_describe(mrn_output *o, const char *run_name, const char *deck_path, const char *deck_text);
/* a value for the next row of the HDF5 series (a new name adds a column);
 * dim: the simulation's, for the units of the diagnostics columns */
int mrn_output_record(mrn_output *o, int dim, const char *name, double value);

/* The settings of the output and where its files stand (snapshots written,
 * the next one due, bytes of CSV rows, rows of the series), walked into or
 * out of a stash (io/stash.h): what a checkpoint keeps so that a resumed run
 * continues the same files. A new setting is one line here. */
void mrn_output_stash(mrn_output *o, mrn_stash *s);
/* Continue the files of an output loaded from a stash: the .pvd keeps its
 * first vtk_count entries (the snapshot files of those it drops are
 * removed), the CSV is cut to its stored bytes and appended to, the series
 * keeps its stored rows and the values recorded for its next row. Missing
 * files start anew. 0, or MRN_ERR_IO naming
 * the file (a CSV shorter than the stored rows is another run's). */
int mrn_output_resume(mrn_output *o, const mrn_stash *s);
/* Before a run writes: the files of this output that already exist in its
 * directory and that this process has not written (another run's). With
 * `overwrite` they are taken over; else MRN_ERR with a message naming them.
 * The files are then this process's: later runs may append. */
int mrn_output_claim(mrn_output *o, int overwrite);

/* forget which CSV files this process has written (they are appended to
 * when a second output names the same file); called when a deck ends */
void mrn_output_forget_files(void);

/* write a snapshot now (0 or MRN_ERR_IO) */
int mrn_output_write_vtk(mrn_output *o, const struct mrn_sim *sim);
/* write a snapshot if one is due at the current time/step */
int mrn_output_maybe_vtk(mrn_output *o, const struct mrn_sim *sim);
/* Append a CSV row if one is due (always when force is set). A row is
 * written whole or not at all: a write cut short by a full disk is taken back
 * by truncating the file to its last whole row. 0 or MRN_ERR_IO. */
int mrn_output_maybe_csv(mrn_output *o, const struct mrn_sim *sim, const mrn_diagnostics *d, int force);
/* Put every row so far on disk, as when a run stops early: the HDF5 series
 * rewritten if it lags, the CSV fsynced. 0 or MRN_ERR_IO. */
int mrn_output_flush(mrn_output *o);

/* The writers above as an observer of mrn_run: a VTK snapshot when one is
 * due, and the CSV and HDF5 series' rows (of the first state, on the CSV's
 * cadence and of the last state). The output must outlive the run. */
mrn_run_observer mrn_output_observer(mrn_output *o);

#endif
