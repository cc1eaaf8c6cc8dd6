#pragma once
#include <stdexcept>
#include <string>

namespace tessera {

/// Bad user input (a file, a flag, a value). what() is one line that names the input,
/// the problem and, where there is one, the fix. Tools print it and exit non-zero.
class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// A file that could not be written (disk full, over quota, not writable). what() names the file
/// and the cause; the previous version of the file is untouched. Tools exit 2 (docs: exit codes).
class WriteError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

}  // namespace tessera
