// libFuzzer harness: the UFF reader (femup::ParseUff) on arbitrary bytes. The
// reader either returns or throws InputError; anything else (another exception,
// an abort, a sanitizer report, a hang, a huge allocation) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "femup/core/errors.h"
#include "femup/core/io/uff.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const femup::UffFile file = femup::ParseUff(text, "fuzz.uff");
    (void)file;
  } catch (const femup::InputError&) {
  }
  return 0;
}
