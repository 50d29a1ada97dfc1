/* moraine: what output.c and output_resume.c share. */
#ifndef MRN_IO_OUTPUT_INTERNAL_H
#define MRN_IO_OUTPUT_INTERNAL_H

/* the suffix of a particle series' collection and of its snapshots: VTK
 * 9.1 reads no .vtkhdf from a .pvd, so ParaView's JSON file series lists
 * those */
#define MRN_OUTPUT_COLLECTION(o) ((o)->vtkhdf ? ".vtkhdf.series" : ".pvd")
#define MRN_OUTPUT_SNAPSHOT_EXT(o) ((o)->vtkhdf ? ".vtkhdf" : ".vtp")

/* a small set of paths (files this process writes) */
#define MRN_PATH_SET_MAX 64
typedef struct mrn_path_set {
  char *p[MRN_PATH_SET_MAX];
  int n;
} mrn_path_set;

int mrn_path_set_has(const mrn_path_set *set, const char *path);
void mrn_path_set_add(mrn_path_set *set, const char *path);
void mrn_path_set_clear(mrn_path_set *set);

/* the CSV or series file at path is one this process writes: a later open
 * appends to it (CSV) or picks another name (series) */
void mrn_output_mark_written(const char *path);
/* forget the files mrn_output_claim took (output_resume.c) */
void mrn_output_forget_claims(void);

#endif
