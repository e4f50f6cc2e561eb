// libFuzzer harness: study files, YAML and JSON (femup::ParseStudy, which
// LoadStudy calls with the file's text), on arbitrary bytes. The study stands
// (by its name only: nothing is written) in tests/data/mm/model, so that a
// matrix_market model finds the Matrix Market files there. The reader either
// returns or throws InputError; anything else is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "femup/core/errors.h"
#include "femup/studies/study.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const femup::Study study =
        femup::ParseStudy(text, FEMUP_FUZZ_STUDY_DIR "/fuzz_study.yaml");
    (void)study;
  } catch (const femup::InputError&) {
  }
  return 0;
}
