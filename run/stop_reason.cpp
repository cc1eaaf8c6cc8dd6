#include "run/stop_reason.h"

#include <array>
#include <utility>

namespace tessera {

namespace {

constexpr std::array<std::pair<StopReason, const char*>, 6> kNames{{{StopReason::Running, "running"},
                                                                    {StopReason::DeltaMax, "delta_max"},
                                                                    {StopReason::Failure, "failure"},
                                                                    {StopReason::Requested, "requested"},
                                                                    {StopReason::Interrupted, "interrupted"},
                                                                    {StopReason::Instability, "instability"}}};

}  // namespace

const char* stopReasonName(StopReason reason) {
  for (const auto& [r, name] : kNames)
    if (r == reason) return name;
  return "running";
}

std::optional<StopReason> parseStopReason(const std::string& name) {
  if (name.empty()) return StopReason::Running;
  for (const auto& [r, n] : kNames)
    if (name == n) return r;
  return std::nullopt;
}

}  // namespace tessera
