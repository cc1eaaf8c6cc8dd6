#pragma once
// JSON text as Tessera writes it (summary.json, sweep.json, attempt.json, jobs.json, layouts,
// inspect --json): indented, one trailing newline, and never an exception for a string that is not
// UTF-8 (a Latin-1 file name, a name read from a file): such bytes are written as U+FFFD, the
// replacement character, and the file is written all the same (a run once computed to its end and
// then stopped with an internal error writing summary.json).
#include <nlohmann/json.hpp>

#include <string>

namespace tessera {

inline std::string jsonText(const nlohmann::json& j) {
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace tessera
