// libFuzzer harness: the modes.json of `femup identify`, as a study's
// modes_file reads it (femup::internal::ParseModesJson, studies/src), on
// arbitrary bytes. The reader either returns or throws InputError; anything
// else (nlohmann's own exceptions included) is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "femup/core/errors.h"
#include "modes_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const femup::internal::FileModes modes =
        femup::internal::ParseModesJson(text, "fuzz/modes.json");
    (void)modes;
  } catch (const femup::InputError&) {
  }
  return 0;
}
