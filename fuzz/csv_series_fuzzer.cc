// libFuzzer harness: the CSV time-series reader (femup::ParseCsvSeries) on
// arbitrary bytes. The reader either returns or throws InputError; anything
// else is a bug.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "femup/core/errors.h"
#include "femup/core/io/csv_series.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const femup::CsvSeries series = femup::ParseCsvSeries(text, "fuzz.csv");
    (void)series;
  } catch (const femup::InputError&) {
  }
  return 0;
}
