#include "core/termination.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>

namespace dicsynth {
namespace {

// Never destroyed: a signal during the static destructors at exit must still find them.
std::mutex& registryMutex() {
  static std::mutex* m = new std::mutex;
  return *m;
}

// Taken before the registry's: held by a set of renames (holdTermination), waited for by the cleanup.
std::mutex& groupMutex() {
  static std::mutex* m = new std::mutex;
  return *m;
}

std::multiset<std::string>& registry() {
  static std::multiset<std::string>* paths = new std::multiset<std::string>;
  return *paths;
}

// The three signals, but those the process was started ignoring: `nohup` (SIGHUP) and a shell
// script's background jobs (SIGINT) must keep ignoring them. A blocked signal is queued even when
// ignored, and sigwait would take it.
sigset_t terminationSignals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) {
    struct sigaction current{};
    if (::sigaction(sig, nullptr, &current) == 0 && current.sa_handler != SIG_IGN) sigaddset(&set, sig);
  }
  return set;
}

[[noreturn]] void cleanUpAndEnd(int sig) {
  // The lock is kept to the end: no temporary file is made, or forgotten, meanwhile. Writers write
  // through the file's descriptor (AtomicFile::duplicateFd), so a removed file is not made again;
  // a writer that reopened one by name would (2 of 30 signalled sweeps left one before they all
  // wrote through descriptors; the next run into the folder removes such a file).
  groupMutex().lock();  // a set of renames under way completes first
  registryMutex().lock();
  std::size_t removed = 0;
  for (const std::string& path : registry()) removed += ::unlink(path.c_str()) == 0 ? 1 : 0;
  std::fprintf(stderr, "dicsynth: ended by %s: removed %zu temporary file%s of unfinished writes\n",
               sig == SIGTERM ? "SIGTERM" : sig == SIGINT ? "SIGINT" : "SIGHUP", removed, removed == 1 ? "" : "s");
  std::fflush(stderr);
  // Once more, for a writer that would reopen one by name while the message was written.
  for (const std::string& path : registry()) ::unlink(path.c_str());
  // End by the same signal, with its default action, so that the parent (a shell, Slurm) sees it.
  ::signal(sig, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, sig);
  ::pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  ::raise(sig);
  ::_exit(128 + sig);  // not reached: the default action of the three ends the process
}

}  // namespace

void removeTemporariesOnTermination() {
  static std::once_flag once;
  std::call_once(once, [] {
    const sigset_t set = terminationSignals();
    if (sigisemptyset(&set)) return;
    if (::pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;  // then signals act as before
    std::thread([set] {
      int sig = 0;
      while (::sigwait(&set, &sig) != 0) {
      }
      cleanUpAndEnd(sig);
    }).detach();
  });
}

int createTemporary(const std::string& path) {
  std::lock_guard lock(registryMutex());
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd >= 0) registry().insert(path);
  return fd;
}

std::unique_lock<std::mutex> holdTermination() { return std::unique_lock<std::mutex>(groupMutex()); }

void unregisterTemporary(const std::string& path) {
  std::lock_guard lock(registryMutex());
  const auto it = registry().find(path);
  if (it != registry().end()) registry().erase(it);
}

}  // namespace dicsynth
