// Fuzz target: the bundle reader (HDF5) and the value checks behind it. A corrupt bundle must be
// an InputError. The seed is a real bundle (fuzz/corpus/bundle, written by `fuzz_checkpoint --seeds`).
#include "fuzz/input_file.h"
#include "io/input_error.h"
#include "levelset/bundle.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    tessera::readBundle(tessera::fuzz::writeInput(data, size, ".h5"));
  } catch (const tessera::InputError&) {
  }
  return 0;
}
