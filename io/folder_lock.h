#pragma once
#include <string>

namespace tessera {

/// An exclusive lock on a folder for one writer (a run, a resume, a sweep): <folder>/.lock, held
/// with flock(2) for the life of the object. The kernel releases it when the process ends, killed
/// or not, so a stale lock never needs removing by hand.
class FolderLock {
public:
  /// Creates the folder if needed. Throws InputError naming the folder, and the process holding
  /// it, when another process holds the lock.
  FolderLock(const std::string& folder, const std::string& what);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

private:
  int fd_ = -1;
};

/// An exclusive lock on one file (created if needed), waited for rather than refused: held with
/// flock(2) for the life of the object, around a short section that one process at a time may run
/// (a sweep's tables rewritten, a shared geometry bundle made). Throws InputError naming the file
/// when it cannot be opened or locked.
class FileLock {
public:
  explicit FileLock(const std::string& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int fd_ = -1;
};

/// The process id holding the FolderLock of `folder` on this machine (-1 for a holder in another
/// pid namespace), 0 when none does or the folder has no lock file. Read from /proc/locks, so it
/// never takes or delays the lock; a holder on another machine of a shared file system is not seen.
long folderLockHolder(const std::string& folder);

}  // namespace tessera
