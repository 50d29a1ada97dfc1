/* moraine: is a path inside the output directory? (the --safe mode,
 * doc/security.md)
 *
 * A path is inside a directory when, with every symbolic link and every
 * ".." it goes through resolved, it names something strictly below that
 * directory. The part of the path that exists is resolved by the kernel
 * (realpath(3)); the rest does not exist yet, so it holds no link and is
 * resolved as text. The answer holds at the moment of the check: a process
 * that replaces a directory by a link between the check and the write is not
 * stopped. */
#ifndef MRN_IO_CONFINE_H
#define MRN_IO_CONFINE_H

/* MRN_OK when `path` (relative to the current directory when not absolute)
 * lies strictly below the directory `dir`; otherwise MRN_ERR with the message
 * "'PATH' is outside the output directory 'DIR'", followed by
 * " (it resolves to 'REAL')" when a symbolic link took it there. */
int mrn_confine_check(const char *dir, const char *path);

#endif
