#include "modes_json.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "femup/core/errors.h"

namespace femup::internal {
namespace {

using Json = nlohmann::json;

// "number", "string", ... for messages.
std::string TypeName(const Json& j) { return j.type_name(); }

}  // namespace

FileModes ReadModesJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "error while reading the file");
  return ParseModesJson(text.str(), path);
}

FileModes ParseModesJson(std::string_view text, const std::string& name) {
  Json j;
  try {
    j = Json::parse(text.begin(), text.end());
  } catch (const Json::out_of_range& e) {
    // A number too large for a double (9e550).
    throw InputError(name, std::string("a number does not fit a double (at most about "
                                       "1.8e308): ") +
                               e.what());
  } catch (const Json::exception& e) {
    throw InputError(name, std::string("not valid JSON: ") + e.what());
  }
  FileModes out;
  try {
    const auto fail = [&](const std::string& field, const std::string& expected,
                          const Json& found) {
      throw InputError(name,
                       field + ": expected " + expected + ", found " + TypeName(found));
    };
    if (!j.is_object())
      fail("top level", "an object (the modes.json of femup identify)", j);
    const auto modes = j.find("modes");
    if (modes == j.end())
      throw InputError(name,
                       "modes: missing (expected the modes.json of femup identify)");
    if (!modes->is_array()) fail("modes", "a list of modes", *modes);
    const auto data = j.find("data");
    if (data != j.end() && data->is_object()) {
      const auto channels = data->find("channels");
      if (channels != data->end()) {
        if (!channels->is_array())
          fail("data.channels", "a list of channel names", *channels);
        for (std::size_t i = 0; i < channels->size(); ++i) {
          const Json& c = (*channels)[i];
          if (!c.is_string())
            fail("data.channels[" + std::to_string(i + 1) + "]", "a channel name (text)",
                 c);
          out.channels.push_back(c.get<std::string>());
        }
      }
    }
    for (std::size_t k = 0; k < modes->size(); ++k) {
      const Json& m = (*modes)[k];
      const std::string where = "modes[" + std::to_string(k + 1) + "]";
      if (!m.is_object()) fail(where, "an object with frequency_hz and shape", m);
      const auto f = m.find("frequency_hz");
      if (f == m.end() || !f->is_number())
        throw InputError(name, where + ".frequency_hz: expected a number" +
                                   (f == m.end() ? std::string(", found none")
                                                 : ", found " + TypeName(*f)));
      const auto shape = m.find("shape");
      if (shape == m.end() || !shape->is_array())
        throw InputError(name, where + ".shape: expected a list of numbers" +
                                   (shape == m.end() ? std::string(", found none")
                                                     : ", found " + TypeName(*shape)));
      const double hz = f->get<double>();
      if (!(hz > 0) || !std::isfinite(hz))
        throw InputError(
            name,
            where + ".frequency_hz: expected a positive frequency, found " + f->dump());
      Eigen::VectorXd v(static_cast<Eigen::Index>(shape->size()));
      for (std::size_t i = 0; i < shape->size(); ++i) {
        const Json& x = (*shape)[i];
        if (!x.is_number())
          throw InputError(name,
                           where + ".shape[" + std::to_string(i + 1) +
                               "]: expected a number (null is a lost value), found " +
                               TypeName(x));
        v[static_cast<Eigen::Index>(i)] = x.get<double>();
      }
      out.frequencies_hz.push_back(hz);
      out.shapes.push_back(std::move(v));
    }
  } catch (const Json::exception& e) {
    // Not expected after the checks above; still an input error, never an escape.
    throw InputError(name, std::string("unexpected content: ") + e.what());
  }
  return out;
}

}  // namespace femup::internal
