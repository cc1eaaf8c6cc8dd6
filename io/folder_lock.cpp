#include "io/folder_lock.h"

#include "io/input_error.h"

#include <filesystem>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

namespace tessera {

namespace fs = std::filesystem;

FolderLock::FolderLock(const std::string& folder, const std::string& what) {
  fs::create_directories(folder);
  const fs::path path = fs::path(folder) / ".lock";
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(folder + ": cannot create its lock file .lock; choose another folder");
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    char holder[32] = {};
    const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
    ::close(fd_);
    fd_ = -1;
    const std::string pid = n > 0 ? std::string(holder) : "?";
    if (pid == std::to_string(::getpid()))  // Python: a Simulation on the folder is still open
      throw InputError(folder + ": this process still holds " + what +
                       " there (a session on it is still open); close that one first (in Python: del sim)");
    throw InputError(folder + ": another tessera process (pid " + pid + ") is writing " + what +
                     " there; wait for it to end, or stop it (Ctrl-C) first");
  }
  const std::string pid = std::to_string(::getpid());
  if (::ftruncate(fd_, 0) == 0 && ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // the pid is only a hint for the message above
  }
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

FileLock::FileLock(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ >= 0 && ::flock(fd_, LOCK_EX) == 0) return;
  if (fd_ >= 0) ::close(fd_);
  throw InputError(path + ": cannot lock it; check that its folder exists and is writable");
}

FileLock::~FileLock() { ::close(fd_); }  // releases the lock

// /proc/locks lines: "1: FLOCK  ADVISORY  WRITE 1234 08:01:5678 0 EOF" (pid, then the file's
// device major:minor in hex and its inode in decimal).
long folderLockHolder(const std::string& folder) {
  struct stat file {};
  if (::stat((fs::path(folder) / ".lock").c_str(), &file) != 0) return 0;
  std::ifstream locks("/proc/locks");
  for (std::string line; std::getline(locks, line);) {
    std::istringstream in(line);
    std::string number, kind, mode, access, id;
    long pid = 0;
    if (!(in >> number >> kind)) continue;
    if (kind == "->") continue;  // a process waiting for the lock, listed under its holder
    if (!(in >> mode >> access >> pid >> id) || kind != "FLOCK") continue;
    unsigned major = 0, minor = 0;
    unsigned long inode = 0;
    if (std::sscanf(id.c_str(), "%x:%x:%lu", &major, &minor, &inode) != 3) continue;
    if (inode == file.st_ino && makedev(major, minor) == file.st_dev) return pid > 0 ? pid : -1;
  }
  return 0;
}

}  // namespace tessera
