#include "io/safe_write.h"

#include "io/file_digest.h"
#include "io/input_error.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fstream>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

namespace tessera {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPrefix = ".tmp-";

// fsync of a file or directory; returns errno, 0 on success.
int syncPath(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int status = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return status;
}

// This machine, as 8 hex digits of its name's digest: a temporary carries it with its writer's
// pid (.tmp-<pid>@<host>@<name>), because on a folder shared between machines (a cluster's file
// system) a pid means something only on the machine that wrote it. (The digest, not the name: a
// host name of up to 64 characters would leave a long file name no room.)
std::string thisHost() {
  char host[256] = {};
  return textDigest(::gethostname(host, sizeof host - 1) == 0 && host[0] != '\0' ? host : "localhost").substr(0, 8);
}

bool diskFull(int error) { return error == ENOSPC || error == EDQUOT || error == EFBIG; }

std::string cause(int error, const std::string& detail) {
  if (diskFull(error)) return "disk full or over quota (" + std::string(std::strerror(error)) + "); free some space and run again";
  if (error == EACCES || error == EPERM || error == EROFS)
    return "not writable (" + std::string(std::strerror(error)) + "); choose another output directory";
  return detail.empty() ? std::string(std::strerror(error)) : detail;
}

}  // namespace

void removeStaleTemporaries(const fs::path& directory) {
  const std::string host = thisHost();
  std::error_code error;
  for (fs::directory_iterator it(directory, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kPrefix, 0) != 0) continue;
    // Only this machine's: .tmp-<pid>@<host>@<name>, or .tmp-<pid>-<name> as written before the host was.
    const std::string rest = name.substr(std::strlen(kPrefix));
    const auto digits = rest.find_first_not_of("0123456789");
    if (digits == 0 || digits > 9 || digits == std::string::npos) continue;  // no pid has more digits
    if (rest[digits] == '@') {
      const auto hostEnd = rest.find('@', digits + 1);
      if (hostEnd == std::string::npos || rest.compare(digits + 1, hostEnd - digits - 1, host) != 0) continue;
    } else if (rest[digits] != '-') {
      continue;
    }
    const long pid = std::stol(rest.substr(0, digits));
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

FileSetWriter::~FileSetWriter() {
  std::error_code ignored;
  for (const Staged& s : staged_) fs::remove(s.temporary, ignored);
}

void FileSetWriter::add(const fs::path& target, const Step& write, const Step& verify) {
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  removeStaleTemporaries(dir);
  const fs::path temporary = dir / (kPrefix + std::to_string(::getpid()) + "@" + thisHost() + "@" + target.filename().string());
  const auto fail = [&](int error, const std::string& detail) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    for (const Staged& s : staged_) fs::remove(s.temporary, ignored);
    staged_.clear();
    throw WriteError(target.string() + ": cannot write: " + cause(error, detail));
  };
  errno = 0;
  try {
    write(temporary);
  } catch (const std::exception& e) {
    fail(errno, e.what());
  }
  const int writeError = errno;  // a writer that does not report its errors may still leave the cause here
  if (verify) {
    try {
      verify(temporary);
    } catch (const std::exception& e) {
      fail(diskFull(writeError) ? writeError : 0, "the file written does not read back (" + std::string(e.what()) + ")");
    }
  }
  if (const int error = syncPath(temporary, O_RDONLY)) fail(error, "");
  staged_.push_back({temporary, target});
}

void FileSetWriter::commit() {
  std::vector<Staged> staged;
  staged.swap(staged_);
  for (std::size_t i = 0; i < staged.size(); ++i) {
    std::error_code renamed;
    fs::rename(staged[i].temporary, staged[i].target, renamed);
    if (renamed) {
      std::error_code ignored;
      for (std::size_t j = i; j < staged.size(); ++j) fs::remove(staged[j].temporary, ignored);
      throw WriteError(staged[i].target.string() + ": cannot write: " + cause(renamed.value(), renamed.message()));
    }
  }
  for (const Staged& s : staged) {  // best effort: some file systems cannot sync a directory
    const fs::path dir = s.target.parent_path().empty() ? fs::path(".") : s.target.parent_path();
    syncPath(dir, O_RDONLY | O_DIRECTORY);
  }
}

void writeFileSafely(const fs::path& target, const std::function<void(const fs::path&)>& write,
                     const std::function<void(const fs::path&)>& verify) {
  FileSetWriter file;
  file.add(target, write, verify);
  file.commit();
}

void writeTextFileSafely(const fs::path& target, const std::string& text) {
  writeFileSafely(target, [&](const fs::path& p) {
    std::ofstream out(p, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error("short write");
  });
}

}  // namespace tessera
