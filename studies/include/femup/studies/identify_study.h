// Modal identification from measured signals (`femup identify`): a UFF 58/58b
// file of time histories or FRFs, or a CSV time series, goes through ERA with a
// stabilisation diagram; the modes stable over enough consecutive orders come
// out with their frequencies, damping ratios, shapes at the sensors and quality
// indicators, as JSON and plots.
//
// Time histories are taken as impulse or free-decay responses (all channels one
// record each, the same sample rate and length). FRFs (UFF function type 4,
// complex, evenly spaced from 0 Hz) are turned into impulse responses by inverse
// FFT first (femup/frf_impulse.h).
#pragma once

#include <string>
#include <vector>

#include "femup/core/invalid.h"
#include "femup/core/sysid/era.h"

namespace femup {

struct IdentifyOptions {
  std::string file;    // .uff / .unv (UFF) or .csv
  std::string format;  // "uff", "csv" or "" (from the file name's extension)
  StabilisationOptions stabilisation;
  int min_consecutive = 5;      // orders a mode must stay stable to be reported
  double max_frequency_hz = 0;  // report modes below this; 0 = Nyquist
  // Ok when valid; otherwise the field and what is wrong.
  Invalid Validate() const;
};

struct IdentifyResult {
  std::string source;                 // the file
  std::string data_kind;              // "time" or "frf"
  std::vector<std::string> channels;  // one name per record row
  double sample_rate_hz = 0;
  int num_samples = 0;
  StabilisationDiagram diagram;
  std::vector<StableMode> modes;   // ascending frequency
  std::vector<std::string> notes;  // reader notes (skipped datasets etc.)
};

// Throws InputError naming the file (and line, from the readers) or the option.
IdentifyResult RunIdentify(const IdentifyOptions& options);

}  // namespace femup
