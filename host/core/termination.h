#pragma once
// A command-line run ended by a signal (SIGTERM: a Slurm time limit or `kill`; SIGINT: Ctrl-C;
// SIGHUP: a closed terminal) removes the temporary files of its unfinished writes before it ends,
// instead of leaving them for the next run into the folder (core/atomic_file.h). Files already
// complete under their final names stay. A signal the process was started ignoring (`nohup`'s
// SIGHUP, SIGINT in a script's background job) stays ignored.
//
// How: main() blocks the three signals before any thread exists (every thread, the libraries'
// included, inherits the mask) and one thread waits for them (sigwait). On a signal that thread,
// in ordinary context, takes the registry's lock (so no write registers or finishes meanwhile),
// removes every registered temporary file, says so on stderr, and ends the process by the same
// signal (its exit status is the signal's: 128 + 15 = 143 in a shell for SIGTERM).
#include <mutex>
#include <string>

namespace dicsynth {

// Call first in main(), before any thread is created. Not for library users (the Python module:
// Python handles its own signals); without it the registry below costs a lock per file and nothing
// else.
void removeTemporariesOnTermination();

// AtomicFile makes its temporary file here: created (open with O_RDWR | O_CREAT | O_EXCL) and registered
// under the registry's lock, so a signal's cleanup either removes it or runs before it exists (the
// caller then waits at the lock until the process ends, and never makes it). Returns open's file
// descriptor, or -1 with errno set (EEXIST: another's file, not registered). Unregistered once
// committed or removed.
int createTemporary(const std::string& path);
void unregisterTemporary(const std::string& path);

// Holds a signal's cleanup, while the lock lives, so that the renames of a set of files (an image
// and its ground truth, a manifest's CSV and JSON, a rig's calibration files) all happen before the
// run ends, or none: a SIGTERM between two of them left manifest.csv without manifest.json, or a
// TIFF without its EXR (the faults audit of 2026-11-28, with the renames held open by strace). Take
// it for the renames only, after the files are written: the cleanup waits for it.
std::unique_lock<std::mutex> holdTermination();

}  // namespace dicsynth
