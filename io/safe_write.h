#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tessera {

/// Writes `target` so that it is either the complete new file or the previous one, never a part:
///  1. `write` fills a temporary sibling, .tmp-<pid>@<host>@<name> (the pid and 8 hex digits of the
///     machine name's digest keep concurrent writers apart, also on a folder shared between machines);
///  2. `verify`, if given, reads the temporary back (a writer that does not report its own errors,
///     such as a library's, is caught here);
///  3. the temporary is synced to disk (a full disk can first show up here), renamed over `target`,
///     and the directory is synced, so the rename survives a power cut.
/// Any failure removes the temporary and throws WriteError naming `target` and the cause ("disk full
/// or over quota" when the system says so). Temporaries left by killed processes of this machine are
/// removed first.
void writeFileSafely(const std::filesystem::path& target, const std::function<void(const std::filesystem::path&)>& write,
                     const std::function<void(const std::filesystem::path&)>& verify = {});

/// Several files replaced together (a bundle's bundle.h5 and its grids): each is written, verified
/// and synced under its temporary name as by writeFileSafely when it is added; only when every one
/// is, commit() renames them over their targets. A failure while adding (WriteError), or an unused
/// set, removes every temporary and leaves every target as it was.
class FileSetWriter {
public:
  using Step = std::function<void(const std::filesystem::path&)>;
  FileSetWriter() = default;
  FileSetWriter(const FileSetWriter&) = delete;
  FileSetWriter& operator=(const FileSetWriter&) = delete;
  ~FileSetWriter();
  void add(const std::filesystem::path& target, const Step& write, const Step& verify = {});
  void commit();

private:
  struct Staged {
    std::filesystem::path temporary, target;
  };
  std::vector<Staged> staged_;
};

/// writeFileSafely of a text.
void writeTextFileSafely(const std::filesystem::path& target, const std::string& text);

/// Removes the temporaries in `directory` written on this machine by a process that is gone (a killed
/// writer's): .tmp-<pid>@<host>@<name> with this host, and .tmp-<pid>-<name> (the form before the
/// host). Another machine's are kept: its pid says nothing here.
void removeStaleTemporaries(const std::filesystem::path& directory);

}  // namespace tessera
